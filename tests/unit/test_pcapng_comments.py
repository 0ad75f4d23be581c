"""pcapng packet comments (opt_comment: `editcap -a 1:"text"`, Wireshark's Packet Comment) are shown and
kept (sources/trail.py): -V above the frame as tshark -V ("Packet comments"), --json as `comments`, kept
on each record of `-w COPY.pcapng`; a frame gets the comments of every record it has bytes in. The
summary does not show them: one line on standard error says how many there are and where. pcap has no
place for them: `-w COPY.pcap` warns. The comments vw3-decode writes itself (noise runs) are its decode's
words, not a user's: read back, they are not shown (a copy decodes as its original). Before, comments
were dropped without a word (every assertion below on a comment failed)."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import pcapng_packets, run_cli, use_engine
from dissector.sources.trail import own_comment

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER = bytes.fromhex("0C0306000100020003A5E4")  # 8400=1, CHCF=SEP, COP=ALL
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
T0 = 1_767_225_600_000_000  # 2026-01-01 in microseconds


def _block(kind: int, body: bytes) -> bytes:
    total = 12 + len(body)
    return struct.pack("<II", kind, total) + body + struct.pack("<I", total)


def _comment(text: str) -> bytes:
    value = text.encode()
    return struct.pack("<HH", 1, len(value)) + value + b"\0" * (-len(value) % 4)


def pcapng(packets: list[tuple[int, bytes, list[str]]]) -> bytes:
    """Packets (microseconds, bytes, comments) of one USER0 interface, as editcap -a writes comments."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    out += _block(1, struct.pack("<HHI", 147, 0, 0))
    for micros, data, comments in packets:
        stamp = T0 + micros
        options = b"".join(map(_comment, comments)) + (b"\0" * 4 if comments else b"")
        out += _block(6, struct.pack("<IIIII", 0, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data))
                      + data + b"\0" * (-len(data) % 4) + options)
    return out


def records(path: Path) -> list[tuple[int, bytes, list[str]]]:
    """(microseconds from T0, bytes, comments) of each packet block of a little-endian pcapng."""
    return pcapng_packets(path, T0)


COMMENTED = [(0, REQUEST, ["poll \x1b[31m of 12"]), (10_000, ANSWER, ["answer", "again"]),
             (1_000_000, b"\xff\xff\xff", ["glitch"])]
SUMMARY = [
    "     1     0.000000  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
    "     2     0.010000  12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3 "
    "[#1, 10.0 ms]  CRC ok",
    "     3     1.000000   - noise     3 bytes of noise at offset 19: ff ff ff",
]


def _write(tmp_path: Path, packets: list[tuple[int, bytes, list[str]]], name: str = "c.pcapng") -> Path:
    path = tmp_path / name
    path.write_bytes(pcapng(packets))
    return path


