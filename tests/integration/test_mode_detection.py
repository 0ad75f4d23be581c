"""RTU or ASCII, told from a stream's first bytes (protocol/ascii.py detect_mode, sources/reader.py), the same
in vw3-decode (the engine and VW3_PURE_PYTHON=1) and in the plugin reading what `vw3-decode -w` wrote.

A review found three ways to get it wrong. An ASCII capture that starts mid-frame decoded in vw3-decode,
but its -w pcap read as noise in the plugin, which told the mode from the first record alone (-w writes
the leading noise as a record of its own); the plugin now holds records until the same first bytes
have come (lua/src/dissector.lua). vw3-decode warned that such text was `neither a hex dump nor Modbus
ASCII` and then decoded ASCII frames. And an ASCII capture after a few bytes of line noise decoded as
nothing but noise: a whole frame with a good LRC in the first bytes now says ASCII, whatever came before.
"""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_compare import compare
from lua_harness import ROOT, lua_errors, lua_items, python_items, run_tshark, write_pcap

from dissector.protocol.ascii import detect_mode, holds_frame
from dissector.sources.reader import MODE_SAMPLE, open_source

LINE = b":02062329000AA2\r\n"  # slave 2 writes 10 to register 9001 (its LRC A2 good)
MID_FRAME = b"9000AA2\r\n" + LINE * 6  # a capture that starts inside a frame
ONE_ZERO = b"\x00" + LINE * 6
LINE_NOISE = bytes([0, 0xFF, 0x13, 0x80, 0x55, 0xAA, 0, 0]) + LINE * 20
SHORT = b"\x00" + LINE * 2  # shorter than the sample: the mode told from all of it, at the end

PAIRS = ["%6d            -   2 request   Write Single Register 9001 = 10  LRC ok",
         "%6d            -   2 response  Write Single Register 9001 = 10 [#%d]  LRC ok"]


def frames(first: int, count: int) -> list[str]:
    """The summary lines of `count` request/response pairs numbered from `first`."""
    lines = []
    for number in range(first, first + 2 * count, 2):
        lines += [PAIRS[0] % number, PAIRS[1] % (number + 1, number)]
    return lines


EXPECTED = {
    "mid_frame": (MID_FRAME, ["     1            -   - noise     9 bytes of noise at offset 0: 39 30 30 30 41 41 32 0d 0a",
                              *frames(2, 3)]),
    "one_zero": (ONE_ZERO, ["     1            -   - noise     1 byte of noise at offset 0: 00", *frames(2, 3)]),
    "line_noise": (LINE_NOISE, ["     1            -   - noise     8 bytes of noise at offset 0: 00 ff 13 80 55 aa 00 00",
                                *frames(2, 10)]),
    "short": (SHORT, ["     1            -   - noise     1 byte of noise at offset 0: 00", *frames(2, 1)]),
}


