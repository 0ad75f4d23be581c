"""The protocol table: one entry per function code, the one place its rules are stated.

Each entry gives, per direction, the Construct layout of the data (protocol/layouts.py), the length
rule of the whole RTU frame, the decoder's handler and the spec limit it checks; and per code whether
the response echoes the request, what it accesses (read, write) and whether the compiled summary path
(accel/_summary.c) shows it. Everything else derives from here: the framer's length rules
(framing/rtu.py), the grammars (protocol/grammar.py), the fast parser and the handlers (decode/), the
annotator's read classes, and, through `python3 -m dissector.codegen`, the C header
accel/_tables.h and the rule tables of the Wireshark plugin (lua/vw3.lua).

Only stage-0 names are imported (model): the later stages look the names given here up in their own
registries (a handler name in decode/fields.py, a rule name in framing/rtu.py, a parser name in the
plugin), and a unit test holds every name to an implementation.
"""
from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from construct import Construct, Struct

from dissector.model import Kind
from dissector.protocol import layouts as L
from dissector.protocol.rules import LIFTS, Confirm, Lift, ValueKind, confirmed_by
from dissector.protocol.spec import SPEC


@dataclass(frozen=True, slots=True)
class Fixed:
    """The frame is `length` bytes long, CRC included."""

    length: int


@dataclass(frozen=True, slots=True)
class Counted:
    """The frame is `extra` + the byte count at `position` (`width` 1: one byte, 2: a big-endian word)."""

    position: int
    extra: int
    width: int = 1


class Scan:
    """No length in the frame's first bytes: the frame is found by a CRC scan from `minimum` bytes.

    (Scan, Special and Select are plain classes, not dataclasses: a dataclass costs every start-up some
    4 M instructions, 0.4 % of a 20,000-frame plant summary.)"""

    __slots__ = ("minimum",)

    def __init__(self, minimum: int) -> None:
        self.minimum = minimum


class Special:
    """A rule too irregular for data, implemented by name in the framers, with its two offsets:
    "mei_objects", FC43/14's object list, its count at `position` and its objects (id, length byte,
    value) from `start`."""

    __slots__ = ("name", "position", "start")

    def __init__(self, name: str, position: int, start: int) -> None:
        self.name, self.position, self.start = name, position, start


class Select:
    """The rule a field of the frame picks: `chosen` when the byte (`width` 1) or big-endian word (2) at
    `position` is `value`, else `otherwise` (FC8's sub-function, FC43's MEI type)."""

    __slots__ = ("position", "width", "value", "chosen", "otherwise")

    def __init__(self, position: int, width: int, value: int, chosen: LengthRule, otherwise: LengthRule) -> None:
        self.position, self.width, self.value, self.chosen, self.otherwise = position, width, value, chosen, otherwise


LengthRule = Fixed | Counted | Scan | Select | Special


@dataclass(frozen=True, slots=True)
class ByQuantity:
    """A second length for a request whose byte count may disagree with its quantity (the Altivar
    212 manual's FC16 example, libmodbus's unit test): `extra` + the data the quantity (a big-endian
    word at `position`) calls for, `unit` bytes an item (2: registers; 0: coils, 8 to a byte). The
    framer tries it after the byte count's length; the decoder warns about the disagreement."""

    position: int
    extra: int
    unit: int


SCAN = Scan(4)  # (from the shortest frame: slave, function, CRC)


class Access(StrEnum):
    READ = "read"
    WRITE = "write"
    READ_WRITE = "read_write"
    DIAGNOSTIC = "diagnostic"  # the device's state, counters, identity: neither reads nor writes data


class Data(StrEnum):
    """What the decoder lifts out of a frame's data: addressed registers, addressed bits, or neither."""

    REGISTERS = "registers"
    BITS = "bits"
    NONE = "none"


@dataclass(frozen=True, slots=True)
class Layout:
    """One direction of one function code."""

    name: str  # the layout's name: keys the fast parser (decode/fastpath.py) and the plugin's parser
    grammar: Construct
    length: LengthRule
    handler: str | None = None  # decode/fields.py handler (the plugin's `<name>_handler`)
    limit: str | None = None  # data/modbus.toml [limits] entry the handler checks the quantity against
    by_quantity: ByQuantity | None = None  # a request's length by its quantity, when it has a byte count too


