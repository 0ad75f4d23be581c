"""The length of the normal answer a request implies, where the protocol table fixes it by the request: an
answer counted by a byte count (table.Counted) whose lifting rule has that count follow the quantity the
request asks ([lift] count of `request.quantity`: FC1..4 and FC23's reads). The framers weigh an answer
awaited that the end of the capture cuts by it (rtu.py, ascii.py _cut_answer): a response reading of another
length is no answer of this request, whatever its byte count says (the next request cut short, `0C 03 20 D0`
after a read of 3 registers, was 'the response (4 of 37 bytes)')."""
from __future__ import annotations

from dissector.model import Frame, Kind
from dissector.protocol import table
from dissector.protocol.rules import REQUEST_PREFIX, Count

_WINDOW_QUANTITY = REQUEST_PREFIX + "quantity"  # (the quantity of the window the request was lifted to)


def _answers() -> dict[int, tuple[int, int, Count]]:
    """code -> (offset of the request's quantity word in its data, the answer's length besides its byte
    count, the count's rule)."""
    found = {}
    for entry in table.FUNCTIONS:
        counted = entry.response.length
        answer = table.lift_of(entry.code, Kind.RESPONSE)
        request = table.lift_of(entry.code, Kind.REQUEST)
        if not isinstance(counted, table.Counted) or answer is None or request is None:
            continue
        asked = request.quantity
        if answer.count is None or answer.count.of != _WINDOW_QUANTITY or not isinstance(asked, str):
            continue
        offset = table.field_offset(entry.request.grammar, asked)
        found[entry.code] = (offset, counted.extra, answer.count)
    return found


ANSWERS = _answers()


def answer_length(request: Frame) -> int | None:
    """The length (CRC included) of the normal answer `request` implies; None: its code's answer length does
    not follow from the request alone, or the request is too short to say."""
    rule = ANSWERS.get(request.function)
    if rule is None:
        return None
    offset, extra, count = rule
    pdu = request.pdu
    if len(pdu) < 3 + offset:
        return None
    return extra + count.expected(pdu[1 + offset] << 8 | pdu[2 + offset])
