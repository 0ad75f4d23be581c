"""`vw3-decode -w` keeps a capture's empty records (caplen 0, length 0) where they stood, as `tshark -r in -w out`
does: one first, one between a request and its answer, two in a row, one between the halves of a frame split
across records, one last, past the first reads (a pcap's records after them are read in bulk by the engine).
Before, the copy lost them: tshark's frame numbers of the copy slid against the input's (the plugin's
vw3.request_frame of the answer after an empty record said 2 in the copy, 3 in the input). Engine and
VW3_PURE_PYTHON=1, pcap and pcapng copies, a pcapng input too; the copy still decodes as the input."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from helpers import rtu, run_cli, use_engine
from lua_harness import ensure_tool, run_tshark
from part_records import raw_pcap

pytestmark = pytest.mark.integration
REQUEST, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")


def _records() -> list[tuple[int, int, bytes]]:
    """(us, length, bytes): 40 polls, then the empty records."""
    records: list[tuple[int, int, bytes]] = [(0, 0, b"")]
    for poll in range(40):
        records += [(1000 + poll * 100_000, 8, REQUEST), (11_000 + poll * 100_000, 9, ANSWER)]
    at = 4_001_000
    records += [(at, 8, REQUEST), (at + 5000, 0, b""), (at + 10_000, 9, ANSWER),
                (at + 60_000, 0, b""), (at + 70_000, 0, b""),
                (at + 100_000, 4, REQUEST[:4]), (at + 100_300, 0, b""), (at + 100_400, 4, REQUEST[4:]),
                (at + 110_000, 9, ANSWER), (at + 400_000, 0, b"")]
    return records


def _tshark(path: Path, *fields: str) -> list[str]:
    done = subprocess.run([ensure_tool("tshark", "tshark"), "-n", "-r", str(path), "-T", "fields",
                           *(option for field in fields for option in ("-e", field))],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


FIELDS = ("frame.number", "frame.len", "frame.cap_len", "frame.time_epoch", "data.data")


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("form", ["pcap", "pcapng"])
def test_a_copy_keeps_every_record(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, form: str) -> None:
    use_engine(monkeypatch, pure)
    source = raw_pcap(tmp_path / "in.pcap", _records())
    theirs = tmp_path / f"tshark.{form}"
    done = subprocess.run([ensure_tool("tshark", "tshark"), "-r", str(source), "-F", form, "-w", str(theirs)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    ours = tmp_path / f"copy.{form}"
    assert run_cli(["-n", "-F", form, "-w", str(ours), "-q", str(source)])[0] == 0
    expected = _tshark(theirs, *FIELDS)
    assert len(expected) == 91 and expected[0].split("\t")[:3] == ["1", "0", "0"]
    assert _tshark(ours, *FIELDS) == expected
    assert run_cli(["-n", str(ours)])[1] == run_cli(["-n", str(source)])[1]
    again = tmp_path / f"again.{form}"  # (a pcapng input's empty records: its own reader)
    assert run_cli(["-n", "-F", form, "-w", str(again), "-q", str(theirs)])[0] == 0
    assert _tshark(again, *FIELDS) == expected


def test_the_plugin_numbers_the_copy_as_the_input(tmp_path: Path) -> None:
    source = raw_pcap(tmp_path / "in.pcap", _records())
    ours = tmp_path / "copy.pcap"
    assert run_cli(["-n", "-w", str(ours), "-q", str(source)])[0] == 0
    fields = ("-T", "fields", "-e", "frame.number", "-e", "vw3.request_frame", "-e", "vw3.response_frame")
    wanted = run_tshark(source, *fields)
    assert wanted.returncode == 0, wanted.stderr[-2000:]
    assert wanted.stdout.splitlines()[81:84] == ["82\t\t84", "83\t\t", "84\t82\t"]
    assert run_tshark(ours, *fields).stdout == wanted.stdout
