"""Decoding: parse a paired frame's PDU with its grammar and lift out what users ask about.

Runs after pairing, because a response's registers are numbered from the request it answers. Spec
limits are checked here and reported as warnings, never raised.

The generic lifter (`Lifter`) interprets the rule tables of data/modbus.toml [lift] (protocol/rules.py)
for every handler but the few named special cases below (diagnostics, the server id, FC43 objects);
each rule is prepared once (its limits looked up), so that a frame costs a few attribute tests. The
compiled engine (accel/_summary.c) and the plugin interpret the same rules from their generated tables.
Warnings come in the order the table's comment gives: checks, span, byte count, odd count, coil, echo.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from construct import Container

from dissector.decode.fastpath import fast_parse
from dissector.protocol import table
from dissector.protocol.grammar import GrammarError, parse_pdu
from dissector.protocol.rules import LIFTS, REQUEST_PREFIX, Echo, Lift, Names, Test, ValueKind, echo_text, text
from dissector.model import Bit, BitList, DeviceObject, Frame, Kind, Register, RegisterList
from dissector.protocol.spec import SPEC

_MAX_SLAVE = int(SPEC.limits["max_slave"])  # type: ignore[call-overload]  # 248..255 reserved


def decode_frame(frame: Frame) -> Frame:
    """Fill frame.fields, start, quantity, registers, bits, objects and warnings. Idempotent."""
    if frame.decoded:
        return frame
    frame.decoded = True
    if frame.slave > _MAX_SLAVE:
        frame.warnings.append(text("reserved_slave", slave=frame.slave))
    function = frame.function
    kind = frame.kind
    rtu = frame.mode == "rtu"
    if kind is _REQUEST and rtu and not frame.broadcast:
        known = _REQUESTS.get(frame.raw)
        if known is not None:  # a polled request: what its bytes decoded to last time
            frame.fields, frame.start, frame.quantity, frame.subfunction, warnings = known
            if warnings:
                frame.warnings.extend(warnings)
            return frame
        before = len(frame.warnings)
        _decode(frame, function, kind, frame.raw[1:-2])
        if frame.fields is not None and frame.registers is None and frame.bits is None and frame.objects is None:
            if len(_REQUESTS) >= _REQUESTS_MAX:
                _REQUESTS.clear()
            _REQUESTS[frame.raw] = (
                frame.fields, frame.start, frame.quantity, frame.subfunction, tuple(frame.warnings[before:])
            )
        return frame
    return _decode(frame, function, kind, frame.raw[1:-2] if rtu else frame.pdu)


# Requests without values (reads, diagnostics) repeat on a polled bus: what a request's bytes decode
# to is kept by those bytes (fields are never changed after decoding, so frames may share them).
# Bounded: cleared when full.
_REQUEST = Kind.REQUEST
_REQUESTS: dict[bytes, tuple[Container, int | None, int | None, int | None, tuple[str, ...]]] = {}
_REQUESTS_MAX = 1 << 14


def _decode(frame: Frame, function: int, kind: Kind, pdu: bytes) -> Frame:
    fields = fast_parse(function, kind, pdu)
    if fields is None:
        try:
            fields = parse_pdu(function, kind, pdu[1:])
        except GrammarError as error:
            frame.warnings.append(text("malformed", kind=frame.kind, error=error))
            return frame
    frame.fields = fields
    if kind is Kind.EXCEPTION:
        code = fields["exception_code"]
        if code not in SPEC.exceptions:
            frame.warnings.append(text("unknown_exception", code=code))
    else:
        handler = _HANDLERS_BY_KIND[kind].get(function)
        if handler is not None:
            handler(frame, fields)
    trailing = fields.get("trailing")
    if trailing:
        frame.warnings.append(text("trailing", count=len(trailing)))
    if frame.broadcast and function in SPEC.not_broadcast:
        frame.warnings.append(text("not_broadcast", function=SPEC.function_name(function)))
    return frame


COIL_ON, COIL_OFF = 0xFF00, 0x0000


@dataclass(frozen=True, slots=True)
class _Check:
    what: str
    field: str
    low: int
    high: int
    above: bool  # Test.ABOVE: only the high bound


def _limits(name: str) -> tuple[int, int]:
    low, high = SPEC.limits[name]  # type: ignore[misc]
    return int(low), int(high)


class Lifter:
    """One prepared rule; calling it lifts a frame (a decode/fields.py handler)."""

    __slots__ = ("rule", "checks", "request_of", "from_request", "_start", "_quantity", "_quantity_const")

    def __init__(self, rule: Lift, limit: str | None, request_of: RequestOf) -> None:
        self.rule = rule
        self.request_of = request_of
        checks = []
        for check in rule.checks:
            name = check.limit or limit
            if name is None:
                raise ValueError(f"[lift.{rule.name}]: {check.field} has no limit (the layout gives none)")
            low, high = _limits(name)
            checks.append(_Check(check.what, check.field, low, high, check.test is Test.ABOVE))
        self.checks = tuple(checks)
        quantity = rule.quantity
        self._quantity_const = quantity if isinstance(quantity, int) else None
        self._start = rule.start
        self._quantity = quantity if isinstance(quantity, str) else None
        named = [value for value in (rule.start, self._quantity, rule.count.of if rule.count else None) if value]
        self.from_request = any(value.startswith(REQUEST_PREFIX) for value in named) or rule.echo is not None

    def __call__(self, frame: Frame, fields: Container) -> None:
        rule = self.rule
        request = self.request_of(frame) if self.from_request else None
        start = self._value(self._start, fields, request)
        quantity = self._quantity_const if self._quantity_const is not None else self._value(self._quantity, fields, request)
        if quantity is None and rule.unpaired_unit and request is None:
            count = fields["byte_count"]
            if count % rule.unpaired_unit == 0:
                quantity = count // rule.unpaired_unit
        frame.start, frame.quantity = start, quantity
        warnings = frame.warnings
        for check in self.checks:
            value = fields[check.field]
            if check.above:
                if value > check.high:
                    warnings.append(text("above", what=check.what, value=value, high=check.high))
            elif not check.low <= value <= check.high:
                warnings.append(text("range", what=check.what, value=value, low=check.low, high=check.high))
        if rule.span and start + quantity > 0x10000:
            warnings.append(text("span", first=start, last=start + quantity - 1))
        count = rule.count
        if count is not None:
            of = self._value(count.of, fields, request)
            if of is not None and fields["byte_count"] != count.expected(of):
                warnings.append(text(count.text, count=fields["byte_count"], quantity=of))
        if rule.odd_count and fields["byte_count"] % 2:
            warnings.append(text("odd_count", count=fields["byte_count"]))
        if rule.coil is not None and fields[rule.coil] not in (COIL_ON, COIL_OFF):
            warnings.append(text("coil_value", value=fields[rule.coil]))
        if rule.echo is not None and request is not None:
            _check_echo(frame, fields, request, rule.echo)
        values = rule.values
        if values is not None:
            data = fields[values.field]
            kind = values.kind
            if kind is ValueKind.REGISTERS:
                # In bulk: a 125-register block makes no Register object until a view asks for one.
                frame.registers = RegisterList(start if values.start is None else fields[values.start], data)
            elif kind is ValueKind.BITS:
                # In bulk: a 2000-coil read makes no Bit object until a view asks for one.
                bits = len(data) * 8
                frame.bits = BitList(start, data, bits if quantity is None else min(quantity, bits))
            elif kind is ValueKind.REGISTER:
                frame.registers = [Register(start, data)]
            else:
                frame.bits = [Bit(start, 1 if data == COIL_ON else 0)]

    @staticmethod
    def _value(name: str | None, fields: Container, request: Frame | None) -> int | None:
        if name is None:
            return None
        if name.startswith(REQUEST_PREFIX):
            if request is None:
                return None
            return request.start if name == "request.start" else request.quantity
        return fields[name]  # type: ignore[no-any-return]


def _check_echo(frame: Frame, fields: Container, request: Frame, echo: Echo) -> None:
    """An answer that repeats its request (FC5/FC6's address and value, FC15/FC16's start and quantity)
    but differs from it wrote something else."""
    answered = request.fields
    differ = [name for name in echo.fields if answered[name] != fields[name]]
    if differ:
        frame.warnings.append(echo_text(differ if echo.names is Names.DIFFERING else list(echo.fields)))


def _request_of(frame: Frame) -> Frame | None:
    """The request a response answers, decoded; None when it is not in the capture or did not parse."""
    request = frame.request
    if request is None:
        return None
    decode_frame(request)
    return request if request.fields is not None else None


def _diagnostics(frame: Frame, fields: Container) -> None:
    frame.subfunction = fields["subfunction"]
    if fields["subfunction"] not in SPEC.diagnostics:
        frame.warnings.append(text("unknown_subfunction", subfunction=fields["subfunction"]))
    if len(fields["data"]) % 2:
        frame.warnings.append(text("odd_diagnostic_data"))


def _report_server_id_response(frame: Frame, fields: Container) -> None:
    indicator = fields["run_indicator"]
    if not isinstance(indicator, str):  # construct's Enum gives the name (a str) for 00 and FF only
        frame.warnings.append(text("run_indicator", value=int(indicator)))


def _mei_response(frame: Frame, fields: Container) -> None:
    if fields["mei_type"] != 14:
        return
    frame.objects = [
        DeviceObject(
            id=obj.id,
            name=SPEC.device_id_objects.get(obj.id, f"Object {obj.id}"),
            value=obj.value.decode("latin-1"),
        )
        for obj in fields["body"]["objects"]
    ]


# Handlers by name; the protocol table says which (function code, direction) uses which. Every name
# with a rule in data/modbus.toml [lift] is the generic lifter's (Lifter above); the named special
# cases below are the layouts no rule describes.
SPECIAL_HANDLERS = {
    "diagnostics": _diagnostics,
    "mei_response": _mei_response,
    "report_server_id_response": _report_server_id_response,
}


def _handlers() -> dict[Kind, dict[int, Handler]]:
    by_kind: dict[Kind, dict[int, Handler]] = {}
    for kind, names in table.by_kind("handler").items():
        limits = table.by_kind("limit")[kind]
        handlers: dict[int, Handler] = {}
        for code, name in names.items():
            rule = LIFTS.get(name)  # type: ignore[call-overload]
            handlers[code] = (
                Lifter(rule, limits.get(code), _request_of)  # type: ignore[arg-type]
                if rule is not None else SPECIAL_HANDLERS[name]  # type: ignore[index]
            )
        by_kind[kind] = handlers
    return by_kind


Handler = Callable[[Frame, Container], None]
HANDLERS: dict[str, object] = {**{name: LIFTS[name] for name in LIFTS}, **SPECIAL_HANDLERS}
_HANDLERS_BY_KIND = _handlers()
