"""Assemble the Wireshark Lua plugin (lua/vw3.lua) from its modules and the Python package's data.

The plugin must decode exactly as the Python decoder does, so every table it needs (function and
exception names, spec limits, framing constants, device profiles and register maps) is written here
from the same sources the Python side loads, never copied by hand, between two marker lines. Its logic
is hand-written in lua/src/: one module a stage (each names the Python module it mirrors), and
lua/src/main.lua, the entry, which lists them in load order (PURE: no Wireshark API, then WIRESHARK).
lua/vw3.lua is their assembly, one installable file: main.lua's header comment, the generated data,
each module as a function in package.preload["vw3.NAME"] (obtained with require), begun by the lines that say
how it sees the names the modules share (ENV_LINES) and its bindings of those it uses, then main.lua's body.

    python3 -m dissector.codegen.lua            # rewrite lua/vw3.lua
    python3 -m dissector.codegen.lua --check    # exit 1 when lua/vw3.lua is not that assembly
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path
from typing import Any

from dissector.codegen import fields_lua, lanes_lua, pack_lua, printable_table, profiles_lua, timing_lua
from dissector.decode import pairing
from dissector.devices import access, maps, maps_refs, profiles
from dissector.errors import GenerateError
from dissector.framing import ascii as ascii_framer, evidence, rtu as framer, stream as streambuf
from dissector.framing.rules import SILENCE_CUTS
from dissector.model import CUT_ANSWER, Kind
from dissector.protocol import ascii as ascii_mode, crc, rules, table
from dissector.protocol.spec import SPEC
from dissector.render import detail, summary
from dissector.sources import reader

BEGIN = "-- BEGIN GENERATED DATA: python3 -m dissector.codegen.lua (do not edit by hand)"
END = "-- END GENERATED DATA"
PLUGIN = Path(__file__).resolve().parents[2] / "lua" / "vw3.lua"
SRC = PLUGIN.parent / "src"
MAIN = "main.lua"
MODULE_LINE = "-- ---- vw3.{name}: lua/src/{name}.lua ----"


def lua_literal(value: Any, indent: str = "") -> str:
    """A Lua literal for plain Python data: dicts, lists, sets, strings, numbers, booleans, None."""
    if value is None:
        return "nil"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        return _lua_string(value)
    inner = indent + "  "
    if isinstance(value, (set, frozenset)):
        # Sets become lookup tables: key = true.
        value = {key: True for key in sorted(value)}
    if isinstance(value, dict):
        if not value:
            return "{}"
        rows = [f"{inner}[{lua_literal(key)}] = {lua_literal(item, inner)}," for key, item in value.items()]
        return "{\n" + "\n".join(rows) + "\n" + indent + "}"
    if isinstance(value, (list, tuple)):
        if not value:
            return "{}"
        if all(isinstance(item, (int, str, bool, float)) for item in value) and len(value) <= 16:
            return "{ " + ", ".join(lua_literal(item) for item in value) + " }"
        rows = [f"{inner}{lua_literal(item, inner)}," for item in value]
        return "{\n" + "\n".join(rows) + "\n" + indent + "}"
    raise TypeError(f"no Lua literal for {type(value).__name__}")


def _lua_string(text: str) -> str:
    # Decimal escapes for everything outside printable ASCII: valid in Lua 5.1 to 5.4 alike.
    out = []
    for byte in text.encode("utf-8"):
        char = chr(byte)
        if char in '"\\':
            out.append("\\" + char)
        elif 32 <= byte < 127:
            out.append(char)
        else:
            out.append(f"\\{byte:03d}")
    return '"' + "".join(out) + '"'


def plugin_data() -> dict[str, Any]:
    """Everything the plugin takes from the Python side, as plain data."""
    from dissector.codegen import rules_lua  # (it imports this module)
    data: dict[str, Any] = {
        "functions": SPEC.functions,
        "exceptions": SPEC.exceptions,
        "diagnostics": SPEC.diagnostics,
        "device_id_objects": SPEC.device_id_objects,
        "names": SPEC.names,  # value names of layout fields (u8{NAMES}: the run indicator)
        # (the spec limits: in the rule data, DATA.rules.limits, codegen/rules_lua.py)
        "framing": {
            "max_adu": framer.MAX_ADU,
            "max_counted": framer.MAX_COUNTED,  # (a length rule's frame over max_adu: a good CRC only, warned)
            "min_adu": framer.MIN_ADU,
            "max_slave": framer.MAX_SLAVE,
            "noise_item_max": streambuf.NOISE_ITEM_MAX,
            "glitch_skip": framer.GLITCH_SKIP,
            "glitch_run": streambuf.GLITCH_RUN,
            "glitchy_after": streambuf.GLITCHY_AFTER,
            "glitch_score_max": streambuf.GLITCH_SCORE_MAX,
            "glitch_bytes": streambuf.GLITCH_BYTES,
            "glitch_addresses": framer.GLITCH_ADDRESSES,
            # (a repetition's period is found by the last REPEAT_PROBE bytes; the window a decision reads)
            "repeat_probe": framer.REPEAT_PROBE,
            "repeat_window": framer.REPEAT_WINDOW,
            "cut_answer": CUT_ANSWER,
            "silence_cuts": SILENCE_CUTS,  # (live closes bytes at a silence, and a file says the same: rules.py)
        },
        "ascii": {
            "max_ascii": ascii_mode.MAX_ASCII,
            "min_binary": ascii_mode.MIN_BINARY,
            "share": ascii_mode.ASCII_SHARE,
            "hex_digits": {digit: int(chr(digit), 16) for digit in sorted(ascii_mode._HEX_DIGITS)},  # (their values)
            "alphabet": ascii_mode._ALPHABET,  # (the characters of ASCII mode: hex digits, ':', CR, LF)
            "delimiters": [ascii_mode.COLON, ascii_mode.CR, ascii_mode.LF],
            "mode_sample": reader.MODE_SAMPLE,
            # FC8 sub-functions whose data word is a character then 00: the line end they set (framing/ascii.py).
            "sets_delimiter": ascii_framer.DELIMITER_SUBFUNCTIONS,
        },
        "map_format": {
            "columns": frozenset(maps.COLUMNS),
            "required": list(maps.REQUIRED),
            "reference": maps.REFERENCE,  # (the column a map written in PLC references has for `address`)
            "reference_bases": list(maps.REFERENCE_BASES),
            # (the codes whose registers are input registers, a reference map's 3X rows: profiles.register_table)
            "input_functions": frozenset(
                code for code in range(256) if profiles.TABLES[code] == profiles.INPUT_REGISTERS),
            "max_bytes": maps.MAX_MAP_BYTES,
            "scale_min": maps.SCALE_MIN,
            "scale_max": maps.SCALE_MAX,
            "scale_unknown": maps.SCALE_UNKNOWN,
            "types": maps.TYPES,
            "orders": frozenset(maps.ORDERS),
            "order_list": list(maps.ORDERS),
            "default_types": list(maps.DEFAULT_TYPES),
            "signed_types": maps.SIGNED_TYPES,
            "pairs": {column: list(bounds) for column, bounds in maps.PAIRS.items()},
            "separators": list(maps.SEPARATORS),
            "access": maps.ACCESS,
            "read_only": access.READ_ONLY,  # (the access of a parameter no write changes: a warning's text)
            "references_judged": maps_refs.JUDGED,  # (a slave's frames with registers the reference check judges)
            "messages": _messages(maps.MESSAGES),
        },
        # What printable() escapes: the code points str.isprintable() refuses (codegen/printable_table.py).
        "nonprintable": printable_table.lua_data(),
        # CRC-16/MODBUS's one-byte table (protocol/crc.py): the plugin's CRC steps are built from it.
        "crc_table": crc._TABLE,
        "not_broadcast": SPEC.not_broadcast,
        "read_only_exception": SPEC.read_only_exception,
        # The catalogue's texts that take no parameters, filled in (protocol/rules.py text()): noise reasons,
        # the framers' warnings.
        "plain_texts": {key: rules.text(key) for key in rules.TEXTS if not rules.params(key)},
        # A register's bits without a name in its map row, by bit, as maps.interpret names them.
        "bit_names": {bit: rules.text("bit_unnamed", bit=bit) for bit in range(16)},
        # [pairing]: data bytes an answer echoes by function, values of a request's first data word no answer follows
        "pairing": {"echo": SPEC.echo, "never_answered": SPEC.never_answered, "same_shape": pairing.SAME_SHAPE,
                    # (Listen Only Mode: FC8, its sub-functions that enter and leave it; a cut answer's note)
                    "listen_only": [pairing.DIAGNOSTICS, pairing.LISTEN_ONLY, pairing.RESTART],
                    "answer_in_part": rules_lua.lua_format(pairing.ANSWER_IN_PART)},
        "user_defined": SPEC.user_defined,
        "protocol": protocol_tables(),
        "lanes": lanes_lua.lanes_data(),  # (what the quick lanes take of the protocol table: codegen/lanes_lua.py)
        # The display's texts: a provisional frame's mark in the summary and its line in -V.
        "render": {"provisional": summary.PROVISIONAL, "provisional_line": detail.PROVISIONAL_LINE.strip()},
        "timing": timing_lua.timing_data(),  # the line's timing (framing/timing.py: codegen/timing_lua.py)
        "fields": fields_lua.plugin_fields(),  # the ProtoFields, from data/fields.toml (codegen/fields_lua.py)
    }
    data.update(profiles_lua.profile_data())
    return data


def _messages(templates: dict[str, str]) -> dict[str, Any]:
    """A catalogue of Python templates as the plugin fills them in: a `string.format` pattern, the
    parameters in order, and those Python gives as their repr (`{name!r}`)."""
    import string

    from dissector.codegen import rules_lua  # (it imports this module)

    out = {}
    for key, template in templates.items():
        fields = [(name, conversion) for _, name, _, conversion in string.Formatter().parse(template) if name]
        out[key] = {"format": rules_lua.lua_format(template), "params": [name for name, _ in fields],
                    "repr": {name: True for name, conversion in fields if conversion == "r"}}
    return out


def _length_rule(rule: table.LengthRule) -> list[Any]:
    if isinstance(rule, table.Fixed):
        return ["fixed", rule.length]
    if isinstance(rule, table.Counted):
        return ["counted", rule.position, rule.extra, rule.width]
    if isinstance(rule, table.Scan):
        return ["scan", rule.minimum]
    if isinstance(rule, table.Select):
        return ["select", rule.position, rule.width, rule.value, _length_rule(rule.chosen), _length_rule(rule.otherwise)]
    return [rule.name, rule.position, rule.start]


def _by_quantity(layout: table.Layout) -> list[list[Any]]:
    """A request's length by its quantity (table.ByQuantity, framing/rules.py quantity_rule), as the rule
    `by_quantity` with the fields of accel/_tables.h's RULE_BY_QUANTITY: the quantity's position, extra,
    unit, and the byte count's position and extra; none: an empty list."""
    alternative, counted = layout.by_quantity, layout.length
    if alternative is None or not isinstance(counted, table.Counted):
        return []
    return [["by_quantity", alternative.position, alternative.extra, alternative.unit, counted.position, counted.extra]]


