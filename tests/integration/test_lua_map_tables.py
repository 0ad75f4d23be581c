"""The plugin reads a map copied from a meter's manual, 3X references (30001: input register 0, FC4) and
4X (40001: holding register 0, FC3) in one `reference` column, as vw3-decode does (test_map_tables.py):
each table's rows name its own registers, tshark's two passes and its one pass, through the quick lanes
(a polling slave's frames after its first) and not; the ATV71, whose FC4 reads the holding registers, a
4X row winning. Exact bytes; every item field by field as vw3-decode's --json (lua_compare)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_items, python_items, write_pcap

pytestmark = pytest.mark.integration

MAP = "reference,code,name,unit\n30001,IN0,Input zero,V\n30002,IN1,Input one,V\n40001,HR0,Holding zero,Hz\n" \
      "40002,HR1,Holding one,Hz\n"
# slave 1: FC4 reads input registers 0..1 (10, 11), FC3 holding registers 0..1 (20, 21)
ROUND = ["01 04 0000 0002", "01 04 04 000A 000B", "01 03 0000 0002", "01 03 04 0014 0015"]


def _pcap(tmp_path: Path, frames: list[str]) -> Path:
    return write_pcap(tmp_path / "r.pcap", [(rtu(frame), 1767225600.0 + index * 0.02)
                                            for index, frame in enumerate(frames)])


def _named(items: list) -> list[list[tuple[str | None, str | None]]]:
    return [[(register.get("code"), register.get("text")) for register in item.registers]
            for item in items if item.registers]


@pytest.mark.parametrize("two_pass", [True, False], ids=["two", "one"])
def test_plugin_names_each_table_by_its_references(tmp_path: Path, two_pass: bool) -> None:
    pcap = _pcap(tmp_path, ROUND * 3)
    path = tmp_path / "m.csv"
    path.write_text(MAP)
    options = ("-o", "vw3.profiles:generic", "-o", f"vw3.maps:{path}")
    lua, _, _ = lua_items(pcap, *options, two_pass=two_pass)
    assert _named(lua) == [[("IN0", "10 V"), ("IN1", "11 V")], [("HR0", "20 Hz"), ("HR1", "21 Hz")]] * 3
    ignore = frozenset() if two_pass else frozenset(["response_frame", "unanswered"])
    differences = compare(python_items(pcap, ["generic"], "--map", str(path), one_pass=not two_pass), lua, ignore)
    assert not differences, "\n".join(differences[:40])


def test_plugin_joins_3x_rows_where_fc4_reads_the_holding_registers(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path, ["01 04 0000 0003", "01 04 06 000A 000B 000C", "01 03 0000 0003", "01 03 06 0014 0015 0016"])
    path = tmp_path / "m.csv"
    path.write_text("reference,code\n30001,IN0\n30003,IN2\n40001,HR0\n")
    lua, _, _ = lua_items(pcap, "-o", "vw3.profiles:atv71", "-o", f"vw3.maps:{path}")
    assert [[code for code, _text in item] for item in _named(lua)] == [["HR0", None, "IN2"]] * 2
    differences = compare(python_items(pcap, ["atv71"], "--map", str(path)), lua, frozenset())
    assert not differences, "\n".join(differences[:40])


def test_plugin_auto_judges_fc4_reads_by_the_3x_rows(tmp_path: Path) -> None:
    """As vw3-decode (test_map_tables.py): profile auto chooses sel749m on FC4 reads its map's 3X rows name."""
    pcap = _pcap(tmp_path, ["01 04 0000 0002", "01 04 04 000A 000B", "01 04 000A 0001", "01 04 02 0007"] * 2)
    path = tmp_path / "m.csv"
    path.write_text("reference,code\n30001,IN0\n30002,IN1\n30011,IN10\n40001,HR0\n")
    lua, _, _ = lua_items(pcap, "-o", f"vw3.maps:sel749m={path}")
    assert [[code for code, _text in item] for item in _named(lua)] == [["IN0", "IN1"], ["IN10"]] * 2
    differences = compare(python_items(pcap, None, "--map", f"sel749m={path}"), lua, frozenset())
    assert not differences, "\n".join(differences[:40])
