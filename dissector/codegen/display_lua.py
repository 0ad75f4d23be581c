"""The plugin's Info texts of the forms vw3-decode's render/describe.py TEXT_FORMS gives (lua/src/tree.lua
summary takes them), written out as Lua from the forms the plugin's data states (codegen/fields_lua.py
info_forms, DATA.fields.info) and the layouts' fields (codegen/rules_lua.py rules_data, DATA.rules); and the
display's tables derived from those layouts and lifting rules (where each field is, which codes carry bits).

Each form becomes one function of the frame f and its bytes b (its slave byte at b[base], its data ending at
b[last]) per place its fields have in the layout its codes read, its texts and steps in one concatenation,
each field read at its constant offset: a text costs what a hand-written describer costs, which one generic
interpreter of the steps does not (+0.52 % instructions a record on max-size).
"""
from __future__ import annotations

from typing import Any

from dissector.codegen.decode_lua import WIDTH, _key, _wrap
from dissector.codegen.fields_lua import info_forms
from dissector.codegen.lua import lua_literal
from dissector.codegen.rules_lua import rules_data
from dissector.decode.fields import comm_event, event_bit_lines, event_kind
from dissector.errors import GenerateError
from dissector.protocol import table

# tree.lua's helpers the forms call, and its describers of describe._BY_NAME: DATA.info_forms's arguments.
HELPERS = ("DECIMAL", "DIAGNOSTICS", "count_text", "data_text", "fifo_values", "single_text", "span_text", "BY_NAME")
# (no field's local may hide them or the function's own names)
TAKEN = frozenset({*HELPERS, "format", "form", "coil", "f", "b", "base", "last", "st", "device"})
LUA_KEYWORDS = frozenset("""and break do else elseif end false for function goto if in local nil not or repeat
    return then true until while""".split())


def field_places(shape: list[dict[str, Any]]) -> dict[str, tuple[int, int | None]]:
    """Where each field of a layout begins (from the slave byte, 0) and its size, up to the first field of no
    fixed size (that one too: where it begins, no size)."""
    places, at = {}, 2
    for field in shape:
        size = None if field.get("when") else field["size"]  # (?(n-k): maybe absent, nothing after fixed)
        places[field["name"]] = (at, size)
        if size is None:
            break
        at += size
    return places


def form_body(form: str, steps: list[Any], places: dict[str, tuple[int, int | None]]) -> list[str]:
    """The body of one form's function, `function(f, b, base, last, st, device)`: the fields two steps read,
    each read once into a local of its name, then its texts and its steps' texts (describe._OF_FRAME,
    _OF_FIELD, hex and fifo) in one concatenation. (st, device: where the frame's device is found, for a
    step that names a register: tree.lua summary)"""
    read_by = [step[1] for step in steps
               if not isinstance(step, str) and step[0] not in ("label", "span", "plain_span", "data")]
    body, parts = [], []

    def value(name: str) -> str:  # (the field's value: its local, or read where it is used)
        at, size = places.get(name, (None, None))
        if size is None:
            raise GenerateError(f"render/describe.py TEXT_FORMS: form {form}: {name} has no fixed place")
        read = f"b[base + {at}]" if size == 1 else f"b[base + {at}] * 256 + b[base + {at + 1}]"
        if read_by.count(name) < 2:
            return read
        if name in TAKEN or name in LUA_KEYWORDS:
            raise GenerateError(f"render/describe.py TEXT_FORMS: form {form}: a field named {name}")
        if f"local {name} = {read}" not in body:
            body.append(f"local {name} = {read}")
        return name

    for step in steps:
        if isinstance(step, str):
            parts.append(lua_literal(step))
            continue
        what = step[0]
        if what in ("label", "span", "plain_span"):  # (describe.span_text: the window as named, PLC style too)
            parts.append("span_text(f)")
        elif what == "write":  # (FC23's write window, describe._write_span: PLC style its label; its values left out)
            parts.append(f"span_text({{ start = {value(step[1])}, quantity = {value(step[2])}, "
                         f"span_label = f.write_span_label }})")
        elif what == "dec":
            parts.append(f"DECIMAL[{value(step[1])}]")
        elif what == "hex":
            parts.append(f'format("%0{step[2]}X", {value(step[1])})')
        elif what == "count":  # (describe.count_text: `1 event`, `2 events`)
            parts.append(f"count_text({value(step[1])}, {lua_literal(step[2])})")
        elif what == "coil":  # (describe._coil)
            body.append(f"local coil = {value(step[1])}")
            parts.append('(coil == 0xFF00 and " = ON" or coil == 0 and " = OFF"'
                         ' or format(" = 0x%04X", coil))')
        elif what == "subfunction":  # (as the profile names it, else the spec)
            unknown = lua_literal(info_forms()["unknown_subfunction"])
            parts.append(f"(f.subfunction_text or DIAGNOSTICS[{value(step[1])}] or {unknown})")
        elif what == "single":  # (describe._single: the register as the device names it)
            parts.append(f"single_text(f, st, device, {value(step[1])})")
        elif what == "data":  # (describe._data: the field's bytes to the end of the data)
            parts.append(f"data_text(b, base + {places[step[1]][0]}, last)")
        elif what == "fifo":  # (the values after their count, describe's fifo step)
            parts.append(f"fifo_values(b, {value(step[1])}, base + {places[step[2]][0]}, last)")
        else:
            raise GenerateError(f"render/describe.py TEXT_FORMS: form {form}: the plugin has no step {what}")
    line, lines = "return ", []
    for index, part in enumerate(parts):  # (one concatenation, wrapped before a `..` where it is long)
        joint = "" if index == 0 else " .. "
        if len(line) + len(joint) + len(part) > WIDTH - 4 and line.strip() != "return":
            lines.append(line)
            line, joint = "  ", ".. "
        line += joint + part
    return [*body, *lines, line]


