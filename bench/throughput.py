"""Throughput of vw3-decode against tshark on the same frames, three traffic mixes, one run.

    python3 bench/throughput.py [--frames 100000] [--repeat 3] [--mix NAME] [--memory] [--gigabyte]
    python3 bench/throughput.py --against TREE [--frames 20000] [--mix NAME]

Mixes (each generated reproducibly and written as a USER0 pcap, which both tools read: vw3-decode and
tshark's mbrtu; also written raw, whose vw3-decode summary is printed beside as the raw-stream figure):
- polling: the cyclic ATV71 I/O scan with SEL-749M polls (dissector.sim.simulate.generate_session);
- plant: 4 drives, 2 relays polled for 40-register blocks, a coil/input module (FC1/2/5/15), an energy
  meter (FC4), changing values, ~1 % exceptions (dissector.sim.mixes.plant_mix), decoded with the
  profiles its user would give (relays sel749m, module and meter generic);
- max-size: every public function code at random quantities up to the spec limits, random slaves
  (dissector.sim.mixes.max_size_mix), decoded with the generic profile (and timed with the default
  ATV71 one apart).
For each mix it times, best of --repeat interleaved rounds, on the same pcap file: vw3-decode's summary,
--json, -V and --stats, and tshark's summary, -T json and -V with CRC verification on; and vw3-decode's
summary of the raw stream of the same frames; peak RSS of every vw3-decode
run comes from the same runs (timed from a small probe process). Sub-second commands run SHORT_RUNS
times a round. The package is byte-compiled first, as pip does. It prints the seconds of every run, then one table of ratios from
this one run. With --memory, peak RSS on each mix repeated tenfold; with --gigabyte, also at 1 GB.
With --against TREE, every vw3-decode command runs in the same rounds from another checkout too (built:
`python3 setup.py -q build_ext --inplace` there), on the same files, and its outputs must be the same
bytes: the table then gives this tree's time over TREE's per command (a change to the engine, measured
against the commit before it in one run, so that the machine's load hits both alike).
"""
from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from dissector.sim.mixes import PLANT_PROFILES, max_size_mix, plant_mix  # noqa: E402
from dissector.sim.simulate import Record, generate_session, write_capture  # noqa: E402

TSHARK_OPTIONS = [
    "-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""',
    "-o", "mbrtu.crc_verification:TRUE",
]
VW3 = [sys.executable, "-m", "dissector"]
SHORT_RUNS = 4


@dataclass(frozen=True)
class Mix:
    name: str
    records: Callable[[int], list[Record]]
    options: list[str]  # vw3-decode options a user of that bus gives (profiles)


