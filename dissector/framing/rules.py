"""The RTU framer's length rules and tables (rtu.py): per function code and direction, the frame's length
from its first bytes, CRC included, as the protocol table (protocol/table.py) states them; the order in
which interpretations are tried; the byte pairs that may start a frame; what a glitch byte is."""
from __future__ import annotations

import re
from collections.abc import Callable

from dissector.framing.stream import GLITCH_BYTES
from dissector.model import CUT_ANSWER, Kind
from dissector.protocol import table
from dissector.protocol.crc import crc16, crc_lengths
from dissector.protocol.rules import data_bytes
from dissector.protocol.spec import SPEC

MAX_ADU = int(SPEC.limits["max_adu"])  # type: ignore[call-overload]
MAX_COUNTED = table.LONGEST_COUNTED  # (a length rule's frame over MAX_ADU counts with a good CRC only, warned)
MIN_ADU = table.SCAN.minimum
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
    """A length rule's answer when the layout gives no length: scan for a CRC from this minimum.

    `declared`: the length the frame's own fields gave when they do not end in a valid CRC (a rule with a
    CRC fallback, _mei_objects), NEED when they run past the bytes there, NONE for a plain scan: the
    framer shows a damaged frame of that length, or an answer cut by the end of the capture, by it."""

    declared = NONE
    wanted = 0  # where `declared` is NEED: the index (from the frame's start) of the byte the walk stopped short of


def _crc_ok(buf: bytes | bytearray, i: int, length: int) -> bool:
    stop = i + length - 2
    return crc16(buf[i:stop]) == buf[stop] | buf[stop + 1] << 8


def _scan(minimum: int) -> LengthRule:
    found = Scan(minimum)

    def rule(buf: bytes | bytearray, i: int, n: int) -> int:
        return found

    return rule


def _select(select: table.Select) -> LengthRule:
    """The rule the field at select.position picks (table.Select): the field's count rule with nothing added."""
    field = length_rule(table.Counted(select.position, 0, select.width))
    value, chosen, otherwise = select.value, length_rule(select.chosen), length_rule(select.otherwise)

    def rule(buf: bytes | bytearray, i: int, n: int) -> int:
        found = field(buf, i, n)
        if found == value:
            return chosen(buf, i, n)
        return NEED if found == NEED else otherwise(buf, i, n)

    return rule


def _mei_objects(position: int, start: int) -> LengthRule:
    """Walk the FC43/14 object list: its count at `position`, then (id, length, value) per object from `start`.

    A device may declare more objects than it sends (or fewer): where the walk does not end in a valid CRC
    (it runs past the bytes there or past an RTU frame, or the CRC there fails), the frame is the shortest
    CRC match from the list's start (a Scan of start + 2, the CRC), its `declared` the walk's length."""
    minimum = start + 2

    def fallback(declared: int, wanted: int = 0) -> Scan:
        found = Scan(minimum)
        found.declared, found.wanted = declared, wanted
        return found

    def rule(buf: bytes | bytearray, i: int, n: int) -> int:
        if i + position >= n:
            return NEED
        stop = start
        for _ in range(buf[i + position]):
            if i + stop + 1 >= n:
                return fallback(NEED, stop + 1)
            stop += 2 + buf[i + stop + 1]
            if stop > MAX_ADU:
                return fallback(NONE)
        length = stop + 2
        if i + length <= n and _crc_ok(buf, i, length):
            return length
        return fallback(length)

    return rule


_SPECIAL: dict[str, Callable[[int, int], LengthRule]] = {"mei_objects": _mei_objects}


def length_rule(rule: table.LengthRule) -> LengthRule:
    """The framer's function for a length rule of the protocol table."""
    if isinstance(rule, table.Fixed):
        return _fixed(rule.length)
    if isinstance(rule, table.Counted):
        return (_count8 if rule.width == 1 else _count16)(rule.position, rule.extra)
    if isinstance(rule, table.Scan):
        return _scan(rule.minimum)
    if isinstance(rule, table.Select):
        return _select(rule)
    return _SPECIAL[rule.name](rule.position, rule.start)


def quantity_rule(alternative: table.ByQuantity, counted: table.Counted) -> LengthRule:
    """A request's length by its quantity (table.ByQuantity), NONE where it is the byte count's."""
    position, extra, unit = alternative.position, alternative.extra, alternative.unit

    def rule(buf: bytes | bytearray, i: int, n: int) -> int:
        if i + max(position + 1, counted.position) >= n:
            return NEED
        length = extra + data_bytes(buf[i + position] << 8 | buf[i + position + 1], unit)
        return NONE if length == counted.extra + buf[i + counted.position] else length

    return rule


