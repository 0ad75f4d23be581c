"""A response from slave 0 names the broadcast it follows only when that broadcast is the last request: after
transactions the compiled engine shows itself (which the Python pairer does not see), the broadcast it kept
from before is not the last request. Before, the engine's run said 'response from slave 0 after broadcast #7'
where VW3_PURE_PYTHON=1 (and the plugin) said 'the broadcast address' (differential fuzz, seed found by a
helper)."""
from __future__ import annotations

import pytest

from helpers import run_cli, use_engine

ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
BROADCAST_AND_ECHO = "00 03 00 00 00 01 85 DB 00 03 02 00 00 85 84"  # a broadcast read, a "response" from slave 0
SLAVE_1 = "01 03 00 00 00 01 84 0A 01 03 02 00 00 B8 44"  # an ordinary read and its answer
LATE = "01 00 83 01 D1 30"  # a glitch byte, then an exception from slave 0


@ENGINES
def test_a_broadcast_before_other_transactions_is_not_the_last_request(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    data = " ".join([BROADCAST_AND_ECHO] * 4 + [SLAVE_1, LATE])
    status, out, err = run_cli(["--hex", data])
    lines = out.splitlines()
    assert lines[7].endswith("[warning: response from slave 0 after broadcast #7: no server answers a broadcast]  CRC ok")
    assert lines[11] == (
        "    12            -   0 exception Read Holding Registers: exception 1 (Illegal Function) [no request] "
        "[response without a matching request in the capture] [warning: response from slave 0, the broadcast "
        "address: a server answers with its own address]  CRC ok")
