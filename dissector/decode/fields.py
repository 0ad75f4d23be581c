"""Decoding: parse a paired frame's PDU with its grammar and lift out what users ask about.

Runs after pairing, because a response's registers are numbered from the request it answers. Spec
limits are checked here and reported as warnings, never raised.

The generic lifter (`lifter`) interprets the rule tables of data/modbus.toml [lift] (protocol/rules.py)
for every handler but the few named special cases below (diagnostics, the server id, FC43's code and objects);
each rule is prepared once (its limits looked up), so that a frame costs a few attribute tests. The
compiled engine (accel/_summary.c) and the plugin interpret the same rules from their generated tables.
Warnings come in the order the table's comment gives: checks, span, byte count, odd count, coil, echo, parts.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any
from dataclasses import dataclass

from construct import Container

from dissector.decode.fastpath import fast_parse
from dissector.decode.pairing import trusted_request
from dissector.protocol import table
from dissector.protocol.grammar import GrammarError, parse_pdu
from dissector.protocol.layouts import text_when_printable
from dissector.protocol.printable import bytes_text
from dissector.protocol.rules import (
    LIFTS, REQUEST_PREFIX, Echo, Lift, Names, Parts, Test, ValueKind, echo_text, range_text, text,
)
from dissector.model import Bit, BitList, DeviceObject, Frame, Kind, Register, RegisterList
from dissector.protocol.spec import SPEC, DiagnosticData

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
            frame.fields, frame.start, frame.quantity, frame.subfunction, warnings, notes = known
            if warnings:
                frame.warnings.extend(warnings)
            if notes:  # (FC8's data: what it asks, diagnostic_data)
                frame.notes.extend(notes)
            return frame
        before, noted = len(frame.warnings), len(frame.notes)
        _decode(frame, function, kind, frame.raw[1:-2])
        if frame.fields is not None and frame.registers is None and frame.bits is None and frame.objects is None:
            if len(_REQUESTS) >= _REQUESTS_MAX:
                _REQUESTS.clear()
            _REQUESTS[frame.raw] = (
                frame.fields, frame.start, frame.quantity, frame.subfunction, tuple(frame.warnings[before:]),
                tuple(frame.notes[noted:]),
            )
        return frame
    return _decode(frame, function, kind, frame.raw[1:-2] if rtu else frame.pdu)


# Requests without values (reads, diagnostics) repeat on a polled bus: what a request's bytes decode
# to is kept by those bytes (fields are never changed after decoding, so frames may share them).
# Bounded: cleared when full.
_REQUEST = Kind.REQUEST
_REQUESTS: dict[bytes, tuple[Container, int | None, int | None, int | None, tuple[str, ...], tuple[str, ...]]] = {}
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
    events = fields.get("events")
    if isinstance(events, bytes) and events:  # (FC12's log: each event named, the bytes kept as sent)
        fields["event_list"] = [comm_event(byte) for byte in events]
    trailing = fields.get("trailing")
    if trailing:
        frame.warnings.append(text("trailing", count=len(trailing)))
    if frame.broadcast and function in SPEC.not_broadcast:
        frame.warnings.append(text("not_broadcast", function=SPEC.function_name(function)))
    return frame


_EVENTS = SPEC.names["comm_event"]
_EVENT_KINDS = sorted(SPEC.names["comm_event_kind"].items(), reverse=True)  # (bit, name), the highest first


def event_kind(byte: int) -> int:
    """The kind of an FC12 event byte: the bit of [names.comm_event_kind] it sets (the highest first), 0 for
    none."""
    return next((bit for bit, _name in _EVENT_KINDS if bit and byte & bit), 0)


def comm_event(byte: int) -> dict[str, Any]:
    """One FC12 event byte (Application Protocol 6.13) as data/modbus.toml [names.comm_event*] name it:
    {"byte", "event", "flags"}; flags, the kind's bits set, named (None for an event of no kind). (The
    plugin's tree names the events by this: DATA.comm_events, codegen/display_lua.py)"""
    kind = event_kind(byte)
    if kind:
        flags = SPEC.names[f"comm_event_{kind}"]
        return {"byte": byte, "event": SPEC.names["comm_event_kind"][kind],
                "flags": [flag for mask, flag in sorted(flags.items()) if byte & mask]}
    return {"byte": byte, "event": _EVENTS.get(byte, _EVENT_KINDS[-1][1]), "flags": None}


