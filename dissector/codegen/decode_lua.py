"""The plugin's readers of the layouts and handlers of the lifting rules (lua/src/decode.lua takes them),
written out as Lua from data/modbus.toml [layouts], [parts] and [lift] as the rule data the plugin carries
states them (codegen/rules_lua.py rules_data, DATA.rules).

Each layout and part becomes one reader (DATA.parsers), each lifting rule one handler per limit its codes give
(DATA.lifters), with its fields, limits and offsets in place: a frame costs what a hand-written parser and
handler cost, which one generic interpreter of the rules does not (+13 % instructions a record on max-size).
"""
from __future__ import annotations

from typing import Any

from dissector.codegen.lua import lua_literal
from dissector.codegen.rules_lua import rules_data
from dissector.protocol.grammar import past_the_end, too_short_for

REQUEST_START, REQUEST_QUANTITY = "request.start", "request.quantity"
WIDTH = 110  # (a longer line is wrapped where Lua allows it: between a constructor's keys, around an if's body)
# The decoder's helpers the handlers call (lua/src/decode.lua; data_bytes: lua/src/layouts.lua): their upvalues.
HELPERS = ("warn", "say", "echo_check", "data_bytes", "range_text", "check_asked", "check_data_echo",
           "past_quantity")


def _wrap(head: str, items: list[str], joint: str, tail: str, indent: str) -> list[str]:
    """`head`, the items joined by `joint`, `tail`: one line, or the items on lines of their own at `indent`
    (and two more spaces), as many a line as fit."""
    line = head + joint.join(items) + tail
    if len(line) <= WIDTH:
        return [line]
    lines, current = [head.rstrip()], indent + "  "
    for index, item in enumerate(items):
        item += joint.rstrip() if index < len(items) - 1 else ""
        if current.strip() and len(current) + len(item) + 1 > WIDTH:
            lines.append(current)
            current = indent + "  "
        current += item if not current.strip() else " " + item
    return [*lines, current, indent + tail.lstrip()]


def _if(condition: str, body: str, indent: str = "") -> list[str]:
    """`if condition then body end`, on one line where it fits."""
    line = f"{indent}if {condition} then {body} end"
    if len(line) <= WIDTH:
        return [line]
    return [f"{indent}if {condition} then", f"{indent}  {body}", f"{indent}end"]


def _size_of(field: dict[str, Any], count: str) -> str:
    """A counted field's size in bytes, from the local holding its count: less `minus` (which may make it
    negative: the data do not fit), words(n/2) a whole number of words."""
    if field["type"] == "odd":
        return f"{count} % 2"
    n = f"({count} - {field['minus']})" if field["minus"] > 0 else count
    if field["half"]:
        return f"{n} - {n} % 2"
    return f"2 * {n}" if field["type"] == "words" else n


