"""Capture sources: every format built here byte by byte with struct, read back chunk by chunk.

Frames are the seed vectors (p.38 protection story, slave 12) and the card manual's FC3 and FC43
examples from /work/shared/reference/README.md.
"""
from __future__ import annotations

import gzip
import io
import subprocess
import struct
import sys
from pathlib import Path

import pytest

from lua_harness import ensure_tool

from dissector.sources import reader as sources
from dissector.model import Chunk, Frame, Kind, Noise
from dissector.sources.common import PartChunk
from dissector.pipeline import dissect
from dissector.sources.reader import SourceError, open_source
from helpers import hx

# Seed 000 (p.38): read 8400..8402 on slave 12, the three answers the drive can give.
REQUEST = hx("0C 03 20 D0 00 03 0E EF")
RESPONSE = hx("0C 03 06 80 00 00 03 00 02 17 E4")
RESPONSE_PROTECTED = hx("0C 03 06 80 00 80 00 00 02 CE 24")
EXCEPTION = hx("0C 83 02 51 32")
# Card manual: FC3 3102..3105 on slave 2, and the FC43 basic identification request.
FC3_REQUEST = hx("02 03 0C 1E 00 04 27 6C")
FC3_RESPONSE = hx("02 03 08 00 28 02 58 01 F4 00 00 52 B0")
FC43_REQUEST = hx("02 2B 0E 01 00 34 77")

SESSION = [REQUEST, RESPONSE, REQUEST, RESPONSE_PROTECTED, REQUEST, EXCEPTION, FC3_REQUEST,
           FC3_RESPONSE]
T0 = 1_700_000_000
TIMES = [(T0, 0), (T0, 12_000), (T0 + 1, 0), (T0 + 1, 9_500), (T0 + 2, 0), (T0 + 2, 7_250),
         (T0 + 3, 500_000), (T0 + 3, 521_125)]


# -- file builders -------------------------------------------------------------------------------
def pcap(records: list[tuple[int, int, bytes]], linktype: int = 147, order: str = "<",
         nano: bool = False, original: int | None = None) -> bytes:
    magic = 0xA1B23C4D if nano else 0xA1B2C3D4
    out = struct.pack(order + "IHHiIII", magic, 2, 4, 0, 0, 65535, linktype)
    for seconds, fraction, data in records:
        out += struct.pack(order + "IIII", seconds, fraction, len(data),
                           len(data) if original is None else original) + data
    return out


def rtac(seconds: int, micros: int, data: bytes, event: int = 0x02) -> bytes:
    return struct.pack(">IIBBH", seconds, micros, event, 0x41, 0) + data


