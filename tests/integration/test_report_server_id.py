"""Report Server ID (FC17), added to the protocol table once: shown by the plugin under tshark, and
vw3-decode decoding the answer of a real libmodbus slave (tests/unit/test_server_id.py: -V,
--json and the summary line).

libmodbus answers `11 11 0A B4 FF 4C 4D 42 33 2E 31 2E 36 76 3E` (version 3.1.6): byte count 10, server
id 180 (0xB4), run indicator ON, then "LMB" and its version. The live test compiles a libmodbus RTU
slave in C, talks to it over a pseudo-terminal, and decodes what went over the wire.
"""
from __future__ import annotations

import os
import select
import subprocess
import termios
import time
import tty
from pathlib import Path

import pytest

from libmodbus_slave import build_slave
from lua_harness import lua_items, run_tshark, write_pcap
from server_id import REQUEST, RESPONSE, check_decoded

pytestmark = pytest.mark.integration


MAPPING = 'modbus_mapping_t *map = modbus_mapping_new(0, 0, 16, 0);'


def test_plugin_shows_the_fields(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "fc17.pcap", [(REQUEST, 1.0), (RESPONSE, 1.01)])
    items, _, _ = lua_items(pcap)
    response = items[1].fields
    assert response["function"] == "17"
    assert (response["byte_count"], response["server_id"], response["run_indicator"]) == ("10", "180", "0xff")
    assert response["additional_data"] == "LMB3.1.6"
    assert not items[1].experts
    text = run_tshark(pcap, "-V").stdout
    assert "    Server id: 180 (0xb4)\n    Run indicator: ON (0xff)\n    Additional data: LMB3.1.6\n" in text
    # (no 00 or FF after the first byte: no run indicator where a longer server id would put one either)
    odd = write_pcap(tmp_path / "odd.pcap", [(REQUEST, 1.0), (bytes.fromhex("11 11 04 01 12 01 02 C9 28"), 1.01)])
    odd_items, _, _ = lua_items(odd)
    assert "additional_data" not in odd_items[1].fields and odd_items[1].fields["additional_bytes"] == "01:02"
    assert odd_items[1].texts["warning"] == ["run indicator 0x12 is neither 0x00 (OFF) nor 0xFF (ON)"]


def _read_answer(fd: int, length: int, timeout: float = 5.0) -> bytes:
    data, deadline = b"", time.monotonic() + timeout
    while len(data) < length and time.monotonic() < deadline:
        ready, _, _ = select.select([fd], [], [], 0.1)
        if ready:
            data += os.read(fd, 256)
    return data


def test_real_libmodbus_slave_answer_decoded(tmp_path: Path) -> None:
    binary = build_slave(tmp_path, MAPPING)
    master, slave = os.openpty()
    tty.setraw(master)
    path = os.ttyname(slave)
    process = subprocess.Popen([str(binary), path], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        version = process.stdout.readline().strip()  # type: ignore[union-attr]
        assert version, process.stderr.read()  # type: ignore[union-attr]
        termios.tcflush(master, termios.TCIOFLUSH)
        os.write(master, REQUEST)
        text = "LMB" + version
        answer = _read_answer(master, 7 + len(text))
    finally:
        process.kill()
        process.wait()
        os.close(master)
        os.close(slave)
    assert answer[:5] == bytes([0x11, 0x11, 2 + len(text), 0xB4, 0xFF])
    if version == "3.1.6":
        assert answer == RESPONSE
    check_decoded(REQUEST, answer, text)
