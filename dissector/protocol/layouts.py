"""Construct layouts of the Modbus PDU data, one Struct per shape; protocol/table.py says which
(function code, direction) uses which.

The function code itself and the check (CRC/LRC) are not part of these layouts: the framer finds the
frame and records the check, so that a frame with a bad CRC is still shown rather than thrown away.
Every layout ends in `trailing`, so bytes past the documented layout are kept and reported, never lost.

The regular layouts are made from their field descriptions (data/modbus.toml [layouts], read by
protocol/shapes.py), which the fast parser is made from too; the irregular ones are written here.
"""
from __future__ import annotations

from construct import (
    Adapter,
    Construct,
    Array,
    Bytes,
    Enum,
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

from dissector.protocol.shapes import SHAPES, Field, Type, has_trailing

_trailing = "trailing" / GreedyBytes


def _subcon(field: Field) -> Construct:
    count = field.count
    if field.type is Type.U8:
        return field.name / Int8ub
    if field.type is Type.U16:
        return field.name / Int16ub
    if field.type is Type.BYTES:
        return field.name / Bytes(this[count])
    if field.type is Type.WORDS:
        return field.name / Array((this[count] // 2) if field.half else this[count], Int16ub)
    if field.type is Type.ODD:
        return field.name / If(this[count] % 2 == 1, Bytes(1))
    return field.name / GreedyBytes


def regular(name: str) -> Struct:
    """The Construct grammar of a layout data/modbus.toml [layouts] describes."""
    shape = SHAPES[name]
    return Struct(*map(_subcon, shape), *([_trailing] if has_trailing(shape) else []))


READ_REQUEST = regular("read_request")
READ_BITS_RESPONSE = regular("read_bits_response")
READ_REGISTERS_RESPONSE = regular("read_registers_response")
WRITE_SINGLE = regular("write_single")
EMPTY = regular("empty")
DIAGNOSTICS = regular("diagnostics")
WRITE_COILS_REQUEST = regular("write_coils_request")
WRITE_REGISTERS_REQUEST = regular("write_registers_request")
WRITE_MULTIPLE_RESPONSE = regular("write_multiple_response")
EXCEPTION_STATUS_RESPONSE = regular("exception_status_response")
COMM_EVENT_COUNTER_RESPONSE = regular("comm_event_counter_response")
COMM_EVENT_LOG_RESPONSE = Struct(
    "byte_count" / Int8ub,
    "status" / Int16ub,
    "event_count" / Int16ub,
    "message_count" / Int16ub,
    "events" / Bytes(this.byte_count - 6),
    _trailing,
)


class _TextWhenPrintable(Adapter):  # type: ignore[misc]
    """Bytes shown as text when every one is printable ASCII (a version string), as bytes otherwise."""

    def _decode(self, obj: bytes, context: object, path: str) -> str | bytes:
        return obj.decode("ascii") if obj and all(0x20 <= byte < 0x7F for byte in obj) else obj

    def _encode(self, obj: str | bytes, context: object, path: str) -> bytes:
        return obj.encode("ascii") if isinstance(obj, str) else obj


# Report Server ID: the server id (one byte, as libmodbus and most devices send it), the run
# indicator (00 OFF, FF ON), then device-specific data, often a version string.
REPORT_SERVER_ID_RESPONSE = Struct(
    "byte_count" / Int8ub,
    "server_id" / Int8ub,
    "run_indicator" / Enum(Int8ub, OFF=0x00, ON=0xFF),
    "additional_data" / _TextWhenPrintable(Bytes(this.byte_count - 2)),
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
MASK_WRITE = regular("mask_write")
READ_WRITE_REQUEST = regular("read_write_request")
FIFO_REQUEST = regular("fifo_request")
FIFO_RESPONSE = regular("fifo_response")
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
EXCEPTION = regular("exception")
RAW = regular("raw")
