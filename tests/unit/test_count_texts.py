"""Texts a review found wrong (issue 30's review of the outputs), exact for exact bytes, under the compiled
engine and the Python stages (VW3_PURE_PYTHON=1), which must agree byte for byte:

- a count with its noun reads singular for one: `1 byte of noise at offset 8` (summary and -V), `(+1 byte)`
  after FC8's first 16 data bytes, `1 byte of data`; the warnings whose count follows its noun read right
  for 1 as for 3 (`the registers asked (1)`, `unexpected bytes after the data (1)`);
- a window past 65535 shows its last address as asked (`65535..65539 (5)`), as its warning says it, in
  the info of the request and of its answer, protocol and PLC style (`465536..465540`), never wrapped back
  to 3;
- an FC43 object the spec does not name reads `Object 128: 'ABC'` in -V, as a named one reads `Object 5
  ModelName: 'XY'`, not `Object 128 Object 128`;
- `-w OUT -V` prints nothing (as tshark, -P prints): the help says -P prints even with -w.

The plugin's side is tests/integration/test_lua_count_texts.py.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from dissector.render.pcapwriter import PcapWriter
from helpers import rtu, run_cli, use_engine

T0 = 1767225600.0
# (bytes, seconds after T0): each record one frame or one noise run
RECORDS = [
    (rtu("01 03 FFFF 0005"), 0.0),
    (rtu("01 03 0A 0001 0002 0003 0004 0005"), 0.010),
    (bytes([0xAA]), 0.050),
    (rtu("01 0F FFFF 000A 02 FF 03"), 0.100),
    (rtu("01 0F FFFF 000A"), 0.110),
    (rtu("01 2B 0E 04 80"), 0.200),
    (rtu("01 2B 0E 04 81 00 00 02 80 03 414243 05 02 5859"), 0.210),
    (rtu("01 08 0000 0102030405060708090A0B0C0D0E0F1011"), 0.300),
    (rtu("01 08 0000 0102030405060708090A0B0C0D0E0F1011"), 0.310),
    (rtu("01 03 0010 0001"), 0.400),
    (rtu("01 03 04 0001 0002"), 0.410),
    (rtu("01 01 0020 0001"), 0.500),
    (rtu("01 01 02 01 00"), 0.510),
    (bytes([0xBB, 0xCC]), 0.550),
]
SUMMARY = [
    "     1     0.000000   1 request   Read Holding Registers 65535..65539 (5) "
    "[warning: addresses 65535..65539 run past 65535]  CRC ok",
    "     2     0.010000   1 response  Read Holding Registers 65535..65539 (5): 65535=1 0=2 1=3 2=4 3=5 "
    "[#1, 10.0 ms]  CRC ok",
    "     3     0.050000   - noise     1 byte of noise at offset 23: aa",
    "     4     0.100000   1 request   Write Multiple Coils 65535..65544 (10): 1111111111 "
    "[warning: addresses 65535..65544 run past 65535]  CRC ok",
    "     5     0.110000   1 response  Write Multiple Coils 65535..65544 (10) written [#4, 10.0 ms]  CRC ok",
    "     6     0.200000   1 request   Encapsulated Interface Transport Read Device Identification, individual, "
    "from object 128  CRC ok",
    "     7     0.210000   1 response  Encapsulated Interface Transport Read Device Identification, individual: "
    "Object 128='ABC' ModelName='XY' [#6, 10.0 ms]  CRC ok",
    "     8     0.300000   1 request   Diagnostics 00h Return Query Data data 0102030405060708090a0b0c0d0e0f10… "
    "(+1 byte) [warning: diagnostic data is not a whole number of words]  CRC ok",
    "     9     0.310000   1 response  Diagnostics 00h Return Query Data data 0102030405060708090a0b0c0d0e0f10… "
    "(+1 byte) [#8, 10.0 ms] [warning: diagnostic data is not a whole number of words]  CRC ok",
    "    10     0.400000   1 request   Read Holding Registers 16  CRC ok",
    "    11     0.410000   1 response  Read Holding Registers 16: 16=1 17=2 [#10, 10.0 ms] "
    "[warning: byte count 4 disagrees with the registers asked (1)]  CRC ok",
    "    12     0.500000   1 request   Read Coils 32  CRC ok",
    "    13     0.510000   1 response  Read Coils 32: 1 [#12, 10.0 ms] "
    "[warning: byte count 2 disagrees with the bits asked (1)]  CRC ok",
    "    14     0.550000   - noise     2 bytes of noise at offset 147: bb cc",
]
# PLC style: the same windows as 4X (and 0X) references, past the top as asked
SUMMARY_PLC = {
    1: "     1     0.000000   1 request   Read Holding Registers 465536..465540 (5) "
       "[warning: addresses 65535..65539 run past 65535]  CRC ok",
    2: "     2     0.010000   1 response  Read Holding Registers 465536..465540 (5): 465536=1 40001=2 40002=3 "
       "40003=4 40004=5 [#1, 10.0 ms]  CRC ok",
    4: "     4     0.100000   1 request   Write Multiple Coils 065536..065545 (10): 1111111111 "
       "[warning: addresses 65535..65544 run past 65535]  CRC ok",
}


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("texts") / "texts.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for data, at in RECORDS:
            writer.write(data, T0 + at)
    return path


@pytest.fixture(params=["engine", "pure"])
def engine(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> str:
    use_engine(monkeypatch, request.param == "pure")
    return request.param


def cli(*argv: str) -> str:
    """vw3-decode's output; -n (no device profile) unless PLC style, which a profile (auto) gives."""
    status, out, err = run_cli([*argv] if "plc" in argv else [*argv, "-n"])
    assert status == 0, err
    return out


