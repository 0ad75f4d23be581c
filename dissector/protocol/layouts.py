"""Construct layouts of the Modbus PDU data, one Struct per shape; protocol/table.py says which
(function code, direction) uses which.

The function code itself and the check (CRC/LRC) are not part of these layouts: the framer finds the
frame and records the check, so that a frame with a bad CRC is still shown rather than thrown away.
Every layout ends in `trailing`, so bytes past the documented layout are kept and reported, never lost.
"""
from __future__ import annotations

from construct import (
    Array,
    Bytes,
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