def event_bit_lines() -> dict[int, list[tuple[int, str]]]:
    """By event kind (its bit), each bit of that kind as (mask, line): tshark -V's Modbus/TCP line of the bit
    with `{}` where the bit's value goes, twice (`.... ..{}. = Communication Error: {}`), the lowest bit
    first. -V (comm_event_bits) and the plugin's tree (DATA.event_bits, codegen/display_lua.py) fill them."""
    lines: dict[int, list[tuple[int, str]]] = {}
    for kind in SPEC.names["comm_event_kind"]:
        if kind:
            for mask, flag in sorted(SPEC.names[f"comm_event_{kind}"].items()):
                marks = ["{}" if mask & place else "." for place in (128, 64, 32, 16, 8, 4, 2, 1)]
                line = "".join(marks[:4]) + " " + "".join(marks[4:]) + f" = {flag}: {{}}"
                lines.setdefault(kind, []).append((mask, line))
    return lines


_EVENT_BITS = event_bit_lines()


def comm_event_bits(byte: int) -> list[str]:
    """Each bit of an FC12 event's kind, set or not, as tshark -V lists it (`.... ..0. = Communication
    Error: 0`); none for an event of no kind."""
    return [line.format(*[1 if byte & mask else 0] * 2) for mask, line in _EVENT_BITS.get(event_kind(byte), ())]


COIL_ON, COIL_OFF = 0xFF00, 0x0000
# The request a response answers, decoded, or None (not in the capture, or its data did not parse).
RequestOf = Callable[[Frame], "Frame | None"]


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


# Module globals: an Enum member looked up on its class costs a descriptor call per frame.
_REGISTERS, _BITS, _REGISTER = ValueKind.REGISTERS, ValueKind.BITS, ValueKind.REGISTER
_DIFFERING = Names.DIFFERING