def test_summary_lines(capture: Path, engine: str) -> None:
    assert cli(str(capture)).splitlines() == SUMMARY


def test_summary_lines_plc_style(capture: Path, engine: str) -> None:
    lines = cli("--address-style", "plc", str(capture)).splitlines()
    assert {number: lines[number - 1] for number in SUMMARY_PLC} == SUMMARY_PLC


def test_raw_stream_noise_of_one_byte(engine: str) -> None:
    """The raw-bytes path (the engine frames the stream itself): a turn-around glitch of one byte."""
    stream = rtu("01 03 0010 0001") + b"\x00" + rtu("01 03 02 0007")
    status, out, err = run_cli(["-", "-n"], stdin=stream)
    assert status == 0, err
    assert out.splitlines() == [
        "     1            -   1 request   Read Holding Registers 16  CRC ok",
        "     2            -   - noise     1 byte of noise at offset 8: 00",
        "     3            -   1 response  Read Holding Registers 16: 16=7 [#1]  CRC ok",
    ]


def test_detail_of_noise_and_of_an_unnamed_object(capture: Path, engine: str) -> None:
    out = cli("-V", "-Y", "frame == 3 or frame == 7", str(capture))
    assert ("Item 3: noise, 1 byte at offset 23\n"
            "    Arrival time: 2026-01-01 00:00:00.050000 UTC (0.050000 s since the first item)\n"
            "    1 byte of noise at offset 23: aa\n    Reason: too short for a frame\n") in out
    assert "        Object 128: 'ABC'\n        Object 5 ModelName: 'XY'\n" in out
    assert "Object 128 Object 128" not in out


def test_json_keeps_the_window_and_the_warning(capture: Path, engine: str) -> None:
    first = json.loads(cli("--json", "--address-style", "plc", str(capture)).splitlines()[0])
    assert (first["start"], first["quantity"], first["span_label"], first["warnings"]) == (
        65535, 5, "465536..465540", ["addresses 65535..65539 run past 65535"])


def test_one_byte_of_data_of_an_unknown_function(engine: str) -> None:
    out = cli("--hex", rtu("01 41 05").hex(" "))
    assert out.splitlines()[0].startswith("     1            -   1 request   User-defined function 65 1 byte of data ")


def test_write_without_print_prints_nothing_even_with_detail(capture: Path, tmp_path: Path, engine: str) -> None:
    """tshark's habit: -w writes, -P prints as well (the help: `-P  print the items even with -w`)."""
    out_pcap = tmp_path / "out.pcap"
    assert cli("-V", "-w", str(out_pcap), str(capture)) == ""
    assert out_pcap.read_bytes() == capture.read_bytes()
    assert cli("-V", "-P", "-w", str(out_pcap), str(capture)).startswith("Frame 1: 8 bytes at offset 0, request (RTU)\n")
    status, out, err = run_cli(["--help"])
    assert "print the items even with -w" in " ".join(out.split())


def fc23_polls(times: int) -> bytes:
    """FC23 reading 65534..65537 (its request warned: the window runs past 65535) and writing 16, then a
    read of 16..17, `times` over: the engine writes the info of the answers (the first is handed over; the
    requests, warned, are too)."""
    stream = b""
    for value in range(times):
        stream += rtu(f"01 17 FFFE 0004 0010 0001 02 00{value:02X}") + rtu(f"01 17 08 0001 0002 00{value:02X} 0004")
        stream += rtu("01 03 0010 0002") + rtu(f"01 03 04 0001 00{value:02X}")
    return stream


