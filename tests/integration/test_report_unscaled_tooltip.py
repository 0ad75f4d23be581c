"""A value whose scale the device's settings choose (map scale `?`: the ATV71's ACC and DEC, atv71.csv) is
`10 (unscaled, in s)` in the summary and in --report's table of single values, but the chart's tooltip said
`10 s` (and the chart's axis and heading `s`, `in s`): the data's unit was the map row's. Now the unit the
data gives a trend is what the value's text says after its number (report/reading.py shown_unit), so
report.js's tooltip, run here under node with its own formatter, says what the table says. The compiled
engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import ensure_tool, write_pcap

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[2]
REPORT_JS = ROOT / "dissector" / "render" / "report" / "static" / "report.js"
# Slave 2 (ATV71): FC16 of ACC, DEC = 10, 10 (9001..9002), then FC6 of ACC = 20: ACC a trend, DEC one value.
FRAMES = ["02 10 23 29 00 02 04 00 0A 00 0A", "02 10 23 29 00 02", "02 06 23 29 00 14", "02 06 23 29 00 14"]
# Then LFR (8502, scale 0.1 Hz) = 30.0 Hz, 30.5 Hz: a trend whose tooltip said `30 Hz` where the summary says 30.0
SCALED = ["02 06 21 36 01 2C", "02 06 21 36 01 2C", "02 06 21 36 01 31", "02 06 21 36 01 31"]
# report.js run with a uPlot that keeps each trend's options: its label, axis label and each point's tooltip
HARNESS = r"""
const fs = require("fs");
const html = fs.readFileSync(process.argv[2], "utf8");
const data = html.match(/id="report-data">([\s\S]*?)<\/script>/)[1];
const trends = [...html.matchAll(/<div class="chart trend"[^>]*data-index="(\d+)"/g)].map(m => m[1]);
const element = index => ({ clientWidth: 900, getAttribute: () => index, setAttribute() {}, appendChild() {} });
global.document = {
  getElementById: () => ({ textContent: data }),
  querySelectorAll: selector => selector === ".chart.trend" ? trends.map(element) : [],
  createElement: () => ({}), createTextNode: () => ({}), body: { setAttribute() {} },
};
const drawn = [];
global.uPlot = function (opts, points) {
  const series = opts.series[1];
  drawn.push({ label: series.label, axis: opts.axes[1].label, tips: points[1].map(v => series.value(null, v)) });
};
global.uPlot.paths = { stepped: () => null };
eval(fs.readFileSync(process.argv[3], "utf8"));
process.stdout.write(JSON.stringify(drawn));
"""


@pytest.mark.parametrize("pure", [False, True])
def test_tooltip_says_what_the_table_says(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    node = ensure_tool("node", "nodejs")
    use_engine(monkeypatch, pure)
    path = write_pcap(tmp_path / "ramps.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                                for index, frame in enumerate(FRAMES + SCALED)])
    assert run_cli(["--profile", "atv71", str(path)])[1].splitlines()[2].endswith(
        "Write Single Register 9001 ACC=20 (unscaled, in s)  CRC ok")
    page = tmp_path / "ramps.html"
    assert run_cli(["--profile", "atv71", "--report", str(page), str(path)])[0] == 0
    text = page.read_text(encoding="utf-8")
    assert "<td>DEC</td><td>Deceleration</td><td>10 (unscaled, in s)</td><td>0</td><td>1</td>" in text  # written once
    assert '<span class="code">ACC (9001)</span> <small>Acceleration, unscaled, in s; 2 values</small>' in text
    harness = tmp_path / "harness.js"
    harness.write_text(HARNESS)
    done = subprocess.run([node, str(harness), str(page), str(REPORT_JS)], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    assert json.loads(done.stdout) == [  # (by address)
        {"label": "LFR", "axis": "Hz", "tips": ["30.0 Hz", "30.5 Hz"]},
        {"label": "ACC", "axis": "(unscaled, in s)", "tips": ["10 (unscaled, in s)", "20 (unscaled, in s)"]}]
