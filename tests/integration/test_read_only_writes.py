"""A write of a parameter the map gives as read-only (access R) is warned on its request, and the exception
02 that refuses it (data/modbus.toml read_only_exception: Illegal Data Address, the simulator's answer too)
names the parameters instead of the code's plain meaning: devices/access.py, the plugin's
lua/src/explain.lua. FC6, FC16, FC23's write, FC22 (by a user map's access column). Before, every engine
was silent on the request and explained the exception as `address does not exist`. vw3-decode (compiled
engine, VW3_PURE_PYTHON=1) and the plugin."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine, write_rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

# Slave 12 (ATV71): ETA (3201, R) written, refused 02; RFR (3202, R) written, answered; ETA again, refused 03;
# CHCF (8401, RW) written, refused 02; FC23 reading RFR and writing ETA, refused 02.
HEX = ["0C 06 0C 81 00 07", "0C 86 02", "0C 10 0C 82 00 01 02 00 64", "0C 10 0C 82 00 01",
       "0C 06 0C 81 00 07", "0C 86 03", "0C 06 20 D1 00 03", "0C 86 02",
       "0C 17 0C 82 00 01 0C 81 00 01 02 00 03", "0C 97 02"]
ETA, RFR = "ETA (3201) is read-only (access R)", "RFR (3202) is read-only (access R)"
REFUSED = "exception 02 from the VW3 A3 303: ETA (3201) read-only (access R), not written"
WARNINGS = [[ETA], [], [RFR], [], [ETA], [], [], [], [ETA], []]
NOTES = [[], [REFUSED], [], [], [], ["exception 03 from the VW3 A3 303: value not permitted"], [],
         ["exception 02 from the VW3 A3 303: address does not exist"], [], [REFUSED]]
# A user map's access column, profile generic: SPD (100) R, SET (101) RW; FC22 of SPD, FC6 of SET, FC16 of
# both.
MAP = "address,code,name,access\n100,SPD,Speed,R\n101,SET,Setpoint,RW\n"
USER_HEX = ["05 16 00 64 00 FF 00 00", "05 96 02", "05 06 00 65 00 01", "05 06 00 65 00 01",
            "05 10 00 64 00 02 04 00 01 00 02", "05 90 02"]


@pytest.mark.parametrize("pure", [False, True])
def test_read_only_writes_warned(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = str(write_rtu(tmp_path / "writes.rtu", HEX))
    lines = run_cli(["--profile", "atv71", path])[1].splitlines()
    assert lines[:4] == [
        "     1            -  12 request   Write Single Register 3201 ETA=Ready to switch on, Switched on, "
        f"Operation enabled [warning: {ETA}]  CRC ok",
        "     2            -  12 exception Write Single Register: exception 2 (Illegal Data Address) [#1] "
        f"[{REFUSED}]  CRC ok",
        f"     3            -  12 request   Write Multiple Registers 3202: RFR=10.0 Hz [warning: {RFR}]"
        "  CRC ok",
        "     4            -  12 response  Write Multiple Registers 3202 written [#3]  CRC ok",
    ]
    frames = [json.loads(line) for line in run_cli(["--profile", "atv71", "--json", path])[1].splitlines()]
    assert [frame["warnings"] for frame in frames] == WARNINGS
    assert [frame["notes"] for frame in frames] == NOTES


@pytest.mark.parametrize("pure", [False, True])
def test_a_user_maps_access_column(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    (tmp_path / "user.csv").write_text(MAP)
    path = str(write_rtu(tmp_path / "user.rtu", USER_HEX))
    lines = run_cli(["--map", str(tmp_path / "user.csv"), path])[1].splitlines()
    spd = "SPD (100) is read-only (access R)"
    refused = "exception 02 from the device: SPD (100) read-only (access R), not written"
    assert [line[34:] for line in lines] == [
        f"Mask Write Register 100 AND 0x00FF OR 0x0000 [warning: {spd}]  CRC ok",
        f"Mask Write Register: exception 2 (Illegal Data Address) [#1] [{refused}]  CRC ok",
        "Write Single Register 101 SET=1  CRC ok",
        "Write Single Register 101 SET=1 [#3]  CRC ok",
        f"Write Multiple Registers 100..101 (2): SPD=1 SET=2 [warning: {spd}]  CRC ok",
        f"Write Multiple Registers: exception 2 (Illegal Data Address) [#5] [{refused}]  CRC ok",
    ]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_warns_of_read_only_writes(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "writes.pcap", [(rtu(text), 1.0 + 0.1 * n) for n, text in enumerate(HEX)])
    items, _, _ = lua_items(pcap, "-o", "vw3.profiles:atv71", two_pass=two_pass)
    assert [item.texts.get("warning", []) for item in items] == WARNINGS
    assert [item.texts.get("note", []) for item in items] == NOTES


def test_the_plugin_reads_a_user_maps_access_column(tmp_path: Path) -> None:
    (tmp_path / "user.csv").write_text(MAP)
    pcap = write_pcap(tmp_path / "user.pcap", [(rtu(text), 1.0 + 0.1 * n) for n, text in enumerate(USER_HEX)])
    items, _, _ = lua_items(pcap, "-o", f"vw3.maps:{tmp_path / 'user.csv'}")
    spd = "SPD (100) is read-only (access R)"
    refused = "exception 02 from the device: SPD (100) read-only (access R), not written"
    assert [item.texts.get("warning", []) for item in items] == [[spd], [], [], [], [spd], []]
    assert [item.texts.get("note", []) for item in items] == [[], [refused], [], [], [], [refused]]
