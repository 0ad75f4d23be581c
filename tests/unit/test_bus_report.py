"""--report of a pcapng with packets from several interfaces (Wireshark capturing two vw3 extcap lines):
each interface is its own bus (render/buses.py), a section of the page under its title, drawn from its
own counts, devices and clock. Before, such a file was refused ('a report draws one bus', exit 2, with
the tshark command that splits it). A bus's section is the page of that interface saved alone (as
tshark -Y 'frame.interface_id == 1' -w writes it), its anchors and data block numbered; one bus's page is
unchanged (the other report tests). Interface names are bus data: text in the page, never markup.
Profile `auto`'s notes on a terminal are each bus's, under its title (only the first bus's were said).
"""
from __future__ import annotations

import io
import re
from pathlib import Path

import pytest

from dissector.accel import reportfeed
from dissector.app.cli import Environment, run
from helpers import run_cli, use_engine
from test_bus_stats import PACKETS, _pcapng

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
NAMES = ["/dev/pts/0", "/dev/pts/1"]
ATV71 = ("traffic fits its map: function 3 at 8400..8402 in frames #2 and #4; 16#8000 at 8400, its answer for a "
         "non-existent parameter")


def _report(argv: list[str], page: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--report", str(page), *argv])
    assert (status, out, err) == (0, "", "")
    return page.read_text(encoding="utf-8")


def _sections(page: str) -> list[str]:
    return re.findall(r'<section class="bus" id="b\d+">.*?</section>\n', page, re.S)


def _alone(page: str, index: int) -> str:
    """A one-bus page's body as the section of bus `index` shows it: anchors and data block numbered."""
    body = page[page.index("<nav>"):page.index("}</script>\n") + len("}</script>\n")]
    body = re.sub(r'(id|href)="(#?)(slaves|bus|poll|events|parameters|single|p\d+)"', rf'\1="\2b{index}-\3"', body)
    return body.replace('id="report-data"', f'id="report-data-{index}"')


@BOTH
def test_each_interface_is_a_section_as_it_alone_would_be(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                          pure: bool) -> None:
    two = tmp_path / "two.pcapng"
    two.write_bytes(_pcapng(NAMES, PACKETS))
    page = _report([str(two)], tmp_path / "r.html", monkeypatch, pure)
    assert f"<title>vw3-decode report: {two}</title>" in page
    assert (f'<pre id="errors"></pre><nav>buses: <a href="#b0">{two}: /dev/pts/0</a> '
            f'<a href="#b1">{two}: /dev/pts/1</a></nav>\n<section class="bus" id="b0">') in page
    sections = _sections(page)
    assert [re.findall(r'<h2 class="bus">(.*?)</h2>\n.*?<p class="summary">(.*?)</p>', section, re.S)
            for section in sections] == [
        [(f"{two}: /dev/pts/0", "4 frames, 0 noise bytes in 0 runs, 0.208 s")],
        [(f"{two}: /dev/pts/1", "6 frames, 0 noise bytes in 0 runs, 0.600 s")],
    ]
    # Slave 12 of each bus is its own: its device, its answers. (/dev/pts/1's last two requests: one
    # unanswered, the file ending with the other, not known whether it was answered: no outage.)
    profiles = [re.findall(r"<h3>Device profiles</h3>.*?<tbody>(.*?)</tbody>", section)[0] for section in sections]
    assert profiles == [
        f"<tr><td>12</td><td>atv71</td><td>{ATV71}</td></tr>",
        "<tr><td>12</td><td>generic</td><td>no evidence of a device: spec semantics only</td></tr>",
    ]
    outages = [re.findall(r"<h3>Outages.*?<tbody>(.*?)</tbody>|<p>(No outage.*?)</p>", section) for section in sections]
    assert outages == [
        [("", "No outage: no slave left two consecutive requests unanswered.")],
        [("", "No outage: no slave left two consecutive requests unanswered.")],
    ]
    # Each section is, byte for byte, the page of its interface saved alone (tshark -Y 'frame.interface_id
    # == N' -w: one interface, its packets, the same if_name and description).
    for index, name in enumerate(NAMES):
        alone = tmp_path / f"bus{index}.pcapng"
        alone.write_bytes(_pcapng([name], [(0, micros, data) for bus, micros, data in PACKETS if bus == index]))
        single = _report([str(alone)], tmp_path / f"bus{index}.html", monkeypatch, pure)
        assert sections[index] == (f'<section class="bus" id="b{index}"><h2 class="bus">{two}: {name}</h2>\n'
                                   + _alone(single, index) + "</section>\n")
    assert page.count("<script>") == 3  # the error hook, uPlot, the drawing: once for every bus


@BOTH
def test_interface_names_are_text_in_the_page(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    # if_name is whatever the capturing host wrote: markup, a spreadsheet formula, a terminal escape.
    names = ['<img src=x onerror=alert(1)>', '=HYPERLINK("http://x")\x1b[2J</h2>']
    evil = tmp_path / "evil.pcapng"
    evil.write_bytes(_pcapng(names, PACKETS))
    page = _report([str(evil)], tmp_path / "r.html", monkeypatch, pure)
    shown = [f"{evil}: &lt;img src=x onerror=alert(1)&gt;", f"{evil}: =HYPERLINK(&quot;http://x&quot;)\\x1b[2J&lt;/h2&gt;"]
    assert f'<nav>buses: <a href="#b0">{shown[0]}</a> <a href="#b1">{shown[1]}</a></nav>' in page
    assert re.findall(r'<h2 class="bus">(.*?)</h2>', page) == shown
    assert "<img" not in page and "\x1b" not in page


def test_the_engine_feeds_each_bus(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The compiled count path (timedpath.count_input) feeds each interface's own collector: two Reports.
    made = []
    engine_report = reportfeed.engine_report

    def making(collector: object, health: object, annotator: object) -> object:
        made.append((collector, health))
        return engine_report(collector, health, annotator)  # type: ignore[arg-type]

    monkeypatch.setattr(reportfeed, "engine_report", making)
    two = tmp_path / "two.pcapng"
    two.write_bytes(_pcapng(NAMES, PACKETS))
    _report([str(two)], tmp_path / "r.html", monkeypatch, False)
    assert len(made) == 2 and made[0][0] is not made[1][0] and made[0][1] is not made[1][1]


@BOTH
def test_ring_files_are_a_section_an_interface(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    first, second = tmp_path / "a_00001.pcapng", tmp_path / "a_00002.pcapng"
    first.write_bytes(_pcapng(NAMES, PACKETS[:4]))
    second.write_bytes(_pcapng(NAMES, [(bus, micros + 1_000_000, data) for bus, micros, data in PACKETS[4:8]]))
    page = _report([str(first), str(second)], tmp_path / "r.html", monkeypatch, pure)
    merged = ("captures counted as one bus, as mergecap would join them (decode each alone for its own traffic "
              "and timing)")
    assert re.findall(r'<h2 class="bus">(.*?)</h2>\n.*?<p class="summary">(.*?)</p>', page, re.S) == [
        (f"{first}: /dev/pts/0, {second}: /dev/pts/0",
         f"4 frames, 0 noise bytes in 0 runs, 1.208 s, from 2 {merged}: {first}: /dev/pts/0, {second}: /dev/pts/0"),
        (f"{first}: /dev/pts/1, {second}: /dev/pts/1",
         f"4 frames, 0 noise bytes in 0 runs, 1.212 s, from 2 {merged}: {first}: /dev/pts/1, {second}: /dev/pts/1"),
    ]


@BOTH
@pytest.mark.parametrize("extra", [[], ["--report", "REPORT"], ["-T", "registers"]])
def test_profile_notes_of_each_bus(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                   extra: list[str]) -> None:
    use_engine(monkeypatch, pure)
    two = tmp_path / "two.pcapng"
    two.write_bytes(_pcapng(NAMES, PACKETS))
    argv = [str(tmp_path / "r.html") if arg == "REPORT" else arg for arg in extra] + [str(two)]
    out, err = io.StringIO(), io.StringIO()
    assert run(argv, Environment(io.BytesIO(), out, err, stdout_isatty=False, stderr_isatty=True)) == 0
    wrote = f"vw3-decode: wrote {tmp_path / 'r.html'}\n" if extra[:1] == ["--report"] else ""
    assert err.getvalue() == (
        f"vw3-decode: {two}: /dev/pts/0: profile slave 12: atv71 ({ATV71})\n"
        f"vw3-decode: {two}: /dev/pts/1: profile slave 12: generic (no evidence of a device: spec semantics only)\n"
        + wrote
    )
