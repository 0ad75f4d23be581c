"""Review 3's plugin findings, under real tshark with lua/vw3.lua (-2 and one pass): a frame split over
records (a USB sniffer's reads) answers with its exact response time and highlights only the bytes that
continue, its records' 'ends inside a frame' is a Note, not a Warning, and an ASCII frame's check is
named an LRC (one byte) as vw3-decode names it."""
from __future__ import annotations

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0


def split_capture(tmp_path):
    # request 0c 03 20d0 0003 (8 bytes) and its answer (11 bytes), read 5, 5, 5, 4 bytes at a time
    data = rtu("0c 03 20d0 0003") + rtu("0c 03 06 0000 0002 0001")
    times = [T0, T0 + 0.000999, T0 + 0.002, T0 + 0.003]
    return write_pcap(tmp_path / "split5.pcap", [(data[i * 5:i * 5 + 5], times[i]) for i in range(4)])


@pytest.mark.parametrize("two_pass", [True, False])
def test_split_frames_response_time_and_partial_note(tmp_path, two_pass: bool) -> None:
    pcap = split_capture(tmp_path)
    got = run_tshark(pcap, "-T", "fields", "-e", "frame.number", "-e", "vw3.response_time", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    # (the answer starts in record 2, 0.000999 s after record 1 where its request starts: as vw3-decode)
    assert got.stdout.splitlines() == ["1\t", "2\t", "3\t", "4\t0.000999000"]
    experts = run_tshark(pcap, "-q", "-z", "expert", two_pass=two_pass).stdout
    if not two_pass:
        assert "Warns" not in experts
        assert ("Notes (3)\n=============\n   Frequency      Group           Protocol  Summary\n"
                "           2 Reassemble                VW3  The record ends inside a frame: its last 5 bytes are "
                "framed with the next records'\n"
                "           1 Reassemble                VW3  The record ends inside a frame: its last 2 bytes are "
                "framed with the next records'\n") in experts


def test_continued_in_covers_the_bytes_that_continue(tmp_path) -> None:
    pdml = run_tshark(split_capture(tmp_path), "-T", "pdml").stdout
    lines = [line.strip() for line in pdml.splitlines() if "vw3.continued_in" in line or "in a later record" in line]
    assert lines == [
        '<proto name="vw3" showname="VW3 bytes of a frame shown in a later record: 5 bytes continue in item 1 '
        '(record 2)" size="5" pos="0">',
        '<field name="vw3.continued_in" showname="Continued in record: 2" size="5" pos="0" show="2" '
        'value="0c0320d000"/>',
        '<proto name="vw3" showname="VW3 bytes of a frame shown in a later record: 2 bytes continue in item 2 '
        '(record 4)" size="2" pos="3">',
        '<field name="vw3.continued_in" showname="Continued in record: 4" size="2" pos="3" show="4" '
        'value="0c03"/>',
        '<proto name="vw3" showname="VW3 bytes of a frame shown in a later record: 5 bytes continue in item 2 '
        '(record 4)" size="5" pos="0">',
        '<field name="vw3.continued_in" showname="Continued in record: 4" size="5" pos="0" show="4" '
        'value="0600000002"/>',
    ]


@pytest.mark.parametrize("lrc", ["A3", "A2"])
def test_ascii_check_is_an_lrc(tmp_path, lrc: str) -> None:
    pcap = write_pcap(tmp_path / "lrc.pcap", [(f":02062329000A{lrc}\r\n".encode(), T0)])
    tree = run_tshark(pcap, "-V").stdout
    shown = [line.strip() for line in tree.splitlines() if "LRC" in line or "CRC" in line]
    if lrc == "A3":
        assert shown == [
            "VW3 Modbus ASCII, 2 Write Single Register request 9001 = 10 BAD LRC",
            "LRC: 0xa3", "[Expected LRC: 0xa2]", "[LRC OK: False]",
            "[Expert Info (Error/Checksum): Bad LRC: 0xA3, expected 0xA2]", "[Bad LRC: 0xA3, expected 0xA2]"]
    else:
        assert shown == ["LRC: 0xa2", "[Expected LRC: 0xa2]", "[LRC OK: True]"]
    # (the fields stay vw3.crc*, one filter for both modes)
    found = run_tshark(pcap, "-T", "fields", "-e", "vw3.crc", "-e", "vw3.crc_ok").stdout
    assert found.splitlines() == ["0x00" + lrc.lower() + "\t" + ("0" if lrc == "A3" else "1")]


def _columns(pcap, *options: str, two_pass: bool) -> list[tuple[str, ...]]:
    got = run_tshark(pcap, *options, "-T", "fields", "-e", "frame.interface_id", "-e", "_ws.col.Info", "-e",
                     "vw3.response_time", "-e", "_ws.expert.message", two_pass=two_pass)
    assert got.returncode == 0 and not lua_errors(got.stdout + got.stderr), got.stderr
    return [tuple(line.split("\t")) for line in got.stdout.splitlines()]


@pytest.mark.parametrize("two_pass", [True, False])
def test_interfaces_are_buses_of_their_own(tmp_path, monkeypatch, two_pass: bool) -> None:
    # Two captures merged into one pcapng, one interface each (mergecap -I none): with VW3_INTERFACES=1
    # each interface shows what its capture alone shows (framing, pairing, response times, devices), as
    # vw3-decode reads each interface as a bus. (tshark -2 needs a display filter for it: -Y frame.)
    from lua_harness import ROOT, ensure_tool
    import subprocess
    captures = [ROOT / "captures" / "p38_protection.pcap", ROOT / "captures" / "sel749m_polling.pcap"]
    merged = tmp_path / "merged.pcapng"
    subprocess.run([ensure_tool("mergecap", "wireshark-common"), "-I", "none", "-w", str(merged), *map(str, captures)],
                   check=True)
    options = ("-Y", "frame") if two_pass else ()
    one_bus = _columns(merged, *options, two_pass=two_pass)
    monkeypatch.setenv("VW3_INTERFACES", "1")
    rows = _columns(merged, *options, two_pass=two_pass)
    for interface, capture in enumerate(captures):
        alone = [row[1:] for row in _columns(capture, *options, two_pass=two_pass)]
        assert [row[1:] for row in rows if row[0] == str(interface)] == alone
    assert not any("Request not answered" in row[3] for row in rows)
    assert one_bus != rows  # (without it: one bus, as before)
