"""The report's data: per-column downsampling that keeps extremes, protection marks, a self-contained page."""
from __future__ import annotations

import json
import math
import re

from dissector.devices.build import build_annotator
from dissector.model import Frame, Kind, Register
from dissector.pipeline import dissect
from dissector.render.report import ReportCollector
from dissector.render.report.collect import COLUMNS, Columns
from dissector.render.report.html import render_report
from dissector.render.stats import StatsCollector
from dissector.sources.reader import open_source

from conftest import ROOT

CAPTURES = ROOT / "captures"


def collect(name: str) -> tuple[ReportCollector, StatsCollector]:
    annotate = build_annotator(["atv71"], [])
    report, stats = ReportCollector(annotate), StatsCollector()
    for item in dissect(open_source(str(CAPTURES / name)), annotate=annotate):
        report.add(item)
        stats.add(item)
    return report, stats


def reading(number: int, time: float, value: int, scaled: float) -> Frame:
    frame = Frame(0, b"", time, Kind.RESPONSE, 4, 3, 0, 0, number=number)
    frame.registers = [Register(3202, value, code="RFR", unit="Hz", scaled=scaled, status="ok")]
    return frame


def test_a_day_of_samples_keeps_every_spike_in_few_points() -> None:
    report = ReportCollector()
    spikes = {23_457: 900.0, 151_234: -50.0}
    count = 200_000  # one every 150 ms: 8.3 hours
    for number in range(count):
        scaled = spikes.get(number, round(30 + 10 * math.sin(number / 5000), 1))
        report.add(reading(number, 1_767_225_600 + number * 0.15, int(scaled * 10) & 0xFFFF, scaled))
    data = report.data()
    (series,) = data["parameters"]
    assert data["span"] == round((count - 1) * 0.15, 6) and series["values"] == count
    assert data["span"] / data["column_width"] < COLUMNS  # at most COLUMNS pixel columns
    assert len(series["x"]) <= 4 * COLUMNS and series["x"] == sorted(series["x"])
    assert max(series["y"]) == 900 and min(series["y"]) == -50  # one sample each, still drawn
    for number, value in spikes.items():
        assert round(number * 0.15, 6) in series["x"]
    assert (series["code"], series["unit"], series["step"]) == ("RFR", "Hz", False)


def test_constant_values_need_two_points() -> None:
    columns = Columns()
    for x in range(10_000):
        columns.add(x // 10, float(x), 7.0)
    assert columns.points() == ([0.0, 9999.0], [7.0, 7.0])


def test_p38_marks_and_steps() -> None:
    report, _stats = collect("p38_protection.pcap")
    data = report.data()
    by_code = {p["code"]: p for p in data["parameters"]}
    chcf = by_code["CHCF"]
    assert chcf["step"] and chcf["labels"] == {"3": "IO (I/O profile)"}
    assert chcf["x"] == [0.010157, 0.534233] and chcf["y"] == [3, 3]
    # One story, as the summary and --watch tell it: CHCF protected from frame 6 (16#8000), COP from
    # frame 10 (exception 02); staying protected is no new mark.
    assert chcf["marks"] == [[1.059949, "protected"]]
    assert by_code["COP"]["marks"] == [[2.10596, "protected (exception 02)"]]
    assert data["event_counts"] == {
        "exception": 2, "protection": 3, "crc": 0, "noise": 0, "silence": 0, "unanswered": 0
    }


def test_untimed_events_are_numbered_by_their_frames() -> None:
    from helpers import run_cli

    for name in ("p38_protection.bin", "noisy_bus.bin"):
        path = f"/tmp/vw3-report-{name}.html"
        status, out, err = run_cli(["--report", path, str(CAPTURES / name)])
        assert (status, out) == (0, "")
        page = open(path, encoding="utf-8").read()
        # Grouped (issue 29): kind, slave, event, count, first and last frame.
        rows = re.findall(
            r"<tr><td>(\w+)</td><td>(\d*)</td><td>([^<]*)</td><td>(\d+)</td><td>(#\d+)</td><td>(#\d+|)</td></tr>", page)
        exception = "exception 02 to function 3: address does not exist (also: every parameter read is non-existent or protected)"
        expected = {
            "p38_protection.bin": [
                # #2: profile auto chooses the ATV71 over the whole file, before the decode (issue 27)
                ("protection", "12", "8400 non-existent", "1", "#2", ""),
                ("protection", "12", "CHCF (8401) protected", "1", "#6", ""),
                ("exception", "12", exception, "2", "#10", "#12"),
                ("protection", "12", "COP (8402) protected (exception 02)", "1", "#10", ""),
            ],
        }
        if name in expected:
            assert rows == expected[name]
        assert rows
        # Every event's number is the frame it happened in, as the summary numbers it.
        status, summary, _ = run_cli([str(CAPTURES / name)])
        kinds = {int(line.split()[0]): line.split()[3] for line in summary.splitlines() if line.strip()}
        for kind, _slave, _text, _count, first, last in rows:
            for number in filter(None, (first, last)):
                shown = kinds[int(number[1:])]
                assert {"noise": "noise", "crc": None}.get(kind, shown) in (shown, None), (number, kind, shown)


def test_noisy_bus_events() -> None:
    report, _stats = collect("noisy_bus.pcap")
    events = report.data()["events"]
    assert [(kind, slave) for _x, kind, slave, _text in events] == [
        ("noise", None), ("crc", 1), ("unanswered", 5), ("unanswered", 5), ("noise", None)
    ]
    assert events[0][3] == "4 bytes of noise at offset 0"


def test_page_is_self_contained_and_escapes_its_data() -> None:
    report, stats = collect("atv71_commissioning.pcap")
    page = render_report(report, stats)
    assert not re.search(r"https?://", page)
    assert not re.search(r"<(script|link|img)[^>]+(src|href)=", page)
    payload = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', page, re.S).group(1)
    data = json.loads(payload)
    assert [p["code"] for p in data["parameters"]][:4] == ["SFR", "TFR", "HSP", "LSP"]
    assert data["slaves"][0]["time"]["count"] == 52 and sum(data["slaves"][0]["time"]["counts"]) == 52
    assert "<td>23 Read/Write Multiple Registers</td><td>read 3201..3202 (2), write 8501..8502 (2)</td><td>40</td>" in page


def test_unwritable_report_is_one_line(tmp_path) -> None:
    from helpers import run_cli

    status, out, err = run_cli([str(CAPTURES / "p38_protection.bin"), "--report", str(tmp_path / "no" / "r.html")])
    assert (status, out) == (2, "")  # refused before decoding, as -w
    assert err == f"vw3-decode: --report {tmp_path / 'no' / 'r.html'}: No such file or directory\n"


def test_report_of_a_live_line_is_refused() -> None:
    from helpers import run_cli

    for option in (["--report", "r.html"], ["--stats"]):
        assert run_cli(["--live", "loop://", *option]) == (
            2, "", "vw3-decode: --report and --stats read files: capture with -w FILE, then report on it\n"
        )
