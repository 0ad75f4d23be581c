"""The Wireshark Lua plugin (lua/vw3.lua) against tshark's own mbrtu, measured in one run.

    python3 bench/lua_throughput.py [--frames 100000] [--repeat 3] [--mix NAME] [--pcap FILE] [--plugin FILE]

The traffic mixes are bench/throughput.py's (dissector.sim.mixes, seed 1): `plant` (a plant floor: ATV71
drives on FC23, SEL-749M relays, an I/O module, a meter, about 1 % exceptions, with the plant's
profiles), `max-size` (every public function code at quantities up to the spec's limits) and `polling`
(the simulator's polling loop). For each mix, best of --repeat interleaved rounds:
- one pass (`tshark -r`, what Wireshark does on opening a file), the one-line summary to a file: the
  plugin and mbrtu (USER0 mapped to each through the DLT_USER table, CRC verification on), and their
  frames per second and ratio; and each round's own ratio, with their median (the two one passes of a
  round run seconds apart, so a slow spell of the machine hits both, where the best times may pair a
  lucky run of one with an unlucky run of the other);
- `tshark -2` (two passes, the plugin's documented way to run tshark): wall time and peak RSS of both,
  and the RSS ratio.
--pcap times one capture instead of the mixes; --plugin another copy of the plugin (an older commit's,
`git show REV:lua/vw3.lua > old.lua`).

--instructions counts instead of timing: the machine instructions of one pass of each (valgrind's
callgrind, which a shared machine's load does not move), of the capture and of an empty one (tshark's
start-up, with the plugin's tables and fields), so that the ratio per record is told apart from the
start-up's share, and the ratio that start-ups and per-record counts give at 100,000 records (where
the one-pass target is stated). It counts a third dissector too, the floor: a Lua dissector that does
only what any Lua dissector of records must (read the record's number, bytes and time, look at the
tree, set the Protocol and Info columns), so that what the plugin's own work costs is told apart from
what calling Lua from Wireshark costs. Slow (some 50 times a run): use it with --frames 20000.
--plugin may be given more than once with --instructions: each plugin is counted on the same captures,
mbrtu and the floor once. The counts repeat run after run: tshark runs with address space randomisation
off (setarch -R) and a clock stopped at one second (a time() of our own, built with cc into --out),
because Lua 5.2 seeds its string hashes with the time and the heap's addresses: with either moving, the
same plugin counted twice differed by up to 0.3 %. Two plugins still differ by where their strings land:
Wireshark's column look-up (cols.protocol, cols.info: some 70 strcmp a record) costs 23 to 34
instructions a strcmp by the address of the Lua string it compares (some 0.5 % of the plant mix's count),
so a difference under that is no difference of the plugin's work.
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import statistics
import struct
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

PLUGIN = ROOT / "lua" / "vw3.lua"

from throughput import MIXES, TSHARK_OPTIONS as MBRTU_OPTIONS, run_once  # noqa: E402  (bench/ is this folder)

from dissector.sim.simulate import write_capture  # noqa: E402

USER_DLT = 'uat:user_dlts:"User 0 (DLT=147)","vw3","0","","0",""'


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


def plugin_options(cli_options: list[str]) -> list[str]:
    """vw3-decode's --profile options as the plugin's preference."""
    profiles = [cli_options[index + 1] for index, option in enumerate(cli_options) if option == "--profile"]
    return ["-o", f"vw3.profiles:{','.join(profiles)}"] if profiles else []


def measure(name: str, pcap: Path, options: list[str], plugin: Path, tshark: str, repeat: int,
            out: Path) -> dict[str, float]:
    frames = pcap_records(pcap)
    lua = [tshark, "-X", f"lua_script:{plugin}", "-o", USER_DLT, *options, "-r", str(pcap)]
    mbrtu = [tshark, "-r", str(pcap), *MBRTU_OPTIONS]
    runs = {
        "vw3.lua one pass": lua,
        "mbrtu one pass": mbrtu,
        "vw3.lua -2": lua[:1] + ["-2"] + lua[1:],
        "mbrtu -2": mbrtu[:1] + ["-2"] + mbrtu[1:],
    }
    best = {run: (float("inf"), 0.0) for run in runs}
    round_ratios = []
    # Rounds interleave the commands, so a slow spell of the shared machine hits them all alike.
    for _round in range(repeat):
        this_round = {}
        for run, command in runs.items():
            seconds, rss = run_once(command, out / "lua_output.txt")
            this_round[run] = seconds
            best[run] = (min(best[run][0], seconds), max(best[run][1], rss))
        round_ratios.append(this_round["mbrtu one pass"] / this_round["vw3.lua one pass"])
    print(f"{name}: {pcap.name}, {frames} records")
    for run, (seconds, rss) in best.items():
        print(f"  {run:<18} {seconds:8.3f} s {frames / seconds:>10,.0f} frames/s  peak RSS {rss:7.1f} MB")
    speed = best["mbrtu one pass"][0] / best["vw3.lua one pass"][0]
    memory = best["vw3.lua -2"][1] / best["mbrtu -2"][1]
    print(f"  one pass: vw3.lua at {speed:.2f}x mbrtu's speed; -2: vw3.lua's peak RSS {memory:.2f}x mbrtu's")
    # The best times can pair a lucky run of one with an unlucky run of the other; the two one passes of
    # a round ran seconds apart, under the same load.
    rounds = ", ".join(f"{ratio:.2f}x" for ratio in round_ratios)
    print(f"  one pass, each round's ratio: {rounds} (median {statistics.median(round_ratios):.2f}x)")
    return {"speed": speed, "memory": memory, "round_median": statistics.median(round_ratios)}


# time() stopped at one second: the seed Lua 5.2 takes from the clock (luai_makeseed) the same every run.
FIXED_TIME_C = "#include <time.h>\ntime_t time(time_t *t) { if (t) *t = 1700000000; return 1700000000; }\n"
REPEATABLE: dict[str, str] = {}  # (the environment and prefix that make a count repeat: repeatable())


def repeatable(out: Path) -> list[str]:
    """The prefix (setarch -R) and, in REPEATABLE, the LD_PRELOAD that make a count repeat run after run;
    none where cc or setarch is missing (said once)."""
    compiler, setarch = shutil.which("cc"), shutil.which("setarch")
    if compiler is None or setarch is None:
        print("  (no cc or setarch: counts vary run to run by up to 0.3 %)")
        return []
    source, library = out / "fixed_time.c", out / "fixed_time.so"
    source.write_text(FIXED_TIME_C)
    built = subprocess.run([compiler, "-shared", "-fPIC", "-o", str(library), str(source)], capture_output=True,
                           text=True)
    if built.returncode != 0:
        print(f"  (cc failed, counts vary run to run by up to 0.3 %: {built.stderr.strip()[:200]})")
        return []
    REPEATABLE["LD_PRELOAD"] = str(library)
    return [setarch, "-R"]


def instructions(command: list[str], prefix: list[str] | None = None) -> int:
    """Machine instructions of one run of `command` under callgrind (its output thrown away)."""
    env = dict(os.environ, **REPEATABLE) if prefix else None
    probe = subprocess.run([*(prefix or []), "valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
                            *command], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, cwd=ROOT,
                           env=env)
    found = re.search(r"Collected : (\d+)", probe.stderr)
    if probe.returncode != 0 or found is None:
        sys.exit(f"failed under valgrind ({probe.returncode}): {' '.join(command)}\n{probe.stderr[-2000:]}")
    return int(found.group(1))


def peak_rss(command: list[str], prefix: list[str], out: Path) -> float:
    """Peak RSS (MB) of one run of `command` (as repeatable as the counts: the same prefix and clock)."""
    saved = {key: os.environ.get(key) for key in REPEATABLE}
    os.environ.update(REPEATABLE)  # (run_once's probe passes its environment on to tshark)
    try:
        return run_once([*prefix, *command], out / "lua_output.txt")[1]
    finally:
        for key, value in saved.items():
            if value is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = value


# The floor (see --instructions): named vw3, so that the same DLT_USER entry hands it the records.
FLOOR_DISSECTOR = """local proto = Proto("vw3", "Lua dissector floor")
function proto.dissector(tvb, pinfo, tree)
  local number, bytes, time, text = pinfo.number, tvb:raw(), pinfo.abs_ts, tree.text
  local cols = pinfo.cols
  cols.protocol = "VW3"
  cols.info = "1 Read Holding Registers request 3201..3210"
  return #bytes
