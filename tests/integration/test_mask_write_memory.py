"""A Mask Write (FC22) its echo confirms changes the parameter memory as the spec has the register change
(Application Protocol 6.16): (current AND and_mask) OR (or_mask AND NOT and_mask) where the current value
is known (or and_mask is 0), the parameter forgotten otherwise (data/modbus.toml [confirm] "mask",
memory.remember_mask). What a user sees of it: the 16#8000 story (`written 23 in frame #4`, not the value
read before the mask), a bits_depend layout (CMD's bits named once CHCF is masked from 3 to 1), no
`readable again` after a mask on an unreadable parameter. The ATV71 card does not support FC22 (a warning),
yet a slave that answers one changed its register all the same. vw3-decode (compiled engine and
VW3_PURE_PYTHON=1; under a profile whose device supports FC22 the engine hands a tracked slave's mask
writes to the Python stages) and the plugin (tshark -2 and one pass)."""
from __future__ import annotations

import random
import shutil
import subprocess
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import PLUGIN, ensure_tool, lua_errors, run_tshark, write_pcap

ROOT = Path(__file__).resolve().parents[2]

# 8401 CHCF read 3, 8402 COP read 18 (16#12); COP masked AND 00F2 OR 0025 (the spec's example: 16#17 = 23);
# CHCF masked AND 0000 OR 0001 (1, whatever it held); CMD (8501, bits_depend on CHCF = 3) read; COP then
# 16#8000; COP masked while unreadable (nothing known of it now); COP read 23.
FRAMES = [
    "0C 03 20D1 0002", "0C 03 04 0003 0012",
    "0C 16 20D2 00F2 0025", "0C 16 20D2 00F2 0025",
    "0C 16 20D1 0000 0001", "0C 16 20D1 0000 0001",
    "0C 03 2135 0001", "0C 03 02 0006",
    "0C 03 20D1 0002", "0C 03 04 0001 8000",
    "0C 16 20D2 00F2 0025", "0C 16 20D2 00F2 0025",
    "0C 03 20D1 0002", "0C 03 04 0001 0017",
]
PREFIX = "            -  12 response  Read Holding Registers "
EXPECTED = {
    8: "     8" + PREFIX + "8501: CMD=Enable voltage, No quick stop [#7]  CRC ok",
    10: "    10" + PREFIX + "8401..8402 (2): CHCF=SIM (combined) COP=protected [#9] [COP (8402) became protected: "
        "written 23 in frame #4, 16#8000 now]  CRC ok",
    14: "    14" + PREFIX + "8401..8402 (2): CHCF=SIM (combined) COP=23 (not a listed value) [#13]  CRC ok",
}
# The plugin's fields of the responses: frame, register texts (an echo's: its masks, as --json's), notes.
PLUGIN_LINES = [
    "2|IO (I/O profile),18 (not a listed value)|",
    "4|AND 0x00F2 OR 0x0025: the result depends on the value before|",
    "6|AND 0x0000 OR 0x0001|",
    "8|Enable voltage, No quick stop|",
    "10|SIM (combined),16#8000: protected|COP (8402) became protected: written 23 in frame #4, 16#8000 now",
    "12|AND 0x00F2 OR 0x0025: the result depends on the value before|",
    "14|SIM (combined),23 (not a listed value)|",
]


def _data() -> bytes:
    return b"".join(rtu(frame) for frame in FRAMES)


def _lines(out: str) -> dict[int, str]:
    return {int(line.split()[0]): line for line in out.splitlines() if line[:6].strip().isdigit()}


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_follows_a_confirmed_mask_write(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                   pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = tmp_path / "mask.bin"
    capture.write_bytes(_data())
    status, out, err = run_cli([str(capture), "--profile", "atv71"])
    assert status == 0, err
    lines = _lines(out)
    assert {number: lines[number] for number in EXPECTED} == EXPECTED
    assert "Mask Write Register (22) is not supported by the VW3 A3 303" in lines[3]


@pytest.mark.parametrize("pure", [False, True])
def test_a_device_that_supports_mask_write_gives_the_same_lines(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                pure: bool) -> None:
    """No warning on the mask write: the compiled engine would write its lines itself, and must leave the
    transaction to the Python stages, whose memory it changes."""
    use_engine(monkeypatch, pure)
    shutil.copy(ROOT / "dissector" / "data" / "maps" / "atv71.csv", tmp_path / "atv71.csv")
    text = (ROOT / "dissector" / "data" / "profiles" / "atv71.toml").read_text()
    text = text.replace('name = "atv71"', 'name = "atv71mask"').replace(
        "functions = [3, 4, 6, 8, 11, 16, 23, 43]", "functions = [3, 4, 6, 8, 11, 16, 22, 23, 43]")
    profile = tmp_path / "atv71mask.toml"
    profile.write_text(text)
    capture = tmp_path / "mask.bin"
    capture.write_bytes(_data())
    status, out, err = run_cli([str(capture), "--profile", str(profile)])
    assert status == 0, err
    lines = _lines(out)
    assert {number: lines[number] for number in EXPECTED} == EXPECTED
    assert lines[3] == "     3            -  12 request   Mask Write Register 8402 AND 0x00F2 OR 0x0025  CRC ok"


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_follows_a_confirmed_mask_write(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "mask.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                               for index, frame in enumerate(FRAMES)])
    got = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                     "-e", "vw3.reg.text", "-e", "vw3.note", "-Y", 'vw3.kind == "response"', two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == PLUGIN_LINES


# The plugin's pure part under plain Lua (no Wireshark, no `bit` module): the mask computed by arithmetic.
MASK_RUNNER = """
local vw3 = dofile(arg[1])
local env = package.loaded["vw3.env"]
for line in io.lines(arg[2]) do
  local current, and_mask, or_mask = line:match("(%d+) (%d+) (%d+)")
  local seen = { [7] = { value = tonumber(current), frame = 1, how = "read" } }
  env.remember_mask(seen, 2, { address = 7, and_mask = tonumber(and_mask), or_mask = tonumber(or_mask) })
  print(seen[7].value, seen[7].frame, seen[7].how)
end
"""


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_plain_lua_computes_the_mask_as_the_spec(tmp_path: Path, lua: str) -> None:
    chosen = random.Random(22)
    cases = [(0x12, 0xF2, 0x25), (0, 0, 0xFFFF), (0xFFFF, 0xFFFF, 0), (0xFFFF, 0, 0), (0x8000, 0x7FFF, 0x8000)]
    cases += [(chosen.randrange(65536), chosen.randrange(65536), chosen.randrange(65536)) for _ in range(200)]
    (tmp_path / "runner.lua").write_text(MASK_RUNNER, encoding="utf-8")
    (tmp_path / "cases.txt").write_text("".join(f"{a} {b} {c}\n" for a, b, c in cases), encoding="ascii")
    command = [ensure_tool(lua, lua), str(tmp_path / "runner.lua"), str(PLUGIN), str(tmp_path / "cases.txt")]
    done = subprocess.run(command, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[0] == "23\t2\twritten"
    assert [int(line.split()[0]) for line in done.stdout.splitlines()] == [
        (current & and_mask) | (or_mask & ~and_mask & 0xFFFF) for current, and_mask, or_mask in cases]
