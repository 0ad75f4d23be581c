"""Time and size of `--report` on the benchmark sessions, against `--stats` and the summary, one run.

    python3 bench/report.py [--frames 100000,400000] [--repeat 2] [--mix NAME]
    python3 bench/report.py --instructions [--against TREE] [--frames 20000]

For each mix of bench/throughput.py (polling, plant, max-size; the same generators and the profiles
their users would give) and each size, it writes the session as a time-stamped pcap (so the report
has response times, a time axis and a poll cycle) and times, best of --repeat interleaved rounds,
the summary, `--stats` and `--report` (and the latter two's time over the summary's: issue 28 wants
them within 2x and 3x), with peak RSS of the report run and the size of the page.
The page's size is bounded by construction (at most COLUMNS pixel columns of 4 points for at most
MAX_SERIES parameters, MAX_EVENTS listed events), so a size that stays flat from one frame count to
four times as many is what a 1 GB capture gives too.
With --instructions it counts machine instructions instead (valgrind's callgrind, one run each, which a
shared machine's load does not move), and with --against TREE also those of another checkout (built:
`python3 setup.py -q build_ext --inplace` there) on the same files, whose outputs must be the same bytes.
"""
from __future__ import annotations

import argparse
import os
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


def callgrind(command: list[str], tree: Path, output: Path) -> int:
    """Machine instructions of one run of `command` from the checkout `tree`, stdout to `output`."""
    with output.open("wb") as sink:
        probe = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", *command],
                               cwd=tree, env={**os.environ, "PYTHONPATH": str(tree), "PYTHONHASHSEED": "0"},
                               stdout=sink, stderr=subprocess.PIPE, text=True)
    totals = [line.split()[-1] for line in probe.stderr.splitlines() if "Collected :" in line]
    if probe.returncode != 0 or not totals:
        sys.exit(f"failed in {tree}: {' '.join(command)}\n{probe.stderr[-2000:]}")
    return int(totals[0])


def counted(mix, frames: int, trees: list[Path], out: Path) -> None:
    """The instructions of the summary, --stats and --report in each tree, the first's ratio to each other's."""
    _raw, pcap = write_capture(mix.records(frames), out / f"{mix.name}-{frames}")
    for name in ("summary", "--stats", "--report"):
        counts, outputs = [], set()
        for k, tree in enumerate(trees):
            output, page = out / f"output-{k}.txt", out / f"{mix.name}-{frames}-{k}.html"
            extra = {"summary": [], "--stats": ["--stats"], "--report": ["--report", str(page)]}[name]
            counts.append(callgrind(VW3 + [str(pcap), *mix.options, *extra], tree, output))
            outputs.add((page if name == "--report" else output).read_bytes())
        ratios = "".join(f" {counts[0] / count:.4f}x |" for count in counts[1:])
        same = "" if len(trees) == 1 else " same |" if len(outputs) == 1 else " DIFFER |"
        figures = " | ".join(f"{count:,}" for count in counts)
        print(f"| {mix.name} | {frames:,} | {name} | {figures} |{ratios}{same}", flush=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", default="100000,400000", help="frame counts, comma-separated")
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--mix", action="append", choices=[mix.name for mix in MIXES])
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    parser.add_argument("--instructions", action="store_true", help="callgrind instruction counts, one run each")
    parser.add_argument("--against", type=Path, action="append", default=[], help="another checkout to count too")
    args = parser.parse_args()
    args.out = args.out.resolve()
    args.out.mkdir(parents=True, exist_ok=True)
    trees = [ROOT, *(tree.resolve() for tree in args.against)]
    for tree in trees:
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree / "dissector")], check=True)
    sizes = [int(text) for text in args.frames.split(",")]
    if args.instructions:
        heads = [f"{tree} instructions" for tree in trees] + [f"{trees[0].name} / {tree.name}" for tree in trees[1:]]
        print("| mix | frames | run | " + " | ".join(heads) + " |" + (" outputs |" if len(trees) > 1 else ""))
        for mix in (mix for mix in MIXES if not args.mix or mix.name in args.mix):
            for frames in sizes:
                counted(mix, frames, trees, args.out)
        return 0
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
