"""Profile `auto`'s reason names the frame that decided it ('Read Device Identification in frame #2: ...');
--stats, --stats --json and the --report page show it as it is, as -V's `Profile:` line and the plugin's
`Why this profile` do (tests/integration/test_lua_profile_reason_once.py). Before, --stats and the report
said the frame again after it: `... ProductCode 'ATV71HU15M3' (frame #2)`."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import write_pcap

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
T0 = 1767225600.0
# Read Device Identification of slave 1 (its answer: ProductCode ATV71HU15M3), then a read of 8400.
FRAMES = [rtu("01 2B 0E 01 00"), rtu("01 2B 0E 01 01 00 00 01 01 0B " + b"ATV71HU15M3".hex()),
          rtu("01 03 20 D0 00 01"), rtu("01 03 02 00 05")]
REASON = "Read Device Identification in frame #2: ProductCode 'ATV71HU15M3'"


def _pcap(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "id.pcap", [(frame, T0 + 0.05 * index) for index, frame in enumerate(FRAMES)])


@BOTH
def test_stats_names_the_deciding_frame_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", str(_pcap(tmp_path))])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    start = lines.index("Device profiles")
    assert lines[start:start + 5] == [
        "Device profiles",
        "slave  profile  why",
        "-" * 81,
        f"    1  atv71    {REASON}",
        "",
    ]


@BOTH
def test_stats_json_gives_the_reason_and_the_frame(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                   pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--stats", "--json", str(_pcap(tmp_path))])
    assert (status, err) == (0, "")
    assert json.loads(out)["profiles"] == [{"slave": 1, "profile": "atv71", "reason": REASON, "frame": 2}]


@BOTH
def test_report_names_the_deciding_frame_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    page = tmp_path / "r.html"
    status, out, err = run_cli(["--report", str(page), str(_pcap(tmp_path))])
    assert (status, out, err) == (0, "", "")
    assert re.findall(r"<h3>Device profiles</h3>.*?<tbody>(.*?)</tbody>", page.read_text(encoding="utf-8")) == [
        "<tr><td>1</td><td>atv71</td><td>Read Device Identification in frame #2: ProductCode "
        "&#x27;ATV71HU15M3&#x27;</td></tr>"
    ]


@BOTH
def test_detail_profile_line_is_the_same_text(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["-V", str(_pcap(tmp_path))])
    assert (status, err) == (0, "")
    assert out.count(f"    Profile: atv71 ({REASON})\n") == 4
