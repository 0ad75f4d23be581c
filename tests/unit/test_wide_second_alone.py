"""A 32-bit map row's second register without its first in the frame is named and said to be one, as a first
word alone is: `PWR=second word of the int32, the first is not in this frame` (before: `40004=65336`, a
plain register); 16#8000 there is ambiguous, as on a first word alone (it may be the value's real low
word). vw3-decode's summary, -V and --json under the compiled engine and VW3_PURE_PYTHON=1; the plugin:
tests/integration/test_lua_wide_second_alone.py."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

from dissector.render.pcapwriter import PcapWriter

# The SEL-749M (4X labels) with a user map: PWR int32 at 2..3, FREQ float32 (CDAB) at 4..5, STAT at 8.
MAP = """address;code;name;unit;scale;type;order
0;IA;Phase A current;A;0,1;;
2;PWR;Real power;kW;0,001;int32;ABCD
4;FREQ;Frequency;Hz;;float32;CDAB
8;STAT;State;;;;
"""
# Reads of 3..4 (PWR's second word, FREQ's first), of 3 alone, of 5..6 (FREQ's second, an unmapped 6);
# then the ATV71 (16#8000: protected) with the same rows, reading 16#8000 in PWR's second word.
SEL = ["03 03 0003 0002", "03 03 04 FF38 147B", "03 03 0003 0001", "03 03 02 FF38",
       "03 03 0005 0002", "03 03 04 4248 0007"]
ATV = ["0C 03 0003 0003", "0C 03 06 8000 147B 4248"]
SECOND_PWR = "second word of the int32, the first is not in this frame"
FIRST_FREQ = "first word of the float32, the second is not in this frame"
SECOND_FREQ = "second word of the float32, the first is not in this frame"


def _capture(path: Path, frames: list[str]) -> Path:
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, frame in enumerate(frames):
            writer.write(rtu(frame), 1700000000 + index * 0.01)
    return path


@pytest.fixture
def files(tmp_path: Path) -> tuple[Path, Path, Path]:
    table = tmp_path / "map.csv"
    table.write_text(MAP, encoding="utf-8")
    return table, _capture(tmp_path / "sel.pcap", SEL), _capture(tmp_path / "atv.pcap", ATV)


@pytest.mark.parametrize("pure", [False, True])
def test_summary(files: tuple[Path, Path, Path], pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    table, sel, atv = files
    status, out, err = run_cli(["--profile", "sel749m", "--map", f"sel749m={table}", str(sel)])
    assert (status, err) == (0, "")
    assert out.splitlines()[1::2] == [
        f"     2     0.010000   3 response  Read Holding Registers 40004..40005 (2): PWR={SECOND_PWR} "
        f"FREQ={FIRST_FREQ} [#1, 10.0 ms]  CRC ok",
        f"     4     0.030000   3 response  Read Holding Registers 40004: PWR={SECOND_PWR} [#3, 10.0 ms]  CRC ok",
        f"     6     0.050000   3 response  Read Holding Registers 40006..40007 (2): FREQ={SECOND_FREQ} 40007=7 "
        "[#5, 10.0 ms]  CRC ok",
    ]
    status, out, err = run_cli(["--profile", "atv71", "--map", f"atv71={table}", str(atv)])
    assert (status, err) == (0, "")
    assert out.splitlines()[1] == (
        f"     2     0.010000  12 response  Read Holding Registers 3..5 (3): PWR={SECOND_PWR} (16#8000: ambiguous) "
        "FREQ=50.02 Hz [#1, 10.0 ms]  CRC ok")


@pytest.mark.parametrize("pure", [False, True])
def test_json_and_verbose(files: tuple[Path, Path, Path], pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    table, sel, atv = files
    out = run_cli(["--profile", "sel749m", "--map", f"sel749m={table}", "--json", str(sel)])[1]
    assert json.loads(out.splitlines()[1])["registers"] == [
        {"address": 3, "value": 65336, "code": "PWR", "name": "Real power", "unit": "kW", "text": SECOND_PWR,
         "label": "40004"},
        {"address": 4, "value": 5243, "code": "FREQ", "name": "Frequency", "unit": "Hz", "text": FIRST_FREQ,
         "label": "40005"},
    ]
    detail = run_cli(["--profile", "sel749m", "--map", f"sel749m={table}", "-V", str(sel)])[1]
    assert (
        "        Register 40004: 65336 (0xFF38)  PWR [Real power]\n"
        f"            Value: {SECOND_PWR}\n"
        "            Unit: kW\n"
        "        Register 40005") in detail
    out = run_cli(["--profile", "atv71", "--map", f"atv71={table}", "--json", str(atv)])[1]
    assert json.loads(out.splitlines()[1])["registers"][0] == {
        "address": 3, "value": 32768, "code": "PWR", "name": "Real power", "unit": "kW", "text": SECOND_PWR,
        "status": "ambiguous"}
