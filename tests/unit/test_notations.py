"""Notations people paste (issue 26): colon hex (ESPHome), 0x bytes, decimal lists (NModbus), a whole
capture on one line longer than the format sniffer's sample; and dumps whose `*` lines claim far more
bytes than they hold (issue 32). Vectors: the issue's own frames.

NModbus writes frames as `string.Join(", ", frame)`: `TX: 1, 3, 0, 22, 0, 2, 37, 207` is
01 03 00 16 00 02 25 CF (read 2 holding registers at 22 of slave 1, CRC 0xCF25).
"""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.model import Chunk
from dissector.sources import dumps
from dissector.sources.reader import SourceError, open_source
from helpers import run_cli

READ_22 = "     1            -   1 request   Read Holding Registers 22..23 (2) " \
          "[the capture ends before any response: not known whether it was answered]  CRC ok\n"
READ_22_PAIR = (
    "     1            -   1 request   Read Holding Registers 22..23 (2)  CRC ok\n"
    "     2            -   1 response  Read Holding Registers 22..23 (2): 22=1 23=2 [#1]  CRC ok\n"
)
# ESPHome's log of a read of 80 input registers at 0 of slave 2; the CRC is F0 05 on the wire.
ESPHOME = "     1            -   2 request   Read Input Registers 0..79 (80) " \
          "[the capture ends before any response: not known whether it was answered]  CRC ok\n"


def decode(tmp_path: Path, text: str, *options: str) -> tuple[int, str, str]:
    path = tmp_path / "pasted.txt"
    path.write_text(text)
    status, out, err = run_cli([*options, str(path)])
    return status, out, err.replace(f"{path}", "pasted.txt")


@pytest.mark.parametrize(
    "text",
    [
        "02:04:00:00:00:50:F0:05\n",
        "0x02 0x04 0x00 0x00 0x00 0x50 0xF0 0x05\n",
        "{0x2, 0x4, 0x0, 0x0, 0x0, 0x50, 0xf0, 0x5}\n",
        "0x020400000050 0xF005\n",
        "[2, 4, 0, 0, 0, 80, 240, 5]\n",
        "2,4,0,0,0,80,240,5\n",
    ],
)
def test_each_notation_of_one_frame_in_a_file(tmp_path: Path, text: str) -> None:
    assert decode(tmp_path, text) == (0, ESPHOME, "")


def test_colon_hex_after_a_time_stamp(tmp_path: Path) -> None:
    assert decode(tmp_path, "[10:15:30.125] 02:04:00:00:00:50:f0:05\n") == (
        0, ESPHOME.replace("            -", "     0.000000"), "")


@pytest.mark.parametrize(
    "typed",
    ["02:04:00:00:00:50:F0:05", "0x02 0x04 0x00 0x00 0x00 0x50 0xF0 0x05", "0x2,0x4,0x0,0x0,0x0,0x50,0xf0,0x5",
     "2, 4, 0, 0, 0, 80, 240, 5", "[2, 4, 0, 0, 0, 80, 240, 5]"],
)
def test_each_notation_typed_with_hex(typed: str) -> None:
    assert run_cli(["--hex", typed]) == (0, ESPHOME, "")


def test_nmodbus_log_lines_are_decimal(tmp_path: Path) -> None:
    text = "TX: 1, 3, 0, 22, 0, 2, 37, 207\nRX: 1, 3, 4, 0, 1, 0, 2, 42, 50\n"
    assert decode(tmp_path, text) == (0, READ_22_PAIR, "")
    assert run_cli(["--hex", "1, 3, 0, 22, 0, 2, 37, 207", "--hex", "1, 3, 4, 0, 1, 0, 2, 42, 50"]) == (
        0, READ_22_PAIR, "")


def test_decimal_lines_are_chunks_of_their_bytes(tmp_path: Path) -> None:
    path = tmp_path / "d.txt"
    path.write_text("12.5 1, 3, 0, 22, 0, 2, 37, 207\n1 3 4 0 1 0 2 42 50\n# two-digit numbers follow the input\n"
                    "10 20, 30\n")
    source = open_source(str(path))
    assert list(source) == [Chunk(bytes.fromhex("01030016000225CF"), 12.5, True),
                            Chunk(bytes.fromhex("010304000100022A32"), None, True),
                            Chunk(bytes([10, 20, 30]), None, True)]
    assert source.format == "hexdump"


def test_a_list_that_may_be_decimal_or_hex_is_refused(tmp_path: Path) -> None:
    refused = ("'10, 20, 30, 40' may be decimal or hex: write hex as 0x10 or without commas, "
               "or give --format decimal or --format hex")
    assert decode(tmp_path, "10, 20, 30, 40\n") == (2, "", f"vw3-decode: pasted.txt line 1: {refused}\n")
    assert run_cli(["--hex", "10, 20, 30, 40"]) == (2, "", f"vw3-decode: --hex: {refused}\n")
    assert decode(tmp_path, "10, 20, 30, 40\n", "--format", "decimal")[1] == (
        "     1            -   - noise     4 bytes of noise at offset 0: 0a 14 1e 28\n")
    assert decode(tmp_path, "10, 20, 30, 40\n", "--format", "hex")[1] == (
        "     1            -   - noise     4 bytes of noise at offset 0: 10 20 30 40\n")
    # without commas two-digit numbers are the hex dump's own notation, as always
    assert decode(tmp_path, "10 20 30 40\n")[1] == (
        "     1            -   - noise     4 bytes of noise at offset 0: 10 20 30 40\n")


