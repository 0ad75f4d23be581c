"""Parsing and building PDU data with the Construct grammar of each (function code, direction).

The grammars are the layouts of protocol/layouts.py, chosen by the protocol table (protocol/table.py).
Unknown function codes fall back to raw `data`.

Data that end before their layout does (too short for a field, a count pointing past the end) are malformed,
said in the words `shortfall` derives from the layout's description (data/modbus.toml [layouts]), which the
plugin's readers say too (codegen/decode_lua.py reader): never a parser's own text. It judges before the
compiled parser reads, as that reads what is there of a count (`io.read(n)` gives fewer bytes, no error).
"""
from __future__ import annotations

import struct
from typing import Any

from construct import Construct, ConstructError, Container, StreamError

from dissector.errors import MalformedInput, NeedData
from dissector.model import Kind
from dissector.protocol.shapes import PARTS, SHAPES, Field, Type
from dissector.protocol.table import EXCEPTION_LAYOUT, FUNCTIONS, RAW_LAYOUT, layout_for

# The grammar of each (function code, direction): the protocol table's, nothing kept here.
GRAMMARS: dict[tuple[int, Kind], Construct] = {
    (entry.code, kind): entry.layout(kind).grammar for entry in FUNCTIONS for kind in (Kind.REQUEST, Kind.RESPONSE)
}
EXCEPTION = EXCEPTION_LAYOUT.grammar
RAW = RAW_LAYOUT.grammar


def _compile(grammar: Construct) -> Construct:
    # Compiled parsers are about 3x faster; building always goes through the declarative form.
    try:
        return grammar.compile()
    except Exception:  # construct refuses some constructs; the interpreted form is equivalent
        return grammar


_COMPILED: dict[int, Construct] = {}


def grammar_for(function: int, kind: Kind) -> Construct:
    if kind is Kind.EXCEPTION:
        return EXCEPTION
    return GRAMMARS.get((function, kind), RAW)


def _compiled(grammar: Construct) -> Construct:
    compiled = _COMPILED.get(id(grammar))
    if compiled is None:
        compiled = _COMPILED[id(grammar)] = _compile(grammar)
    return compiled


class GrammarError(MalformedInput):
    """The PDU does not fit its grammar: a field out of its range, bytes left over."""


class TruncatedPdu(GrammarError, NeedData):
    """The PDU ends before its grammar does: too short, or a count pointing past the end."""


def _grammar_error(error: ConstructError) -> GrammarError:
    kind = TruncatedPdu if isinstance(error, StreamError) else GrammarError
    return kind(_short_error(error))


def too_short_for(names: list[str]) -> str:
    """Why the data end before fixed-size fields: `too short for start and quantity`."""
    return "too short for " + (", ".join(names[:-1]) + " and " + names[-1] if len(names) > 1 else names[0])


def past_the_end(count: str) -> str:
    """Why the data end before a counted field: its count (`byte_count past the end`)."""
    return f"{count} past the end"


def fixed_head(shape: tuple[Field, ...]) -> tuple[Field, ...]:
    """The fixed-size fields a layout begins with, up to a counted one or one present on a condition: where
    they end is known before reading any, so the data are measured against them all at once."""
    head = 0
    while head < len(shape) and shape[head].size is not None and shape[head].when is None:
        head += 1
    return shape[:head]


def counted_size(field: Field, count: int) -> int:
    """A counted field's bytes from its count's value: less `minus` (below 0: no room), words(n/2) a whole
    number of words, an odd byte where the count is odd."""
    if field.type is Type.ODD:
        return count % 2
    count -= field.minus
    if field.half:
        return count - count % 2
    return 2 * count if field.type is Type.WORDS else count


def shortfall(shape: tuple[Field, ...], data: bytes, at: int = 0) -> tuple[int, str | None]:
    """Where the layout's fields end in `data` read from `at` (trailing bytes follow), and None; or -1 and why
    the data end first. An array's parts end at the first that does not fit (layouts._UpTo); a records
    field takes its count's bytes, its parts fill what they can (layouts FixedSized)."""
    head = fixed_head(shape)
    end = at + sum(field.size or 0 for field in head)
    if end > len(data):
        return -1, too_short_for([field.name for field in head])
    values, position = {}, at
    for field in shape:
        if field.when is not None and values[field.when] - field.when_minus <= 0:
            continue  # (absent: its count leaves it no room)
        if field.size is not None:
            if position + field.size > len(data):
                return -1, too_short_for([field.name])
            values[field.name] = int.from_bytes(data[position : position + field.size], "big")
            position += field.size
        elif field.type is Type.REST:
            position = len(data)
        elif field.type is Type.ARRAY:
            for _ in range(values[str(field.count)]):
                stop, _why = shortfall(PARTS[str(field.part)], data, position)
                if stop < 0:
                    break
                position = stop
        elif field.type is Type.SWITCH:
            value = values[str(field.count)]
            part = next(part for case, part in field.cases if case is None or case == value)
            position, why = shortfall(PARTS[part], data, position)
            if why is not None:
                return -1, why
        else:
            size = counted_size(field, values[str(field.count)])
            if size < 0 or position + size > len(data):
                return -1, past_the_end(str(field.count))
            position += size
    return position, None


def parse_pdu(function: int, kind: Kind, data: bytes) -> Container:
    """Parse the PDU data that follows the function code. Raises TruncatedPdu where they end before their
    layout (shortfall's words), GrammarError where they do not fit it otherwise."""
    _end, why = shortfall(SHAPES[layout_for(function, kind).name], data)
    if why is not None:
        raise TruncatedPdu(why)
    grammar = grammar_for(function, kind)
    try:
        return _compiled(grammar).parse(data)
    except (ConstructError, struct.error, ValueError, IndexError, OverflowError, EOFError):
        # The compiled parsers fail with plain Python errors, or without the path (a linked instance's
        # `(???)`); the interpreted grammar names it.
        try:
            return grammar.parse(data)
        except ConstructError as error:
            raise _grammar_error(error) from None


def build_pdu(function: int, kind: Kind, fields: dict[str, Any]) -> bytes:
    """Encode PDU data (without function code) from fields; used by the simulator and tests."""
    return grammar_for(function, kind).build(fields)


def _short_error(error: ConstructError) -> str:
    text = str(error).strip().splitlines()[-1] if str(error).strip() else type(error).__name__
    path = getattr(error, "path", None)
    if path:
        return f"{text} at {path}"
    return text
