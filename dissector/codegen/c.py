"""Generate dissector/accel/_tables.h, the per-function-code tables of the compiled summary path.

Everything _summary.c keeps per function code comes from the protocol table (protocol/table.py):
which codes it shows, their length rules in both directions, where a request's start, quantity and
written registers are (field offsets of the Construct grammars, counted from the frame's first
byte) and the spec limits it checks them against. The header is checked in, so that a build needs
no Python step; `python3 -m dissector.codegen --check` fails when it is stale.
"""
from __future__ import annotations

from pathlib import Path

from dissector.errors import GenerateError
from dissector.protocol import table
from dissector.protocol.table import Compiled, Counted, Fixed, Layout, Special

HEADER = Path(__file__).resolve().parents[1] / "accel" / "_tables.h"
_ADU_HEAD = 2  # slave and function code before the grammar's data
# Special length rules the engine implements (framing/rtu.py's functions of the same names).
_SPECIAL_RULES = {"mei_request": 1, "mei_response": 2, "diagnostics": 3, "scan": 4}


def _rule(layout: Layout, code: int) -> str:
    rule = layout.length
    if isinstance(rule, Fixed):
        return f"{{{rule.length}, 0, 0, 0, 0}}"
    if isinstance(rule, Counted) and rule.width in (1, 2):
        return f"{{0, {rule.position}, {rule.extra}, {rule.width}, 0}}"
    if isinstance(rule, Special) and rule.name in _SPECIAL_RULES:
        return f"{{0, 0, 0, 0, {_SPECIAL_RULES[rule.name]}}}"
    raise GenerateError(f"function {code}: the compiled path handles fixed and counted lengths only, not {rule}")


def _offset(layout: Layout, field: str | None, code: int) -> int:
    if field is None:
        return 0
    try:
        return _ADU_HEAD + table.field_offset(layout.grammar, field)
    except Exception as error:
        raise GenerateError(f"function {code}: field {field!r} of {layout.name}: {error}") from None


def _request_layout(code: int, layout: Layout, compiled: Compiled, limits: tuple[str, ...]) -> str:
    writes = compiled.writes
    values = [
        _offset(layout, compiled.start, code),
        _offset(layout, compiled.quantity, code),
        limits.index(compiled.limit) if compiled.limit else -1,
        int(compiled.span),
    ]
    coils = compiled.coils
    values += [
        _offset(layout, compiled.coil, code),
        _offset(layout, coils.status if coils else None, code),
        _offset(layout, coils.count if coils else None, code),
    ]
    if writes is None:
        values += [0, 0, 0, -1, 0]
    else:
        values += [
            _offset(layout, writes.values, code),
            # 0: the request's own start and quantity (then no separate write quantity to check)
            _offset(layout, None if writes.start == compiled.start else writes.start, code),
            _offset(layout, None if writes.quantity == compiled.quantity else writes.quantity, code),
            limits.index(writes.limit) if writes.limit else -1,
            _offset(layout, writes.count, code),
        ]
    values.append(int(compiled.texts))
    return "{" + ", ".join(map(str, values)) + "}"


def _known_rules() -> tuple[list[int], list[str], list[str]]:
    """The framer's rules for every code it knows (framing/rtu.py RULES: the table's codes, then the
    codes found by a CRC scan): slots by code, request rules, response rules."""
    slots = [-1] * 256
    requests: list[str] = []
    responses: list[str] = []
    codes = [(entry.code, entry.request, entry.response) for entry in table.FUNCTIONS]
    scan = table.RAW_LAYOUT
    codes += [(code, scan, scan) for code in sorted(table.OTHER_FUNCTIONS) if code not in table.TABLE]
    for code, request, response in codes:
        slots[code] = len(requests)
        requests.append(_rule(request, code))
        responses.append(_rule(response, code))
    return slots, requests, responses


