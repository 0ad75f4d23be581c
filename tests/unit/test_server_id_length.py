"""FC17's server id is device specific in length (Application Protocol 6.17), its run indicator the byte after
it: pymodbus answers with a name as the id and the run indicator last, which the one-byte reading took for
`run 101`: the id is read up to the first 00 or FF after its first byte, warned
(tests/integration/test_report_server_id_longer.py). Only an answer with no 00 or FF
after its first byte has no run indicator where any id length puts it. Same lines under the engine and VW3_PURE_PYTHON=1; the plugin's in
tests/integration/test_lua_server_id_length.py."""
from __future__ import annotations

import pytest

from helpers import run_cli, use_engine

REQUEST = "0C 11 C4 BC"
PYMODBUS = "0C 11 1F " + b"Telemecanique-ATV71HU15M3-0201".hex(" ") + " FF B9 C7"  # the run indicator last
LONGER_ID = "0C 11 04 01 02 FF 41 04 7D"  # a two-byte id 01 02, ON, 'A'
NONE = "0C 11 04 01 02 03 41 45 7D"  # no 00 or FF after the first byte


@pytest.mark.parametrize("pure", [False, True])
def test_only_an_answer_without_any_run_indicator_is_warned(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    args = [arg for frame in (REQUEST, PYMODBUS, REQUEST, LONGER_ID, REQUEST, NONE) for arg in ("--hex", frame)]
    status, out, err = run_cli(args)
    assert (status, err) == (0, "")
    assert out.splitlines()[1::2] == [
        "     2            -  12 response  Report Server ID server id 'Telemecanique-ATV71HU15M3-0201', run ON, "
        "0 bytes [#1] [warning: server id of 30 bytes, up to the first 00 (OFF) or FF (ON) after its first byte: "
        "after a one-byte id, 0x65 is no run indicator]  CRC ok",
        "     4            -  12 response  Report Server ID server id 01 02, run ON, 'A' [#3] "
        "[warning: server id of 2 bytes, up to the first 00 (OFF) or FF (ON) after its first byte: after a "
        "one-byte id, 0x02 is no run indicator]  CRC ok",
        "     6            -  12 response  Report Server ID server id 1, run 2, 2 bytes [#5] "
        "[warning: run indicator 0x02 is neither 0x00 (OFF) nor 0xFF (ON)]  CRC ok",
    ]