def protocol_tables() -> dict[str, Any]:
    """The protocol table as the plugin uses it: per code, the length rules (request, response, by
    quantity); the read classes. (Per direction each code's layout, handler and the limit it checks
    come with the rule data, codegen/rules_lua.py's by_code.)"""
    return {
        # (the codes without a layout, found by a CRC scan: framing/rules.py RULES)
        "rules": {
            code: [_length_rule(request.length), _length_rule(response.length), *_by_quantity(request)]
            for code, request, response in table.known_layouts()
        },
        "exception_rule": _length_rule(table.EXCEPTION_LAYOUT.length),
        # A counted layout's length when its count is 0, by kind and code (framing/rtu.py _COUNTS_NOTHING).
        "counts_nothing": {
            str(kind): {code: length for (code, of), length in sorted(framer._COUNTS_NOTHING.items())
                        if of is kind}
            for kind in (Kind.REQUEST, Kind.RESPONSE)
        },
        "reads": table.register_reads(),
        "plain_reads": table.plain_register_reads(),
        # The reads whose quantity limits make a request plausible on its own (framing/evidence.py).
        "plausible_reads": {code: list(limits) for code, limits in evidence.READ_LIMITS.items()},
        # The requests whose coil value makes them plausible, and the values it may have (evidence.py).
        "coil_requests": evidence.COIL_REQUESTS,
        "coil_values": frozenset(evidence.COIL_VALUES),
    }


