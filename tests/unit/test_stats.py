"""Statistics on the sample captures: exact counts, response times against the pcap timestamps, tables."""
from __future__ import annotations

import struct
from io import StringIO
from pathlib import Path

import pytest
from rich.console import Console

from dissector.framing.ascii import AsciiFramer
from dissector.pipeline import dissect, dissect_bytes
from dissector.devices.build import build_annotator
from dissector.sources.reader import open_source
from dissector.render.stats import StatsCollector, percentile

from conftest import ROOT
from helpers import rtu

CAPTURES = ROOT / "captures"


def collect(file_name: str) -> StatsCollector:
    annotate = build_annotator(["atv71", "1=sel749m"], [])
    source = open_source(str(CAPTURES / file_name))
    framer = AsciiFramer() if source.mode == "ascii" else None
    stats = StatsCollector()
    for item in dissect(source, annotate=annotate, framer=framer):
        stats.add(item)
    return stats


def pcap_times(path: Path) -> list[int]:
    """Record timestamps in microseconds, read straight from the file (the oracle for response times)."""
    data = path.read_bytes()
    times, offset = [], 24
    while offset < len(data):
        seconds, micros, length, _original = struct.unpack_from("<IIII", data, offset)
        times.append(seconds * 1_000_000 + micros)
        offset += 16 + length
    return times


def row(report: dict, slave: int, function: int) -> dict:
    (found,) = [r for r in report["functions"] if (r["slave"], r["function"]) == (slave, function)]
    return found


def counts(found: dict) -> tuple:
    return (
        found["requests"],
        found["responses"],
        found["exceptions"],
        found["unanswered"],
        found["crc_errors"],
        None if found["response_time"] is None else found["response_time"]["count"],
    )


def parameter(report: dict, slave: int, address: int) -> dict:
    (found,) = [p for p in report["parameters"] if (p["slave"], p["address"]) == (slave, address)]
    return {key: found[key] for key in ("code", "reads", "unreadable", "writes", "refused", "last", "changes")}


def test_p38_counts_and_parameters() -> None:
    # p.38 as the summary tells it: frames 6/8 read 16#8000 at CHCF, frames 10/12 are exception 02
    # (every parameter of the read non-existent or protected): CHCF 2 reads and 4 unreadable, COP 4
    # and 2, both last seen protected, each changed once (readable -> protected).
    report = collect("p38_protection.pcap").report()
    assert report["frames"] == 12 and report["noise"] == {"items": 0, "bytes": 0}
    assert [(r["slave"], r["function"]) for r in report["functions"]] == [(12, 3)]
    assert counts(row(report, 12, 3)) == (6, 4, {"2": 2}, 0, 0, 6)
    assert parameter(report, 12, 8400) == {
        "code": None, "reads": 0, "unreadable": 6, "writes": 0, "refused": 0, "last": None, "changes": 0
    }
    assert parameter(report, 12, 8401) == {
        "code": "CHCF", "reads": 2, "unreadable": 4, "writes": 0, "refused": 0, "last": None, "changes": 1
    }
    assert parameter(report, 12, 8402) == {
        "code": "COP", "reads": 4, "unreadable": 2, "writes": 0, "refused": 0, "last": None, "changes": 1
    }
    last = {p["address"]: (p["last_text"], p["last_status"]) for p in report["parameters"]}
    assert last == {8400: ("non-existent", "non-existent"), 8401: ("protected", "protected"),
                    8402: ("protected", "protected")}


def test_p38_stats_table_as_a_user_sees_it() -> None:
    from helpers import run_cli

    for name in ("p38_protection.pcap", "p38_protection.bin"):
        # (forced: under profile auto frame 2 is before the evidence, issue 26)
        status, out, err = run_cli(["--stats", "--profile", "atv71", str(CAPTURES / name)])
        assert status == 0
        assert out.split("Parameters\n", 1)[1].splitlines()[:6] == [
            "slave   address  code  reads  unreadable  writes  refused  last          changes",
            "--------------------------------------------------------------------------------",
            "   12      8400            0           6       0        0  non-existent        0",
            "   12      8401  CHCF      2           4       0        0  protected           1",
            "   12      8402  COP       4           2       0        0  protected           1",
            "  all  3 params            6          12       0        0                      2",
        ]


