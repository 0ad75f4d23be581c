"""--parquet time and size against --json on the same capture, one run; the 1 GB figure extrapolated.

    python3 bench/parquet.py [--transactions 100000] [--files 4]

A simulated polling session (dissector.sim.simulate, 19200 baud, pcap with timestamps) of
--transactions request/response pairs is written once as one pcap and once cut into --files ring-buffer
files (`vw3-decode -w bus.pcap -b filesize:KB`). It then times, in one run on this machine:
- `vw3-decode --json FILE > /dev/null` (the peer: the same decoding, NDJSON out);
- `vw3-decode --parquet DIR FILE` (one process);
- `vw3-decode --parquet DIR --jobs 2 FILE...` on the separate files (two worker processes; the files
  are named as independent captures, not one ring, so that they can run in parallel);
and prints the input size, the seconds and MB/s of each, the dataset's size per table, and the ratios.
The 1 GB line is an extrapolation from the measured rate and size ratio (decoding is linear in the
input and memory flat: row groups of 65,536 rows), labelled as such.
"""
from __future__ import annotations

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GIGABYTE = 1_000_000_000


CPU: dict[str, float] = {}  # CPU seconds (user + system) of each run, its worker processes included


def _run(argv: list[str], stdout: object = subprocess.DEVNULL, name: str = "") -> float:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "dissector", *argv], check=True, env=env, stdout=stdout, cwd=ROOT)
    seconds = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    CPU[name] = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    return seconds


def _size(path: Path) -> int:
    return sum(file.stat().st_size for file in path.rglob("*") if file.is_file())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--transactions", type=int, default=100_000)
    parser.add_argument("--files", type=int, default=4)
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix="vw3-parquet-bench-"))
    try:
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        subprocess.run([sys.executable, "-m", "dissector.sim.simulate", "--out", str(work), "--transactions",
                        str(args.transactions), "--seed", "1"], check=True, env=env, stdout=subprocess.DEVNULL)
        (capture,) = work.glob("*.pcap")
        size = capture.stat().st_size
        parts = work / "parts"
        parts.mkdir()
        kilobytes = max(1, size // args.files // 1000 + 1)
        _run([str(capture), "-w", str(parts / "part.pcap"), "-b", f"filesize:{kilobytes}"])
        files = []
        for index, path in enumerate(sorted(parts.iterdir())):  # independent captures: no ring name
            if path.stat().st_size > 24:
                files.append(path.rename(parts / f"segment{index}.pcap"))
        json_seconds = _run(["--json", str(capture)], name="--json > /dev/null")
        one = work / "one"
        out = work / "one.txt"
        with out.open("w") as stream:
            parquet_seconds = _run(["--parquet", str(one), str(capture)], stdout=stream, name="--parquet")
        jobs_name = f"--parquet --jobs 2 ({len(files)} files)"
        jobs_seconds = _run(["--parquet", str(work / "jobs"), "--jobs", "2", *map(str, files)], name=jobs_name)
        tables = {name: _size(one / name) for name in ("frames", "registers", "events")}
        dataset = sum(tables.values())
        megabytes = size / 1e6
        print(f"input: {capture.name}, {megabytes:.1f} MB pcap, {args.transactions} transactions; "
              f"{out.read_text().strip()}")
        print(f"cores: {os.cpu_count()}, load average before: {os.getloadavg()[0]:.2f}")
        for name, seconds in (("--json > /dev/null", json_seconds), ("--parquet", parquet_seconds),
                              (jobs_name, jobs_seconds)):
            print(f"{name:<34} {seconds:8.2f} s wall  {megabytes / seconds:6.2f} MB/s  {CPU[name]:8.2f} s CPU")
        print(f"dataset: {dataset / 1e6:.2f} MB ({dataset / size:.3f} x the pcap): "
              + ", ".join(f"{name} {value / 1e6:.2f} MB" for name, value in tables.items()))
        print(f"ratios in this run: --parquet / --json {parquet_seconds / json_seconds:.2f}x wall, "
              f"{CPU['--parquet'] / CPU['--json > /dev/null']:.2f}x CPU; --jobs 2 / one process "
              f"{jobs_seconds / parquet_seconds:.2f}x wall, {CPU[jobs_name] / CPU['--parquet']:.2f}x CPU")
        rate = size / parquet_seconds
        jobs_rate = size / jobs_seconds
        cpu_rate = size / CPU["--parquet"]
        print(f"1 GB of pcap, EXTRAPOLATED from {megabytes:.1f} MB measured: --parquet {GIGABYTE / rate / 60:.0f} min "
              f"wall in one process at this run's load ({GIGABYTE / cpu_rate / 60:.0f} min of CPU), "
              f"{GIGABYTE / jobs_rate / 60:.0f} min wall with --jobs 2; dataset about {dataset / size * GIGABYTE / 1e6:.0f} MB")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