end
"""


PROJECTED_RECORDS = 100_000  # the timed run's default length, where the one-pass target is stated


def per_record(command: list[str], pcap: Path, empty: Path, frames: int,
               prefix: list[str]) -> tuple[int, int, float]:
    """Instructions of one pass over `pcap`, over the empty capture, and their difference a record."""
    total, start = instructions(command + [str(pcap)], prefix), instructions(command + [str(empty)], prefix)
    return total, start, (total - start) / frames


def count(name: str, pcap: Path, options: list[str], plugins: list[Path], tshark: str, out: Path) -> float:
    """One pass of each plugin, of mbrtu and of the floor in instructions; the per-record ratio of the first
    plugin (start-up apart)."""
    frames = pcap_records(pcap)
    empty = out / "lua-empty.pcap"
    empty.write_bytes(pcap.read_bytes()[:24])  # the pcap header alone: tshark's start-up and end
    floor_script = out / "lua-floor.lua"
    floor_script.write_text(FLOOR_DISSECTOR)
    prefix = repeatable(out)
    mbrtu = [tshark, *MBRTU_OPTIONS, "-r"]
    floor = [tshark, "-X", f"lua_script:{floor_script}", "-o", USER_DLT, "-r"]
    mbrtu_total, mbrtu_start, per_mbrtu = per_record(mbrtu, pcap, empty, frames, prefix)
    _floor_total, _floor_start, per_floor = per_record(floor, pcap, empty, frames, prefix)
    print(f"{name}: {pcap.name}, {frames} records (instructions, one pass)")
    print(f"  mbrtu   {mbrtu_total / 1e9:7.3f} G, start-up {mbrtu_start / 1e9:.3f} G, {per_mbrtu:,.0f} a record")
    print(f"  floor   {per_floor:,.0f} a record (a Lua dissector that reads the record and sets its columns)")
    mbrtu_rss = peak_rss(mbrtu[:1] + ["-2"] + mbrtu[1:] + [str(pcap)], prefix, out)
    print(f"  mbrtu   tshark -2: peak RSS {mbrtu_rss:.1f} MB")
    ratios = []
    for plugin in plugins:
        lua = [tshark, "-X", f"lua_script:{plugin}", "-o", USER_DLT, *options, "-r"]
        plugin_total, plugin_start, per_plugin = per_record(lua, pcap, empty, frames, prefix)
        print(f"  {plugin}")
        print(f"    vw3.lua {plugin_total / 1e9:7.3f} G, start-up {plugin_start / 1e9:.3f} G, {per_plugin:,.0f} a "
              f"record, the plugin's own work {per_plugin - per_floor:,.0f} a record")
        print(f"    vw3.lua at {mbrtu_total / plugin_total:.2f}x mbrtu's instructions on this capture, "
              f"{per_mbrtu / per_plugin:.2f}x a record")
        # Memory beside the counts, so that plugins compare in one run: tshark -2's peak RSS (the timed
        # run's memory figure), one run each (the heap's size moves little from run to run).
        rss = peak_rss(lua[:1] + ["-2"] + lua[1:] + [str(pcap)], prefix, out)
        print(f"    tshark -2: peak RSS {rss:.1f} MB ({rss / mbrtu_rss:.2f}x mbrtu's)")
        # The speed target is stated at the timed run's length: the start-ups weigh less there than here.
        projected = (mbrtu_start + PROJECTED_RECORDS * per_mbrtu) / (plugin_start + PROJECTED_RECORDS * per_plugin)
        print(f"    at {PROJECTED_RECORDS:,} records (start-ups and the counts a record above): "
              f"vw3.lua at {projected:.3f}x mbrtu's instructions")
        ratios.append(per_mbrtu / per_plugin)
    return ratios[0]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=100_000, help="records of each mix (default 100,000)")
    parser.add_argument("--repeat", type=int, default=3, help="best of this many rounds (default 3)")
    parser.add_argument("--mix", action="append", choices=[mix.name for mix in MIXES],
                        help="only these mixes (default: plant and max-size)")
    parser.add_argument("--pcap", type=Path, help="time this capture instead of the mixes")
    parser.add_argument("--plugin", type=Path, action="append",
                        help="the plugin file (default lua/vw3.lua); more than one with --instructions")
    parser.add_argument("--out", type=Path, default=ROOT / "bench" / "out")
    parser.add_argument("--instructions", action="store_true",
                        help="count machine instructions under valgrind instead of timing")
    args = parser.parse_args()
    tshark = shutil.which("tshark")
    if tshark is None:
        sys.exit("tshark is not installed: apt-get install -y tshark")
    version = subprocess.run([tshark, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    plugins = [path.resolve() for path in args.plugin or [PLUGIN]]
    if len(plugins) > 1 and not args.instructions:
        sys.exit("more than one --plugin: only with --instructions (timings of several are not one run)")
    plugin = plugins[0]
    print(f"{version}\nplugin: {', '.join(str(path) for path in plugins)}")
    args.out.mkdir(parents=True, exist_ok=True)
    if args.instructions and shutil.which("valgrind") is None:
        sys.exit("valgrind is not installed: apt-get install -y valgrind")
    if args.pcap:
        if args.instructions:
            count(args.pcap.name, args.pcap.resolve(), [], plugins, tshark, args.out)
        else:
            measure(args.pcap.name, args.pcap.resolve(), [], plugin, tshark, args.repeat, args.out)
        return 0
    chosen = [mix for mix in MIXES if (mix.name in args.mix if args.mix else mix.name != "polling")]
    for mix in chosen:
        _raw, pcap = write_capture(mix.records(args.frames), args.out / f"lua-{mix.name}")
        if args.instructions:
            count(mix.name, pcap, plugin_options(mix.options), plugins, tshark, args.out)
        else:
            measure(mix.name, pcap, plugin_options(mix.options), plugin, tshark, args.repeat, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
