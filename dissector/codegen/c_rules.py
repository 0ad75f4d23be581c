"""The lifting rules (data/modbus.toml [lift], protocol/rules.py) and text forms as C tables, for the part
of accel/_tables.h the compiled engine's checks and lines interpret (accel/_summary.c lift_frame, the one
lifter of both directions, info_text, confirmed_writes; _stats.h).

Every offset is a field of a Construct grammar named by a rule, counted from the frame's first byte, so
the engine holds no function code: which codes write and how the write is confirmed ([confirm]), where a
request's window and values are, what an answer must repeat (its echo fields), its byte count rule,
its limit checks, and which describer of render/describe.py writes its Info column (table.Function.text,
as a FORM_* below) all come from here. What each form writes (its texts, and the steps that print the
frame's window, values and fields, named) is TEXT_FORMS below: the engine's info_text interprets it
and holds no text of its own.
"""
from __future__ import annotations

from dataclasses import fields

from construct import Construct, Struct

from dissector.errors import GenerateError
from dissector.framing import rules as framing_rules
from dissector.model import Kind
from dissector.protocol import table
from dissector.protocol.rules import CONFIRM, REQUEST_PREFIX, Check, Confirm, ValueKind
from dissector.protocol.table import Data, Function, Layout
from dissector.accel import records
from dissector.accel.fastsummary import HANDOVER, NEED, SlaveFacts, Texts
from dissector.protocol import crc
from dissector.framing.evidence import COIL_VALUES
from dissector.framing.stream import GLITCH_BYTES
from dissector.render import bustiming, describe, stats_store, summary

ADU_HEAD = 2  # slave and function code before the grammar's data

# The Info column of each form the engine writes (its texts and steps, the engine's STEP_*, _summary.c
# info_text) is render/describe.py's TEXT_FORMS, which describe.py interprets too; the fields a step prints
# are read at each code's offsets (Rules.info).
TEXT_FORMS = describe.TEXT_FORMS
FORMS = tuple(TEXT_FORMS)
STEPS = ("end", "none", "text", "unspace", "span", "plain_span", "label", "bits", "values", "write", "coil", "single", "dec",
         "hex", "subfunction", "data", "fifo", "count")
MAX_STEPS = max(len(steps) for steps in TEXT_FORMS.values()) + 1  # and its STEP_END
# The kinds of frame the engine shows by their numbers (KIND_*): those render/bustiming.py gives the engine's
# Stats.bus_item (accel/framespath.py reads its records' answer kinds by them too).
KINDS = {number: kind for kind, number in bustiming._KINDS.items()}


def _arguments(step: tuple[str | int, ...]) -> tuple[str | int, ...]:
    """A step's fields and number: its arguments but a noun (describe.NOUN_STEPS, the step's text)."""
    return step[1:-1] if step[0] in describe.NOUN_STEPS else step[1:]


def _printed(form: str) -> list[str]:
    """The fields a form prints, in the order its steps name them (at most 3)."""
    names: list[str] = []
    for step in TEXT_FORMS[form]:
        for arg in _arguments(step) if isinstance(step, tuple) else ():
            if isinstance(arg, str) and arg not in names:
                names.append(arg)
    return names


def _step(step: str | tuple[str | int, ...], printed: list[str]) -> str:
    """A Step of form_steps: {STEP_*, its first field's index (-1: none), its number or second field's
    index, text (STEP_TEXT's, a noun step's noun), its length in bytes}."""
    if isinstance(step, str):
        return f"{{STEP_TEXT, -1, 0, {c_string(step)}, {len(step.encode())}}}"
    fields = [printed.index(arg) for arg in _arguments(step) if isinstance(arg, str)]
    number = [arg for arg in _arguments(step) if isinstance(arg, int)]
    noun = str(step[-1]) if step[0] in describe.NOUN_STEPS else None
    return (f"{{STEP_{str(step[0]).upper()}, {(fields or [-1])[0]}, {(number or fields[1:] or [0])[0]}, "
            f"{c_string(noun)}, {len(noun.encode()) if noun else 0}}}")


