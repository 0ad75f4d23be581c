"""Time and size of `--report` on the benchmark sessions, against `--stats` and the summary, one run.

    python3 bench/report.py [--frames 100000,400000] [--repeat 2] [--mix NAME]

For each mix of bench/throughput.py (polling, plant, max-size; the same generators and the profiles
their users would give) and each size, it writes the session as a time-stamped pcap (so the report
has response times, a time axis and a poll cycle) and times, best of --repeat interleaved rounds,
the summary, `--stats` and `--report` (and the latter two's time over the summary's: issue 28 wants
them within 2x and 3x), with peak RSS of the report run and the size of the page.
The page's size is bounded by construction (at most COLUMNS pixel columns of 4 points for at most
MAX_SERIES parameters, MAX_EVENTS listed events), so a size that stays flat from one frame count to
four times as many is what a 1 GB capture gives too.
"""
from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from throughput import MIXES, VW3, run_once  # noqa: E402

from dissector.sim.simulate import write_capture  # noqa: E402


def measure(mix, frames: int, repeat: int, out: Path) -> dict[str, float]:
    records = mix.records(frames)
    _raw, pcap = write_capture(records, out / f"{mix.name}-{frames}")
    base = VW3 + [str(pcap), *mix.options]
    page = out / f"{mix.name}-{frames}.html"
    runs = {"summary": base, "--stats": base + ["--stats"], "--report": base + ["--report", str(page)]}
    best = {name: float("inf") for name in runs}
    rss = 0.0
    for _round in range(repeat):
        for name, command in runs.items():
            seconds, peak = run_once(command, out / "output.txt")
            best[name] = min(best[name], seconds)
            if name == "--report":
                rss = max(rss, peak)
    return {
        "frames": float(len(records)),
        "pcap_mb": pcap.stat().st_size / 1e6,
        **best,
        "report_mb": page.stat().st_size / 1e6,
        "rss_mb": rss,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", default="100000,400000", help="frame counts, comma-separated")
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--mix", action="append", choices=[mix.name for mix in MIXES])
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "dissector")], check=True)
    sizes = [int(text) for text in args.frames.split(",")]
    print("| mix | frames | pcap MB | summary s | `--stats` s | `--report` s | stats / summary | "
          "report / summary | report MB | peak RSS MB |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for mix in MIXES:
        if args.mix and mix.name not in args.mix:
            continue
        for frames in sizes:
            r = measure(mix, frames, args.repeat, args.out)
            print(
                f"| {mix.name} | {r['frames']:,.0f} | {r['pcap_mb']:.1f} | {r['summary']:.2f} | {r['--stats']:.2f} "
                f"| {r['--report']:.2f} | {r['--stats'] / r['summary']:.2f}x | {r['--report'] / r['summary']:.2f}x "
                f"| {r['report_mb']:.2f} "
                f"| {r['rss_mb']:.0f} |",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
