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
from dissector.protocol.shapes import PARTS, SHAPES, Field, Type, has_trailing

_WORDS: dict[int, Struct] = {}


def _words(data: bytes, start: int, count: int) -> ListContainer:
    unpacker = _WORDS.get(count)
    if unpacker is None:
        unpacker = _WORDS[count] = Struct(f">{count}H")
    return ListContainer(unpacker.unpack_from(data, start))


def regular(shape: tuple[Field, ...], part: bool = False) -> Callable[..., object] | None:
    """The fast parser of a layout data/modbus.toml [layouts] describes: its fixed-size head in one
    unpack, then its counted fields, its parts (records, arrays, a switch) by their own fast parsers.
    Steps aside (None) where the grammar must judge: data too short for a field, an odd byte count of
    words (the grammar's odd_byte), a count less its constant below zero, records that do not fill
    their byte count exactly (the grammar's GreedyRange).

    It is written as Python source from the description and compiled once, as dataclasses writes its
    methods: a generic loop over the fields cost 1.5 to 4 times the hand-written parsers this replaces,
    on the path every frame takes. Field names are identifiers (protocol/shapes.py checks them).
    A part's parser (`part`) reads from `at` to `n` and gives its Container and where it ends.
    None for a layout with text, named values or fields present on a condition: the grammar makes those."""
    if any(field.type is Type.TEXT or field.names or field.when for field in shape):
        return None
    parts = {name: regular(PARTS[name], part=True) for field in shape
             for name in [field.part, *(case for _, case in field.cases)] if name is not None}
    if None in parts.values():
        return None
    head = 0
    while head < len(shape) and shape[head].size is not None:
        head += 1
    if any(field.size is not None for field in shape[head:]):
        raise ValueError(f"a fixed-size field after a counted one: {shape}")
    unpacker = Struct(">" + "".join("B" if field.size == 1 else "H" for field in shape[:head]))

    def at(offset: int) -> str:  # a layout's data start after the function code, a part's at `at`
        return (f"at + {offset}" if offset else "at") if part else str(offset + 1)

    code = ["def parse(pdu, at, n):" if part else "def parse(pdu):", *([] if part else ["    n = len(pdu)"]),
            f"    if n < {at(unpacker.size)}:", "        return None"]
    if head == 1:  # one byte or word: indexing is quicker than an unpack call
        code.append(f"    f_{shape[0].name} = pdu[{at(0)}]" + (f" << 8 | pdu[{at(1)}]" if shape[0].size == 2 else ""))
    elif head:
        code.append(f"    {''.join(f'f_{field.name}, ' for field in shape[:head])}= unpack(pdu, {at(0)})")
    position = at(unpacker.size)
    for index, field in enumerate(shape[head:]):
        name, count, stop = f"f_{field.name}", f"f_{field.count}", f"e{index}"
        if field.minus:
            code += [f"    s{index} = {count} - {field.minus}", f"    if s{index} < 0:", "        return None"]
            count = f"s{index}"
        if field.type is Type.REST:
            code.append(f"    {name} = pdu[{position}:{'n' if part else ''}]")
            position = "n"
        elif field.type is Type.ODD:  # a byte count of words that is odd is the grammar's to judge
            code += [f"    if {count} & 1:", "        return None", f"    {name} = None"]
        elif field.type is Type.SWITCH:
            choice = " else ".join(f"P_{case} if {count} == {value}" if value is not None else f"P_{case}"
                                   for value, case in field.cases)
            code += [f"    r = ({choice})(pdu, {position}, n)", "    if r is None:", "        return None",
                     f"    {name}, {stop} = r"]
            position = stop
        elif field.type in (Type.RECORDS, Type.ARRAY):
            records = field.type is Type.RECORDS  # (parts that fill `count` bytes, or `count` parts)
            if records:
                code += [f"    {stop} = {position} + {count}", f"    if {stop} > n:", "        return None"]
            code += [f"    {name} = ListContainer()", f"    p = {position}",
                     f"    while p < {stop}:" if records else f"    for _ in range({count}):",
                     f"        r = P_{field.part}(pdu, p, {stop if records else 'n'})",
                     # (an array's part that does not fit ends it: a count the data do not hold, layouts._UpTo)
                     "        if r is None:", "            return None" if records else "            break",
                     "        item, p = r", f"        {name}.append(item)"]
            if not records:
                code.append(f"    {stop} = p")
            position = stop
        else:
            size = (f"({count} >> 1)" if field.half else count) if field.type is Type.WORDS else count
            code += [f"    {stop} = {position} + {'2 * ' if field.type is Type.WORDS else ''}{size}",
                     f"    if {stop} > n:", "        return None"]
            code.append(f"    {name} = words(pdu, {position}, {size})" if field.type is Type.WORDS
                        else f"    {name} = pdu[{position}:{stop}]")
            position = stop
    values = [f"{field.name}=f_{field.name}" for field in shape]
    if part:
        code.append(f"    return Container({', '.join(values)}), {position}")
    else:
        if has_trailing(shape):
            values.append(f"trailing=pdu[{position}:]")
        code.append(f"    return Container({', '.join(values)})")
    namespace: dict[str, object] = {"unpack": unpacker.unpack_from, "words": _words, "Container": Container,
                                    "ListContainer": ListContainer, **{f"P_{name}": parse for name, parse in parts.items()}}
    exec("\n".join(code), namespace)  # noqa: S102  (source made above from checked identifiers)
    return namespace["parse"]  # type: ignore[return-value]


# Fast parsers by layout name (protocol/table.py), from their descriptions; the table says which codes
# use which layout.
_BY_LAYOUT = {name: parser for name, shape in SHAPES.items() if (parser := regular(shape)) is not None}
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