def c_string(text: str | None) -> str:
    """A C string literal of `text`'s UTF-8 bytes (octal escapes past printable ASCII), NULL for None."""
    if text is None:
        return "NULL"
    plain = lambda byte: 0x20 <= byte < 0x7F and byte not in b'"\\?'  # noqa: E731  ("??" trigraphs)
    return '"' + "".join(chr(byte) if plain(byte) else f"\\{byte:03o}" for byte in text.encode()) + '"'


def _form(entry: Function, kind: Kind) -> str:
    """The FORM_* a describer gives in one direction (describe.DESCRIBER_FORMS by table.Function.text)."""
    if entry.compiled is not None and entry.compiled.texts:
        return "python"
    form = describe.form_of(entry.text, kind is Kind.REQUEST, entry.data is Data.BITS)
    if form is None:
        raise GenerateError(f"function {entry.code}: no compiled form for describer {entry.text!r}")
    return form


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


def _check_limit(check: Check, layout: Layout, limits: tuple[str, ...], code: int) -> int:
    name = check.limit or layout.limit
    if name is None:
        raise GenerateError(f"function {code}: {check.field} has no limit (the layout gives none)")
    return limits.index(name)


# The Lift struct's members in order (see LIFT_STRUCT); check_*: two at most, echo_*: MAX_ECHO (FC22's three).
MAX_ECHO = 3
LIFT_FIELDS = (
    "special", "start_at", "quantity_at", "quantity", "check_at", "check_width", "check_limit", "check_above", "span",
    "count_at", "count_width", "min_count", "count_rule", "count_of_at", "count_unit", "count_plus", "odd_count",
    "padding", "coil_at", "echo_at", "echo_request_at", "values", "values_at", "write_start_at", "write_quantity_at",
)
VALUES = {None: 0, ValueKind.REGISTERS: 1, ValueKind.REGISTER: 2, ValueKind.BITS: 3, ValueKind.COIL: 0}


def lift_row(entry: Function, kind: Kind, limits: tuple[str, ...]) -> dict[str, int | list[int]]:
    """Lift (see the header) of a compiled code in one direction, from its lifting rule and its layout."""
    code, layout = entry.code, entry.layout(kind)
    request = kind is Kind.REQUEST
    row: dict[str, int | list[int]] = {name: 0 for name in LIFT_FIELDS}
    row.update(special=_named_case(layout), quantity=int(request), check_at=[0, 0], check_width=[0, 0], check_limit=[-1, -1],
               check_above=[0, 0], echo_at=[0] * MAX_ECHO, echo_request_at=[0] * MAX_ECHO)
    if entry.compiled is not None and entry.compiled.texts:
        return row  # the texts come from the Python stages
    grammar = layout.grammar
    at = lambda name: field_at(grammar, name, code)  # noqa: E731
    rule = table.lift_of(code, kind)
    if isinstance(layout.length, table.Counted) or (rule is not None and rule.count is not None):
        # A byte count shorter than the fixed fields after it is malformed (FC12's events: count - 6).
        row.update(count_at=at("byte_count"), count_width=field_width(grammar, "byte_count"),
                   min_count=fixed_after(grammar, "byte_count"))
    if rule is None:
        return row
    echo = rule.echo.fields if rule.echo and not request else ()  # what an answer repeats
    if len(echo) > MAX_ECHO or any(field_width(grammar, name) != 2 for name in echo) or rule.echo and rule.echo.data:
        raise GenerateError(f"function {code}: the engine compares {MAX_ECHO} 16-bit echo fields at most")
    if rule.parts is not None:
        raise GenerateError(f"function {code}: the engine checks no parts (its texts come from Python)")
    if len(rule.checks) > 2:
        raise GenerateError(f"function {code}: the engine checks two fields of a frame at most")
    quantity = rule.quantity
    if not isinstance(quantity, int):  # a field, the request's (0), or none: one register at a start of its own
        quantity = int(quantity is None and (request or _own(rule.start) is not None))
    values = rule.values
    row.update(
        start_at=at(_own(rule.start)), quantity_at=at(_own(rule.quantity)), quantity=quantity, span=int(rule.span),
        odd_count=int(rule.odd_count), padding=int(rule.padding is not None), coil_at=at(rule.coil),
        echo_at=[at(name) for name in echo] + [0] * (MAX_ECHO - len(echo)),
        echo_request_at=[field_at(entry.request.grammar, name, code) for name in echo] + [0] * (MAX_ECHO - len(echo)),
        values=VALUES[values.kind if values else None], values_at=at(values.field) if values else 0,
        write_start_at=at(values.start) if values and values.start and values.start != rule.start else 0,
        write_quantity_at=at(rule.write_window[1]) if rule.write_window else 0,
    )
    for j, check in enumerate(rule.checks):
        row["check_at"][j] = at(check.field)  # type: ignore[index]
        row["check_width"][j] = field_width(grammar, check.field)  # type: ignore[index]
        row["check_limit"][j] = _check_limit(check, layout, limits, code)  # type: ignore[index]
        row["check_above"][j] = int(check.test == "above")  # type: ignore[index]
    if rule.count is not None:
        count = rule.count
        row.update(count_rule=1, count_of_at=at(_own(count.of)), count_unit=count.unit, count_plus=count.plus)
    return row


