"""An exception whose device lists causes for its code to the function (SEL-749M Appendix D, Table D.5; the
ATV71's 03 past its limits): -V's `Meaning on this device`, --json and -T fields exception_meaning, and the
plugin's vw3.exception_meaning and tree item said the code's name (`Illegal Data Address`), while the note
and --report's event said the cause the request picks (`illegal register to read (increments the Invalid
Address counter)`). Now every view says the causes (devices/explain.py exception_meaning, causes_meaning;
lua/src/explain.lua). Without a request (one not in the capture) every cause the device lists, as the note.
vw3-decode by the compiled engine and VW3_PURE_PYTHON=1, the plugin in one pass and two."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

# Slave 3 (SEL-749M): FC3 of 40101..40102 refused 02; FC3 of 130 words refused 03; FC3 of 2 words refused 03;
# FC16 whose byte count disagrees with its quantity refused 03; an FC16 exception 03 nobody asked for.
SEL = ["03 03 00 64 00 02", "03 83 02", "03 03 00 00 00 82", "03 83 03", "03 03 00 00 00 02", "03 83 03",
       "03 10 00 00 00 02 02 00 01", "03 90 03", "03 90 03"]
SEL_MEANINGS = [
    "illegal register to read (increments the Invalid Address counter)",
    "illegal number of registers to read (increments the Illegal Register counter)",
    "format error (increments the Bad Packet Format counter)",
    "wrong byte count (increments the Bad Packet Format and Illegal Write counters)",
    "illegal number of registers (increments the Illegal Register and Illegal Write counters) or wrong byte "
    "count (increments the Bad Packet Format and Illegal Write counters) or invalid data value (increments the "
    "Illegal Write counter)",
]
SEL_EXCEPTIONS = [2, 4, 6, 8, 9]
# Slave 12 (ATV71): FC3 of 64 words (its limit: 63) refused 03; FC3 of 2 words refused 03 (the card's meaning).
ATV71 = ["0C 03 20 D1 00 40", "0C 83 03", "0C 03 20 D1 00 02", "0C 83 03"]
ATV71_MEANINGS = ["quantity beyond the card's limit", "value not permitted"]


def capture(path: Path, frames: list[str]) -> Path:
    return write_pcap(path, [(rtu(frame), 1700000000 + index * 0.01) for index, frame in enumerate(frames)])


def meaning_lines(verbose: str) -> list[str]:
    return [line.strip() for line in verbose.splitlines() if "Exception meaning on this device" in line]


@pytest.mark.parametrize("pure", [False, True])
def test_sel749m_meaning_is_the_cause(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = str(capture(tmp_path / "sel.pcap", SEL))
    verbose = run_cli(["--profile", "sel749m", "-V", path])[1]
    assert verbose.split("\n\n")[1].splitlines()[3:8] == [
        "        Slave: 3",
        "        Function: 3 (0x03) Read Holding Registers, exception (0x83)",
        "        Exception code: Illegal Data Address (2)",
        f"        Exception meaning on this device: {SEL_MEANINGS[0]}",
        "        CRC: 0x3161 [CRC ok]",
    ]
    assert meaning_lines(verbose) == [f"Exception meaning on this device: {meaning}" for meaning in SEL_MEANINGS]
    frames = [json.loads(line) for line in run_cli(["--profile", "sel749m", "--json", path])[1].splitlines()]
    assert [(frame["frame"], frame["exception_meaning"]) for frame in frames if frame["kind"] == "exception"] == (
        list(zip(SEL_EXCEPTIONS, SEL_MEANINGS)))
    # Each note says the same cause (the one nobody asked for: after the pairing note)
    notes = [frame["notes"][-1] for frame in frames if frame["kind"] == "exception"]
    assert [note.split(": ", 1)[1] for note in notes] == SEL_MEANINGS
    status, out, err = run_cli(["--profile", "sel749m", path, "-Y", 'kind == "exception"', "-T", "fields", "-e",
                                "frame", "-e", "exception_meaning", "-E", "separator=|"])
    assert (status, out.splitlines(), err) == (
        0, [f"{frame}|{meaning}" for frame, meaning in zip(SEL_EXCEPTIONS, SEL_MEANINGS)], "")
    page = tmp_path / "sel.html"
    assert run_cli(["--profile", "sel749m", "--report", str(page), path])[0] == 0
    data = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(encoding="utf-8")).group(1))
    assert [event[3] for event in data["events"] if event[1] == "exception"] == [
        f"exception {code} to function {function}: {meaning}"
        for (code, function), meaning in zip([("02", 3), ("03", 3), ("03", 3), ("03", 16), ("03", 16)],
                                             SEL_MEANINGS)]


@pytest.mark.parametrize("pure", [False, True])
def test_atv71_and_generic_meanings(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = str(capture(tmp_path / "atv71.pcap", ATV71))
    assert meaning_lines(run_cli(["--profile", "atv71", "-V", path])[1]) == [
        f"Exception meaning on this device: {meaning}" for meaning in ATV71_MEANINGS]
    frames = [json.loads(line) for line in run_cli(["--profile", "atv71", "--json", path])[1].splitlines()]
    assert [frame.get("exception_meaning") for frame in frames[1::2]] == ATV71_MEANINGS
    # The generic device has no meaning of its own: the spec's name alone
    verbose = run_cli(["--profile", "generic", "-V", path])[1]
    assert meaning_lines(verbose) == []
    assert verbose.count("        Exception code: Illegal Data Value (3)\n") == 2
    frames = [json.loads(line) for line in run_cli(["--profile", "generic", "--json", path])[1].splitlines()]
    assert [frame.get("exception_meaning") for frame in frames[1::2]] == [None, None]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_says_the_cause(tmp_path: Path, two_pass: bool) -> None:
    runs = [(capture(tmp_path / "sel.pcap", SEL), "sel749m", SEL_EXCEPTIONS, SEL_MEANINGS),
            (capture(tmp_path / "atv71.pcap", ATV71), "atv71", [2, 4], ATV71_MEANINGS)]
    for pcap, profile, numbers, meanings in runs:
        got = run_tshark(pcap, "-o", f"vw3.profiles:{profile}", "-T", "fields", "-E", "separator=|", "-e",
                         "frame.number", "-e", "vw3.exception_meaning", "-Y", "vw3.kind == 3", two_pass=two_pass)
        assert not lua_errors(got.stdout + got.stderr)
        assert got.stdout.splitlines() == [f"{number}|{meaning}" for number, meaning in zip(numbers, meanings)]
        # The tree item (Wireshark cuts a label past 240 characters, marking it [truncated]: then its start)
        tree = run_tshark(pcap, "-o", f"vw3.profiles:{profile}", "-V", "-Y", "vw3.kind == 3", two_pass=two_pass)
        items = [line.strip() for line in tree.stdout.splitlines() if "[Exception meaning on this device" in line]
        assert len(items) == len(meanings)
        for item, meaning in zip(items, meanings):
            whole = f"[Exception meaning on this device: {meaning}]"
            assert item == whole or (item.startswith("[Exception meaning on this device [truncated]: ")
                                     and whole[:-1].startswith(item[:-1].replace(" [truncated]", "", 1)))



def test_the_display_filter_knows_the_causes(tmp_path: Path) -> None:
    # (an enumerated value no profile of the run can give is an error: filter_context.py; the meanings a
    # request may pick, explain.known_meanings)
    path = str(capture(tmp_path / "sel.pcap", SEL))
    for frame, meaning in zip(SEL_EXCEPTIONS, SEL_MEANINGS):
        status, out, err = run_cli(["--profile", "sel749m", path, "-Y", f'exception_meaning == "{meaning}"', "-T",
                                    "fields", "-e", "frame"])
        assert (status, out, err) == (0, f"{frame}\n", "")
