"""The protocol table is the one source: every name it gives has an implementation, its length rules
agree with its grammars, and the generated files (C header, Lua tables) are current."""
from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from construct import ConstructError

from dissector.decode import fields
from dissector.framing import rtu
from dissector.model import Kind
from dissector.protocol import table
from dissector.protocol.grammar import GRAMMARS, parse_pdu
from dissector.protocol.rules import LIFTS
from dissector.protocol.shapes import SHAPES

ROOT = Path(__file__).resolve().parents[2]
PLUGIN = ROOT / "lua" / "vw3.lua"
LAYOUTS = [(entry.code, kind, entry.layout(kind)) for entry in table.FUNCTIONS for kind in (Kind.REQUEST, Kind.RESPONSE)]


def _lua_names(table_name: str) -> set[str]:
    text = PLUGIN.read_text(encoding="utf-8")
    # (to its closing brace at the indentation of its `local`)
    body = re.search(r"\n( *)local %s = \{\n(.*?)\n\1\}\n" % table_name, text, re.DOTALL)
    assert body is not None, f"lua/vw3.lua has no {table_name} table"
    return set(re.findall(r"(\w+) = ", body.group(2)))


def test_every_name_has_an_implementation() -> None:
    handlers = {layout.handler for _, _, layout in LAYOUTS if layout.handler}
    assert handlers <= set(fields.HANDLERS)
    # the plugin: the generic lifter interprets every [lift] rule, the named special cases are its SPECIAL;
    # every layout is read from its description ([layouts])
    assert handlers <= set(LIFTS) | _lua_names("SPECIAL")
    assert {layout.name for _, _, layout in LAYOUTS} <= set(SHAPES)
    assert "DATA.rules = RULES" in PLUGIN.read_text(encoding="utf-8")
    specials = {rule.name for _, _, layout in LAYOUTS for rule in _rules_within(layout.length) if isinstance(rule, table.Special)}
    assert specials == {"mei_objects"}  # (FC43/14's object walk, inside FC43's select on the MEI type)
    assert specials <= set(rtu._SPECIAL) and specials <= _lua_names("makers")
    c_kinds = set(re.findall(r"RULE_(\w+)", (ROOT / "dissector" / "accel" / "_tables.h").read_text(encoding="utf-8")))
    assert {name.upper() for name in specials} <= c_kinds


def _rules_within(rule: table.LengthRule) -> list[table.LengthRule]:
    """A length rule and every rule a select of it may pick (selects nest)."""
    if isinstance(rule, table.Select):
        return [rule, *_rules_within(rule.chosen), *_rules_within(rule.otherwise)]
    return [rule]


def test_derived_tables_follow_the_table() -> None:
    assert set(GRAMMARS) == {(code, kind) for code, kind, _ in LAYOUTS}
    assert set(rtu.RULES) == set(table.TABLE) | table.OTHER_FUNCTIONS
    assert table.register_reads() == {3, 4, 23}
    assert table.plain_register_reads() == {3, 4}
    assert table.COMPILED == (1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 15, 16, 17, 20, 21, 22, 23, 24, 43)


@pytest.mark.parametrize(("code", "kind", "layout"), [row for row in LAYOUTS if isinstance(row[2].length, table.Fixed)])
def test_fixed_lengths_fit_their_grammar(code: int, kind: Kind, layout: table.Layout) -> None:
    data_length = layout.length.length - 4  # slave, function, CRC
    parsed = parse_pdu(code, kind, bytes(data_length))
    assert not parsed.get("trailing")
    with pytest.raises((ConstructError, ValueError, Exception)):
        parse_pdu(code, kind, bytes(data_length - 1))


@pytest.mark.parametrize(("code", "kind", "layout"), [row for row in LAYOUTS if isinstance(row[2].length, table.Counted)])
def test_counted_lengths_point_at_the_byte_count(code: int, kind: Kind, layout: table.Layout) -> None:
    rule = layout.length
    assert table.field_offset(layout.grammar, "byte_count") + 2 == rule.position
    # extra: slave, function, the fields up to the byte count and the count itself, then the CRC
    assert rule.extra == rule.position + rule.width + 2


def test_codegen_check_passes_on_the_checkout() -> None:
    result = subprocess.run([sys.executable, "-m", "dissector.codegen", "--check"], cwd=ROOT, capture_output=True, text=True)
    assert (result.returncode, result.stderr) == (0, "")


def test_codegen_check_names_the_stale_files_after_a_table_change(tmp_path: Path) -> None:
    shutil.copytree(ROOT / "dissector", tmp_path / "dissector", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(ROOT / "lua", tmp_path / "lua")
    source = tmp_path / "dissector" / "protocol" / "table.py"
    text = source.read_text(encoding="utf-8")
    assert text.count("Counted(6, 9)") == 2
    source.write_text(text.replace("Counted(6, 9)", "Counted(6, 10)"), encoding="utf-8")
    check = [sys.executable, "-m", "dissector.codegen", "--check"]
    result = subprocess.run(check, cwd=tmp_path, capture_output=True, text=True)
    assert result.returncode == 1
    assert "_tables.h: stale" in result.stderr and "vw3.lua: stale" in result.stderr
    header = (tmp_path / "dissector" / "accel" / "_tables.h").read_text(encoding="utf-8")
    subprocess.run([sys.executable, "-m", "dissector.codegen"], cwd=tmp_path, check=True, capture_output=True)
    assert "{0, 6, 10, 1, 0, 0, 0, 0}" in (tmp_path / "dissector" / "accel" / "_tables.h").read_text(encoding="utf-8") != header
    assert subprocess.run(check, cwd=tmp_path, capture_output=True).returncode == 0