# The Rules struct's members in order; info: the request's and the response's InfoForm.
RULE_FIELDS = ("special", "confirm", "reads", "texts", "info")


def _info(entry: Function, kind: Kind) -> str:
    """InfoForm of a compiled code in one direction: its form, and where the fields it prints are and their
    widths (FC7's status a byte, FC12's a word; 0: a field printed from its offset only, FIFO values)."""
    form, grammar = _form(entry, kind), entry.layout(kind).grammar
    names = _printed(form)
    if len(names) > 3:
        raise GenerateError(f"form {form}: the engine prints three fields at most")
    at = [field_at(grammar, name, entry.code) for name in names] + [0] * (3 - len(names))
    widths = []
    for name in names:
        try:
            widths.append(field_width(grammar, name))
        except Exception:
            widths.append(0)
    widths += [0] * (3 - len(names))
    return f"{{form_steps[FORM_{form.upper()}], {{{', '.join(map(str, at))}}}, {{{', '.join(map(str, widths))}}}}}"


def _named_case(layout: Layout) -> int:
    """1: the layout is FC8's, which the engine checks by its named case (diagnostics_are_plain)."""
    return int(layout.handler == "diagnostics")


def rules_row(entry: Function) -> dict[str, int | list[int] | str]:
    """Rules (see the header) of a compiled code: what it is, both directions' forms and printed fields."""
    code = entry.code
    request, response = entry.request, entry.response
    return dict(
        special=_named_case(request) | _named_case(response),
        confirm={None: 0, Confirm.ECHO: 1, Confirm.ANSWER: 2, Confirm.MASK: 3}[CONFIRM.get(code)],
        reads=int(code in table.register_reads()),
        texts=int(entry.compiled is not None and entry.compiled.texts),
        info="{" + ", ".join(_info(entry, kind) for kind in (Kind.REQUEST, Kind.RESPONSE)) + "}",
    )


LIFT_STRUCT = """/* How the engine lifts a frame of a compiled code in one direction, from its lifting rule
 * (data/modbus.toml [lift]; codegen/c_rules.py), as decode/fields.py's lifter does. Offsets from the
 * frame's first byte, 0: none. special: FC8's named case checks it instead (diagnostics_are_plain);
 *   the window: start_at, quantity_at; else the constant `quantity` (0: the request's) and the request's start;
 *   check_at[j] (check_width[j] bytes) within LIMIT check_limit[j] (check_above: its high bound only);
 *   span: start + quantity within the 65536 addresses;
 *   the byte count at count_at (count_width bytes), at least min_count; with count_rule it must be
 *   count_plus + of x count_unit (0: bits, ceil(of / 8)), `of` at count_of_at or the request's quantity;
 *   odd_count: an even count; padding: the bits' last byte 0 past the quantity; coil_at: ON or OFF; echo_at[j] must equal the request's echo_request_at[j];
 *   values (VALUES_*) at values_at: a block of the window's registers (at write_start_at and
 *   write_quantity_at when the frame writes a window of its own, FC23), one register at the window's start,
 *   or the window's bits. */
typedef struct {
    int special, start_at, quantity_at, quantity, check_at[2], check_width[2], check_limit[2], check_above[2], span;
    int count_at, count_width, min_count, count_rule, count_of_at, count_unit, count_plus, odd_count, padding;
    int coil_at, echo_at[MAX_ECHO], echo_request_at[MAX_ECHO], values, values_at, write_start_at, write_quantity_at;
} Lift;"""