@pytest.mark.parametrize("style, read, values", [
    ("protocol", "65534..65537 (4)", "65534=1 65535=2 0=39 1=4"),
    ("plc", "465535..465538 (4)", "465535=1 465536=2 40001=39 40002=4"),
])
def test_fc23_read_window_past_65535_as_asked(engine: str, style: str, read: str, values: str) -> None:
    status, out, err = run_cli(["-", "--address-style", style], stdin=fc23_polls(40))
    assert status == 0, err
    write = "16=39" if style == "protocol" else "40017=39"
    assert out.splitlines()[-4:-2] == [
        f"   157            -   1 request   Read/Write Multiple Registers read {read}, write {write} "
        "[warning: addresses 65534..65537 run past 65535]  CRC ok",
        f"   158            -   1 response  Read/Write Multiple Registers {read}: {values} [#157]  CRC ok",
    ]
    assert out.splitlines()[1].startswith(
        f"     2            -   1 response  Read/Write Multiple Registers {read}: {values.replace('39', '0')} [#1] ")


def test_stats_and_report_headers_read_singular_for_one(engine: str, tmp_path: Path) -> None:
    """--stats' first line and the report's summary: one frame, one noise byte in one run, one register
    value without an address (an answer with no request before it)."""
    stream = b"\x00" + rtu("01 03 02 0064")
    status, out, err = run_cli(["-", "-n", "--stats"], stdin=stream)
    assert status == 0, err
    assert out.splitlines()[0] == "1 frame, 1 noise byte in 1 run, 1 register value without an address"
    report = tmp_path / "r.html"
    status, out, err = run_cli(["-", "-n", "--report", str(report)], stdin=stream)
    assert status == 0, err
    assert '<p class="summary">1 frame, 1 noise byte in 1 run, no timestamps' in report.read_text()


def test_stats_header_plural_for_two(engine: str) -> None:
    stream = b"\x00\x00" + rtu("01 03 0010 0001") + rtu("01 03 02 0007")
    status, out, err = run_cli(["-", "-n", "--stats"], stdin=stream)
    assert status == 0, err
    assert out.splitlines()[0] == "2 frames, 2 noise bytes in 1 run"


def test_live_totals_read_singular_for_one() -> None:
    from dissector.app.live_view import LiveStats, totals_text
    from dissector.model import Noise

    stats = LiveStats()
    stats.add(Noise(offset=0, raw=b"\x00", time=None))
    assert totals_text(stats) == "0 frames, 0 CRC errors, 0 unanswered, 1 noise byte, last response time -"


def test_stats_poll_window_past_65535_as_the_summary_shows_it(engine: str, tmp_path: Path) -> None:
    """--stats' poll cycle, PLC style, names the window as the summary line does (465535..465538), not
    wrapped back to 40002."""
    path = tmp_path / "poll.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for k in range(4):
            writer.write(rtu("01 03 FFFE 0004"), T0 + k)
            writer.write(rtu("01 03 08 0001 0002 0003 0004"), T0 + k + 0.010)
    out = cli("--address-style", "plc", "--stats", str(path))
    assert "    1  3 Read Holding Registers  465535..465538 (4)      4  1000.0     0.0       0" in out.splitlines()
    first = cli("--address-style", "plc", str(path)).splitlines()[0]
    assert "Read Holding Registers 465535..465538 (4)" in first


FC23_PAST_65535 = [
    (rtu("01 17 FFFF 0005 0000 0001 02 0001"), 0.0),  # its read window runs past 65535
    (rtu("01 17 FFFF 0001 FFFE 0003 06 0001 0002 0003"), 1.0),  # its write window does
    (rtu("01 17 0000 0001 0010 0001 02 0001"), 2.0),  # neither
]


def test_fc23_windows_past_65535_draw_the_warning(engine: str, tmp_path: Path) -> None:
    """FC23's read window and its write window each draw the `span` warning as FC3's and FC16's do."""
    path = tmp_path / "fc23.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for data, at in FC23_PAST_65535:
            writer.write(data, T0 + at)
    assert cli(str(path)).splitlines() == [
        "     1     0.000000   1 request   Read/Write Multiple Registers read 65535..65539 (5), write 0=1 "
        "[no response] [warning: addresses 65535..65539 run past 65535]  CRC ok",
        "     2     1.000000   1 request   Read/Write Multiple Registers read 65535, write 65534=1 65535=2 0=3 "
        "[no response] [warning: addresses 65534..65536 run past 65535]  CRC ok",
        "     3     2.000000   1 request   Read/Write Multiple Registers read 0, write 16=1 "
        "[the capture ends before any response: not known whether it was answered]  CRC ok",
    ]
