"""Fast parsing of the common, well-formed PDUs without Construct.

The Construct grammars in grammar.py are the reference; this module returns the very same Container
(same keys, same values) for the frames that make up nearly all of a polling bus's traffic (FC1-6,
15, 16, 23 and exceptions), about ten times faster. Anything it does not recognise as well formed it
leaves to the grammar (returns None), so malformed frames get the grammar's precise error messages.
tests/unit/test_fastpath.py holds the two against each other; the protocol table says which
function codes use which layout.
"""
from __future__ import annotations

from struct import Struct

from construct import Container, ListContainer

from dissector.model import Kind
from dissector.protocol import table

_TWO_WORDS = Struct(">HH")
_THREE_WORDS = Struct(">HHH")
_FOUR_WORDS = Struct(">HHHH")
_WORDS: dict[int, Struct] = {}


def _words(data: bytes, start: int, count: int) -> ListContainer:
    unpacker = _WORDS.get(count)
    if unpacker is None:
        unpacker = _WORDS[count] = Struct(f">{count}H")
    return ListContainer(unpacker.unpack_from(data, start))


def _read_request(pdu: bytes) -> Container | None:
    if len(pdu) != 5:
        return None
    start, quantity = _TWO_WORDS.unpack_from(pdu, 1)
    return Container(start=start, quantity=quantity, trailing=b"")


def _registers_response(pdu: bytes) -> Container | None:
    count = pdu[1] if len(pdu) > 1 else -1
    if count < 0 or count & 1 or len(pdu) != 2 + count:
        return None
    return Container(byte_count=count, values=_words(pdu, 2, count >> 1), odd_byte=None, trailing=b"")


def _bits_response(pdu: bytes) -> Container | None:
    count = pdu[1] if len(pdu) > 1 else -1
    if count < 0 or len(pdu) != 2 + count:
        return None
    return Container(byte_count=count, status=pdu[2:], trailing=b"")


def _write_single(pdu: bytes) -> Container | None:
    if len(pdu) != 5:
        return None
    address, value = _TWO_WORDS.unpack_from(pdu, 1)
    return Container(address=address, value=value, trailing=b"")


def _write_registers_request(pdu: bytes) -> Container | None:
    if len(pdu) < 6:
        return None
    count = pdu[5]
    if count & 1 or len(pdu) != 6 + count:
        return None
    start, quantity = _TWO_WORDS.unpack_from(pdu, 1)
    return Container(
        start=start,
        quantity=quantity,
        byte_count=count,
        values=_words(pdu, 6, count >> 1),
        odd_byte=None,
        trailing=b"",
    )


def _write_coils_request(pdu: bytes) -> Container | None:
    if len(pdu) < 6 or len(pdu) != 6 + pdu[5]:
        return None
    start, quantity = _TWO_WORDS.unpack_from(pdu, 1)
    return Container(start=start, quantity=quantity, byte_count=pdu[5], status=pdu[6:], trailing=b"")


def _read_write_request(pdu: bytes) -> Container | None:
    if len(pdu) < 10:
        return None
    count = pdu[9]
    if count & 1 or len(pdu) != 10 + count:
        return None
    read_start, read_quantity, write_start, write_quantity = _FOUR_WORDS.unpack_from(pdu, 1)
    return Container(
        read_start=read_start,
        read_quantity=read_quantity,
        write_start=write_start,
        write_quantity=write_quantity,
        byte_count=count,
        values=_words(pdu, 10, count >> 1),
        odd_byte=None,
        trailing=b"",
    )


def _exception(pdu: bytes) -> Container | None:
    if len(pdu) != 2:
        return None
    return Container(exception_code=pdu[1], trailing=b"")


def _empty(pdu: bytes) -> Container:
    return Container(trailing=pdu[1:])


def _diagnostics(pdu: bytes) -> Container | None:
    if len(pdu) < 3:
        return None
    return Container(subfunction=pdu[1] << 8 | pdu[2], data=pdu[3:])


def _exception_status_response(pdu: bytes) -> Container | None:
    if len(pdu) < 2:
        return None
    return Container(status=pdu[1], trailing=pdu[2:])


def _comm_event_counter_response(pdu: bytes) -> Container | None:
    if len(pdu) < 5:
        return None
    status, count = _TWO_WORDS.unpack_from(pdu, 1)
    return Container(status=status, event_count=count, trailing=pdu[5:])


def _mask_write(pdu: bytes) -> Container | None:
    if len(pdu) < 7:
        return None
    address, and_mask = _TWO_WORDS.unpack_from(pdu, 1)
    return Container(address=address, and_mask=and_mask, or_mask=pdu[5] << 8 | pdu[6], trailing=pdu[7:])


def _fifo_request(pdu: bytes) -> Container | None:
    if len(pdu) < 3:
        return None
    return Container(address=pdu[1] << 8 | pdu[2], trailing=pdu[3:])