def reader(shape: list[dict[str, Any]]) -> tuple[list[str], dict[str, int]]:
    """A layout's or part's reader, `function(b, d, len)`: the byte table, the first data byte, the data length.
    It returns the bytes its grammar consumed (the rest is `trailing`) and the fields, or nil and why the data
    do not fit (Python: GrammarError). The fixed fields that come first: one length check for them all, read
    at constant offsets; u8 and u16 fields by name, a counted field by where it starts (NAME_at), the rest by
    its length (NAME_length), an array as a list of its parts' fields, a switch as the part's it chose, all in
    one table constructor. Also where each field at a constant offset is."""
    body, keys, index_of, fixed, offsets = [], [], {}, [], {}
    # (the fields a count or a condition reads, into a local)
    counts = {field[key] for field in shape for key in ("count", "when") if field.get(key) is not None}
    static: int | None = 0  # where the next field starts while that is a constant; then `p`
    for index, field in enumerate(shape, 1):
        name, kind, size = field["name"], field["type"], field["size"]
        index_of[name] = index
        when = field.get("when")
        if when is not None and static is not None:  # (?(n-k): where it starts, and what follows, is `p`)
            body.append(f"local p = {static}")
            static = None
        before = len(body)
        if static is not None:
            offsets[name] = static
        if size is not None:
            if static is None:
                body.append(f"if p + {size} > len then return nil, {lua_literal(too_short_for([name]))} end")
                value = "b[d + p]" + (" * 256 + b[d + p + 1]" if size == 2 else "")
            else:
                fixed.append(name)
                value = f"b[d + {static}]" if static else "b[d]"
                value += f" * 256 + b[d + {static + 1}]" if size == 2 else ""
            if name in counts or static is None:
                body.append(f"local v{index} = {value}")
                value = f"v{index}"
            keys.append(f"[{lua_literal(name)}] = {value}")
            if static is not None:
                static += size
            else:
                body.append(f"p = p + {size}")
        elif kind == "rest":
            keys.append(f"[{lua_literal(name + '_length')}] = len - {static if static is not None else 'p'}")
        else:
            if static is not None:
                body.append(f"local p = {static}")
            static = None
            count = f"v{index_of[field['count']]}"
            if kind == "array":  # (count parts one after another; one that does not fit ends them: layouts._UpTo)
                body += [f"local a{index} = {{}}", f"for k = 1, {count} do",
                         f"  local used, item = PARTS[{lua_literal(field['part'])}](b, d + p, len - p)",
                         "  if used == nil then break end", f"  a{index}[k], p = item, p + used", "end"]
                keys.append(f"[{lua_literal(name)}] = a{index}")
            elif kind == "switch":  # (the part for the field's value, else the last one)
                choice = [f"PARTS[{lua_literal(case['part'])}]" for case in field["cases"]]
                choice = [f"{count} == {case['value']} and {part}" if case["value"] is not None else part
                          for case, part in zip(field["cases"], choice)]
                body += [f"local used, c{index} = ({' or '.join(choice)})(b, d + p, len - p)",
                         f"if used == nil then return nil, c{index} end", "p = p + used"]
                keys.append(f"[{lua_literal(name)}] = c{index}")
            else:
                body.append(f"local s{index} = {_size_of(field, count)}")
                negative = f"s{index} < 0 or " if field["minus"] > 0 else ""  # (less `minus`: maybe below 0)
                body.append(f"if {negative}p + s{index} > len then return nil, "
                            f"{lua_literal(past_the_end(field['count']))} end")
                if kind != "odd":  # (where an odd byte is, nothing asks)
                    body.append(f"local a{index} = d + p")
                    keys.append(f"[{lua_literal(name + '_at')}] = a{index}")
                body.append(f"p = p + s{index}")
        if when is not None:  # (read where its condition holds; its locals nil where not)
            lines = body[before:]
            hoisted = [line.split()[1] for line in lines if line.startswith("local ")]
            del body[before:]
            body += [f"local {', '.join(hoisted)}"] * bool(hoisted)
            body.append(f"if v{index_of[when]} - {field.get('when_minus', 0)} > 0 then")
            body += [f"  {line.removeprefix('local ')}" for line in lines]
            body.append("end")
    if fixed:
        end = offsets[fixed[-1]] + shape[index_of[fixed[-1]] - 1]["size"]  # (where the last one ends)
        body.insert(0, f"if len < {end} then return nil, {lua_literal(too_short_for(fixed))} end")
    trailing = not shape or shape[-1]["type"] != "rest"
    used = "len" if not trailing else str(static) if static is not None else "p"
    body += _wrap(f"return {used}, {{ ", keys, ", ", " }", "")
    return body, offsets


def _check_line(check: dict[str, Any], value: str, what: str, low: int, high: int) -> list[str]:
    """The line that checks `value` (an expression) against low..high, `what` (an expression) naming it;
    test "above": the high bound only (its text names no low one). The fields are unsigned: a low bound of 0
    is none."""
    if check["test"] == "above":
        text = f'say("above", {{ what = {what}, value = {value}, high = {high} }})'
        return _if(f"{value} > {high}", f"warn(f, {text})")
    outside = (f"{value} ~= {low}" if low == high else f"{value} > {high}" if low == 0
               else f"{value} < {low} or {value} > {high}")
    return _if(outside, f"warn(f, range_text({what}, {value}, {low}, {high}))")


