"""Construct grammars for the Modbus PDU data, one Struct per (function code, direction).

The function code itself and the check (CRC/LRC) are not part of these grammars: the framer finds the
frame and records the check, so that a frame with a bad CRC is still shown rather than thrown away.
Every grammar ends in `trailing`, so bytes past the documented layout are kept and reported, never lost.
Unknown function codes fall back to raw `data`.
"""
from __future__ import annotations

import struct
from typing import Any

from construct import (
    Array,
    Bytes,
    Construct,
    ConstructError,
    StreamError,
    Container,
    FixedSized,
    GreedyBytes,
    GreedyRange,
    If,
    Int8ub,
    Int16ub,
    Struct,
    Switch,
    this,
)

from dissector.errors import MalformedInput, NeedData
from dissector.model import Kind

_trailing = "trailing" / GreedyBytes
_address_quantity = ("start" / Int16ub, "quantity" / Int16ub)

READ_REQUEST = Struct(*_address_quantity, _trailing)
READ_BITS_RESPONSE = Struct("byte_count" / Int8ub, "status" / Bytes(this.byte_count), _trailing)
READ_REGISTERS_RESPONSE = Struct(
    "byte_count" / Int8ub,
    "values" / Array(this.byte_count // 2, Int16ub),
    "odd_byte" / If(this.byte_count % 2 == 1, Bytes(1)),
    _trailing,
)
WRITE_SINGLE = Struct("address" / Int16ub, "value" / Int16ub, _trailing)
EMPTY = Struct(_trailing)
DIAGNOSTICS = Struct("subfunction" / Int16ub, "data" / GreedyBytes)
WRITE_COILS_REQUEST = Struct(
    *_address_quantity, "byte_count" / Int8ub, "status" / Bytes(this.byte_count), _trailing
)
WRITE_REGISTERS_REQUEST = Struct(
    *_address_quantity,
    "byte_count" / Int8ub,
    "values" / Array(this.byte_count // 2, Int16ub),
    "odd_byte" / If(this.byte_count % 2 == 1, Bytes(1)),
    _trailing,
)
WRITE_MULTIPLE_RESPONSE = READ_REQUEST
EXCEPTION_STATUS_RESPONSE = Struct("status" / Int8ub, _trailing)
COMM_EVENT_COUNTER_RESPONSE = Struct("status" / Int16ub, "event_count" / Int16ub, _trailing)
COMM_EVENT_LOG_RESPONSE = Struct(
    "byte_count" / Int8ub,
    "status" / Int16ub,
    "event_count" / Int16ub,
    "message_count" / Int16ub,
    "events" / Bytes(this.byte_count - 6),
    _trailing,
)
BYTE_COUNTED = Struct("byte_count" / Int8ub, "data" / Bytes(this.byte_count), _trailing)

_FILE_SUBREQUEST = Struct(
    "reference_type" / Int8ub, "file" / Int16ub, "record" / Int16ub, "length" / Int16ub
)
READ_FILE_REQUEST = Struct(
    "byte_count" / Int8ub,
    "subrequests" / FixedSized(this.byte_count, GreedyRange(_FILE_SUBREQUEST)),
    _trailing,
)
_FILE_SUBRESPONSE = Struct(
    "length" / Int8ub,
    "reference_type" / Int8ub,
    "values" / Array((this.length - 1) // 2, Int16ub),
)
READ_FILE_RESPONSE = Struct(
    "byte_count" / Int8ub,
    "subresponses" / FixedSized(this.byte_count, GreedyRange(_FILE_SUBRESPONSE)),
    _trailing,
)
_FILE_WRITE_RECORD = Struct(
    "reference_type" / Int8ub,
    "file" / Int16ub,
    "record" / Int16ub,
    "length" / Int16ub,
    "values" / Array(this.length, Int16ub),
)
WRITE_FILE = Struct(
    "byte_count" / Int8ub,
    "records" / FixedSized(this.byte_count, GreedyRange(_FILE_WRITE_RECORD)),
    _trailing,
)
MASK_WRITE = Struct("address" / Int16ub, "and_mask" / Int16ub, "or_mask" / Int16ub, _trailing)
READ_WRITE_REQUEST = Struct(
    "read_start" / Int16ub,
    "read_quantity" / Int16ub,
    "write_start" / Int16ub,
    "write_quantity" / Int16ub,
    "byte_count" / Int8ub,
    "values" / Array(this.byte_count // 2, Int16ub),
    "odd_byte" / If(this.byte_count % 2 == 1, Bytes(1)),
    _trailing,
)
FIFO_REQUEST = Struct("address" / Int16ub, _trailing)
FIFO_RESPONSE = Struct(
    "byte_count" / Int16ub,
    "fifo_count" / Int16ub,
    "values" / Array(this.fifo_count, Int16ub),
    _trailing,
)
MEI_REQUEST = Struct(
    "mei_type" / Int8ub,
    "body"
    / Switch(
        this.mei_type,
        {14: Struct("read_code" / Int8ub, "object_id" / Int8ub)},
        default=Struct("data" / GreedyBytes),
    ),
    _trailing,
)
_DEVICE_OBJECT = Struct("id" / Int8ub, "length" / Int8ub, "value" / Bytes(this.length))
MEI_RESPONSE = Struct(
    "mei_type" / Int8ub,
    "body"
    / Switch(
        this.mei_type,
        {
            14: Struct(
                "read_code" / Int8ub,
                "conformity" / Int8ub,
                "more_follows" / Int8ub,
                "next_object_id" / Int8ub,
                "object_count" / Int8ub,
                "objects" / Array(this.object_count, _DEVICE_OBJECT),
            )
        },
        default=Struct("data" / GreedyBytes),
    ),
    _trailing,
)
EXCEPTION = Struct("exception_code" / Int8ub, _trailing)
RAW = Struct("data" / GreedyBytes)

_REQUEST = Kind.REQUEST
_RESPONSE = Kind.RESPONSE

GRAMMARS: dict[tuple[int, Kind], Construct] = {
    (1, _REQUEST): READ_REQUEST,
    (1, _RESPONSE): READ_BITS_RESPONSE,
    (2, _REQUEST): READ_REQUEST,
    (2, _RESPONSE): READ_BITS_RESPONSE,
    (3, _REQUEST): READ_REQUEST,
    (3, _RESPONSE): READ_REGISTERS_RESPONSE,
    (4, _REQUEST): READ_REQUEST,
    (4, _RESPONSE): READ_REGISTERS_RESPONSE,
    (5, _REQUEST): WRITE_SINGLE,
    (5, _RESPONSE): WRITE_SINGLE,
    (6, _REQUEST): WRITE_SINGLE,
    (6, _RESPONSE): WRITE_SINGLE,
    (7, _REQUEST): EMPTY,
    (7, _RESPONSE): EXCEPTION_STATUS_RESPONSE,
    (8, _REQUEST): DIAGNOSTICS,
    (8, _RESPONSE): DIAGNOSTICS,
    (11, _REQUEST): EMPTY,
    (11, _RESPONSE): COMM_EVENT_COUNTER_RESPONSE,
    (12, _REQUEST): EMPTY,
    (12, _RESPONSE): COMM_EVENT_LOG_RESPONSE,
    (15, _REQUEST): WRITE_COILS_REQUEST,
    (15, _RESPONSE): WRITE_MULTIPLE_RESPONSE,
    (16, _REQUEST): WRITE_REGISTERS_REQUEST,
    (16, _RESPONSE): WRITE_MULTIPLE_RESPONSE,
    (17, _REQUEST): EMPTY,
    (17, _RESPONSE): BYTE_COUNTED,
    (20, _REQUEST): READ_FILE_REQUEST,
    (20, _RESPONSE): READ_FILE_RESPONSE,
    (21, _REQUEST): WRITE_FILE,
    (21, _RESPONSE): WRITE_FILE,
    (22, _REQUEST): MASK_WRITE,
    (22, _RESPONSE): MASK_WRITE,
    (23, _REQUEST): READ_WRITE_REQUEST,
    (23, _RESPONSE): READ_REGISTERS_RESPONSE,
    (24, _REQUEST): FIFO_REQUEST,
    (24, _RESPONSE): FIFO_RESPONSE,
    (43, _REQUEST): MEI_REQUEST,
    (43, _RESPONSE): MEI_RESPONSE,
}


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


def parse_pdu(function: int, kind: Kind, data: bytes) -> Container:
    """Parse the PDU data that follows the function code. Raises GrammarError with the failing path."""
    grammar = grammar_for(function, kind)
    try:
        return _compiled(grammar).parse(data)
    except ConstructError as error:
        raise _grammar_error(error) from None
    except (struct.error, ValueError, IndexError, OverflowError, EOFError):
        # The compiled parsers fail with plain Python errors; the interpreted grammar names the path.
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