def _fifo_response(pdu: bytes) -> Container | None:
    if len(pdu) < 5:
        return None
    byte_count, fifo_count = _TWO_WORDS.unpack_from(pdu, 1)
    if len(pdu) < 5 + 2 * fifo_count:
        return None
    return Container(
        byte_count=byte_count, fifo_count=fifo_count, values=_words(pdu, 5, fifo_count), trailing=pdu[5 + 2 * fifo_count :]
    )


# File records (FC20/21): only runs of records that fill the byte count exactly; anything else (a
# record cut short, bytes the grammar's GreedyRange would leave) is the grammar's to judge.
def _read_file_request(pdu: bytes) -> Container | None:
    count = pdu[1] if len(pdu) > 1 else -1
    if count < 0 or count % 7 or len(pdu) < 2 + count:
        return None
    subrequests = ListContainer()
    for offset in range(2, 2 + count, 7):
        file, record, length = _THREE_WORDS.unpack_from(pdu, offset + 1)
        subrequests.append(Container(reference_type=pdu[offset], file=file, record=record, length=length))
    return Container(byte_count=count, subrequests=subrequests, trailing=pdu[2 + count :])


def _read_file_response(pdu: bytes) -> Container | None:
    count = pdu[1] if len(pdu) > 1 else -1
    end = 2 + count
    if count < 0 or len(pdu) < end:
        return None
    subresponses = ListContainer()
    offset = 2
    while offset < end:
        if offset + 2 > end or pdu[offset] < 1:
            return None
        length = pdu[offset]
        words = (length - 1) // 2
        if offset + 2 + 2 * words > end:
            return None
        subresponses.append(Container(length=length, reference_type=pdu[offset + 1], values=_words(pdu, offset + 2, words)))
        offset += 2 + 2 * words
    return Container(byte_count=count, subresponses=subresponses, trailing=pdu[end:])


def _write_file(pdu: bytes) -> Container | None:
    count = pdu[1] if len(pdu) > 1 else -1
    end = 2 + count
    if count < 0 or len(pdu) < end:
        return None
    records = ListContainer()
    offset = 2
    while offset < end:
        if offset + 7 > end:
            return None
        file, record, length = _THREE_WORDS.unpack_from(pdu, offset + 1)
        if offset + 7 + 2 * length > end:
            return None
        records.append(Container(
            reference_type=pdu[offset], file=file, record=record, length=length, values=_words(pdu, offset + 7, length)
        ))
        offset += 7 + 2 * length
    return Container(byte_count=count, records=records, trailing=pdu[end:])


def _mei_request(pdu: bytes) -> Container | None:
    if len(pdu) < 2:
        return None
    if pdu[1] != 14:
        return Container(mei_type=pdu[1], body=Container(data=pdu[2:]), trailing=b"")
    if len(pdu) < 4:
        return None
    return Container(mei_type=14, body=Container(read_code=pdu[2], object_id=pdu[3]), trailing=pdu[4:])


def _mei_response(pdu: bytes) -> Container | None:
    if len(pdu) < 2:
        return None
    if pdu[1] != 14:
        return Container(mei_type=pdu[1], body=Container(data=pdu[2:]), trailing=b"")
    if len(pdu) < 7:
        return None
    objects = ListContainer()
    offset = 7
    for _ in range(pdu[6]):
        if offset + 2 > len(pdu) or offset + 2 + pdu[offset + 1] > len(pdu):
            return None
        length = pdu[offset + 1]
        objects.append(Container(id=pdu[offset], length=length, value=pdu[offset + 2 : offset + 2 + length]))
        offset += 2 + length
    body = Container(
        read_code=pdu[2], conformity=pdu[3], more_follows=pdu[4], next_object_id=pdu[5], object_count=pdu[6], objects=objects
    )
    return Container(mei_type=14, body=body, trailing=pdu[offset:])


# Fast parsers by layout name (protocol/table.py); the table says which codes use which layout.
_BY_LAYOUT = {
    "read_request": _read_request,
    "write_multiple_response": _read_request,
    "read_bits_response": _bits_response,
    "read_registers_response": _registers_response,
    "write_single": _write_single,
    "write_coils_request": _write_coils_request,
    "write_registers_request": _write_registers_request,
    "read_write_request": _read_write_request,
    "empty": _empty,
    "diagnostics": _diagnostics,
    "exception_status_response": _exception_status_response,
    "comm_event_counter_response": _comm_event_counter_response,
    "mask_write": _mask_write,
    "fifo_request": _fifo_request,
    "fifo_response": _fifo_response,
    "read_file_request": _read_file_request,
    "read_file_response": _read_file_response,
    "write_file": _write_file,
    "mei_request": _mei_request,
    "mei_response": _mei_response,
}

_FAST_BY_KIND = {
    kind: {code: _BY_LAYOUT[name] for code, name in names.items() if name in _BY_LAYOUT}
    for kind, names in table.by_kind("name").items()
}


def fast_parse(function: int, kind: Kind, pdu: bytes) -> Container | None:
    """The grammar's Container for a well-formed common PDU (function code included), else None."""
    if kind is Kind.EXCEPTION:
        return _exception(pdu)
    parser = _FAST_BY_KIND[kind].get(function)
    return parser(pdu) if parser is not None else None
