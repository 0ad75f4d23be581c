"""--report of timed captures fed by the engine (dissector/accel/_report.h through timedpath.count_input:
the x axis and its doublings, events, the trends' points, response times and setpoints of the
transactions the engine counts) against the Python stages (VW3_PURE_PYTHON=1, render/report/collect.py
the reference): the page byte for byte on pcap, pcapng and hex dumps cut at random, with damage, noise,
late answers, outages, times going back and untimed records, on the shipped captures and on the
benchmark's mixes (bench/report.py), alone, with --stats and after other inputs. The extension must be
built: it is not skipped."""
from __future__ import annotations

import os
import random
from pathlib import Path

import pytest

from dissector.accel import reportfeed
from dissector.decode.fields import decode_frame
from dissector.model import Frame, Kind, Stamp
from dissector.render.pollcycle import PollCycle
from dissector.render.report.collect import MAX_SERIES, ReportCollector
from dissector.sim.mixes import PLANT_PROFILES, max_size_mix, plant_mix
from dissector.render.stats_store import new_store
from dissector.sim.simulate import generate_session, write_capture
from helpers import rtu
from test_report_columns import assert_same_report
from test_timed_stats import four_inputs, story
from test_timed_summary import cut_records, frames_of, write_pcap, write_pcapng

ROOT = Path(__file__).resolve().parents[2]
CAPTURES = ROOT / "captures"


class Fed:
    """Of the compiled runs: the Reports the engine fed, and the items the Python stages gave the collector."""

    def __init__(self) -> None:
        self.reports = 0
        self.python_items = 0


@pytest.fixture
def fed(monkeypatch: pytest.MonkeyPatch) -> Fed:
    seen = Fed()
    engine_report, add = reportfeed.engine_report, ReportCollector.add

    def making(*args: object) -> object:
        seen.reports += 1
        return engine_report(*args)  # type: ignore[arg-type]

    def adding(self: ReportCollector, item: object) -> None:
        if not os.environ.get("VW3_PURE_PYTHON"):
            seen.python_items += 1
        add(self, item)  # type: ignore[arg-type]

    monkeypatch.setattr(reportfeed, "engine_report", making)
    monkeypatch.setattr(ReportCollector, "add", adding)
    return seen


@pytest.mark.parametrize("seed", range(10))
def test_random_captures_same_report(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fed: Fed) -> None:
    rng = random.Random(seed)
    how = ["frame", "bursts", "untimed", "frame", "bursts"][seed % 5]
    records = cut_records(rng, frames_of(seed + 700, damaged=0.0 if seed == 0 else 0.08), how)
    capture = tmp_path / ("bus.pcapng" if seed % 3 == 2 else "bus.pcap")
    if seed % 3 == 2:
        write_pcapng(capture, records)
    else:
        write_pcap(capture, records, nano=seed % 2 == 0)
    options = [[], ["--profile", "atv71"], ["--profile", "auto"], ["--profile", "generic"], ["-n"],
               ["--stats", "--timeout", "0.03"], ["--address-style", "plc", "--profile", "atv71"]][seed % 7]
    data = assert_same_report([str(capture), *options], tmp_path, monkeypatch)
    assert fed.reports == 1 and data["parameters"]
    if seed == 0:  # undamaged: the engine counted most transactions itself
        assert fed.python_items < len(records) // 2


@pytest.mark.parametrize("options", [[], ["--stats", "--timeout", "0.03"], ["--profile", "atv71", "-t", "ud"]])
def test_outages_late_answers_and_times_going_back(options: list[str], tmp_path: Path,
                                                   monkeypatch: pytest.MonkeyPatch, fed: Fed) -> None:
    """Exceptions, writes (setpoints), an outage, answers after the timeout (unanswered), a record stamped
    before the one ahead of it, three minutes of silence (the columns double), untimed records."""
    capture = tmp_path / "story.pcap"
    write_pcap(capture, story())
    data = assert_same_report([str(capture), *options], tmp_path, monkeypatch)
    assert fed.reports == 1
    assert data["event_counts"]["exception"] and data["event_counts"]["unanswered"]
    assert data["column_width"] > 0.1  # doubled many times from 1 ms


@pytest.mark.parametrize("name", ["atv71_commissioning", "noisy_bus", "p38_protection", "sel749m_polling",
                                  "ascii_session"])
@pytest.mark.parametrize("profile", ["auto", "atv71"])
def test_shipped_captures_same_report(name: str, profile: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                      fed: Fed) -> None:
    assert_same_report([str(CAPTURES / f"{name}.pcap"), "--profile", profile], tmp_path, monkeypatch)
    assert fed.reports == (name != "ascii_session")  # (Modbus ASCII: the Python stages)


