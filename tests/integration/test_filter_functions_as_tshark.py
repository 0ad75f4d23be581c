"""Functions, arithmetic, character constants and times select the frames tshark 4.0.17 selects with the
plugin, and what tshark refuses vw3-decode refuses (exit 2, one line): a real tshark, two passes, on the
shipped captures (tests/unit/test_filter_functions.py holds the same frames as numbers); `comment` as
tshark's frame.comment on a pcapng whose records carry packet comments."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, assert_same_frames, run_tshark

from dissector.render.pcapngwriter import PcapngWriter

CASES = [
    # (capture, vw3-decode -Y, tshark -Y with the plugin)
    ("noisy_bus.pcap", "len(raw) == 8", "len(frame) == 8"),
    ("noisy_bus.pcap", "len(slave) == 1", "len(vw3.slave) == 1"),
    ("noisy_bus.pcap", "len(crc_ok) == 0", "len(vw3.crc_ok) == 0"),
    ("noisy_bus.pcap", "len(value) == 2", "len(vw3.reg.value) == 2"),
    ("noisy_bus.pcap", 'upper(function_name) contains "READ"', 'upper(vw3.function_name) contains "READ"'),
    ("noisy_bus.pcap", 'lower(function_name)[0:4] == "read"', 'lower(vw3.function_name)[0:4] == "read"'),
    ("noisy_bus.pcap", "count(value) == 2", "count(vw3.reg.value) == 2"),
    ("noisy_bus.pcap", "count(address) == 2", "count(vw3.reg.address) == 2"),
    ("noisy_bus.pcap", 'string(slave) == "12"', 'string(vw3.slave) == "12"'),
    ("noisy_bus.pcap", "min(slave, 10) == 10", "min(vw3.slave, 10) == 10"),
    ("noisy_bus.pcap", "max(value) > 100", "max(vw3.reg.value) > 100"),
    ("noisy_bus.pcap", "abs(slave - 20) == 8", "abs(vw3.slave - 20) == 8"),
    ("noisy_bus.pcap", "abs(response_time - 1) > 0.99", "abs(vw3.response_time - 1) > 0.99"),
    ("noisy_bus.pcap", "slave + 1 == 13", "vw3.slave + 1 == 13"),
    ("noisy_bus.pcap", "slave == 2 * 6 + 0", "vw3.slave == 2 * 6 + 0"),
    ("noisy_bus.pcap", "slave -1 == 11", "vw3.slave -1 == 11"),
    ("noisy_bus.pcap", "{slave - 20} < 0", "{vw3.slave - 20} < 0"),
    ("noisy_bus.pcap", "{slave % 5} == 2", "{vw3.slave % 5} == 2"),
    ("noisy_bus.pcap", "slave & 4 + 1 == 5", "vw3.slave & 4 + 1 == 5"),
    ("noisy_bus.pcap", "{slave - 12}", "{vw3.slave - 12}"),
    ("noisy_bus.pcap", "{slave / 0} == 1", "{vw3.slave / 0} == 1"),
    ("noisy_bus.pcap", "value - address < 0", "vw3.reg.value - vw3.reg.address < 0"),
    ("noisy_bus.pcap", "response_time + 1 > 1.01", "vw3.response_time + 1 > 1.01"),
    ("noisy_bus.pcap", "time_relative > 1.5", "frame.time_relative > 1.5"),
    ("noisy_bus.pcap", "time_relative + 1 > 2.5", "frame.time_relative + 1 > 2.5"),
    ("noisy_bus.pcap", "time_delta > 0.05", "frame.time_delta > 0.05"),
    ("noisy_bus.pcap", "time > 1767225601.5", "frame.time_epoch > 1767225601.5"),
    ("noisy_bus.pcap", "slave == '\\x0c'", "vw3.slave == '\\x0c'"),
    ("noisy_bus.pcap", "raw[0] == '\\x0c'", "frame[0] == '\\x0c'"),
    ("noisy_bus.pcap", "function_name contains 'R'", "vw3.function_name contains 'R'"),
    ("noisy_bus.pcap", "crc_ok == '\\x01'", "vw3.crc_ok == '\\x01'"),
    ("noisy_bus.pcap", "slave != function", "vw3.slave != vw3.function"),
    ("p38_protection.pcap", "len(code) != 4", "len(vw3.reg.code) != 4"),
    ("atv71_commissioning.pcap", 'string(scaled) == "2.1000000000000001"',
     'string(vw3.reg.scaled) == "2.1000000000000001"'),
    ("atv71_commissioning.pcap", "value + 1 === 3", "vw3.reg.value + 1 === 3"),
]

REFUSED = [
    # (vw3-decode -Y, tshark -Y): both refuse
    ("len(slave)", "len(vw3.slave)"),
    ("LEN(slave) == 1", "LEN(vw3.slave) == 1"),
    ('upper(slave) == "12"', 'upper(vw3.slave) == "12"'),
    ("min(value, slave) == 0", "min(vw3.reg.value, vw3.slave) == 0"),
    ("{slave * 1.5} == 18", "{vw3.slave * 1.5} == 18"),
    ("{response_time * 2} > 0.01", "{vw3.response_time * 2} > 0.01"),
    ("slave == 256", "vw3.slave == 256"),
    ("slave == 12 + 'a'", "vw3.slave == 12 + 'a'"),
    ("time_relative > 1e-3", "frame.time_relative > 1e-3"),
    ("time_relative & 1", "frame.time_relative & 1"),
    ("slave == '\\x0c1'", "vw3.slave == '\\x0c1'"),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_the_filter_selects_the_frames_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    path = ROOT / "captures" / capture
    assert_same_frames(path, ours, wiresharks)


@pytest.mark.parametrize(("ours", "wiresharks"), REFUSED)
def test_refused_where_tshark_refuses(ours: str, wiresharks: str) -> None:
    path = ROOT / "captures" / "noisy_bus.pcap"
    command = [sys.executable, "-m", "dissector", "-Y", ours, str(path)]
    mine = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert (mine.returncode, mine.stdout) == (2, "")
    assert mine.stderr.startswith("vw3-decode: ") and "Traceback" not in mine.stderr
    result = run_tshark(path, "-Y", wiresharks)
    assert result.returncode != 0 and result.stdout == ""


COMMENTS = [
    # (vw3-decode -Y, tshark -Y) on a pcapng whose records carry packet comments (opt_comment)
    ("comment", "frame.comment"),
    ("!comment", "!frame.comment"),
    ('comment contains "pump"', 'frame.comment contains "pump"'),
    ('comment matches "^AGAIN"', 'frame.comment matches "^AGAIN"'),
    ('comment == "again"', 'frame.comment == "again"'),
    ('comment != "again"', 'frame.comment != "again"'),
    ("count(comment) == 2", "count(frame.comment) == 2"),
    ("len(comment) > 6", "len(frame.comment) > 6"),
    ('upper(comment) contains "PUMP"', 'upper(frame.comment) contains "PUMP"'),
]


@pytest.mark.parametrize(("ours", "wiresharks"), COMMENTS)
def test_comment_selects_as_frame_comment(tmp_path: Path, ours: str, wiresharks: str) -> None:
    path = tmp_path / "commented.pcapng"
    request, answer = bytes.fromhex("0C0320D000030EEF"), bytes.fromhex("0C0306000100020003A5E4")
    with path.open("wb") as stream:
        writer = PcapngWriter(stream, flush=False)
        for data, time, comments in [(request, 0.0, ["pump 2 check"]), (answer, 0.01, ["answer", "again"]),
                                     (request, 1.0, None), (answer, 1.01, ["done"])]:
            writer.write(data, time, comments)
    assert_same_frames(path, ours, wiresharks)
