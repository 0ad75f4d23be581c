"""An FC8 answer whose sub-function repeats the request's data (00 Return Query Data, 01 Restart, 03, 0A, 14:
data/modbus.toml [diagnostic_answers]) but carries other data answered other data: a warning, as FC5/FC6's echo
draws one (before: nothing). A counter's answer (0B) carries its own word: no warning. vw3-decode's summary and
--json under the compiled engine and VW3_PURE_PYTHON=1; the plugin: tests/integration/test_lua_diagnostic_echo.py."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

from dissector.render.pcapwriter import PcapWriter

FRAMES = ["01 08 0000 1234", "01 08 0000 5678", "01 08 0000 A5A5", "01 08 0000 A5A5",
          "01 08 0000 0102 0304", "01 08 0000 0102 0305",  # (Return Query Data: any amount of data)
          "01 08 0001 0000", "01 08 0001 FF00", "01 08 000B 0000", "01 08 000B 0007",
          "01 08 000A 0000", "01 08 000A 0000"]
ECHO = "the response's data differs from the request's"
SUMMARY = [
    "     1     0.000000   1 request   Diagnostics 00h Return Query Data = 4660  CRC ok",
    f"     2     0.010000   1 response  Diagnostics 00h Return Query Data = 22136 [#1, 10.0 ms] [warning: {ECHO}]  CRC ok",
    "     3     0.020000   1 request   Diagnostics 00h Return Query Data = 42405  CRC ok",
    "     4     0.030000   1 response  Diagnostics 00h Return Query Data = 42405 [#3, 10.0 ms]  CRC ok",
    "     5     0.040000   1 request   Diagnostics 00h Return Query Data data 01020304  CRC ok",
    f"     6     0.050000   1 response  Diagnostics 00h Return Query Data data 01020305 [#5, 10.0 ms] [warning: {ECHO}]  CRC ok",
    "     7     0.060000   1 request   Diagnostics 01h Restart Communications Option = 0  CRC ok",
    "     8     0.070000   1 response  Diagnostics 01h Restart Communications Option = 65280 [#7, 10.0 ms] "
    f"[warning: {ECHO}]  CRC ok",
    "     9     0.080000   1 request   Diagnostics 0Bh Return Bus Message Count = 0  CRC ok",
    "    10     0.090000   1 response  Diagnostics 0Bh Return Bus Message Count = 7 [#9, 10.0 ms]  CRC ok",
    "    11     0.100000   1 request   Diagnostics 0Ah Clear Counters and Diagnostic Register = 0  CRC ok",
    "    12     0.110000   1 response  Diagnostics 0Ah Clear Counters and Diagnostic Register = 0 [#11, 10.0 ms]  CRC ok",
]


@pytest.fixture
def capture(tmp_path: Path) -> Path:
    path = tmp_path / "diagnostics.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, frame in enumerate(FRAMES):
            writer.write(rtu(frame), 1700000000 + index * 0.01)
    return path


@pytest.mark.parametrize("pure", [False, True])
def test_an_answer_with_other_data_is_warned(capture: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    assert run_cli([str(capture)]) == (0, "\n".join(SUMMARY) + "\n", "")
    frames = [json.loads(line) for line in run_cli(["--json", str(capture)])[1].splitlines()]
    assert [frame.get("warnings", []) for frame in frames] == [
        [], [ECHO], [], [], [], [ECHO], [], [ECHO], [], [], [], []]