@BOTH
def test_detail_shows_comments_above_the_frame(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = _write(tmp_path, COMMENTED)
    status, out, err = run_cli([str(path), "-V"])
    assert (status, err) == (0, "")
    blocks = out.split("\n\n")
    assert blocks[0].splitlines()[:3] == [
        "Packet comments", "    poll \\x1b[31m of 12", "Frame 1: 8 bytes at offset 0, request (RTU)"]
    assert blocks[1].splitlines()[:4] == [
        "Packet comments", "    answer", "    again", "Frame 2: 11 bytes at offset 8, response (RTU)"]
    assert blocks[2].splitlines()[:3] == ["Packet comments", "    glitch", "Item 3: noise, 3 bytes at offset 19"]


@BOTH
def test_json_has_the_comments(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    import json

    path = _write(tmp_path, COMMENTED)
    every = [["poll \x1b[31m of 12"], ["answer", "again"], ["glitch"]]
    for extra, expected in (([], every), (["-Y", 'kind != "response"'], [every[0], every[2]])):
        status, out, err = run_cli([str(path), "--json", *extra])
        assert (status, err) == (0, "")
        rows = [json.loads(line) for line in out.splitlines()]
        assert [row["comments"] for row in rows] == expected
        assert list(rows[0])[-2:] == ["notes", "comments"]
    plain = _write(tmp_path, [(0, REQUEST, [])], "plain.pcapng")
    assert "comments" not in json.loads(run_cli([str(plain), "--json"])[1])


@BOTH
def test_summary_says_where_the_comments_are(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = _write(tmp_path, COMMENTED)
    status, out, err = run_cli([str(path)])
    assert (status, out.splitlines()) == (0, SUMMARY)
    assert err == f"vw3-decode: {path}: 4 packet comments (records 1, 2, 3): -V and --json show them\n"
    plain = _write(tmp_path, [(0, REQUEST, [])], "plain.pcapng")
    assert run_cli([str(plain)])[2] == ""


@BOTH
def test_a_frame_of_several_records_has_all_their_comments(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                           pure: bool) -> None:
    """The request read in two records (the same time: one read cut in two), each commented; the second
    record also holds the answer's first bytes: the answer has that record's comment too."""
    use_engine(monkeypatch, pure)
    path = _write(tmp_path, [(0, REQUEST[:5], ["head"]), (0, REQUEST[5:] + ANSWER[:4], ["tail"]),
                             (10_000, ANSWER[4:], [])])
    import json

    rows = [json.loads(line) for line in run_cli([str(path), "--json"])[1].splitlines()]
    assert [(row["kind"], row["comments"]) for row in rows] == [
        ("request", ["head", "tail"]), ("response", ["tail"])]


@BOTH
def test_a_pcapng_copy_keeps_them_without_its_own(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                  pure: bool) -> None:
    """The copy's noise record carries the user's comment, then vw3-decode's; read back, only the user's
    is a packet comment: the copy decodes as the original (-V and --json alike), and so does its copy."""
    use_engine(monkeypatch, pure)
    path = _write(tmp_path, COMMENTED)
    copy, again = tmp_path / "copy.pcapng", tmp_path / "again.pcapng"
    assert run_cli([str(path), "-w", str(copy)]) == (0, "", "")
    assert records(copy) == [
        (0, REQUEST, ["poll \x1b[31m of 12"]), (10_000, ANSWER, ["answer", "again"]),
        (1_000_000, b"\xff\xff\xff", ["glitch", "noise: 3 bytes, too short for a frame"])]
    assert run_cli([str(copy), "-w", str(again)]) == (0, "", "")
    assert records(again) == records(copy)
    for options in (["-V"], ["--json"]):
        original = run_cli([str(path), *options])[1]
        assert run_cli([str(copy), *options])[1] == original.replace(str(path), str(copy))


def test_a_pcap_copy_says_they_are_not_kept(tmp_path: Path) -> None:
    path = _write(tmp_path, COMMENTED)
    copy = tmp_path / "copy.pcap"
    assert run_cli([str(path), "-w", str(copy)]) == (0, "", (
        f"vw3-decode: warning: -w {copy}: pcap has no packet comments: the 4 packet comments (records 1, 2, 3) "
        f"of {path} are not kept (write pcapng, -F pcapng, to keep them)\n"))


def test_a_comment_on_a_record_of_no_byte_is_told(tmp_path: Path) -> None:
    path = _write(tmp_path, [(0, REQUEST, []), (5_000, b"", ["empty"]), (10_000, ANSWER, [])])
    status, out, err = run_cli([str(path), "-V"])
    assert (status, "Packet comments" in out) == (0, False)
    assert err == ("vw3-decode: warning: 1 packet comment on records with no serial byte not shown "
                   "(tshark -V shows them)\n")


@pytest.mark.parametrize("text", [
    "noise: 3 bytes, no valid frame", "noise: 1 byte, no valid frame; then a damaged frame (5 bytes)",
    "a frame (4 bytes); then noise: 24 bytes, no valid frame",
    "noise: 2 bytes, the capture ends inside the answer (2 of 9 bytes)"])
def test_own_comments(text: str) -> None:
    assert own_comment(text)


@pytest.mark.parametrize("text", ["noise here", "glitch", "noise: 3 bytes", "a frame (4 bytes); checked"])
def test_user_comments(text: str) -> None:
    assert not own_comment(text)


def test_a_ring_buffers_files_and_standard_input(tmp_path: Path) -> None:
    """A ring buffer's files are one stream: each file's comments on its items, and each file named with
    its own records (they number from 1 in each: before, one line named the first file for both). A
    pcapng read from standard input has its comments too."""
    import json

    first = _write(tmp_path, [(0, REQUEST, ["one"]), (10_000, ANSWER, [])], "r_00001_20260101000000.pcapng")
    second = _write(tmp_path, [(1_000_000, REQUEST, []), (1_010_000, ANSWER, ["four", "five"])],
                    "r_00002_20260101000001.pcapng")
    status, out, err = run_cli([str(first), str(second), "--json"])
    assert (status, err) == (0, "")
    assert [json.loads(line).get("comments") for line in out.splitlines()] == [["one"], None, None, ["four", "five"]]
    assert run_cli([str(first), str(second)])[2] == (
        f"vw3-decode: {first}: 1 packet comment (record 1): -V and --json show them\n"
        f"vw3-decode: {second}: 2 packet comments (record 2): -V and --json show them\n")
    status, out, err = run_cli(["-", "--json"], stdin=second.read_bytes())
    assert (status, err) == (0, "")
    assert [json.loads(line).get("comments") for line in out.splitlines()] == [None, ["four", "five"]]
    assert run_cli(["-"], stdin=second.read_bytes())[2] == (
        "vw3-decode: standard input: 2 packet comments (record 2): -V and --json show them\n")
