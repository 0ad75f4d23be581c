"""Decoding: parse a paired frame's PDU with its grammar and lift out what users ask about.

Runs after pairing, because a response's registers are numbered from the request it answers. Spec
limits are checked here and reported as warnings, never raised.
"""
from __future__ import annotations

from construct import Container

from dissector.decode.fastpath import fast_parse
from dissector.protocol import table
from dissector.protocol.grammar import GrammarError, parse_pdu
from dissector.model import Bit, BitList, DeviceObject, Frame, Kind, Register, RegisterList
from dissector.protocol.spec import SPEC

_LIMITS = SPEC.limits
_MAX_SLAVE = int(SPEC.limits["max_slave"])  # type: ignore[call-overload]  # 248..255 reserved


def _check_range(frame: Frame, what: str, value: int, limit_name: str) -> None:
    low, high = _LIMITS[limit_name]  # type: ignore[misc]
    if not low <= value <= high:
        frame.warnings.append(f"{what} {value} outside the spec's {low}..{high}")


def _check_span(frame: Frame, start: int, quantity: int) -> None:
    if start + quantity > 0x10000:
        frame.warnings.append(f"addresses {start}..{start + quantity - 1} run past 65535")


def _registers(start: int | None, values: list[int]) -> RegisterList:
    # In bulk: a 125-register block makes no Register object until a view asks for one (model.RegisterList).
    return RegisterList(start, values)


def _bits(start: int | None, packed: bytes, quantity: int | None) -> BitList:
    # In bulk: a 2000-coil read makes no Bit object until a view asks for one (model.BitList).
    count = len(packed) * 8 if quantity is None else min(quantity, len(packed) * 8)
    return BitList(start, packed, count)


def _ceil_bytes(bits: int) -> int:
    return (bits + 7) // 8


def decode_frame(frame: Frame) -> Frame:
    """Fill frame.fields, start, quantity, registers, bits, objects and warnings. Idempotent."""
    if frame.decoded:
        return frame
    frame.decoded = True
    if frame.slave > _MAX_SLAVE:
        frame.warnings.append(f"slave address {frame.slave} is reserved (248..255 are no device's)")
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
            frame.warnings.append(f"malformed {frame.kind}: {error}")
            return frame
    frame.fields = fields
    if kind is Kind.EXCEPTION:
        code = fields["exception_code"]
        if code not in SPEC.exceptions:
            frame.warnings.append(f"exception code {code} is not defined by the spec")
    else:
        handler = _HANDLERS_BY_KIND[kind].get(function)
        if handler is not None:
            handler(frame, fields)
    trailing = fields.get("trailing")
    if trailing:
        frame.warnings.append(f"{len(trailing)} unexpected bytes after the data")
    if frame.broadcast and function in SPEC.not_broadcast:
        frame.warnings.append(f"{SPEC.function_name(function)} cannot be broadcast (slave 0)")
    return frame




def _request_fields(frame: Frame) -> Container | None:
    request = frame.request
    if request is None:
        return None
    decode_frame(request)
    return request.fields


def _read_request(frame: Frame, fields: Container) -> None:
    frame.start, frame.quantity = fields["start"], fields["quantity"]
    _check_range(frame, "quantity", fields["quantity"], _LIMIT_BY_KIND[Kind.REQUEST][frame.function])
    _check_span(frame, fields["start"], fields["quantity"])


def _read_bits_response(frame: Frame, fields: Container) -> None:
    request = _request_fields(frame)
    start = quantity = None
    if request is not None:
        start, quantity = request["start"], request["quantity"]
        if fields["byte_count"] != _ceil_bytes(quantity):
            frame.warnings.append(
                f"byte count {fields['byte_count']} disagrees with the {quantity} bits asked"
            )
    frame.start, frame.quantity = start, quantity
    frame.bits = _bits(start, fields["status"], quantity)


def _read_registers_response(frame: Frame, fields: Container) -> None:
    request = _request_fields(frame)
    start = None
    if request is not None:
        if frame.function == 23:
            start, quantity = request["read_start"], request["read_quantity"]
        else:
            start, quantity = request["start"], request["quantity"]
        if fields["byte_count"] != 2 * quantity:
            frame.warnings.append(
                f"byte count {fields['byte_count']} disagrees with the {quantity} registers asked"
            )
        frame.quantity = quantity
    elif fields["byte_count"] % 2 == 0:
        frame.quantity = fields["byte_count"] // 2
    if fields["byte_count"] % 2:
        frame.warnings.append(f"odd byte count {fields['byte_count']} for 16-bit registers")
    frame.start = start
    frame.registers = _registers(start, fields["values"])


def _check_echo(frame: Frame, fields: Container) -> None:
    """An FC5/FC6 answer echoes its request: one that does not wrote something else (as FC15/FC16's
    start and quantity are checked)."""
    request = _request_fields(frame)
    if request is None:
        return
    differ = [name for name in ("address", "value") if request[name] != fields[name]]
    if differ:
        verb = "differs" if len(differ) == 1 else "differ"
        frame.warnings.append(f"the response's {' and '.join(differ)} {verb} from the request's")


