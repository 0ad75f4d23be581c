"""Inputs whose own header or marks say something is off: a pcap record longer than the file's snapshot
length (sources/pcap.py), an xxd or hexdump -C dump whose head was cut off (sources/dumps.py dump_tool:
the tool's own marks tell it from a plain hex dump, and its reader names the missing bytes)."""
from __future__ import annotations

import struct
import subprocess
import sys
from pathlib import Path

from dissector.protocol.crc import with_crc

REQUEST = with_crc(bytes.fromhex("010300000001"))
ANSWER = with_crc(bytes.fromhex("0103020005"))


def decode(path: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "dissector", str(path)], capture_output=True, text=True)


def pcap_with_snaplen(snaplen: int, records: list[bytes]) -> bytes:
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, snaplen, 147)
    for index, data in enumerate(records):
        out += struct.pack("<IIII", 1_700_000_000 + index, 0, len(data), len(data)) + data
    return out


def test_record_longer_than_snaplen_is_warned(tmp_path: Path) -> None:
    path = tmp_path / "snap.pcap"
    path.write_bytes(pcap_with_snaplen(4, [REQUEST, ANSWER]))
    run = decode(path)
    assert run.returncode == 0
    assert run.stdout.splitlines()[0].split()[3:7] == ["request", "Read", "Holding", "Registers"]
    assert run.stderr.splitlines() == [
        "vw3-decode: warning: record 1: 8 bytes, more than the file header's snapshot length (4): a damaged file?",
        "vw3-decode: warning: record 2: 7 bytes, more than the file header's snapshot length (4): a damaged file?",
    ]


def test_records_within_snaplen_are_not_warned(tmp_path: Path) -> None:
    path = tmp_path / "ok.pcap"
    path.write_bytes(pcap_with_snaplen(8, [REQUEST, ANSWER]))
    run = decode(path)
    assert run.returncode == 0 and run.stderr == ""


def test_hexdump_c_cut_at_its_head_names_the_missing_bytes(tmp_path: Path) -> None:
    data = REQUEST + ANSWER
    path = tmp_path / "tail.hd"
    # `hexdump -C` of the 15 bytes, its first line (offset 0) deleted
    path.write_text(f"00000010  {' '.join(f'{b:02x}' for b in data[16:])}  |.|\n0000000f\n" if len(data) > 16 else
                    f"00000008  {' '.join(f'{b:02x}' for b in data[8:])}" + " " * 4 + "|.......|\n0000000f\n")
    run = decode(path)
    assert run.returncode == 2
    assert run.stderr == f"vw3-decode: {path} line 1: offset 0x8 where 0x0 was expected (bytes missing or repeated)\n"
    assert run.stdout == ""


def test_xxd_cut_at_its_head_names_the_missing_bytes(tmp_path: Path) -> None:
    path = tmp_path / "tail.xxd"
    path.write_text("00000008: 0103 0200 0578 47                        .....xG\n")
    run = decode(path)
    assert run.returncode == 2
    assert run.stderr == f"vw3-decode: {path} line 1: offset 0x8 where 0x0 was expected (bytes missing or repeated)\n"


def test_plain_hex_lines_with_an_offset_like_first_word_stay_a_hex_dump(tmp_path: Path) -> None:
    # no |...| column: a plain hex dump whose first word is 8 digits is not hexdump -C's offset
    path = tmp_path / "plain.txt"
    path.write_text(f"{REQUEST[:4].hex()}  {' '.join(f'{b:02x}' for b in REQUEST[4:])}\n")
    run = decode(path)
    assert run.returncode == 0, run.stderr
    assert "request   Read Holding Registers 0" in run.stdout
