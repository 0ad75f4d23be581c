"""The RTU framer's length rules and tables (rtu.py): per function code and direction, the frame's length
from its first bytes, CRC included, as the protocol table (protocol/table.py) states them; the order in
which interpretations are tried; the byte pairs that may start a frame; what a glitch byte is."""
from __future__ import annotations

import re
from collections.abc import Callable

from dissector.framing.stream import GLITCH_BYTES
from dissector.model import Kind
from dissector.protocol import table
from dissector.protocol.crc import crc16
from dissector.protocol.spec import SPEC

MAX_ADU = int(SPEC.limits["max_adu"])  # type: ignore[call-overload]
MIN_ADU = 4
MAX_SLAVE = int(SPEC.limits["max_slave"])  # type: ignore[call-overload]

NEED = -1  # not enough bytes yet to know the length
NONE = 0  # this interpretation cannot apply here

LengthRule = Callable[[bytes | bytearray, int, int], int]


def _fixed(length: int) -> LengthRule:
    def rule(buf: bytes | bytearray, i: int, n: int) -> int:
        return length

    return rule


def _count8(position: int, extra: int) -> LengthRule:
    """Length = extra + the byte count found at `position` in the frame."""

    def rule(buf: bytes | bytearray, i: int, n: int) -> int:
        if i + position >= n:
            return NEED
        return extra + buf[i + position]

    return rule


def _count16(position: int, extra: int) -> LengthRule:
    def rule(buf: bytes | bytearray, i: int, n: int) -> int:
        if i + position + 1 >= n:
            return NEED
        return extra + (buf[i + position] << 8 | buf[i + position + 1])

    return rule


class Scan(int):
    """A length rule's answer when the layout gives no length: scan for a CRC from this minimum."""


def _crc_ok(buf: bytes | bytearray, i: int, length: int) -> bool:
    stop = i + length - 2
    return crc16(buf[i:stop]) == buf[stop] | buf[stop + 1] << 8


def _diagnostics(buf: bytes | bytearray, i: int, n: int) -> int:
    # Return Query Data (sub-function 0) echoes any amount of data; all others carry one word.
    if i + 3 >= n:
        return NEED
    if buf[i + 2] == 0 and buf[i + 3] == 0:
        return Scan(6)
    return 8


def _mei_request(buf: bytes | bytearray, i: int, n: int) -> int:
    if i + 2 >= n:
        return NEED
    return 7 if buf[i + 2] == 14 else Scan(5)


def _mei_response(buf: bytes | bytearray, i: int, n: int) -> int:
    """Walk the FC43/14 object list: 8 header bytes, then (id, length, value) per object."""
    if i + 2 >= n:
        return NEED
    if buf[i + 2] != 14:
        return Scan(5)
    if i + 7 >= n:
        return NEED
    count = buf[i + 7]
    position = 8
    for _ in range(count):
        if i + position + 1 >= n:
            return NEED
        position += 2 + buf[i + position + 1]
        if position > MAX_ADU:
            return NONE
    return position + 2


def _scan_any(buf: bytes | bytearray, i: int, n: int) -> int:
    return Scan(MIN_ADU)


_SPECIAL: dict[str, LengthRule] = {
    "diagnostics": _diagnostics,
    "mei_request": _mei_request,
    "mei_response": _mei_response,
    "scan": _scan_any,
}


def length_rule(rule: table.LengthRule) -> LengthRule:
    """The framer's function for a length rule of the protocol table."""
    if isinstance(rule, table.Fixed):
        return _fixed(rule.length)
    if isinstance(rule, table.Counted):
        return (_count8 if rule.width == 1 else _count16)(rule.position, rule.extra)
    return _SPECIAL[rule.name]


def quantity_rule(alternative: table.ByQuantity, counted: table.Counted) -> LengthRule:
    """A request's length by its quantity (table.ByQuantity), NONE where it is the byte count's."""

    def rule(buf: bytes | bytearray, i: int, n: int) -> int:
        if i + max(alternative.position + 1, counted.position) >= n:
            return NEED
        length = alternative.length(buf[i + alternative.position] << 8 | buf[i + alternative.position + 1])
        return NONE if length == counted.extra + buf[i + counted.position] else length

    return rule


