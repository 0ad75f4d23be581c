"""FC12's events are a -T fields and -Y key, fields.event_list, as tshark's Modbus/TCP field modbus.event: one
occurrence an event, its byte (render/filter_fields.py DERIVED_KEYS); --json keeps each event's name and flags.
Before, fields.event_list was in --json alone: -e and -Y refused it ('no PDU layout has the key')."""
from __future__ import annotations

import subprocess
from pathlib import Path

from helpers import run_cli, write_rtu
from lua_net import write_modbus_tcp_pairs

REQUEST, RESPONSE = "0C", "0C 0A 0000 0100 0200 03200140"  # (events 3, 32, 1, 64: newest first)


def test_event_list_is_a_field_as_modbus_event(tmp_path: Path) -> None:
    mbtcp = write_modbus_tcp_pairs(tmp_path / "fc12.pcap", [(REQUEST, RESPONSE)])
    done = subprocess.run(["tshark", "-n", "-r", str(mbtcp), "-T", "fields", "-e", "modbus.event",
                           "-e", "modbus.ev_count"], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0 and done.stdout == "\t\n3,32,1,64\t256\n"
    rtu = tmp_path / "fc12_rtu.pcap"
    write_rtu(rtu, [f"0C{pdu}".replace(" ", "") for pdu in (REQUEST, RESPONSE)])
    assert run_cli(["-T", "fields", "-e", "fields.event_list", "-e", "fields.event_count", str(rtu)]) == (
        0, done.stdout, "")
    assert run_cli(["-T", "fields", "-E", "occurrence=l", "-e", "fields.event_list", str(rtu)])[1] == "\n64\n"


def test_a_filter_tests_each_event(tmp_path: Path) -> None:
    rtu = tmp_path / "fc12_rtu.pcap"
    write_rtu(rtu, [f"0C{pdu}".replace(" ", "") for pdu in (REQUEST, RESPONSE)])
    for expression, frames in (("fields.event_list == 64", "2\n"), ("fields.event_list == 5", ""),
                               ("fields.event_list & 0x40 && count(fields.event_list) == 4", "2\n"),
                               ("fields.event_list", "2\n")):
        assert run_cli(["-Y", expression, "-T", "fields", "-e", "frame", str(rtu)]) == (0, frames, ""), expression
    status, out, err = run_cli(["-Y", 'fields.event_list == "x"', str(rtu)])
    assert (status, out, err.splitlines()[0]) == (
        2, "", "vw3-decode: fields.event_list is a number, not '\"x\"' (column 22)")