def test_p38_response_times_match_the_pcap_timestamps() -> None:
    times = pcap_times(CAPTURES / "p38_protection.pcap")
    # Every request (even records) is answered by the next record.
    expected = sorted(times[index + 1] - times[index] for index in range(0, len(times), 2))
    timing = row(collect("p38_protection.pcap").report(), 12, 3)["response_time"]
    assert round(timing["min"] * 1e6) == expected[0]
    assert round(timing["max"] * 1e6) == expected[-1]
    assert round(timing["median"] * 1e6) == (expected[2] + expected[3]) // 2  # 6 values
    assert round(timing["p95"] * 1e6) == expected[5]  # nearest rank: ceil(0.95 x 6) = 6


def test_commissioning_counts_and_parameters() -> None:
    report = collect("atv71_commissioning.pcap").report()
    assert report["frames"] == 104
    assert counts(row(report, 2, 3)) == (4, 4, {}, 0, 0, 4)
    assert counts(row(report, 2, 6)) == (6, 5, {"7": 1}, 0, 0, 6)
    assert counts(row(report, 2, 16)) == (1, 1, {}, 0, 0, 1)
    assert counts(row(report, 2, 23)) == (40, 40, {}, 0, 0, 40)
    assert counts(row(report, 2, 43)) == (1, 1, {}, 0, 0, 1)
    # CHCF read as 3, written 2 (accepted), 3 (refused while running), 3 (accepted once stopped).
    assert parameter(report, 2, 8401) == {
        "code": "CHCF", "reads": 1, "unreadable": 0, "writes": 3, "refused": 1, "last": 3, "changes": 2
    }
    assert parameter(report, 2, 3104) == {
        "code": "HSP", "reads": 1, "unreadable": 0, "writes": 1, "refused": 0, "last": 550, "changes": 1
    }
    # The scanner's CMD goes 6, 7, 15, 7, 6 and ETA follows: 0x231, 0x233, 0x237, 0x233, 0x231.
    assert parameter(report, 2, 8501) == {
        "code": "CMD", "reads": 0, "unreadable": 0, "writes": 40, "refused": 0, "last": 6, "changes": 4
    }
    assert parameter(report, 2, 3201) == {
        "code": "ETA", "reads": 40, "unreadable": 0, "writes": 0, "refused": 0, "last": 0x231, "changes": 4
    }
    assert parameter(report, 2, 9001)["writes"] == 1 and parameter(report, 2, 9001)["last"] == 10
    assert len(report["parameters"]) == 14


def test_sel_counts_and_refused_writes() -> None:
    report = collect("sel749m_polling.bin").report()
    assert report["frames"] == 68
    assert counts(row(report, 1, 3)) == (14, 12, {"2": 1, "3": 1}, 0, 0, None)  # a .bin has no times
    assert counts(row(report, 1, 4)) == (12, 12, {}, 0, 0, None)
    assert counts(row(report, 1, 6)) == (3, 1, {"2": 1, "3": 1}, 0, 0, None)
    assert counts(row(report, 1, 16)) == (4, 1, {"2": 1, "3": 2}, 0, 0, None)
    assert counts(row(report, 1, 23)) == (1, 0, {"1": 1}, 0, 0, None)
    # 300: FC6 = 1 (accepted), FC23 (function refused), two refused FC16, FC16 = 0 (accepted).
    assert parameter(report, 1, 300) == {
        "code": None, "reads": 0, "unreadable": 0, "writes": 5, "refused": 3, "last": 0, "changes": 1
    }
    # (frame 49, FC16 300..301, carries a word for 302 past its quantity 2: no write of 302 since cb66f1d)
    assert parameter(report, 1, 302) == {
        "code": None, "reads": 0, "unreadable": 0, "writes": 2, "refused": 2, "last": None, "changes": 0
    }
    assert parameter(report, 1, 0)["reads"] == 12