@dataclass(frozen=True, slots=True)
class Compiled:
    """The compiled summary path (accel/_summary.c) shows this code; it reads the request and the answer
    by the lifting rules (data/modbus.toml [lift], through codegen/c_rules.py)."""

    # The engine frames and pairs the transaction, and its texts come from the Python stages (kept by
    # the frames' bytes): for layouts whose decoding and annotation change no state and whose texts
    # are not worth porting (file records, identification objects, the server ID).
    texts: bool = False


@dataclass(frozen=True, slots=True)
class Function:
    code: int
    request: Layout
    response: Layout
    access: Access
    data: Data = Data.NONE
    echo: bool = False  # the response repeats the request (or its first fields)
    compiled: Compiled | None = None
    # How the Info column describes it: a describer of render/describe.py by name (the compiled engine
    # writes the same texts, by the forms codegen/c_rules.py derives from this name and the direction).
    text: str = "simple"

    def layout(self, kind: Kind) -> Layout:
        return self.request if kind is Kind.REQUEST else self.response


def _layout(
    name: str, length: LengthRule, handler: str | None = None, limit: str | None = None,
    by_quantity: ByQuantity | None = None,
) -> Layout:
    return Layout(name, L.LAYOUTS[name], length, handler, limit, by_quantity)


_EIGHT = Fixed(8)
_BYTE_COUNT = Counted(2, 5)  # slave, function, byte count, data, CRC
# FC8: Return Query Data (sub-function 0) echoes any amount of data; all others carry one word.
_DIAGNOSTICS = Select(2, 2, 0, Scan(6), _EIGHT)
DEVICE_ID = 14  # FC43's MEI type Read Device Identification: a fixed request, an object list answer


def _read(code: int, bits: bool) -> Function:
    request_limit = "read_bits" if bits else "read_registers"
    return Function(
        code,
        _layout("read_request", _EIGHT, "read_request", request_limit),
        _layout(
            "read_bits_response" if bits else "read_registers_response",
            _BYTE_COUNT,
            "read_bits_response" if bits else "read_registers_response",
        ),
        Access.READ,
        Data.BITS if bits else Data.REGISTERS,
        compiled=Compiled(),
        text="read",
    )


