"""An ASCII bus's timing is told by ASCII's rules (Serial Line Guide 2.5.2: ':' starts a frame, CR LF ends
it, up to 1 s between its characters), not RTU's: --stats, --stats --json and --report said `t3.5 2.005 ms`
and counted ASCII gaps `below t3.5` (here an answer 1.5 ms after its request: `1 below t3.5`). Now no t3.5, no
such count, a `framing` line saying what applies; RTU and ASCII captures counted as one bus count the RTU
captures' gaps only. Exact output for exact bytes, under the compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

from dissector.render.pcapwriter import PcapWriter

T0 = 1700000000.0
QUERY, ANSWER = b":0C0320D10001FF\r\n", b":0C03020003EC\r\n"  # read 8401 of slave 12, its answer 3
# 17 characters of 10 bits at 19200 baud last 8.854 ms: the first answer starts 1.5 ms after the query ends.
ASCII = [(0.0, QUERY), (0.010354, ANSWER), (1.0, QUERY), (1.02, ANSWER)]
# 8 bytes of 11 bits last 4.583 ms: the answer starts 1.5 ms after, below t3.5 (2.005 ms); 5 s before the above.
RTU = [(-5.0, rtu("0C 03 20D1 0001")), (-4.993917, rtu("0C 03 02 0003"))]

FRAMING = ("framing: Modbus ASCII, ':' to CR LF: no silence separates frames, so t3.5 and t1.5 (RTU rules) "
           "are not applied and the line speed only times the characters (load, gaps); a frame's characters "
           "may be up to 1 s apart (a longer silence is warned on its frame)")
ASCII_TIMING = f"""Bus timing
line: 19200 baud (assumed: --baud sets it), 10 bits a character (start, 7 data, parity or a second stop, stop), timeout 1000 ms
{FRAMING}
load: 3.2 %
inter-frame gaps: 3; min 1.500 median 11.150 p95 981.830 max 981.833 ms
  1-2 ms: 1, 10-20 ms: 1, 500-1000 ms: 1
master turnaround (answer end to next request, ms): median 981.833 p95 981.833 max 981.833 (1)
slave  responses  median ms  p95 ms  max ms  margin to timeout ms  >90% of timeout
   12          2       15.2    20.0    20.0                 988.9                0
outages: none
"""


def _pcap(path: Path, frames: list[tuple[float, bytes]]) -> Path:
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for offset, data in frames:
            writer.write(data, T0 + offset)
    return path


@pytest.fixture
def ascii_pcap(tmp_path: Path) -> Path:
    return _pcap(tmp_path / "ascii.pcap", ASCII)


@pytest.mark.parametrize("pure", [False, True])
def test_stats(ascii_pcap: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["-n", "--stats", str(ascii_pcap)])
    assert (status, err) == (0, "")
    assert out[out.index("Bus timing"):] == ASCII_TIMING


@pytest.mark.parametrize("pure", [False, True])
def test_stats_json(ascii_pcap: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["-n", "--stats", "--json", str(ascii_pcap)])
    assert (status, err) == (0, "")
    bus = json.loads(out)["bus"]
    assert (bus["bits_per_char"], bus["t35"], bus["gaps_below_t35"], bus["gaps"]["count"], bus["overlaps"]) == (
        10, None, None, 3, 0)


@pytest.mark.parametrize("pure", [False, True])
def test_report(ascii_pcap: Path, tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    page = tmp_path / "r.html"
    status, out, err = run_cli(["-n", "--report", str(page), str(ascii_pcap)])
    assert (status, out, err) == (0, "", "")
    table = re.search(r'<table class="bus">.*?</table>', page.read_text("utf-8")).group(0)
    assert table == (
        '<table class="bus"><thead><tr><th></th><th></th></tr></thead><tbody>'
        "<tr><td>line</td><td>19200 baud (assumed: --baud sets it), 10 bits a character (start, 7 data, parity or "
        "a second stop, stop)</td></tr><tr><td>load</td><td>3.2 %</td></tr>"
        "<tr><td>framing</td><td>Modbus ASCII, &#x27;:&#x27; to CR LF: no silence separates frames, so t3.5 and "
        "t1.5 (RTU rules) are not applied and the line speed only times the characters (load, gaps); a frame&#x27;s "
        "characters may be up to 1 s apart (a longer silence is warned on its frame)</td></tr>"
        "<tr><td>inter-frame gaps</td><td>1-2 ms: 1, 10-20 ms: 1, 500-1000 ms: 1</td></tr>"
        "<tr><td>master turnaround</td><td>median 981.8 ms, p95 981.8 ms, max 981.8 ms (1)</td></tr></tbody></table>")


@pytest.mark.parametrize("pure", [False, True])
def test_rtu_and_ascii_captures_as_one_bus(ascii_pcap: Path, tmp_path: Path, pure: bool,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    """The RTU capture's gap below t3.5 is counted, the ASCII capture's is not (before: 2 below t3.5)."""
    use_engine(monkeypatch, pure)
    rtu_pcap = _pcap(tmp_path / "rtu.pcap", RTU)
    status, out, err = run_cli(["-n", "--stats", str(rtu_pcap), str(ascii_pcap)])
    assert (status, err) == (0, "")
    lines = out[out.index("Bus timing"):].splitlines()
    assert lines[1:6] == [
        "line: 19200 baud (assumed: --baud sets it), 11 bits a character in RTU, 10 in ASCII, t3.5 2.005 ms, "
        "timeout 1000 ms",
        "framing: RTU and Modbus ASCII captures: gaps below t3.5 counted in the RTU captures only",
        "2 captures counted as one bus: gaps and turnarounds restart at each capture, the load is over the span "
        "from the first item to the last",
        "load: 0.7 %",
        "inter-frame gaps: 4, 1 below t3.5; min 1.500 median 6.325 p95 981.830 max 981.833 ms",
    ]
    status, out, err = run_cli(["-n", "--stats", "--json", str(rtu_pcap), str(ascii_pcap)])
    bus = json.loads(out)["bus"]
    assert (bus["t35"], bus["gaps_below_t35"]) == (0.002005, 1)
    # An RTU capture alone is told as it always was.
    status, out, err = run_cli(["-n", "--stats", str(rtu_pcap)])
    assert out[out.index("Bus timing"):].splitlines()[1:3] == [
        "line: 19200 baud (assumed: --baud sets it), 11 bits a character, t3.5 2.005 ms, timeout 1000 ms",
        "load: 85.1 %",
    ]
