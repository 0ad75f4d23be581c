"""The Lua plugin's framer on random bytes read one byte a record (a USB tap's reads of a line at the wrong speed).

    python3 bench/lua_noise_records.py [--records 1000 --records 5000 --records 20000] [--plugin OLD.lua]

Each record end is a boundary the framer weighs (lua/src/rtu.lua framed_reach: is the record after a point a frame
of its own?); a look-up through all of the buffer's record ends for each made every byte cost the whole buffer's,
many times over. For each size: the capture (bench/noise_throughput.py --kind random-reads, the same bytes), the
user CPU seconds of `tshark -2` with each plugin (lua/vw3.lua, then each --plugin, e.g. an older commit's:
`git show REV:lua/vw3.lua > old.lua`), best of --repeat, the milliseconds a record, and whether every plugin's
output (one pass, -2, -2 -V) is the same bytes as the first's. Linear: the milliseconds a record stay as the size
grows.
"""
from __future__ import annotations

import argparse
import resource
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))

from noise_throughput import random_reads  # noqa: E402  (bench/ is this folder)

USER_DLT = 'uat:user_dlts:"User 0 (DLT=147)","vw3","0","","0",""'
PASSES = {"one pass": [], "-2": ["-2"], "-2 -V": ["-2", "-V"]}


def tshark(plugin: Path, pcap: Path, options: list[str]) -> tuple[float, bytes]:
    """The user CPU seconds of one tshark run (its child's), and its output."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    done = subprocess.run(["tshark", "-X", f"lua_script:{plugin}", "-o", USER_DLT, "-r", str(pcap), *options],
                          capture_output=True, check=True)
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before, done.stdout


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--records", type=int, action="append", help="one-byte records (default 1,000, 5,000)")
    parser.add_argument("--plugin", type=Path, action="append", default=[], help="another plugin to compare")
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    plugins = [ROOT / "lua" / "vw3.lua", *args.plugin]
    same = True
    for records in args.records or [1000, 5000]:
        pcap = args.out / f"random_reads_{records}.pcap"
        pcap.write_bytes(random_reads(records))
        first: dict[str, bytes] = {}
        for plugin in plugins:
            seconds = min(tshark(plugin, pcap, ["-2"])[0] for _ in range(args.repeat))
            outputs = {name: tshark(plugin, pcap, options)[1] for name, options in PASSES.items()}
            first = first or outputs
            agrees = outputs == first
            same &= agrees
            print(f"{records:>7} records  {plugin}: {seconds:7.2f} s user (-2), {1000 * seconds / records:.3f} ms a "
                  f"record; output {'the same' if agrees else 'DIFFERS'}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