FUNCTIONS: tuple[Function, ...] = (
    _read(1, bits=True),
    _read(2, bits=True),
    _read(3, bits=False),
    _read(4, bits=False),
    Function(
        5,
        _layout("write_single", _EIGHT, "write_single_coil"),
        _layout("write_single", _EIGHT, "write_single_coil"),
        Access.WRITE, Data.BITS, echo=True,
        compiled=Compiled(), text="write_single_coil",
    ),
    Function(
        6,
        _layout("write_single", _EIGHT, "write_single_register"),
        _layout("write_single", _EIGHT, "write_single_register"),
        Access.WRITE, Data.REGISTERS, echo=True,
        compiled=Compiled(), text="write_single_register",
    ),
    Function(
        7, _layout("empty", Fixed(4)), _layout("exception_status_response", Fixed(5)), Access.DIAGNOSTIC,
        compiled=Compiled(),
    ),
    Function(
        8,
        _layout("diagnostics", _DIAGNOSTICS, "diagnostics"),
        _layout("diagnostics", _DIAGNOSTICS, "diagnostics"),
        Access.DIAGNOSTIC, echo=True,
        compiled=Compiled(), text="diagnostics",
    ),
    Function(
        11, _layout("empty", Fixed(4)), _layout("comm_event_counter_response", _EIGHT), Access.DIAGNOSTIC,
        compiled=Compiled(), text="comm_event_counter",
    ),
    Function(
        12, _layout("empty", Fixed(4)), _layout("comm_event_log_response", _BYTE_COUNT), Access.DIAGNOSTIC,
        compiled=Compiled(), text="comm_event_log",
    ),
    Function(
        15,
        _layout("write_coils_request", Counted(6, 9), "write_coils_request", "write_coils", ByQuantity(4, 9, 0)),
        _layout("write_multiple_response", _EIGHT, "write_multiple_response"),
        Access.WRITE, Data.BITS, echo=True,
        compiled=Compiled(), text="write_multiple",
    ),
    Function(
        16,
        _layout(
            "write_registers_request", Counted(6, 9), "write_registers_request", "write_registers", ByQuantity(4, 9, 2)
        ),
        _layout("write_multiple_response", _EIGHT, "write_multiple_response"),
        Access.WRITE, Data.REGISTERS, echo=True,
        compiled=Compiled(), text="write_multiple",
    ),
    Function(
        17,
        _layout("empty", Fixed(4)),
        _layout("report_server_id_response", _BYTE_COUNT, "report_server_id_response"),
        Access.DIAGNOSTIC,
        compiled=Compiled(texts=True), text="report_server_id",
    ),
    Function(
        20,
        _layout("read_file_request", _BYTE_COUNT, "read_file_request"),
        _layout("read_file_response", _BYTE_COUNT, "read_file_response"),
        Access.READ,
        compiled=Compiled(texts=True), text="file_record",
    ),
    Function(
        21, _layout("write_file", _BYTE_COUNT, "write_file"), _layout("write_file", _BYTE_COUNT, "write_file"),
        Access.WRITE, echo=True,
        compiled=Compiled(texts=True), text="file_record",
    ),
    Function(
        22,
        _layout("mask_write", Fixed(10), "mask_write"),
        _layout("mask_write", Fixed(10), "mask_write"),
        Access.WRITE, echo=True,
        compiled=Compiled(), text="mask_write",
    ),
    Function(
        23,
        _layout("read_write_request", Counted(10, 13), "read_write_request", by_quantity=ByQuantity(8, 13, 2)),
        _layout("read_registers_response", _BYTE_COUNT, "read_registers_response"),
        Access.READ_WRITE, Data.REGISTERS,
        compiled=Compiled(), text="read_write",
    ),
    Function(
        24,
        _layout("fifo_request", Fixed(6), "fifo_request"),
        # The FIFO's values have no addresses of their own: Data.NONE.
        _layout("fifo_response", Counted(2, 6, width=2), "fifo_response", "fifo_count"),
        Access.READ,
        compiled=Compiled(), text="fifo",
    ),
    Function(
        43,
        _layout("mei_request", Select(2, 1, DEVICE_ID, Fixed(7), Scan(5)), "mei_request"),
        _layout("mei_response", Select(2, 1, DEVICE_ID, Special("mei_objects", 7, 8), Scan(5)), "mei_response"),
        Access.DIAGNOSTIC,
        compiled=Compiled(texts=True), text="mei",
    ),
)

TABLE: dict[int, Function] = {entry.code: entry for entry in FUNCTIONS}

# Codes with no public layout, found by a CRC scan: the spec's user-defined ranges and the codes device
# profiles speak (both from data files).
OTHER_FUNCTIONS = SPEC.user_defined | SPEC.vendor_functions

EXCEPTION_LAYOUT = Layout("exception", L.EXCEPTION, Fixed(5))
RAW_LAYOUT = Layout("raw", L.RAW, SCAN)

def known_layouts() -> list[tuple[int, Layout, Layout]]:
    """(code, request layout, response layout) of every code a frame may start with: the table's, then
    the codes found by a CRC scan (raw both ways)."""
    known = [(entry.code, entry.request, entry.response) for entry in FUNCTIONS]
    return known + [(code, RAW_LAYOUT, RAW_LAYOUT) for code in sorted(OTHER_FUNCTIONS) if code not in TABLE]


# The longest frame a header may give its length (the framers take one over [limits] max_adu when its CRC is good,
# with a warning): the most a one-byte count can say, FC23's request 13 + 255. A word count or a quantity (FC24's,
# FC16's) is held to it too, so that the bytes weighed at a position stay bounded; a CRC scan keeps max_adu.
LONGEST_COUNTED = max(
    layout.length.extra + 0xFF
    for entry in FUNCTIONS for layout in (entry.request, entry.response)
    if isinstance(layout.length, Counted) and layout.length.width == 1
)

# Codes the compiled summary path shows (accel/_summary.c through accel/_tables.h), in table order.
COMPILED = tuple(entry.code for entry in FUNCTIONS if entry.compiled is not None)


