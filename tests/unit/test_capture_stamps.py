"""Record time stamps of pcap and pcapng files: a record at the epoch, fractions of a second that are not.

vw3-decode -w writes untimed input at the epoch, every record, and reads such records back untimed; a
capture whose first record is at 1970-01-01 00:00:00 and whose next ones are later (a time-of-day log of
day 0) is timed (sources/pcap.py EpochRecord). A fraction of a second of 1 s or more (pcap usec, nsec,
an RTAC serial header's microseconds) is a corrupt stamp: its record decoded untimed, with a warning.
"""
from __future__ import annotations

import json
import shutil
import struct
import subprocess
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

REQUEST = bytes.fromhex("0C0320D000030EEF")
RESPONSE = bytes.fromhex("0C030680000003000217E4")
MIDNIGHT = ("00:00:00.000 0C 03 20 D0 00 03 0E EF\n00:00:00.010 0C 03 06 80 00 00 03 00 02 17 E4\n"
            "00:00:00.500 0C 03 20 D0 00 03 0E EF\n00:00:00.512 0C 03 06 80 00 00 03 00 02 17 E4\n")
READ = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
ANSWER = ("12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) "
          "COP=Cd (command)")
TIMED = [
    f"     1     0.000000  {READ}",
    f"     2     0.010000  {ANSWER} [#1, 10.0 ms]  CRC ok",
    f"     3     0.500000  {READ}",
    f"     4     0.512000  {ANSWER} [#3, 12.0 ms]  CRC ok",
]
UNTIMED = [
    f"     1            -  {READ}",
    f"     2            -  {ANSWER} [#1]  CRC ok",
    f"     3            -  {READ}",
    f"     4            -  {ANSWER} [#3]  CRC ok",
]
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def _pcap(records: list[tuple[int, int, bytes]], linktype: int = 147, nano: bool = False) -> bytes:
    magic = 0xA1B23C4D if nano else 0xA1B2C3D4
    out = struct.pack("<IHHiIII", magic, 2, 4, 0, 0, 65535, linktype)
    for seconds, fraction, data in records:
        out += struct.pack("<IIII", seconds, fraction, len(data), len(data)) + data
    return out


def _pcapng(records: list[tuple[int, int, bytes]]) -> bytes:
    """One interface (linktype 147, microseconds) and its packets (seconds, microseconds, bytes)."""
    def block(kind: int, body: bytes) -> bytes:
        return struct.pack("<II", kind, 12 + len(body)) + body + struct.pack("<I", 12 + len(body))

    out = block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1)) + block(1, struct.pack("<HHI", 147, 0, 0))
    for seconds, micros, data in records:
        stamp = seconds * 1_000_000 + micros
        out += block(6, struct.pack("<IIIII", 0, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data))
                     + data + b"\0" * (-len(data) % 4))
    return out


def _decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> tuple[int, str, str]:
    use_engine(monkeypatch, pure)
    return run_cli(argv)


@BOTH
@pytest.mark.parametrize("fmt", ["pcap", "pcapng"])
def test_a_log_from_midnight_of_day_0_reads_back_timed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, fmt: str
) -> None:
    log, out = tmp_path / "midnight.txt", tmp_path / f"m.{fmt}"
    log.write_text(MIDNIGHT)
    status, _, err = _decode([str(log), "-w", str(out), "-F", fmt], monkeypatch, pure)
    assert status == 0, err
    status, text, err = _decode([str(out)], monkeypatch, pure)
    assert (status, err, text.splitlines()) == (0, "", TIMED)
    items = [json.loads(line) for line in _decode([str(out), "--json"], monkeypatch, pure)[1].splitlines()]
    assert [(item["time"], item.get("response_time")) for item in items] == [
        (0.0, None), (0.01, 0.01), (0.5, None), (0.512, 0.012)]
    stats = _decode([str(out), "--stats"], monkeypatch, pure)[1]
    assert "   12  3 Read Holding Registers      2  10.0    11.0  12.0  12.0" in stats.splitlines()
    tshark = shutil.which("tshark")
    if tshark:  # the oracle: Wireshark's times of the very records
        times = subprocess.run([tshark, "-r", str(out), "-T", "fields", "-e", "frame.time_epoch"],
                               capture_output=True, text=True, check=True).stdout.split()
        assert times == ["0.000000000", "0.010000000", "0.500000000", "0.512000000"]


@BOTH
@pytest.mark.parametrize("fmt", ["pcap", "pcapng"])
def test_untimed_input_written_by_w_still_reads_back_untimed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, fmt: str
) -> None:
    hex_dump, out = tmp_path / "untimed.txt", tmp_path / f"u.{fmt}"
    hex_dump.write_text("".join(line[13:] + "\n" for line in MIDNIGHT.splitlines()))
    status, _, err = _decode([str(hex_dump), "-w", str(out), "-F", fmt], monkeypatch, pure)
    assert status == 0, err
    status, text, err = _decode([str(out)], monkeypatch, pure)
    assert (status, err, text.splitlines()) == (0, "", UNTIMED)


