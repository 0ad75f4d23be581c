"""Time going backwards (review defect): a time-of-day log past midnight rolls to the next day; times that
truly go back (records out of order, a response stamped before its request, a clock step) are shown as
they are, the response warned, and left out of --stats' timing (response times, poll cycle, gaps,
turnaround, load), which says how many. Exact outputs, the engine and the Python stages
(VW3_PURE_PYTHON=1) alike (assert_same)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu
from test_timed_summary import assert_same, write_pcap

REQUEST, RESPONSE = rtu("01 03 0C82 0001"), rtu("01 03 02 0064")  # 01 03 0C 82 00 01 27 72, 01 03 02 00 64 B9 AF
T0 = 1_700_000_000 * 10**9
# Milliseconds from T0: a response stamped 20 ms before its request (frame 4, also earlier than frame 3),
# then the clock steps back 51 s (frame 7) and the bus goes on.
BACKWARDS_MS = [0, 10, 500, 480, 1000, 1012, -50000, -49989, -49500, -49491]
WARNING = "response stamped 20.0 ms before request #3: time goes backwards, left out of the response times"


def backwards_pcap(tmp_path: Path) -> Path:
    capture = tmp_path / "backwards.pcap"
    write_pcap(capture, [(REQUEST if k % 2 == 0 else RESPONSE, T0 + ms * 10**6) for k, ms in enumerate(BACKWARDS_MS)])
    return capture


MIDNIGHT = "23:59:59.900 01 03 0C 82 00 01 27 72\n00:00:00.010 01 03 02 00 64 B9 AF\n"


def test_time_of_day_past_midnight_is_the_next_day(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    dump = tmp_path / "mid.txt"
    dump.write_text(MIDNIGHT)
    out, _ = assert_same([str(dump)], monkeypatch)
    assert out == (
        "     1     0.000000   1 request   Read Holding Registers 3202  CRC ok\n"
        "     2     0.110000   1 response  Read Holding Registers 3202: 3202=100 [#1, 110.0 ms]  CRC ok\n"
    )  # was -86399.890000 ... [#1, -86399890.0 ms]
    out, _ = assert_same([str(dump), "-t", "ud"], monkeypatch)
    assert [line[6:33] for line in out.splitlines()] == [" 1970-01-01 23:59:59.900000", " 1970-01-02 00:00:00.010000"]
    out, _ = assert_same([str(dump), "--stats"], monkeypatch)
    assert "    1  3 Read Holding Registers      1  110.0   110.0  110.0  110.0\n" in out
    assert out.endswith(
        "Bus timing\n"
        "line: 19200 baud (assumed: --baud sets it), 11 bits a character, t3.5 2.005 ms, timeout 1000 ms\n"
        "load: 7.5 %\n"
        "inter-frame gaps: 1, 0 below t3.5; min 105.417 median 105.417 p95 105.417 max 105.417 ms\n"
        "  100-200 ms: 1\n"
        "slave  responses  median ms  p95 ms  max ms  margin to timeout ms  >90% of timeout\n"
        "    1          1      110.0   110.0   110.0                 894.6                0\n"
        "outages: none\n"
    )  # was load 100.0 %, gaps of -86399894.583 ms, a margin of 86400890.0 ms and an overlap warning


def test_traffic_log_past_midnight(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    log = tmp_path / "traffic.txt"
    log.write_text("Tx:000000-23:59:59.900-01 03 0C 82 00 01 27 72\nRx:000001-00:00:00.010-01 03 02 00 64 B9 AF\n"
                   "Tx:000002-00:00:00.500-01 03 0C 82 00 01 27 72\nRx:000003-00:00:00.509-01 03 02 00 64 B9 AF\n")
    out, _ = assert_same([str(log), "-t", "ud"], monkeypatch)
    assert out == (
        "     1 1970-01-01 23:59:59.900000   1 request   Read Holding Registers 3202  CRC ok\n"
        "     2 1970-01-02 00:00:00.010000   1 response  Read Holding Registers 3202: 3202=100 [#1, 110.0 ms]  CRC ok\n"
        "     3 1970-01-02 00:00:00.500000   1 request   Read Holding Registers 3202  CRC ok\n"
        "     4 1970-01-02 00:00:00.509000   1 response  Read Holding Registers 3202: 3202=100 [#3, 9.0 ms]  CRC ok\n"
    )


def test_time_of_day_a_little_earlier_goes_back(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Less than 12 hours earlier: the same day, time going back as the log says (not a day later)."""
    dump = tmp_path / "step.txt"
    dump.write_text("10:00:00.500 01 03 0C 82 00 01 27 72\n10:00:00.480 01 03 02 00 64 B9 AF\n"
                    "22:00:00.000 01 03 0C 82 00 01 27 72\n22:00:00.012 01 03 02 00 64 B9 AF\n")
    out, _ = assert_same([str(dump), "-t", "ud"], monkeypatch)
    assert out == (
        "     1 1970-01-01 10:00:00.500000   1 request   Read Holding Registers 3202  CRC ok\n"
        f"     2 1970-01-01 10:00:00.480000   1 response  Read Holding Registers 3202: 3202=100 [#1, -20.0 ms] "
        f"[warning: {WARNING.replace('#3', '#1')}]  CRC ok\n"
        "     3 1970-01-01 22:00:00.000000   1 request   Read Holding Registers 3202  CRC ok\n"
        "     4 1970-01-01 22:00:00.012000   1 response  Read Holding Registers 3202: 3202=100 [#3, 12.0 ms]  CRC ok\n"
    )
    # Seconds and date-times are absolute: kept as they are.
    dump.write_text("2024-05-01 23:59:59.900 01 03 0C 82 00 01 27 72\n2024-05-01T00:00:00.010 01 03 02 00 64 B9 AF\n")
    out, _ = assert_same([str(dump)], monkeypatch)
    assert "[#1, -86399890.0 ms] [warning: response stamped 86399890.0 ms before request #1" in out


