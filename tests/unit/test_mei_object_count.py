"""An FC43/14 Read Device Identification answer whose number of objects declares more objects than it
holds (a device may send this; its CRC says the frame is whole): framed by its CRC (the object list's
walk falls back to the shortest CRC match, framing/rules.py _mei_objects), paired, its objects shown and
a warning. Before, the walk asked for 147 bytes: the request read "[the capture ends inside the response
(19 of 147 bytes)]" and the answer was 19 bytes of noise. An answer truly cut by the end of the capture
still says so; one whose CRC fails is still a damaged frame. Exact lines under the compiled engine and
VW3_PURE_PYTHON=1 (the plugin: tests/integration/test_lua_mei_object_count.py)."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.render.pcapwriter import PcapWriter
from helpers import rtu, run_cli, use_engine

T0 = 1767225600.0
REQUEST = "01 2b 0e 01 00 70 77"  # basic identification from object 0
# 3 objects declared, 2 sent (VendorName 'ABC', ProductCode 'XY'), CRC 0x7E03 over what is sent
SHORT = "01 2b 0e 01 01 00 00 03 00 03 41 42 43 01 02 58 59 03 7e"
# The same answer with its third object (MajorMinorRevision '1.0'): 24 bytes
FULL = rtu("01 2b 0e 01 01 00 00 03 00 03 41 42 43 01 02 58 59 02 03 31 2e 30")
READ = "01 03 00 00 00 01 84 0a"
ASKED = "Encapsulated Interface Transport Read Device Identification, basic, from object 0"
ANSWER = "Encapsulated Interface Transport Read Device Identification, basic: VendorName='ABC' ProductCode='XY'"
WARNING = "[warning: number of objects 3 disagrees with the objects present (2)]"


def decode(argv: list[str], pure: bool, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(argv)
    assert (status, err) == (0, "")
    return out.splitlines()


def capture(path: Path, frames: list[bytes]) -> str:
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, frame in enumerate(frames):
            writer.write(frame, T0 + 0.05 * index)
    return str(path)


@pytest.mark.parametrize("pure", [False, True])
def test_the_answer_with_fewer_objects_is_framed_and_paired(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    assert decode(["--hex", REQUEST, "--hex", SHORT], pure, monkeypatch) == [
        f"     1            -   1 request   {ASKED}  CRC ok",
        f"     2            -   1 response  {ANSWER} [#1] {WARNING}  CRC ok",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_in_a_stream_with_frames_after_it(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    # One run of bytes: the walk takes the CRC for a third object (id 03, 7E bytes: 147 in all), the CRC
    # scan finds the answer's end, and what follows is framed as before.
    assert decode(["--hex", f"{REQUEST} {SHORT} {READ}"], pure, monkeypatch) == [
        f"     1            -   1 request   {ASKED}  CRC ok",
        f"     2            -   1 response  {ANSWER} [#1] {WARNING}  CRC ok",
        "     3            -   1 request   Read Holding Registers 0 [the capture ends before any response: not known whether it was answered]  CRC ok",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_a_pcap_and_ascii(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    pcap = capture(tmp_path / "short.pcap", [bytes.fromhex(REQUEST), bytes.fromhex(SHORT)])
    assert decode([pcap], pure, monkeypatch) == [
        f"     1     0.000000   1 request   {ASKED}  CRC ok",
        f"     2     0.050000   1 response  {ANSWER} [#1, 50.0 ms] {WARNING}  CRC ok",
    ]
    # (ASCII: the ':' and CR LF delimit it; before, "no Modbus layout fits" left it noise)
    lines = tmp_path / "ascii.txt"
    lines.write_bytes(b":012B0E0100C5\r\n:012B0E010100000300034142430102585944\r\n")
    assert decode([str(lines)], pure, monkeypatch) == [
        f"     1            -   1 request   {ASKED}  LRC ok",
        f"     2            -   1 response  {ANSWER} [#1] {WARNING}  LRC ok",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_a_walk_that_ends_with_the_record(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    # The answer, then 16 reads of slave 2 in its record: 147 bytes, as many as the walk asks for (the CRC
    # taken for a third object of 7E bytes); the CRC there fails, the scan finds the answer's end.
    poll = rtu("02 03 0000 0001")
    pcap = capture(tmp_path / "record.pcap", [bytes.fromhex(REQUEST), bytes.fromhex(SHORT) + poll * 16])
    lines = decode([pcap], pure, monkeypatch)
    assert lines[:3] == [
        f"     1     0.000000   1 request   {ASKED}  CRC ok",
        f"     2     0.050000   1 response  {ANSWER} [#1, 50.0 ms] {WARNING}  CRC ok",
        "     3     0.050000   2 request   Read Holding Registers 0 [no response]  CRC ok",
    ]
    assert len(lines) == 18 and lines[-1].startswith("    18     0.050000   2 request   Read Holding Registers 0 ")


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize(("cut", "reason"), [
    (20, "20 of 24 bytes"),  # the walk's length known: 24
    (15, "15 bytes of it"),  # the third object's length byte not there: its length unknown
])
def test_an_answer_cut_by_the_end_of_the_capture_says_so(
    tmp_path: Path, cut: int, reason: str, pure: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    pcap = capture(tmp_path / "cut.pcap", [bytes.fromhex(REQUEST), FULL[:cut]])
    shown = " ".join(f"{byte:02x}" for byte in FULL[:min(cut, 16)]) + ("…" if cut > 16 else "")
    assert decode([pcap], pure, monkeypatch) == [
        f"     1     0.000000   1 request   {ASKED} [the capture ends inside the response ({reason})]  CRC ok",
        f"     2     0.050000   - noise     {cut} bytes of noise at offset 7: {shown}",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_the_whole_answer_and_a_damaged_one(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    assert decode(["--hex", REQUEST, "--hex", FULL.hex(" ")], pure, monkeypatch)[1] == (
        f"     2            -   1 response  {ANSWER} MajorMinorRevision='1.0' [#1]  CRC ok"
    )
    # Two objects declared and sent, the CRC the one of three declared: a damaged frame of the walk's
    # length, as before (no CRC match to fall back to).
    damaged = SHORT.replace("00 03 00 03", "00 02 00 03")
    assert decode(["--hex", f"{REQUEST} {damaged} {READ}"], pure, monkeypatch) == [
        f"     1            -   1 request   {ASKED}  CRC ok",
        f"     2            -   1 response  {ANSWER} [#1]  CRC BAD (received 0x7E03, expected 0xBB52)",
        "     3            -   1 request   Read Holding Registers 0 [the capture ends before any response: not known whether it was answered]  CRC ok",
    ]
