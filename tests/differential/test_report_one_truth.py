"""--report's trends tell what the other outputs tell, and the four ways to make the page agree: the file
and standard input (one pass, profile `auto` choosing while it reads), each with the compiled engine
(dissector/accel/_report.h, _columns.h) and with the Python stages (VW3_PURE_PYTHON=1). Exact series
data for exact bytes:
- an FC23 read/write writes a register and reads it back in one transaction: both values are drawn at the
  answer's time, the value written then the value read back, which is the trend's last point as it is
  the summary's value and --stats' `last` (the first of them was drawn alone);
- values kept before profile `auto` took its choice back are read again as the file reads them (FC23's
  written words stayed unscaled on standard input in Python, 32767 Hz beside the engine's 3276.7; names,
  units and steps of a device no longer chosen stayed);
- beyond MAX_SERIES parameters, the series kept are the first seen in the stream on standard input too
  (frames held back until their slave's choice made theirs later). The extension must be built."""
from __future__ import annotations

import io
import json
import random
import re
from pathlib import Path

import pytest

from dissector.accel._summary import Columns as CompiledColumns
from dissector.app.cli import Environment, run
from dissector.render.report.collect import MAX_SERIES, Columns
from test_report_columns import report
from test_timed_summary import frames_of, write_pcap

WAYS = [(where, pure) for where in ("file", "stdin") for pure in (False, True)]

# A capture of 15 frames (pcap, microseconds): an FC6 write of 3201 to slave 1, its echo; an FC23 of slave 1
# writing 3202..3203 and reading 3202..3204 (its answer at 3.068400 s after the first frame); FC2 to slave 1,
# which profile `auto` then finds the ATV71 does not support (the choice of frame 8 taken back); broadcasts,
# slave 247's read of 8606..8615, unanswered requests.
S8 = [(1700000001, 852099, "01060c810000dab2"), (1700000001, 854099, "01060c810000dab2"),
      (1700000003, 366399, "00010c8500082ea4"), (1700000003, 368399, "0308000e0000802a"),
      (1700000004, 868399, "0308000e0000802a"), (1700000004, 918399, "001031c6000204b6a000028513"),
      (1700000004, 918499, "01170c8200030c820002047fff00648846"), (1700000004, 920499, "0117068000ffff00643f85"),
      (1700000006, 420499, "f703219e000aba89"),
      (1700000006, 470499, "f703140003000080008000000200017fff000380000000848a"),
      (1700000006, 520499, "01022135000863fe"), (1700000006, 530499, "0101015591b7"),
      (1700000006, 830499, "00060c8b80015b61"), (1700000006, 840499, "030621378000521a"),
      (1700000008, 342499, "01102329000102000232aa")]


def page_data(argv: list[str], page: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, stdin: bytes = b"") -> dict:
    """The data the page embeds, from a run of test_report_columns.report (engine or VW3_PURE_PYTHON=1)."""
    found = re.search(r'<script type="application/json" id="report-data">(.*?)</script>',
                      report(argv, page, monkeypatch, pure, stdin), re.S)
    assert found is not None
    return json.loads(found.group(1))


