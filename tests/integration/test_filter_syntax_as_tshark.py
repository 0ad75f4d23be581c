"""The syntax of -Y as tshark 4.0.17 reads it, against a real tshark running the plugin (two passes) on the
shipped captures: what tshark takes selects the same frames, what it refuses vw3-decode refuses (exit 2,
a message, the filter and a caret under the token, no traceback). Session 56's filter hunt: sets
(members separated by commas, a range inside braces); slices (blanks inside, C numbers, a slice of a
slice, a length that is not positive and first-last with first >= last refused); raw strings; true/false fields; any/all quantifiers; negative numbers; layers (#); a byte written 0xhh."""
from __future__ import annotations

import subprocess
import sys

import pytest

from lua_harness import ROOT, assert_same_frames, run_tshark

CASES = [
    # (capture, vw3-decode -Y, tshark -Y with the plugin)
    ("noisy_bus.pcap", "slave in {12,13}", "vw3.slave in {12,13}"),
    ("noisy_bus.pcap", "slave in {12 ,13}", "vw3.slave in {12 ,13}"),
    ("noisy_bus.pcap", "slave in {10..12, 13}", "vw3.slave in {10..12, 13}"),
    ("noisy_bus.pcap", "slave in {10 .. 12}", "vw3.slave in {10 .. 12}"),
    ("atv71_commissioning.pcap", "scaled in {-200..50}", "vw3.reg.scaled in {-200..50}"),
    ("atv71_commissioning.pcap", 'code in {"FR1", "CD1"}', 'vw3.reg.code in {"FR1", "CD1"}'),
    ("noisy_bus.pcap", "raw[ 0 : 2 ] == 0c:03", "frame[ 0 : 2 ] == 0c:03"),
    ("noisy_bus.pcap", "raw[0 :2] == 0c:03 or raw[4-5] == 00:03", "frame[0 :2] == 0c:03 or frame[4-5] == 00:03"),
    ("noisy_bus.pcap", "raw[0x1] == 03", "frame[0x1] == 03"),
    ("noisy_bus.pcap", "raw[1:0x2] == 0300", "frame[1:0x2] == 0300"),
    ("noisy_bus.pcap", "raw[-0x2:] == 27:5a", "frame[-0x2:] == 27:5a"),
    ("noisy_bus.pcap", "raw[0:2][1] == 03", "frame[0:2][1] == 03"),
    ("noisy_bus.pcap", "raw[1:] [0:2] == 03:08", "frame[1:] [0:2] == 03:08"),
    ("noisy_bus.pcap", "raw[0-1] == 0c03", "frame[0-1] == 0c03"),
    # raw strings keep their backslashes
    ("noisy_bus.pcap", 'function_name matches r"^read\\sh"', 'vw3.function_name matches r"^read\\sh"'),
    ("noisy_bus.pcap", 'function_name matches R"Read\\x20Holding"', 'vw3.function_name matches R"Read\\x20Holding"'),
    ("noisy_bus.pcap", 'function_name contains r"\\x52"', 'vw3.function_name contains r"\\x52"'),
    ("noisy_bus.pcap", 'function_name matches r"Read\\"H"', 'vw3.function_name matches r"Read\\"H"'),
    ("noisy_bus.pcap", 'function_name in {r"Read Holding Registers"}', 'vw3.function_name in {r"Read Holding Registers"}'),
    # true/false fields: a whole number is true unless 0, true/false quoted or not, ordered (false first)
    ("noisy_bus.pcap", "crc_ok == 2", "vw3.crc_ok == 2"),
    ("noisy_bus.pcap", "crc_ok == 0x10 and slave == 12", "vw3.crc_ok == 0x10 and vw3.slave == 12"),
    ("noisy_bus.pcap", "crc_ok == 0b10", "vw3.crc_ok == 0b10"),
    ("noisy_bus.pcap", 'crc_ok == "TRUE"', 'vw3.crc_ok == "TRUE"'),
    ("noisy_bus.pcap", 'crc_ok == "false"', 'vw3.crc_ok == "false"'),
    ("noisy_bus.pcap", "crc_ok == '\\0'", "vw3.crc_ok == '\\0'"),
    ("noisy_bus.pcap", "crc_ok < 1", "vw3.crc_ok < 1"),
    ("noisy_bus.pcap", "crc_ok >= false", "vw3.crc_ok >= false"),
    ("noisy_bus.pcap", "crc_ok > true", "vw3.crc_ok > true"),
    ("noisy_bus.pcap", "crc_ok in {0..0}", "vw3.crc_ok in {0..0}"),
    ("noisy_bus.pcap", "crc_ok in {2..3}", "vw3.crc_ok in {2..3}"),
    ("noisy_bus.pcap", "crc_ok != 2", "vw3.crc_ok != 2"),
    ("noisy_bus.pcap", "crc_ok === 4294967296", "vw3.crc_ok === 4294967296"),
    ("noisy_bus.pcap", "broadcast == 7", "vw3.broadcast == 7"),
    ("noisy_bus.pcap", "max(crc_ok) == 1", "max(vw3.crc_ok) == 1"),
    # quantifiers: any / all before a relation; a masked != is all_ne, as every !=
    ("atv71_commissioning.pcap", "all value == 2", "all vw3.reg.value == 2"),
    ("atv71_commissioning.pcap", "any value === 2", "any vw3.reg.value === 2"),
    ("atv71_commissioning.pcap", "any value != 2", "any vw3.reg.value != 2"),
    ("atv71_commissioning.pcap", "all value !== 2", "all vw3.reg.value !== 2"),
    ("atv71_commissioning.pcap", "all value > 2", "all vw3.reg.value > 2"),
    ("atv71_commissioning.pcap", "all value >= 0", "all vw3.reg.value >= 0"),
    ("atv71_commissioning.pcap", "all value in {2, 3}", "all vw3.reg.value in {2, 3}"),
    ("atv71_commissioning.pcap", "all value in {2..3}", "all vw3.reg.value in {2..3}"),
    ("atv71_commissioning.pcap", "all address in {8400..8500, 3201}", "all vw3.reg.address in {8400..8500, 3201}"),
    ("atv71_commissioning.pcap", 'all code matches "^C"', 'all vw3.reg.code matches "^C"'),
    ("atv71_commissioning.pcap", 'all code contains "C"', 'all vw3.reg.code contains "C"'),
    ("atv71_commissioning.pcap", 'any notes contains "a"', 'any vw3.note contains "a"'),
    ("atv71_commissioning.pcap", 'all notes contains "a"', 'all vw3.note contains "a"'),
    ("atv71_commissioning.pcap", "all value & 1 == 1", "all vw3.reg.value & 1 == 1"),
    ("atv71_commissioning.pcap", "value & 1 != 1", "vw3.reg.value & 1 != 1"),
    ("atv71_commissioning.pcap", "value & 1 === 0", "vw3.reg.value & 1 === 0"),
    ("atv71_commissioning.pcap", "all value + 1 > 3", "all vw3.reg.value + 1 > 3"),
    ("atv71_commissioning.pcap", "all len(code) == 4", "all len(vw3.reg.code) == 4"),
    ("atv71_commissioning.pcap", "all value > slave", "all vw3.reg.value > vw3.slave"),
    ("atv71_commissioning.pcap", 'not all value == 2 and any code == "CHCF"',
     'not all vw3.reg.value == 2 and any vw3.reg.code == "CHCF"'),
    # a negative number compares with no unsigned field: only != and === (and all ...) hold
    ("noisy_bus.pcap", "slave > -1", "vw3.slave > -1"),
    ("noisy_bus.pcap", "slave >= -1", "vw3.slave >= -1"),
    ("noisy_bus.pcap", "slave != -1", "vw3.slave != -1"),
    ("noisy_bus.pcap", "slave ~= -1", "vw3.slave ~= -1"),
    ("noisy_bus.pcap", "slave === -1", "vw3.slave === -1"),
    ("noisy_bus.pcap", "slave in {-1, 12}", "vw3.slave in {-1, 12}"),
    ("noisy_bus.pcap", "slave in {-1..20}", "vw3.slave in {-1..20}"),
    ("noisy_bus.pcap", "frame > -1", "vw3.item > -1"),
    ("atv71_commissioning.pcap", "value > -1", "vw3.reg.value > -1"),
    ("atv71_commissioning.pcap", "value != -1", "vw3.reg.value != -1"),
    ("atv71_commissioning.pcap", "value === -1", "vw3.reg.value === -1"),
    ("atv71_commissioning.pcap", "all value > -1", "all vw3.reg.value > -1"),
    ("atv71_commissioning.pcap", "address > -1", "vw3.reg.address > -1"),
    ("atv71_commissioning.pcap", "scaled > -1", "vw3.reg.scaled > -1"),
    # layers: an item is one vw3 layer, so #1 is the field and any other layer none
    ("noisy_bus.pcap", "slave#1 == 12", "vw3.slave#1 == 12"),
    ("noisy_bus.pcap", "slave #1 != 12", "vw3.slave #1 != 12"),
    ("noisy_bus.pcap", "slave#2 == 12 or slave#0 == 12", "vw3.slave#2 == 12 or vw3.slave#0 == 12"),
    ("noisy_bus.pcap", "slave#[1-2] == 12", "vw3.slave#[1-2] == 12"),
    ("noisy_bus.pcap", "slave#[2-3] == 12", "vw3.slave#[2-3] == 12"),
    ("noisy_bus.pcap", "slave#[-1] == 12", "vw3.slave#[-1] == 12"),
    ("noisy_bus.pcap", "slave#1", "vw3.slave#1"),
    ("noisy_bus.pcap", "!slave#2", "!vw3.slave#2"),
    ("noisy_bus.pcap", "raw#1[0] == 0c", "frame#1[0] == 0c"),
    ("noisy_bus.pcap", "slave#1 == function", "vw3.slave#1 == vw3.function"),
    ("noisy_bus.pcap", "len(slave#1) == 1", "len(vw3.slave#1) == 1"),
    ("atv71_commissioning.pcap", "value#1 == 2", "vw3.reg.value#1 == 2"),
    # a byte written 0xhh
    ("noisy_bus.pcap", "raw[0] == 0x0c", "frame[0] == 0x0c"),
    ("noisy_bus.pcap", "raw[0] > 0x0b", "frame[0] > 0x0b"),
    ("noisy_bus.pcap", "raw contains 0X0C", "frame contains 0X0C"),
    ("noisy_bus.pcap", "raw[0:2] & 0x0f", "frame[0:2] & 0x0f"),
]