# (request rule, response rule) per function code: lengths of the whole ADU, CRC included.
RULES: dict[int, tuple[LengthRule, LengthRule]] = {
    entry.code: (length_rule(entry.request.length), length_rule(entry.response.length))
    for entry in table.FUNCTIONS
}
# Requests whose byte count may disagree with their quantity: the quantity's length, tried last.
BY_QUANTITY: dict[int, LengthRule] = {
    entry.code: quantity_rule(entry.request.by_quantity, entry.request.length)  # type: ignore[arg-type]
    for entry in table.FUNCTIONS
    if entry.request.by_quantity is not None and isinstance(entry.request.length, table.Counted)
}
OTHER_FUNCTIONS = table.OTHER_FUNCTIONS
for _code in OTHER_FUNCTIONS:
    RULES.setdefault(_code, (_scan_any, _scan_any))


_EXCEPTION_LENGTH = table.EXCEPTION_LAYOUT.length.length  # type: ignore[union-attr]
_EXCEPTION_RULE = _fixed(_EXCEPTION_LENGTH)

# Interpretations to try at a frame start, in order: the expected direction first.
REQUEST_FIRST: dict[int, tuple[tuple[Kind, LengthRule], ...]] = {}
RESPONSE_FIRST: dict[int, tuple[tuple[Kind, LengthRule], ...]] = {}
for _code, (_request_rule, _response_rule) in RULES.items():
    _extra = ((Kind.REQUEST, BY_QUANTITY[_code]),) if _code in BY_QUANTITY else ()
    REQUEST_FIRST[_code] = ((Kind.REQUEST, _request_rule), (Kind.RESPONSE, _response_rule), *_extra)
    RESPONSE_FIRST[_code] = ((Kind.RESPONSE, _response_rule), (Kind.REQUEST, _request_rule), *_extra)
    REQUEST_FIRST[_code | 0x80] = RESPONSE_FIRST[_code | 0x80] = ((Kind.EXCEPTION, _EXCEPTION_RULE),)



def interpretations(
    slave: int, function: int, expect: tuple[int, int] | None
) -> tuple[tuple[Kind, LengthRule], ...]:
    """The (kind, length rule) pairs a frame starting with slave and function may have, likeliest
    first: after a request from (slave, function), its response. Empty: no frame starts here."""
    if expect == (slave, function):
        return RESPONSE_FIRST.get(function, ())
    return REQUEST_FIRST.get(function, ())


# A byte pair that may start a frame: any address (248..255 are reserved, framed with a warning by the
# decoder: pymodbus uses 254 and 255, tshark decodes them), then a function code with a layout.
_POSSIBLE_START = re.compile(
    b".[%s]" % b"".join(b"\\x%02x" % code for code in sorted(REQUEST_FIRST)),
    re.DOTALL,
)

GLITCH_SKIP = 16  # glitch bytes looked past when asking what follows a frame
NOT_BROADCAST = frozenset(SPEC.not_broadcast)  # function codes a broadcast (slave 0) may not carry
# Glitch bytes that are no device's address (broadcast, reserved): a frame read from one loses to a frame
# right after it (the glitch, then the frame): on a line with idle FF before every frame, a reserved
# slave 255 would otherwise pass a CRC once in 65,536 frames.
GLITCH_ADDRESSES = frozenset(value for value in GLITCH_BYTES if value == 0 or value > MAX_SLAVE)


# The fast path of _run: the first interpretation only, with fixed lengths as plain numbers.
def _fixed_lengths(kind: Kind) -> dict[int, int]:
    rules = ((entry.code, entry.layout(kind).length) for entry in table.FUNCTIONS)
    return {code: rule.length for code, rule in rules if isinstance(rule, table.Fixed)}


def _first_choice(orders: dict[int, tuple[tuple[Kind, LengthRule], ...]]) -> dict[int, tuple[Kind, int, LengthRule]]:
    fixed_requests = _fixed_lengths(Kind.REQUEST)
    fixed_responses = _fixed_lengths(Kind.RESPONSE)
    first = {}
    for code, choices in orders.items():
        kind, rule = choices[0]
        if kind is Kind.EXCEPTION:
            fixed = _EXCEPTION_LENGTH
        elif kind is Kind.REQUEST:
            fixed = fixed_requests.get(code, 0)
        else:
            fixed = fixed_responses.get(code, 0)
        first[code] = (kind, fixed, rule)
    return first


_REQUEST_FIRST_FAST = _first_choice(REQUEST_FIRST)
_RESPONSE_FIRST_FAST = _first_choice(RESPONSE_FIRST)