def _write_single_coil(frame: Frame, fields: Container) -> None:
    frame.start, frame.quantity = fields["address"], 1
    if fields["value"] not in (0xFF00, 0x0000):
        frame.warnings.append(f"coil value 0x{fields['value']:04X} is neither 0xFF00 (on) nor 0x0000 (off)")
    _check_echo(frame, fields)
    frame.bits = [Bit(fields["address"], 1 if fields["value"] == 0xFF00 else 0)]


def _write_single_register(frame: Frame, fields: Container) -> None:
    frame.start, frame.quantity = fields["address"], 1
    _check_echo(frame, fields)
    frame.registers = [Register(fields["address"], fields["value"])]


def _diagnostics(frame: Frame, fields: Container) -> None:
    frame.subfunction = fields["subfunction"]
    if fields["subfunction"] not in SPEC.diagnostics:
        frame.warnings.append(f"diagnostic sub-function {fields['subfunction']} is not defined by the spec")
    if len(fields["data"]) % 2:
        frame.warnings.append("diagnostic data is not a whole number of words")


def _write_coils_request(frame: Frame, fields: Container) -> None:
    frame.start, frame.quantity = fields["start"], fields["quantity"]
    _check_range(frame, "quantity", fields["quantity"], _LIMIT_BY_KIND[Kind.REQUEST][frame.function])
    _check_span(frame, fields["start"], fields["quantity"])
    if fields["byte_count"] != _ceil_bytes(fields["quantity"]):
        frame.warnings.append(
            f"byte count {fields['byte_count']} disagrees with the quantity {fields['quantity']}"
        )
    frame.bits = _bits(fields["start"], fields["status"], fields["quantity"])


def _write_registers_request(frame: Frame, fields: Container) -> None:
    frame.start, frame.quantity = fields["start"], fields["quantity"]
    _check_range(frame, "quantity", fields["quantity"], _LIMIT_BY_KIND[Kind.REQUEST][frame.function])
    _check_span(frame, fields["start"], fields["quantity"])
    if fields["byte_count"] != 2 * fields["quantity"]:
        frame.warnings.append(
            f"byte count {fields['byte_count']} disagrees with the quantity {fields['quantity']}"
        )
    frame.registers = _registers(fields["start"], fields["values"])


def _write_multiple_response(frame: Frame, fields: Container) -> None:
    frame.start, frame.quantity = fields["start"], fields["quantity"]
    request = _request_fields(frame)
    if request is not None and (request["start"], request["quantity"]) != (fields["start"], fields["quantity"]):
        frame.warnings.append("the response's start and quantity differ from the request's")


def _mask_write(frame: Frame, fields: Container) -> None:
    frame.start, frame.quantity = fields["address"], 1


def _read_write_request(frame: Frame, fields: Container) -> None:
    frame.start, frame.quantity = fields["read_start"], fields["read_quantity"]
    _check_range(frame, "read quantity", fields["read_quantity"], "rw_read")
    _check_range(frame, "write quantity", fields["write_quantity"], "rw_write")
    if fields["byte_count"] != 2 * fields["write_quantity"]:
        frame.warnings.append(
            f"byte count {fields['byte_count']} disagrees with the write quantity {fields['write_quantity']}"
        )
    frame.registers = _registers(fields["write_start"], fields["values"])


def _fifo_request(frame: Frame, fields: Container) -> None:
    frame.start = fields["address"]


def _fifo_response(frame: Frame, fields: Container) -> None:
    request = _request_fields(frame)
    if request is not None:
        frame.start = request["address"]
    frame.quantity = fields["fifo_count"]
    if fields["fifo_count"] > _LIMITS["fifo_count"][1]:  # type: ignore[index]
        frame.warnings.append(f"FIFO count {fields['fifo_count']} above the spec's 31")
    if fields["byte_count"] != 2 + 2 * fields["fifo_count"]:
        frame.warnings.append(f"byte count {fields['byte_count']} disagrees with the FIFO count")


def _report_server_id_response(frame: Frame, fields: Container) -> None:
    indicator = fields["run_indicator"]
    if not isinstance(indicator, str):  # construct's Enum gives the name (a str) for 00 and FF only
        frame.warnings.append(f"run indicator 0x{int(indicator):02X} is neither 0x00 (OFF) nor 0xFF (ON)")


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


# Handlers by name; the protocol table says which (function code, direction) uses which.
HANDLERS = {
    "read_request": _read_request,
    "read_bits_response": _read_bits_response,
    "read_registers_response": _read_registers_response,
    "write_single_coil": _write_single_coil,
    "write_single_register": _write_single_register,
    "diagnostics": _diagnostics,
    "write_coils_request": _write_coils_request,
    "write_registers_request": _write_registers_request,
    "write_multiple_response": _write_multiple_response,
    "mask_write": _mask_write,
    "read_write_request": _read_write_request,
    "fifo_request": _fifo_request,
    "fifo_response": _fifo_response,
    "mei_response": _mei_response,
    "report_server_id_response": _report_server_id_response,
}

_HANDLERS_BY_KIND: dict[Kind, dict[int, object]] = {
    kind: {code: HANDLERS[name] for code, name in names.items()}  # type: ignore[index]
    for kind, names in table.by_kind("handler").items()
}
# The spec limit each handler checks a quantity against, from the table.
_LIMIT_BY_KIND = table.by_kind("limit")
