"""A broadcast (slave 0) reaches every slave: under profile `auto` its registers are named with the profile
every slave with a device has (chosen, or forced per slave), and a note says it was inferred; when those
slaves are different devices, a note says no one device names them. Before, every broadcast under `auto`
was `generic` (`8401 = 3 [broadcast]`) while `--profile atv71` named it CHCF. Exact summary lines for exact
bytes (a file, read twice: the choices over the whole input; standard input: the choices so far, and a
broadcast is provisional while a slave met may still get a device), engine
and VW3_PURE_PYTHON=1; the plugin (tshark 4.0.17, one pass and -2) field by field as vw3-decode."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration
LATER = frozenset(["response_frame", "unanswered"])

READ = "0C 03 20D0 0003"
RECORDS = [READ, "0C 03 06 8000 0003 0002", READ, "0C 03 06 8000 8000 0002", "00 06 20D1 0003",
           "00 10 20D1 0002 04 0003 0002", "05 03 0000 0001", "05 03 02 0007", "00 06 20D1 0003"]
INFERRED = " [named with profile atv71, which every slave with a device here has (slave 12): a broadcast reaches them all]"
MIXED = (" [named with spec semantics only: a broadcast reaches every slave, and those here are different devices"
         " (slave 5 sel749m, slave 12 atv71)]")
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
    f"     5     2.000000   0 request   Write Single Register 8401 CHCF=IO (I/O profile) [broadcast]{INFERRED}  CRC ok",
    "     6     2.500000   0 request   Write Multiple Registers 8401..8402 (2): CHCF=IO (I/O profile) COP=Cd (command)"
    f" [broadcast]{INFERRED}  CRC ok",
]
SLAVE_5 = [
    "     7     3.000000   5 request   Read Holding Registers 0  CRC ok",
    "     8     3.500000   5 response  Read Holding Registers 0: 0=7 [#7, 500.0 ms]  CRC ok",
]


def _pcap(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "broadcast.pcap", [(rtu(hexa), 1700000000 + 0.5 * index)
                                                     for index, hexa in enumerate(RECORDS)])


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_broadcast_is_named_by_the_device_every_slave_shares(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                               pure: bool) -> None:
    use_engine(monkeypatch, pure)
    pcap = _pcap(tmp_path)
    last = f"     9     4.000000   0 request   Write Single Register 8401 CHCF=IO (I/O profile) [broadcast]{INFERRED}  CRC ok"
    status, out, err = run_cli([str(pcap)])
    assert (status, out.splitlines(), err) == (0, HEAD + NAMED + SLAVE_5 + [last], "")
    # Read once: frames 1 to 3 before the choice (provisional), the broadcasts after it
    status, out, err = run_cli(["-"], stdin=pcap.read_bytes())
    once = [line.replace("  CRC ok", " [provisional]  CRC ok") for line in HEAD[:3]]
    once[1] = once[1].replace("8400=non-existent CHCF=IO (I/O profile) COP=Cd (command)", "8400=32768 8401=3 8402=2")
    slave_5 = [line.replace("  CRC ok", " [provisional]  CRC ok") for line in SLAVE_5]
    # (frame 9: slave 5 may still get a device, which may name the broadcast otherwise: provisional)
    later = last.replace("[broadcast]", "[broadcast] [provisional]")
    assert (status, out.splitlines(), err) == (0, once + HEAD[3:] + NAMED + slave_5 + [later], "")
    # Slave 5 forced to another device: slaves of different devices, no one device names the broadcast
    status, out, err = run_cli([str(pcap), "--profile", "5=sel749m"])
    mixed = [line.replace(INFERRED, MIXED) for line in NAMED]
    mixed[0] = mixed[0].replace("8401 CHCF=IO (I/O profile)", "8401 = 3")
    mixed[1] = mixed[1].replace("CHCF=IO (I/O profile) COP=Cd (command)", "8401=3 8402=2")
    plc = [line.replace(" 0", " 40001", 1).replace(" 0=7", " 40001=7") for line in SLAVE_5]  # (its 4X style)
    assert (status, out.splitlines()[4:8], err) == (0, mixed + plc, "")


@pytest.mark.parametrize("two_pass", [False, True], ids=["one-pass", "two-pass"])
def test_plugin_names_a_broadcast_as_vw3_decode(tmp_path: Path, two_pass: bool) -> None:
    pcap = _pcap(tmp_path)
    got = run_tshark(pcap, "-T", "fields", "-e", "vw3.profile", "-e", "vw3.note", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    broadcasts = [got.stdout.splitlines()[index] for index in (4, 5, 8)]
    assert broadcasts == ["atv71\t" + INFERRED[2:-1]] * 3
    provisional = run_tshark(pcap, "-T", "fields", "-e", "vw3.provisional", two_pass=two_pass).stdout.splitlines()
    assert provisional == ([""] * 9 if two_pass else ["1", "1", "1", "", "", "", "1", "1", "1"])
    lua, _, _ = lua_items(pcap, two_pass=two_pass)
    differences = compare(python_items(pcap, one_pass=not two_pass), lua, ignore=LATER if not two_pass else frozenset())
    assert not differences, "\n".join(differences[:40])
    lua, _, _ = lua_items(pcap, "-o", "vw3.profiles:auto,5=sel749m", two_pass=two_pass)
    differences = compare(python_items(pcap, ["auto", "5=sel749m"], one_pass=not two_pass), lua,
                          ignore=LATER if not two_pass else frozenset())
    assert not differences, "\n".join(differences[:40])
