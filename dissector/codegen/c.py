"""Generate dissector/accel/_tables.h, the per-function-code tables of the compiled summary path.

Everything _summary.c keeps per function code comes from the protocol table (protocol/table.py):
which codes it shows, their length rules in both directions, how a frame is lifted in each direction
(field offsets of the Construct grammars, counted from the frame's first byte: codegen/c_rules.py)
and the spec limits it checks them against. The header is checked in, so that a build needs
no Python step; `python3 -m dissector.codegen --check` fails when it is stale.
"""
from __future__ import annotations

from pathlib import Path

from dissector.errors import GenerateError
from dissector.protocol import table
from dissector.protocol.spec import SPEC
from dissector.accel.timedpath import CLOCKS, PACKET_DELTAS
from dissector.codegen import c_rules, c_stats
from dissector.protocol.table import Counted, Fixed, Layout, LengthRule, Scan, Select, Special

HEADER = Path(__file__).resolve().parents[1] / "accel" / "_tables.h"
# The kinds of length rule the engine interprets (rule_length in _summary.c), LengthRule.special: a count
# (or a fixed length), then framing/rules.py length_rule's others and its quantity_rule ("by_quantity").
_KINDS = ("counted", "scan", "select", "by_quantity", "mei_objects")
_FIELDS = ("fixed", "position", "extra", "width", "special", "unit", "count_at", "count_extra")
_SELECT_FIELDS = ("value", "chosen", "otherwise")  # (written on a select's row only: zero elsewhere)


def _row(**values: int) -> str:
    names = _FIELDS + _SELECT_FIELDS if values.get("special") == _KINDS.index("select") else _FIELDS
    return "{" + ", ".join(str(values.get(name, 0)) for name in names) + "}"


def _rule(rule: LengthRule, code: int, selected: list[str]) -> str:
    """A length rule as a LengthRule; a select's two rules appended to `selected` (selected_rule)."""
    if isinstance(rule, Fixed):
        return _row(fixed=rule.length)
    if isinstance(rule, Counted) and rule.width in (1, 2):
        return _row(position=rule.position, extra=rule.extra, width=rule.width)
    if isinstance(rule, Scan):
        return _row(extra=rule.minimum, special=_KINDS.index("scan"))
    if isinstance(rule, Select) and rule.width in (1, 2):
        selected += [_rule(rule.chosen, code, selected), _rule(rule.otherwise, code, selected)]
        return _row(position=rule.position, width=rule.width, special=_KINDS.index("select"), value=rule.value,
                    chosen=len(selected) - 2, otherwise=len(selected) - 1)
    if isinstance(rule, Special) and rule.name in _KINDS:
        return _row(position=rule.position, extra=rule.start, width=1, special=_KINDS.index(rule.name))
    raise GenerateError(f"function {code}: the compiled path has no length rule {rule}")


def _by_quantity(layout: Layout) -> str:
    """A request's length by its quantity where its byte count disagrees (table.ByQuantity,
    framing/rules.py quantity_rule), as a LengthRule; none: all zero."""
    alternative, counted = layout.by_quantity, layout.length
    if alternative is None or not isinstance(counted, Counted):
        return _row()
    return _row(position=alternative.position, extra=alternative.extra, width=2, special=_KINDS.index("by_quantity"),
                unit=alternative.unit, count_at=counted.position, count_extra=counted.extra)


def _known_rules() -> tuple[list[int], list[str], list[str]]:
    """The framer's interpretations for every code it knows (framing/rules.py REQUEST_FIRST: the table's
    codes, then the codes found by a CRC scan): slots by code, per slot {request, response, by quantity}, and
    the rules their selects pick."""
    slots = [-1] * 256
    rows: list[str] = []
    selected: list[str] = []
    for code, request, response in table.known_layouts():
        slots[code] = len(rows)
        rules = (_rule(request.length, code, selected), _rule(response.length, code, selected), _by_quantity(request))
        rows.append(f"{{{', '.join(rules)}}}, /* {code} */")
    return slots, rows, selected


def _slot_rows(slots: list[int]) -> list[str]:
    return [", ".join(f"{value:2d}" for value in slots[row : row + 16]) for row in range(0, 256, 16)]


def _clocks() -> list[str]:
    return [
        "/* The time column -t r's code (accel/timedpath.py CLOCKS; the others' are deltas), and -t d's counted from",
        " * the packet before each item's first (PACKET_DELTAS: a network or several-interface capture's), for _timeline.h. */",
        f"#define CLOCK_RELATIVE {CLOCKS['r']}",
        f"#define CLOCK_PACKETS {PACKET_DELTAS}",
    ]


def _quiet_word(subfunction: int) -> int:
    """diagnostic_quiet's entry: the one word an FC8 request of this sub-function may carry without a note or
    a warning ([diagnostic_data]'s with no meaning to say), -1 any, -2 none."""
    rule = SPEC.diagnostic_data.get(subfunction)
    if rule is None:
        return -1
    quiet = [word for word, meaning in (rule.data or {}).items() if not meaning]
    if len(quiet) > 1:
        raise GenerateError(f"[diagnostic_data] {subfunction}: the engine keeps one quiet word, not {quiet}")
    return quiet[0] if quiet else -2


