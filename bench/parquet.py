"""--parquet time and size against --json on the same capture, one run; or measured on a given capture.

    python3 bench/parquet.py [--transactions 100000] [--files 4]
    python3 bench/parquet.py --capture FILE --only-parquet [--split N] [--keep DIR]

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

With `--capture FILE --only-parquet` nothing is simulated or extrapolated: it measures
`vw3-decode --parquet DIR FILE` on that capture (the 1 GB figure of the README: a capture written by
`python3 -m dissector.sim.simulate --out DIR --transactions 16100000 --seed 1`) and prints the input's
size, wall and CPU seconds, the decoding process's peak RSS, the dataset's size and rows per table.
`--split N` then cuts the same pcap into N files at record boundaries (named as independent captures,
so that `--jobs 2` can run two at a time; a transaction cut at a boundary is an unanswered request in
one file and an orphan answer in the next) and measures `--parquet DIR --jobs 2` over them.
"""
from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GIGABYTE = 1_000_000_000


CPU: dict[str, float] = {}  # CPU seconds (user + system) of each run, its worker processes included
RSS: dict[str, int] = {}  # peak resident set of each run's process (or of its largest worker), bytes


def _run(argv: list[str], stdout: object = subprocess.DEVNULL, name: str = "") -> float:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    start = time.perf_counter()
    process = subprocess.Popen([sys.executable, "-m", "dissector", *argv], env=env, stdout=stdout, cwd=ROOT)
    # wait4: this run's own usage (Linux counts the workers it waited for in its CPU and peak RSS)
    _pid, status, usage = os.wait4(process.pid, 0)
    seconds = time.perf_counter() - start
    process.returncode = os.waitstatus_to_exitcode(status)
    if process.returncode != 0:
        raise subprocess.CalledProcessError(process.returncode, argv)
    CPU[name] = usage.ru_utime + usage.ru_stime
    RSS[name] = usage.ru_maxrss * 1024
    return seconds


def _size(path: Path) -> int:
    return sum(file.stat().st_size for file in path.rglob("*") if file.is_file())


def _split_pcap(capture: Path, folder: Path, parts: int) -> list[Path]:
    """The pcap cut into `parts` pcaps of about equal size at record boundaries (global header copied)."""
    import struct

    size = capture.stat().st_size
    files = []
    with capture.open("rb") as source:
        header = source.read(24)
        order = "<" if header[:4] in (b"\xd4\xc3\xb2\xa1", b"\x4d\x3c\xb2\xa1") else ">"
        target = None
        for index in range(parts):
            path = folder / f"segment{index}.pcap"
            files.append(path)
            with path.open("wb") as target:
                target.write(header)
                limit = size * (index + 1) // parts
                while index == parts - 1 or source.tell() < limit:
                    record = source.read(16)
                    if len(record) < 16:
                        break
                    (length,) = struct.unpack_from(order + "I", record, 8)
                    target.write(record + source.read(length))
    return files


def _rows(line: str) -> dict[str, int]:
    """`NAME: 1 frames, 2 registers, 3 events` -> {'frames': 1, ...}"""
    counts = line.rsplit(": ", 1)[1].split(", ")
    return {name: int(number) for number, name in (count.split(" ") for count in counts)}


def measure_capture(capture: Path, split: int, keep: Path | None) -> None:
    """--parquet (and --jobs 2 over `split` pieces) on a given capture: nothing extrapolated."""
    work = keep if keep is not None else Path(tempfile.mkdtemp(prefix="vw3-parquet-bench-"))
    work.mkdir(parents=True, exist_ok=True)
    try:
        size = capture.stat().st_size
        print(f"input: {capture} {size:,} bytes; cores: {os.cpu_count()}, load average before: "
              f"{' '.join(f'{value:.2f}' for value in os.getloadavg())}; "
              f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}", flush=True)
        runs = [("--parquet", [str(capture)], work / "one")]
        if split > 1:
            parts = work / "parts"
            parts.mkdir(exist_ok=True)
            start = time.perf_counter()
            files = _split_pcap(capture, parts, split)
            print(f"cut into {len(files)} pcaps in {time.perf_counter() - start:.0f} s", flush=True)
            runs.append((f"--parquet --jobs 2 ({len(files)} files)", ["--jobs", "2", *map(str, files)], work / "jobs"))
        for name, argv, dataset in runs:
            shutil.rmtree(dataset, ignore_errors=True)
            out = work / f"{dataset.name}.txt"
            with out.open("w") as stream:
                seconds = _run(["--parquet", str(dataset), *argv], stdout=stream, name=name)
            rows: dict[str, int] = {}
            for line in out.read_text().splitlines():
                for table, count in _rows(line).items():
                    rows[table] = rows.get(table, 0) + count
            tables = {table: _size(dataset / table) for table in ("frames", "registers", "events")}
            total = sum(tables.values())
            print(f"vw3-decode --parquet {dataset} {' '.join(argv) if len(argv) < 6 else '...'}", flush=True)
            print(f"  {seconds:9.1f} s wall ({seconds / 60:.1f} min)  {CPU[name]:9.1f} s CPU ({CPU[name] / 60:.1f} min)  "
                  f"{size / 1e6 / seconds:.2f} MB/s  peak RSS {RSS[name] / 1e6:.0f} MB; "
                  f"load average after: {os.getloadavg()[0]:.2f}", flush=True)
            print(f"  dataset {total:,} bytes ({total / size:.3f} x the input): "
                  + ", ".join(f"{table} {tables[table]:,} bytes {rows.get(table, 0):,} rows" for table in tables),
                  flush=True)
    finally:
        if keep is None:
            shutil.rmtree(work, ignore_errors=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--transactions", type=int, default=100_000)
    parser.add_argument("--files", type=int, default=4)
    parser.add_argument("--capture", type=Path, help="measure --parquet on this capture (with --only-parquet)")
    parser.add_argument("--only-parquet", action="store_true", help="no --json peer, no extrapolation")
    parser.add_argument("--split", type=int, default=0, help="with --capture: also --jobs 2 over N pieces")
    parser.add_argument("--keep", type=Path, help="with --capture: write the datasets here and keep them")
    args = parser.parse_args()
    if args.capture is not None or args.only_parquet:
        if args.capture is None or not args.only_parquet:
            parser.error("--capture FILE and --only-parquet go together")
        measure_capture(args.capture, args.split, args.keep)
        return
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
