"""Exception 02 on the ATV71 (VW3 A3 303) is the card's "address does not exist"; to a function that reads
registers (FC3, FC4, FC23) it also says every parameter read is non-existent or protected (p.38), to a write
(FC5, FC6, FC15, FC16, FC22) it does not: data/profiles/atv71.toml [exceptions] and all_protected_exception,
data/modbus.toml [texts] all_protected_read. The meaning of the code (exception_meaning, -V's "Meaning on this
device", the report's event) says the clause to a read too. vw3-decode's summary, -V and --json, under the compiled engine
and VW3_PURE_PYTHON=1; the plugin: tests/integration/test_lua_atv71_write_exceptions.py."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

from dissector.render.pcapwriter import PcapWriter

# Slave 12: a write of CHCF (8401), of 3201..3202, a read/write (read 3202..3203, write CHCF), a read of
# 8400..8402 (p.38), a coil write, a coils write, a mask write; each answered with exception 02.
FRAMES = ["0C 06 20D1 0003", "0C 86 02", "0C 10 0C81 0002 04 0001 0002", "0C 90 02",
          "0C 17 0C82 0002 20D1 0001 02 0003", "0C 97 02", "0C 03 20D0 0003", "0C 83 02",
          "0C 05 0001 FF00", "0C 85 02", "0C 0F 0001 0008 01 FF", "0C 8F 02", "0C 16 20D1 00FF 0000", "0C 96 02"]
MEANING = "address does not exist"
READ_MEANING = f"{MEANING} (also: every parameter read is non-existent or protected)"  # (p.38: to a read)
# (the FC16 of 3201..3202, read-only: its refusal's meaning, data/modbus.toml read_only_meaning)
REFUSED = "write refused: read-only parameter (access R)"
MEANINGS = [MEANING, REFUSED, READ_MEANING, READ_MEANING, MEANING, MEANING, MEANING]  # FC23 and FC3 read
WRITE = f"exception 02 from the VW3 A3 303: {MEANING}"
NOTES = [
    WRITE,
    # (3201..3202 are read-only, ETA and RFR: the card refuses their write, named: devices/access.py)
    "exception 02 from the VW3 A3 303: ETA (3201), RFR (3202) read-only (access R), not written",
    f"{WRITE} (also: every parameter read is non-existent or protected)",
    "exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: "
    "8400 non-existent, CHCF (8401) protected, COP (8402) protected",
    WRITE,
    WRITE,
    WRITE,
]
FUNCTIONS = ["Write Single Register", "Write Multiple Registers", "Read/Write Multiple Registers",
             "Read Holding Registers", "Write Single Coil", "Write Multiple Coils", "Mask Write Register"]


@pytest.fixture
def capture(tmp_path: Path) -> Path:
    path = tmp_path / "writes.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, frame in enumerate(FRAMES):
            writer.write(rtu(frame), 1700000000 + index * 0.01)
    return path


@pytest.mark.parametrize("pure", [False, True])
def test_summary_says_the_meaning_per_access(capture: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--profile", "atv71", str(capture)])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    assert lines[1::2] == [
        f"{2 * index + 2:6d}     0.{2 * index + 1:02d}0000  12 exception {function}: exception 2 (Illegal Data Address) "
        f"[#{2 * index + 1}, 10.0 ms] [{note}]  CRC ok"
        for index, (function, note) in enumerate(zip(FUNCTIONS, NOTES))
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_verbose_and_json(capture: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    frames = [json.loads(line) for line in run_cli(["--profile", "atv71", "--json", str(capture)])[1].splitlines()]
    assert [frame["notes"] for frame in frames[1::2]] == [[note] for note in NOTES]
    # The card's meaning of the code, to a read with p.38's clause (before: the clause nowhere but a note).
    assert [frame["exception_meaning"] for frame in frames[1::2]] == MEANINGS
    verbose = run_cli(["--profile", "atv71", "-V", str(capture)])[1]
    assert [line.strip() for line in verbose.splitlines() if line.strip().startswith("Note:")] == [
        f"Note: {note}" for note in NOTES]
    assert [line.strip() for line in verbose.splitlines() if "Exception meaning on this device" in line] == [
        f"Exception meaning on this device: {meaning}" for meaning in MEANINGS]