# (request rule, response rule) per function code: lengths of the whole ADU, CRC included.
RULES: dict[int, tuple[LengthRule, LengthRule]] = {
    code: (length_rule(request.length), length_rule(response.length))
    for code, request, response in table.known_layouts()
}
# Requests whose byte count may disagree with their quantity: the quantity's length, tried last.
BY_QUANTITY: dict[int, LengthRule] = {
    entry.code: quantity_rule(entry.request.by_quantity, entry.request.length)  # type: ignore[arg-type]
    for entry in table.FUNCTIONS
    if entry.request.by_quantity is not None and isinstance(entry.request.length, table.Counted)
}
OTHER_FUNCTIONS = table.OTHER_FUNCTIONS


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



def spans_a_frame(data: bytes | bytearray) -> bool:
    """Have these bytes, a record of their own, a frame's shape: a layout at their first byte whose length
    (its rule's, a CRC scan's match, or the length its fields declare) is all of them, CRC good or bad?
    Between its record's start and end such a reading is a frame (rtu.py _match: a record that is a frame is
    the source's word); ending an input that has no records it is not, unless awaited (rtu.py _followed:
    the end of the input says little). The -w writer reads it so (render/capturefile.py
    CaptureOutput.release). Over MAX_ADU, a length rule's frame with a good CRC only (as the framer takes it)."""
    n = len(data)
    if not MIN_ADU <= n <= MAX_COUNTED:
        return False
    for _kind, rule in REQUEST_FIRST.get(data[1], ()):
        length = rule(data, 0, n)
        if type(length) is Scan:
            if n <= MAX_ADU and (length.declared == n or n in crc_lengths(data, 0, length, n)):
                return True
        elif length == n and (n <= MAX_ADU or _crc_ok(data, 0, n)):  # (over MAX_ADU: a good CRC only, rtu.py)
            return True
    return False


# How bytes live closes at a silence are cut (_cut_reason): not by the capture's end (model.py CUT_ANSWER, which
# pairing takes as the answer's fate: the capture goes on, and the answer may still come).
SILENCE_CUTS = "a silence cuts "


class Awaiting:
    """What a framer (RTU and ASCII alike) reads a frame start as, given the answer it awaits: its
    `_expect` (slave, function) and `_echo` (the bytes the answer repeats, StreamFramer._await_after)."""

    _expect: tuple[int, int] | None
    _echo: bytes
    _answer: int | None
    _cut_by_silence: bool

    def _awaited(self, buf: bytes | bytearray, i: int) -> bool:
        """Do the bytes at i begin the answer awaited: its slave and function (an exception's too) and, for a
        normal answer, what the spec has it repeat of the request (_echo, [pairing] echo: an FC8
        sub-function, as far as its bytes have come)? An FC8 frame that does not is the master's next
        request: an FC8 request and its answer have the same shape (decode/pairing.py pairs it so too)."""
        function = buf[i + 1]
        if self._expect != (buf[i], function & 0x7F):
            return False
        echo = self._echo
        if not echo or function & 0x80:
            return True
        got = buf[i + 2 : i + 2 + len(echo)]
        return got == echo[: len(got)]

    def _bounded_kind(self, buf: bytes | bytearray, i: int) -> Kind:
        """What a frame the line bounds is, whatever length its layout takes (bounded.py, an ASCII line with a
        good LRC): an exception by its function, else the answer awaited or a request."""
        if buf[i + 1] & 0x80:
            return Kind.EXCEPTION
        return Kind.RESPONSE if self._awaited(buf, i) else Kind.REQUEST

    def _not_the_answer(self, kind: Kind, length: int) -> bool:
        """Is a reading of `kind` and `length` at the answer awaited's start a normal answer of another length
        than its request implies (_answer, answers.py)? Its byte count cannot be the answer's then: at the end
        of the capture the bytes are read as the next request (0C 03 20 D0 after a read of 3 registers: 20 is
        its address's high byte, not a byte count of 32)."""
        return kind is Kind.RESPONSE and self._answer is not None and length != NEED and length != self._answer

    def _cut_reason(self, kind: Kind, size: str) -> str:
        """Why bytes the end of the capture cuts are noise, read as `kind`, `size` of it ('4 of 8 bytes'); where
        live closes them at a silence (StreamFramer.finish(silence=True)) the capture goes on: the silence cuts."""
        what = "response" if kind is Kind.RESPONSE else "exception response"
        if self._cut_by_silence:
            return f"{SILENCE_CUTS}{'a request' if kind is Kind.REQUEST else 'the ' + what} ({size})"
        if kind is Kind.REQUEST:
            # ('... inside a request': not the answer's words, which the request awaiting it takes, pairing.py)
            return f"{CUT_ANSWER[:-4]}a request ({size})"
        return f"{CUT_ANSWER}{what} ({size})"

    def _interpretations(self, buf: bytes | bytearray, i: int) -> tuple[tuple[Kind, LengthRule], ...]:
        """The (kind, length rule) pairs a frame at i may have, likeliest first: after a request, its
        answer's (_awaited); else a request's. Empty: no frame starts here."""
        return (RESPONSE_FIRST if self._awaited(buf, i) else REQUEST_FIRST).get(buf[i + 1], ())


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