def test_noisy_counts() -> None:
    report = collect("noisy_bus.pcap").report()
    assert report["frames"] == 36 and report["noise"] == {"items": 2, "bytes": 9}
    assert counts(row(report, 1, 3)) == (9, 8, {}, 0, 1, 8)
    assert counts(row(report, 5, 3)) == (2, 0, {}, 2, 0, None)
    assert counts(row(report, 12, 3)) == (8, 8, {}, 0, 0, 8)


def test_ascii_counts() -> None:
    report = collect("ascii_session.pcap").report()
    assert report["frames"] == 10
    assert counts(row(report, 2, 3)) == (3, 2, {"2": 1}, 0, 0, 3)
    assert counts(row(report, 2, 6)) == (1, 1, {}, 0, 0, 1)
    assert parameter(report, 2, 9001) == {
        "code": "ACC", "reads": 1, "unreadable": 0, "writes": 1, "refused": 0, "last": 10, "changes": 0
    }


def test_broadcast_and_unpaired_registers() -> None:
    stats = StatsCollector()
    for item in dissect_bytes(rtu("00 06 23 29 00 0A") + rtu("0C 03 04 00 01 00 02")):
        stats.add(item)
    report = stats.report()
    assert counts(row(report, 0, 6)) == (1, 0, {}, 0, 0, None)
    assert row(report, 0, 6)["broadcasts"] == 1
    assert parameter(report, 0, 9001)["writes"] == 1 and parameter(report, 0, 9001)["last"] == 10
    assert counts(row(report, 12, 3)) == (0, 1, {}, 0, 0, None)
    assert report["registers_without_address"] == 2


def test_percentile_nearest_rank() -> None:
    values = [float(n) for n in range(1, 21)]
    assert percentile(values, 0.95) == 19.0
    assert percentile([5.0], 0.95) == 5.0
    assert percentile(values, 0.5) == 10.0


def test_render_p38() -> None:
    console = Console(file=StringIO(), width=100, color_system=None)
    console.print(collect("p38_protection.pcap").render())
    lines = [line.rstrip() for line in console.file.getvalue().splitlines()]
    assert lines == [
        "12 frames, 0 noise bytes in 0 runs",
        "",
        "Traffic per slave and function",
        " slave  function                  req  resp  exceptions  no reply  bad CRC",
        "─" * 75,
        "    12  3 Read Holding Registers    6     4  02:2               0        0",  # as the notes: 02
        "req: requests, resp: normal responses, exceptions: code:count (hex code)",
        "",
        "Response times (ms)",
        " slave  function                  count  min  median   p95   max",
        "─" * 65,
        "    12  3 Read Holding Registers      6  8.0     9.5  11.9  11.9",
        "",
        "Poll cycle (requests repeated 3 times or more)",
        " slave  function                  addresses       count  period  jitter  misses",
        "─" * 80,
        "    12  3 Read Holding Registers  8400..8402 (3)      6   523.9     5.2       2",
        "period: median interval (ms); jitter: largest deviation from it (ms); misses:",
        "cycles skipped (intervals of 1.5 periods or more) + requests without a normal",
        "answer",
        "",
        "Parameters",
        " slave   address  code  reads  unreadable  writes  refused  last          changes",
        "─" * 82,
        "    12      8400            0           6       0        0  non-existent        0",
        "    12      8401  CHCF      2           4       0        0  protected           1",
        "    12      8402  COP       4           2       0        0  protected           1",
        "   all  3 params            6          12       0        0                      2",
    ]


def test_plain_tables_are_the_same_numbers_at_full_width() -> None:
    # Piped output: no rich layout, nothing cut (a 35-character function name, a 64-character ETA text).
    text = collect("atv71_commissioning.pcap").render_plain()
    lines = text.splitlines()
    assert "    2  43 Encapsulated Interface Transport    1     1                     0        0" in lines
    assert (
        "    2       3201  ETA      40           0       0        0  "
        "Ready to switch on, Voltage enabled, Quick stop inactive, Remote        4"
    ) in lines
    assert "    2       3104  HSP       1           0       1        0  55.0 Hz" + " " * 65 + "1" in lines
    assert "    2  23 Read/Write Multiple Registers  read 3201..3202 (2), write 8501..8502 (2)     40    50.4     6.4       1" in lines