@BOTH
def test_only_the_first_record_at_the_epoch_can_be_timed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    # Records 1, 2 at the epoch: both untimed (the second says so of the first). Then a timed capture with
    # a later record at the epoch (past the first records, where the engine reads records in bulk): that
    # one is untimed, as -w writes an untimed chunk between timed ones.
    path = tmp_path / "e.pcap"
    path.write_bytes(_pcap([(0, 0, REQUEST), (0, 0, RESPONSE)]))
    lines = _decode([str(path)], monkeypatch, pure)[1].splitlines()
    assert [line[:20] for line in lines] == ["     1            - ", "     2            - "]
    records = [(0, 0, REQUEST), (0, 10_000, RESPONSE), (0, 500_000, REQUEST), (0, 512_000, RESPONSE),
               (0, 0, REQUEST), (0, 600_000, RESPONSE)]
    path.write_bytes(_pcap(records))
    lines = _decode([str(path)], monkeypatch, pure)[1].splitlines()
    assert [line[:20] for line in lines] == [
        "     1     0.000000 ", "     2     0.010000 ", "     3     0.500000 ", "     4     0.512000 ",
        "     5            - ", "     6     0.600000 "]


@BOTH
@pytest.mark.parametrize("pcapng", [False, True])
def test_a_first_record_at_the_epoch_before_a_real_date_is_untimed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, pcapng: bool
) -> None:
    # Timed only as the start of a time-of-day log of day 0: before a record of 2023 it is untimed, not
    # the start of a 54-year silence inside the request (the request's bytes cut across the two records).
    records = [(0, 0, REQUEST[:3]), (1_700_000_000, 500_000, REQUEST[3:]), (1_700_000_000, 520_000, RESPONSE)]
    path = tmp_path / ("e.pcapng" if pcapng else "e.pcap")
    path.write_bytes(_pcapng(records) if pcapng else _pcap(records))
    status, text, err = _decode([str(path), "-t", "r"], monkeypatch, pure)
    assert (status, err) == (0, "")
    assert [line[:20] for line in text.splitlines()] == ["     1            - ", "     2     0.000000 "]
    assert "[#1]" in text and "silence" not in text and "timeout" not in text
    day_zero = [(0, 0, REQUEST[:3]), (3_600, 500_000, REQUEST[3:]), (3_600, 520_000, RESPONSE)]
    path.write_bytes(_pcapng(day_zero) if pcapng else _pcap(day_zero))
    text = _decode([str(path), "-t", "r"], monkeypatch, pure)[1]
    assert "silence of 3600498.281 ms inside the frame before byte 3" in text


@BOTH
@pytest.mark.parametrize("nano, fraction, units", [(False, 4_000_000_000, 1_000_000), (False, 1_000_000, 1_000_000),
                                                   (True, 1_000_000_000, 1_000_000_000)])
def test_a_fraction_of_a_second_of_1_s_or_more_is_decoded_untimed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, nano: bool, fraction: int, units: int
) -> None:
    """The record's bytes decoded untimed with a warning, the file not refused: tshark 4.0 reads it (its
    column shows the stamp unnormalised). Before, the whole file was refused (exit 2)."""
    # Record 4: past the first records, where the engine reads records in bulk (it hands this one back).
    path = tmp_path / "usec.pcap"
    path.write_bytes(_pcap([(100, 1, REQUEST), (100, 2, RESPONSE), (100, 3, REQUEST), (100, fraction, RESPONSE),
                            (101, 0, REQUEST)], nano=nano))
    status, out, err = _decode([str(path)], monkeypatch, pure)
    zero = "0." + "0" * (9 if nano else 6)
    assert (status, err) == (0, f"vw3-decode: warning: record 4: fraction of a second {fraction} is not below "
                                f"{units} (1 s in the file's units): a corrupt time stamp? Its bytes are decoded "
                                "untimed\n")
    assert [line[:20] for line in out.splitlines()] == [
        f"     1 {zero:>12} ", "     2 " + ("0.000000001" if nano else "0.000001").rjust(12) + " ",
        "     3 " + ("0.000000002" if nano else "0.000002").rjust(12) + " ", "     4            - ",
        "     5 " + ("0.999999999" if nano else "0.999999").rjust(12) + " "]
    assert out.splitlines()[3].endswith("[#3]  CRC ok")  # (no response time from a stamp not known)
    path.write_bytes(_pcap([(100, fraction, REQUEST)], nano=nano))
    status, out, err = _decode([str(path), "--json"], monkeypatch, pure)
    assert (status, json.loads(out)["time"], err.count("corrupt time stamp?")) == (0, None, 1)


def _rtac(seconds: int, micros: int, data: bytes) -> bytes:
    return struct.pack(">IIBBH", seconds, micros, 1, 0, 0) + data


@BOTH
def test_rtac_microseconds_of_1_s_or_more_are_decoded_untimed(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    path = tmp_path / "rtac.pcap"
    path.write_bytes(_pcap([(100, 0, _rtac(15815525, 999_999, REQUEST)),
                            (100, 0, _rtac(15815525, 0xFFFFFFFF, RESPONSE))], linktype=250))
    status, out, err = _decode([str(path)], monkeypatch, pure)
    assert (status, err) == (0, "vw3-decode: warning: record 2: RTAC microseconds 4294967295 are not below "
                                "1000000: a corrupt time stamp? Its bytes are decoded untimed\n")
    assert out.splitlines()[1].startswith("     2            -  12 response") and out.endswith("[#1]  CRC ok\n")
    path.write_bytes(_pcap([(0, 0, _rtac(15815525, 990_000, REQUEST)),
                            (0, 0, _rtac(15815526, 0, RESPONSE))], linktype=250))
    status, out, err = _decode([str(path)], monkeypatch, pure)
    assert (status, err) == (0, "")
    assert out.splitlines()[1].endswith("8400=32768 8401=3 8402=2 [#1, 10.0 ms]  CRC ok")
