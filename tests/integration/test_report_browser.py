"""The HTML report in a real browser (Debian's chromium, headless): it loads without a script error and
draws what the capture holds. Installed with apt-get when missing, never skipped."""
from __future__ import annotations

import html
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT
from lua_harness import ensure_tool

CAPTURES = ROOT / "captures"


def chromium() -> str:
    return ensure_tool("chromium", "chromium")


def report(tmp_path: Path, capture: str) -> Path:
    out = tmp_path / (Path(capture).stem + ".html")
    result = subprocess.run(
        [sys.executable, "-m", "dissector", str(CAPTURES / capture), "--report", str(out)],
        cwd=ROOT, capture_output=True, text=True, timeout=120,
    )
    assert (result.returncode, result.stderr) == (0, "")
    return out


def dump_dom(tmp_path: Path, page: Path) -> str:
    profile = tmp_path / f"profile-{page.stem}"
    profile.mkdir()
    command = [
        chromium(), "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        f"--user-data-dir={profile}", "--window-size=1200,900", "--dump-dom", page.as_uri(),
    ]
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr[-2000:]
    return result.stdout


def errors(dom: str) -> str:
    match = re.search(r'<pre id="errors">(.*?)</pre>', dom, re.S)
    assert match is not None, "the page has no error hook"
    return match.group(1)


def charts(dom: str, kind: str) -> list[str]:
    """The opening tags of the chart containers of one kind."""
    return re.findall(rf'<div class="chart {kind}"[^>]*>', dom)


def test_commissioning_report_draws_every_slave_and_parameter(tmp_path: Path) -> None:
    page = report(tmp_path, "atv71_commissioning.pcap")
    text = page.read_text()
    assert not re.search(r"https?://", text)  # nothing to fetch on an offline laptop
    assert not re.search(r"<(script|link|img)[^>]+(src|href)=", text)
    dom = dump_dom(tmp_path, page)
    assert errors(dom) == ""
    (histogram,) = charts(dom, "rt")
    assert 'data-slave="2"' in histogram and 'data-drawn="uplot"' in histogram
    trends = charts(dom, "trend")
    codes = [re.search(r'data-code="([^"]*)"', tag).group(1) for tag in trends]
    # Every parameter the capture reads or writes, with its code from the ATV71 map: a trend when its
    # value changed, a row of the single-value table when not; the index links them all, named first.
    assert codes == ["HSP", "ETA", "RFR", "CHCF", "CMD", "LFR"]
    single = re.search(r'<h3 id="single">.*?</table>', dom, re.S).group(0)
    assert re.findall(r"<tr><td>2</td><td>\d+</td><td>(\w+)</td>", single) == [
        "SFR", "TFR", "LSP", "COP", "FR1", "CD1", "ACC", "DEC"]
    # (as --stats says it: the scale's decimals kept)
    assert "<td>3102</td><td>SFR</td><td>Switching frequency</td><td>4.0 kHz</td><td>1</td>" in single
    index = re.search(r'<p class="index">(.*?)</p>', dom).group(1)
    assert re.findall(r">(\w+)</a>", index) == ["SFR", "TFR", "HSP", "LSP", "ETA", "RFR", "CHCF", "COP", "FR1",
                                                "CD1", "CMD", "LFR", "ACC", "DEC"]
    assert all('data-drawn="uplot"' in tag for tag in trends)
    # Setpoints (written: HSP, CHCF, CMD, LFR) and enumerations are steps; RFR, a measurement, is not.
    assert [code for code, tag in zip(codes, trends) if 'data-step="1"' in tag] == ["HSP", "ETA", "CHCF", "CMD", "LFR"]
    # Status words that share their first 26 characters are told apart on the axis.
    eta = json.loads(html.unescape(re.search(r'data-code="ETA"[^>]*data-labels="([^"]*)"', dom).group(1)))
    assert len(set(eta)) == len(eta) == 3
    (timeline,) = charts(dom, "timeline")
    assert 'data-drawn="uplot"' in timeline
    (responses,) = charts(dom, "rtt")
    assert 'data-slave="2"' in responses and 'data-drawn="uplot"' in responses
    (load,) = charts(dom, "load")
    assert 'data-drawn="uplot"' in load
    assert dom.count('class="uplot') == len(trends) + 4  # one canvas chart each: histogram, response times, load, timeline
    assert "exception 07 to function 6" in dom  # the refused CHCF write, on the timeline's list


def test_p38_protection_events_are_marked(tmp_path: Path) -> None:
    dom = dump_dom(tmp_path, report(tmp_path, "p38_protection.pcap"))
    assert errors(dom) == ""
    chcf = re.search(r'data-code="CHCF".*?</ul>', dom, re.S).group(0)
    marks = re.findall(r'<li class="mark" data-x="([^"]+)">([^<]*)</li>', chcf)
    # frame 6: 16#8000 at a known parameter; still protected at frame 10 (the read refused): no new mark.
    assert marks == [("1.059949", "1.059949: protected")]
    # Events grouped, with their frame numbers although the capture is timed.
    assert "<td>protection</td><td>12</td><td>CHCF (8401) protected</td><td>1</td><td>1.059949 #6</td><td></td>" in dom
    assert ("<td>exception</td><td>12</td><td>exception 02 to function 3: address does not exist (also: every parameter read is non-existent or protected)"
            "</td><td>2</td><td>2.105960 #10</td><td>2.627401 #12</td>") in dom


