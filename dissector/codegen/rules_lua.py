"""The rule tables of data/modbus.toml (protocol/rules.py) as Lua data for the Wireshark plugin, and the
Lua literal writer the conformance vectors (tests/conformance/vectors.lua) use.

`render_rules()` gives a Lua chunk defining `local RULES = {...}`: the lifting rules per handler name
(with each check's limit resolved per function code), how each write is confirmed, every layout's
fields (and the parts they repeat or switch to), and the catalogue of texts, each with its Python
template, its parameters in order and a `string.format` form (`%s` for a plain parameter, the format
spec carried over: `0x{value:04X}` -> `0x%04X`). The plugin's code generator (codegen/lua.py) places it
inside its generated block, between the markers below, so that `python3 -m dissector.codegen --check`
covers it with the rest of the plugin.
"""
from __future__ import annotations

import re
import string
from pathlib import Path
from typing import Any

from dissector.codegen import fields_lua
from dissector.codegen.lua import lua_literal as scalar_literal
from dissector.decode import fields
from dissector.framing.answers import ANSWERS
from dissector.model import Kind
from dissector.protocol import table
from dissector.protocol.printable import bytes_text
from dissector.protocol.rules import CONFIRM, LIFTS, TEXTS, Check, Confirm, Lift, params, text
from dissector.protocol.shapes import PARTS, SHAPES, Field
from dissector.protocol.spec import SPEC

BEGIN = "-- BEGIN RULES: python3 -m dissector.codegen (codegen/rules_lua.py, data/modbus.toml)"
END = "-- END RULES"


def lua_literal(value: Any) -> str:
    """A Lua literal for plain data: dicts, lists, strings, numbers, booleans; None is nil (an absent
    key in a table, a hole in a list)."""
    if not isinstance(value, (dict, list, tuple)):
        return scalar_literal(value)  # nil, booleans, numbers, strings: as the plugin's own block writes them
    if isinstance(value, dict):
        rows = [f"[{lua_literal(key)}]={lua_literal(item)}" for key, item in value.items() if item is not None]
        return "{" + ",".join(rows) + "}"
    if isinstance(value, (list, tuple)):
        return "{" + ",".join(lua_literal(item) for item in value) + "}"
    raise TypeError(f"no Lua literal for {type(value).__name__}")


_SPEC = re.compile(r"^[0-9]*(\.[0-9]+)?[dfxX]?$")


def lua_format(template: str) -> str:
    """A catalogue text as a `string.format` pattern; its parameters come in `params()` order."""
    out = []
    for literal, name, spec, conversion in string.Formatter().parse(template):
        out.append(literal.replace("%", "%%"))
        if name is None:
            continue
        if conversion == "r":
            out.append("%s")  # Python's repr: the parameter is listed in the text's `repr` (the plugin quotes it)
            continue
        if conversion or not _SPEC.match(spec or ""):
            raise ValueError(f"text {template!r}: no Lua form for {{{name}:{spec}}}")
        if not spec:
            out.append("%s")
        else:
            out.append("%" + spec + ("" if spec[-1] in "dfxX" else "d"))
    return "".join(out)


def _checks(checks: tuple[Check, ...]) -> list[dict[str, Any]]:
    return [{"what": c.what, "field": c.field, "limit": c.limit, "test": str(c.test)} for c in checks]


def _part_shape(rule: Lift) -> tuple[Field, ...]:
    """The [parts] entry a rule's records field repeats (every layout naming the field repeats the same)."""
    names = {f.part for shape in SHAPES.values() for f in shape if f.name == rule.parts.field and f.part}  # type: ignore[union-attr]
    if len(names) != 1:
        raise ValueError(f"[lift.{rule.name}] parts: {rule.parts.field!r} repeats {sorted(names)} parts")  # type: ignore[union-attr, type-var]
    return PARTS[names.pop()]  # type: ignore[arg-type]


