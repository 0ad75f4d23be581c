"""Fields a Wireshark user filters and graphs on, against vw3-decode on the same captures (real tshark):
`vw3.unanswered` only where a request went unanswered, `vw3.reg.scaled` a number, one field per
parameter of the built-in maps (`vw3.atv71.rfr`) that an IO graph can plot."""
from __future__ import annotations

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
