"""A request asking for no register or bit says what it asked, start and count, in every code: FC23 with a
write quantity 0 reads `write 5 (0)` as FC16's `5 (0)` does, not `write` followed by nothing; its read part
`read 0 (0)` as FC3's. Exact bytes, exact lines, under the compiled engine and the Python stages
(VW3_PURE_PYTHON=1), which must agree byte for byte (engine_output_as_python)."""
from __future__ import annotations

import pytest

from helpers import engine_output_as_python, rtu

UNKNOWN = "[the capture ends before any response: not known whether it was answered]"


@pytest.mark.parametrize("frame, info, warnings", [
    # FC23 writing none: the write window as sent, as FC16's below
    ("01 17 0000 0001 0005 0000 00", "Read/Write Multiple Registers read 0, write 5 (0)",
     "[warning: write quantity 0 outside the spec's 1..121]"),
    ("01 17 0000 0000 0005 0000 00", "Read/Write Multiple Registers read 0 (0), write 5 (0)",
     "[warning: read quantity 0 outside the spec's 1..125] [warning: write quantity 0 outside the spec's 1..121]"),
    ("01 17 0003 0002 0010 0000 00", "Read/Write Multiple Registers read 3..4 (2), write 16 (0)",
     "[warning: write quantity 0 outside the spec's 1..121]"),
    # FC23 sending no value for its 2: its write window as sent, as FC16's below
    ("01 17 0000 0001 0005 0002 00", "Read/Write Multiple Registers read 0, write 5..6 (2)",
     "[warning: byte count 0 disagrees with the write quantity 2]"),
    ("01 10 0005 0002 00", "Write Multiple Registers 5..6 (2)",
     "[warning: byte count 0 disagrees with the quantity 2]"),
    # FC23 reading none, writing one: unchanged
    ("01 17 0000 0000 0005 0001 02 0001", "Read/Write Multiple Registers read 0 (0), write 5=1",
     "[warning: read quantity 0 outside the spec's 1..125]"),
    # the other codes a quantity or a list may leave empty: unchanged
    ("01 10 0005 0000 00", "Write Multiple Registers 5 (0)", "[warning: quantity 0 outside the spec's 1..123]"),
    ("01 0F 0005 0000 00", "Write Multiple Coils 5 (0)", "[warning: quantity 0 outside the spec's 1..1968]"),
    ("01 03 0005 0000", "Read Holding Registers 5 (0)", "[warning: quantity 0 outside the spec's 1..125]"),
    ("01 01 0005 0000", "Read Coils 5 (0)", "[warning: quantity 0 outside the spec's 1..2000]"),
    ("01 14 00", "Read File Record 0 record group(s)", "[warning: byte count 0 outside the spec's 7..245]"),
    ("01 15 00", "Write File Record 0 record group(s)", "[warning: byte count 0 outside the spec's 9..251]"),
])
def test_request_of_none_says_its_window(frame: str, info: str, warnings: str, monkeypatch: pytest.MonkeyPatch) -> None:
    out, _ = engine_output_as_python(["-", "-n"], monkeypatch, stdin=rtu(frame))
    assert out == f"     1            -   1 request   {info} {UNKNOWN} {warnings}  CRC ok\n"
