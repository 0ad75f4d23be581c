"""Construct layouts of the Modbus PDU data, one Struct per shape; protocol/table.py says which
(function code, direction) uses which.

The function code itself and the check (CRC/LRC) are not part of these layouts: the framer finds the
frame and records the check, so that a frame with a bad CRC is still shown rather than thrown away.
Every layout ends in `trailing`, so bytes past the documented layout are kept and reported, never lost.

Every layout is made from its field description (data/modbus.toml [layouts] and the [parts] they
repeat or switch to, read by protocol/shapes.py), which the fast parsers and the plugin's reader are
made from too: nothing of a layout is written here.
"""
from __future__ import annotations

from construct import (
    Adapter,
    Array,
    Bytes,
    Construct,
    Enum,
    FixedSized,
    GreedyBytes,
    GreedyRange,
    If,
    Int8ub,
    Int16ub,
    ListContainer,
    StreamError,
    Struct,
    Switch,
    this,
)

from dissector.protocol.shapes import PARTS, SHAPES, Field, Type, has_trailing
from dissector.protocol.spec import SPEC

_trailing = "trailing" / GreedyBytes


def text_when_printable(data: bytes) -> str | bytes:
    """Bytes as text when every one is printable ASCII (a version string), as bytes otherwise."""
    return data.decode("ascii") if data and all(0x20 <= byte < 0x7F for byte in data) else data


class _TextWhenPrintable(Adapter):  # type: ignore[misc]
    """A text(n) field: text_when_printable."""

    def _decode(self, obj: bytes, context: object, path: str) -> str | bytes:
        return text_when_printable(obj)

    def _encode(self, obj: str | bytes, context: object, path: str) -> bytes:
        return obj.encode("ascii") if isinstance(obj, str) else obj


class _Exact(Bytes):  # type: ignore[misc]
    """`count` bytes, a StreamError when fewer are left (as Bytes parses them, and the plugin's readers):
    Construct's compiled Bytes reads `io.read(count)` and took 1 byte for an FC15 byte count of 137."""

    _emitparse = Construct._emitparse  # (not compiled: the compiled parsers call _parse above)


class _UpTo(Array):  # type: ignore[misc]
    """`count` parts, fewer when the data end first (a part that does not fit ends them): a device may
    declare more FC43 objects than it sends; the decoder warns (decode/fields.py)."""

    def _parse(self, stream: object, context: object, path: str) -> ListContainer:
        count = self.count(context) if callable(self.count) else self.count
        parts = ListContainer()
        for _ in range(count):
            start = stream.tell()  # type: ignore[attr-defined]
            try:
                parts.append(self.subcon._parsereport(stream, context, path))
            except StreamError:
                stream.seek(start)  # type: ignore[attr-defined]
                break
        return parts

    # Not compiled: construct's own default (Construct._emitparse), not Array's fixed-count loop, so that
    # the compiled parsers link this instance and call its _parse above.
    _emitparse = Construct._emitparse


def _count(field: Field) -> object:
    """A counted field's size: the earlier field, less `minus`, halved for words(n/2)."""
    count = this[field.count] - field.minus if field.minus else this[field.count]
    return count // 2 if field.half else count


def _subcon(field: Field) -> Construct:
    if field.when is not None:  # (?(n-k): None where the count leaves no room for it)
        return field.name / If(this[field.when] - field.when_minus > 0, _present(field))
    return _present(field)


def _present(field: Field) -> Construct:
    name = field.name
    if field.type is Type.U8:
        if field.names is not None:
            return name / Enum(Int8ub, **{text: value for value, text in SPEC.names[field.names].items()})
        return name / Int8ub
    if field.type is Type.U16:
        return name / Int16ub
    if field.type is Type.REST:
        return name / GreedyBytes
    if field.type is Type.SWITCH:
        cases = {value: _part(part) for value, part in field.cases if value is not None}
        return name / Switch(this[field.count], cases, default=_part(field.cases[-1][1]))
    count = _count(field)
    if field.type is Type.BYTES:
        return name / _Exact(count)
    if field.type is Type.TEXT:
        return name / _TextWhenPrintable(_Exact(count))
    if field.type is Type.WORDS:
        return name / Array(count, Int16ub)
    if field.type is Type.ODD:
        return name / If(this[field.count] % 2 == 1, Bytes(1))
    if field.type is Type.RECORDS:
        return name / FixedSized(count, GreedyRange(_part(field.part)))
    return name / _UpTo(count, _part(field.part))  # Type.ARRAY


def _part(name: str | None) -> Struct:
    return Struct(*map(_subcon, PARTS[str(name)]))


def regular(name: str) -> Struct:
    """The Construct grammar of a layout data/modbus.toml [layouts] describes."""
    shape = SHAPES[name]
    return Struct(*map(_subcon, shape), *([_trailing] if has_trailing(shape) else []))


LAYOUTS: dict[str, Struct] = {name: regular(name) for name in SHAPES}
EXCEPTION = LAYOUTS["exception"]
RAW = LAYOUTS["raw"]
