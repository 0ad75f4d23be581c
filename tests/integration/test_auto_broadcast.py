"""A broadcast (slave 0) reaches every slave: under profile `auto` its registers are named with the profile every
slave met has (chosen, or forced per slave), its profile reason (-V Profile, vw3.profile_reason) saying it was
inferred (not repeated as a note); when those slaves are different devices, or one met has no device (unknown), a
note says no one device names them. Before, every broadcast under `auto` was `generic` (`8401 = 3 [broadcast]`)
while `--profile atv71` named it CHCF. Exact summary lines for exact bytes (a file, read twice: the choices over
the whole input; standard input: the choices so far, and a broadcast is provisional while no slave is met or one
met may still get a device), engine and VW3_PURE_PYTHON=1; the plugin (tshark 4.0.17, one pass and -2) field by
field as vw3-decode."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration
LATER = frozenset(["response_frame", "unanswered"])

READ = "0C 03 20D0 0003"
P38 = [READ, "0C 03 06 8000 0003 0002", READ, "0C 03 06 8000 8000 0002"]
RECORDS = [*P38, "00 06 20D1 0003", "00 10 20D1 0002 04 0003 0002", "05 03 0000 0001", "05 03 02 0007",
           "00 06 20D1 0003"]
REASON = "named with profile atv71, which every slave with a device here has (slave 12): a broadcast reaches them all"
MIXED = (" [named with spec semantics only: a broadcast reaches every slave, and those here are different devices"
         " (slave 5 {}, slave 12 atv71)]")
R1 = "Read Holding Registers 8400..8402 (3)"
HEAD = [
    f"     1     0.000000  12 request   {R1}  CRC ok",
    f"     2     0.500000  12 response  {R1}: 8400=non-existent CHCF=IO (I/O profile) COP=Cd (command) [#1, 500.0 ms]"
    "  CRC ok",
    f"     3     1.000000  12 request   {R1}  CRC ok",
    f"     4     1.500000  12 response  {R1}: 8400=non-existent CHCF=protected COP=Cd (command) [#3, 500.0 ms]"
    " [CHCF (8401) became protected: read 3 in frame #2, 16#8000 now]  CRC ok",
]
NAMED = [
    "     5     2.000000   0 request   Write Single Register 8401 CHCF=IO (I/O profile) [broadcast]  CRC ok",
    "     6     2.500000   0 request   Write Multiple Registers 8401..8402 (2): CHCF=IO (I/O profile) COP=Cd (command)"
    " [broadcast]  CRC ok",
]
SPEC = [
    "     5     2.000000   0 request   Write Single Register 8401 = 3 [broadcast]{}  CRC ok",
    "     6     2.500000   0 request   Write Multiple Registers 8401..8402 (2): 8401=3 8402=2 [broadcast]{}  CRC ok",
]
SLAVE_5 = [
    "     7     3.000000   5 request   Read Holding Registers 0  CRC ok",
    "     8     3.500000   5 response  Read Holding Registers 0: 0=7 [#7, 500.0 ms]  CRC ok",
]
LAST = "     9     4.000000   0 request   Write Single Register 8401 = 3 [broadcast]{}  CRC ok"


def _pcap(tmp_path: Path, records: list[str] = RECORDS) -> Path:
    return write_pcap(tmp_path / f"broadcast{len(records)}.pcap", [(rtu(hexa), 1700000000 + 0.5 * index)
                                                     for index, hexa in enumerate(records)])


def _provisional(lines: list[str]) -> list[str]:
    return [line.replace("  CRC ok", " [provisional]  CRC ok") for line in lines]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_broadcast_is_named_by_the_device_every_slave_shares(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                               pure: bool) -> None:
    use_engine(monkeypatch, pure)
    pcap = _pcap(tmp_path, RECORDS[:6])
    status, out, err = run_cli([str(pcap)])
    assert (status, out.splitlines(), err) == (0, HEAD + NAMED, "")
    # Its reason said once: the profile's (no note repeating it)
    status, out, err = run_cli(["-V", str(pcap)])
    frame_5 = out.split("Frame 5")[1].split("Frame 6")[0]
    assert (status, err, frame_5.count("named with")) == (0, "", 1)
    assert f"    Profile: atv71 ({REASON})\n" in frame_5
    # Read once: frames 1 to 3 before the choice (provisional), the broadcasts after it
    status, out, err = run_cli(["-"], stdin=pcap.read_bytes())
    once = _provisional(HEAD[:3])
    once[1] = once[1].replace("8400=non-existent CHCF=IO (I/O profile) COP=Cd (command)", "8400=32768 8401=3 8402=2")
    assert (status, out.splitlines(), err) == (0, once + HEAD[3:] + NAMED, "")


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_slave_met_without_a_device_leaves_a_broadcast_spec_semantics(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    pcap = _pcap(tmp_path)
    # Slave 5 stays generic over the file: the broadcasts reach it too, no one device names them
    unknown = MIXED.format("unknown")
    status, out, err = run_cli([str(pcap)])
    expected = HEAD + [line.format(unknown) for line in SPEC] + SLAVE_5 + [LAST.format(unknown)]
    assert (status, out.splitlines(), err) == (0, expected, "")
    # Read once: slave 5 not met yet at frames 5 and 6; at frame 9 it may still get a device (provisional)
    status, out, err = run_cli(["-"], stdin=pcap.read_bytes())
    lines = out.splitlines()
    last = LAST.format(" [provisional]" + unknown)
    assert (status, lines[4:], err) == (0, NAMED + _provisional(SLAVE_5) + [last], "")
    # Slave 5 forced to another device: slaves of different devices
    mixed = MIXED.format("sel749m")
    status, out, err = run_cli([str(pcap), "--profile", "5=sel749m"])
    plc = [line.replace(" 0", " 40001", 1).replace(" 0=7", " 40001=7") for line in SLAVE_5]  # (its 4X style)
    assert (status, out.splitlines()[4:9], err) == (0, [line.format(mixed) for line in SPEC] + plc
                                                    + [LAST.format(mixed)], "")


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_broadcast_before_any_slave_is_provisional(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     pure: bool) -> None:
    use_engine(monkeypatch, pure)
    pcap = _pcap(tmp_path, [RECORDS[4], *P38])
    first = "     1     0.000000   0 request   Write Single Register 8401 {} [broadcast]{}  CRC ok"
    status, out, err = run_cli([str(pcap)])
    assert (status, out.splitlines()[0], err) == (0, first.format("CHCF=IO (I/O profile)", ""), "")
    status, out, err = run_cli(["-"], stdin=pcap.read_bytes())
    assert (status, out.splitlines()[0], err) == (0, first.format("= 3", " [provisional]"), "")


@pytest.mark.parametrize("two_pass", [False, True], ids=["one-pass", "two-pass"])
def test_plugin_names_a_broadcast_as_vw3_decode(tmp_path: Path, two_pass: bool) -> None:
    named = _pcap(tmp_path, RECORDS[:6])
    got = run_tshark(named, "-T", "fields", "-e", "vw3.profile", "-e", "vw3.profile_reason", "-e", "vw3.note",
                     two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    assert got.stdout.splitlines()[4:] == [f"atv71\t{REASON}\t"] * 2
    first = _pcap(tmp_path, [RECORDS[4], *P38])
    provisional = run_tshark(first, "-T", "fields", "-e", "vw3.provisional", two_pass=two_pass).stdout.splitlines()
    assert provisional == ([""] * 5 if two_pass else ["1", "1", "1", "1", ""])
    for capture in (named, first):
        lua, _, _ = lua_items(capture, two_pass=two_pass)
        differences = compare(python_items(capture, one_pass=not two_pass), lua,
                              ignore=LATER if not two_pass else frozenset())
        assert not differences, "\n".join(differences[:40])
    pcap = _pcap(tmp_path)
    lua, _, _ = lua_items(pcap, "-o", "vw3.profiles:auto,5=sel749m", two_pass=two_pass)
    differences = compare(python_items(pcap, ["auto", "5=sel749m"], one_pass=not two_pass), lua,
                          ignore=LATER if not two_pass else frozenset())
    assert not differences, "\n".join(differences[:40])



@pytest.mark.parametrize("two_pass", [False, True], ids=["one-pass", "two-pass"])
def test_plugin_counts_a_slave_without_a_device_as_vw3_decode(tmp_path: Path, two_pass: bool) -> None:
    pcap = _pcap(tmp_path)
    got = run_tshark(pcap, "-T", "fields", "-e", "vw3.profile", "-e", "vw3.note", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    unknown = MIXED.format("unknown")[2:-1]
    broadcasts = [got.stdout.splitlines()[index] for index in (4, 5, 8)]
    assert broadcasts == ([f"generic\t{unknown}"] * 3 if two_pass else ["atv71\t"] * 2 + [f"generic\t{unknown}"])
    provisional = run_tshark(pcap, "-T", "fields", "-e", "vw3.provisional", two_pass=two_pass).stdout.splitlines()
    assert provisional == ([""] * 9 if two_pass else ["1", "1", "1", "", "", "", "1", "1", "1"])
    lua, _, _ = lua_items(pcap, two_pass=two_pass)
    differences = compare(python_items(pcap, one_pass=not two_pass), lua, ignore=LATER if not two_pass else frozenset())
    assert not differences, "\n".join(differences[:40])
