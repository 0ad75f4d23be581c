"""Start-up of vw3-decode against tshark on one frame, side by side, one run.

    python3 bench/startup.py [--runs 21]

Times `vw3-decode --hex '0C 03 20 D0 00 03 0E EF'` (the console script as a user runs it, found on
PATH), the same through `python3 -m dissector`, and `tshark -r` of a one-frame USER0 pcap of the same
bytes (mbrtu, CRC verification on, as bench/throughput.py), interleaved so that a slow spell of a shared
machine hits them all alike, and prints each one's median wall time and the median ratio to tshark
(issue 28's target: vw3-decode in at most 2/3 of tshark's time, a ratio <= 0.67). The package is
byte-compiled first, as pip leaves it. Also prints the interpreter's own start-up (`python3 -c pass`)
and the load average, which move these figures on a shared machine.
"""
from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from throughput import TSHARK_OPTIONS  # noqa: E402  (bench/ is this folder)

FRAME = "0C 03 20 D0 00 03 0E EF"


def one_frame_pcap(path: Path) -> None:
    """A classic pcap, linktype 147 (USER0), one record holding FRAME."""
    data = bytes.fromhex(FRAME)
    header = (0xA1B2C3D4).to_bytes(4, "little") + (2).to_bytes(2, "little") + (4).to_bytes(2, "little")
    header += bytes(8) + (65535).to_bytes(4, "little") + (147).to_bytes(4, "little")
    record = (1).to_bytes(4, "little") + bytes(4) + len(data).to_bytes(4, "little") * 2 + data
    path.write_bytes(header + record)


def wall(command: list[str]) -> float:
    start = time.perf_counter()
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=ROOT)
    elapsed = time.perf_counter() - start
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(command)}\n{result.stderr.decode()[-2000:]}")
    return elapsed


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=21)
    args = parser.parse_args()
    tshark, script = shutil.which("tshark"), shutil.which("vw3-decode")
    if tshark is None:
        sys.exit("tshark is not installed: apt-get install -y tshark")
    if script is None:
        sys.exit("vw3-decode is not on PATH: pip install -e .")
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "dissector")], check=True)
    with tempfile.TemporaryDirectory() as folder:
        pcap = Path(folder) / "one-frame.pcap"
        one_frame_pcap(pcap)
        commands = {
            "vw3-decode --hex": [script, "--hex", FRAME],
            "python3 -m dissector --hex": [sys.executable, "-m", "dissector", "--hex", FRAME],
            "tshark -r one-frame.pcap": [tshark, "-r", str(pcap), *TSHARK_OPTIONS],
            "python3 -c pass": [sys.executable, "-c", "pass"],
        }
        for command in commands.values():
            wall(command)  # warm the page cache
        times: dict[str, list[float]] = {name: [] for name in commands}
        load = os.getloadavg()[0]
        for _ in range(args.runs):
            for name, command in commands.items():
                times[name].append(wall(command))
    tshark_times = times["tshark -r one-frame.pcap"]
    print(f"{args.runs} interleaved runs each, load average {load:.2f} -> {os.getloadavg()[0]:.2f}")
    for name, values in times.items():
        ratios = [value / peer for value, peer in zip(values, tshark_times)]
        print(f"  {name:<28} median {statistics.median(values) * 1000:6.1f} ms  "
              f"median ratio to tshark {statistics.median(ratios):.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
