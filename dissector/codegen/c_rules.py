"""The lifting rules (data/modbus.toml [lift], protocol/rules.py) and text forms as C tables, for the part
of accel/_tables.h the compiled engine's checks and lines interpret (accel/_summary.c request_is_quiet,
response_is_quiet, request_line, response_line, track; _stats.h).

Every offset is a field of a Construct grammar named by a rule, counted from the frame's first byte, so
the engine holds no function code: which codes write and how the write is confirmed ([confirm]), where a
request's window and values are, what an answer must repeat (its echo fields), its byte count rule,
its limit checks, and which describer of render/describe.py writes its Info column (table.Function.text,
as a FORM_* below) all come from here. A form's printed fields are named per describer in _FORMS.
"""
from __future__ import annotations

from construct import Construct, Struct

from dissector.errors import GenerateError
from dissector.framing import rules as framing_rules
from dissector.model import Kind
from dissector.protocol import table
from dissector.protocol.rules import CONFIRM, REQUEST_PREFIX, Confirm, Lift, ValueKind
from dissector.protocol.table import Data, Function, Layout
from dissector.render import describe

ADU_HEAD = 2  # slave and function code before the grammar's data

# The forms the engine writes (describe.py's describers, by direction), and the fields each prints.
FORMS = ("none", "name", "span", "bits", "values", "coil", "single", "written", "status", "counter", "diagnostics",
         "mask", "pointer", "read_write", "fifo", "python")
_PRINTS = {
    "coil": ("value",), "single": ("value",), "status": ("status",), "counter": ("status", "event_count"),
    "mask": ("address", "and_mask", "or_mask"), "pointer": ("address",), "fifo": ("fifo_count", "values"),
}


def _form(entry: Function, kind: Kind) -> str:
    """The FORM_* a describer gives in one direction (describe._DESCRIBERS by table.Function.text)."""
    request = kind is Kind.REQUEST
    bits = entry.data is Data.BITS
    forms = {
        "read": "span" if request else ("bits" if bits else "values"),
        "write_single_coil": "coil",
        "write_single_register": "single",
        "simple": "name" if request else "status",
        "comm_event_counter": "name" if request else "counter",
        "diagnostics": "diagnostics",
        "write_multiple": ("bits" if bits else "values") if request else "written",
        "mask_write": "mask",
        "read_write": "read_write" if request else "values",
        "fifo": "pointer" if request else "fifo",
    }
    if entry.compiled is not None and entry.compiled.texts:
        return "python"
    if entry.text not in forms:
        raise GenerateError(f"function {entry.code}: no compiled form for describer {entry.text!r}")
    return forms[entry.text]


def field_at(grammar: Construct, name: str | None, code: int) -> int:
    """Offset of a field from the frame's first byte; 0: no field."""
    if name is None:
        return 0
    try:
        return ADU_HEAD + table.field_offset(grammar, name)
    except Exception as error:
        raise GenerateError(f"function {code}: field {name!r}: {error}") from None


def field_width(grammar: Construct, name: str) -> int:
    for sub in grammar.subcons if isinstance(grammar, Struct) else ():
        if sub.name == name:
            return int(sub.sizeof())
    raise GenerateError(f"no fixed-size field {name!r}")


def fixed_after(grammar: Construct, name: str) -> int:
    """Bytes of the fixed-size fields right after `name` (a byte count): the least count it may give."""
    total, seen = 0, False
    for sub in grammar.subcons if isinstance(grammar, Struct) else ():
        if seen:
            try:
                total += sub.sizeof()
            except Exception:
                break
        seen = seen or sub.name == name
    return total


def _own(name: str | int | None) -> str | None:
    """A rule value naming a field of the frame itself (not the request's window, not a number)."""
    return name if isinstance(name, str) and not name.startswith(REQUEST_PREFIX) else None


def _limit(rule: Lift, field: str | None, layout: Layout, limits: tuple[str, ...]) -> int:
    for check in rule.checks:
        if field is None or check.field == field:
            name = check.limit or layout.limit
            return limits.index(name) if name else -1
    return -1


