"""Differential campaign of the Wireshark Lua plugin (lua/vw3.lua under tshark -2) against `vw3-decode --json`
on random timed captures.

    python3 bench/lua_timed_fuzz.py FIRST_SEED LAST_SEED [--plugin PATH]

Per seed, the random bus of bench/timed_fuzz.py (bench/noise_accuracy.py sessions: every public code,
broadcasts, unanswered requests, answers from 2 ms to past the 1 s timeout), damaged at a random rate, with
glitch bytes after some frames, cut into pcap (us or ns) or pcapng records (one frame a record, bursts cut
anywhere with some late inside a frame, or some records untimed: tests/differential/test_timed_summary.py
cut_records), decoded by both with a random line speed (--baud, the plugin's `baud` preference) and response
timeout (--timeout, `timeout_ms`), then compared frame by frame (tests/support/lua_compare.py: every field,
warning and note, response times). Prints each difference (seed, how the records were cut, the options, the
first differing frame and field) and the count. tests/integration/test_lua_timed_parity.py holds a bounded
version of this. --plugin: another build of the plugin (a baseline) than lua/vw3.lua.
"""
from __future__ import annotations

import argparse
import json
import random
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "tests" / "support"), str(ROOT / "tests" / "differential"), str(ROOT / "bench")]

import lua_harness  # noqa: E402
import test_timed_summary as timed  # noqa: E402
from lua_compare import compare  # noqa: E402
from timed_fuzz import capture_of  # noqa: E402
from lua_harness import lua_items, place_items, PythonItem  # noqa: E402

BAUDS = [None, 9600, 19200, 115200]
TIMEOUTS_MS = [None, 30, 500]  # (None: both sides' default, 1000 ms)


def options_of(seed: int) -> tuple[list[str], list[str]]:
    """(vw3-decode's options, the plugin's preferences) of the seed: a line speed and a timeout, or none."""
    rng = random.Random(seed * 31 + 7)
    cli: list[str] = []
    prefs: list[str] = []
    baud, timeout_ms = rng.choice(BAUDS), rng.choice(TIMEOUTS_MS)
    if baud is not None:
        cli += ["--baud", str(baud)]
        prefs += ["-o", f"vw3.baud:{baud}"]
    if timeout_ms is not None:
        cli += ["--timeout", str(timeout_ms / 1000)]
        prefs += ["-o", f"vw3.timeout_ms:{timeout_ms}"]
    return cli, prefs


def python_items(capture: Path, lengths: list[int], options: list[str]) -> list[PythonItem]:
    """vw3-decode FILE --json (the file read twice, as the plugin shows it under tshark -2)."""
    command = [sys.executable, "-m", "dissector", str(capture), "--json", *options]
    run = subprocess.run(command, capture_output=True, cwd=ROOT, timeout=900)
    if run.returncode != 0:
        raise AssertionError(f"{' '.join(command)} failed: {run.stderr.decode(errors='replace')[-2000:]}")
    return place_items([json.loads(line) for line in run.stdout.decode().splitlines() if line.strip()], lengths)


def differences_of(seed: int, folder: Path) -> tuple[str, list[str], list[str]]:
    """How the seed's records were cut, its options, and every difference between the two sides."""
    capture, lengths, how = capture_of(seed, folder)
    cli, prefs = options_of(seed)
    python = python_items(capture, lengths, cli)
    lua, _record_experts, _stderr = lua_items(capture, *prefs)
    return how, cli, compare(python, lua)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("first", type=int, metavar="FIRST_SEED")
    parser.add_argument("last", type=int, metavar="LAST_SEED", help="the last seed run (inclusive)")
    parser.add_argument("--plugin", type=Path, help="another build of the plugin than lua/vw3.lua")
    arguments = parser.parse_args()
    first, last = arguments.first, arguments.last
    if arguments.plugin:
        lua_harness.PLUGIN = arguments.plugin.resolve()
    differing = 0
    with tempfile.TemporaryDirectory() as folder:
        for seed in range(first, last + 1):
            how, cli, differences = differences_of(seed, Path(folder))
            if differences:
                differing += 1
                print(f"difference: seed {seed} ({how}, {' '.join(cli) or 'defaults'}): {len(differences)} field(s);"
                      f" first: {differences[0][:300]}", flush=True)
    print(f"seeds {first}..{last}: {differing} seed(s) with differences")
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