def render_header() -> str:
    entries = [entry for entry in table.FUNCTIONS if entry.compiled is not None]
    known_slots, known_rows, selected = _known_rules()
    limits = table.compiled_limits()
    slots = [-1] * 256
    for index, entry in enumerate(entries):
        slots[entry.code] = index
    slot_rows = _slot_rows(slots)
    lines = [
        "/* GENERATED by python3 -m dissector.codegen from dissector/protocol/table.py: do not edit by hand.",
        " * The compiled summary path's knowledge per function code (see dissector/codegen/c.py). */",
        "#ifndef VW3_TABLES_H",
        "#define VW3_TABLES_H",
        "",
        f"#define HANDLED {len(entries)}",
        f"static const int handled_codes[HANDLED] = {{{', '.join(str(entry.code) for entry in entries)}}};",
        "",
        "/* Index of a function code in the tables below; -1: not shown here (handed over). */",
        "static const signed char handled_slot[256] = {",
        *(f"    {row}," for row in slot_rows),
        "};",
        "",
        "static int handled_index(int function) {",
        "    return function >= 0 && function < 256 ? handled_slot[function] : -1;",
        "}",
        "",
        "/* The spec limits the lifting rules check (data/modbus.toml [limits]): {low, high} by LIMIT_*. */",
        f"#define LIMIT_COUNT {len(limits)}",
        *(f"#define LIMIT_{name.upper()} {index}" for index, name in enumerate(limits)),
        "static const long spec_limits[LIMIT_COUNT][2] = {"
        + ", ".join(f"{{{int(SPEC.limits[name][0])}, {int(SPEC.limits[name][1])}}}" for name in limits) + "};",
        "",
        "/* The spec's FC8 sub-function names by number (data/modbus.toml [diagnostics]); NULL: none. */",
        f"#define SUBFUNCTIONS {max(SPEC.diagnostics) + 1}",
        "static const char *const subfunction_names[SUBFUNCTIONS] = {",
        *(f"    {c_rules.c_string(SPEC.diagnostics.get(number))}," for number in range(max(SPEC.diagnostics) + 1)),
        "};",
        "",
        "/* An FC8 request's data word that draws neither a note nor a warning, by sub-function (data/modbus.toml",
        " * [diagnostic_data], decode/fields.py _diagnostic_data): DIAG_ANY any (the sub-function is not listed),",
        " * DIAG_NONE none (a character: always a note). */",
        "#define DIAG_ANY -1",
        "#define DIAG_NONE -2",
        "static const long diagnostic_quiet[SUBFUNCTIONS] = {"
        + ", ".join(str(_quiet_word(number)) for number in range(max(SPEC.diagnostics) + 1)) + "};",
        "",
        "/* 1: an FC8 answer of this sub-function repeats its request's data (data/modbus.toml [diagnostic_answers],",
        " * decode/fields.py _diagnostics), one that differs draws a warning. */",
        "static const unsigned char diagnostic_echo[SUBFUNCTIONS] = {"
        + ", ".join(str(int(number in SPEC.diagnostic_echoes)) for number in range(max(SPEC.diagnostics) + 1)) + "};",
        "",
        "/* Pairing (data/modbus.toml [pairing]): {function, data bytes an answer echoes of its request}, and",
        " * {function, value of a request's first data word} that no answer follows. */",
        f"#define ECHOES {len(SPEC.echo)}",
        "static const unsigned char answer_echo[ECHOES][2] = {"
        + ", ".join(f"{{{code}, {count}}}" for code, count in sorted(SPEC.echo.items())) + "};",
        f"#define NEVER_ANSWERED {sum(map(len, SPEC.never_answered.values()))}",
        "static const unsigned short never_answered[NEVER_ANSWERED][2] = {"
        + ", ".join(f"{{{code}, {value}}}" for code, values in sorted(SPEC.never_answered.items())
                    for value in sorted(values)) + "};",
        "",
        "/* Frame length, CRC included: `fixed` when not 0, else by `special`: RULE_SCAN, a CRC scan from `extra`",
        " * bytes (table.Scan); the others read the byte (`width` 1) or big-endian word (2) at `position`:",
        " * RULE_COUNTED `extra` + it; RULE_SELECT the rule selected_rule[`chosen`] where it is `value`, else",
        " * selected_rule[`otherwise`] (table.Select); RULE_BY_QUANTITY, framing/rules.py quantity_rule: `extra` + it",
        " * (a quantity) x `unit` bytes (0: bits, ceil(q / 8)), none where that is the byte count's length,",
        " * count_extra + the byte at count_at; RULE_MEI_OBJECTS, rules.py _mei_objects: it objects (an id, a",
        " * length byte, that many bytes) from `extra`, else (no valid CRC where they end) a CRC scan from `extra` + 2. */",
        f"enum {{ {', '.join(f'RULE_{kind.upper()}' for kind in _KINDS)} }};",
        f"typedef struct {{ int {', '.join(_FIELDS + _SELECT_FIELDS)}; }} LengthRule;",
        "static const LengthRule selected_rule[] = {",
        *(f"    {row}," for row in selected),
        "};",
        "",
        "/* The framer's interpretations of a frame start for every code it knows (framing/rules.py",
        " * REQUEST_FIRST): its request's and its response's length rules, and a request's by its quantity",
        " * (special 0: none); -1: no frame starts with this code. */",
        f"#define KNOWN {len(known_rows)}",
        "static const signed char known_slot[256] = {",
        *(f"    {row}," for row in _slot_rows(known_slots)),
        "};",
        "enum { LAYOUT_REQUEST, LAYOUT_RESPONSE, LAYOUT_BY_QUANTITY };",
        "static const LengthRule known_rule[KNOWN][3] = {",
        *(f"    {row}" for row in known_rows),
        "};",
        "",
        *c_rules.render(entries, limits),
        "",
        *c_stats.render(),
        *_clocks(),
        "",
        "#endif",
    ]
    return "\n".join(lines) + "\n"


def current_header(path: Path = HEADER) -> str:
    return path.read_text(encoding="utf-8") if path.exists() else ""


def write_header(path: Path = HEADER) -> bool:
    new = render_header()
    if current_header(path) == new:
        return False
    path.write_text(new, encoding="utf-8")
    return True
