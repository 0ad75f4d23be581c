"""A capture file with its headers and no packet: tshark prints nothing; vw3-decode says why its output
is empty (as for an empty file) and exits 0, in every output."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import run_cli

PCAP_HEADER = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)


def _block(block_type: int, body: bytes) -> bytes:
    total = 12 + len(body)
    return struct.pack("<II", block_type, total) + body + struct.pack("<I", total)


SHB = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
IDB = _block(1, struct.pack("<HHI", 147, 0, 0))


@pytest.mark.parametrize(
    ("name", "data", "said"),
    [
        ("header.pcap", PCAP_HEADER, "header.pcap: the capture holds no records"),
        ("section.pcapng", SHB, "section.pcapng: the capture holds no packets"),
        ("interface.pcapng", SHB + IDB, "interface.pcapng: the capture holds no packets"),
    ],
    ids=["pcap", "pcapng-section", "pcapng-interface"],
)
@pytest.mark.parametrize("options", [[], ["--stats"], ["--json"], ["-V"]])
def test_no_packets_is_told(tmp_path: Path, name: str, data: bytes, said: str, options: list[str]) -> None:
    path = tmp_path / name
    path.write_bytes(data)
    status, _, err = run_cli([*options, str(path)])
    assert status == 0
    assert err.endswith(f"warning: {path}: the capture holds no {said.split('holds no ')[1]}\n")
    assert err.count("holds no") == 1


def test_a_capture_with_packets_is_not_told_empty(tmp_path: Path) -> None:
    record = struct.pack("<IIII", 1, 0, 4, 4) + bytes.fromhex("0C830251")
    path = tmp_path / "one.pcap"
    path.write_bytes(PCAP_HEADER + record)
    status, _, err = run_cli([str(path)])
    assert "holds no" not in err