def request_layout(entry: Function, limits: tuple[str, ...]) -> list[int]:
    """RequestLayout (see the header) of a compiled code's request, from its lifting rule."""
    layout, code = entry.request, entry.code
    rule = table.lift_of(code, Kind.REQUEST)
    texts = int(entry.compiled is not None and entry.compiled.texts)
    if rule is None:
        return [0, 0, -1, 0, 0, 0, 0, 0, 0, 0, -1, 0, texts]
    grammar = layout.grammar
    at = lambda name: field_at(grammar, name, code)  # noqa: E731
    values = rule.values
    registers = values is not None and values.kind in (ValueKind.REGISTERS, ValueKind.REGISTER)
    coils = values is not None and values.kind is ValueKind.BITS
    window = rule.write_window
    row = [at(_own(rule.start)), at(_own(rule.quantity)), _limit(rule, None, layout, limits), int(rule.span)]
    row += [at(rule.coil), at(values.field) if coils else 0, at("byte_count") if coils and rule.count else 0]
    row += [
        at(values.field) if registers else 0,
        at(values.start) if registers and values.start and values.start != rule.start else 0,
        at(window[1]) if window else 0,
        _limit(rule, window[1], layout, limits) if window else -1,
        at("byte_count") if registers and rule.count else 0,
        texts,
    ]
    return row


# The Rules struct's members in order; request_at, response_at: 3 offsets; echo_at, echo_request_at: 2.
RULE_FIELDS = (
    "special", "confirm", "reads", "request_form", "response_form", "request_at", "response_at",
    "start_at", "quantity_at", "bits_at", "one",
    "count_at", "count_width", "count_rule", "count_of_at", "count_unit", "count_plus", "odd_count", "min_count",
    "coil_at", "echo_at", "echo_request_at", "values", "values_at",
    "check_at", "check_width", "check_limit", "check_above", "print_width",
)


def rules_row(entry: Function, limits: tuple[str, ...]) -> dict[str, int | list[int]]:
    """Rules (see the header) of a compiled code: both directions' forms, the answer's checks."""
    code = entry.code
    request, response = entry.request, entry.response
    forms = [_form(entry, kind) for kind in (Kind.REQUEST, Kind.RESPONSE)]
    printed = [
        ([field_at(layout.grammar, name, code) for name in _PRINTS.get(form, ())] + [0, 0, 0])[:3]
        for form, layout in zip(forms, (request, response))
    ]
    row: dict[str, int | list[int]] = {name: 0 for name in RULE_FIELDS}
    row.update(
        special=int("diagnostics" in (request.handler, response.handler)),
        confirm={None: 0, Confirm.ECHO: 1, Confirm.ANSWER: 2}[CONFIRM.get(code)],
        reads=int(code in table.register_reads()),
        request_form=FORMS.index(forms[0]), response_form=FORMS.index(forms[1]),
        request_at=printed[0], response_at=printed[1], one=1, echo_at=[0, 0], echo_request_at=[0, 0],
        check_limit=-1,
    )
    if printed[1][0]:
        row["print_width"] = field_width(response.grammar, _PRINTS[forms[1]][0])  # FC7's 8-bit, FC12's 16-bit status
    if forms[1] == "python":
        return row
    grammar = response.grammar
    at = lambda name: field_at(grammar, name, code)  # noqa: E731
    if isinstance(response.length, table.Counted):
        # A byte count shorter than the fixed fields after it is malformed (FC12's events: count - 6).
        row.update(count_at=at("byte_count"), count_width=field_width(grammar, "byte_count"),
                   min_count=fixed_after(grammar, "byte_count"))
    rule = table.lift_of(code, Kind.RESPONSE)
    if rule is None:
        return row
    values = rule.values
    count = rule.count
    echo = rule.echo.fields if rule.echo else ()
    if len(echo) > 2 or any(field_width(grammar, name) != 2 for name in echo):
        raise GenerateError(f"function {code}: the engine compares two 16-bit echo fields at most")
    if len(rule.checks) > 1:
        raise GenerateError(f"function {code}: the engine checks one field of an answer")
    row.update(
        start_at=at(_own(rule.start)), quantity_at=at(_own(rule.quantity)),
        bits_at=at(values.field) if values is not None and values.kind is ValueKind.BITS else 0,
        one=rule.quantity if isinstance(rule.quantity, int) else 1,
        odd_count=int(rule.odd_count), coil_at=at(rule.coil),
        echo_at=[at(name) for name in echo] + [0] * (2 - len(echo)),
        echo_request_at=[field_at(request.grammar, name, code) for name in echo] + [0] * (2 - len(echo)),
    )
    if count is not None:
        row.update(count_rule=1, count_of_at=at(_own(count.of)), count_unit=count.unit, count_plus=count.plus)
    if values is not None and values.kind in (ValueKind.REGISTERS, ValueKind.REGISTER):
        row.update(values=1 if values.kind is ValueKind.REGISTERS else 2, values_at=at(values.field))
    if rule.checks:
        check = rule.checks[0]
        row.update(check_at=at(check.field), check_width=field_width(grammar, check.field),
                   check_limit=_limit(rule, check.field, response, limits), check_above=int(check.test == "above"))
    return row


