"""Text captures saved with a byte order mark: Windows Notepad's "UTF-8 with BOM" and "Unicode" (UTF-16 LE),
PowerShell 5's `>` (UTF-16 LE with a BOM), UTF-16 BE, UTF-32. Before, a hex dump with a BOM was 28 bytes of
noise (`--format hex`: `binary data in a hex dump`, exit 2) and a UTF-16 one 52 bytes of noise. A binary RTU
capture that starts with the same bytes must stay binary. Vectors: the VW3-A3-303 manual's p.38 request
0C 03 20 D0 00 03 0E EF and answer 0C 03 06 80 00 00 03 00 02 17 E4; the ASCII manual example
:02062329000AA2 (Write Single Register 9001 = 10)."""
from __future__ import annotations

import codecs
import io
import random
from pathlib import Path

import pytest

from dissector.sources.reader import SourceError, open_source
from helpers import hx, run_cli, use_engine

REQUEST = "0C 03 20 D0 00 03 0E EF"
ANSWER = "0C 03 06 80 00 00 03 00 02 17 E4"
ALONE = ("     1            -  12 request   Read Holding Registers 8400..8402 (3) "
         "[the capture ends before any response: not known whether it was answered]  CRC ok\n")
PAIR = ("     1            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#1]  CRC ok\n")
ASCII_PAIR = ("     1            -   2 request   Write Single Register 9001 = 10  LRC ok\n"
              "     2            -   2 response  Write Single Register 9001 = 10 [#1]  LRC ok\n")
ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
# As the tools write them (iconv -t UTF-16 / PowerShell 5 `>`: BOM FF FE then little-endian).
ENCODED = {
    "utf-8 bom": lambda text: codecs.BOM_UTF8 + text.encode(),
    "utf-16 le": lambda text: codecs.BOM_UTF16_LE + text.encode("utf-16-le"),
    "utf-16 be": lambda text: codecs.BOM_UTF16_BE + text.encode("utf-16-be"),
    "utf-32 le": lambda text: codecs.BOM_UTF32_LE + text.encode("utf-32-le"),
    "utf-32 be": lambda text: codecs.BOM_UTF32_BE + text.encode("utf-32-be"),
}


def _decode(tmp_path: Path, data: bytes, *options: str) -> tuple[int, str, str]:
    path = tmp_path / "capture.txt"
    path.write_bytes(data)
    status, out, err = run_cli([*options, str(path)])
    return status, out, err.replace(str(path), "FILE")


