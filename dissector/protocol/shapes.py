"""The regular layouts' fields, as data/modbus.toml [layouts] states them: one description from which the
Construct grammars (protocol/layouts.py) and the fast parsers (decode/fastpath.py) are made, and whose
offsets the compiled engine (codegen/c.py, c_rules.py) and the plugin read.

A description is a list of "name:type" (the types are explained in data/modbus.toml). Parsed here into
`Field`s, and refused with a one-line reason when a type is unknown or a count names no earlier field.
"""
from __future__ import annotations

import keyword
import re
from dataclasses import dataclass
from enum import StrEnum

from dissector.protocol.spec import SPEC


class Type(StrEnum):
    U8 = "u8"
    U16 = "u16"
    BYTES = "bytes"  # `count` bytes
    WORDS = "words"  # `count` big-endian words (`half`: count // 2)
    ODD = "odd"  # one byte when `count` is odd, else None
    REST = "rest"  # every byte to the end (the layout has no trailing then)


@dataclass(frozen=True, slots=True)
class Field:
    name: str
    type: Type
    count: str | None = None  # the earlier field a counted type's size comes from
    half: bool = False  # words(n/2)

    @property
    def size(self) -> int | None:
        """Bytes of a fixed-size field, None for a counted one."""
        return {Type.U8: 1, Type.U16: 2}.get(self.type)


class ShapeError(ValueError):
    """A layout description the grammars cannot be made from."""


_FIELD = re.compile(r"(?P<name>[A-Za-z_][A-Za-z0-9_]*):(?P<type>u8|u16|rest|(?P<counted>bytes|words|odd)\((?P<count>\w+)(?P<half>/2)?\))")


def parse_shape(name: str, description: list[str]) -> tuple[Field, ...]:
    fields: list[Field] = []
    for text in description:
        match = _FIELD.fullmatch(text.replace(" ", ""))
        if match is None:
            raise ShapeError(f"[layouts] {name}: {text!r} is no field (name:u8, u16, bytes(n), words(n), words(n/2), odd(n), rest)")
        count = match["count"]
        if count is not None and count not in {field.name for field in fields}:
            raise ShapeError(f"[layouts] {name}: {text!r} counts by {count!r}, no earlier field")
        if match["half"] and match["counted"] != "words":
            raise ShapeError(f"[layouts] {name}: {text!r}: only words take a half count")
        if keyword.iskeyword(match["name"]) or match["name"] == "trailing":
            raise ShapeError(f"[layouts] {name}: {text!r}: the name cannot be a field's")
        kind = Type(match["counted"] or match["type"])
        if fields and fields[-1].type is Type.REST:
            raise ShapeError(f"[layouts] {name}: {text!r} after the rest of the data")
        fields.append(Field(match["name"], kind, count, bool(match["half"])))
    return tuple(fields)


SHAPES: dict[str, tuple[Field, ...]] = {name: parse_shape(name, value) for name, value in SPEC.layouts.items()}


def has_trailing(shape: tuple[Field, ...]) -> bool:
    return not shape or shape[-1].type is not Type.REST