def render_data() -> str:
    """The generated data between the markers: `local DATA = {...}`, then the rule tables of
    data/modbus.toml (codegen/rules_lua.py: `local RULES = {...}`, what the modules' lifter, parsers and
    texts interpret), which the modules reach as DATA.rules."""
    from dissector.codegen import decode_lua, display_lua, rules_lua  # (they import this module's lua_literal)

    data = plugin_data()
    # (in a block of its own: the modules below are closures of this chunk, a `local RULES` in their
    # scope would hide the length rules the framing modules share under that name)
    rules = ["do", rules_lua.render_rules().rstrip("\n"), "DATA.rules = RULES", "end"]
    # (DATA.pack: how a record's frames are packed, codegen/pack_lua.py; DATA.parsers and DATA.lifters: the
    # layouts' readers and the lifting rules' handlers, written out from the rule data, codegen/decode_lua.py;
    # DATA.info_forms, .field_places, .bit_windows: the Info texts of describe.TEXT_FORMS's forms and the display's
    # tables, codegen/display_lua.py)
    lines = [BEGIN, "local DATA = " + lua_literal(data), *rules, *pack_lua.render_pack(), *decode_lua.render_decoders(),
             *display_lua.render_display(), END]
    return "\n".join(lines) + "\n"


def module_names(main_text: str) -> list[str]:
    """The modules main.lua loads, in order: its PURE list, then its WIRESHARK list."""
    names = []
    for list_name in ("PURE", "WIRESHARK"):
        match = re.search(r"^local %s = \{([^}]*)\}" % list_name, main_text, re.M)
        if match is None:
            raise GenerateError(f"{MAIN} must list its modules as `local {list_name} = {{ \"name\", ... }}`")
        names += re.findall(r'"([a-z_][a-z0-9_]*)"', match.group(1))
    return names


