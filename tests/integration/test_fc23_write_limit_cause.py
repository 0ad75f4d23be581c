"""ATV71 exception 03 to a Read/Write Multiple Registers (FC23) whose write quantity is past the card's limit
(atv71.toml [limits] 23 = [20, 20]; the request draws its warning): the card's cause `quantity beyond the
card's limit` (exception_causes when = "quantity") held only for the read quantity, so the note, -V's
meaning and the plugin said `value not permitted`. Now every quantity the request's lifting rule checks
(modbus.toml: read and write) is held to its limit (devices/explain.py _holds, lua/src/explain.lua holds).
vw3-decode (engine and VW3_PURE_PYTHON=1) and the plugin."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

# Slave 12: FC23 reading 21 words (past 20), writing 21 (past 20), within both; each refused 03.
FRAMES = ["0C 17 20 D1 00 15 20 D1 00 01 02 00 03", "0C 97 03",
          "0C 17 20 D1 00 02 20 D1 00 15 2A" + " 0003" * 21, "0C 97 03",
          "0C 17 20 D1 00 02 20 D1 00 01 02 00 03", "0C 97 03"]
CAUSE, PLAIN = "quantity beyond the card's limit", "value not permitted"
MEANINGS = [CAUSE, CAUSE, PLAIN]
NOTES = [f"exception 03 from the VW3 A3 303 to Read/Write Multiple Registers: {meaning}" for meaning in MEANINGS]


def capture(path: Path) -> Path:
    return write_pcap(path, [(rtu(frame), 1700000000 + index * 0.01) for index, frame in enumerate(FRAMES)])


@pytest.mark.parametrize("pure", [False, True])
def test_write_quantity_past_the_limit_is_the_cause(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                    pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = str(capture(tmp_path / "fc23.pcap"))
    status, out, err = run_cli(["--profile", "atv71", path, "-Y", 'kind == "exception"', "-T", "fields", "-e",
                                "frame", "-e", "exception_meaning", "-e", "notes", "-E", "separator=|"])
    assert (status, err) == (0, "")
    assert out.splitlines() == [f"{2 * index + 2}|{meaning}|{note}"
                                for index, (meaning, note) in enumerate(zip(MEANINGS, NOTES))]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_says_the_same(tmp_path: Path, two_pass: bool) -> None:
    got = run_tshark(capture(tmp_path / "fc23.pcap"), "-o", "vw3.profiles:atv71", "-T", "fields", "-E",
                     "separator=|", "-e", "frame.number", "-e", "vw3.exception_meaning", "-e", "vw3.note",
                     "-Y", "vw3.kind == 3", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == [f"{2 * index + 2}|{meaning}|{note}"
                                       for index, (meaning, note) in enumerate(zip(MEANINGS, NOTES))]