RULES_STRUCT = """/* How the engine reads a transaction of a compiled code, from the lifting rules (data/modbus.toml
 * [lift], [confirm]; codegen/c_rules.py). Offsets from the frame's first byte, 0: none.
 *   special: 1 diagnostics (FC8's named case); confirm: 1 by the answer's echo, 2 by a normal answer;
 *   reads: the answer's registers are values read; request_form, response_form: FORM_*, printing the
 *   fields at request_at[] / response_at[] (_PRINTS in codegen/c_rules.py);
 *   the answer's window: start_at, quantity_at (0: the request's; `one` when a constant), bits_at;
 *   its byte count at count_at (count_width bytes), at least min_count; with count_rule it must be
 *   count_plus + of x count_unit (0: bits, ceil(of / 8)), `of` at count_of_at or the request's quantity;
 *   odd_count: an even count; coil_at: ON or OFF; echo_at[k] must equal the request's echo_request_at[k];
 *   values (1 a block, 2 one register) at values_at; check_at (check_width bytes) within LIMIT check_limit
 *   (check_above: its high bound only). */
typedef struct {
    int special, confirm, reads, request_form, response_form, request_at[3], response_at[3];
    int start_at, quantity_at, bits_at, one;
    int count_at, count_width, count_rule, count_of_at, count_unit, count_plus, odd_count, min_count;
    int coil_at, echo_at[2], echo_request_at[2];
    int values, values_at, check_at, check_width, check_limit, check_above;
    int print_width; /* bytes of the answer's first printed field (FORM_STATUS: 1 or 2) */
} Rules;"""


def _braced(row: dict[str, int | list[int]]) -> str:
    def one(value: int | list[int]) -> str:
        return "{" + ", ".join(map(str, value)) + "}" if isinstance(value, list) else str(value)

    return "{" + ", ".join(one(row[name]) for name in RULE_FIELDS) + "}"


def render(entries: list[Function], limits: tuple[str, ...]) -> list[str]:
    """The header lines for the rules, the forms and the constants the engine shares with describe.py."""
    lines = [
        "/* Constants of the framer (framing/rules.py, data/modbus.toml [limits]) and of render/describe.py. */",
        f"#define MIN_ADU {framing_rules.MIN_ADU}",
        f"#define MAX_ADU {framing_rules.MAX_ADU}",
        f"#define MAX_SLAVE {framing_rules.MAX_SLAVE}",
        f"#define GLITCH_SKIP {framing_rules.GLITCH_SKIP}",
        f"#define MAX_VALUES {describe.MAX_VALUES}",
        f"#define MAX_BITS {describe.MAX_BITS}",
        f"#define MAX_FIFO_VALUES {describe.MAX_FIFO_VALUES}",
        f"#define MAX_DATA_BYTES {describe.MAX_DATA_BYTES}",
        "",
        "enum { " + ", ".join(f"FORM_{name.upper()}" for name in FORMS) + " };",
        "enum { CONFIRM_NONE, CONFIRM_ECHO, CONFIRM_ANSWER };",
        "enum { VALUES_NONE, VALUES_BLOCK, VALUES_ONE };",
        RULES_STRUCT,
        "static const Rules rules[HANDLED] = {",
        *(f"    {_braced(rules_row(entry, limits))}, /* {entry.code} */" for entry in entries),
        "};",
    ]
    return lines