def test_parameter_ranges_with_the_same_story_and_the_cap() -> None:
    from dissector.render.stats import MAX_PARAMETER_ROWS

    stats = StatsCollector()
    # Slave 9: 100 unnamed registers read twice (the same story), then a lone one read once; slave 10: MAX_PARAMETER_ROWS + 5 scattered single registers.
    frames = []
    for _ in range(2):
        frames += [rtu("09 03 03 E8 00 64"), rtu("09 03 C8" + " 00 07" * 100)]
    frames += [rtu("09 03 07 D0 00 01"), rtu("09 03 02 00 01")]
    for index in range(MAX_PARAMETER_ROWS + 5):
        address = 10 * index
        frames += [rtu(f"0A 03 {address >> 8:02X} {address & 255:02X} 00 01"), rtu("0A 03 02 00 05")]
    for item in dissect_bytes(b"".join(frames), annotate=build_annotator(["generic"], [])):
        stats.add(item)
    report = stats.report()
    assert len(report["parameters"]) == 100 + 1 + MAX_PARAMETER_ROWS + 5  # JSON stays per address
    lines = stats.render_plain().splitlines()
    table = lines[lines.index("Parameters") + 3 :]
    assert table[0] == "    9    1000..1099 (100)            2           0       0        0  7           0"
    assert table[1] == "    9                2000            1           0       0        0  1           0"
    assert table[2] == "   10                   0            1           0       0        0  5           0"
    assert len(table) == MAX_PARAMETER_ROWS + 2
    assert table[-2].strip() == "... (+7 more rows)"
    assert table[-1] == "  all          166 params          266           0       0        0              0"


@pytest.mark.parametrize("width", [60, 80, 120])
def test_render_never_fails_at_any_width(width: int) -> None:
    console = Console(file=StringIO(), width=width, color_system=None)
    console.print(collect("sel749m_polling.pcap").render())
    assert "Write Multiple" in console.file.getvalue() or width < 80


def test_profile_rows_say_which_slave_got_which_profile_and_why() -> None:
    from types import SimpleNamespace

    from dissector.render.report.html import render_report
    from dissector.render.report import ReportCollector

    # The annotator's choices() (profile `auto`): asked once, at the end. A reason names the frame that decided
    # it; the table says it once (it said "(frame #2)" again after it).
    identified = "Read Device Identification in frame #2: ProductCode 'ATV71HU15M3'"
    choices = [
        SimpleNamespace(slave=2, profile="atv71", reason=identified, frame=2),
        SimpleNamespace(slave=5, profile="generic", reason="no evidence of a device: spec semantics only", frame=None),
    ]
    stats = StatsCollector(lambda: choices)
    for item in dissect(open_source(str(CAPTURES / "atv71_commissioning.pcap")), annotate=build_annotator(["atv71"], [])):
        stats.add(item)
    assert stats.report()["profiles"] == [
        {"slave": 2, "profile": "atv71", "reason": identified, "frame": 2},
        {"slave": 5, "profile": "generic", "reason": "no evidence of a device: spec semantics only", "frame": None},
    ]
    lines = stats.render_plain().splitlines()
    start = lines.index("Device profiles")
    assert lines[start : start + 5] == [
        "Device profiles",
        "slave  profile  why",
        "-" * 81,
        f"    2  atv71    {identified}",
        "    5  generic  no evidence of a device: spec semantics only",
    ]
    shown = identified.replace("'", "&#x27;")
    assert f"<td>2</td><td>atv71</td><td>{shown}</td>" in render_report(ReportCollector(), stats)
    assert "Device profiles" not in collect("p38_protection.pcap").render_plain()  # no choices(): no table