def _at(shape: tuple[Field, ...], name: str) -> list[int]:
    """[offset, width] of a fixed-size field of a part, among the fixed-size fields it starts with."""
    offset = 0
    for f in shape:
        if f.size is None:
            break
        if f.name == name:
            return [offset, f.size]
        offset += f.size
    raise ValueError(f"no fixed-size field {name!r} at the start of a part")


def _parts(rule: Lift) -> dict[str, Any]:
    """A parts rule with where each field it reads is in its part and each part's size (the plugin walks the
    parts in the frame's bytes, making no table for one: check_parts), and what of a request's parts an answer
    asks for (`keep`: the field a request's rule keeps a list of)."""
    parts, shape = rule.parts, _part_shape(rule)
    assert parts is not None
    fixed = sum(f.size or 0 for f in shape if f.size is not None)
    counted = [f for f in shape if f.size is None]
    if len(counted) > 1 or any(f is not shape[-1] for f in counted) or (counted and counted[0].type not in ("words", "bytes")):
        raise ValueError(f"[lift.{rule.name}] parts: one counted field (words, bytes), last, at most")
    size = None if not counted else {
        "at": _at(shape, counted[0].count or ""), "minus": counted[0].minus, "half": counted[0].half,
        "words": counted[0].type == "words"}
    keep = [other.parts.length.of for other in LIFTS.values() if other.parts is not None and other.parts.length
            and other.parts.request == parts.field]
    return {
        "field": parts.field, "name": parts.name, "fixed": fixed, "size": size,
        "checks": [{"what": c.what, "at": _at(shape, c.field), "limit": c.limit, "test": str(c.test)} for c in parts.checks],
        "request": parts.request, "keep": _at(shape, keep[0]) if keep else None,
        "length": None if parts.length is None else {
            "at": _at(shape, parts.length.field), "unit": parts.length.unit, "plus": parts.length.plus,
            "text": parts.length.text},
    }


def _lift(rule: Lift) -> dict[str, Any]:
    return {
        "start": rule.start, "quantity": rule.quantity, "unpaired_unit": rule.unpaired_unit,
        "checks": _checks(rule.checks),
        "span": rule.span,
        "count": None if rule.count is None else {
            "of": rule.count.of, "unit": rule.count.unit, "plus": rule.count.plus, "text": rule.count.text},
        "odd_count": rule.odd_count, "padding": rule.padding, "coil": rule.coil,
        "echo": None if rule.echo is None else {"fields": list(rule.echo.fields), "names": str(rule.echo.names),
                                                "data": rule.echo.data},
        "parts": None if rule.parts is None else _parts(rule),
        "values": None if rule.values is None else {
            "kind": str(rule.values.kind), "field": rule.values.field, "start": rule.values.start,
            "most": rule.values.most, "past": rule.values.past},
        "write_window": None if rule.write_window is None else list(rule.write_window),
    }


def _shape(owner: str, shape: tuple[Field, ...], shown: dict[str, list[str]]) -> list[dict[str, Any]]:
    """A layout's or part's fields: each with its size (a fixed one's), what its size or part comes from,
    and the plugin fields that show it (`shown`: codegen/fields_lua.py pdu_fields; none: the display shows
    it otherwise)."""
    return [{"name": f.name, "type": str(f.type), "size": f.size, "count": f.count, "half": f.half,
             "minus": f.minus, "part": f.part, "shown": shown.get(f"{owner}.{f.name}"),
             # (?(n-k): present only where the field `when` less `when_minus` is above 0)
             "when": f.when, "when_minus": f.when_minus if f.when else None,
             # (switch: the parts by value, the last the default's)
             "cases": [{"value": value, "part": part} for value, part in f.cases] or None} for f in shape]


