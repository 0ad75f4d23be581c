"""A write whose byte count carries more values than its quantity (FC16: quantity 1, byte count 4, two
values; FC23's write part alike): the words past the quantity are no register written. Before, they were
listed as registers, remembered by the parameter memory (a later read of 16#8000 said `COP (8402) became
protected: written 2 in frame #2`) and counted as writes by --stats and --report. Now they are warned by
their bytes and nothing else (data/modbus.toml [lift] values' `most` and `past`: decode/fields.py, the
plugin's generated lifters; the compiled engine hands every byte count that disagrees over to Python).
A server answers exception 03 to such a request (Application Protocol 6.12); Wireshark 4.0's mbrtu lists
every value of the byte count (Register 8403 for quantity 2): no oracle for what was written.
vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin (tshark -2 and one pass)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [rtu("0C 10 20D1 0001 04 0003 0002"), rtu("0C 10 20D1 0001"),  # CHCF=3, then 00 02 past the quantity
          rtu("0C 03 20D1 0002"), rtu("0C 03 04 0003 8000"),  # COP reads 16#8000: nothing was known of it
          rtu("0C 17 20D1 0001 20D1 0001 04 0003 0002"), rtu("0C 17 02 0003")]  # FC23: the same past its write
PAST = "2 bytes past the {}quantity 1, not written: 00 02"
LINES = [
    "     1            -  12 request   Write Multiple Registers 8401: CHCF=IO (I/O profile) "
    f"[warning: byte count 4 disagrees with the quantity 1] [warning: {PAST.format('')}]  CRC ok",
    "     2            -  12 response  Write Multiple Registers 8401 written [#1]  CRC ok",
    "     3            -  12 request   Read Holding Registers 8401..8402 (2)  CRC ok",
    "     4            -  12 response  Read Holding Registers 8401..8402 (2): CHCF=IO (I/O profile) COP=protected "
    "[#3]  CRC ok",
    "     5            -  12 request   Read/Write Multiple Registers read 8401, write CHCF=IO (I/O profile) "
    f"[warning: byte count 4 disagrees with the write quantity 1] [warning: {PAST.format('write ')}]  CRC ok",
    "     6            -  12 response  Read/Write Multiple Registers 8401: CHCF=IO (I/O profile) [#5]  CRC ok",
]
PARAMETERS = [
    "slave   address  code  reads  unreadable  writes  refused  last              changes",
    "------------------------------------------------------------------------------------",
    "   12      8401  CHCF      2           0       2        0  IO (I/O profile)        0",
    "   12      8402  COP       0           1       0        0  protected               0",
    "  all  2 params            2           1       2        0                          0",
]


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_writes_no_value_past_the_quantity(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                      pure: bool) -> None:
    assert decode_frames(FRAMES, tmp_path, monkeypatch, pure, "--profile", "atv71").splitlines() == LINES
    out = decode_frames(FRAMES, tmp_path, monkeypatch, pure, "--profile", "atv71", "--stats").splitlines()
    start = out.index("Parameters") + 1
    assert out[start:start + len(PARAMETERS)] == PARAMETERS


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_writes_no_value_past_the_quantity(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "past.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap, "-o", "vw3.profiles:atv71", two_pass=two_pass)
    assert [[register["address"] for register in item.registers] for item in items] == [
        ["8401"], [], [], ["8401", "8402"], ["8401"], ["8401"]]
    assert [item.texts.get("warning", []) for item in items] == [
        ["byte count 4 disagrees with the quantity 1", PAST.format("")], [], [], [],
        ["byte count 4 disagrees with the write quantity 1", PAST.format("write ")], []]
    assert [item.texts.get("note", []) for item in items] == [[]] * 6