# The globals of Lua and of Wireshark's Lua API a module may use; the generator binds those it uses as
# locals (a global read through the shared table of names costs a metatable look-up a use). Globals the
# plugin itself changes while it runs (`config`, `state`, ...) are never bound: they are read as they are.
LUA_GLOBALS = frozenset("""
    assert bit bit32 collectgarbage error getmetatable io ipairs load math next os package pairs pcall print
    rawget rawset select setmetatable string table tonumber tostring type xpcall
    ByteArray DESEGMENT_ONE_MORE_SEGMENT DissectorTable NSTime Pref Proto ProtoExpert ProtoField base expert
    frametype wtap
""".split())
# How every module sees the names it shares (main.lua's vw3.env: DATA, the modules' exports, then the globals),
# written by the generator at its head, after its `-- Assembled into` line (ASSEMBLED), so that no module
# restates it; the locals the module uses are bound after them (module_bindings).
ENV_LINES = ('local M = require("vw3.env")', "local _ENV = M -- (the globals and the other modules' exports; "
             "the generator binds those used here as locals)")
ASSEMBLED = "-- Assembled into lua/vw3.lua by python3 -m dissector.codegen"
_STRING_OR_COMMENT = re.compile(r"--\[(=*)\[.*?\]\1\]|--[^\n]*|\[(=*)\[.*?\]\2\]|\"(?:\\.|[^\"\\\n])*\"|'(?:\\.|[^'\\\n])*'",
                                re.S)
# (a number, `..`, or a field `.name`/`:name` is matched whole, so that only names used as names remain)
_TOKEN = re.compile(r"\d[\w.]*|\.\.+|[.:]\s*[A-Za-z_]\w*|[A-Za-z_]\w*\s*=(?!=)|([A-Za-z_]\w*)")


def _code_only(text: str) -> str:
    """A module's text without its comments and strings (what it names as code)."""
    return _STRING_OR_COMMENT.sub(" ", text)


