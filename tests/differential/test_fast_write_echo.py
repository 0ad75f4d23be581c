"""FC5/FC6 answers that do not echo their request (issue 26): the compiled path hands them to the Python
stages, which warn, and takes the echoes; both paths write the same lines. The engine's share is
asserted so that the check cannot pass by the engine never running."""
from __future__ import annotations

import pytest

from dissector.protocol.crc import crc16
from test_fastsummary import atv71, auto, fast_lines, python_lines


def rtu(text: str) -> bytes:
    body = bytes.fromhex(text)
    return body + crc16(body).to_bytes(2, "little")


ECHOED = (rtu("0105004AFF00") + rtu("0105004AFF00") + rtu("010600370063") + rtu("010600370063")) * 10
NOT_ECHOED = [
    rtu("0105004AFF00") + rtu("010500470000"),  # the issue's: address and value
    rtu("0105004AFF00") + rtu("0105004A0000"),  # value only
    rtu("010600370063") + rtu("010600370062"),  # the issue's: value only
    rtu("010600380063") + rtu("010600370063"),  # address only
]


@pytest.mark.parametrize("pair", NOT_ECHOED)
@pytest.mark.parametrize("annotator", [auto, atv71, lambda: None])
def test_a_write_answer_that_is_not_the_echo_is_warned_by_both_paths(pair: bytes, annotator) -> None:  # noqa: ANN001
    data = ECHOED + pair + ECHOED
    got = fast_lines(data, annotator())
    expected = python_lines(data, annotator())
    assert got.lines == expected
    assert "[warning: the response's " in expected[41] and "from the request's]" in expected[41]
    assert got.engine_lines >= 30  # most echoed writes around it were the engine's