def compiled_limits() -> tuple[str, ...]:
    """The spec limits the engine checks (its lifting rules' checks, requests then answers), in the order
    of LIMIT_* and spec_limits in accel/_tables.h."""
    names: list[str] = []
    for kind in (Kind.REQUEST, Kind.RESPONSE):
        for entry in FUNCTIONS:
            rule = lift_of(entry.code, kind) if entry.compiled is not None else None
            for check in rule.checks if rule is not None else ():
                name = check.limit or entry.layout(kind).limit
                if name is not None and name not in names:
                    names.append(name)
    return tuple(names)


def layout_for(function: int, kind: Kind) -> Layout:
    """The layout of a frame's data; unknown codes: raw bytes."""
    if kind is Kind.EXCEPTION:
        return EXCEPTION_LAYOUT
    entry = TABLE.get(function)
    return entry.layout(kind) if entry is not None else RAW_LAYOUT


def by_kind(attribute: str) -> dict[Kind, dict[int, object]]:
    """{kind: {code: layout.attribute}} for both directions, leaving out codes where it is None."""
    out: dict[Kind, dict[int, object]] = {}
    for kind in (Kind.REQUEST, Kind.RESPONSE):
        values = ((entry.code, getattr(entry.layout(kind), attribute)) for entry in FUNCTIONS)
        out[kind] = {code: value for code, value in values if value is not None}
    return out


def register_reads() -> frozenset[int]:
    """Codes whose response registers are values read from the device (the annotator's reads)."""
    return frozenset(
        entry.code for entry in FUNCTIONS
        if entry.data is Data.REGISTERS and entry.access in (Access.READ, Access.READ_WRITE)
    )


def plain_register_reads() -> frozenset[int]:
    """Reads with no write part: an exception to them concerns the registers read alone."""
    return frozenset(entry.code for entry in FUNCTIONS if entry.data is Data.REGISTERS and entry.access is Access.READ)


def field_offset(grammar: Construct, name: str) -> int:
    """Offset of a field in a grammar's data, counted over the fixed-size fields before it."""
    offset = 0
    for sub in grammar.subcons if isinstance(grammar, Struct) else ():
        if sub.name == name:
            return offset
        offset += sub.sizeof()  # raises for a variable-size field: no fixed offset then
    raise KeyError(f"no field {name!r} at a fixed offset")


# -- what the rule tables (protocol/rules.py) say per function code ------------------------------------
def lift_of(function: int, kind: Kind) -> Lift | None:
    """The lifting rule of a frame's data; None: a named special case, or no handler."""
    entry = TABLE.get(function)
    if entry is None or kind is Kind.EXCEPTION:
        return None
    handler = entry.layout(kind).handler
    return None if handler is None else LIFTS.get(handler)


def write_windows() -> dict[int, tuple[str, str]]:
    """Codes whose request writes a window of its own beside the one it reads (FC23): its fields."""
    out = {}
    for entry in FUNCTIONS:
        rule = lift_of(entry.code, Kind.REQUEST)
        if rule is not None and rule.write_window is not None:
            out[entry.code] = rule.write_window
    return out


def register_writes() -> frozenset[int]:
    """Codes whose request registers are values written (FC6, FC16, FC23)."""
    return frozenset(
        entry.code for entry in FUNCTIONS
        if entry.data is Data.REGISTERS and entry.access in (Access.WRITE, Access.READ_WRITE)
    )


def confirmed_registers(how: Confirm) -> frozenset[int]:
    """Register writes `how` confirms (data/modbus.toml [confirm]): by its echo FC6, by a normal answer
    FC16 and FC23."""
    return confirmed_by(how, register_writes())


def bit_windows() -> frozenset[int]:
    """Codes whose request or answer carries bits (its lifting rule's values "bits" or "coil": FC1, 2, 5,
    15): their windows' addresses are bits', and bits carry no label (render/filter_match.py, the plugin's
    DATA.bit_windows from codegen/display_lua.py)."""
    return frozenset(
        entry.code for entry in FUNCTIONS for kind in (Kind.REQUEST, Kind.RESPONSE)
        if (rule := lift_of(entry.code, kind)) is not None and rule.values is not None
        and rule.values.kind in (ValueKind.BITS, ValueKind.COIL)
    )


def coil_requests() -> frozenset[int]:
    """Codes whose request carries one coil value that must be ON or OFF (FC5)."""
    return frozenset(
        entry.code for entry in FUNCTIONS if (rule := lift_of(entry.code, Kind.REQUEST)) is not None and rule.coil
    )