def _declared(code: str) -> tuple[set[str], set[str]]:
    """The names a module's code (no comments, no strings) declares: at its top level (`local function
    NAME`, `local NAME, ... =` at a line's start), and anywhere (locals, parameters, loop variables)."""
    top = set(re.findall(r"^local function (\w+)", code, re.M))
    for names in re.findall(r"^local ([\w, ]+?)(?: =|$)", code, re.M):
        top.update(part.strip() for part in names.split(","))
    anywhere = set()
    for names in re.findall(r"\bfunction\s*[\w.:]*\s*\(([^)]*)\)|\blocal\s+(?!function\b)([\w, ]+)|\bfor\s+([\w, ]+?)\s*(?:=|in\b)", code):
        anywhere.update(part.strip() for group in names for part in group.split(","))
    return top - {"M", "_ENV"}, anywhere


def _uses(code: str) -> set[str]:
    """The names a module's code names as names (a name followed by `=` is assigned or a table
    constructor's key: no use)."""
    return set(_TOKEN.findall(code + " ")) - {""}


def own_exports(text: str) -> list[str]:
    """The `M.NAME` a module's own `M.a, M.b = a, b` lines set: a name only the tests use, a table it builds
    (refused: a line that exports a name under another, `M.a, M.b = b, a`)."""
    names = []
    for line in text.split("\n"):
        if line.startswith("M.") and " = " in line:
            targets, values = line.split(" = ", 1)
            exported = re.findall(r"M\.(\w+)", targets)
            if re.fullmatch(r"\w+(, \w+)*", values) and values.split(", ") != exported:
                raise GenerateError(f"an export line does not export each name as itself: {line}")
            names += exported
    return names


def free_names(text: str) -> set[str]:
    """The names a module's code names without declaring them anywhere (what it takes from elsewhere)."""
    code = _code_only(text)
    return _uses(code) - _declared(code)[1]


def module_exports(text: str, later_free: set[str]) -> list[str]:
    """The names a module shares, sorted: its own export lines' (own_exports), and its top-level locals
    that a later module names without declaring them anywhere (`later_free`: the union of their
    free_names), but for one that would hide from them a global of Lua's or Wireshark's."""
    top, _ = _declared(_code_only(text))
    return sorted(((top & later_free) - LUA_GLOBALS) | set(own_exports(text)))


def export_lines(text: str, names: list[str]) -> list[str]:
    """The lines, at the module's end, that put in the shared table of names those of `names` its own lines
    do not: `M.a, M.b = a, b`, as many names a line as fit in 116 characters."""
    lines: list[str] = []
    own = set(own_exports(text))
    for name in (name for name in names if name not in own):
        if lines:
            targets, values = lines[-1].split(" = ")
            longer = f"{targets}, M.{name} = {values}, {name}"
            if len(longer) <= 116:
                lines[-1] = longer
                continue
        lines.append(f"M.{name} = {name}")
    return lines


def module_bindings(name: str, text: str, available: set[str]) -> list[str]:
    """The lines that bind as locals what module `name` uses of the globals and of the earlier modules'
    exports (`available`), in sorted order, after its ENV_LINES. Refused: a module that
    assigns such a name (it would assign the local, not the shared name)."""
    code = _code_only(text)
    # (a global the module also names as a local or a parameter somewhere, as `base`, is left unbound: the
    # binding would stand for either)
    declared, anywhere = _declared(code)
    used = _uses(code) & (available | (LUA_GLOBALS - anywhere))
    used -= declared | {"M", "_ENV"}
    depth = 0  # (open brackets at a line's start: a `key = value` inside a table constructor is no assignment)
    for line in code.split("\n"):
        if depth == 0:
            target = re.match(r"\s*((?:[\w.]+\s*,\s*)*[\w.]+)\s*=(?!=)", line)
            for bound in set(re.split(r"\s*,\s*", target.group(1)) if target else ()) & used:
                raise GenerateError(f"lua/src/{name}.lua assigns {bound}, a name the generator binds as a local")
        depth += sum(line.count(char) for char in "({[") - sum(line.count(char) for char in ")}]")
    lines = []
    names = sorted(used)
    while names:
        take = 1
        while take < len(names) and len(", ".join(names[:take + 1])) * 2 + 10 <= 116:
            take += 1
        part, names = names[:take], names[take:]
        lines.append(f"local {', '.join(part)} = {', '.join(part)}")
    return lines


