"""Throughput of vw3-decode against tshark on the same frames, measured in one run.

    python3 bench/throughput.py [--frames 200000] [--repeat 3] [--memory]

Builds a simulated session (dissector.sim.simulate.generate_session: ATV71 I/O scanning, SEL-749M polls,
exceptions, unanswered requests), writes it raw (for vw3-decode) and as a USER0 pcap (for tshark's
mbrtu dissector), then times, best of --repeat:
- vw3-decode summary to a file, with the ATV71 annotator (the default) and without it (-n);
- vw3-decode --json to a file;
- tshark's one-line summary, and tshark -T json, with CRC verification on.
The rounds interleave the commands (best of --repeat rounds each; commands under a second, the
summaries of both tools, run 4 times a round). The package is byte-compiled first, as pip does.
With --memory, peak RSS of vw3-decode on the session and on a tenfold session; with --gigabyte, also on
the session repeated to 1 GB (a few minutes).
Figures are frames per second and ratios against tshark from this one run.
"""
from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from dissector.sim.simulate import generate_session, write_capture  # noqa: E402

TSHARK_OPTIONS = [
    "-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""',
    "-o", "mbrtu.crc_verification:TRUE",
]
VW3 = [sys.executable, "-m", "dissector"]
SHORT_RUNS = 4


def timed(command: list[str], output: Path, repeat: int) -> float:
    """Best wall time of `repeat` runs, stdout to `output`."""
    best = float("inf")
    for _ in range(repeat):
        with output.open("wb") as sink:
            start = time.perf_counter()
            result = subprocess.run(command, stdout=sink, stderr=subprocess.PIPE, cwd=ROOT)
            elapsed = time.perf_counter() - start
        if result.returncode != 0:
            sys.exit(f"failed ({result.returncode}): {' '.join(command)}\n{result.stderr.decode()[-2000:]}")
        best = min(best, elapsed)
    return best


def peak_rss_mb(command: list[str]) -> float:
    """Peak resident memory of one run of `command`, measured in a fresh wrapper process."""
    probe = (
        "import resource, subprocess, sys\n"
        "subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, check=True)\n"
        "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
    )
    result = subprocess.run([sys.executable, "-c", probe, *command], capture_output=True, text=True, cwd=ROOT, check=True)
    return int(result.stdout.strip()) / 1024


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--memory", action="store_true", help="also measure peak RSS at 1x and 10x")
    parser.add_argument("--gigabyte", action="store_true", help="with --memory: also peak RSS on 1 GB of input")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    args = parser.parse_args()
    tshark = shutil.which("tshark")
    if tshark is None:
        sys.exit("tshark is not installed: apt-get install -y tshark")
    args.out.mkdir(parents=True, exist_ok=True)
    # Byte-compile the package as pip does when it installs it: with PYTHONDONTWRITEBYTECODE set (as on
    # this machine) every run would otherwise compile its modules from source again (~60 ms).
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "dissector")], check=True)

    records = generate_session(args.frames // 2 + args.frames // 20, seed=1)[: args.frames]
    frames = len(records)
    raw, pcap = write_capture(records, args.out / "session")
    print(f"session: {frames} frames, {raw.stat().st_size} bytes raw, {pcap.stat().st_size} bytes pcap")

    runs = {
        "vw3-decode summary (atv71 annotator)": VW3 + [str(raw)],
        "vw3-decode summary (-n, no annotator)": VW3 + [str(raw), "-n"],
        "vw3-decode --json": VW3 + [str(raw), "--json"],
        "tshark summary": [tshark, "-r", str(pcap), *TSHARK_OPTIONS],
        "tshark -T json": [tshark, "-r", str(pcap), "-T", "json", *TSHARK_OPTIONS],
    }
    # Rounds interleave the commands, so a slow spell of a shared machine hits them all alike. Commands
    # under a second (the summaries, vw3-decode's and tshark's alike) run SHORT_RUNS times a round: at
    # 0.2-0.7 s a run, a 30 ms hiccup would otherwise move their ratio by 10%.
    best: dict[str, float] = {name: float("inf") for name in runs}
    for _round in range(args.repeat):
        for name, command in runs.items():
            times = SHORT_RUNS if best[name] < 1.0 else 1
            best[name] = min(best[name], timed(command, args.out / "output.txt", times))
    rates: dict[str, float] = {}
    for name, seconds in best.items():
        rates[name] = frames / seconds
        print(f"{name:<40} {seconds:7.3f} s  {rates[name]:>10,.0f} frames/s")

    summary = rates["vw3-decode summary (atv71 annotator)"]
    bare = rates["vw3-decode summary (-n, no annotator)"]
    print()
    print(f"summary vs tshark summary:      {summary / rates['tshark summary']:.2f}x")
    print(f"json vs tshark -T json:         {rates['vw3-decode --json'] / rates['tshark -T json']:.2f}x")
    print(f"annotation cost:                {(1 - summary / bare) * 100:.1f}% of decode throughput")

    if args.memory:
        big = args.out / "session10.bin"
        with big.open("wb") as sink:
            for _ in range(10):
                sink.write(raw.read_bytes())
        small_mb = peak_rss_mb(VW3 + [str(raw)])
        big_mb = peak_rss_mb(VW3 + [str(big)])
        json_mb = peak_rss_mb(VW3 + [str(big), "--json"])
        print(f"peak RSS: {small_mb:.1f} MB at {raw.stat().st_size / 1e6:.1f} MB input, "
              f"{big_mb:.1f} MB at {big.stat().st_size / 1e6:.1f} MB input (x{big_mb / small_mb:.2f}); "
              f"--json {json_mb:.1f} MB at {big.stat().st_size / 1e6:.1f} MB")
        big.unlink()
        if args.gigabyte:
            huge = args.out / "session1g.bin"
            data = raw.read_bytes()
            with huge.open("wb") as sink:
                for _ in range(-(-10**9 // len(data))):
                    sink.write(data)
            start = time.perf_counter()
            huge_mb = peak_rss_mb(VW3 + [str(huge)])
            seconds = time.perf_counter() - start
            print(f"peak RSS: {huge_mb:.1f} MB at {huge.stat().st_size / 1e9:.2f} GB input ({seconds:.0f} s)")
            huge.unlink()
    return 0


if __name__ == "__main__":
    sys.exit(main())
