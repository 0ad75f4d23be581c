"""A Mask Write (FC22) lists its register in --json's `registers` and -V, as -T registers has shown its rows:
the address, the value where the value before does not matter (and_mask 0: or_mask; else null) and the
masks as text (`AND 0x00F2 OR 0x0025: the result depends on the value before`), a PLC label under
--address-style plc. Before, --json had no `registers` for FC22 (its masks in `fields` only), so -T fields
`-e value -e text` and -Y 'value == 37' did not see what -T registers showed. -T registers' rows are made
from these (render/registers.py register_rows), so the two cannot disagree. The plugin lists the same
register (vw3.reg.*): tshark -2 with lua/vw3.lua. Compiled engine and VW3_PURE_PYTHON=1 alike."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import engine_output_as_python, rtu
from lua_harness import lua_items, write_pcap
from lua_compare import lua_frame

BUS = ["01 16 0028 00F2 0025", "01 16 0028 00F2 0025", "01 16 0029 0000 0025", "01 16 0029 0000 0025",
       "01 16 0029 0000 0025", "01 96 02"]
UNKNOWN = "AND 0x00F2 OR 0x0025: the result depends on the value before"
REGISTERS = [
    [{"address": 40, "value": None, "text": UNKNOWN}], [{"address": 40, "value": None, "text": UNKNOWN}],
    [{"address": 41, "value": 37, "text": "AND 0x0000 OR 0x0025"}],
    [{"address": 41, "value": 37, "text": "AND 0x0000 OR 0x0025"}],
    [{"address": 41, "value": 37, "text": "AND 0x0000 OR 0x0025"}], None,  # (an exception: none)
]


def _argv(*options: str) -> list[str]:
    return [*options] + [arg for frame in BUS for arg in ("--hex", rtu(frame).hex())]


def test_json_lists_the_mask_register(monkeypatch: pytest.MonkeyPatch) -> None:
    out, _framed = engine_output_as_python(_argv("--json"), monkeypatch)
    records = [json.loads(line) for line in out.splitlines()]
    assert [record.get("registers") for record in records] == REGISTERS
    # -T fields and -Y see it as -T registers does
    out, _framed = engine_output_as_python(_argv("-T", "fields", "-e", "frame", "-e", "address", "-e", "value",
                                                 "-e", "text", "-Y", "value == 37"), monkeypatch)
    assert out.splitlines() == [f"{frame}\t41\t37\tAND 0x0000 OR 0x0025" for frame in (3, 4, 5)]


def test_plc_label(monkeypatch: pytest.MonkeyPatch) -> None:
    out, _framed = engine_output_as_python(_argv("--json", "--address-style", "plc"), monkeypatch)
    first = json.loads(out.splitlines()[0])
    assert first["span_label"] == "40041" and first["registers"] == [
        {"address": 40, "value": None, "text": UNKNOWN, "label": "40041"}]


def test_the_plugin_lists_the_same_register(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "mask.pcap", [(rtu(frame), 1767225600 + 0.01 * index)
                                               for index, frame in enumerate(BUS)])
    items = lua_items(pcap)[0]
    got = [lua_frame(item)["registers"] for item in items]
    assert got == [[(r["address"], r["value"], None, None, r["text"], None, None, None, None, None, 1)
                    for r in registers or []] for registers in REGISTERS]


def test_detail_shows_the_register(monkeypatch: pytest.MonkeyPatch) -> None:
    """-V lists it as a register too, after the masks (as the plugin's tree does)."""
    out, _framed = engine_output_as_python(_argv("-V"), monkeypatch)
    frames = out.split("\n\n")
    assert ("        OR mask: 37 (0x0025)\n        Register 40: no value\n"
            f"            Value: {UNKNOWN}\n        CRC: 0x28F6 [CRC ok]\n") in frames[0]
    assert ("        OR mask: 37 (0x0025)\n        Register 41: 37 (0x0025)\n"
            "            Value: AND 0x0000 OR 0x0025\n        CRC: 0x1B6A [CRC ok]\n") in frames[2]
    assert "        Register" not in frames[5]  # (the exception)
