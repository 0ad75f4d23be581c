"""Fast parsing of the common, well-formed PDUs without Construct.

The Construct grammars in grammar.py are the reference; this module returns the very same Container
(same keys, same values) for the frames that make up nearly all of a polling bus's traffic (FC1-6,
15, 16, 23 and exceptions), about ten times faster. Anything it does not recognise as well formed it
leaves to the grammar (returns None), so malformed frames get the grammar's precise error messages.
tests/unit/test_fastpath.py holds the two against each other; the protocol table says which
function codes use which layout.
"""
from __future__ import annotations

from collections.abc import Callable
from struct import Struct

from construct import Container, ListContainer

from dissector.model import Kind
from dissector.protocol import table
from dissector.protocol.shapes import SHAPES, Field, Type, has_trailing

_THREE_WORDS = Struct(">HHH")
_WORDS: dict[int, Struct] = {}


def _words(data: bytes, start: int, count: int) -> ListContainer:
    unpacker = _WORDS.get(count)
    if unpacker is None:
        unpacker = _WORDS[count] = Struct(f">{count}H")
    return ListContainer(unpacker.unpack_from(data, start))


def regular(shape: tuple[Field, ...]) -> Callable[[bytes], Container | None]:
    """The fast parser of a layout data/modbus.toml [layouts] describes: its fixed-size head in one
    unpack, then its counted fields. Steps aside (None) where the grammar must judge: data too short
    for a field, or an odd byte count of words (the grammar's odd_byte).

    It is written as Python source from the description and compiled once, as dataclasses writes its
    methods: a generic loop over the fields cost 1.5 to 4 times the hand-written parsers this replaces,
    on the path every frame takes. Field names are identifiers (protocol/shapes.py checks them)."""
    head = 0
    while head < len(shape) and shape[head].size is not None:
        head += 1
    if any(field.size is not None for field in shape[head:]):
        raise ValueError(f"a fixed-size field after a counted one: {shape}")
    unpacker = Struct(">" + "".join("B" if field.size == 1 else "H" for field in shape[:head]))
    end = 1 + unpacker.size
    code = ["def parse(pdu):", "    n = len(pdu)", f"    if n < {end}:", "        return None"]
    if head == 1:  # one byte or word: indexing is quicker than an unpack call
        code.append(f"    f_{shape[0].name} = pdu[1]" + (" << 8 | pdu[2]" if shape[0].size == 2 else ""))
    elif head:
        code.append(f"    {''.join(f'f_{field.name}, ' for field in shape[:head])}= unpack(pdu, 1)")
    position = str(end)
    for index, field in enumerate(shape[head:]):
        name, count = f"f_{field.name}", f"f_{field.count}"
        if field.type is Type.REST:
            code.append(f"    {name} = pdu[{position}:]")
            position = "n"
        elif field.type is Type.ODD:  # a byte count of words that is odd is the grammar's to judge
            code += [f"    if {count} & 1:", "        return None", f"    {name} = None"]
        else:
            size = (f"({count} >> 1)" if field.half else count) if field.type is Type.WORDS else count
            stop = f"e{index}"
            code += [f"    {stop} = {position} + {'2 * ' if field.type is Type.WORDS else ''}{size}",
                     f"    if {stop} > n:", "        return None"]
            code.append(f"    {name} = words(pdu, {position}, {size})" if field.type is Type.WORDS
                        else f"    {name} = pdu[{position}:{stop}]")
            position = stop
    values = [f"{field.name}=f_{field.name}" for field in shape]
    if has_trailing(shape):
        values.append(f"trailing=pdu[{position}:]")
    code.append(f"    return Container({', '.join(values)})")
    namespace: dict[str, object] = {"unpack": unpacker.unpack_from, "words": _words, "Container": Container}
    exec("\n".join(code), namespace)  # noqa: S102  (source made above from checked identifiers)
    return namespace["parse"]  # type: ignore[return-value]


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


# Fast parsers by layout name (protocol/table.py): the regular layouts' from their descriptions, the
# irregular ones written above; the table says which codes use which layout.
_BY_LAYOUT = {
    **{name: regular(shape) for name, shape in SHAPES.items()},
    "read_file_request": _read_file_request,
    "read_file_response": _read_file_response,
    "write_file": _write_file,
    "mei_request": _mei_request,
    "mei_response": _mei_response,
}
_EXCEPTION = _BY_LAYOUT["exception"]

_FAST_BY_KIND = {
    kind: {code: _BY_LAYOUT[name] for code, name in names.items() if name in _BY_LAYOUT}
    for kind, names in table.by_kind("name").items()
}


def fast_parse(function: int, kind: Kind, pdu: bytes) -> Container | None:
    """The grammar's Container for a well-formed common PDU (function code included), else None."""
    if kind is Kind.EXCEPTION:
        return _EXCEPTION(pdu)
    parser = _FAST_BY_KIND[kind].get(function)
    return parser(pdu) if parser is not None else None
