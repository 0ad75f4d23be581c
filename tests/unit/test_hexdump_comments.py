"""Hex dumps whose comments are not ASCII: a German or French engineer's notes (`# Drehzahl ändern`,
`# consigne modifiée`), saved in UTF-8 (no BOM) or in Windows' 8-bit code page (Notepad's "ANSI").
Before, one such character made the whole file raw bytes: 78 bytes of noise, exit 0. The bytes after
80h are comments' characters only: elsewhere the line is not hex, and a control byte is binary data, as
before. Vector: the VW3-A3-303 manual's p.38 request 0C 03 20 D0 00 03 0E EF and its answer."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.sources.reader import SNIFF_BYTES
from helpers import run_cli, use_engine

ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
PAIR = ("     1            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#1]  CRC ok\n")
LINES = "0C 03 20 D0 00 03 0E EF\n0C 03 06 80 00 00 03 00 02 17 E4\n"


def _decode(tmp_path: Path, data: bytes, *options: str) -> tuple[int, str, str]:
    path = tmp_path / "capture.txt"
    path.write_bytes(data)
    status, out, err = run_cli([*options, str(path)])
    return status, out, err.replace(str(path), "FILE")


@ENGINES
@pytest.mark.parametrize("encoding", ["utf-8", "cp1252", "latin-1"])
@pytest.mark.parametrize("text", [
    "# Pumpe Nr.2 – Drehzahl °C\n" + LINES,
    "# consigne modifiée à 10 h\n" + LINES,
    LINES.replace("0E EF\n", "0E EF  # Lesen: Status, Sollwert, Istwert (ä ö ü ß µ)\n"),
    LINES + "# Ende — grüße\n",
])
def test_comments_in_any_characters(
    tmp_path: Path, pure: bool, encoding: str, text: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    use_engine(monkeypatch, pure)
    data = text.encode(encoding, errors="replace")
    assert _decode(tmp_path, data) == (0, PAIR, "")
    assert _decode(tmp_path, data, "--format", "hex") == (0, PAIR, "")


@ENGINES
def test_a_character_cut_by_the_sniffed_sample_is_still_text(tmp_path: Path, pure: bool,
                                                             monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # The format is judged on the first SNIFF_BYTES: here they end inside a two-byte character.
    data = (("# x" + "ä" * 100 + "\n") * 3 + LINES).encode()
    with pytest.raises(UnicodeDecodeError):
        data[:SNIFF_BYTES].decode()
    assert _decode(tmp_path, data) == (0, PAIR, "")


@ENGINES
def test_a_character_outside_a_comment_is_no_hex(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = _decode(tmp_path, "0C 03 20 D0 00 03 0E EF\n0C 03 Ä 00\n".encode(), "--format", "hex")
    assert (status, out) == (2, "")
    assert err.startswith("vw3-decode: FILE line 2: ") and "Traceback" not in err
    # Unformatted too: a line of bytes with one that is no hex is a dump's typo, named (before: raw text).
    assert _decode(tmp_path, "0C 03 20 D0 00 03 0E EF\n0C 03 Ä 00\n".encode()) == (
        2, "", "vw3-decode: FILE line 2: 'Ä' is not hex\n")


@ENGINES
def test_control_bytes_are_binary_data(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = _decode(tmp_path, b"# Drehzahl \xc3\xa4\n0C 03 20 D0 00 03 0E EF\n\x1b[31m\n", "--format", "hex")
    assert (status, err) == (2, "vw3-decode: FILE line 3: binary data in a hex dump\n")


@ENGINES
def test_high_bytes_without_text_stay_binary(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # No control byte, not UTF-8, no text format: bytes, without a "the input is text" warning.
    status, out, err = _decode(tmp_path, bytes([0xFF, 0xC0, 0xC1, 0xF5, 0x80, 0x81]))
    assert status == 0
    assert out == "     1            -   - noise     6 bytes of noise at offset 0: ff c0 c1 f5 80 81\n"
    assert "the input is text" not in err


@ENGINES
@pytest.mark.parametrize("encoding", ["ascii", "utf-8", "utf-16"])
def test_a_header_of_comments_longer_than_the_sniffed_sample(
    tmp_path: Path, pure: bool, encoding: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Before, 6 comment lines of 100 characters (no data line in the first 512 bytes) made the dump
    789 bytes of noise, with "the input is text, but neither a hex dump nor Modbus ASCII"."""
    use_engine(monkeypatch, pure)
    header = "".join(f"# {line}: " + "x" * 100 + "\n" for line in range(6)) + "#" + " " * 300 + "\n\n"
    data = (header + LINES).encode(encoding)  # utf-16: Python writes the BOM, as Notepad's "Unicode"
    assert len(header) > SNIFF_BYTES
    assert _decode(tmp_path, data) == (0, PAIR, "")
    status, out, err = run_cli(["-"], stdin=data)
    # (read once, from a pipe: profile auto's choice is provisional until the capture shows more)
    assert (status, out, err) == (0, PAIR.replace("  CRC ok", " [provisional]  CRC ok"), "")