MIXES = [
    Mix("polling", lambda frames: generate_session(frames // 2 + frames // 20, seed=1)[:frames], []),
    Mix("plant", lambda frames: plant_mix(frames, seed=1),
        [option for profile in PLANT_PROFILES for option in ("--profile", profile)]),
    # Random slaves of no known make: decoded as a user of such a bus would, with the generic profile
    # (the default ATV71 profile would add "not supported by the VW3 A3 303" to most requests; that
    # run is timed too, apart from the table).
    Mix("max-size", lambda frames: max_size_mix(frames, seed=1), ["--profile", "generic"]),
]


# Runs a command from a small process that times it and reads its peak RSS: Linux counts the memory
# of the process a child was forked from before exec in the child's ru_maxrss, so a command started
# from this script (which holds the mix's records) would report this script's size.
PROBE = """
import resource, subprocess, sys, time
with open(sys.argv[1], "wb") as sink:
    start = time.perf_counter()
    result = subprocess.run(sys.argv[2:], stdout=sink, stderr=subprocess.PIPE)
    elapsed = time.perf_counter() - start
sys.stderr.buffer.write(result.stderr[-2000:])
print(result.returncode, elapsed, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
"""


def run_once(command: list[str], output: Path, cwd: Path = ROOT) -> tuple[float, float]:
    """Wall time and peak RSS (MB) of one run of `command` in the checkout `cwd`, stdout to `output`."""
    probe = subprocess.run([sys.executable, "-c", PROBE, str(output), *command], capture_output=True, cwd=cwd)
    returncode, elapsed, rss = probe.stdout.split()
    if probe.returncode != 0 or int(returncode) != 0:
        sys.exit(f"failed ({returncode.decode()}): {' '.join(command)}\n{probe.stderr.decode()[-2000:]}")
    return float(elapsed), int(rss) / 1024


def timed(command: list[str], output: Path, repeat: int) -> float:
    """Best wall time of `repeat` runs, stdout to `output` (bench/lua_throughput.py uses it too)."""
    return min(run_once(command, output)[0] for _ in range(repeat))


def peak_rss_mb(command: list[str]) -> float:
    return run_once(command, Path(os.devnull))[1]


def against_runs(mix: Mix, frames: int, repeat: int, out: Path, tree: Path) -> dict[str, tuple[float, float]]:
    """--against: best seconds of each vw3-decode command of `measure` from this tree and from `tree`, in
    interleaved rounds, as {command: (this tree's, tree's)}; a difference of outputs stops the run."""
    records = mix.records(frames)
    raw, pcap = write_capture(records, out / mix.name)
    print(f"{mix.name}: {len(records)} frames", flush=True)
    vw3 = VW3 + [str(pcap), *mix.options]
    runs = {"summary": vw3, "summary raw": VW3 + [str(raw), *mix.options], "--json": vw3 + ["--json"],
            "-V": vw3 + ["-V"], "--stats": vw3 + ["--stats"]}
    best = {(name, cwd): float("inf") for name in runs for cwd in (ROOT, tree)}
    for _round in range(repeat):
        for name, command in runs.items():
            outputs = []
            for cwd in (ROOT, tree):
                outputs.append(out / f"output-{len(outputs)}.txt")
                for _ in range(SHORT_RUNS if best[name, cwd] < 1.0 else 1):
                    best[name, cwd] = min(best[name, cwd], run_once(command, outputs[-1], cwd)[0])
            if outputs[0].read_bytes() != outputs[1].read_bytes():
                sys.exit(f"{mix.name} {name}: the outputs of {ROOT} and {tree} differ")
    result = {name: (best[name, ROOT], best[name, tree]) for name in runs}
    for name, (ours, theirs) in result.items():
        print(f"  {name:<16} {ours:8.3f} s  against {theirs:8.3f} s  {ours / theirs:6.3f}", flush=True)
    return result


def measure(mix: Mix, frames: int, repeat: int, out: Path, tshark: str) -> dict[str, tuple[float, float]]:
    records = mix.records(frames)
    raw, pcap = write_capture(records, out / mix.name)
    print(f"{mix.name}: {len(records)} frames, {raw.stat().st_size:,} bytes raw", flush=True)
    vw3 = VW3 + [str(pcap), *mix.options]
    runs = {
        "summary": vw3,
        "summary raw": VW3 + [str(raw), *mix.options],
        "--json": vw3 + ["--json"],
        "-V": vw3 + ["-V"],
        "--stats": vw3 + ["--stats"],
        "tshark summary": [tshark, "-r", str(pcap), *TSHARK_OPTIONS],
        "tshark -T json": [tshark, "-r", str(pcap), "-T", "json", *TSHARK_OPTIONS],
        "tshark -V": [tshark, "-r", str(pcap), "-V", *TSHARK_OPTIONS],
    }
    if mix.name == "polling":
        runs["summary -n"] = vw3 + ["-n"]
    if mix.name == "max-size":
        runs["summary atv71"] = VW3 + [str(pcap)]
    # Rounds interleave the commands, so a slow spell of a shared machine hits them all alike; a 30 ms
    # hiccup would move the ratio of two 0.3 s runs by 10%, hence several runs of the short ones.
    best = {name: (float("inf"), 0.0) for name in runs}
    for _round in range(repeat):
        for name, command in runs.items():
            for _ in range(SHORT_RUNS if best[name][0] < 1.0 else 1):
                seconds, rss = run_once(command, out / "output.txt")
                best[name] = (min(best[name][0], seconds), max(best[name][1], rss))
    for name, (seconds, rss) in best.items():
        rss_text = f"{rss:6.1f} MB" if not name.startswith("tshark") else ""
        print(f"  {name:<16} {seconds:8.3f} s {len(records) / seconds:>11,.0f} frames/s  {rss_text}")
    return {**best, "frames": (float(len(records)), 0.0)}


def ratio_table(results: dict[str, dict[str, tuple[float, float]]]) -> str:
    lines = [
        "| mix | frames | summary vs tshark | (raw stream vs tshark) | `--json` vs `tshark -T json` "
        "| `-V` vs `tshark -V` | `--stats` time / summary time | peak RSS |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for name, best in results.items():
        seconds = {run: value[0] for run, value in best.items()}
        rss = max(value[1] for run, value in best.items() if not run.startswith("tshark"))
        lines.append(
            f"| {name} | {int(seconds['frames']):,} "
            f"| {seconds['tshark summary'] / seconds['summary']:.2f}x "
            f"| ({seconds['tshark summary'] / seconds['summary raw']:.2f}x) "
            f"| {seconds['tshark -T json'] / seconds['--json']:.2f}x "
            f"| {seconds['tshark -V'] / seconds['-V']:.2f}x "
            f"| {seconds['--stats'] / seconds['summary']:.2f} "
            f"| {rss:.1f} MB |"
        )
    return "\n".join(lines)


def memory_runs(mix: Mix, out: Path, gigabyte: bool) -> None:
    raw = out / f"{mix.name}.bin"
    data = raw.read_bytes()
    sizes = [("x10", 10)] + ([("1 GB", -(-10**9 // len(data)))] if gigabyte else [])
    for label, times in sizes:
        big = out / f"{mix.name}-big.bin"
        with big.open("wb") as sink:
            for _ in range(times):
                sink.write(data)
        vw3 = VW3 + [str(big), *mix.options]
        start = time.perf_counter()
        summary_mb = peak_rss_mb(vw3)
        seconds = time.perf_counter() - start
        extra = ""
        if label == "x10":
            extra = (f", --json {peak_rss_mb(vw3 + ['--json']):.1f} MB, -V {peak_rss_mb(vw3 + ['-V']):.1f} MB, "
                     f"--stats {peak_rss_mb(vw3 + ['--stats']):.1f} MB")
        print(f"  {mix.name} {label} ({big.stat().st_size / 1e6:,.0f} MB): summary {summary_mb:.1f} MB "
              f"({seconds:.0f} s){extra}", flush=True)
        big.unlink()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=100_000, help="frames of each mix")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--mix", action="append", choices=[mix.name for mix in MIXES], help="only these mixes")
    parser.add_argument("--memory", action="store_true", help="also peak RSS on each mix repeated tenfold")
    parser.add_argument("--gigabyte", action="store_true", help="with --memory: also peak RSS at 1 GB")
    parser.add_argument("--memory-only", action="store_true", help="with --memory: no timings, only peak RSS")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    parser.add_argument("--against", type=Path, help="another checkout, timed in the same rounds (no tshark)")
    args = parser.parse_args()
    tshark = shutil.which("tshark")
    if tshark is None:
        sys.exit("tshark is not installed: apt-get install -y tshark")
    args.out.mkdir(parents=True, exist_ok=True)
    # Byte-compile the package as pip does when it installs it: with PYTHONDONTWRITEBYTECODE set (as on
    # this machine) every run would otherwise compile its modules from source again (~60 ms).
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "dissector")], check=True)
    chosen = [mix for mix in MIXES if not args.mix or mix.name in args.mix]
    if args.against is not None:
        tree = args.against.resolve()
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree / "dissector")], check=True)
        compared = {mix.name: against_runs(mix, args.frames, args.repeat, args.out, tree) for mix in chosen}
        names = list(next(iter(compared.values())))
        print(f"\n| mix | {' | '.join(names)} |\n|---|{'---:|' * len(names)}")
        for mix_name, result in compared.items():
            print(f"| {mix_name} | " + " | ".join(f"{ours / theirs:.3f}" for ours, theirs in result.values()) + " |")
        print(f"(this tree's best time over {tree}'s, per command: below 1 is faster)")
        return 0
    if args.memory_only:
        for mix in chosen:
            write_capture(mix.records(args.frames), args.out / mix.name)
        print("peak RSS:")
        for mix in chosen:
            memory_runs(mix, args.out, args.gigabyte)
        return 0
    results = {mix.name: measure(mix, args.frames, args.repeat, args.out, tshark) for mix in chosen}
    print()
    print(ratio_table(results))
    if "max-size" in results:
        sizes = results["max-size"]
        print(f"max-size with the default ATV71 profile: {sizes['tshark summary'][0] / sizes['summary atv71'][0]:.2f}x "
              "tshark summary (its warnings keep every transaction in the Python stages)")
    if "polling" in results:
        polling = results["polling"]
        print(f"\nannotation cost (polling): {(1 - polling['summary -n'][0] / polling['summary'][0]) * 100:.1f}% "
              "of decode throughput")
    if args.memory:
        print("\npeak RSS:")
        for mix in chosen:
            memory_runs(mix, args.out, args.gigabyte)
    return 0


if __name__ == "__main__":
    sys.exit(main())