def four_ways(capture: Path, options: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict:
    """The report's data made the four ways, asserted equal; the file's, with the engine."""
    made = {(where, pure): page_data([str(capture) if where == "file" else "-", *options],
                                     tmp_path / f"{where}-{pure}.html", monkeypatch, pure,
                                     capture.read_bytes() if where == "stdin" else b"")
            for where, pure in WAYS}
    for way in WAYS[1:]:
        assert made[way] == made[WAYS[0]], way
    return made[WAYS[0]]


def series(data: dict, slave: int, address: int) -> dict:
    found = [p for p in data["parameters"] if (p["slave"], p["address"]) == (slave, address)]
    assert len(found) == 1
    return found[0]


def trend(data: dict, slave: int, address: int) -> tuple:
    p = series(data, slave, address)
    return p["code"], p["unit"], p["step"], p["labels"], p["values"], p["x"], p["y"]


def s8_capture(tmp_path: Path) -> Path:
    capture = tmp_path / "s8.pcap"
    write_pcap(capture, [(bytes.fromhex(data), s * 10**9 + us * 1000) for s, us, data in S8], nano=False)
    return capture


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("profile, written, read, last", [([], 32767, 4660, "4660"),
                                                          (["--profile", "atv71"], 3276.7, 466, "466.0 Hz")])
def test_fc23_written_then_read_back_both_drawn_the_read_last(pure: bool, profile: list[str], written: float,
                                                              read: float, last: str, tmp_path: Path,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    """FC23 writes 16#7FFF to 3202 and reads it back as 16#1234 (the summary's 3202=4660, RFR=466.0 Hz with
    the ATV71 profile; --stats' last 4660): a step at the answer (frame 2, the x of an untimed input)."""
    argv = ["--hex", "01 17 0C 82 00 01 0C 82 00 01 02 7F FF", "--hex", "01 17 02 12 34", *profile]
    data = page_data(argv, tmp_path / "page.html", monkeypatch, pure)
    unit = "Hz" if profile else None
    assert trend(data, 1, 3202) == ("RFR" if profile else None, unit, False, {}, 2, [2.0, 2.0], [written, read])
    stdout = io.StringIO()
    assert run([*argv, "--stats"], Environment(io.BytesIO(b""), stdout, io.StringIO(), False, False)) == 0
    assert re.search(rf"\n +1 +3202 .* {last} +1\n", stdout.getvalue())


def test_capture_with_a_choice_taken_back_same_series_four_ways(tmp_path: Path,
                                                                 monkeypatch: pytest.MonkeyPatch) -> None:
    """Profile auto chooses the ATV71 for slave 1 at its FC23 answer (frame 8) and takes it back at its
    FC2 request (frame 11): the file names every frame with the last choice (no device: the words), and so
    does standard input now. FC23: 32767 written, 32768 read back, both at the answer's time."""
    data = four_ways(s8_capture(tmp_path), [], tmp_path, monkeypatch)
    assert trend(data, 1, 3201) == (None, None, False, {}, 1, [0.002], [0])
    assert trend(data, 1, 3202) == (None, None, False, {}, 2, [3.0684, 3.0684], [32767, 32768])
    assert trend(data, 1, 3203) == (None, None, False, {}, 2, [3.0684, 3.0684], [100, 65535])
    assert trend(data, 1, 3204) == (None, None, False, {}, 1, [3.0684], [100])
    assert trend(data, 247, 8608) == (None, None, False, {}, 1, [4.6184], [32768])
    assert [p["name"] for p in data["parameters"]] == [None] * 17


def test_capture_read_with_the_atv71_same_series_four_ways(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The same capture with the ATV71 profile given: FC23's written words scaled as its reads (3276.7 Hz,
    not 32767) on standard input in Python as well; 16#8000 read back from RFR is -3276.8 Hz (ambiguous)."""
    data = four_ways(s8_capture(tmp_path), ["--profile", "atv71"], tmp_path, monkeypatch)
    assert trend(data, 1, 3201) == ("ETA", None, True, {"0": "no bit set"}, 1, [0.002], [0])
    assert trend(data, 1, 3202) == ("RFR", "Hz", False, {}, 2, [3.0684, 3.0684], [3276.7, -3276.8])
    # (FRH is signed, data/maps/atv71.csv: 16#FFFF is -0.1 Hz)
    assert trend(data, 1, 3203) == ("FRH", "Hz", False, {}, 2, [3.0684, 3.0684], [10, -0.1])
    assert trend(data, 1, 3204) == ("LCR", "A", False, {}, 1, [3.0684], [10])
    assert series(data, 247, 8608)["marks"] == [[4.6184, "non-existent"]]


def test_more_parameters_than_kept_same_series_four_ways(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A random bus of some 4,000 parameters: the MAX_SERIES kept are the first seen in the stream, on
    standard input as from the file (328 of them differed: the frames held until their slave's choice)."""
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, frames_of(900, damaged=0.0))
    data = four_ways(capture, [], tmp_path, monkeypatch)
    assert len(data["parameters"]) == MAX_SERIES and data["parameters_dropped"] > 3000


@pytest.mark.parametrize("points, xs, ys", [
    ([(1.0, 5.0), (1.0, 3.0)], [1.0, 1.0], [5.0, 3.0]),  # written, read back: the read last
    ([(1.0, 3.0), (1.0, 5.0)], [1.0, 1.0], [3.0, 5.0]),
    ([(1.0, 5.0), (1.0, 3.0), (1.0, 5.0)], [1.0, 1.0, 1.0], [5.0, 3.0, 5.0]),  # left and come back to
    ([(1.0, 5.0), (1.0, 5.0)], [1.0], [5.0]),
    ([(1.0, 5.0), (1.0, 9.0), (1.0, 3.0), (1.0, 4.0)], [1.0, 1.0, 1.0, 1.0], [5.0, 3.0, 9.0, 4.0]),
    ([(1.0, 5.0), (2.0, 3.0), (2.0, 4.0), (3.0, 4.0)], [1.0, 2.0, 3.0], [5.0, 3.0, 4.0]),  # (2, 4): none of the 4
    ([(1.0, 2.0), (1.0, 7.0), (2.0, 7.0), (2.0, 2.0)], [1.0, 1.0, 2.0], [2.0, 7.0, 2.0]),  # the highest: its first
])
def test_points_at_one_x_in_order_the_last_last(points: list, xs: list, ys: list) -> None:
    """One column's points (Columns.points, the compiled columns' drawn_json): first, lowest, highest,
    last, those at one x in that order, none drawn twice."""
    python, compiled = Columns(), CompiledColumns()
    for x, y in points:
        python.add(0, x, y)
        compiled.add(0, x, y)
    assert python.points() == (xs, ys)
    assert compiled.drawn_json(0.0, 6) == (json.dumps(xs, separators=(",", ":")),
                                           json.dumps([int(y) for y in ys], separators=(",", ":")))


@pytest.mark.parametrize("seed", range(4))
def test_random_buses_same_series_four_ways(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(seed)
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, frames_of(seed + 910, damaged=0.05))
    four_ways(capture, rng.choice([[], ["--profile", "auto"], ["--address-style", "plc"], ["--stats"]]),
              tmp_path, monkeypatch)