def _decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> tuple[str, str]:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(argv)
    assert status == 0, err
    return out, err


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_ascii_after_noise_or_mid_frame_decodes_as_ascii_without_a_contradicting_warning(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str, pure: bool
) -> None:
    data, lines = EXPECTED[name]
    path = tmp_path / f"{name}.bin"
    path.write_bytes(data)
    assert _decode([str(path)], monkeypatch, pure) == ("\n".join(lines) + "\n", "")
    source = open_source(str(path))
    assert (source.format, source.mode, source.warnings) == ("ascii", "ascii", [])
    source.close()


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_text_that_is_not_ascii_mode_still_says_so(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = tmp_path / "notes.txt"
    path.write_bytes(b"9000AA2\r\nhello\r\n")
    assert _decode([str(path), "--stats"], monkeypatch, pure)[1].startswith(
        f"vw3-decode: warning: {path}: the input is text, but neither a hex dump nor Modbus ASCII: decoded as raw bytes\n")


# The plugin's Info column for each record of the -w pcap (tshark -2).
PLUGIN_INFO = {
    "mid_frame": ["noise (9 bytes)"] + ["2 Write Single Register request 9001 = 10",
                                        "2 Write Single Register response 9001 = 10"] * 3,
    "one_zero": ["noise (1 byte)"] + ["2 Write Single Register request 9001 = 10",
                                      "2 Write Single Register response 9001 = 10"] * 3,
    "line_noise": ["noise (8 bytes)"] + ["2 Write Single Register request 9001 = 10",
                                         "2 Write Single Register response 9001 = 10"] * 10,
    "short": ["noise (1 byte)", "2 Write Single Register request 9001 = 10", "2 Write Single Register response 9001 = 10"],
}


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_the_plugin_reads_the_written_pcap_as_vw3_decode_reads_the_stream(tmp_path: Path, name: str) -> None:
    data, lines = EXPECTED[name]
    path, written = tmp_path / f"{name}.bin", tmp_path / f"{name}.pcap"
    path.write_bytes(data)
    assert run_cli([str(path), "-w", str(written)]) == (0, "", "")
    assert run_cli([str(written)])[1] == "\n".join(lines) + "\n"
    result = run_tshark(written, "-T", "fields", "-e", "_ws.col.Info")
    assert not lua_errors(result.stdout + result.stderr)
    assert result.stdout.splitlines() == PLUGIN_INFO[name]
    differences = compare(python_items(written, []), lua_items(written)[0])
    assert not differences, "\n".join(differences[:40])


def test_the_plugin_tells_the_mode_from_the_first_bytes_across_records(tmp_path: Path) -> None:
    """The first MODE_SAMPLE bytes in records of 1 to 5 bytes, the last of them completing the sample
    inside a record: the records held until then are decoded as if the mode had been known."""
    records, at, size = [], 0, 1
    data = LINE_NOISE
    while at < len(data):
        records.append((data[at : at + size], 1_700_000_000 + len(records) * 0.01))
        at, size = at + size, size % 5 + 1
    assert sum(len(record) for record, _ in records[:23]) > MODE_SAMPLE > sum(len(record) for record, _ in records[:22])
    pcap = write_pcap(tmp_path / "pieces.pcap", records)
    python = python_items(pcap, [])
    kinds = [item.data["kind"] for item in python]  # (the noise run: a piece in each of its records)
    assert kinds[0] == "noise" and [kind for kind in kinds if kind != "noise"] == ["request", "response"] * 10
    differences = compare(python, lua_items(pcap)[0])
    assert not differences, "\n".join(differences[:40])


@pytest.mark.parametrize(
    ("sample", "mode"),
    [
        (LINE_NOISE[:MODE_SAMPLE], "ascii"),  # a whole frame after noise
        (b"\xff" * 40 + LINE, "ascii"),
        (b"\xff" * 40 + LINE.replace(b"\r", b""), "ascii"),  # (a line that lost its CR)
        (b"\xff" * 40 + LINE.lower(), "ascii"),
        (b"\xff" * 40 + LINE.replace(b"A2", b"A3"), "rtu"),  # its LRC bad
        (b"\xff" * 40 + b":020623\r\n", "rtu"),  # odd digits
        (b"\xff" * 40 + b":02FC\r\n", "rtu"),  # no LRC
        (b"\xff" * 40 + b":020623290", "rtu"),  # no line end
        (b"\xff" * 40 + b":0206:2329000AA2\r\n", "rtu"),  # cut by a ':'
        (MID_FRAME[:MODE_SAMPLE], "ascii"),
        # RTU whose bytes hold ':' and hex digits, and CR LF: no whole frame, mostly binary
        (bytes.fromhex("0C 03 20 D0 00 03 0E EF") + b":0102\r\n" + bytes(range(0x80, 0xB2)), "rtu"),
    ],
)
def test_detect_mode_by_whole_frames(sample: bytes, mode: str) -> None:
    assert detect_mode(sample) == mode


def test_holds_frame_looks_at_each_byte_a_bounded_number_of_times() -> None:
    # A flood of ':' and of hex digits: each ':' starts one scan, which the next ':' ends.
    assert not holds_frame(b":" * 10_000)
    assert not holds_frame(b":" + b"0" * 10_000)
    assert holds_frame(b":0" * 5_000 + LINE)


SHIPPED_MODES = {"ascii_session": "ascii", "atv71_commissioning": "rtu", "noisy_bus": "rtu",
                 "p38_protection": "rtu", "sel749m_polling": "rtu"}


CAPTURES = sorted([*(ROOT / "captures").glob("*.bin"), *(ROOT / "captures").glob("*.pcap")])


@pytest.mark.parametrize("capture", CAPTURES, ids=lambda path: path.name)
def test_the_shipped_captures_keep_their_mode(capture: Path) -> None:
    with open_source(str(capture)) as source:
        assert source.mode == SHIPPED_MODES[capture.stem]
    if SHIPPED_MODES[capture.stem] == "rtu" and capture.suffix == ".bin":
        # No whole ASCII frame anywhere in them: cut anywhere, they stay RTU.
        assert not holds_frame(capture.read_bytes())


def test_the_recorded_rtu_buses_hold_no_ascii_frame() -> None:
    for records in sorted((ROOT / "tests" / "corpus").glob("*.records")):
        data = b""
        for line in records.read_text().splitlines():
            if line.strip() and not line.startswith("#"):
                text = line.split(" ", 1)[1] if re.match(r"\d+\.\d+ ", line) else line
                data += bytes.fromhex("".join(re.findall(r"\b[0-9a-fA-F]{2}\b", text)))
        assert len(data) > 100 and not holds_frame(data), records.name


def test_ascii_lines_behind_long_noise_get_the_mode_ascii_hint(tmp_path: Path) -> None:
    # 60 bytes of noise no longer hide the frames (the sample reads on: protocol/ascii.py sample_mode); 1044
    # bytes (past MODE_REACH) do: read as RTU, every byte noise; the warning then names --mode ascii, which
    # decodes the 20 frames. Random-looking RTU noise gets no hint.
    early = tmp_path / "early.bin"
    early.write_bytes(bytes(range(60)) + LINE * 20)
    assert run_cli([str(early)])[1].splitlines()[-20:] == frames(3, 10)  # after 2 noise runs (':' in them)
    path = tmp_path / "late.bin"
    path.write_bytes(bytes(range(58)) * 18 + LINE * 20)
    status, out, err = run_cli([str(path)])
    assert status == 0 and err == (
        f"vw3-decode: warning: {path}: no valid Modbus RTU frame in 1384 bytes (every item is noise or a "
        "frame with a bad check): not a Modbus capture, or another format or line speed? (it holds Modbus ASCII "
        "frames: try --mode ascii)\n")
    assert run_cli(["--mode", "ascii", str(path)])[1].splitlines()[-20:] == frames(2, 10)  # after 1 noise run
    binary = tmp_path / "binary.bin"
    binary.write_bytes(bytes(range(200, 256)) * 5)
    assert run_cli([str(binary)])[2].endswith("or another format or line speed?\n")