def lifter(rule: Lift, limit: str | None, request_of: RequestOf) -> Handler:
    """One rule prepared as a handler: each value it names is resolved here once to a field name or the
    request's window, into the closure's variables, so that a frame costs a few tests (decoding is the
    Python path's hot loop; a closure is called faster than an object's __call__)."""
    checks: list[_Check] | None = []
    for check in rule.checks:
        name = check.limit or limit
        if name is None:
            raise ValueError(f"[lift.{rule.name}]: {check.field} has no limit (the layout gives none)")
        low, high = _limits(name)
        checks.append(_Check(check.what, check.field, low, high, check.test is Test.ABOVE))
    checks = checks or None  # most rules check nothing: no loop set up per frame
    quantity_const = rule.quantity if isinstance(rule.quantity, int) else None
    start_field, start_from_request = _source(rule.start, "request.start")
    quantity_field, quantity_from_request = _source(
        rule.quantity if isinstance(rule.quantity, str) else None, "request.quantity"
    )
    count = rule.count
    count_field, count_from_request = _source(count.of if count else None, "request.quantity")
    from_request = (start_from_request or quantity_from_request or count_from_request or rule.echo is not None
                    or (rule.parts is not None and rule.parts.request is not None))
    unpaired, span, odd_count, coil, echo, values = (
        rule.unpaired_unit, rule.span, rule.odd_count, rule.coil, rule.echo, rule.values
    )
    padding = rule.padding if values is not None else None
    parts = None if rule.parts is None else (rule.parts, _part_checks(rule.parts))
    write_window = rule.write_window if span else None

    def lift(frame: Frame, fields: Container) -> None:
        request = request_of(frame) if from_request else None
        if start_from_request:
            start = None if request is None else request.start
        else:
            start = None if start_field is None else fields[start_field]
        if quantity_const is not None:
            quantity = quantity_const
        elif quantity_from_request:
            quantity = None if request is None else request.quantity
            if quantity is None and unpaired is not None:
                given = fields["byte_count"]
                if unpaired == 0:  # bits: no byte, no bit; a byte holds 1 to 8 of them
                    quantity = 0 if given == 0 else None
                elif given % unpaired == 0:
                    quantity = given // unpaired
        else:
            quantity = None if quantity_field is None else fields[quantity_field]
        frame.start, frame.quantity = start, quantity
        if start_from_request and request is None and frame.request is not None and not frame.request.crc_ok:
            frame.notes.append(text("request_damaged", check="LRC" if frame.mode == "ascii" else "CRC"))
        for check in checks or ():
            value = fields[check.field]
            if check.above:
                if value > check.high:
                    frame.warnings.append(text("above", what=check.what, value=value, high=check.high))
            elif not check.low <= value <= check.high:
                frame.warnings.append(range_text(check.what, value, check.low, check.high))
        if span and start + quantity > 0x10000:
            frame.warnings.append(text("span", first=start, last=start + quantity - 1))
        if write_window is not None:
            first, many = fields[write_window[0]], fields[write_window[1]]
            if first + many > 0x10000:
                frame.warnings.append(text("span", first=first, last=first + many - 1))
        if count is not None:
            if count_from_request:  # the request's quantity: the window's already when it is the request's
                of = None if request is None else quantity if quantity_from_request else request.quantity
            else:
                of = fields[count_field]
            if of is not None:
                given = fields["byte_count"]
                if given != count.plus + (of * count.unit if count.unit else (of + 7) >> 3):  # Count.expected
                    frame.warnings.append(text(count.text, count=given, quantity=of))
                elif padding is not None and of & 7:  # (the last byte's bits past the quantity)
                    unused = fields[values.field][-1] >> (of & 7) << (of & 7)
                    if unused:
                        frame.warnings.append(text(padding, quantity=of, mask=unused))
        if odd_count and fields["byte_count"] % 2:
            frame.warnings.append(text("odd_count", count=fields["byte_count"]))
        if coil is not None and fields[coil] not in (COIL_ON, COIL_OFF):
            frame.warnings.append(text("coil_value", value=fields[coil]))
        if request is not None and echo is not None:
            _check_echo(frame, fields, request, echo)
        if parts is not None:
            _check_parts(frame, fields, request, *parts)
        if values is not None:
            data = fields[values.field]
            kind = values.kind
            if kind is _REGISTERS:
                if values.most is not None and len(data) > fields[values.most]:
                    data = _past_quantity(frame, data, fields[values.most], values.past)  # type: ignore[arg-type]
                # In bulk: a 125-register block makes no Register object until a view asks for one.
                frame.registers = RegisterList(start if values.start is None else fields[values.start], data)
            elif kind is _BITS:
                # In bulk: a 2000-coil read makes no Bit object until a view asks for one.
                bits = len(data) * 8
                frame.bits = BitList(start, data, bits if quantity is None else min(quantity, bits))
            elif kind is _REGISTER:
                frame.registers = [Register(start, data)]
            elif data in (COIL_ON, COIL_OFF):  # (any other value is illegal and sets nothing, 6.5)
                frame.bits = [Bit(start, 1 if data == COIL_ON else 0)]

    lift.__qualname__ = f"lifter[{rule.name}]"
    return lift


def _past_quantity(frame: Frame, data: list[int], quantity: int, past: str) -> list[int]:
    """The values a write's quantity takes; the words its byte count carries past them are no register
    written: warned by their bytes (text `past`)."""
    extra = " ".join(f"{word >> 8:02x} {word & 0xFF:02x}" for word in data[quantity:])
    frame.warnings.append(text(past, count=2 * (len(data) - quantity), quantity=quantity, data=extra))
    return data[:quantity]


def _source(name: str | None, window: str) -> tuple[str | None, bool]:
    """(the frame's field, from the request's window) for a rule value; `window` is the one allowed."""
    if name is None or not name.startswith(REQUEST_PREFIX):
        return name, False
    if name != window:
        raise ValueError(f"{name!r}: only {window!r} can be taken from the request here")
    return None, True