def test_backwards_pcap_shown_as_it_is_and_warned(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (a nanosecond pcap: 9 decimals, as tshark shows them; a 13th character where the time is negative)
    out, engine_lines = assert_same([str(backwards_pcap(tmp_path))], monkeypatch)
    assert out == (
        "     1  0.000000000   1 request   Read Holding Registers 3202  CRC ok\n"
        "     2  0.010000000   1 response  Read Holding Registers 3202: 3202=100 [#1, 10.0 ms]  CRC ok\n"
        "     3  0.500000000   1 request   Read Holding Registers 3202  CRC ok\n"
        f"     4  0.480000000   1 response  Read Holding Registers 3202: 3202=100 [#3, -20.0 ms] [warning: {WARNING}]  CRC ok\n"
        "     5  1.000000000   1 request   Read Holding Registers 3202  CRC ok\n"
        "     6  1.012000000   1 response  Read Holding Registers 3202: 3202=100 [#5, 12.0 ms]  CRC ok\n"
        "     7 -50.000000000   1 request   Read Holding Registers 3202  CRC ok\n"
        "     8 -49.989000000   1 response  Read Holding Registers 3202: 3202=100 [#7, 11.0 ms]  CRC ok\n"
        "     9 -49.500000000   1 request   Read Holding Registers 3202  CRC ok\n"
        "    10 -49.491000000   1 response  Read Holding Registers 3202: 3202=100 [#9, 9.0 ms]  CRC ok\n"
    )
    assert engine_lines == 8  # the engine shows all but the answer stamped before its request (handed over)
    out, _ = assert_same([str(backwards_pcap(tmp_path)), "-V"], monkeypatch)
    assert f"    Request in frame: 3\n    Response time: -20.000 ms\n    Warning: {WARNING}\n" in out
    out, _ = assert_same([str(backwards_pcap(tmp_path)), "--json"], monkeypatch)
    frame = json.loads(out.splitlines()[3])
    assert (frame["request_frame"], frame["response_time"], frame["warnings"]) == (3, -0.02, [WARNING])


def test_backwards_pcap_left_out_of_stats(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out, _ = assert_same([str(backwards_pcap(tmp_path)), "--stats"], monkeypatch)
    assert out == """10 frames, 0 noise bytes in 0 runs

Device profiles
slave  profile  why
------------------------------------------------------------
    1  generic  no evidence of a device: spec semantics only

Traffic per slave and function
slave  function                  req  resp  exceptions  no reply  bad CRC
-------------------------------------------------------------------------
    1  3 Read Holding Registers    5     5                     0        0
req: requests, resp: normal responses, exceptions: code:count (hex code)

Response times (ms)
slave  function                  count  min  median   p95   max
---------------------------------------------------------------
    1  3 Read Holding Registers      4  9.0    10.5  12.0  12.0

Poll cycle (requests repeated 3 times or more)
slave  function                  addresses  count  period  jitter  misses
-------------------------------------------------------------------------
    1  3 Read Holding Registers  3202           5   500.0     0.0       0
period: median interval (ms); jitter: largest deviation from it (ms); misses: cycles skipped (intervals of 1.5 periods or more) + requests without a normal answer

Parameters
slave  address  code  reads  unreadable  writes  refused  last  changes
-----------------------------------------------------------------------
    1     3202            5           0       0        0  100         0

Bus timing
line: 19200 baud (assumed: --baud sets it), 11 bits a character, t3.5 2.005 ms, timeout 1000 ms
load: 2.8 % (busiest minute 1.7 % from 0.000000)
inter-frame gaps: 7, 0 below t3.5; min 4.417 median 7.420 p95 515.990 max 515.990 ms
  2-5 ms: 1, 5-10 ms: 3, 200-500 ms: 2, 500-1000 ms: 1
master turnaround (answer end to next request, ms): median 485.990 p95 515.990 max 515.990 (3)
slave  responses  median ms  p95 ms  max ms  margin to timeout ms  >90% of timeout
    1          4       10.5    12.0    12.0                 992.6                0
time going backwards, left out of the timing: 2 items stamped earlier than the item before, 1 response earlier than its request
outages: none
"""  # was: response times from -20.0 ms, jitter 51500.0 ms, gaps from -51016.010 ms, 5 overlaps warned
    out, _ = assert_same([str(backwards_pcap(tmp_path)), "--stats", "--json"], monkeypatch)
    report = json.loads(out)
    bus = report["bus"]
    assert bus["backwards"] == {"items": 2, "responses": 1}
    assert (bus["span"], bus["load"], bus["overlaps"], bus["gaps"]["count"], bus["gaps"]["min"]) == (
        1.553604, 0.027657, 0, 7, 0.004417)  # the stretches 0..0.5046, 0.48..1.016, -50..-49.487 s
    assert bus["responses"] == [{"slave": 1, "count": 4, "min": 0.009, "median": 0.0105, "p95": 0.012, "max": 0.012,
                                 "margin": 0.992583, "close_to_timeout": 0}]
    assert report["functions"][0]["response_time"] == {"count": 4, "min": 0.009, "median": 0.0105, "p95": 0.012,
                                                       "max": 0.012}
    poll = report["poll_cycle"][0]
    assert (poll["period"], poll["jitter"], poll["skipped"]) == (0.5, 0.0, 0)


def test_no_backwards_line_when_time_goes_forward(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "forward.pcap"
    write_pcap(capture, [(REQUEST if k % 2 == 0 else RESPONSE, T0 + k * 10**7) for k in range(6)])
    out, _ = assert_same([str(capture), "--stats"], monkeypatch)
    assert "backwards" not in out and "warning" not in out
    out, _ = assert_same([str(capture), "--stats", "--json"], monkeypatch)
    assert json.loads(out)["bus"]["backwards"] == {"items": 0, "responses": 0}


def test_days_rule() -> None:
    """hexdump.Days: more than 12 hours earlier than the time of day before is the next day (each midnight
    of a log of several days); 12 hours earlier or less is the same day; absolute times pass as they are."""
    from dissector.model import Stamp
    from dissector.sources.hexdump import DAY_NS, Days, TimeOfDay

    hour = 3600 * 10**9
    days = Days()
    placed = [days.place(TimeOfDay(h * hour)).ns for h in (23, 1, 13, 1, 0)]  # type: ignore[union-attr]
    assert placed == [23 * hour, DAY_NS + hour, DAY_NS + 13 * hour, DAY_NS + hour, DAY_NS]
    assert [days.place(TimeOfDay(h * hour)).ns for h in (12, 23, 10)] == [  # type: ignore[union-attr]
        DAY_NS + 12 * hour, DAY_NS + 23 * hour, 2 * DAY_NS + 10 * hour]
    assert type(days.place(TimeOfDay(0))) is Stamp
    absolute = Stamp(1_700_000_000 * 10**9)
    assert days.place(absolute) is absolute and days.place(None) is None
