"""The rule tables of data/modbus.toml as typed objects: how frames are lifted, how writes are confirmed,
and the catalogue of warning and note texts.

They are data so that each engine interprets the same statement: the Python lifter (decode/fields.py),
the compiled engine (accel/_summary.c through the generated accel/_tables.h, codegen/c_rules.py) and
the plugin (its generated rule data, codegen/rules_lua.py). A rule names fields of the layout grammars
(protocol/layouts.py); tests/unit/test_rules.py holds every name to a grammar field.
"""
from __future__ import annotations

import string
from dataclasses import dataclass
from enum import StrEnum

from dissector.model import Frame
from dissector.protocol.spec import SPEC

REQUEST_PREFIX = "request."  # a window value taken from the request a frame answers


class Test(StrEnum):
    RANGE = "range"  # low <= value <= high
    ABOVE = "above"  # value <= high (the low bound is 0, an unsigned field's own)


@dataclass(frozen=True, slots=True)
class Check:
    """A field checked against a spec limit; `limit` None: the layout's own (protocol/table.py)."""

    what: str
    field: str
    limit: str | None = None
    test: Test = Test.RANGE


@dataclass(frozen=True, slots=True)
class Count:
    """The byte count must be `plus` + `of` x `unit` (unit 0: bits, ceil(of / 8))."""

    of: str
    unit: int
    text: str
    plus: int = 0

    def expected(self, quantity: int) -> int:
        return self.plus + data_bytes(quantity, self.unit)


def data_bytes(quantity: int, unit: int) -> int:
    """The data `quantity` items take, `unit` bytes an item (0: bits, 8 to a byte): what a byte count
    counts (Count.expected) and what a request's length by its quantity adds (table.ByQuantity,
    framing/rules.py quantity_rule)."""
    return quantity * unit if unit else (quantity + 7) // 8


class Names(StrEnum):
    DIFFERING = "differing"  # the text names the fields that differ
    ALL = "all"  # the text names every field when any differs


@dataclass(frozen=True, slots=True)
class Echo:
    fields: tuple[str, ...]
    names: Names
    data: bool = False  # the answer repeats the request's data whole (FC21): no fields named


@dataclass(frozen=True, slots=True)
class PartLength:
    """A part's `field` must be `plus` + `unit` x the field `of` of the request's part in its place."""

    field: str
    of: str
    unit: int
    plus: int
    text: str

    def held(self, given: int) -> str:
        """What a part's `field` of `given` holds in the request's unit (FC20: length 5 holds 2 registers), the
        bytes short of a whole one after them: the warning says both sides in one unit."""
        whole, rest = divmod(max(given - self.plus, 0), self.unit)
        return f"{whole} and {rest} byte(s)" if rest else str(whole)


@dataclass(frozen=True, slots=True)
class Parts:
    """Each part of a records field checked (FC20, FC21): its `checks`, and with `request` (the request's
    records field) against the request's part in its place."""

    field: str
    name: str  # what a part is called in a text, before its place (`sub-request 2`)
    checks: tuple[Check, ...] = ()
    request: str | None = None
    length: PartLength | None = None


class ValueKind(StrEnum):
    REGISTERS = "registers"
    BITS = "bits"
    REGISTER = "register"
    COIL = "coil"


@dataclass(frozen=True, slots=True)
class Values:
    kind: ValueKind
    field: str
    start: str | None = None  # a field; None: the window's start
    most: str | None = None  # registers: a field, the most values there are (those past it: text `past`)
    past: str | None = None


@dataclass(frozen=True, slots=True)
class Lift:
    """How one handler lifts a frame (data/modbus.toml [lift.<name>], the keys explained there)."""

    name: str
    start: str | None = None
    quantity: str | int | None = None
    unpaired_unit: int | None = None
    checks: tuple[Check, ...] = ()
    span: bool = False
    count: Count | None = None
    odd_count: bool = False
    padding: str | None = None  # bits: the text of padding bits set
    coil: str | None = None
    echo: Echo | None = None
    values: Values | None = None
    write_window: tuple[str, str] | None = None
    parts: Parts | None = None

    def fields(self) -> set[str]:
        """The grammar fields the rule names of its own frame (the request's are the window's)."""
        names = {check.field for check in self.checks}
        for value in (self.start, self.quantity, self.coil, self.count.of if self.count else None):
            if isinstance(value, str) and not value.startswith(REQUEST_PREFIX):
                names.add(value)
        if self.echo:
            names.update(self.echo.fields)
        if self.values:
            names.add(self.values.field)
            if self.values.start:
                names.add(self.values.start)
            if self.values.most:
                names.add(self.values.most)
        if self.write_window:
            names.update(self.write_window)
        if self.count:
            names.add("byte_count")
        if self.parts:
            names.add(self.parts.field)
        return names


class RuleError(ValueError):
    """A rule table entry the engines cannot interpret."""


_KEYS = set(Lift.__dataclass_fields__) - {"name"}