@ENGINES
def test_the_reviewers_files(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    bom = b"\xef\xbb\xbf0C 03 20 D0 00 03 0E EF\r\n"  # printf '\xef\xbb\xbf0C ...\r\n'
    # printf '0C 03 20 D0 00 03 0E EF\r\n' | iconv -t UTF-16
    utf16 = bytes.fromhex("fffe") + b"".join(bytes([char, 0]) for char in b"0C 03 20 D0 00 03 0E EF\r\n")
    assert _decode(tmp_path, bom) == (0, ALONE, "")
    assert _decode(tmp_path, bom, "--format", "hex") == (0, ALONE, "")
    assert _decode(tmp_path, utf16) == (0, ALONE, "")
    assert _decode(tmp_path, utf16, "--format", "hex") == (0, ALONE, "")


@ENGINES
@pytest.mark.parametrize("encoding", sorted(ENCODED))
def test_every_text_format_in_every_marked_encoding(
    tmp_path: Path, encoding: str, pure: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    use_engine(monkeypatch, pure)
    encode = ENCODED[encoding]
    hexdump = f"# p.38\r\n{REQUEST}\r\n{ANSWER}\r\n"
    traffic = f"Tx:000000-{REQUEST}\r\nRx:000001-{ANSWER}\r\n"
    xxd = "00000000: 0c03 20d0 0003 0eef 0c03 0680 0000 0300  .. .............\n00000010: 0217 e4  ...\n"
    ascii = ":02062329000AA2\r\n:02062329000AA2\r\n"
    assert _decode(tmp_path, encode(hexdump)) == (0, PAIR, "")
    assert _decode(tmp_path, encode(traffic)) == (0, PAIR, "")
    assert _decode(tmp_path, encode(xxd)) == (0, PAIR, "")
    # Modbus ASCII: the BOM is the file's, not the line's: no noise before the first frame
    assert _decode(tmp_path, encode(ascii)) == (0, ASCII_PAIR, "")
    assert _decode(tmp_path, encode(ascii), "--format", "ascii") == (0, ASCII_PAIR, "")
    assert _decode(tmp_path, encode(hexdump), "--format", "hex") == (0, PAIR, "")


@ENGINES
@pytest.mark.parametrize("start", ["ff fe", "fe ff", "ef bb bf", "ff fe 00 00", "00 00 fe ff", "ff fe 30 00 43 00"])
def test_a_binary_capture_that_starts_like_a_bom_stays_binary(
    tmp_path: Path, start: str, pure: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = _decode(tmp_path, hx(start) + hx(REQUEST) + hx(ANSWER))
    assert (status, err) == (0, "")
    count = len(hx(start))
    assert out == (
        f"     1            -   - noise     {count} bytes of noise at offset 0: {hx(start).hex(' ')}\n"
        "     2            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
        "     3            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#2]  "
        "CRC ok\n"
    )


def test_marked_text_in_no_format_is_its_bytes_with_the_usual_warning(tmp_path: Path) -> None:
    data = ENCODED["utf-16 le"]("hello\r\n")
    status, out, err = _decode(tmp_path, data)
    assert status == 0
    assert out == "     1            -   - noise     16 bytes of noise at offset 0: ff fe 68 00 65 00 6c 00 6c 00 6f 00 0d 00 0a 00\n"
    assert err.splitlines()[0] == (
        "vw3-decode: warning: FILE: the input is text (UTF-16 LE), but neither a hex dump nor Modbus ASCII: "
        "decoded as raw bytes"
    )


def test_a_file_that_stops_being_its_encoding_is_refused_at_that_byte(tmp_path: Path) -> None:
    # a lone high surrogate (D800) after a good line, in a small file and past the first 512 bytes
    damaged = ENCODED["utf-16 le"](f"{REQUEST}\r\n") + hx("00 d8 41 00") + "0C\r\n".encode("utf-16-le")
    assert _decode(tmp_path, damaged) == (2, "", (
        "vw3-decode: FILE: not UTF-16 LE text near byte 52 (illegal UTF-16 surrogate), though it starts with "
        "that BOM: save it as UTF-8\n"))
    long = ENCODED["utf-16 le"](f"{REQUEST}\r\n" * 20) + hx("00 d8 41 00")
    # (judged a hex dump by its first 512 bytes; the reading meets the damage, as a bad line of a hex dump)
    assert _decode(tmp_path, long) == (2, "", (
        "vw3-decode: FILE: not UTF-16 LE text near byte 1002 (illegal UTF-16 surrogate), though it starts with "
        "that BOM: save it as UTF-8\n"))


class _Trickle(io.RawIOBase):
    """A pipe that delivers one byte a read: every character of the UTF-16 text is cut somewhere."""

    def __init__(self, data: bytes) -> None:
        self.data = data

    def readable(self) -> bool:
        return True

    def readinto(self, buffer: bytearray) -> int:  # type: ignore[override]
        if not self.data or not len(buffer):
            return 0
        buffer[0], self.data = self.data[0], self.data[1:]
        return 1

    def read1(self, count: int = -1) -> bytes:
        part, self.data = self.data[:1], self.data[1:]
        return part


def test_a_trickling_utf16_pipe_gives_the_lines_of_the_file() -> None:
    text = f"# p.38\r\n1700000000.5 {REQUEST}\r\n1700000000.625 {ANSWER}\r\n"
    source = open_source("-", stdin=_Trickle(ENCODED["utf-16 be"](text)), chunk_size=256)  # type: ignore[arg-type]
    chunks = list(source)
    assert (source.format, source.mode) == ("hexdump", "rtu")
    assert [(chunk.data, chunk.time.ns, chunk.boundary) for chunk in chunks] == [  # type: ignore[union-attr]
        (hx(REQUEST), 1_700_000_000_500_000_000, True), (hx(ANSWER), 1_700_000_000_625_000_000, True),
    ]


def test_mutated_utf16_files_raise_only_one_line_source_errors() -> None:
    valid = ENCODED["utf-16 le"](f"# p.38\r\n{REQUEST}\r\n{ANSWER}\r\n" * 10)
    generator = random.Random(38)
    for _ in range(400):
        data = bytearray(valid)
        for _ in range(generator.randint(1, 6)):
            data[generator.randrange(len(data))] = generator.randrange(256)
        for forced in (None, "hex", "ascii"):
            try:
                source = open_source("-", forced, chunk_size=256, stdin=io.BufferedReader(io.BytesIO(bytes(data))))
                for chunk in source:
                    assert chunk.data
            except SourceError as error:
                assert str(error) and "\n" not in str(error)