def _check_echo(frame: Frame, fields: Container, request: Frame, echo: Echo) -> None:
    """An answer that repeats its request (FC5/FC6's address and value, FC15/FC16's start and quantity)
    but differs from it wrote something else."""
    if echo.data:  # (FC21: the whole data, after the function code)
        if frame.pdu[1:] != request.pdu[1:]:
            frame.warnings.append(echo_text(["data"]))
        return
    answered = request.fields
    differ = [name for name in echo.fields if answered[name] != fields[name]]
    if differ:
        frame.warnings.append(echo_text(differ if echo.names is _DIFFERING else list(echo.fields)))


def _part_checks(parts: Parts) -> list[_Check]:
    return [_Check(check.what, check.field, *_limits(check.limit), check.test is Test.ABOVE)  # type: ignore[arg-type]
            for check in parts.checks]


def _check_parts(frame: Frame, fields: Container, request: Frame | None, parts: Parts, checks: list[_Check]) -> None:
    """Each part of a records field (FC20's sub-requests and sub-responses, FC21's records) by its checks,
    and an answer's against the request's part in its place (FC20: the record length asked)."""
    items = fields[parts.field]
    for index, item in enumerate(items, start=1):
        for check in checks:
            value = item[check.field]
            if value > check.high or (not check.above and value < check.low):
                what = f"{parts.name} {index}'s {check.what}"
                frame.warnings.append(text("above", what=what, value=value, high=check.high) if check.above
                                      else range_text(what, value, check.low, check.high))
    if request is None or parts.request is None:
        return
    asked = request.fields[parts.request]
    if len(asked) != len(items):
        frame.warnings.append(text("part_count", part=parts.name, count=len(items), quantity=len(asked)))
    length = parts.length
    if length is not None:
        for index, (item, part) in enumerate(zip(items, asked), start=1):
            given = item[length.field]
            if given != length.plus + length.unit * part[length.of]:
                frame.warnings.append(text(length.text, part=parts.name, index=index, count=given,
                                           held=length.held(given), quantity=part[length.of]))


def _request_of(frame: Frame) -> Frame | None:
    """The request a response answers, decoded; None when it is not in the capture, failed its check
    (pairing.trusted_request) or did not parse."""
    request = trusted_request(frame)
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
    elif frame.kind is _REQUEST:
        rule = SPEC.diagnostic_data.get(fields["subfunction"])
        if rule is not None:
            _diagnostic_data(frame, fields["subfunction"], bytes(fields["data"]), rule)
    elif fields["subfunction"] in SPEC.diagnostic_echoes:
        # An answer that repeats its request's data ([diagnostic_answers]) but differs answered other data.
        request = _request_of(frame)  # (the pairing had it repeat the sub-function)
        if request is not None and bytes(request.fields["data"]) != bytes(fields["data"]):
            frame.warnings.append(echo_text(["data"]))


def _diagnostic_data(frame: Frame, subfunction: int, data: bytes, rule: DiagnosticData) -> None:
    """An FC8 request's data word as the spec has it for its sub-function ([diagnostic_data]): what it asks
    (a note), or a warning where the spec allows another."""
    word = int.from_bytes(data, "big") if len(data) == 2 else None
    if rule.data is not None:
        meaning = rule.data.get(word) if word is not None else None
        if meaning is None:
            allowed = " or ".join(f"{value:04X}" for value in sorted(rule.data))
        else:
            if meaning:
                frame.notes.append(meaning)
            return
    elif word is not None and word & 0xFF == 0:
        code = word >> 8
        name = (rule.names or {}).get(code)
        if name is None and 0x20 < code < 0x7F:
            name = f"'{chr(code)}'"
        frame.notes.append(
            text("diagnostic_character", what=rule.character, character=name, code=code) if name is not None
            else text("diagnostic_byte", what=rule.character, code=code))
        return
    else:
        allowed = text("character_then_00")
    frame.warnings.append(text("diagnostic_data", data=data.hex().upper() or "(none)", subfunction=subfunction,
                               allowed=allowed))


_RUN_VALUES = frozenset(SPEC.names["run_indicator"])  # 00 OFF, FF ON


