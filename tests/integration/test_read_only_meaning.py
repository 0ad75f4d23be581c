"""What an exception 02 refusing a write of read-only parameters (map access R) means on the device: -V's
`Meaning on this device`, --json exception_meaning, the report's event and the plugin's tree said the code's
plain meaning (ATV71: `address does not exist`) while the note named the read-only parameter (4ebcd87). Now
the meaning is data/modbus.toml read_only_meaning (devices/access.py READ_ONLY_MEANING), and the note keeps the
relay counters the device's causes say any 02 to the function increments (SEL-749M, Appendix D: 06h and
10h, Invalid Address and Illegal Write), which it dropped. vw3-decode (compiled engine and
VW3_PURE_PYTHON=1) and the plugin (lua/src/explain.lua)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

MEANING = "write refused: read-only parameter (access R)"
# Slave 12 (ATV71): ETA (3201, R) written, refused 02; RFR (3202, R) by FC16, refused 02; CHCF (8401, RW)
# written, refused 02 (the card's own meaning).
ATV71 = ["0C 06 0C 81 00 07", "0C 86 02", "0C 10 0C 82 00 01 02 00 64", "0C 90 02", "0C 06 20 D1 00 03",
         "0C 86 02"]
ATV71_NOTES = ["exception 02 from the VW3 A3 303: ETA (3201) read-only (access R), not written",
               "exception 02 from the VW3 A3 303: RFR (3202) read-only (access R), not written",
               "exception 02 from the VW3 A3 303: address does not exist"]
ATV71_MEANINGS = [MEANING, MEANING, "address does not exist"]
# Slave 3 (SEL-749M) with a user map: SPD (100) R, SET (101) RW; FC6 of SPD, FC16 of both, FC6 of the
# unmapped 102, each refused 02.
MAP = "address,code,name,access\n100,SPD,Speed,R\n101,SET,Setpoint,RW\n"
SEL = ["03 06 00 64 00 01", "03 86 02", "03 10 00 64 00 02 04 00 01 00 02", "03 90 02", "03 06 00 66 00 01",
       "03 86 02"]
COUNTERS = "(increments the Invalid Address and Illegal Write counters)"
# (a PLC-style device: its parameters named by the 4X reference the frame shows, 40101, as its other notes)
SEL_NOTES = [f"exception 02 from the SEL-749M: SPD (40101) read-only (access R), not written {COUNTERS}"] * 2 + [
    f"exception 02 from the SEL-749M to Write Single Register: illegal register address {COUNTERS}"]
SEL_MEANINGS = [MEANING, MEANING, f"illegal register address {COUNTERS}"]  # (the cause, as the note: explain.py)
SEL_WARNINGS = [["SPD (40101) is read-only (access R)"]] * 2 + [[]]


def capture(path: Path, frames: list[str]) -> Path:
    return write_pcap(path, [(rtu(frame), 1700000000 + index * 0.01) for index, frame in enumerate(frames)])


@pytest.mark.parametrize("pure", [False, True])
def test_atv71_meaning_of_a_refused_read_only_write(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = str(capture(tmp_path / "atv71.pcap", ATV71))
    verbose = run_cli(["--profile", "atv71", "-V", path])[1].split("\n\n")
    assert verbose[1].splitlines()[3:] == [
        "        Slave: 12",
        "        Function: 6 (0x06) Write Single Register, exception (0x86)",
        "        Exception code: Illegal Data Address (2)",
        f"        Exception meaning on this device: {MEANING}",
        "        CRC: 0x6252 [CRC ok]",
        "    Request in frame: 1",
        "    Response time: 10.000 ms",
        f"    Note: {ATV71_NOTES[0]}",
    ]
    assert [line.strip() for line in "\n".join(verbose).splitlines() if "meaning on this device" in line] == [
        f"Exception meaning on this device: {meaning}" for meaning in ATV71_MEANINGS]
    frames = [json.loads(line) for line in run_cli(["--profile", "atv71", "--json", path])[1].splitlines()]
    assert [(frame["exception_meaning"], frame["notes"]) for frame in frames[1::2]] == [
        (meaning, [note]) for meaning, note in zip(ATV71_MEANINGS, ATV71_NOTES)]
    # The meaning is one the display filter knows (an unknown enumerated value is an error)
    status, out, err = run_cli(["--profile", "atv71", path, "-Y", f'exception_meaning == "{MEANING}"',
                                "-T", "fields", "-e", "frame"])
    assert (status, out, err) == (0, "2\n4\n", "")
    page = tmp_path / "atv71.html"
    assert run_cli(["--profile", "atv71", "--report", str(page), path])[0] == 0
    data = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(encoding="utf-8")).group(1))
    assert [event[3] for event in data["events"] if event[1] == "exception"] == [
        f"exception 02 to function 6: {MEANING}", f"exception 02 to function 16: {MEANING}",
        "exception 02 to function 6: address does not exist"]


@pytest.mark.parametrize("pure", [False, True])
def test_sel749m_refusal_keeps_its_counters(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    (tmp_path / "sel.csv").write_text(MAP)
    path = str(capture(tmp_path / "sel.pcap", SEL))
    options = ["--profile", "sel749m", "--map", f"sel749m={tmp_path / 'sel.csv'}", path]
    frames = [json.loads(line) for line in run_cli([*options, "--json"])[1].splitlines()]
    assert [(frame["exception_meaning"], frame["notes"]) for frame in frames[1::2]] == [
        (meaning, [note]) for meaning, note in zip(SEL_MEANINGS, SEL_NOTES)]
    assert [frame["warnings"] for frame in frames[0::2]] == SEL_WARNINGS
    lines = run_cli(options)[1].splitlines()
    assert lines[0] == ("     1     0.000000   3 request   Write Single Register 40101 SPD=1 "
                        f"[warning: {SEL_WARNINGS[0][0]}]  CRC ok")
    assert lines[1] == ("     2     0.010000   3 exception Write Single Register: exception 2 (Illegal Data Address) "
                        f"[#1, 10.0 ms] [{SEL_NOTES[0]}]  CRC ok")


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_says_the_same_meaning(tmp_path: Path, two_pass: bool) -> None:
    (tmp_path / "sel.csv").write_text(MAP)
    runs = [(capture(tmp_path / "atv71.pcap", ATV71), ["-o", "vw3.profiles:atv71"], ATV71_NOTES, ATV71_MEANINGS),
            (capture(tmp_path / "sel.pcap", SEL), ["-o", "vw3.profiles:sel749m", "-o",
                                                   f"vw3.maps:sel749m={tmp_path / 'sel.csv'}"], SEL_NOTES,
             SEL_MEANINGS)]
    for pcap, options, notes, meanings in runs:
        if notes is SEL_NOTES:  # (the SEL's requests: its 4X references, as vw3-decode's)
            warned = run_tshark(pcap, *options, "-T", "fields", "-e", "vw3.warning", "-Y", "vw3.kind == 1",
                                two_pass=two_pass)
            assert warned.stdout.splitlines() == [",".join(warnings) for warnings in SEL_WARNINGS]
        got = run_tshark(pcap, *options, "-T", "fields", "-E", "separator=|", "-e", "frame.number", "-e",
                         "vw3.note", "-e", "vw3.exception_meaning", "-e", "_ws.expert.message",
                         "-Y", "vw3.kind == 3", two_pass=two_pass)
        assert not lua_errors(got.stdout + got.stderr)
        assert got.stdout.splitlines() == [
            f"{2 * index + 2}|{note}|{meaning}|Exception 2: {meaning},{note}"
            for index, (note, meaning) in enumerate(zip(notes, meanings))]
