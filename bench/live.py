"""CPU time of `vw3-decode --live` on a fast stream: the compiled live path against the Python stages.

    python3 bench/live.py [--frames 20000] [--repeat 3] [--mix plant] [--baud 115200] [--rate 200000]

A mix of bench/throughput.py (MIXES, with the options its user gives) is written to a pseudo-terminal
whose other end `vw3-decode --live` reads, in writes of 1..256 bytes at random, at --rate bytes a second
(200,000 by default: about 8,000 frames a second of the plant mix, which the Python stages keep up with,
so that both sides decode every frame; 0: as fast as the sniffer takes them); the sniffer's lines go to a pipe this script counts. Once
every frame is shown, the sniffer is stopped with SIGINT and its CPU time (user + system, from wait4,
both threads) is read. Each round runs the engine (default) and VW3_PURE_PYTHON=1, interleaved, and
the best of --repeat rounds is kept; the outputs of the two are checked equal first (plain summary: the
lines less the time column and response times, which depend on when the reads came).
"""
from __future__ import annotations

import argparse
import os
import random
import re
import select
import signal
import subprocess
import sys
import threading
import time
import tty
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from throughput import MIXES  # noqa: E402

VW3 = [sys.executable, "-m", "dissector"]


def run_live(stream: bytes, options: list[str], pure: bool, baud: int, rate: float | None, seed: int,
             expected: int | None, idle: float = 0.0) -> tuple[float, list[str], str]:
    """(CPU seconds, stdout lines, stderr) of one live decode of `stream` (none: `idle` seconds of a
    silent line)."""
    line, device, path = _pty()
    env = dict(os.environ, PYTHONPATH=str(ROOT), VW3_LIVE_REPORT="1")
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    process = subprocess.Popen([*VW3, "--live", path, "--baud", str(baud), *options], cwd=ROOT, env=env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    lines: list[bytes] = []
    done = threading.Event()

    def collect() -> None:
        for text in process.stdout:  # type: ignore[union-attr]
            lines.append(text)
            if expected is not None and len(lines) >= expected:
                done.set()
        done.set()

    reader = threading.Thread(target=collect, daemon=True)
    try:
        assert process.stderr is not None
        assert b"listening on" in process.stderr.readline()
        reader.start()
        rng = random.Random(seed)
        at, started = 0, time.perf_counter()
        while at < len(stream):
            piece = stream[at : at + rng.randint(1, 256)]
            if rate:
                delay = started + at / rate - time.perf_counter()
                if delay > 0:
                    time.sleep(delay)
            select.select([], [line], [])
            at += os.write(line, piece)
        if not stream:
            time.sleep(idle)
        elif expected is None:  # until no line comes for a second
            count = -1
            while count != len(lines):
                count = len(lines)
                time.sleep(1.0)
        else:
            done.wait(600)
        time.sleep(0.3)  # (the last reads, the flush after silence)
        if os.environ.get("BENCH_THREADS"):
            for task in sorted(Path(f"/proc/{process.pid}/task").iterdir(), key=lambda p: int(p.name)):
                fields = (task / "stat").read_text().rsplit(")", 1)[1].split()
                print("   thread", task.name, (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK"), "s")
        process.send_signal(signal.SIGINT)
        _pid, _status, usage = os.wait4(process.pid, 0)
        process.returncode = 0
        reader.join(10)
        err = process.stderr.read().decode()
    finally:
        if process.poll() is None:
            process.kill()
        os.close(line)
        os.close(device)
    return usage.ru_utime + usage.ru_stime, [text.decode().rstrip("\n") for text in lines], err


def _pty() -> tuple[int, int, str]:
    line, device = os.openpty()
    tty.setraw(device)
    return line, device, os.ttyname(device)


def untimed(line: str) -> str:
    line = re.sub(r"^( *\d+) +\d+\.\d{6} ", r"\1 ", line)
    return re.sub(r"\[#(\d+), \d+\.\d ms\]", r"[#\1]", line)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=20_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--mix", default="plant", choices=[mix.name for mix in MIXES])
    parser.add_argument("--baud", type=int, default=115200)
    parser.add_argument("--rate", type=float, default=200_000,
                        help="bytes a second written (default 200,000: the Python stages keep up; 0: as fast as read)")
    parser.add_argument("--option", action="append", default=[], help="a vw3-decode option (repeatable)")
    args = parser.parse_args()
    mix = next(mix for mix in MIXES if mix.name == args.mix)
    stream = b"".join(data for data, _time in mix.records(args.frames))
    options = [*mix.options, *args.option]
    print(f"{mix.name}: {args.frames:,} frames, {len(stream):,} bytes, vw3-decode --live PTY {' '.join(options)}")
    best: dict[str, float] = {}
    outputs: dict[str, list[str]] = {}
    expected = None
    for round_ in range(args.repeat):
        for name, pure in (("python", True), ("engine", False)):
            seconds, lines, err = run_live(stream, options, pure, args.baud, args.rate, round_, expected)
            expected = expected or len(lines)
            report = next((text for text in err.splitlines() if "live path:" in text), "live path: Python stages")
            hidden = next((text.split("; ")[-1] for text in err.splitlines() if "not shown" in text), "")
            print(f"  round {round_ + 1} {name:6}: {seconds:6.2f} s CPU, {len(lines):,} lines; {report.split(': ', 1)[1]}"
                  + (f"; {hidden}" if hidden else ""))
            best[name] = min(best.get(name, seconds), seconds)
            outputs.setdefault(name, lines)
    same = [untimed(text) for text in outputs["python"]] == [untimed(text) for text in outputs["engine"]]
    print(f"outputs equal (less times): {'yes' if same else 'NO'}")
    print(f"CPU time, best of {args.repeat}: Python stages {best['python']:.2f} s, engine {best['engine']:.2f} s: "
          f"{best['python'] / best['engine']:.2f}x less CPU with the engine")
    if args.rate:
        # What a silent line costs for as long (start-up, the reads timing out, the display waking):
        # the rest is what decoding the stream cost.
        seconds = len(stream) / args.rate + 0.3
        idle = {name: min(run_live(b"", options, pure, args.baud, None, 0, None, seconds)[0]
                          for _round in range(args.repeat)) for name, pure in (("python", True), ("engine", False))}
        work = {name: best[name] - idle[name] for name in best}
        print(f"a silent line for {seconds:.1f} s: Python stages {idle['python']:.2f} s, engine {idle['engine']:.2f} s; "
              f"decoding the stream: Python stages {work['python']:.2f} s, engine {work['engine']:.2f} s: "
              f"{work['python'] / work['engine']:.2f}x")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