RULES_STRUCT = """/* What the engine does with a transaction of a compiled code (codegen/c_rules.py):
 *   special: 1 diagnostics (FC8's named case); confirm ([confirm]): 1 by the answer's echo, 2 by a normal
 *   answer, 3 masks the echo confirms (the Python stages'); reads: the answer's registers are values read;
 *   texts: the texts come from the Python stages (table.Compiled.texts); info: the request's and the
 *   response's Info column, the steps of its form (form_steps) printing the fields at at[] of width[] bytes
 *   (0: from its offset only). */
typedef struct { const Step *steps; int at[3], width[3]; } InfoForm;
typedef struct {
    int special, confirm, reads, texts;
    InfoForm info[2];
} Rules;"""

STEP_STRUCT = """/* The Info column's forms (codegen/c_rules.py TEXT_FORMS, describe.py's describers): the steps of each,
 * up to STEP_END. A step writes `text` (STEP_TEXT, `length` bytes) or a part of the frame: its window,
 * bits, registers, or a printed field (`field`: its index in InfoForm.at, -1 none) as a number (`number`:
 * STEP_HEX's least digits, STEP_FIFO's values field; STEP_COUNT's noun in `text`). */
typedef struct { int step, field, number; const char *text; int length; } Step;"""


def _braced(row: dict[str, int | list[int] | str], names: tuple[str, ...]) -> str:
    def one(value: int | list[int] | str) -> str:
        return "{" + ", ".join(map(str, value)) + "}" if isinstance(value, list) else str(value)

    return "{" + ", ".join(one(row[name]) for name in names) + "}"


def _field_names(cls: type, prefix: str, count: str, names: str) -> list[str]:
    """An enum of a dataclass's fields by name, and their names, for the engine to read them in order."""
    found = [field.name for field in fields(cls)]
    return [
        "enum { " + ", ".join(f"{prefix}_{name.upper()}" for name in found) + f", {count} }};",
        f"static const char *const {names}[{count}] = {{" + ", ".join(f'"{name}"' for name in found) + "};",
    ]


def _mei_function() -> int:
    """The one function code the table describes as an MEI transport (FC43: --stats keys its polls by MEI type)."""
    (code,) = (entry.code for entry in table.FUNCTIONS if entry.text == "mei")
    return code


