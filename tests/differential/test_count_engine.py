"""-c N with the compiled engine covers the first N frames only, as VW3_PURE_PYTHON=1 (and tshark -c):
--stats' bus timing (load, gaps, turnaround) and device profiles must not see the frames after the Nth,
which the engine's frames path (accel/framespath.py) frames many transactions at a time: it is given
only the bytes that cannot hold the Nth frame, the Python stages the rest (framespath._Counted;
test_count_cut.py)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from dissector.accel import fastsummary

ROOT = Path(__file__).resolve().parents[2]
CAPTURE = str(ROOT / "captures" / "sel749m_polling.pcap")
ENGINES = ["engine", "pure"]


def run(engine: str, *args: str, stdin: bytes | None = None) -> bytes:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    env.pop("VW3_PURE_PYTHON", None)
    if engine == "pure":
        env["VW3_PURE_PYTHON"] = "1"
    done = subprocess.run([sys.executable, "-m", "dissector", *args], env=env, input=stdin,
                          capture_output=True, check=True)
    return done.stdout


@pytest.mark.parametrize("engine", ENGINES)
def test_stats_json_of_ten_frames(engine: str) -> None:
    assert engine == "pure" or fastsummary.built(), "the compiled engine must be built"
    stats = json.loads(run(engine, CAPTURE, "-c", "10", "--stats", "--json"))
    assert stats["frames"] == 10
    bus = stats["bus"]
    assert bus["span"] == 0.663696
    assert bus["load"] == 0.166602
    assert bus["gaps"] == {"count": 9, "min": 0.003245, "median": 0.00712, "p95": 0.25448, "max": 0.254481}
    assert bus["turnaround"] == {"count": 4, "median": 0.131575, "p95": 0.25448, "max": 0.254481}
    assert [(p["slave"], p["profile"]) for p in stats["profiles"]] == [(1, "generic")]


@pytest.mark.parametrize("engine", ENGINES)
def test_stats_text_of_ten_frames(engine: str) -> None:
    assert engine == "pure" or fastsummary.built(), "the compiled engine must be built"
    lines = run(engine, CAPTURE, "-c", "10", "--stats").decode().splitlines()
    profiles = lines.index("Device profiles")
    assert lines[profiles + 3 : profiles + 5] == ["    1  generic  no evidence of a device: spec semantics only", ""]
    assert "inter-frame gaps: 9, 0 below t3.5; min 3.245 median 7.120 p95 254.480 max 254.481 ms" in lines
    assert "  2-5 ms: 2, 5-10 ms: 5, 200-500 ms: 2" in lines
    assert "master turnaround (answer end to next request, ms): median 131.575 p95 254.480 max 254.481 (4)" in lines
    assert "    1          5       10.8    13.0    13.0                 991.6                0" in lines


OPTIONS = [["--stats"], ["--stats", "--json"], ["--profile", "auto", "--stats"], ["-t", "d", "--stats"],
           ["-Y", "slave == 1", "--stats"], ["-V"], ["--json"], []]


@pytest.mark.parametrize("count", ["1", "10", "33", "100"])
@pytest.mark.parametrize("options", OPTIONS, ids=" ".join)
def test_engine_equals_pure(count: str, options: list[str]) -> None:
    assert fastsummary.built(), "the compiled engine must be built: a missing one fails here, it is not skipped"
    args = [CAPTURE, "-c", count, *options]
    assert run("engine", *args) == run("pure", *args)


def test_stdin_report_and_pcap(tmp_path: Path) -> None:
    assert fastsummary.built(), "the compiled engine must be built: a missing one fails here, it is not skipped"
    data = Path(CAPTURE).read_bytes()
    assert run("engine", "-", "-c", "10", "--stats", stdin=data) == run("pure", "-", "-c", "10", "--stats", stdin=data)
    for engine in ENGINES:
        run(engine, CAPTURE, "-c", "10", "--stats", "--report", str(tmp_path / f"{engine}.html"),
            "-w", str(tmp_path / f"{engine}.pcap"))
    assert (tmp_path / "engine.html").read_bytes() == (tmp_path / "pure.html").read_bytes()
    assert (tmp_path / "engine.pcap").read_bytes() == (tmp_path / "pure.pcap").read_bytes()