REFUSED = [
    # (capture, vw3-decode -Y, tshark -Y): both refuse
    ("noisy_bus.pcap", "slave in {12 13}", "vw3.slave in {12 13}"),
    ("noisy_bus.pcap", "slave in {10..12 13}", "vw3.slave in {10..12 13}"),
    ("noisy_bus.pcap", "slave in {10..12,13 14}", "vw3.slave in {10..12,13 14}"),
    ("atv71_commissioning.pcap", 'code in {"FR1" "CD1"}', 'vw3.reg.code in {"FR1" "CD1"}'),
    ("noisy_bus.pcap", "slave in {12,}", "vw3.slave in {12,}"),
    ("noisy_bus.pcap", "slave in {,12}", "vw3.slave in {,12}"),
    ("noisy_bus.pcap", "slave in {12,,13}", "vw3.slave in {12,,13}"),
    ("noisy_bus.pcap", "slave in {}", "vw3.slave in {}"),
    ("noisy_bus.pcap", "slave in {12", "vw3.slave in {12"),
    ("noisy_bus.pcap", "slave in 10..12", "vw3.slave in 10..12"),
    ("noisy_bus.pcap", "slave in 12", "vw3.slave in 12"),
    ("noisy_bus.pcap", "raw[2:0] == 0c", "frame[2:0] == 0c"),
    ("noisy_bus.pcap", "raw[:0] == 0c", "frame[:0] == 0c"),
    ("noisy_bus.pcap", "raw[:-1] == 0c", "frame[:-1] == 0c"),
    ("noisy_bus.pcap", "raw[1-1] == 03", "frame[1-1] == 03"),
    ("noisy_bus.pcap", "raw[2-1] == 03", "frame[2-1] == 03"),
    ("noisy_bus.pcap", "raw[2147483648] == 0c", "frame[2147483648] == 0c"),
    ("noisy_bus.pcap", "raw[0:2,] == 0c03", "frame[0:2,] == 0c03"),
    ("noisy_bus.pcap", "raw[1e0] == 0c", "frame[1e0] == 0c"),
    ("noisy_bus.pcap", "raw[08] == 0c", "frame[08] == 0c"),
    ("noisy_bus.pcap", 'function_name matches r"Read\\"', 'vw3.function_name matches r"Read\\"'),
    ("noisy_bus.pcap", 'function_name matches r "Read"', 'vw3.function_name matches r "Read"'),
    ("noisy_bus.pcap", 'crc_ok == "1"', 'vw3.crc_ok == "1"'),
    ("noisy_bus.pcap", "crc_ok == -1", "vw3.crc_ok == -1"),
    ("noisy_bus.pcap", "crc_ok == 1.5", "vw3.crc_ok == 1.5"),
    ("noisy_bus.pcap", "crc_ok == 1e0", "vw3.crc_ok == 1e0"),
    ("noisy_bus.pcap", "crc_ok == yes", "vw3.crc_ok == yes"),
    ("noisy_bus.pcap", "crc_ok == 99999999999999999999", "vw3.crc_ok == 99999999999999999999"),
    ("noisy_bus.pcap", "crc_ok & 1", "vw3.crc_ok & 1"),
    ("noisy_bus.pcap", "crc_ok contains 1", "vw3.crc_ok contains 1"),
    ("atv71_commissioning.pcap", "all value", "all vw3.reg.value"),
    ("atv71_commissioning.pcap", "any value & 2", "any vw3.reg.value & 2"),
    ("atv71_commissioning.pcap", "all (value == 2)", "all (vw3.reg.value == 2)"),
    ("atv71_commissioning.pcap", "all not value == 2", "all not vw3.reg.value == 2"),
    ("atv71_commissioning.pcap", "all all value == 2", "all all vw3.reg.value == 2"),
    ("atv71_commissioning.pcap", "ALL value == 2", "ALL vw3.reg.value == 2"),
    ("atv71_commissioning.pcap", "slave == any", "vw3.slave == any"),
    ("noisy_bus.pcap", "slave >= -300", "vw3.slave >= -300"),
    ("noisy_bus.pcap", "slave#-1 == 12", "vw3.slave#-1 == 12"),
    ("noisy_bus.pcap", "slave# == 12", "vw3.slave# == 12"),
    ("noisy_bus.pcap", "raw[0] == 0xc", "frame[0] == 0xc"),
    ("noisy_bus.pcap", "raw[0:2] == 0x0c03", "frame[0:2] == 0x0c03"),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_the_filter_selects_the_frames_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    assert_same_frames(ROOT / "captures" / capture, ours, wiresharks)


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), REFUSED)
def test_refused_with_a_caret_where_tshark_refuses(capture: str, ours: str, wiresharks: str) -> None:
    path = ROOT / "captures" / capture
    mine = subprocess.run([sys.executable, "-m", "dissector", "-Y", ours, str(path)],
                          capture_output=True, text=True, timeout=300)
    assert (mine.returncode, mine.stdout) == (2, "")
    lines = mine.stderr.splitlines()
    assert lines[0].startswith("vw3-decode: ") and "Traceback" not in mine.stderr
    assert lines[1:] == [f"  {ours}", "  " + " " * (len(lines[2]) - 3) + "^"]
    result = run_tshark(path, "-Y", wiresharks)
    assert result.returncode != 0 and result.stdout == ""
    assert "unexpected" in result.stderr.lower() or "^" in result.stderr
