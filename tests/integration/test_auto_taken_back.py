"""Profile `auto` read once (standard input, live, the plugin's single pass): once a traffic choice is taken
back (an answer to a function the chosen device does not support), the slave has no device again, and while
its traffic may still choose one (fewer than 8 answers or 32 frames) its frames are provisional, as before
the first choice; the device taken back is ruled out, the other candidates judged on. Before, the frames
after the take-back were shown final `generic` (p.38's read, then FC22, which the VW3 A3 303 does not
support (reference: FC 3/4/6/8/11/16/23/43), answered: frames 6 to 8 final). Exact summary lines, engine and
VW3_PURE_PYTHON=1; the plugin's Info one pass and -2, and every field as vw3-decode reading once says it."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import assert_as_vw3_decode_in_one_and_two_passes, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration
LATER = frozenset(["response_frame", "unanswered"])

READ = "0C 03 20D0 0003"
MASK = "0C 16 20D1 00F2 0025"  # FC22 Mask Write Register, answered by its echo
RECORDS = [(READ, 0.0), ("0C 03 06 8000 0003 0002", 0.02), (READ, 1.0), ("0C 03 06 8000 8000 0002", 1.02),
           (MASK, 2.0), (MASK, 2.02), (READ, 3.0), ("0C 03 06 8000 0003 0002", 3.02)]

P = " [provisional]"
R1 = "Read Holding Registers 8400..8402 (3)"
ONCE = [
    f"     1     0.000000  12 request   {R1}{P}  CRC ok",
    f"     2     0.020000  12 response  {R1}: 8400=32768 8401=3 8402=2 [#1, 20.0 ms]{P}  CRC ok",
    f"     3     1.000000  12 request   {R1}{P}  CRC ok",
    f"     4     1.020000  12 response  {R1}: 8400=non-existent CHCF=protected COP=Cd (command) [#3, 20.0 ms]"
    " [CHCF (8401) became protected: read 3 in frame #2, 16#8000 now]  CRC ok",
    "     5     2.000000  12 request   Mask Write Register 8401 AND 0x00F2 OR 0x0025"
    " [warning: Mask Write Register (22) is not supported by the VW3 A3 303]  CRC ok",
    f"     6     2.020000  12 response  Mask Write Register 8401 AND 0x00F2 OR 0x0025 [#5, 20.0 ms]{P}  CRC ok",
    f"     7     3.000000  12 request   {R1}{P}  CRC ok",
    f"     8     3.020000  12 response  {R1}: 8400=32768 8401=3 8402=2 [#7, 20.0 ms]{P}  CRC ok",
]
# (a file, read twice: the choice over the whole input is the one taken back, generic from frame 1 on)
FILE = [line.replace(P, "") for line in ONCE]
FILE[3] = f"     4     1.020000  12 response  {R1}: 8400=32768 8401=32768 8402=2 [#3, 20.0 ms]  CRC ok"
FILE[4] = "     5     2.000000  12 request   Mask Write Register 8401 AND 0x00F2 OR 0x0025  CRC ok"


def _pcap(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "taken_back.pcap", [(rtu(hexa), 1700000000 + time) for hexa, time in RECORDS])


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_frames_after_a_take_back_are_provisional_read_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                            pure: bool) -> None:
    use_engine(monkeypatch, pure)
    pcap = _pcap(tmp_path)
    status, out, err = run_cli(["-"], stdin=pcap.read_bytes())
    assert (status, out.splitlines(), err) == (0, ONCE, "")
    status, out, err = run_cli([str(pcap)])
    assert (status, out.splitlines(), err) == (0, FILE, "")


def test_plugin_frames_after_a_take_back_are_provisional(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path)
    infos = {}
    for two_pass in (False, True):
        got = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", "-e", "vw3.provisional", two_pass=two_pass)
        assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
        infos[two_pass] = [line.split("\t")[1] for line in got.stdout.splitlines()]
    assert infos[False] == ["1", "1", "1", "", "", "1", "1", "1"]
    assert infos[True] == [""] * 8
    assert_as_vw3_decode_in_one_and_two_passes(pcap, LATER)
