"""Packet hex dumps as `tshark -x` and `vw3-decode -x` print them (hunt 58): pasting the dump a Wireshark user
has in front of them was refused (`line 1: '.+...4w' is not hex`: read as a one-frame-a-line hex dump, the
character column taken for bytes), and `vw3-decode -x`'s own output read as 706 bytes of noise. Each packet
(offset 0000 on) is one record; summary lines are passed over, as text2pcap passes them; the bytes are
those text2pcap gives."""
from __future__ import annotations

import subprocess


from conftest import ROOT
from helpers import run_cli
from lua_harness import ensure_tool

ATV71 = str(ROOT / "captures" / "atv71_commissioning.pcap")
MBRTU = ["-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""']

# tshark 4.0.17 -x of p38_protection.pcap's first two records, as printed (bytes 0x80 and 0x20 in a column).
P38_X = """\
0000  0c 03 20 d0 00 03 0e ef                           .. .....

0000  0c 03 06 80 00 00 03 00 02 17 e4                  ...........

"""


def _decode(tmp_path, text: str, *argv: str) -> tuple[int, str, str]:
    path = tmp_path / "dump.txt"
    path.write_text(text)
    return run_cli([*argv, str(path)])


def test_tshark_x_dump_is_read_as_packets(tmp_path):
    assert _decode(tmp_path, P38_X) == (0, (
        "     1            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#1]  CRC ok\n"
    ), "")


def test_vw3_decode_x_reads_back(tmp_path):
    """Summary lines between the dumps are passed over; every item, frames and noise, comes back whole."""
    capture = str(ROOT / "captures" / "noisy_bus.bin")
    status, dump, _ = run_cli(["-x", capture])
    assert status == 0
    keys = ["-T", "fields", "-e", "frame", "-e", "kind", "-e", "offset", "-e", "raw"]
    assert _decode(tmp_path, dump, *keys) == run_cli([*keys, capture])


def test_lines_missing_or_cut(tmp_path):
    first, second = P38_X.split("\n\n")[:2]
    long = "0000  " + " ".join(["00"] * 16) + "   " + "." * 16 + "\n"
    status, out, err = _decode(tmp_path, long + "0020  0c 03                                             ..\n")
    assert (status, out) == (2, "")
    assert err == f"vw3-decode: {tmp_path}/dump.txt line 2: offset 0x0020 where 0x0010 was expected (bytes missing or repeated)\n"
    status, out, err = _decode(tmp_path, first + "\n" + second[:19])  # copied while tshark wrote it
    assert status == 0
    assert err == (f"vw3-decode: warning: {tmp_path}/dump.txt line 2 is cut short (the input ends inside it, without a line"
                   " end): its 4 whole bytes are decoded, the rest ('0') is not\n")
    assert out.splitlines()[1] == "     2            -   - noise     4 bytes of noise at offset 8: 0c 03 06 80"


def test_one_line_without_line_end(tmp_path):
    assert _decode(tmp_path, P38_X.split("\n")[0], "-T", "fields", "-e", "raw") == (0, "0c0320d000030eef\n", "")


def test_a_hex_dump_without_character_column_stays_one(tmp_path):
    """`0000  0C 03 ...` with no character column is a hex dump line, as before: its bytes are 00 00 0C 03 ..."""
    status, out, _ = _decode(tmp_path, "0000  0C 03 20 D0 00 03 0E EF\n", "-T", "fields", "-e", "raw")
    assert (status, out) == (0, "0000\n0c0320d000030eef\n")


def test_same_bytes_as_text2pcap(tmp_path):
    ensure_tool("tshark", "tshark")  # (a missing tool fails, never skips)
    ensure_tool("text2pcap", "wireshark-common")  # (a missing tool fails, never skips)
    dump = subprocess.run(["tshark", *MBRTU, "-r", ATV71, "-x"], capture_output=True, text=True, check=True).stdout
    (tmp_path / "x.txt").write_text(dump)
    subprocess.run(["text2pcap", "-q", "-l", "147", str(tmp_path / "x.txt"), str(tmp_path / "t.pcap")], check=True,
                   capture_output=True)
    keys = ["-T", "fields", "-e", "frame", "-e", "kind", "-e", "raw"]
    ours, theirs = run_cli([*keys, str(tmp_path / "x.txt")]), run_cli([*keys, str(tmp_path / "t.pcap")])
    assert ours[0] == 0 and ours == theirs
    assert len(ours[1].splitlines()) == 104