def _quantity_rules() -> list[str]:
    """Per known slot (as _known_rules): a request's length by its quantity (table.ByQuantity) as
    {position, extra, unit, the byte count's position, its extra}; position 0: none."""
    rules = []
    for entry in table.FUNCTIONS:
        alternative, counted = entry.request.by_quantity, entry.request.length
        if alternative is None or not isinstance(counted, Counted):
            rules.append("{0, 0, 0, 0, 0}")
        else:
            rules.append(
                f"{{{alternative.position}, {alternative.extra}, {alternative.unit}, {counted.position}, {counted.extra}}}"
            )
    others = [code for code in sorted(table.OTHER_FUNCTIONS) if code not in table.TABLE]
    return rules + ["{0, 0, 0, 0, 0}"] * len(others)


def _slot_rows(slots: list[int]) -> list[str]:
    return [", ".join(f"{value:2d}" for value in slots[row : row + 16]) for row in range(0, 256, 16)]


def render_header() -> str:
    entries = [entry for entry in table.FUNCTIONS if entry.compiled is not None]
    known_slots, known_requests, known_responses = _known_rules()
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
        "/* Spec limits (data/modbus.toml), in the order of the engine's `limits` argument. */",
        f"#define LIMIT_COUNT {len(limits)}",
        *(f"#define LIMIT_{name.upper()} {index}" for index, name in enumerate(limits)),
        "",
        "/* Frame length, CRC included: `fixed` when not 0, else `extra` + the count at `position` (`width`",
        " * 1: a byte, 2: a big-endian word), else the special rule (1: mei_request, 2: mei_response,",
        " * 3: diagnostics, 4: scan, framing/rtu.py's functions of those names). */",
        "typedef struct { int fixed, position, extra, width, special; } LengthRule;",
        "static const LengthRule request_rule[HANDLED] = {"
        + ", ".join(_rule(entry.request, entry.code) for entry in entries) + "};",
        "static const LengthRule response_rule[HANDLED] = {"
        + ", ".join(_rule(entry.response, entry.code) for entry in entries) + "};",
        "",
        "/* The framer's rules for every code it knows (framing/rtu.py RULES), as the check that an intact",
        " * frame follows a frame found by a CRC scan needs them; -1: no frame starts with this code. */",
        f"#define KNOWN {len(known_requests)}",
        "static const signed char known_slot[256] = {",
        *(f"    {row}," for row in _slot_rows(known_slots)),
        "};",
        "static const LengthRule known_request_rule[KNOWN] = {" + ", ".join(known_requests) + "};",
        "static const LengthRule known_response_rule[KNOWN] = {" + ", ".join(known_responses) + "};",
        "/* A request's length by its quantity when its byte count disagrees (framing/rtu.py BY_QUANTITY):",
        " * {quantity's position, extra, bytes an item (0: coils, 8 a byte), byte count's position, extra}. */",
        "typedef struct { int position, extra, unit, count_position, count_extra; } QuantityRule;",
        "static const QuantityRule known_quantity_rule[KNOWN] = {" + ", ".join(_quantity_rules()) + "};",
        "",
        "/* Where a request's fields are, as offsets from the frame's first byte (0: absent). The quantity",
        " * defaults to one register; the written registers' start and quantity default to the request's. */",
        "typedef struct {",
        "    int start_at, quantity_at, limit, span; /* limit: LIMIT_* or -1; span: start + quantity <= 65536 */",
        "    int coil_at, coils_at, coils_count_at; /* FC5's ON/OFF value; FC15's packed coils, ceil(quantity / 8) */",
        "    int values_at, write_start_at, write_quantity_at, write_limit, count_at; /* count: 2 x quantity */",
        "    int texts; /* 1: the texts come from the Python stages (table.Compiled.texts) */",
        "} RequestLayout;",
        "static const RequestLayout request_layout[HANDLED] = {",
        *(
            f"    {_request_layout(entry.code, entry.request, entry.compiled, limits)}, /* {entry.code} */"
            for entry in entries
            if entry.compiled is not None
        ),
        "};",
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
