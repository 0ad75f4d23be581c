"""--stats and --watch of a pcapng with packets from several interfaces (Wireshark capturing two vw3 extcap
lines at once): each interface is its own bus (render/buses.py), counted under its title. Before, both
were 'counted as one bus, as mergecap would join them': slave 12 of /dev/pts/0 and of /dev/pts/1 one
device, 8401 read 4 times with 2 changes (3 on one bus, 2 then 3 on the other), --watch
'12 8401 3 -> 2' where no value changed. --report: a section a bus (test_bus_report.py).
"""
from __future__ import annotations

import json
import struct
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER_A = bytes.fromhex("0C030680000003000217E4")  # 8400 16#8000, 8401=3, 8402=2
ANSWER_B = bytes.fromhex("0C0306000100020003A5E4")  # 8400=1, 8401=2, 8402=3
ANSWER_B2 = bytes.fromhex("0C0306000100030003F424")  # 8401 now 3
# /dev/pts/0: two polls answered in 8 ms. /dev/pts/1: answered in 9 and 12 ms, 8401 changes, then a request
# unanswered (the next comes 200 ms later) and one the capture ends with (not known whether it was answered).
PACKETS = [(0, 0, REQUEST), (1, 2000, REQUEST), (0, 8000, ANSWER_A), (1, 11_000, ANSWER_B),
           (0, 200_000, REQUEST), (1, 202_000, REQUEST), (0, 208_000, ANSWER_A), (1, 214_000, ANSWER_B2),
           (1, 402_000, REQUEST), (1, 602_000, REQUEST)]


def _block(kind: int, body: bytes) -> bytes:
    total = 12 + len(body)
    return struct.pack("<II", kind, total) + body + struct.pack("<I", total)


def _option(code: int, text: str) -> bytes:
    value = text.encode()
    return struct.pack("<HH", code, len(value)) + value + b"\0" * (-len(value) % 4)


def _pcapng(names: list[str], packets: list[tuple[int, int, bytes]]) -> bytes:
    """Interfaces (if_name) and packets (interface, microseconds, bytes), as test_pcapng_interfaces."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    for name in names:
        options = _option(2, name) + _option(3, f"serial port {name}, 19200 baud") + b"\0" * 4
        out += _block(1, struct.pack("<HHI", 147, 0, 0) + options)
    for interface, micros, data in packets:
        stamp = 1_767_225_600_000_000 + micros
        out += _block(6, struct.pack("<IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data))
                      + data + b"\0" * (-len(data) % 4))
    return out


@pytest.fixture
def two(tmp_path: Path) -> Path:
    path = tmp_path / "two.pcapng"
    path.write_bytes(_pcapng(["/dev/pts/0", "/dev/pts/1"], PACKETS))
    return path


def _run(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> tuple[int, str, str]:
    use_engine(monkeypatch, pure)
    return run_cli(argv)


TRAFFIC = """\
Traffic per slave and function
slave  function                  req  resp  exceptions  no reply  bad CRC
-------------------------------------------------------------------------
{row}
req: requests, resp: normal responses, exceptions: code:count (hex code)
"""
LINE = "line: 19200 baud (pcapng interface description), 11 bits a character, t3.5 2.005 ms, timeout 1000 ms"
RESPONSES = "slave  responses  median ms  p95 ms  max ms  margin to timeout ms  >90% of timeout"


@BOTH
def test_stats_counts_each_interface_as_its_own_bus(two: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    status, out, err = _run(["--stats", "-n", str(two)], monkeypatch, pure)
    assert (status, err) == (0, "")
    assert out == f"""\
==> {two}: /dev/pts/0 <==
4 frames, 0 noise bytes in 0 runs

{TRAFFIC.format(row="   12  3 Read Holding Registers    2     2                     0        0")}
Response times (ms)
slave  function                  count  min  median  p95  max
-------------------------------------------------------------
   12  3 Read Holding Registers      2  8.0     8.0  8.0  8.0

Parameters
slave         address  code  reads  unreadable  writes  refused  last       changes
-----------------------------------------------------------------------------------
   12  8400..8402 (3)            2           0       0        0  (various)        0
  all        3 params            6           0       0        0                   0

Bus timing
{LINE}
load: 10.2 %
inter-frame gaps: 3, 0 below t3.5; min 3.417 median 3.420 p95 185.698 max 185.698 ms
  2-5 ms: 2, 100-200 ms: 1
master turnaround (answer end to next request, ms): median 185.698 p95 185.698 max 185.698 (1)
{RESPONSES}
   12          2        8.0     8.0     8.0                 996.6                0
outages: none

==> {two}: /dev/pts/1 <==
6 frames, 0 noise bytes in 0 runs

{TRAFFIC.format(row="   12  3 Read Holding Registers    4     2                     1        0")}
Response times (ms)
slave  function                  count  min  median   p95   max
---------------------------------------------------------------
   12  3 Read Holding Registers      2  9.0    10.5  12.0  12.0

Poll cycle (requests repeated 3 times or more)
slave  function                  addresses       count  period  jitter  misses
------------------------------------------------------------------------------
   12  3 Read Holding Registers  8400..8402 (3)      4   200.0     0.0       1