def _parts_lines(parts: dict[str, Any], at: str, size: str, limits: dict[str, list[int]]) -> list[str]:
    """The lines of a handler walking each part of a records field in the frame's bytes (FC20, FC21): its
    checks, what an answer asks of a request's part kept (`keep`), an answer's length fields (check_asked).
    Where its fields are and its size: rules_lua._parts; a part that does not fit ends them, as the grammar's."""
    def read(spec: list[int]) -> str:  # (a field of the part at `p`: its offset and width)
        return f"b[p + {spec[0]}]" if spec[1] == 1 else f"b[p + {spec[0]}] * 256 + b[p + {spec[0] + 1}]"

    out = [f"local p, stop, index = {at}, {at} + {size}, 0"]
    out += ["local kept = {}"] * bool(parts["keep"]) + ["local given = {}"] * bool(parts["length"])
    out.append(f"while p + {parts['fixed']} <= stop do")
    loop, bytes_ = [], str(parts["fixed"])
    if parts["size"]:
        counted = parts["size"]
        loop += [f"local n = {read(counted['at'])} - {counted['minus']}", "if n < 0 then break end"]
        bytes_ += " + " + ("n - n % 2" if counted["half"] else "2 * n" if counted["words"] else "n")
    loop += [f"if p + {bytes_} > stop then break end", "index = index + 1"]
    for check in parts["checks"]:
        what = f"{lua_literal(parts['name'] + ' ')} .. index .. {lua_literal(chr(39) + 's ' + check['what'])}"
        loop += [f"local v = {read(check['at'])}", *_check_line(check, "v", what, *limits[check["limit"]])]
    if parts["keep"]:
        loop.append(f"kept[index] = {read(parts['keep'])}")
    if parts["length"]:
        loop.append(f"given[index] = {read(parts['length']['at'])}")
    out += [*(f"  {line}" for line in loop), f"  p = p + {bytes_}", "end"]
    if parts["keep"]:
        out.append(f"fields[{lua_literal(parts['field'])}] = kept")
    if parts["request"]:
        asked = f"request.fields[{lua_literal(parts['request'])}]"
        out += [f"if request ~= nil and {asked} ~= nil then",
                f"  check_asked(f, parts, index, {'given' if parts['length'] else 'nil'}, {asked})", "end"]
    return out