def rules_data() -> dict[str, Any]:
    """Everything the plugin needs to interpret the rule tables, as plain data."""
    by_code: dict[str, dict[int, Any]] = {}
    shown = fields_lua.pdu_fields()
    for kind in (Kind.REQUEST, Kind.RESPONSE):
        layouts = table.by_kind("name")[kind]
        handlers = table.by_kind("handler")[kind]
        limits = table.by_kind("limit")[kind]
        # Per code: its layout's name, the handler's rule name (or the special case's) and the layout's own
        # limit (a check without `limit` uses it).
        by_code[str(kind)] = {}
        for code in sorted(layouts.keys() | handlers.keys()):
            name = handlers.get(code)
            by_code[str(kind)][code] = {"layout": layouts.get(code), "rule": name if name in LIFTS else None,
                                        "special": None if name is None or name in LIFTS else name,
                                        "limit": limits.get(code)}
    return {
        "lift": {name: _lift(rule) for name, rule in LIFTS.items()},
        "by_code": by_code,
        "confirm": {code: str(how) for code, how in CONFIRM.items()},
        # The codes by how [confirm] says each write is confirmed (the masks an echo confirms: FC22).
        "by_confirm": {str(how): {code: True for code, said in CONFIRM.items() if said is how}
                       for how in Confirm},
        # The register writes by how the annotator's parameter memory takes them as confirmed
        # (table.confirmed_registers, annotator.py _BY_ECHO, _BY_ANSWER): by their echo FC6, by a normal
        # answer FC16 and FC23.
        "confirmed": {str(how): {code: True for code in sorted(table.confirmed_registers(how))} for how in Confirm},
        "limits": {name: list(value) for name, value in SPEC.limits.items() if isinstance(value, list)},
        "texts": {key: {"template": TEXTS[key], "format": lua_format(TEXTS[key]), "params": list(params(key)),
                        "repr": [name for _, name, _, conversion in string.Formatter().parse(TEXTS[key])
                                 if name and conversion == "r"]}
                  for key in TEXTS},
        # Every layout's fields in order (data/modbus.toml [layouts], and the [parts] they repeat or switch
        # to): what the plugin's reader reads.
        "layouts": {name: _shape(name, shape, shown) for name, shape in SHAPES.items()},
        "parts": {name: _shape(name, shape, shown) for name, shape in PARTS.items()},
        # An FC8 request's data word by sub-function ([diagnostic_data], fields._diagnostic_data): the words
        # allowed with what each asks, or the character it sets (and its names); and what its warning says is
        # allowed (`allowed`: the words in hex, or a character then 00).
        "diagnostic_data": {sub: _diagnostic_data(rule) for sub, rule in sorted(SPEC.diagnostic_data.items())},
        # The FC8 sub-functions whose answer repeats the request's data ([diagnostic_answers], fields._diagnostics).
        "diagnostic_echoes": SPEC.diagnostic_echoes,
        # A device object's byte as its value's text shows it (printable.bytes_text), and the objects an FC43/14
        # answer without any lacks (fields._MANDATORY_OBJECTS).
        "byte_text": {byte: bytes_text(bytes([byte])) for byte in range(256)},
        "mandatory_objects": fields._MANDATORY_OBJECTS,
        # The normal answer's length a request implies, by code (framing/answers.py ANSWERS): where the request's
        # quantity word is (from the slave byte), the count's unit and plus, the answer's length besides its count.
        "answers": {code: [offset + 2, count.unit, count.plus, extra] for code, (offset, extra, count) in ANSWERS.items()},
    }


def _diagnostic_data(rule: Any) -> dict[str, Any]:
    if rule.data is not None:
        return {"data": dict(sorted(rule.data.items())),
                "allowed": " or ".join(f"{value:04X}" for value in sorted(rule.data))}
    return {"character": rule.character, "names": dict(sorted((rule.names or {}).items())),
            "allowed": text("character_then_00")}


def render_rules() -> str:
    """The Lua chunk (between BEGIN and END) that defines `local RULES`."""
    return f"{BEGIN}\nlocal RULES = {lua_literal(rules_data())}\n{END}\n"


def current_in(plugin: Path) -> bool:
    """The plugin carries no rules block, or the one the tables give now (`--check` holds it to them)."""
    text = plugin.read_text(encoding="utf-8") if plugin.exists() else ""
    if BEGIN not in text:
        return True
    start = text.index(BEGIN)
    end = text.find(END, start)
    return end >= 0 and text[start : end + len(END) + 1] == render_rules()