def test_an_input_that_mixes_hex_and_decimal_is_refused_where_it_does(tmp_path: Path) -> None:
    assert decode(tmp_path, "01 03 00 16 00 02 25 CF\n1, 3, 4, 0, 1, 0, 2, 42, 50\n") == (
        2, "",  # the request waits for its answer when the error stops the reading (as for any bad line)
        "vw3-decode: pasted.txt line 2: decimal '1', but line 1 ('CF') was read as hex: one notation an input\n")
    assert decode(tmp_path, "1, 3, 0, 22, 0, 2, 37, 207\n01 03 04 00 01 00 02 2A 32\n")[2] == (
        "vw3-decode: pasted.txt line 2: hex '2A', but line 1 ('1') was read as decimal: one notation an input\n")
    assert run_cli(["--hex", "0C 3 00 16"]) == (2, "", "vw3-decode: --hex: '3' is an odd number of hex digits\n")
    assert run_cli(["--hex", "0C 03 20 D0", "--hex", "1, 3"])[2] == (
        "vw3-decode: --hex argument 2: decimal '1', but --hex argument 1 ('0C') was read as hex: "
        "one notation an input\n")
    assert decode(tmp_path, "1, 3, 256\n")[2] == "vw3-decode: pasted.txt line 1: '256' is not a byte (0..255)\n"
    assert decode(tmp_path, "1, 3, 0C\n", "--format", "decimal")[2] == (
        "vw3-decode: pasted.txt line 1: '0C' is not a decimal byte (--format decimal)\n")
    assert decode(tmp_path, "1, 3, 0, 22\n", "--format", "hex")[2] == (
        "vw3-decode: pasted.txt line 1: '1' is an odd number of hex digits\n")


def test_a_line_that_is_only_a_time_of_day_shape_is_colon_hex(tmp_path: Path) -> None:
    path = tmp_path / "t.txt"
    path.write_text("10:00:00\n10:00:00 0C 83 02 51 32\n")
    assert list(open_source(str(path))) == [Chunk(b"\x10\x00\x00", None, True),
                                            Chunk(bytes.fromhex("0C83025132"), 36000.0, True)]


@pytest.mark.parametrize(
    ("line", "count"),
    [
        (" ".join(["01 03 00 16 00 02 25 CF"] * 30), 30),  # 719 characters, spaced
        ("01030016000225CF" * 40, 40),  # 640 characters, one group
        (", ".join(["1, 3, 0, 22, 0, 2, 37, 207"] * 25), 25),  # 674 characters, decimal
        (":".join(["01:03:00:16:00:02:25:CF"] * 25), 25),  # 599 characters, colon hex
    ],
)
def test_a_first_line_longer_than_the_sniffed_sample_is_a_hex_dump(tmp_path: Path, line: str, count: int) -> None:
    assert len(line) > 512
    status, out, err = decode(tmp_path, line + "\n")
    assert (status, err) == (0, "")
    lines = out.splitlines()
    assert len(lines) == count and all("1 request   Read Holding Registers 22..23 (2)" in row for row in lines)


# A dump whose `*` lines claim 192 MiB of 1-byte lines, in 71 bytes (issue 32: it ran 25 minutes).
XXD_BOMB = "00000000: 00  .\n*\n04000000: 00  .\n*\n08000000: 00  .\n*\n0c000000: 00  .\n"
HEXDUMP_C_BOMB = ("00000000  00                                                |.|\n*\n"
                  "04000000  00                                                |.|\n*\n"
                  "08000000  00                                                |.|\n*\n0c000001\n")


@pytest.mark.parametrize("bomb", [XXD_BOMB, HEXDUMP_C_BOMB])
def test_a_squeeze_bomb_is_refused_before_it_is_expanded(tmp_path: Path, bomb: str) -> None:
    status, out, err = decode(tmp_path, bomb)
    assert (status, out) == (2, "")
    assert err == (
        "vw3-decode: pasted.txt line 3: the * lines stand for 67108863 bytes by offset 0x4000000, over the "
        "16 MiB a dump may expand to: convert it back to bytes and decode those\n")
    path = tmp_path / "pasted.txt"
    source = open_source(str(path), mode="rtu")
    taken = []
    with pytest.raises(SourceError):
        for chunk in source:
            taken.append(chunk)
    assert taken == [Chunk(b"\x00")]  # the first line only: nothing of the claimed run was made


def test_a_squeezed_run_comes_out_in_big_chunks(tmp_path: Path) -> None:
    path = tmp_path / "run.xxd"
    path.write_text("00000000: 00  .\n*\n00100000: 0c83 0251 32  ...Q2\n")  # 1 MiB of 1-byte lines, then a frame
    source = open_source(str(path), chunk_size=65536)
    chunks = list(source)
    assert b"".join(chunk.data for chunk in chunks) == bytes(1 << 20) + bytes.fromhex("0C83025132")
    assert [len(chunk.data) for chunk in chunks] == [1] + [65536] * 15 + [65535, 5]


def test_the_expansion_cap_counts_every_star_of_a_dump(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(dumps, "MAX_EXPANSION", 1 << 20)
    zeros, ones = "0000 " * 7 + "0000  " + "." * 16, "0101 " * 7 + "0101  " + "." * 16
    path = tmp_path / "two.xxd"
    path.write_text(f"00000000: {zeros}\n*\n00080000: {ones}\n*\n00100030: {zeros}\n")
    source = open_source(str(path), mode="rtu")
    taken = 0
    with pytest.raises(SourceError) as error:
        for chunk in source:
            taken += len(chunk.data)
    assert str(error.value) == (
        f"{path} line 5: the * lines stand for 1048592 bytes by offset 0x100030, over the 1 MiB a dump may "
        "expand to: convert it back to bytes and decode those")
    assert taken == 0x80010  # the first run and the line after it, not the second run
