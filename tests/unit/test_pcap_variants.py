"""The pcap variants wiretap's libpcap.c reads besides the standard one and modpcap, told apart as it does
(the first two record headers read under each record header size, the first that looks sane taken): the
standard magic with 24-byte record headers (ss990417, RedHat 6.1's tcpdump: editcap -F rh6_1pcap) or 20-byte
ones (Nokia IPSO: -F nokiapcap), the modified magic with 28-byte ones (ss990915, SuSE 6.3's: -F suse6_3pcap).
tshark reads all three. Before, their records were read with the standard (or modpcap's 24-byte) headers:
the extra bytes decoded as serial bytes and every record after the first astray ("record 2: fraction of a
second 1767225600 is not below 1000000", "1767225600 bytes, more than the file header's snapshot length")."""
from __future__ import annotations

import gzip
import struct
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER = bytes.fromhex("0C0306000100020003A5E4")  # 8400=1, CHCF=SEP, COP=ALL
RECORDS = [(1_767_225_600, 0, REQUEST), (1_767_225_600, 10_000, ANSWER), (1_767_225_600, 50_000, REQUEST)]
LINES = ["     1     0.000000  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
         "     2     0.010000  12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3 "
         "[#1, 10.0 ms]  CRC ok",
         "     3     0.050000  12 request   Read Holding Registers 8400..8402 (3) [the capture ends before any "
         "response: not known whether it was answered]  CRC ok"]
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
# (magic, the record header's bytes after the standard 16, as wiretap's writer fills them)
VARIANTS = {
    "rh6_1pcap": (0xA1B2C3D4, struct.pack("IHBB", 3, 0x0800, 4, 0)),  # ifindex, protocol, pkt_type, pad
    "nokiapcap": (0xA1B2C3D4, b"\0" * 4),  # "mysterious stuff", as editcap writes it
    "suse6_3pcap": (0xA1B2CD34, struct.pack("IHBBBBH", 3, 0x0800, 4, 0, 1, 2, 0)),  # ... cpu1, cpu2, pad
}


def _variant(name: str, order: str, records: list[tuple[int, int, bytes]] = RECORDS) -> bytes:
    magic, extra = VARIANTS[name]
    out = struct.pack(order + "IHHiIII", magic, 2, 4, 0, 0, 65535, 147)
    for seconds, micros, data in records:
        out += struct.pack(order + "IIII", seconds, micros, len(data), len(data)) + extra + data
    return out


@BOTH
@pytest.mark.parametrize("order", ["<", ">"], ids=["little", "big"])
@pytest.mark.parametrize("name", list(VARIANTS))
def test_a_variant_is_read_as_tshark_reads_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                              order: str, name: str) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / f"{name}.pcap"
    path.write_bytes(_variant(name, order))
    status, out, err = run_cli([str(path)])
    assert (status, err) == (0, "")
    assert out.splitlines() == LINES
    packed = tmp_path / f"{name}.pcap.gz"  # (a compressed file is read ahead as a file is)
    packed.write_bytes(gzip.compress(path.read_bytes(), mtime=0))
    assert run_cli([str(packed)]) == (0, "\n".join(LINES) + "\n", "")


def test_one_record_of_a_variant(tmp_path: Path) -> None:
    # (no second record to tell by: the first variant whose first header is sane, as wiretap at the file's end)
    path = tmp_path / "one.pcap"
    path.write_bytes(_variant("rh6_1pcap", "<", RECORDS[:1]))
    status, out, _err = run_cli([str(path)])
    assert status == 0
    assert out.splitlines()[0] == "     1     0.000000   - noise     8 bytes of noise at offset 0: 03 00 00 00 00 08 04 00"


def test_a_standard_pcap_with_a_corrupt_stamp_stays_standard(tmp_path: Path) -> None:
    # (every variant's first header is the standard one's: a corrupt first record counts against each alike)
    path = tmp_path / "corrupt.pcap"
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)
    for seconds, micros, data in [(1_767_225_600, 4_000_000_000, REQUEST), *RECORDS[1:]]:
        out += struct.pack("<IIII", seconds, micros, len(data), len(data)) + data
    path.write_bytes(out)
    status, lines, err = run_cli([str(path)])
    assert status == 0
    assert err == ("vw3-decode: warning: record 1: fraction of a second 4000000000 is not below 1000000 (1 s in "
                   "the file's units): a corrupt time stamp? Its bytes are decoded untimed\n")
    assert [line.split()[-2:] for line in lines.splitlines()] == [["CRC", "ok"]] * 3