def block(order: str, block_type: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    total = len(body) + 12
    return struct.pack(order + "II", block_type, total) + body + struct.pack(order + "I", total)


def option(order: str, code: int, value: bytes) -> bytes:
    return struct.pack(order + "HH", code, len(value)) + value + b"\0" * (-len(value) % 4)


def shb(order: str) -> bytes:
    return block(order, 0x0A0D0D0A, struct.pack(order + "IHHq", 0x1A2B3C4D, 1, 0, -1))


def idb(order: str, linktype: int, tsresol: int | None = None, tsoffset: int | None = None) -> bytes:
    options = b""
    if tsresol is not None:
        options += option(order, 9, bytes([tsresol]))
    if tsoffset is not None:
        options += option(order, 14, struct.pack(order + "q", tsoffset))
    if options:
        options += struct.pack(order + "HH", 0, 0)
    return block(order, 1, struct.pack(order + "HHI", linktype, 0, 0) + options)


def epb(order: str, interface: int, stamp: int, data: bytes) -> bytes:
    head = struct.pack(order + "IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data))
    return block(order, 6, head + data)


def spb(order: str, data: bytes) -> bytes:
    return block(order, 3, struct.pack(order + "I", len(data)) + data)


def opb(order: str, interface: int, stamp: int, data: bytes) -> bytes:
    head = struct.pack(order + "HHIIII", interface, 0, stamp >> 32, stamp & 0xFFFFFFFF, len(data),
                       len(data))
    return block(order, 2, head + data)


def write(tmp_path: Path, name: str, content: bytes) -> str:
    path = tmp_path / name
    path.write_bytes(content)
    return str(path)


def chunks(path: str, **options: object) -> list[Chunk]:
    return list(open_source(path, **options))  # type: ignore[arg-type]


def summary(items: list) -> list[tuple]:
    """What a user sees of each item: enough to tell two framings apart."""
    out = []
    for item in items:
        if isinstance(item, Frame):
            out.append((item.offset, item.raw, item.kind, item.slave, item.function, item.crc_ok,
                        item.time, item.request.number if item.request else None))
        else:
            out.append((item.offset, item.raw, "noise", item.time))
    return out


def session_chunks() -> list[Chunk]:
    return [Chunk(data, s + us / 1_000_000, True) for (s, us), data in zip(TIMES, SESSION)]


# -- pcap ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("order", ["<", ">"])
def test_pcap_microseconds_both_byte_orders(tmp_path: Path, order: str) -> None:
    records = [(s, us, data) for (s, us), data in zip(TIMES, SESSION)]
    source = open_source(write(tmp_path, "capture.bin", pcap(records, order=order)))
    assert (source.format, source.mode) == ("pcap", "rtu")
    assert list(source) == session_chunks()
    assert source.warnings == []


@pytest.mark.parametrize("order", ["<", ">"])
def test_pcap_nanoseconds(tmp_path: Path, order: str) -> None:
    records = [(T0, 123_456_789, REQUEST), (T0, 140_000_001, RESPONSE)]
    path = write(tmp_path, "c", pcap(records, order=order, nano=True))
    assert chunks(path) == [Chunk(REQUEST, T0 + 123_456_789 / 1e9, True),
                            Chunk(RESPONSE, T0 + 140_000_001 / 1e9, True)]


def test_pcap_session_decodes_with_record_times(tmp_path: Path) -> None:
    records = [(s, us, data) for (s, us), data in zip(TIMES, SESSION)]
    items = list(dissect(open_source(write(tmp_path, "c.pcap", pcap(records)))))
    assert [(i.kind, i.slave, i.function) for i in items] == [
        (Kind.REQUEST, 12, 3), (Kind.RESPONSE, 12, 3), (Kind.REQUEST, 12, 3), (Kind.RESPONSE, 12, 3),
        (Kind.REQUEST, 12, 3), (Kind.EXCEPTION, 12, 3), (Kind.REQUEST, 2, 3), (Kind.RESPONSE, 2, 3)]
    # Float seconds since 1970 keep about 0.2 us.
    assert items[1].response_time == pytest.approx(0.012, abs=1e-6)
    assert items[5].exception_code == 2
    assert [r.value for r in items[7].registers] == [0x28, 0x258, 0x1F4, 0]
    assert items[7].time == T0 + 3 + 521_125 / 1_000_000


def test_pcap_rtac_serial_takes_time_from_its_header(tmp_path: Path) -> None:
    records = [(T0 + 9, 0, rtac(T0, 250_000, REQUEST)), (T0 + 9, 1, rtac(T0, 262_500, RESPONSE))]
    source = open_source(write(tmp_path, "c", pcap(records, linktype=250)))
    assert list(source) == [Chunk(REQUEST, T0 + 0.25, True), Chunk(RESPONSE, T0 + 0.2625, True)]
    assert source.warnings == []


def test_rtac_trouble_events_and_short_records_are_reported(tmp_path: Path) -> None:
    records = [(T0, 0, rtac(T0, 0, REQUEST, event=0x05)), (T0, 1, b"\0" * 7),
               (T0, 2, rtac(T0, 5, RESPONSE, event=0x08))]
    source = open_source(write(tmp_path, "c", pcap(records, linktype=250)))
    # (the short record's bytes, noise at its record's time, as tshark shows it a frame undissected: -w keeps it)
    assert list(source) == [Chunk(REQUEST, float(T0), True), Chunk(b"\0" * 7, T0 + 1e-6, True),
                            Chunk(RESPONSE, T0 + 5e-6, True)]
    assert source.warnings == [
        "record 1: the RTAC reports a capture data lost (event 0x05)",
        "record 2: 7 bytes, shorter than the 12-byte RTAC serial header; its bytes are noise",
        "record 3: the RTAC reports a parity error (event 0x08)",
    ]


def test_pcap_other_linktype_is_a_clear_error(tmp_path: Path) -> None:
    path = write(tmp_path, "eth.pcap", pcap([(T0, 0, REQUEST)], linktype=1))
    with pytest.raises(SourceError) as error:
        open_source(path)
    assert str(error.value) == (  # (read for Modbus RTU over TCP/UDP: test_rtu_over_tcp_sources.py)
        f"{path}: Ethernet (linktype 1): no TCP or UDP payload on the Modbus RTU ports (none given: --tcp-port "
        "and --udp-port, as the plugin's vw3.tcp_port and vw3.udp_port preferences, set them); its 1 packet: "
        "1 not IP")


def test_truncated_last_record_is_delivered_with_a_warning(tmp_path: Path) -> None:
    whole = pcap([(T0, 0, REQUEST), (T0, 10, RESPONSE)])
    path = write(tmp_path, "cut.pcap", whole[:-4])
    source = open_source(path)
    assert list(source) == [Chunk(REQUEST, float(T0), True), Chunk(RESPONSE[:-4], T0 + 1e-5, False)]
    assert source.warnings == [
        "record 2 is cut short: 7 of 11 bytes (the capture ends inside it); "
        "the bytes that are there are decoded"]
    items = list(dissect(open_source(path)))
    # (its answer cut by the end of the capture: answered, not counted unanswered)
    assert isinstance(items[0], Frame) and not items[0].unanswered
    assert items[0].notes == ["the capture ends inside the response (7 of 11 bytes)"]
    assert isinstance(items[1], Noise) and items[1].raw == RESPONSE[:-4]


def test_truncated_record_header_is_reported(tmp_path: Path) -> None:
    whole = pcap([(T0, 0, REQUEST), (T0, 10, RESPONSE)])
    source = open_source(write(tmp_path, "cut.pcap", whole[: 24 + 16 + 8 + 5]))
    assert list(source) == [Chunk(REQUEST, float(T0), True)]
    assert source.warnings == ["record 2: the capture ends inside its header (5 of 16 bytes)"]


def test_short_capture_length_is_reported(tmp_path: Path) -> None:
    source = open_source(write(tmp_path, "c", pcap([(T0, 0, REQUEST)], original=20)))
    # (a PartChunk: the framers cut at its end, framing/stream.py _cut_part)
    assert list(source) == [PartChunk(REQUEST, float(T0), True, 1, (), 8, 20)]
    assert source.warnings == ["record 1: only 8 of its 20 bytes were captured"]


def test_truncated_pcap_file_header_is_an_error(tmp_path: Path) -> None:
    path = write(tmp_path, "c", pcap([])[:10])
    with pytest.raises(SourceError, match=r"truncated pcap file header \(10 of 24 bytes\)"):
        open_source(path)


def test_format_pcap_on_something_else_is_an_error(tmp_path: Path) -> None:
    path = write(tmp_path, "c.pcap", REQUEST + RESPONSE)
    with pytest.raises(SourceError) as error:
        open_source(path, fmt="pcap")
    assert str(error.value) == f"{path}: not a pcap file (magic 0c0320d0)"


def test_big_record_comes_in_bounded_chunks(tmp_path: Path) -> None:
    data = bytes(range(256)) * 3
    source = open_source(write(tmp_path, "c", pcap([(T0, 7, data)])), chunk_size=300)
    assert list(source) == [Chunk(data[:300], T0 + 7e-6, False), Chunk(data[300:600], T0 + 7e-6, False),
                            Chunk(data[600:], T0 + 7e-6, True)]


# -- pcapng --------------------------------------------------------------------------------------
def test_pcapng_blocks_and_unknown_block(tmp_path: Path) -> None:
    o = "<"
    content = (shb(o) + idb(o, 147) + epb(o, 0, (T0 * 1_000_000) + 250_000, REQUEST)
               + block(o, 0x99, b"future") + spb(o, RESPONSE) + block(o, 5, b"\0" * 12)
               + opb(o, 0, (T0 + 1) * 1_000_000, FC43_REQUEST))
    source = open_source(write(tmp_path, "c", content))
    assert (source.format, source.mode) == ("pcapng", "rtu")
    assert list(source) == [Chunk(REQUEST, T0 + 0.25, True), Chunk(RESPONSE, None, True),
                            Chunk(FC43_REQUEST, float(T0 + 1), True)]
    unknown_at = len(shb(o) + idb(o, 147) + epb(o, 0, 0, REQUEST))
    assert source.warnings == [f"skipped a pcapng block of unknown type 0x00000099 at byte {unknown_at}"]


def test_pcapng_big_endian_tsresol_tsoffset_and_rtac(tmp_path: Path) -> None:
    o = ">"
    content = (shb(o) + idb(o, 147, tsresol=9, tsoffset=100) + idb(o, 250) + idb(o, 147, tsresol=0x80 | 10)
               + epb(o, 0, 1_500_000_000, REQUEST) + epb(o, 1, 7, rtac(T0, 40, RESPONSE))
               + epb(o, 2, 3 * 1024 + 512, EXCEPTION))
    source = open_source(write(tmp_path, "c", content))
    # ns resolution + 100 s offset; the RTAC header's own time; 2^-10 s resolution.
    assert list(source) == [Chunk(REQUEST, 101.5, True), Chunk(RESPONSE, T0 + 40e-6, True),
                            Chunk(EXCEPTION, 3.5, True)]
    assert source.warnings == ["packets come from several interfaces; their bytes are decoded as one stream "
                               "(vw3-decode FILE decodes each interface as its own bus: save standard input to a file)"]


def test_pcapng_interface_with_other_linktype_is_an_error(tmp_path: Path) -> None:
    o = "<"
    path = write(tmp_path, "c", shb(o) + idb(o, 1) + epb(o, 0, 0, REQUEST))
    with pytest.raises(SourceError, match=r": Ethernet \(linktype 1\): no TCP or UDP payload on the Modbus RTU "
                       r"ports \(none given: .*; its 1 packet: 1 not IP$"):
        list(open_source(path))


def test_pcapng_truncated_last_packet(tmp_path: Path) -> None:
    o = "<"
    content = shb(o) + idb(o, 147) + epb(o, 0, 5, REQUEST) + epb(o, 0, 6, RESPONSE)
    source = open_source(write(tmp_path, "c", content[:-8]))
    assert list(source) == [Chunk(REQUEST, 5e-6, True), Chunk(RESPONSE[:8], 6e-6, False)]
    assert source.warnings == [
        "record 2 is cut short: 8 of 11 bytes (the capture ends inside it); "
        "the bytes that are there are decoded"]


def test_pcapng_corrupt_block_length_is_an_error(tmp_path: Path) -> None:
    o = "<"
    bad = struct.pack("<II", 6, 13) + b"\0" * 8
    path = write(tmp_path, "c", shb(o) + idb(o, 147) + bad)
    with pytest.raises(SourceError, match="block at byte 48 has an invalid length 13"):
        list(open_source(path))


# -- hex dumps -----------------------------------------------------------------------------------
HEXDUMP = """\
# p.38: CHCF protected, then both protected
0C 03 20 D0 00 03 0E EF
0C0306 800080000002 CE24   # scenario 2

1700000000.125 0C 03 20 D0 00 03 0E EF
1700000000.1375 0C 83 02 51 32
"""


def test_hexdump_lines_comments_and_timestamps(tmp_path: Path) -> None:
    source = open_source(write(tmp_path, "frames.pcap", HEXDUMP.encode()))
    assert (source.format, source.mode) == ("hexdump", "rtu")
    assert list(source) == [Chunk(REQUEST, None, True), Chunk(RESPONSE_PROTECTED, None, True),
                            Chunk(REQUEST, 1700000000.125, True), Chunk(EXCEPTION, 1700000000.1375, True)]
    items = list(dissect(open_source(write(tmp_path, "f", HEXDUMP.encode()))))
    assert [(i.kind, i.crc_ok) for i in items] == [(Kind.REQUEST, True), (Kind.RESPONSE, True),
                                                   (Kind.REQUEST, True), (Kind.EXCEPTION, True)]
    assert items[3].response_time == pytest.approx(0.0125, abs=1e-6)
    assert [r.value for r in items[1].registers] == [0x8000, 0x8000, 2]


def test_hexdump_iso_and_time_of_day_stamps(tmp_path: Path) -> None:
    text = "2023-11-14T22:13:20.5 0C 03 20 D0 00 03 0E EF\n[22:13:20.75] 0C8302 5132\n"
    assert chunks(write(tmp_path, "f", text.encode())) == [
        Chunk(REQUEST, 1700000000.5, True), Chunk(EXCEPTION, 22 * 3600 + 13 * 60 + 20.75, True)]


def test_hexdump_bad_line_names_the_line(tmp_path: Path) -> None:
    path = write(tmp_path, "f", b"0C 03 20 D0 00 03 0E EF\n0C 03 2\n")
    with pytest.raises(SourceError) as error:
        list(open_source(path, fmt="hex"))
    assert str(error.value) == f"{path} line 2: '2' is an odd number of hex digits"


def test_format_hex_on_binary_is_an_error(tmp_path: Path) -> None:
    path = write(tmp_path, "f", REQUEST)
    with pytest.raises(SourceError, match="line 1: binary data in a hex dump"):
        list(open_source(path, fmt="hex"))


# -- raw, ASCII, detection -----------------------------------------------------------------------
def test_raw_file_in_bounded_chunks(tmp_path: Path) -> None:
    data = b"".join(SESSION) * 40
    source = open_source(write(tmp_path, "capture.pcap", data), chunk_size=256)
    got = list(source)
    assert (source.format, source.mode) == ("raw", "rtu")
    assert b"".join(c.data for c in got) == data
    assert all(len(c.data) <= 256 and c.time is None and not c.boundary for c in got)


def test_modbus_ascii_raw_file(tmp_path: Path) -> None:
    data = b":02062329000AA2\r\n:02062329000AA2\r\n"
    source = open_source(write(tmp_path, "a.pcapng", data))
    assert (source.format, source.mode) == ("ascii", "ascii")
    assert list(source) == [Chunk(data)]


def test_modbus_ascii_inside_pcap_records(tmp_path: Path) -> None:
    path = write(tmp_path, "a", pcap([(T0, 0, b":02062329000AA2\r\n"), (T0, 30_000, b":02062329000AA2\r\n")]))
    source = open_source(path)
    assert (source.format, source.mode) == ("pcap", "ascii")
    assert [c.time for c in source] == [float(T0), T0 + 0.03]


def test_text_that_is_neither_is_raw_with_a_warning(tmp_path: Path) -> None:
    path = write(tmp_path, "notes.txt", b"hello world\nthis is not a capture\n")
    source = open_source(path)
    assert (source.format, source.mode) == ("raw", "rtu")
    assert source.warnings == [
        f"{path}: the input is text, but neither a hex dump nor Modbus ASCII: decoded as raw bytes"]


def test_overrides(tmp_path: Path) -> None:
    path = write(tmp_path, "f", HEXDUMP.encode())
    source = open_source(path, fmt="raw", mode="ascii")
    assert (source.format, source.mode) == ("raw", "ascii")
    assert b"".join(c.data for c in source) == HEXDUMP.encode()
    with pytest.raises(SourceError, match="unknown format 'wav'"):
        open_source(path, fmt="wav")
    with pytest.raises(SourceError, match="unknown mode 'tcp'"):
        open_source(path, mode="tcp")


def test_stdin(monkeypatch: pytest.MonkeyPatch) -> None:
    content = pcap([(T0, 0, REQUEST), (T0, 12_000, RESPONSE)])
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BufferedReader(io.BytesIO(content))))
    source = open_source("-")
    assert (source.name, source.format) == ("standard input", "pcap")
    assert list(source) == [Chunk(REQUEST, float(T0), True), Chunk(RESPONSE, T0 + 0.012, True)]


