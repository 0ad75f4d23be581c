"""Compressed captures read as tshark reads a `capture.pcap.gz`: decompressed as they are read, whatever format
is inside (sources/compressed.py). The command's own output for the compressed file is the output for the file
itself; a cut or damaged file decodes what is there with a warning, one that holds nothing readable is one line
and exit 2; zstd and lz4 name the tool; a raw capture whose first bytes look like a gzip magic stays raw."""
from __future__ import annotations

import bz2
import gzip
import lzma
import subprocess
import sys
from pathlib import Path

import pytest

from dissector.protocol.crc import crc_bytes

ROOT = Path(__file__).resolve().parents[2]
CAPTURES = ROOT / "captures"
COMPRESS = {"gz": gzip.compress, "bz2": bz2.compress, "xz": lzma.compress}


def run(*args: str, stdin: bytes | None = None) -> tuple[int, str, str]:
    done = subprocess.run([sys.executable, "-m", "dissector", *args], cwd=ROOT, input=stdin,
                          capture_output=True, timeout=120)
    return done.returncode, done.stdout.decode(), done.stderr.decode()


@pytest.mark.parametrize("suffix", sorted(COMPRESS))
@pytest.mark.parametrize("capture", ["noisy_bus.pcap", "atv71_commissioning.bin", "ascii_session.bin"])
def test_a_compressed_capture_decodes_as_the_capture(capture: str, suffix: str, tmp_path: Path) -> None:
    original = CAPTURES / capture
    packed = tmp_path / f"{capture}.{suffix}"
    packed.write_bytes(COMPRESS[suffix](original.read_bytes()))
    for options in ([], ["-V"], ["--json"], ["--stats"]):
        expected = run(*options, str(original))
        assert expected[0] == 0 and expected[1]
        assert run(*options, str(packed)) == (0, expected[1], expected[2].replace(str(original), str(packed)))


def test_standard_input_gzipped() -> None:
    data = (CAPTURES / "sel749m_polling.pcap").read_bytes()
    assert run("-", stdin=gzip.compress(data)) == run("-", stdin=data)


def test_a_hex_dump_gzipped(tmp_path: Path) -> None:
    dump = tmp_path / "frames.txt.gz"
    dump.write_bytes(gzip.compress(b"# two frames\n0C 03 20 D0 00 03 0E EF\n0C 83 02 51 32\n"))
    status, out, err = run(str(dump))
    assert (status, err) == (0, "")
    assert [line.split(None, 3)[3] for line in out.splitlines()] == [
        "request   Read Holding Registers 8400..8402 (3)  CRC ok",
        "exception Read Holding Registers: exception 2 (Illegal Data Address) [#1]  CRC ok",
    ]


def test_a_cut_gzip_decodes_what_is_there(tmp_path: Path) -> None:
    whole = (CAPTURES / "noisy_bus.pcap").read_bytes()
    cut = tmp_path / "cut.pcap.gz"
    cut.write_bytes(gzip.compress(whole)[:300])
    status, out, err = run(str(cut))
    frames = run(str(CAPTURES / "noisy_bus.pcap"))[1].splitlines()
    lines = out.splitlines()
    # (the last request's response is cut off: it says so, where the whole file shows it answered)
    assert status == 0 and 1 < len(lines) < len(frames) and lines[:-1] == frames[: len(lines) - 1]
    assert f"vw3-decode: warning: {cut}: the gzip data ends early (a file cut short?): the bytes before are decoded" \
        in err.splitlines()


@pytest.mark.parametrize(("content", "message"), [
    (gzip.compress(b"x" * 100, mtime=0)[:10] + b"\xff" * 20, "the gzip data is damaged"),
    (bz2.compress(bytes(range(256)) * 8)[:60], "the bzip2 data ends early (a file cut short?)"),
    (b"\x04\x22\x4d\x18" + bytes(20), "compressed input (lz4): decompress it first (`lz4 -d FILE`)"),
    (gzip.compress(gzip.compress(b"01 03 00 00 00 01 84 0A\n", mtime=0), mtime=0), "compressed twice (gzip, then gzip): decompress it first"),
])
def test_nothing_readable_is_one_line_and_exit_2(content: bytes, message: str, tmp_path: Path) -> None:
    path = tmp_path / "capture"
    path.write_bytes(content)
    status, out, err = run(str(path))
    assert (status, out) == (2, "") and err.startswith(f"vw3-decode: {path}: {message}") and err.count("\n") == 1


def test_a_raw_capture_opening_with_1f_8b_is_not_gzip(tmp_path: Path) -> None:
    """Slave 31's exception 8 to function 11 is 1f 8b 08 ...: the header's other bytes tell it from gzip."""
    frames = bytes.fromhex("1f8b08") + crc_bytes(bytes.fromhex("1f8b08"))
    raw = tmp_path / "bus.bin"
    raw.write_bytes(frames + bytes.fromhex("1f0b") + crc_bytes(bytes.fromhex("1f0b")))
    status, out, err = run(str(raw))
    assert status == 0, err
    assert "exception Get Comm Event Counter: exception 8 (Memory Parity Error)" in out.splitlines()[0]


def test_format_raw_keeps_the_bytes(tmp_path: Path) -> None:
    packed = tmp_path / "bus.bin.gz"
    packed.write_bytes(gzip.compress((CAPTURES / "p38_protection.bin").read_bytes()))
    status, out, _ = run("--format", "raw", str(packed))
    assert status == 0 and out.splitlines()[0].split(None, 3)[3].startswith("noise")
