"""Exception 02 to a write on the ATV71 (VW3 A3 303) is the card's "address does not exist": p.38's clause
(every parameter read non-existent or protected) is about reads, and FC23, which reads too, keeps it
(data/profiles/atv71.toml [[exception_causes]]). vw3-decode's summary, -V and --json, under the compiled
engine and VW3_PURE_PYTHON=1; the plugin: tests/integration/test_lua_atv71_write_exceptions.py."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

from dissector.render.pcapwriter import PcapWriter

# Slave 12: a write of CHCF (8401), of 3201..3202, a read/write (read 3202..3203, write CHCF), each
# answered with exception 02; then a read of 8400..8402 answered with exception 02 (p.38).
FRAMES = ["0C 06 20D1 0003", "0C 86 02", "0C 10 0C81 0002 04 0001 0002", "0C 90 02",
          "0C 17 0C82 0002 20D1 0001 02 0003", "0C 97 02", "0C 03 20D0 0003", "0C 83 02"]
READS_TOO = "address does not exist (also: every parameter read is non-existent or protected)"
NOTES = [
    "exception 02 from the VW3 A3 303 to Write Single Register: address does not exist",
    "exception 02 from the VW3 A3 303 to Write Multiple Registers: address does not exist",
    f"exception 02 from the VW3 A3 303: {READS_TOO}",
    "exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: "
    "8400 non-existent, CHCF (8401) protected, COP (8402) protected",
]


@pytest.fixture
def capture(tmp_path: Path) -> Path:
    path = tmp_path / "writes.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, frame in enumerate(FRAMES):
            writer.write(rtu(frame), 1700000000 + index * 0.01)
    return path


@pytest.mark.parametrize("pure", [False, True])
def test_summary_says_the_write_meaning(capture: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--profile", "atv71", str(capture)])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    assert lines[1::2] == [
        "     2     0.010000  12 "
        f"exception Write Single Register: exception 2 (Illegal Data Address) [#1, 10.0 ms] [{NOTES[0]}]  CRC ok",
        "     4     0.030000  12 "
        f"exception Write Multiple Registers: exception 2 (Illegal Data Address) [#3, 10.0 ms] [{NOTES[1]}]  CRC ok",
        "     6     0.050000  12 "
        f"exception Read/Write Multiple Registers: exception 2 (Illegal Data Address) [#5, 10.0 ms] [{NOTES[2]}]"
        "  CRC ok",
        "     8     0.070000  12 "
        f"exception Read Holding Registers: exception 2 (Illegal Data Address) [#7, 10.0 ms] [{NOTES[3]}]  CRC ok",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_verbose_and_json(capture: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    frames = [json.loads(line) for line in run_cli(["--profile", "atv71", "--json", str(capture)])[1].splitlines()]
    assert [frame["notes"] for frame in frames[1::2]] == [[note] for note in NOTES]
    # The card's meaning of the code stays its own key (its exceptions table, whatever the function).
    assert {frame["exception_meaning"] for frame in frames[1::2]} == {READS_TOO}
    verbose = run_cli(["--profile", "atv71", "-V", str(capture)])[1]
    assert [line.strip() for line in verbose.splitlines() if line.strip().startswith("Note:")] == [
        f"Note: {note}" for note in NOTES]