def test_a_script_error_shows_in_the_page(tmp_path: Path) -> None:
    # The hook the tests rely on does catch errors: a report with a failing script says so.
    page = report(tmp_path, "p38_protection.pcap")
    broken = tmp_path / "broken.html"
    broken.write_text(page.read_text().replace("</body>", "<script>undefinedFunction()</script></body>"))
    assert "undefinedFunction" in errors(dump_dom(tmp_path, broken))


@pytest.mark.parametrize(
    "capture", ["noisy_bus.pcap", "sel749m_polling.pcap", "ascii_session.pcap", "p38_protection.bin"]
)
def test_every_shipped_capture_renders_without_script_error(tmp_path: Path, capture: str) -> None:
    dom = dump_dom(tmp_path, report(tmp_path, capture))
    assert errors(dom) == ""
    drawn = re.findall(r'<div class="chart [a-z]+"[^>]*data-drawn="uplot"', dom)
    assert len(drawn) == len(re.findall(r'<div class="chart [a-z]+"', dom)) > 1


def test_empty_capture_gives_an_empty_report(tmp_path: Path) -> None:
    empty = tmp_path / "empty.bin"
    empty.write_bytes(b"")
    page = tmp_path / "empty.html"
    result = subprocess.run(
        [sys.executable, "-m", "dissector", str(empty), "--report", str(page)],
        cwd=ROOT, capture_output=True, text=True, timeout=60,
    )
    assert result.returncode == 0
    dom = dump_dom(tmp_path, page)
    assert errors(dom) == "" and "0 frames, 0 noise bytes in 0 runs" in dom and "No events." in dom


def test_a_200000_frame_capture_renders_with_the_health_charts(tmp_path: Path) -> None:
    """Issue 29: a long polling session (198,061 frames) gives a page of bounded size whose every chart
    draws: response times against time per slave, bus load, the timeline, trends; events grouped."""
    subprocess.run([sys.executable, "-m", "dissector.sim.simulate", "--out", str(tmp_path), "--transactions",
                    "100000", "--seed", "1"], cwd=ROOT, check=True, capture_output=True, timeout=600)
    capture = tmp_path / "bench-100000-1.pcap"
    page = tmp_path / "long.html"
    result = subprocess.run(
        [sys.executable, "-m", "dissector", str(capture), "--report", str(page), "-t", "ud"],
        cwd=ROOT, capture_output=True, text=True, timeout=900,
    )
    assert (result.returncode, result.stderr) == (0, "")
    assert page.stat().st_size < 3_000_000  # downsampled: the page does not grow with the capture
    dom = dump_dom(tmp_path, page)
    assert errors(dom) == ""
    assert "198061 frames" in dom
    responses = charts(dom, "rtt")
    assert len(responses) >= 2 and all('data-drawn="uplot"' in tag for tag in responses)
    assert len(charts(dom, "load")) == 1 and 'data-drawn="uplot"' in charts(dom, "load")[0]
    drawn = re.findall(r'<div class="chart [a-z]+"[^>]*data-drawn="uplot"', dom)
    assert len(drawn) == len(re.findall(r'<div class="chart [a-z]+"', dom)) > 6
    # Grouped: a handful of rows, each with its count, its first and last time (-t ud) and frame.
    table = re.search(r'<table class="events">.*?</table>', dom, re.S).group(0)
    rows = re.findall(r"<tr><td>(\w+)</td><td>(\d*)</td><td>[^<]*</td><td>(\d+)</td><td>([^<]*)</td>", table)
    assert 0 < len(rows) < 200 and sum(int(count) for _kind, _slave, count, _first in rows) > len(rows)
    assert all(re.fullmatch(r"2026-01-01 \d\d:\d\d:\d\d\.\d{6} #\d+", first) for *_rest, first in rows)
    assert re.search(r'<p class="index">(<a href="#(p\d+|single)"[^>]*>[^<]+</a> ?)+</p>', dom)


def test_a_register_written_and_read_back_at_one_time_draws_a_step(tmp_path: Path) -> None:
    """FC23 writes RFR (3202) 16#7FFF and reads it back as 16#1234 in one transaction: two points at the
    answer's x (3276.7 then 466 Hz, the value read back last); the page draws them without error."""
    page = tmp_path / "fc23.html"
    result = subprocess.run(
        [sys.executable, "-m", "dissector", "--hex", "01 17 0C 82 00 01 0C 82 00 01 02 7F FF",
         "--hex", "01 17 02 12 34", "--profile", "atv71", "--report", str(page)],
        cwd=ROOT, capture_output=True, text=True, timeout=120,
    )
    assert (result.returncode, result.stderr) == (0, "")
    assert '"values":2,"marks":[],"marks_dropped":0,"decimals":1,"x":[2.0,2.0],"y":[3276.7,466]}' in page.read_text()
    dom = dump_dom(tmp_path, page)
    assert errors(dom) == ""
    (trend,) = charts(dom, "trend")
    assert 'data-code="RFR"' in trend and 'data-drawn="uplot"' in trend
