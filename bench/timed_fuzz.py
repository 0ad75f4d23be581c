"""Differential campaign of the compiled path for timed captures against the Python stages.

    python3 bench/timed_fuzz.py FIRST_SEED LAST_SEED [--stats]

Per seed, a random bus (bench/noise_accuracy.py sessions: every public code, broadcasts, unanswered
requests, answers from 2 ms to past the 1 s timeout), damaged at a random rate, with glitch bytes after
some frames, cut into pcap or pcapng records (one frame a record, bursts cut anywhere with some late
inside a frame, or some records untimed: tests/differential/test_timed_summary.py cut_records), then
decoded by `vw3-decode` with a random option among the time columns, --timeout, --baud, -n, a profile,
--json, -V, --stats, -x and -T fields, with the compiled path and with VW3_PURE_PYTHON=1: stdout and
stderr must be equal (`--stats`: only --stats, --stats --json and --stats with a time column, --timeout
or --baud, the outputs the engine counts). Prints each difference (seed, cut, options, first differing lines) and the count.
tests/differential/test_timed_summary.py and test_timed_outputs.py hold bounded versions of this.
"""
from __future__ import annotations

import argparse
import io
import os
import random
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "tests" / "support"), str(ROOT / "tests" / "differential"), str(ROOT / "bench")]

from dissector.app.cli import Environment, run  # noqa: E402
import test_timed_summary as timed  # noqa: E402

OUTPUTS = [["--json"], ["-V"], ["--stats"], ["-x"], ["-T", "fields", "-e", "frame", "-e", "time_delta", "-e", "registers"],
           ["--stats", "--json"]]


def capture_of(seed: int, folder: Path, rng: random.Random | None = None) -> tuple[Path, list[int], str]:
    """The seed's capture, its records' lengths, and how its records were cut (rng: the seed's, to go on with)."""
    rng = rng or random.Random(seed)
    frames = timed.frames_of(seed, damaged=rng.choice([0, 0.02, 0.1, 0.3]))
    if rng.random() < 0.5:  # glitch bytes after frames
        frames = [(frame + bytes([rng.choice([0, 0xFE, 0xFF])]) if rng.random() < 0.3 else frame, ns)
                  for frame, ns in frames]
    how = rng.choice(["frame", "bursts", "untimed"])
    records = timed.cut_records(rng, frames, how)
    capture = folder / f"bus{seed}.pcap"
    if rng.random() < 0.3:
        capture = capture.with_suffix(".pcapng")
        timed.write_pcapng(capture, records)
        how += " pcapng"
    else:
        nano = rng.random() < 0.5
        timed.write_pcap(capture, records, nano=nano)
        how += " pcap-ns" if nano else " pcap-us"
    return capture, [len(data) for data, _ns in records], how


def decode(argv: list[str], pure: bool) -> str:
    if pure:
        os.environ["VW3_PURE_PYTHON"] = "1"
    else:
        os.environ.pop("VW3_PURE_PYTHON", None)
    stdout, stderr = io.StringIO(), io.StringIO()
    status = run(argv, Environment(io.BytesIO(), stdout, stderr, False, False))
    return f"{status}\n{stdout.getvalue()}{stderr.getvalue()}"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("first", type=int, metavar="FIRST_SEED")
    parser.add_argument("last", type=int, metavar="LAST_SEED", help="the last seed run (inclusive)")
    parser.add_argument("--stats", action="store_true", help="compare only the outputs the engine counts")
    arguments = parser.parse_args()
    first, last, stats_only = arguments.first, arguments.last, arguments.stats
    differences = 0
    with tempfile.TemporaryDirectory() as folder:
        for seed in range(first, last + 1):
            rng = random.Random(seed)
            capture, _lengths, how = capture_of(seed, Path(folder), rng)
            options = rng.choice(timed.OPTIONS + OUTPUTS)
            if stats_only:
                options = [*rng.choice([[], ["--json"]]), "--stats", *rng.choice(timed.OPTIONS)]
            argv = [str(capture), *options]
            fast, pure = decode(argv, False), decode(argv, True)
            if fast != pure:
                differences += 1
                print("difference: seed", seed, how, options, capture.suffix, flush=True)
                for fast_line, pure_line in zip(fast.splitlines(), pure.splitlines()):
                    if fast_line != pure_line:
                        print("  compiled:", fast_line[:200])
                        print("  Python:  ", pure_line[:200])
                        break
    print(f"seeds {first}..{last}: {differences} difference(s)")
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())