period: median interval (ms); jitter: largest deviation from it (ms); misses: cycles skipped (intervals of 1.5 \
periods or more) + requests without a normal answer

Parameters
slave   address  code  reads  unreadable  writes  refused  last  changes
------------------------------------------------------------------------
   12      8400            2           0       0        0  1           0
   12      8401            2           0       0        0  3           1
   12      8402            2           0       0        0  3           0
  all  3 params            6           0       0        0              1

Bus timing
{LINE}
load: 5.1 %
inter-frame gaps: 5, 0 below t3.5; min 4.416 median 181.700 p95 195.417 max 195.417 ms
  2-5 ms: 1, 5-10 ms: 1, 100-200 ms: 3
master turnaround (answer end to next request, ms): median 183.199 p95 184.698 max 184.698 (2)
{RESPONSES}
   12          2       10.5    12.0    12.0                 992.6                0
outages: none
"""


@BOTH
def test_stats_json_is_one_line_a_bus(two: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    status, out, err = _run(["--stats", "--json", str(two)], monkeypatch, pure)
    assert (status, err) == (0, "")
    buses = [json.loads(line) for line in out.splitlines()]
    assert [list(bus)[:2] for bus in buses] == [["file", "frames"]] * 2
    assert "merged_captures" not in buses[0] and "merged_captures" not in buses[1]
    summary = [(bus["file"], bus["frames"],
                [(row["slave"], row["requests"], row["unanswered"], row["response_time"]["count"])
                 for row in bus["functions"]],
                [(row["address"], row["reads"], row["unreadable"], row["last"], row["changes"])
                 for row in bus["parameters"]],
                [(row["slave"], row["count"], row["max"]) for row in bus["bus"]["responses"]],
                [(row["slave"], row["requests"], row["first_frame"]) for row in bus["bus"]["outages"]],
                [(choice["slave"], choice["profile"]) for choice in bus["profiles"]]) for bus in buses]
    assert summary == [
        (f"{two}: /dev/pts/0", 4, [(12, 2, 0, 2)],
         [(8400, 0, 2, None, 0), (8401, 2, 0, 3, 0), (8402, 2, 0, 2, 0)], [(12, 2, 0.008)], [],
         [(12, "atv71")]),  # 16#8000 at 8400: its device's non-existent parameter
        (f"{two}: /dev/pts/1", 6, [(12, 4, 1, 2)],
         [(8400, 2, 0, 1, 0), (8401, 2, 0, 3, 1), (8402, 2, 0, 3, 0)], [(12, 2, 0.012)], [],
         [(12, "generic")]),  # its own slave 12: no evidence of the first bus's device
    ]


@BOTH
def test_watch_follows_each_bus(two: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    status, out, err = _run(["--watch", "8401", str(two)], monkeypatch, pure)
    assert (status, err) == (0, "")
    # (from the file's first packet, /dev/pts/0's, as tshark's frame.time_relative)
    assert out == f"==> {two}: /dev/pts/0 <==\n\n==> {two}: /dev/pts/1 <==\n     4     0.214000  12 8401 2 -> 3\n"
    status, out, err = _run(["--watch", "8401", "--json", str(two)], monkeypatch, pure)
    assert (status, err) == (0, "")
    assert [json.loads(line) for line in out.splitlines()] == [{
        "time": 1767225600.214, "time_relative": 0.214, "frame": 4, "slave": 12, "address": 8401, "code": None,
        "old": "2", "new": "3", "unit": None, "file": f"{two}: /dev/pts/1"}]


@BOTH
def test_ring_files_join_each_interface(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    # Two files of one two-line capture: each interface is one bus over both files, as mergecap joins them.
    first, second = tmp_path / "a_00001.pcapng", tmp_path / "a_00002.pcapng"
    first.write_bytes(_pcapng(["/dev/pts/0", "/dev/pts/1"], PACKETS[:4]))
    second.write_bytes(_pcapng(["/dev/pts/0", "/dev/pts/1"], [(bus, micros + 1_000_000, data)
                                                             for bus, micros, data in PACKETS[4:8]]))
    status, out, err = _run(["--stats", "-n", str(first), str(second)], monkeypatch, pure)
    assert (status, err) == (0, "")
    merged = ("captures counted as one bus, as mergecap would join them (decode each alone for its own traffic "
              "and timing)")
    assert [line for line in out.splitlines() if "pts" in line or "counted as one" in line] == [
        f"==> {first}: /dev/pts/0, {second}: /dev/pts/0 <==",
        f"4 frames, 0 noise bytes in 0 runs, from 2 {merged}: {first}: /dev/pts/0, {second}: /dev/pts/0",
        "2 captures counted as one bus: gaps and turnarounds restart at each capture, the load is over the span "
        "from the first item to the last",
        f"==> {first}: /dev/pts/1, {second}: /dev/pts/1 <==",
        f"4 frames, 0 noise bytes in 0 runs, from 2 {merged}: {first}: /dev/pts/1, {second}: /dev/pts/1",
        "2 captures counted as one bus: gaps and turnarounds restart at each capture, the load is over the span "
        "from the first item to the last",
    ]
