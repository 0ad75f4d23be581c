"""A map row's contradicting cells are judged from one table, maps.CONFLICTS, by Python's reader and by the
plugin's (lua/src/maps.lua, from the DATA codegen writes): a copy of the table judged in another order
changes the first error both readers give, and their default order gives the same one."""
from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

from dissector.codegen import lua as luagen
from dissector.devices import maps
from dissector.errors import ProfileError
from lua_harness import ensure_tool

# Signed, with enum and bit labels: contradicts three rules (signed_enum, enum_bits, labels_quantity's none).
ROW = "address,code,signed,enum,bits\n5,SPD,1,0=stop,0=run\n"


def _python(text: str) -> str:
    with pytest.raises(ProfileError) as raised:
        maps.parse_map(text, "map.csv")
    return str(raised.value)


def _plugin(plugin: Path, text: str, tmp_path: Path) -> str:
    script = tmp_path / "read.lua"
    script.write_text(f'dofile({json.dumps(str(plugin))})\nlocal rows, problem = package.loaded["vw3.env"]'
                      f'.parse_map({json.dumps(text)}, "map.csv")\nio.write(problem or "no error")\n', encoding="utf-8")
    result = subprocess.run([ensure_tool("lua5.4", "lua5.4"), str(script)], capture_output=True, text=True,
                            timeout=60)
    assert result.returncode == 0, result.stderr
    return result.stdout


@pytest.mark.parametrize("order", ["as shipped", "enum_bits first"])
def test_both_readers_judge_the_conflicts_table(order: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    if order == "enum_bits first":
        first = [rule for rule in maps.CONFLICTS if rule[0] == "enum_bits"]
        monkeypatch.setattr(maps, "CONFLICTS", (*first, *(rule for rule in maps.CONFLICTS if rule[0] != "enum_bits")))
    plugin = tmp_path / "vw3.lua"
    plugin.write_text(luagen.render_plugin(), encoding="utf-8")
    want = {"as shipped": "map.csv:2: a signed register cannot carry enum labels",
            "enum_bits first": "map.csv:2: a register cannot carry both enum and bit labels"}[order]
    assert _python(ROW) == want
    assert _plugin(plugin, ROW, tmp_path) == want
