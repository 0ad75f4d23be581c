"""The poll cycle of the sample captures against the pcap timestamps read straight from the files."""
from __future__ import annotations

import statistics
import struct

from dissector.devices.build import build_annotator
from dissector.model import Frame, Kind
from dissector.pipeline import dissect
from dissector.render.pollcycle import PollCycle, describe_key
from dissector.render.stats import StatsCollector
from dissector.sources.reader import open_source

from conftest import ROOT

CAPTURES = ROOT / "captures"


def poll_rows(name: str) -> list[dict]:
    stats = StatsCollector()
    for item in dissect(open_source(str(CAPTURES / name)), annotate=build_annotator(["atv71"], [])):
        stats.add(item)
    return stats.poll.report()


def records(name: str) -> list[tuple[int, bytes]]:
    data = (CAPTURES / name).read_bytes()
    out, offset = [], 24
    while offset < len(data):
        seconds, micros, length, _ = struct.unpack_from("<IIII", data, offset)
        out.append((seconds * 1_000_000 + micros, data[offset + 16 : offset + 16 + length]))
        offset += 16 + length
    return out


def test_commissioning_io_scanner_cycle() -> None:
    rows = poll_rows("atv71_commissioning.pcap")
    assert [(r["slave"], r["function"], describe_key(r), r["count"]) for r in rows] == [
        (2, 6, "8401", 3),
        (2, 23, "read 3201..3202 (2), write 8501..8502 (2)", 40),
    ]
    scan = rows[1]
    # Oracle: FC23 requests are the 17-byte records with function 0x17; intervals from the pcap's microseconds.
    times = [time for time, raw in records("atv71_commissioning.pcap") if len(raw) == 17 and raw[1] == 0x17]
    intervals = [b - a for a, b in zip(times, times[1:])]
    period = statistics.median_low(intervals)  # the lower middle, as the histogram gives it
    assert abs(scan["period"] * 1e6 - period) <= 50  # 100 us histogram steps
    long_gaps = [i for i in intervals if i >= 1.5 * period]
    assert scan["skipped"] == sum(round(i / period) - 1 for i in long_gaps) == 1  # HSP and CHCF writes in between
    normal = [i for i in intervals if i < 1.5 * period]
    assert abs(scan["jitter"] * 1e6 - max(abs(i - period) for i in normal)) <= 100
    assert (scan["no_answer"], scan["misses"]) == (0, 1)


def test_p38_exceptions_are_misses_and_noisy_bus_timeouts() -> None:
    (row,) = poll_rows("p38_protection.pcap")
    assert (row["slave"], row["function"], describe_key(row), row["count"]) == (12, 3, "8400..8402 (3)", 6)
    assert (row["skipped"], row["no_answer"], row["misses"]) == (0, 2, 2)  # frames 10 and 12
    rows = {(r["slave"], r["function"], r["start"]): r for r in poll_rows("noisy_bus.pcap")}
    assert set(rows) == {(12, 3, 3201), (1, 3, 0)}  # slave 5's two timed-out requests are no cycle
    # Frame 17 answers slave 1's request #16 with a bad CRC: that cycle missed (before: no_answer 0, misses 3).
    assert (rows[1, 3, 0]["no_answer"], rows[1, 3, 0]["misses"]) == (1, 4)


def test_untimed_capture_has_counts_without_period() -> None:
    (row,) = poll_rows("p38_protection.bin")
    assert row["count"] == 6 and row["period"] is None and row["jitter"] is None and row["misses"] == 2


def test_skipped_cycles_are_counted_by_length() -> None:
    cycle = PollCycle()
    times = [0.0, 0.1, 0.2, 0.5, 0.6, 0.71]  # 0.2 -> 0.5: two cycles missing
    for number, time in enumerate(times, 1):
        frame = Frame(0, b"", time, Kind.REQUEST, 7, 3, 0, 0, number=number)
        frame.start, frame.quantity = 100, 2
        cycle.add_request(frame)
    (row,) = cycle.report()
    assert (row["count"], round(row["period"], 5), row["skipped"], round(row["jitter"], 5)) == (6, 0.1, 2, 0.01)
