"""Modified pcap (Alexey Kuznetzov's patched libpcap; editcap -F modpcap; magic a1b2cd34): each record
header is the standard 16 bytes plus ifindex u32, protocol u16, pkt_type u8, pad u8. Before, it was not
recognised: read as raw bytes, '48 bytes of noise' then frames with the 24-byte record headers between
them as noise; tshark reads it. Now its records decode as the standard pcap's of the same records."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER = bytes.fromhex("0C0306000100020003A5E4")  # 8400=1, CHCF=SEP, COP=ALL
RECORDS = [(1_767_225_600, 0, REQUEST), (1_767_225_600, 10_000, ANSWER)]
LINES = ["     1     0.000000  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
         "     2     0.010000  12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3 "
         "[#1, 10.0 ms]  CRC ok"]
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def _modified(order: str, records: list[tuple[int, int, bytes]]) -> bytes:
    out = struct.pack(order + "IHHiIII", 0xA1B2CD34, 2, 4, 0, 0, 65535, 147)
    for seconds, micros, data in records:
        out += struct.pack(order + "IIIIIHBB", seconds, micros, len(data), len(data), 3, 0x0800, 4, 0) + data
    return out


@BOTH
@pytest.mark.parametrize("order", ["<", ">"], ids=["little", "big"])
def test_modified_pcap_is_read(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, order: str) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "modified.pcap"
    path.write_bytes(_modified(order, RECORDS))
    status, out, err = run_cli([str(path)])
    assert (status, err) == (0, "")
    assert out.splitlines() == LINES


@BOTH
def test_modified_pcap_header_cut_short(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "cut.pcap"
    path.write_bytes(_modified("<", RECORDS)[:-len(ANSWER) - 4])  # the second record's header, 20 of 24 bytes
    status, out, err = run_cli([str(path)])
    assert status == 0
    assert out.splitlines() == [
        "     1     0.000000  12 request   Read Holding Registers 8400..8402 (3) [the capture ends before "
        "any response: not known whether it was answered]  CRC ok"]
    assert err.splitlines() == [
        "vw3-decode: warning: record 2: the capture ends inside its header (20 of 24 bytes)"]
