"""The layouts' fields, as data/modbus.toml [layouts] and [parts] state them: one description from which
the Construct grammars (protocol/layouts.py) and the fast parsers (decode/fastpath.py) are made, and
whose offsets the compiled engine (codegen/c.py, c_rules.py) and the plugin read.

A description is a list of "name:type" (the types are explained in data/modbus.toml). Parsed here into
`Field`s, and refused with a one-line reason when a type is unknown, a count names no earlier field or
a part names none of [parts].
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
    TEXT = "text"  # `count` bytes, a str when every one is printable ASCII
    WORDS = "words"  # `count` big-endian words (`half`: count // 2)
    ODD = "odd"  # one byte when `count` is odd, else None
    REST = "rest"  # every byte to the end (the layout has no trailing then)
    RECORDS = "records"  # `part`s filling `count` bytes
    ARRAY = "array"  # `count` `part`s
    SWITCH = "switch"  # the part `cases` gives for the value of the field `count`


@dataclass(frozen=True, slots=True)
class Field:
    name: str
    type: Type
    count: str | None = None  # the earlier field a counted type's size comes from (switch: chosen by)
    half: bool = False  # words(n/2)
    minus: int = 0  # bytes(n-6): the count less this
    part: str | None = None  # records, array: the [parts] entry repeated
    cases: tuple[tuple[int | None, str], ...] = ()  # switch: (value, part), the last (None, default)
    names: str | None = None  # u8{NAMES}: the [names] table of its values
    # ?(n-k): present only when the earlier field `when` less `when_minus` is above 0 (else None), as a
    # byte count that leaves no room for it says
    when: str | None = None
    when_minus: int = 0

    @property
    def size(self) -> int | None:
        """Bytes of a fixed-size field, None for a counted one."""
        return {Type.U8: 1, Type.U16: 2}.get(self.type)


class ShapeError(ValueError):
    """A layout description the grammars cannot be made from."""


_FIELD = re.compile(
    r"(?P<name>[A-Za-z_][A-Za-z0-9_]*):(?:(?P<fixed>u8|u16)(?:\{(?P<names>\w+)\})?|(?P<rest>rest)"
    r"|(?P<counted>bytes|text|words|odd|records|array)\((?P<count>\w+)(?:-(?P<minus>\d+))?(?P<half>/2)?(?:,(?P<part>\w+))?\)"
    r"|switch\((?P<on>\w+),(?P<cases>(?:\d+=\w+,)+)(?P<default>\w+)\))"
    r"(?:\?\((?P<when>\w+)(?:-(?P<when_minus>\d+))?\))?"
)
_REPEATED = {"records", "array"}


def parse_shape(name: str, description: list[str]) -> tuple[Field, ...]:
    fields: list[Field] = []
    for text in description:
        match = _FIELD.fullmatch(text.replace(" ", ""))
        if match is None or (match["counted"] in _REPEATED) != (match["part"] is not None):
            raise ShapeError(f"[layouts] {name}: {text!r} is no field (name:u8, u16, bytes(n), words(n), words(n/2), "
                             "odd(n), rest, text(n), records(n, PART), array(n, PART), switch(f, K=PART, PART))")
        count = match["count"] or match["on"]
        for earlier in (count, match["when"]):
            if earlier is not None and earlier not in {field.name for field in fields}:
                raise ShapeError(f"[layouts] {name}: {text!r} counts by {earlier!r}, no earlier field")
        if match["half"] and match["counted"] != "words":
            raise ShapeError(f"[layouts] {name}: {text!r}: only words take a half count")
        if keyword.iskeyword(match["name"]) or match["name"] == "trailing":
            raise ShapeError(f"[layouts] {name}: {text!r}: the name cannot be a field's")
        cases = tuple((int(value), part) for value, part in re.findall(r"(\d+)=(\w+),", match["cases"] or ""))
        if match["default"]:
            cases += ((None, match["default"]),)
        parts = [part for _, part in cases] + ([match["part"]] if match["part"] else [])
        if any(part not in SPEC.parts for part in parts) or (match["names"] and match["names"] not in SPEC.names):
            raise ShapeError(f"[layouts] {name}: {text!r} names no [parts] or [names] entry")
        kind = Type(match["counted"] or match["fixed"] or match["rest"] or "switch")
        if fields and fields[-1].type is Type.REST:
            raise ShapeError(f"[layouts] {name}: {text!r} after the rest of the data")
        fields.append(Field(match["name"], kind, count, bool(match["half"]), int(match["minus"] or 0), match["part"],
                            cases, match["names"], match["when"], int(match["when_minus"] or 0)))
    return tuple(fields)


SHAPES: dict[str, tuple[Field, ...]] = {name: parse_shape(name, value) for name, value in SPEC.layouts.items()}
PARTS: dict[str, tuple[Field, ...]] = {name: parse_shape(name, value) for name, value in SPEC.parts.items()}


def has_trailing(shape: tuple[Field, ...]) -> bool:
    return not shape or shape[-1].type is not Type.REST
