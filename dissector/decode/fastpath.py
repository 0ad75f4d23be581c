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
