"""A Write Single Coil whose value is neither 0xFF00 nor 0x0000 sets nothing: Application Protocol 6.5, "All
other values are illegal and will not affect the output". It is warned (data/modbus.toml [texts] coil_value)
and shows its raw value; it writes no bit (fields.lifter's "coil" values, the plugin's generated lifter; the
compiled engine hands such a frame to Python). Before, every engine wrote the coil OFF: --json's bits
[{address 172, value 0}], -T registers' write and echo rows of 0, -V's `172: 0`, the plugin's `Bit 172 = 0`.
vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine, write_rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

# coil 172 written 0x1234, refused; written 0x1234, echoed; coil 173 written ON, echoed
HEX = ["01 05 00 AC 12 34", "01 85 03", "01 05 00 AC 12 34", "01 05 00 AC 12 34", "01 05 00 AD FF 00",
       "01 05 00 AD FF 00"]
WARNING = "coil value 0x1234 is neither 0xFF00 (on) nor 0x0000 (off)"


@pytest.mark.parametrize("pure", [False, True])
def test_no_bit_written_by_an_illegal_value(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = str(write_rtu(tmp_path / "coil.rtu", HEX))
    frames = [json.loads(line) for line in run_cli(["--json", path])[1].splitlines()]
    assert [frame.get("bits") for frame in frames] == [None, None, None, None, [{"address": 173, "value": 1}],
                                                       [{"address": 173, "value": 1}]]
    assert [frame["warnings"] for frame in frames] == [[WARNING], [], [WARNING], [WARNING], [], []]
    assert run_cli(["-T", "registers", path])[1].splitlines() == [
        "5\t\t1\t5\twrite\t173\t\t\t\t1\t\t\t\t\tconfirmed\t", "6\t\t1\t5\techo\t173\t\t\t\t1\t\t\t\t\tconfirmed\t"]
    verbose = [line.strip() for line in run_cli(["-V", path])[1].splitlines()]
    assert [line for line in verbose if line.startswith(("Value:", "Bits", "172:", "173:", "Warning:"))] == [
        "Value: 4660 (0x1234)", f"Warning: {WARNING}", "Value: 4660 (0x1234)", f"Warning: {WARNING}",
        "Value: 4660 (0x1234)", f"Warning: {WARNING}", "Value: 65280 (0xFF00)", "Bits (1)", "173: 1",
        "Value: 65280 (0xFF00)", "Bits (1)", "173: 1"]


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_writes_no_bit(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "coil.pcap", [(rtu(text), 1.0 + 0.1 * n) for n, text in enumerate(HEX)])
    items, _, _ = lua_items(pcap, two_pass=two_pass)
    on = [{"address": "173", "value": "1"}]
    assert [item.bits for item in items] == [[], [], [], [], on, on]
    assert [item.texts.get("warning", []) for item in items] == [[WARNING], [], [WARNING], [WARNING], [], []]