def test_several_inputs_one_report(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fed: Fed) -> None:
    """A pcap, a raw file (the Python stages) and a pcapng, then a hex dump: one axis, one set of series."""
    pcap, raw, polling, dump = four_inputs(tmp_path, 400, 5, 2, 9)
    # (after a raw file counted first, the statistics cannot go to the compiled store: Python's path)
    for files, engine in (([pcap, raw, polling], 2), ([dump, pcap], 2), ([raw, dump], 0)):
        fed.reports = 0
        assert_same_report([*map(str, files), "--stats"], tmp_path, monkeypatch)
        assert fed.reports == engine


@pytest.mark.parametrize("mix", ["polling", "plant", "max-size"])
def test_bench_mixes_same_report(mix: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fed: Fed) -> None:
    """The sessions of bench/report.py, with the profiles their users give: max-size has more parameters
    than the report keeps (MAX_SERIES), the plant floor relays' scaled values and exceptions."""
    frames = 6000
    records, options = {
        "polling": (generate_session(frames // 2, seed=1)[:frames], []),
        "plant": (plant_mix(frames, seed=2), [option for profile in PLANT_PROFILES for option in ("--profile", profile)]),
        "max-size": (max_size_mix(frames, seed=3), ["--profile", "generic"]),
    }[mix]
    _raw, pcap = write_capture(records, tmp_path / mix)
    data = assert_same_report([str(pcap), *options], tmp_path, monkeypatch)
    assert fed.reports == 1 and fed.python_items < len(records) // 5
    if mix == "max-size":
        assert len(data["parameters"]) == MAX_SERIES and data["parameters_dropped"]
    if mix == "plant":
        assert any(parameter["unit"] for parameter in data["parameters"])


@pytest.mark.parametrize("seed", range(6))
def test_poll_timings_in_the_store_as_in_python(seed: int) -> None:
    """pollcycle's period, jitter and skipped cycles of the compiled store's intervals (its tallies, _timing)
    as by the Python PollCycle: random intervals, skipped cycles, times going back, and intervals of days
    whose variance a double does not hold exactly."""
    rng = random.Random(seed)
    python, compiled = PollCycle(), PollCycle(new_store())
    ns = 1_700_000_000 * 10**9
    for number in range(1, 3000):
        slave = rng.randrange(1, 6)
        frame = Frame(0, rtu(f"{slave:02X} 03 0000 000{slave}"), None, Kind.REQUEST, slave, 3, 0, 0, number=number,
                      unanswered=rng.random() < 0.1)
        decode_frame(frame)
        step = rng.choice([10**7, 10**7 + rng.randrange(-10**6, 10**6), 3 * 10**7, -5 * 10**6])
        if seed % 2 and slave == 5:
            step = rng.choice([86_400 * 10**9, 3 * 86_400 * 10**9 // 2 - 10**9, -86_400 * 10**9 // 3])
        ns += step
        frame.time = Stamp(ns)
        for cycle in (python, compiled):
            cycle.add_request(frame)
    assert compiled.report() == python.report() and compiled.report(2) == python.report(2)


@pytest.mark.parametrize("name", ["atv71_commissioning", "p38_protection", "sel749m_polling"])
def test_standard_input_same_report(name: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, fed: Fed) -> None:
    """A pcap on standard input (read once): profile auto chooses while the engine counts the slaves
    already settled, the parameter history holds and reads again the frames named before."""
    stdin = (CAPTURES / f"{name}.pcap").read_bytes()
    assert_same_report(["-", "--profile", "auto"], tmp_path, monkeypatch, stdin=stdin)
    assert fed.reports == 1


def test_readable_again_drawn_by_the_engine_as_in_python(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                        fed: Fed) -> None:
    """HSP read for 12 s, protected (16#8000 in a two-register read, VW3 A3 303 p.38) twice, then readable
    again for 12 s: the page the engine feeds (the polls it counts, the story's frames the Python stages
    hand it) equals the Python stages' one, with the trend's marks at the same times."""
    request = rtu("0C 03 0C 20 00 02")  # HSP, LSP
    readable, protected = rtu("0C 03 04 01 F4 00 00"), rtu("0C 03 04 80 00 00 00")
    answers = [readable] * 40 + [protected] * 2 + [readable] * 40
    records = []
    for k, answer in enumerate(answers):
        records += [(request, k * 300_000_000), (answer, k * 300_000_000 + 12_000_000)]
    capture = tmp_path / "hsp_again.pcap"
    write_pcap(capture, records)
    data = assert_same_report([str(capture), "--profile", "atv71"], tmp_path, monkeypatch)
    hsp = next(parameter for parameter in data["parameters"] if parameter["code"] == "HSP")
    assert hsp["marks"] == [[12.012, "protected"], [12.612, "readable again (protected before)"]]
    assert fed.reports == 1 and fed.python_items < len(records) // 10
