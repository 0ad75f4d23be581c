"""Fields a Wireshark user filters and graphs on, against vw3-decode on the same captures (real tshark):
`vw3.unanswered` only where a request went unanswered, `vw3.reg.scaled` a number, one field per
parameter of the built-in maps (`vw3.atv71.rfr`) that an IO graph can plot."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from lua_harness import ROOT, python_items, run_tshark, write_pcap
from lua_session import SessionBuilder


def _numbers(result) -> list[int]:
    assert result.returncode == 0, result.stderr
    return [int(line) for line in result.stdout.split()]


def _unanswered_records(pcap: Path) -> list[int]:
    return sorted(item.record for item in python_items(pcap) if item.data.get("unanswered"))


def test_unanswered_filter_matches_exactly_the_requests_vw3_decode_marks(tmp_path: Path) -> None:
    noisy = ROOT / "captures" / "noisy_bus.pcap"
    filtered = _numbers(run_tshark(noisy, "-Y", "vw3.unanswered", "-T", "fields", "-e", "frame.number"))
    assert filtered == _unanswered_records(noisy) and len(filtered) == 2  # the issue: 19 matched
    pcap = write_pcap(tmp_path / "session.pcap", SessionBuilder(seed=7).session(400))
    expected = _unanswered_records(pcap)
    assert len(expected) > 10
    assert _numbers(run_tshark(pcap, "-Y", "vw3.unanswered", "-T", "fields", "-e", "frame.number")) == expected
    # The field is absent, not false, on answered requests.
    assert _numbers(run_tshark(pcap, "-Y", "vw3.unanswered == 0", "-T", "fields", "-e", "frame.number")) == []


def test_scaled_values_are_numbers_and_each_parameter_has_its_field() -> None:
    capture = ROOT / "captures" / "atv71_commissioning.pcap"
    python = python_items(capture)
    rfr = [(item.record, reg["scaled"]) for item in python for reg in item.data.get("registers", [])
           if reg.get("code") == "RFR"]
    assert len(rfr) == 40
    result = run_tshark(capture, "-Y", "vw3.atv71.rfr", "-T", "fields", "-e", "frame.number", "-e", "vw3.atv71.rfr")
    assert result.returncode == 0, result.stderr
    rows = [line.split("\t") for line in result.stdout.splitlines()]
    assert [(int(number), float(value)) for number, value in rows] == [(record, float(v)) for record, v in rfr]
    # A numeric comparison (a string field compared text) and an IO graph average over one parameter.
    above = [record for record, value in rfr if value > 5]
    assert 0 < len(above) < len(rfr)
    assert _numbers(run_tshark(capture, "-Y", "vw3.atv71.rfr > 5", "-T", "fields", "-e", "frame.number")) == above
    scaled = run_tshark(capture, "-Y", "vw3.reg.scaled > 49.5 && vw3.reg.code == \"HSP\"", "-T", "fields",
                        "-e", "frame.number")
    assert _numbers(scaled) == sorted({item.record for item in python for reg in item.data.get("registers", [])
                                       if reg.get("code") == "HSP" and reg["scaled"] > 49.5})
    stat = run_tshark(capture, "-q", "-z", "io,stat,0,AVG(vw3.atv71.rfr)vw3.atv71.rfr")
    assert stat.returncode == 0, stat.stderr
    average = sum(value for _, value in rfr) / len(rfr)
    assert f"{average:.3f}"[:-1] in stat.stdout or f"{average:.2f}" in stat.stdout, stat.stdout
    # Status by name on the integer field: the 16#8000 reads and the exceptions 02 that say it (p.38).
    p38 = ROOT / "captures" / "p38_protection.pcap"
    protected = run_tshark(p38, "-Y", 'vw3.reg.status == "protected"', "-T", "fields", "-e", "frame.number")
    expected = sorted({item.record for item in python_items(p38) for reg in item.data.get("registers", [])
                       if reg.get("status") == "protected"})
    assert _numbers(protected) == expected == [6, 8, 10, 12]


def _parameter_rows(lines: str, code: str) -> list[tuple[int, str | None, str, str]]:
    """(frame, value, status, text) of each occurrence of the register `code`, from `-T fields -E
    aggregator=^` rows of frame, code, value, status, text."""
    rows = []
    for line in lines.splitlines():
        frame, codes, values, statuses, texts = (cell.split("^") if cell else [] for cell in line.split("\t"))
        for index, name in enumerate(codes):
            if name == code:
                value = values[index] if values and values[index] != "" else None
                rows.append((int(frame[0]), value, statuses[index], texts[index]))
    return rows


P38_STORY = {
    # read 3 twice, 16#8000 twice, then twice refused with exception 02 (every parameter unreadable)
    "CHCF": [(2, "3", "ok", "IO (I/O profile)"), (4, "3", "ok", "IO (I/O profile)"),
             (6, "32768", "protected", "16#8000: protected"), (8, "32768", "protected", "16#8000: protected"),
             (10, None, "protected", "no value: exception 02"), (12, None, "protected", "no value: exception 02")],
    "COP": [(frame, "2", "ok", "Cd (command)") for frame in (2, 4, 6, 8)]
           + [(frame, None, "protected", "no value: exception 02") for frame in (10, 12)],
}


def test_p38_story_register_by_register_as_vw3_decode() -> None:
    """The p.38 capture's parameters, occurrence by occurrence, in tshark -2 as in vw3-decode -T fields of
    the file: CHCF read 3, 3, protected (16#8000) twice, then twice more from the exceptions 02, COP 2
    four times then protected twice (vw3-decode --stats: CHCF 2 reads / 4 unreadable, COP 4 / 2). Read once
    (tshark's single pass, vw3-decode on standard input) frame 2 is not named yet: its slave's device is
    chosen at frame 4."""
    p38 = ROOT / "captures" / "p38_protection.pcap"
    plugin_keys = ["-e", "frame.number"] + [arg for key in ("code", "value", "status", "text")
                                            for arg in ("-e", f"vw3.reg.{key}")]
    python_keys = [arg for key in ("frame", "code", "value", "status", "text") for arg in ("-e", key)]
    for two_pass in (True, False):
        plugin = run_tshark(p38, "-T", "fields", "-E", "aggregator=^", *plugin_keys, two_pass=two_pass)
        assert plugin.returncode == 0, plugin.stderr
        python = subprocess.run([sys.executable, "-m", "dissector", str(p38) if two_pass else "-", "-T", "fields",
                                 "-E", "aggregator=^", *python_keys], capture_output=True, cwd=ROOT, timeout=120,
                                input=None if two_pass else p38.read_bytes())
        assert python.returncode == 0, python.stderr
        for code, story in P38_STORY.items():
            expected = story if two_pass else story[1:]
            assert _parameter_rows(plugin.stdout, code) == expected, (code, two_pass)
            assert _parameter_rows(python.stdout.decode(), code) == expected, (code, two_pass)