def _field_key(name: str) -> str:
    """A key in a table constructor: `name`, or `["name"]` for one that is no identifier."""
    return name if name.isidentifier() and name not in LUA_KEYWORDS else f"[{lua_literal(name)}]"


def render_display() -> list[str]:
    """The Lua lines, inside the generated block, that define DATA.info_forms (below), DATA.field_places (by
    layout, where each field begins and its size: field_places) and DATA.bit_windows (table.bit_windows: the
    codes whose request or answer carries bits, its lifting rule's values "bits" or "coil": its window's
    addresses are bits') and DATA.event_bits (by FC12 event kind, each bit's mask and tshark's line), DATA.comm_events (by event
    byte, its name and kind: decode/fields.py comm_event, event_kind)."""
    rules = rules_data()
    lines = ["DATA.field_places = {"]
    for layout, shape in rules["layouts"].items():
        places = [f"{_field_key(name)} = {{ at = {at}" + (f", size = {size} }}" if size else " }")
                  for name, (at, size) in field_places(shape).items()]
        lines += _wrap(f"  {_field_key(layout)} = {{ ", places, ", ", " },", "  ") if places else [
            f"  {_field_key(layout)} = {{}},"]
    bit_windows = ", ".join(f"[{code}] = true" for code in sorted(table.bit_windows()))
    # (FC12's event bits, tshark's line of each with %d for its value: decode/fields.py event_bit_lines)
    event_bits = {kind: [[mask, line.replace("{}", "%d")] for mask, line in bits]
                  for kind, bits in event_bit_lines().items()}
    events = {byte: [comm_event(byte)["event"], event_kind(byte)] for byte in range(256)}  # (its name and kind)
    return [*render_info_forms(), *lines, "}", f"DATA.bit_windows = {{ {bit_windows} }}",
            f"DATA.event_bits = {lua_literal(event_bits)}", f"DATA.comm_events = {lua_literal(events)}"]


def render_info_forms() -> list[str]:
    """The Lua lines, inside the generated block, that define DATA.info_forms: given tree.lua's helpers, the
    forms' functions by function code, then kind (FORMS[fn][kind]); a describer of describe._BY_NAME by its
    name in BY_NAME. And DATA.info_naming[fn][kind]: the forms that name a register as the frame's device
    does (a `single` step)."""
    info, rules = info_forms(), rules_data()
    functions: dict[str, dict[str, list[str]]] = {}  # (by form, the distinct bodies its codes' layouts give)
    chosen: dict[int, dict[str, str]] = {}
    naming: dict[int, list[str]] = {}  # (the forms with a `single` step: their text needs the frame's device)
    for kind, forms in info["forms"].items():
        for code, form in forms.items():
            steps = info["steps"][form]
            if isinstance(steps, str):
                chosen.setdefault(code, {})[kind] = "BY_NAME" + _key(steps)
                continue
            if any(not isinstance(step, str) and step[0] == "single" for step in steps):
                naming.setdefault(code, []).append(kind)
            places = field_places(rules["layouts"][rules["by_code"][kind][code]["layout"]])
            body = form_body(form, steps, places)
            bodies = functions.setdefault(form, {})
            name = next((name for name, other in bodies.items() if other == body), None)
            if name is None:
                name = form if not bodies else f"{form}_{kind}_{code}"
                bodies[name] = body
            chosen.setdefault(code, {})[kind] = "form" + _key(name)
    lines = [f"function DATA.info_forms({', '.join(HELPERS)})", "  local format = string.format",
             "  local form = {} -- (by form; by code and kind too where its layouts place its fields apart)"]
    for bodies in functions.values():
        for name, body in bodies.items():
            lines += [f"  form{_key(name)} = function(f, b, base, last, st, device)", *(f"    {line}" for line in body),
                      "  end"]
    lines.append("  return {")
    for code, kinds in sorted(chosen.items()):
        entries = ", ".join(f"{kind} = {function}" for kind, function in sorted(kinds.items()))
        lines.append(f"    [{code}] = {{ {entries} }},")
    return [*lines, "  }", "end", f"DATA.info_naming = {lua_literal({code: set(kinds) for code, kinds in naming.items()})}"]