def _lift(name: str, entry: dict[str, object]) -> Lift:
    unknown = set(entry) - _KEYS
    if unknown:
        raise RuleError(f"[lift.{name}]: unknown keys {sorted(unknown)}")
    try:
        count = entry.get("count")
        echo = entry.get("echo")
        values = entry.get("values")
        window = entry.get("write_window")
        parts = entry.get("parts")
        return Lift(
            name,
            start=entry.get("start"),  # type: ignore[arg-type]
            quantity=entry.get("quantity"),  # type: ignore[arg-type]
            unpaired_unit=entry.get("unpaired_unit"),  # type: ignore[arg-type]
            checks=_checks(entry.get("checks", [])),  # type: ignore[arg-type]
            span=bool(entry.get("span", False)),
            count=None if count is None else Count(count["of"], int(count["unit"]), count["text"], int(count.get("plus", 0))),  # type: ignore[index, attr-defined]
            odd_count=bool(entry.get("odd_count", False)),
            padding=entry.get("padding"),  # type: ignore[arg-type]
            coil=entry.get("coil"),  # type: ignore[arg-type]
            echo=None if echo is None else Echo(  # type: ignore[index, attr-defined]
                tuple(echo.get("fields", ())), Names(echo.get("names", "differing")), bool(echo.get("data", False))),
            parts=None if parts is None else _parts(parts),  # type: ignore[arg-type]
            values=None if values is None else Values(  # type: ignore[index, attr-defined]
                ValueKind(values["kind"]), values["field"], values.get("start"), values.get("most"), values.get("past")),
            write_window=None if window is None else (window[0], window[1]),  # type: ignore[index]
        )
    except (KeyError, TypeError, ValueError) as error:
        raise RuleError(f"[lift.{name}]: {error}") from None


def _checks(entries: list[dict[str, str]]) -> tuple[Check, ...]:
    return tuple(Check(c["what"], c["field"], c.get("limit"), Test(c.get("test", "range"))) for c in entries)


def _parts(entry: dict[str, object]) -> Parts:
    length = entry.get("length")
    return Parts(
        entry["field"], entry["name"], _checks(entry.get("checks", [])), entry.get("request"),  # type: ignore[arg-type]
        None if length is None else PartLength(  # type: ignore[index]
            length["field"], length["of"], int(length["unit"]), int(length.get("plus", 0)), length["text"]),
    )


LIFTS: dict[str, Lift] = {name: _lift(name, entry) for name, entry in SPEC.lift.items()}  # type: ignore[arg-type]


# -- writes and their confirmation ---------------------------------------------------------------------
class Confirm(StrEnum):
    ECHO = "echo"  # the answer repeats the values written
    ANSWER = "answer"  # a normal answer confirms the request's values
    MASK = "mask"  # the echo confirms masks applied to the value held (FC22)


CONFIRM: dict[int, Confirm] = {code: Confirm(how) for code, how in SPEC.confirm.items()}


def confirmed_by(how: Confirm, codes: frozenset[int] | set[int] | None = None) -> frozenset[int]:
    """Codes whose writes `how` confirms, among `codes` when given (e.g. the codes with registers)."""
    return frozenset(code for code, way in CONFIRM.items() if way is how and (codes is None or code in codes))


# -- the catalogue of texts ----------------------------------------------------------------------------
TEXTS: dict[str, str] = dict(SPEC.texts)


def params(key: str) -> tuple[str, ...]:
    """The parameter names a text takes, in order of appearance."""
    return tuple(name for _, name, _, _ in string.Formatter().parse(TEXTS[key]) if name)


def text(key: str, **values: object) -> str:
    """The catalogue's text `key` with its parameters filled in."""
    return TEXTS[key].format(**values)


def range_text(what: str, value: int, low: int, high: int) -> str:
    """A value outside the spec's low..high; `is not the spec's 6` where it allows one value only."""
    if low == high:
        return text("range_one", what=what, value=value, low=low)
    return text("range", what=what, value=value, low=low, high=high)


def echo_text(names: list[str]) -> str:
    """`the response's address and value differ from the request's`."""
    return text("echo", fields=" and ".join(names), verb="differs" if len(names) == 1 else "differ")


# [pairing], by function code (the framer's expectation and decode/pairing.py follow it).
NEVER_ANSWERED = SPEC.never_answered  # function -> values of a request's first data word no answer follows
ECHO = SPEC.echo  # function -> data bytes an answer repeats from its request


def awaits_answer(frame: Frame) -> bool:
    """Does a request await an answer: not a broadcast, not one the spec has no server answer? The framer's
    expectation and the pairing (decode/pairing.py) follow it."""
    values = NEVER_ANSWERED.get(frame.function)
    if values is None:
        return frame.slave != 0
    pdu = frame.pdu
    return frame.slave != 0 and not (len(pdu) >= 3 and pdu[1] << 8 | pdu[2] in values)


def echoed(request: Frame) -> bytes:
    """The data bytes of a request its answer must repeat ([pairing] echo: an FC8 sub-function); b"": none.
    The framer's expectation holds them: a frame that does not repeat them is not the answer awaited."""
    count = ECHO.get(request.function)
    return request.pdu[1 : 1 + count] if count is not None else b""

