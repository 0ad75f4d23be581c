"""The report of a pcapng with two interfaces (two buses: render/buses.py) in headless chromium: each bus's
section draws its own charts from its own data block (report.js run once a bus, html.py buses_pieces),
without a script error; an error in one bus's drawing is shown and the other bus is still drawn."""
from __future__ import annotations

import re
import struct
import subprocess
import sys
from pathlib import Path

from conftest import ROOT
from dissector.render.pcapngwriter import PcapngWriter
from test_report_browser import charts, dump_dom, errors

CAPTURES = ROOT / "captures"


def _records(path: Path) -> list[tuple[int, bytes]]:
    """A little-endian microsecond pcap's records: (microseconds from its first, bytes)."""
    data = path.read_bytes()
    assert data[:4] == bytes.fromhex("d4c3b2a1")
    records, at, first = [], 24, None
    while at < len(data):
        seconds, micros, length, _original = struct.unpack_from("<IIII", data, at)
        stamp = seconds * 1_000_000 + micros
        first = stamp if first is None else first
        records.append((stamp - first, data[at + 16:at + 16 + length]))
        at += 16 + length
    return records


def two_bus_report(tmp_path: Path) -> Path:
    """p38_protection.pcap heard on /dev/ttyUSB0, atv71_commissioning.pcap on /dev/ttyUSB1, at once."""
    packets = [(micros, 0, data) for micros, data in _records(CAPTURES / "p38_protection.pcap")]
    packets += [(micros + 500, 1, data) for micros, data in _records(CAPTURES / "atv71_commissioning.pcap")]
    capture = tmp_path / "two.pcapng"
    names = [(f"/dev/ttyUSB{index}", f"serial port /dev/ttyUSB{index}, 19200 baud") for index in (0, 1)]
    with open(capture, "wb") as stream:
        writer = PcapngWriter(stream, if_name=names[0][0], if_description=names[0][1])
        for micros, interface, data in sorted(packets):
            writer.use_interface(*names[interface])
            writer.write(data, 1_767_225_600 + micros / 1e6)
        writer.close()
    page = tmp_path / "two.html"
    result = subprocess.run([sys.executable, "-m", "dissector", str(capture), "--report", str(page)],
                            cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert (result.returncode, result.stderr) == (0, "")
    return page


def test_each_bus_draws_its_own_charts(tmp_path: Path) -> None:
    page = two_bus_report(tmp_path)
    dom = dump_dom(tmp_path, page)
    assert errors(dom) == ""
    sections = re.findall(r'<section class="bus" id="b(\d)" data-charts="(\d+)">(.*?)</section>', dom, re.S)
    assert [index for index, _count, _body in sections] == ["0", "1"]
    for _index, count, body in sections:
        drawn = re.findall(r'<div class="chart [a-z]+"[^>]*data-drawn="uplot"', body)
        assert len(drawn) == len(re.findall(r'<div class="chart [a-z]+"', body)) == body.count('class="uplot') == int(count)
    assert re.search(r'<body data-charts="(\d+)"', dom).group(1) == str(sum(int(count) for _i, count, _b in sections))
    # Bus 0 is p.38's line: CHCF protected at its frame 6; bus 1 the commissioning's, its slave 2's trends.
    p38, commissioning = sections[0][2], sections[1][2]
    chcf = re.search(r'data-code="CHCF".*?</ul>', p38, re.S).group(0)
    assert re.findall(r'<li class="mark" data-x="([^"]+)">([^<]*)</li>', chcf) == [("1.059949", "1.059949: protected")]
    codes = [re.search(r'data-code="([^"]*)"', tag).group(1) for tag in charts(commissioning, "trend")]
    assert codes == ["HSP", "ETA", "RFR", "CHCF", "CMD", "LFR"]
    (histogram,) = charts(commissioning, "rt")
    assert 'data-slave="2"' in histogram and 'data-drawn="uplot"' in histogram


def test_one_bus_failing_leaves_the_other_drawn(tmp_path: Path) -> None:
    page = two_bus_report(tmp_path)
    broken = tmp_path / "broken.html"
    broken.write_text(page.read_text().replace('id="report-data-0"', 'id="gone"'))
    dom = dump_dom(tmp_path, broken)
    assert errors(dom) != ""
    sections = dict(re.findall(r'<section class="bus" id="b(\d)"([^>]*)>', dom))
    assert sections["0"] == "" and re.fullmatch(r' data-charts="\d+"', sections["1"])