def _report_server_id_response(frame: Frame, fields: Container) -> None:
    """The spec's server id is device specific in length (Application Protocol 6.17), the run indicator the
    byte after it: the layout reads a one-byte id (libmodbus); a longer id (pymodbus: a name, the run
    indicator last) has a run indicator further on. Where the byte after a one-byte id is no run indicator
    (00 OFF, FF ON) and a later one is, the fields are read again with the id up to the first of them (text
    where printable, as additional data is): `server id 'Pymodbus', run ON`, not the one-byte reading's
    wrong split `server id 80, run 121, 7 bytes`; warned, as the length is read from the bytes. Only an
    answer with no 00 or FF after its first byte has none where any id length puts it; a byte count of 1
    (the layout's ?(byte_count-1)) holds the id alone, the spec's run indicator is missing; 0 neither."""
    indicator = fields["run_indicator"]
    if fields["server_id"] is None:  # (byte count 0: the layout's ?(byte_count))
        frame.warnings.append(text("no_server_id", count=fields["byte_count"]))
    elif indicator is None:
        frame.warnings.append(text("no_run_indicator", count=fields["byte_count"]))
    elif not isinstance(indicator, str):  # construct's Enum gives the name (a str) for 00 and FF only
        data = frame.pdu[2 : 2 + fields["byte_count"]]  # (after the function code and byte count)
        end = next((at for at in range(1, len(data)) if data[at] in _RUN_VALUES), None)
        if end is None:
            frame.warnings.append(text("run_indicator", value=int(indicator)))
        else:  # (the id runs to the first 00 or FF after its first byte: pymodbus's name, then FF)
            fields["server_id"] = text_when_printable(data[:end])
            fields["run_indicator"] = SPEC.names["run_indicator"][data[end]]
            fields["additional_data"] = text_when_printable(data[end + 1 :])
            frame.warnings.append(text("server_id_read_longer", count=end, value=int(indicator)))


_DEVICE_ID_CODES = _limits("device_id_code")
_MANDATORY_OBJECTS = ", ".join(SPEC.device_id_objects[id] for id in range(_limits("device_id_mandatory")[0],
                                                                           _limits("device_id_mandatory")[1] + 1))


def _mei_request(frame: Frame, fields: Container) -> None:
    if fields["mei_type"] != table.DEVICE_ID:
        return
    code = fields["body"]["read_code"]
    low, high = _DEVICE_ID_CODES
    if not low <= code <= high:
        frame.warnings.append(text("device_id_code", code=code, low=low, high=high))


def _mei_response(frame: Frame, fields: Container) -> None:
    if fields["mei_type"] != table.DEVICE_ID:
        return
    frame.objects = [
        DeviceObject(
            id=obj.id,
            name=SPEC.device_id_objects.get(obj.id) or text("other_object", id=obj.id),
            # Objects 0..6 are ASCII strings (Application Protocol 6.21), the private ones the device's own:
            # as a bytes literal's text (printable.bytes_text: `\xc3` the byte C3, `\\` a backslash; never a
            # guess at a charset; the bytes: fields.body), shown between single quotes
            value=bytes_text(obj.value),
        )
        for obj in fields["body"]["objects"]
    ]
    # (a count the frame does not hold: the objects there are shown, the layout's array stops at its end)
    declared = fields["body"]["object_count"]
    if len(frame.objects) < declared:
        frame.warnings.append(text("object_count", count=declared, present=len(frame.objects)))
    if not frame.objects:  # (the basic objects are mandatory: a server sends one at least)
        frame.warnings.append(text("no_objects", names=_MANDATORY_OBJECTS))


# Handlers by name; the protocol table says which (function code, direction) uses which. Every name
# with a rule in data/modbus.toml [lift] is the generic lifter's (`lifter` above); the named special
# cases below are the layouts no rule describes.
SPECIAL_HANDLERS = {
    "diagnostics": _diagnostics,
    "mei_request": _mei_request,
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
                lifter(rule, limits.get(code), _request_of)  # type: ignore[arg-type]
                if rule is not None else SPECIAL_HANDLERS[name]  # type: ignore[index]
            )
        by_kind[kind] = handlers
    return by_kind


Handler = Callable[[Frame, Container], None]
HANDLERS: dict[str, object] = {**{name: LIFTS[name] for name in LIFTS}, **SPECIAL_HANDLERS}
_HANDLERS_BY_KIND = _handlers()