def render_plugin(src: Path = SRC) -> str:
    """lua/vw3.lua as the modules in `src` and the package's data assemble it."""
    try:
        main_text = (src / MAIN).read_text(encoding="utf-8")
    except OSError as error:
        raise GenerateError(f"{src / MAIN}: {error.strerror or error}") from None
    lines = main_text.split("\n")
    cut = 0
    while cut < len(lines) and lines[cut].startswith("--"):
        cut += 1
    header, body = "\n".join(lines[:cut]), "\n".join(lines[cut:]).lstrip("\n")
    parts = [header, "", render_data()]
    available = {"DATA"}  # (main.lua puts it in the shared table of names, vw3.env)
    names = module_names(main_text)
    texts = []
    for name in names:
        path = src / f"{name}.lua"
        try:
            texts.append(path.read_text(encoding="utf-8"))
        except OSError as error:
            raise GenerateError(f"{path}: {error.strerror or error} (listed in {MAIN})") from None
    # (what the modules after each one take from elsewhere: each module's text read once, from the last)
    later_free: list[set[str]] = [set()]
    for text in reversed(texts[1:]):
        later_free.append(later_free[-1] | free_names(text))
    later_free.reverse()
    for index, (name, text) in enumerate(zip(names, texts)):
        lines = text.rstrip("\n").split("\n")
        at = next((number for number, line in enumerate(lines) if not line.startswith("--")), len(lines))
        at = next((number for number, line in enumerate(lines[:at]) if line.startswith(ASSEMBLED)), None)
        if at is None:
            raise GenerateError(f"{src / name}.lua: no `{ASSEMBLED}` line in its head comment (after which the "
                                "generator writes how it sees the shared names and binds what it uses)")
        own = [line for line in lines if line.split(" --")[0] in [env.split(" --")[0] for env in ENV_LINES]]
        if own:
            raise GenerateError(f"{src / name}.lua: its own `{own[0]}`: the generator writes how a module sees the "
                                "shared names")
        lines[at + 1:at + 1] = [*ENV_LINES, *module_bindings(name, text, available)]
        exports = module_exports(text, later_free[index])
        lines += export_lines(text, exports)
        available.update(exports)
        parts.append(MODULE_LINE.format(name=name))
        parts.append(f'package.preload["vw3.{name}"] = function(...)')
        parts.append("\n".join(lines))
        parts.append("end")
        parts.append("")
    parts.append(body.rstrip("\n"))
    return "\n".join(parts) + "\n"


def render_block() -> str:
    """The whole plugin as it must be (python3 -m dissector.codegen compares it with current_block())."""
    return render_plugin()


def current_block(path: Path = PLUGIN) -> str:
    """The plugin as it is."""
    return path.read_text(encoding="utf-8")


def write_block(path: Path = PLUGIN, src: Path = SRC) -> bool:
    """Write the assembly; True when the file changed."""
    new = render_plugin(src)
    old = path.read_text(encoding="utf-8") if path.exists() else None
    if new == old:
        return False
    path.write_text(new, encoding="utf-8")
    return True


def stale(path: Path = PLUGIN, src: Path = SRC) -> bool:
    """lua/vw3.lua is not the assembly of `src` and the package's data."""
    return current_block(path) != render_plugin(src)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m dissector.codegen.lua", description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 when lua/vw3.lua is stale")
    parser.add_argument("--plugin", type=Path, default=PLUGIN, help="plugin file (default: lua/vw3.lua)")
    parser.add_argument("--src", type=Path, default=SRC, help="its modules (default: lua/src)")
    args = parser.parse_args(argv)
    try:
        if args.check:
            if stale(args.plugin, args.src):
                print(f"{args.plugin}: stale, not the assembly of {args.src} and the package's data; "
                      "run python3 -m dissector.codegen", file=sys.stderr)
                return 1
            return 0
        changed = write_block(args.plugin, args.src)
    except (OSError, GenerateError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    print(f"{args.plugin}: {'updated' if changed else 'up to date'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
