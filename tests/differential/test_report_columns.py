"""--report's pixel columns kept in C (dissector/accel/_columns.h) against the Python `Columns` of
render/report/collect.py, the reference (VW3_PURE_PYTHON=1): the page byte for byte on pcap and pcapng
captures cut at random, damaged, with profile changes (profile auto choosing a device after values were
read), protections (16#8000 and exceptions the profile explains), exceptions and long polls whose
series are merged column into column; and the two column stores point for point on random points.
The extension must be built: it is not skipped."""
from __future__ import annotations

import io
import json
import random
import re
from pathlib import Path

import pytest

from helpers import use_engine

from dissector.accel._summary import Columns as CompiledColumns
from dissector.app.cli import Environment, run
from dissector.pipeline import dissect
from dissector.render.report.collect import COLUMNS, Columns, ReportCollector, drawn
from dissector.render.report.reading import remap
from dissector.sources.reader import open_source
from dissector.sim.simulate import generate_session
from test_timed_summary import cut_records, frames_of, write_pcap, write_pcapng

ROOT = Path(__file__).resolve().parents[2]
CAPTURES = ROOT / "captures"


def report(argv: list[str], page: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, stdin: bytes = b"") -> str:
    use_engine(monkeypatch, pure)
    stdout, stderr = io.StringIO(), io.StringIO()
    assert run([*argv, "--report", str(page)], Environment(io.BytesIO(stdin), stdout, stderr, False, False)) == 0
    return page.read_text(encoding="utf-8") + stdout.getvalue() + stderr.getvalue()


def assert_same_report(argv: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch, stdin: bytes = b"") -> dict:
    compiled = report(argv, tmp_path / "compiled.html", monkeypatch, pure=False, stdin=stdin)
    reference = report(argv, tmp_path / "reference.html", monkeypatch, pure=True, stdin=stdin)
    assert compiled == reference
    found = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', compiled, re.S)
    assert found is not None
    return json.loads(found.group(1))


@pytest.mark.parametrize("seed", range(6))
def test_random_damaged_captures_same_report(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(seed)
    how = ["frame", "bursts", "untimed"][seed % 3]
    records = cut_records(rng, frames_of(seed + 500, damaged=0.0 if seed == 0 else 0.07), how)
    capture = tmp_path / ("bus.pcapng" if seed % 2 else "bus.pcap")
    (write_pcapng if seed % 2 else write_pcap)(capture, records)
    options = [[], ["--profile", "atv71"], ["--profile", "auto"], ["--profile", "generic"]][seed % 4]
    assert_same_report([str(capture), *options], tmp_path, monkeypatch)


@pytest.mark.parametrize("profile", ["auto", "atv71"])
def test_shipped_captures_one_after_another_same_report(profile: str, tmp_path: Path,
                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    """Protections (p38: 16#8000, exceptions the profile explains), exceptions, noise, a commissioning
    whose device profile auto chooses after reading, then a polling bus: one report over them all."""
    names = ["atv71_commissioning", "p38_protection", "noisy_bus", "sel749m_polling"]
    data = assert_same_report([str(CAPTURES / f"{name}.pcap") for name in names] + ["--profile", profile],
                              tmp_path, monkeypatch)
    assert data["event_counts"]["protection"] > 0 and data["event_counts"]["exception"] > 0


def test_profile_chosen_after_values_were_read_same_report(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Standard input (one pass): the drive's reads and writes come before its device identification,
    then a polling bus of another make: profile auto chooses each device after values of it were kept,
    and the series kept are named again (ReportCollector.renamed)."""
    items = list(dissect(open_source(str(CAPTURES / "atv71_commissioning.bin"))))
    raws = [bytes(item.raw) for item in items]
    stream = b"".join(raws[18:60] + raws[:2] + raws[2:]) + (CAPTURES / "sel749m_polling.bin").read_bytes()
    renamed: list[int] = []
    original = ReportCollector.renamed

    def spy(self: ReportCollector, slave: int) -> None:
        renamed.append(slave)
        original(self, slave)

    monkeypatch.setattr(ReportCollector, "renamed", spy)
    data = assert_same_report(["-", "--profile", "auto"], tmp_path, monkeypatch, stdin=stream)
    assert renamed and data["parameters"]


def test_long_poll_merges_columns_same_report(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Thousands of values of each parameter over a long span: columns doubled and merged many times."""
    records = generate_session(20_000, seed=3)
    capture = tmp_path / "polling.pcap"
    write_pcap(capture, [(data, round(time * 1e9)) for data, time in records])
    data = assert_same_report([str(capture)], tmp_path, monkeypatch)
    counts = [parameter["values"] for parameter in data["parameters"]]
    assert max(counts) > 2 * COLUMNS


def compare(python: Columns, compiled: CompiledColumns, origin: float) -> None:
    assert len(python) == len(compiled)
    assert python.values() == compiled.values()
    # The compiled columns' points are the Python Columns.points of their doubles (drawn()'s fallback, for a
    # value json.dumps refuses)
    assert drawn(compiled, origin, 6) == drawn(python, origin, 6)
    for digits in (6, 0):  # as the page writes them (collect.py drawn), written by the compiled columns
        # themselves as JSON (collect.py _parameter_json), with and without a scale (health.py)
        for scale, places in ((0.0, 0), (1000.0, 3)):
            assert compiled.drawn_json(origin, digits, scale, places) == tuple(
                json.dumps(values, separators=(",", ":")) for values in drawn(python, origin, digits, scale, places))
    assert python.levels() == compiled.levels()


@pytest.mark.parametrize("seed", range(20))
def test_columns_point_for_point(seed: int) -> None:
    """Random points (ties, repeated x, negative and equal values, steps), closes, merges and remaps."""
    rng = random.Random(seed)
    python, compiled = Columns(), CompiledColumns()
    origin, width, x = 1_700_000_000.123, 1e-3, 1_700_000_000.123
    values = [rng.choice([0.0, -0.0, 1.5, -3.0, 7.0, 1e-7, -2.5e-5, 3e9 + 0.25, 2.0**60]) for _ in range(5)]
    for _step in range(rng.randrange(1, 4000)):
        x += rng.choice([0.0, 1e-4, 1e-3, 0.01, 0.5])
        y = rng.choice(values) if rng.random() < 0.5 else round(rng.uniform(-100, 100), rng.randrange(9))
        while x - origin >= 2 * COLUMNS * width:
            width *= 2
            python.close(), compiled.close()
            if rng.random() < 0.5:
                python.compact(origin, width), compiled.compact(origin, width)
        col = max(0, int((x - origin) / width))
        python.add(col, x, y), compiled.add(col, x, y)
        if rng.random() < 0.002:
            compare(python, compiled, origin)
    compare(python, compiled, origin)
    for store in (python, compiled):
        remap(store, lambda y: float(-y if y > 50 else y * 0.1))
    compare(python, compiled, origin)
    python.close(), compiled.close()
    python.compact(origin, width * 4), compiled.compact(origin, width * 4)
    compare(python, compiled, origin)
