"""The plugin (lua/vw3.lua) is the assembly of its modules (lua/src) and the generated data, and the data's
Lua literals are exact."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.codegen import lua as luagen, rules_lua
from dissector.protocol.spec import SPEC


def test_generated_block_is_current() -> None:
    # Fails when a data file (modbus.toml, profiles/*.toml, maps/*.csv) or a module of lua/src changed
    # without regenerating.
    assert luagen.current_block() == luagen.render_block(), "run: python3 -m dissector.codegen.lua"
    assert luagen.render_data() in luagen.current_block()


def test_check_command_reports_a_stale_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    stale = tmp_path / "vw3.lua"
    stale.write_text(luagen.PLUGIN.read_text().replace('"Read Coils"', '"Read Coils (old)"'))
    assert luagen.main(["--check", "--plugin", str(stale)]) == 1
    assert "stale" in capsys.readouterr().err
    assert luagen.main(["--plugin", str(stale)]) == 0
    assert luagen.main(["--check", "--plugin", str(stale)]) == 0
    assert stale.read_text() == luagen.PLUGIN.read_text()


def test_a_main_without_its_module_lists_is_an_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = tmp_path / "src"
    src.mkdir()
    (src / "main.lua").write_text("-- entry\nrequire('vw3.crc')\n")
    assert luagen.main(["--plugin", str(tmp_path / "vw3.lua"), "--src", str(src)]) == 2
    assert "must list its modules" in capsys.readouterr().err


def test_lua_literals() -> None:
    assert luagen.lua_literal({3: "Read", 4: None}) == '{\n  [3] = "Read",\n  [4] = nil,\n}'
    assert luagen.lua_literal(frozenset([7, 2])) == "{\n  [2] = true,\n  [7] = true,\n}"
    assert luagen.lua_literal([1, 125]) == "{ 1, 125 }"
    assert luagen.lua_literal('a "q" \\ é\n') == '"a \\"q\\" \\\\ \\195\\169\\010"'
    assert luagen.lua_literal(0.1) == "0.1"
    with pytest.raises(TypeError):
        luagen.lua_literal(b"bytes")


def test_data_comes_from_the_package() -> None:
    data = luagen.plugin_data()
    assert data["functions"] == SPEC.functions
    # the spec limits once, in the rule data (DATA.rules.limits), as data/modbus.toml [limits] gives them
    assert "limits" not in data and rules_lua.rules_data()["limits"]["read_registers"] == [1, 125]
    atv71 = data["profiles"]["atv71"]
    assert atv71["protected_value"] == 0x8000 and atv71["all_protected_exception"] == 2
    assert atv71["map"][8401]["code"] == "CHCF"
    assert atv71["map"][3102] == {"code": "SFR", "name": "Switching frequency", "unit": "kHz", "scale": 0.1,
                                  "source": "A", "decimals": 1}
    assert data["default_profile"] == "auto"  # as vw3-decode's
    assert data["selection"]["fallback"] == "generic" and data["selection"]["candidates"] == ["atv71", "sel749m"]
    assert data["profiles"]["atv71"]["identify"]["product_codes"] == ["ATV71"]
