"""Throughput of the Wireshark Lua plugin (lua/vw3.lua) against tshark's own mbrtu, measured in one run.

    python3 bench/lua_throughput.py [--frames 200000] [--repeat 1] [--pcap FILE] [--plugin FILE]

Reuses bench/out/session.pcap when it holds --frames records (bench/throughput.py writes it), or builds
it the same way (dissector.sim.simulate.generate_session, seed 1, write_capture). Then times, best of
--repeat rounds (the rounds interleave the commands):
- `tshark -2 -X lua_script:lua/vw3.lua -r session.pcap`, the one-line summary to a file;
- tshark's own mbrtu on the same pcap (USER0 mapped to mbrtu, CRC verification on), summary to a file.
Prints frames per second of each and their ratio. --plugin times another copy of the plugin (an older
commit's, `git show REV:lua/vw3.lua > old.lua`) the same way.
"""
from __future__ import annotations

import argparse
import shutil
import struct
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

PLUGIN = ROOT / "lua" / "vw3.lua"

from throughput import TSHARK_OPTIONS as MBRTU_OPTIONS, timed  # noqa: E402  (bench/ is this script's folder)


def pcap_records(path: Path) -> int:
    """The number of records in a classic pcap file (0 when it is not one)."""
    data = path.read_bytes()
    if len(data) < 24:
        return 0
    magic = data[:4]
    if magic in (b"\xd4\xc3\xb2\xa1", b"\x4d\x3c\xb2\xa1"):
        order = "<"
    elif magic in (b"\xa1\xb2\xc3\xd4", b"\xa1\xb2\x3c\x4d"):
        order = ">"
    else:
        return 0
    count, offset = 0, 24
    while offset + 16 <= len(data):
        (captured,) = struct.unpack_from(order + "I", data, offset + 8)
        offset += 16 + captured
        count += 1
    return count


def session_pcap(frames: int, out: Path) -> Path:
    pcap = out / "session.pcap"
    if pcap.exists() and pcap_records(pcap) == frames:
        return pcap
    from dissector.sim.simulate import generate_session, write_capture

    out.mkdir(parents=True, exist_ok=True)
    records = generate_session(frames // 2 + frames // 20, seed=1)[:frames]
    _raw, pcap = write_capture(records, out / "session")
    return pcap


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=1, help="best of this many rounds (default 1)")
    parser.add_argument("--pcap", type=Path, help="time this capture instead of the simulated session")
    parser.add_argument("--plugin", type=Path, default=PLUGIN, help="the plugin file (default lua/vw3.lua)")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    args = parser.parse_args()
    tshark = shutil.which("tshark")
    if tshark is None:
        sys.exit("tshark is not installed: apt-get install -y tshark")
    pcap = args.pcap.resolve() if args.pcap else session_pcap(args.frames, args.out)
    frames = pcap_records(pcap)
    version = subprocess.run([tshark, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    plugin = args.plugin.resolve()
    print(f"{version}\n{pcap}: {frames} frames\nplugin: {plugin}")

    args.out.mkdir(parents=True, exist_ok=True)
    runs = {
        "tshark -2 + vw3.lua summary": [tshark, "-2", "-X", f"lua_script:{plugin}", "-r", str(pcap)],
        "tshark mbrtu summary": [tshark, "-r", str(pcap), *MBRTU_OPTIONS],
    }
    best = {name: float("inf") for name in runs}
    for _round in range(args.repeat):
        for name, command in runs.items():
            best[name] = min(best[name], timed(command, args.out / "lua_output.txt", 1))
    rates = {name: frames / seconds for name, seconds in best.items()}
    for name, seconds in best.items():
        print(f"{name:<32} {seconds:8.3f} s  {rates[name]:>10,.0f} frames/s")
    lua, mbrtu = rates["tshark -2 + vw3.lua summary"], rates["tshark mbrtu summary"]
    print(f"\nvw3.lua vs mbrtu: {lua / mbrtu:.3f}x (mbrtu is {mbrtu / lua:.1f} times faster)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