def lifter(rule: dict[str, Any], limit: str | None, shape: list[dict[str, Any]], offsets: dict[str, int],
           limits: dict[str, list[int]]) -> list[str]:
    """The body of one rule's handler, `function(f, b)`, for a layout (`shape`, `offsets`: reader's) and the
    limit its code checks (decode/fields.py lifter). Warnings in the table's order: checks, span, byte count,
    odd count, coil, echo."""
    named = {item["name"]: item for item in shape}

    def field(name: str) -> str:
        return f"fields[{lua_literal(name)}]"

    out = ["local fields = f.fields"]
    start, quantity, count, values, echo = (rule[key] for key in ("start", "quantity", "count", "values", "echo"))
    if (start == REQUEST_START or quantity == REQUEST_QUANTITY or (count and count["of"] == REQUEST_QUANTITY)
            or echo or (rule["parts"] and rule["parts"]["request"])):
        out += ["local request = f.request",
                "if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)"]
    first = "request and request.start" if start == REQUEST_START else field(start) if start else "nil"
    out.append(f"local first = {first}")
    if isinstance(quantity, int):
        out.append(f"local many = {quantity}")
    elif quantity == REQUEST_QUANTITY:
        out.append("local many = request and request.quantity")
        unit = rule["unpaired_unit"]
        if unit == 0:  # (bits: a byte count of 0 alone says the quantity, decode/fields.py)
            out += _if("many == nil and fields.byte_count == 0", "many = 0")
        elif unit:
            out += _if(f"many == nil and fields.byte_count % {unit} == 0", f"many = floor(fields.byte_count / {unit})")
    else:
        out.append("local many = " + (field(quantity) if quantity else "nil"))
    out.append("f.start, f.quantity = first, many")
    for check in rule["checks"]:
        low, high = limits[check["limit"] or limit]
        out += _check_line(check, field(check["field"]), lua_literal(check["what"]), low, high)

    def span(first: str, many: str) -> list[str]:  # (a window past the last address, 65535)
        text = f'say("span", {{ first = {first}, last = {first} + {many} - 1 }})'
        return _if(f"{first} + {many} > 65536", f"warn(f, {text})")

    if rule["span"]:
        out += span("first", "many")
        if rule["write_window"]:  # (FC23: its written window too)
            out += span(*map(field, rule["write_window"]))
    if count:
        of = "request and request.quantity" if count["of"] == REQUEST_QUANTITY else field(count["of"])
        text = f"say({lua_literal(count['text'])}, {{ count = fields.byte_count, quantity = of }})"
        out += [f"local of = {of}", f"if of ~= nil and fields.byte_count ~= {count['plus']} + data_bytes(of, "
                f"{count['unit']}) then", f"  warn(f, {text})"]
        if rule["padding"] and values:  # (the last byte's bits past the quantity: 2^(of % 8) and up)
            last = f"b[{field(values['field'] + '_at')} + fields.byte_count - 1]"
            said = f"say({lua_literal(rule['padding'])}, {{ quantity = of, mask = unused }})"
            out += ["elseif of ~= nil and of % 8 > 0 then", "  local low = floor(2 ^ (of % 8))",
                    f"  local unused = {last} - {last} % low", f"  if unused > 0 then warn(f, {said}) end"]
        out.append("end")
    if rule["odd_count"]:
        out += _if("fields.byte_count % 2 == 1", 'warn(f, say("odd_count", { count = fields.byte_count }))')
    if rule["coil"]:
        coil = field(rule["coil"])
        out += _if(f"{coil} ~= 65280 and {coil} ~= 0", f'warn(f, say("coil_value", {{ value = {coil} }}))')
    if echo and echo["data"]:  # (FC21: the answer repeats the request's data whole)
        out.append("check_data_echo(f, b, request, 0)")
    elif echo:  # (an answer that repeats its request but differs from it wrote something else)
        differs = [f"request.fields[{lua_literal(name)}] ~= {field(name)}" for name in echo["fields"]]
        out += _wrap("if request ~= nil and (", differs, " or ", ") then echo_check(f, fields, request, echo) end",
                     "")
    if values:  # (a run's `shift`: see lua/src/decode.lua release_run; a block's from its count field)
        at, item, offset = field(values["field"] + "_at"), named.get(values["field"], {}), offsets.get(values["field"])
        counted = item.get("count") and field(item["count"])
        if counted and item["half"]:  # (words)
            counted = f"floor({counted} / 2)"
        if values["kind"] == "registers":
            first = field(values["start"]) if values["start"] else "first"
            if values["most"]:  # (a write's words past its quantity: no register written, fields._past_quantity)
                most, past = field(values["most"]), lua_literal(values["past"])
                out += [f"local count, most = {counted}, {most}", "if count > most then",
                        f"  past_quantity(f, b, {at} + 2 * most, 2 * (count - most), most, {past})",
                        "  count = most", "end"]
                counted = "count"
            out += _wrap("f.registers = { ", ["b = b", f"first = {at}", f"count = {counted}", f"start = {first}",
                                              "shift = nil"], ", ", " }", "")
        elif values["kind"] == "bits":
            out += [f"local count = 8 * {counted}", "if many ~= nil and many < count then count = many end",
                    f"f.bits = {{ b = b, first = {at}, count = count, start = first, shift = nil }}"]
        elif values["kind"] == "register":
            out += _wrap("f.registers = { ", ["b = b", f"first = f.data_at + {offset}", "count = 1", "start = first",
                                              "shift = nil"], ", ", " }", "")
        else:  # (a value neither ON nor OFF is illegal and sets nothing, Application Protocol 6.5)
            value = field(values["field"])
            out += [f"if {value} == 65280 or {value} == 0 then"]
            out += _wrap("  f.bits = { ", [f"first = f.data_at + {offset}", "count = 1", "start = first",
                                           f"single = {value} == 65280 and 1 or 0"], ", ", " }", "  ")
            out.append("end")
    if rule["parts"]:  # (its parts by the layout's part, in the bytes its count gives)
        name = rule["parts"]["field"]
        out += _parts_lines(rule["parts"], field(name + "_at"), field(named[name]["count"]), limits)
    return out