def render(entries: list[Function], limits: tuple[str, ...]) -> list[str]:
    """The header lines for the rules, the forms and the constants the engine shares with describe.py."""
    lines = [
        "/* Constants of the framer (framing/rules.py, data/modbus.toml [limits]) and of render/describe.py. */",
        f"#define MIN_ADU {framing_rules.MIN_ADU}",
        f"#define MAX_ADU {framing_rules.MAX_ADU}",
        f"#define MAX_COUNTED {framing_rules.MAX_COUNTED}",
        f"#define MEI_FUNCTION {_mei_function()}",
        f"#define MEI_DEVICE_ID {table.DEVICE_ID}",
        f"#define MAX_SLAVE {framing_rules.MAX_SLAVE}",
        f"#define GLITCH_SKIP {framing_rules.GLITCH_SKIP}",
        f"#define MAX_VALUES {describe.MAX_VALUES}",
        f"#define MAX_BITS {describe.MAX_BITS}",
        f"#define MAX_FIFO_VALUES {describe.MAX_FIFO_VALUES}",
        f"#define MAX_DATA_BYTES {describe.MAX_DATA_BYTES}",
        f"#define COIL_ON 0x{COIL_VALUES[0]:04X}",
        f"#define COIL_OFF 0x{COIL_VALUES[1]:04X}",
        "/* An exception's length rule (table.EXCEPTION_LAYOUT), and the bytes a short low pulse on an idle line",
        " * reads as (framing/stream.py GLITCH_BYTES: a driver's turn-around), by byte. */",
        f"static const LengthRule exception_rule = {{{table.EXCEPTION_LAYOUT.length.length}, 0, 0, 0, 0, 0, 0, 0}};",
        "static const uint8_t glitch_bytes[256] = {",
        *(f"    {', '.join(str(int(byte in GLITCH_BYTES)) for byte in range(row, row + 32))},"
          for row in range(0, 256, 32)),
        "};",
        "/* The function codes a broadcast (slave 0) may not carry (framing/rules.py NOT_BROADCAST), by code. */",
        "static const uint8_t not_broadcast[256] = {",
        *(f"    {', '.join(str(int(code in framing_rules.NOT_BROADCAST)) for code in range(row, row + 32))},"
          for row in range(0, 256, 32)),
        "};",
        "/* Of the --stats store (render/stats_store.py) and the timed path (_timeline.h's chunk",
        " * flags are accel/records.py's). */",
        f"#define MAX_PARAMETERS {stats_store.MAX_PARAMETERS}",
        f"#define MAX_TALLY {stats_store.MAX_TALLY}",
        f"enum {{ CHUNK_TIMED = {records.TIMED}, CHUNK_RECORD_END = {records.RECORD_END}, "
        f"CHUNK_SILENCE_BEFORE = {records.SILENCE_BEFORE} }};",
        "/* CRC-16/MODBUS by byte (protocol/crc.py's table). */",
        "static const uint16_t crc_table[256] = {",
        *(f"    {', '.join(f'0x{value:04X}' for value in crc._TABLE[row : row + 8])}," for row in range(0, 256, 8)),
        "};",
        "/* The kinds of frame (KIND_*), and each as a summary line shows it between its slave and its info",
        " * (render/summary.py summary_line: ` {_KIND_COLUMN} `), by kind. */",
        "enum { " + ", ".join(f"KIND_{kind.name} = {number}" for number, kind in KINDS.items()) + " };",
        "static const char *const kind_column[] = {"
        + ", ".join(c_string(f" {summary._KIND_COLUMN[KINDS[number]]} " if number in KINDS else None)
                    for number in range(max(KINDS) + 1))
        + "};",
        "/* run()'s status (accel/fastsummary.py): more bytes needed, or the stream handed over. */",
        f"enum {{ STATUS_NEED = {NEED}, STATUS_HANDOVER = {HANDOVER} }};",
        "/* The fields of accel/fastsummary.py's SlaveFacts (what the engine knows of a slave) and Texts (what",
        " * the Python stages write of a transaction), read by name. */",
        *_field_names(SlaveFacts, "FACT", "FACTS", "fact_names"),
        *_field_names(Texts, "TEXT", "TEXTS", "text_names"),
        "",
        "enum { " + ", ".join(f"FORM_{name.upper()}" for name in FORMS) + " };",
        "enum { CONFIRM_NONE, CONFIRM_ECHO, CONFIRM_ANSWER, CONFIRM_MASK };",
        "enum { VALUES_NONE, VALUES_BLOCK, VALUES_ONE, VALUES_BITS };",
        f"#define MAX_ECHO {MAX_ECHO}",
        LIFT_STRUCT,
    ]
    for kind in (Kind.REQUEST, Kind.RESPONSE):
        lines += [
            f"static const Lift {kind.value}_lift[HANDLED] = {{",
            *(f"    {_braced(lift_row(entry, kind, limits), LIFT_FIELDS)}, /* {entry.code} */" for entry in entries),
            "};",
        ]
    return lines + [
        "enum { " + ", ".join(f"STEP_{name.upper()}" for name in STEPS) + " };",
        STEP_STRUCT,
        f"#define MAX_STEPS {MAX_STEPS}",
        "static const Step form_steps[][MAX_STEPS] = {",
        *(f"    {{{', '.join(_step(step, _printed(form)) for step in steps)}}}, /* {form} */"
          for form, steps in TEXT_FORMS.items()),
        "};",
        RULES_STRUCT,
        "static const Rules rules[HANDLED] = {",
        *(f"    {_braced(rules_row(entry), RULE_FIELDS)}, /* {entry.code} */" for entry in entries),
        "};",
    ]