def test_missing_directory_unreadable_gzip(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    missing = str(tmp_path / "nope.pcap")
    with pytest.raises(SourceError) as error:
        open_source(missing)
    assert str(error.value) == f"{missing}: no such file"
    with pytest.raises(SourceError) as error:
        open_source(str(tmp_path))
    assert str(error.value) == f"{tmp_path}: is a directory, not a capture"
    gz = write(tmp_path, "c.pcap.gz", gzip.compress(pcap([(T0, 0, REQUEST)])))
    with open_source(gz) as source:  # (decompressed as it is read: test_compressed_input.py)
        assert (source.format, list(source)) == ("pcap", [Chunk(REQUEST, float(T0), True)])
    # Root reads anything, so permission is simulated where the file is opened.
    locked = write(tmp_path, "locked", REQUEST)

    def refuse(*args: object, **kwargs: object) -> None:
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(sources, "open", refuse, raising=False)
    with pytest.raises(SourceError) as error:
        open_source(locked)
    assert str(error.value) == f"{locked}: permission denied"


def test_empty_input(tmp_path: Path) -> None:
    path = write(tmp_path, "empty", b"")
    source = open_source(path)
    assert (source.format, source.mode, list(source)) == ("raw", "rtu", [])
    assert source.warnings == [f"{path}: the input is empty"]


# -- the split does not matter -------------------------------------------------------------------
def test_one_record_per_frame_or_any_split_gives_the_same_frames(tmp_path: Path) -> None:
    per_frame = pcap([(s, us, data) for (s, us), data in zip(TIMES, SESSION)])
    stream = b"".join(SESSION)
    # The same bytes in records of 3 bytes, each stamped with the time of the frame it starts in.
    starts, position = [], 0
    for (s, us), data in zip(TIMES, SESSION):
        starts.append((position, s, us))
        position += len(data)
    records = []
    for offset in range(0, len(stream), 3):
        s, us = next((s, us) for start, s, us in reversed(starts) if start <= offset)
        records.append((s, us, stream[offset : offset + 3]))
    split = pcap(records)
    whole = list(dissect(open_source(write(tmp_path, "a", per_frame))))
    pieces = list(dissect(open_source(write(tmp_path, "b", split))))
    raw = list(dissect(open_source(write(tmp_path, "c", stream))))
    hexdump = "\n".join(data.hex(" ") for data in SESSION).encode()
    lines = list(dissect(open_source(write(tmp_path, "d", hexdump))))
    assert len(whole) == len(SESSION)
    untimed = [entry[:6] + (None,) + entry[7:] for entry in summary(whole)]
    assert [entry[:6] + (None,) + entry[7:] for entry in summary(pieces)] == untimed
    # A frame's time is that of the record its first byte came in.
    assert [item.time for item in pieces] == [
        records[item.offset // 3][0] + records[item.offset // 3][1] / 1_000_000 for item in pieces]
    assert summary(raw) == untimed
    assert summary(lines) == untimed


def test_format_pcapng_on_a_pcap_is_an_error(tmp_path: Path) -> None:
    path = write(tmp_path, "c", pcap([(T0, 0, REQUEST)]))
    with pytest.raises(SourceError) as error:
        list(open_source(path, fmt="pcapng"))
    assert str(error.value) == f"{path}: not a pcapng file (no section header block)"


def test_take_warnings_returns_each_warning_once(tmp_path: Path) -> None:
    records = [(T0, k, rtac(T0, k, REQUEST, event=0x07)) for k in range(8)]
    source = open_source(write(tmp_path, "c", pcap(records, linktype=250)))
    iterator = iter(source)
    next(iterator)
    # Mode detection read ahead 64 payload bytes: the first 8 records.
    assert len(source.take_warnings()) == 5
    assert len(list(iterator)) == 7
    assert source.take_warnings() == ["... and 3 more RTAC line events"]
    assert source.take_warnings() == []


@pytest.mark.integration
@pytest.mark.parametrize("target", ["pcapng", "nsecpcap"])
def test_files_written_by_wireshark_editcap(tmp_path: Path, target: str) -> None:
    """Wireshark's own writer as an oracle: its pcapng and nanosecond pcap read back the same."""
    editcap = ensure_tool("editcap", "tshark")  # Debian's tshark brings editcap (wireshark-common)
    records = [(s, us, data) for (s, us), data in zip(TIMES, SESSION)]
    original = write(tmp_path, "a.pcap", pcap(records))
    converted = str(tmp_path / "b")
    subprocess.run([editcap, "-F", target, original, converted], check=True, capture_output=True)
    source = open_source(converted)
    assert source.format == ("pcapng" if target == "pcapng" else "pcap")
    assert list(source) == session_chunks()
    assert source.warnings == []
