"""The rule tables of data/modbus.toml (protocol/rules.py) name what exists: every field a lifting rule
names is a field of the grammars of the layouts that use it, every text key is in the catalogue, every
confirmed write is a write; and their Lua forms format as Python does."""
from __future__ import annotations

import pytest
from construct import Struct

from dissector.codegen.rules_lua import lua_format
from dissector.model import Kind
from dissector.protocol import rules, table
from dissector.protocol.rules import LIFTS, TEXTS, params, text


def _grammar_fields(grammar: Struct) -> set[str]:
    return {sub.name for sub in grammar.subcons if sub.name}


@pytest.mark.parametrize("name", sorted(LIFTS))
def test_a_rule_names_fields_of_every_layout_using_it(name: str) -> None:
    layouts = [entry.layout(kind) for entry in table.FUNCTIONS for kind in (Kind.REQUEST, Kind.RESPONSE)
               if entry.layout(kind).handler == name]
    assert layouts, f"[lift.{name}] is no handler of the protocol table"
    for layout in layouts:
        assert LIFTS[name].fields() <= _grammar_fields(layout.grammar), layout.name


def test_every_handler_is_a_rule_or_a_named_special_case() -> None:
    from dissector.decode.fields import SPECIAL_HANDLERS

    handlers = {entry.layout(kind).handler for entry in table.FUNCTIONS for kind in (Kind.REQUEST, Kind.RESPONSE)}
    handlers.discard(None)
    assert handlers == set(LIFTS) | set(SPECIAL_HANDLERS)
    assert set(SPECIAL_HANDLERS) == {"diagnostics", "mei_request", "mei_response", "report_server_id_response"}


def test_request_values_and_texts_exist() -> None:
    for rule in LIFTS.values():
        for value in (rule.start, rule.quantity, rule.count.of if rule.count else None):
            if isinstance(value, str) and value.startswith(rules.REQUEST_PREFIX):
                assert value in ("request.start", "request.quantity")
        if rule.count:
            assert rule.count.text in TEXTS


def test_confirmed_writes_are_writes() -> None:
    for code in rules.CONFIRM:
        assert table.TABLE[code].access in (table.Access.WRITE, table.Access.READ_WRITE)
    assert table.confirmed_registers(rules.Confirm.ECHO) == {6}
    assert table.confirmed_registers(rules.Confirm.ANSWER) == {16, 23}
    assert table.write_windows() == {23: ("write_start", "write_quantity")}
    assert table.coil_requests() == {5}


def test_a_broken_rule_is_refused() -> None:
    with pytest.raises(rules.RuleError, match="unknown keys"):
        rules._lift("x", {"strat": "start"})
    with pytest.raises(rules.RuleError):
        rules._lift("x", {"checks": [{"what": "quantity"}]})


@pytest.mark.parametrize(("key", "values"), [
    ("late", {"delay_ms": 12.345, "number": 5, "timeout_ms": 200.0}),
    ("coil_value", {"value": 0x12AB}),
    ("range", {"what": "quantity", "value": 126, "low": 1, "high": 125}),
    ("inner_silence", {"silence_ms": 1.23456, "byte": 3, "limit": "1.5 characters"}),
])
def test_lua_format_gives_the_python_text(key: str, values: dict[str, object]) -> None:
    pattern = lua_format(TEXTS[key])
    ordered = tuple(values[name] for name in params(key))
    # %s of Lua is str(); %d, %X, %.1f are C's as Python's % operator has them.
    assert pattern % ordered == text(key, **values)


def test_layout_descriptions_are_checked() -> None:
    from dissector.protocol.shapes import SHAPES, ShapeError, parse_shape

    assert parse_shape("x", ["byte_count:u8", "values:words(byte_count/2)"])[1].half
    for bad, why in ((["a:u32"], "is no field"), (["a:bytes(n)"], "no earlier field"), (["n:u8", "a:bytes(n/2)"], "half"),
                     (["a:rest", "b:u8"], "after the rest"), (["class:u8"], "cannot be")):
        with pytest.raises(ShapeError, match=why):
            parse_shape("x", bad)
    for bad, why in ((["a:records(n, p)"], "no earlier field"), (["n:u8", "a:array(n, nothing)"], "no \\[parts\\]"),
                     (["n:u8", "a:bytes(n, file_record)"], "is no field"), (["n:u8{nothing}"], "no \\[parts\\] or \\[names\\]")):
        with pytest.raises(ShapeError, match=why):
            parse_shape("x", bad)
    # Every layout the protocol table names is described in data/modbus.toml, none written by hand.
    names = {entry.layout(kind).name for entry in table.FUNCTIONS for kind in (Kind.REQUEST, Kind.RESPONSE)}
    assert names <= set(SHAPES)


def test_the_lua_rules_load_and_format_as_python_does(tmp_path) -> None:  # noqa: ANN001
    """The RULES chunk the plugin will carry is valid Lua, and its string.format forms give the
    catalogue's texts (the integration test of the plugin itself waits for the wiring)."""
    import subprocess

    from dissector.codegen.rules_lua import render_rules
    from lua_harness import ensure_tool

    lua = ensure_tool("lua5.4", "lua5.4")
    script = tmp_path / "rules.lua"
    script.write_text(render_rules() + (
        'local t = RULES.texts\n'
        'print(string.format(t.late.format, 12.345, 5, 200.0))\n'
        'print(string.format(t.coil_value.format, 0x12AB))\n'
        'print(RULES.lift.read_write_request.write_window[2], RULES.confirm[6], RULES.by_code.response[3].rule)\n'
        'print(#RULES.layouts.read_registers_response, RULES.layouts.read_registers_response[2].type)\n'
    ), encoding="utf-8")
    out = subprocess.run([lua, str(script)], capture_output=True, text=True, check=True).stdout.splitlines()
    assert out == [
        text("late", delay_ms=12.345, number=5, timeout_ms=200.0),
        text("coil_value", value=0x12AB),
        "write_quantity\techo\tread_registers_response",
        "3\twords",
    ]