def _key(name: str) -> str:
    """A table key in Lua: `.name`, or `["name"]` for one that is no identifier."""
    return f".{name}" if name.isidentifier() else f"[{lua_literal(name)}]"


def _function(target: str, body: list[str], params: str, indent: str) -> list[str]:
    return [f"{indent}{target} = function({params})", *(f"{indent}  {line}" for line in body), f"{indent}end"]


def _handler_names(by_code: dict[str, dict[int, Any]]) -> dict[tuple[str, str | None, str], str]:
    """A handler's name per rule, limit and layout its codes give: the rule's, with the limit or layout where
    its codes give it several."""
    uses: dict[str, dict[tuple[str | None, str], None]] = {}  # (in the table's order: the file stays the same)
    for codes in by_code.values():
        for entry in codes.values():
            if entry["rule"]:
                uses.setdefault(entry["rule"], {})[entry["limit"], entry["layout"]] = None
    names = {}
    for rule, pairs in uses.items():
        for use in pairs:
            differ = [part for index, part in enumerate(use) if part and len({other[index] for other in pairs}) > 1]
            names[(rule, *use)] = "_".join([rule, *differ])
    return names


def render_decoders() -> list[str]:
    """The Lua lines, inside the generated block, that define DATA.parsers (the readers by layout name),
    DATA.grammars and DATA.lift_of (by direction and code: its layout's reader, its lifting rule) and
    DATA.lifters (given the named special cases and the decoder's helpers, the handlers by direction and
    code)."""
    rules = rules_data()
    lines = ["do", "local PARTS, PARSERS = {}, {} -- (a layout's reader calls its parts' by name)"]
    offsets = {}
    for table, shapes in (("PARTS", rules["parts"]), ("PARSERS", rules["layouts"])):
        for name, shape in shapes.items():
            body, offsets[name] = reader(shape)
            lines += _function(table + _key(name), body, "b, d, len", "")
    lines.append("DATA.parsers = PARSERS")
    # (per direction and code: its layout's reader, and its lifting rule's data, which the device checks read)
    for target, table, key in (("grammars", "PARSERS", "layout"), ("lift_of", "DATA.rules.lift", "rule")):
        lines.append(f"DATA.{target} = {{")
        for kind, codes in rules["by_code"].items():
            entries = [f"[{code}] = {table}{_key(entry[key])}" for code, entry in codes.items() if entry[key]]
            lines += _wrap(f"  {kind} = {{ ", entries, ", ", " },", "  ")
        lines.append("}")
    lines += [*_wrap("function DATA.lifters(", ["special", *HELPERS], ", ", ")", ""),
              "  local floor, lift = math.floor, DATA.rules.lift",
              "  local handler = {} -- (by rule, and limit where codes give a rule several)"]
    names = _handler_names(rules["by_code"])
    for (rule, limit, layout), name in names.items():
        lift = rules["lift"][rule]
        body = lifter(lift, limit, rules["layouts"][layout], offsets[layout], rules["limits"])
        upvalues = []  # (what the rule's helpers read of it; in a block of its own, named as they are)
        if lift["echo"] and not lift["echo"]["data"]:
            upvalues.append(f"local echo = lift{_key(rule)}.echo")
        if lift["parts"] and lift["parts"]["request"]:
            upvalues.append(f"local parts = lift{_key(rule)}.parts")
        if upvalues:
            lines += ["  do", *(f"    {line}" for line in upvalues),
                      *_function("handler" + _key(name), body, "f, b", "    "), "  end"]
        else:
            lines += _function("handler" + _key(name), body, "f, b", "  ")
    lines.append("  return {")
    for kind, codes in rules["by_code"].items():
        # (a code without a rule: the named special case's handler, lua/src/decode.lua SPECIAL)
        entries = [f"[{code}] = special{_key(entry['special'])}" if not entry["rule"]
                   else f"[{code}] = handler{_key(names[entry['rule'], entry['limit'], entry['layout']])}"
                   for code, entry in codes.items() if entry["rule"] or entry["special"]]
        lines += _wrap(f"    {kind} = {{ ", entries, ", ", " },", "    ")
    return [*lines, "  }", "end", "end"]
