"""Short human descriptions of a decoded frame, shared by the summary line and the detail tree."""
from __future__ import annotations

import re

from dissector.model import DeviceObject, Frame, Kind, Register
from dissector.protocol.spec import SPEC
from dissector.protocol.table import FUNCTIONS

MAX_VALUES = 6  # register values a summary shows (the compiled engine reads these three in _tables.h)
MAX_BITS = 32  # bits a summary shows
MAX_FIFO_VALUES = 8  # FIFO values a summary shows
_FUNCTION_NAMES = SPEC.functions


def address_text(address: int | None, label: str | None = None) -> str:
    if label is not None:
        return label
    return "?" if address is None else str(address)


def span_text(frame: Frame) -> str:
    """`8400..8402 (3)` or `9001` for the frame's start and quantity; `8400 (0)` for a quantity of 0 (no
    register: the start the request names, never a range wrapped back to 8399)."""
    start, quantity = frame.start, frame.quantity
    if frame.span_label is not None:
        return frame.span_label if quantity is None or quantity == 1 else f"{frame.span_label} ({quantity})"
    if start is None:
        return f"({quantity})" if quantity is not None else ""
    first = _label_for(frame, start)
    if quantity is None or quantity == 1:
        return first
    if quantity == 0:
        return f"{first} (0)"
    last = _label_for(frame, (start + quantity - 1) & 0xFFFF)
    return f"{first}..{last} ({quantity})"


def plain_span(start: int, quantity: int | None) -> str:
    """`8400..8402 (3)`, `8400` (one or no quantity), `8400 (0)` (no register: nothing wraps)."""
    if quantity is None or quantity == 1:
        return str(start)
    if quantity == 0:
        return f"{start} (0)"
    return f"{start}..{start + quantity - 1} ({quantity})"


def _label_for(frame: Frame, address: int) -> str:
    registers = frame.registers
    if not registers or registers[0].label is None:
        return str(address)
    for register in registers:
        if register.address == address and register.label:
            return register.label
    return str(address)


def register_text(register: Register, index: int = 0) -> str:
    """`CHCF=IO (I/O profile)`, `8400=non-existent`, or `8401=3` without a profile.

    A response whose request is not in the capture has no addresses: its values show as `?+index`.
    """
    code = register.code
    if code is None and register.status is None and register.text is None and register.label is None:
        if register.address is None:
            return f"?+{index}={register.value}"
        return f"{register.address}={register.value}"
    if register.address is None:
        name = f"?+{index}"
    else:
        name = code or address_text(register.address, register.label)
    status = register.status
    if status is not None and status not in ("ok",):
        if status == "ambiguous":
            return f"{name}={register.text or register.value} (16#8000: ambiguous)"
        return f"{name}={status}"
    if register.text is not None:
        return f"{name}={register.text}"
    return f"{name}={register.value}"


def values_text(frame: Frame) -> str:
    registers = frame.registers or []
    if any(register.words == 0 for register in registers):
        # A 32-bit value is one value over two registers: its second register is not listed again.
        registers = [register for register in registers if register.words != 0]
    parts = [register_text(register, index) for index, register in enumerate(registers[:MAX_VALUES])]
    if len(registers) > MAX_VALUES:
        parts.append(f"… (+{len(registers) - MAX_VALUES})")
    return " ".join(parts)


def bits_text(frame: Frame) -> str:
    bits = frame.bits or []
    text = "".join(str(bit.value) for bit in bits[:MAX_BITS])
    if len(bits) > MAX_BITS:
        text += f"… (+{len(bits) - MAX_BITS})"
    return text


def function_label(function: int, function_text: str | None = None) -> str:
    """The function as the Info column names it: the device profile's word, else the spec's."""
    return function_text or _FUNCTION_NAMES.get(function) or SPEC.function_name(function)


def info_text(frame: Frame) -> str:
    """The Info column: what was asked or answered, in a few words."""
    function = frame.function
    name = function_label(function, frame.function_text)
    if frame.kind is Kind.EXCEPTION:
        code = frame.exception_code
        # The spec's name always; what it means on the device is said once, in a note.
        return f"{name}: exception {code if code is not None else '?'} ({SPEC.exception_name(code)})"
    fields = frame.fields
    if fields is None:
        return f"{name} (malformed)"
    request = frame.kind is Kind.REQUEST
    describe = _DESCRIBERS.get(function)
    detail = describe(frame, request) if describe else f"{len(frame.pdu) - 1} bytes of data"
    return f"{name} {detail}".rstrip()


def _read(frame: Frame, request: bool) -> str:
    if request:
        return span_text(frame)
    if frame.bits is not None:
        return f"{span_text(frame)}: {bits_text(frame)}".lstrip()
    return f"{span_text(frame)}: {values_text(frame)}".lstrip(": ")


def _write_single_coil(frame: Frame, request: bool) -> str:
    value = frame.fields.value
    state = {0xFF00: "ON", 0x0000: "OFF"}.get(value, f"0x{value:04X}")
    return f"{span_text(frame)} = {state}"


def _write_single_register(frame: Frame, request: bool) -> str:
    registers = frame.registers or []
    if registers and (registers[0].code or registers[0].text):
        return f"{span_text(frame)} {register_text(registers[0])}"
    return f"{span_text(frame)} = {frame.fields.value}"


def _diagnostics(frame: Frame, request: bool) -> str:
    sub = frame.subfunction if frame.subfunction is not None else -1
    sub_name = frame.subfunction_text or SPEC.diagnostics.get(sub, "unknown sub-function")
    data = frame.fields.data
    if len(data) == 2:
        value = int.from_bytes(data, "big")
        return f"{sub:02X}h {sub_name} = {value}"
    return f"{sub:02X}h {sub_name}" + (f" data {_hex_preview(data)}" if data else "")


MAX_DATA_BYTES = 16  # bytes of echoed data a summary shows (-V and JSON show them all)


def _hex_preview(data: bytes) -> str:
    if len(data) <= MAX_DATA_BYTES:
        return data.hex()
    return f"{data[:MAX_DATA_BYTES].hex()}… (+{len(data) - MAX_DATA_BYTES} bytes)"


def _write_multiple(frame: Frame, request: bool) -> str:
    if request and frame.registers is not None:
        return f"{span_text(frame)}: {values_text(frame)}"
    if request and frame.bits is not None:
        return f"{span_text(frame)}: {bits_text(frame)}"
    return f"{span_text(frame)} written"


def _comm_event_counter(frame: Frame, request: bool) -> str:
    if request:
        return ""
    return f"status 0x{frame.fields.status:04X}, {frame.fields.event_count} events"


def _mask_write(frame: Frame, request: bool) -> str:
    fields = frame.fields
    return f"{fields.address} AND 0x{fields.and_mask:04X} OR 0x{fields.or_mask:04X}"


def _read_write(frame: Frame, request: bool) -> str:
    fields = frame.fields
    if request:
        start, quantity = fields["read_start"], fields["read_quantity"]
        if frame.span_label is not None:  # PLC style: the read window as its answer shows it (43202..43203)
            return f"read {span_text(frame)}, write {values_text(frame)}"
        return f"read {plain_span(start, quantity)}, write {values_text(frame)}"
    return f"{span_text(frame)}: {values_text(frame)}"


def _fifo(frame: Frame, request: bool) -> str:
    if request:
        return f"pointer {frame.fields.address}"
    return f"{frame.fields.fifo_count} values: {' '.join(map(str, frame.fields['values'][:MAX_FIFO_VALUES]))}"


def _mei(frame: Frame, request: bool) -> str:
    fields = frame.fields
    mei = SPEC.mei_types.get(fields.mei_type, f"MEI {fields.mei_type}")
    if fields.mei_type != 14:
        return mei
    code = SPEC.device_id_codes.get(fields.body.read_code, str(fields.body.read_code))
    if request:
        return f"{mei}, {code}, from object {fields.body.object_id}"
    objects = " ".join(f"{obj.name}={_object_value(obj)}" for obj in frame.objects or [])
    return f"{mei}, {code}: {objects}"


_VERSION = re.compile(r"V\d+\.\d+")


def _object_value(obj: DeviceObject) -> str:
    """The value as sent; a revision the profile decoded (`0201` -> `V2.1`) shows decoded."""
    if obj.text is not None and _VERSION.fullmatch(obj.text):
        return obj.text
    return repr(obj.value)


def _simple(frame: Frame, request: bool) -> str:
    if request:
        return ""
    fields = frame.fields
    if "status" in fields and isinstance(fields.status, int):
        return f"status 0x{fields.status:02X}"
    if "data" in fields:
        return f"{len(fields.data)} bytes"
    return ""


def _report_server_id(frame: Frame, request: bool) -> str:
    fields = frame.fields
    if request or "server_id" not in fields:
        return ""
    data = fields.additional_data
    text = repr(data) if isinstance(data, str) else f"{len(data)} bytes"
    return f"server id {fields.server_id}, run {fields.run_indicator}, {text}"


def _file_record(frame: Frame, request: bool) -> str:
    fields = frame.fields
    groups = fields.get("subrequests") or fields.get("subresponses") or fields.get("records") or []
    return f"{len(groups)} record group(s)"


# Describers by name; the protocol table says which function code uses which (table.Function.text).
_BY_NAME = {
    "read": _read,
    "write_single_coil": _write_single_coil,
    "write_single_register": _write_single_register,
    "simple": _simple,
    "diagnostics": _diagnostics,
    "comm_event_counter": _comm_event_counter,
    "write_multiple": _write_multiple,
    "report_server_id": _report_server_id,
    "file_record": _file_record,
    "mask_write": _mask_write,
    "read_write": _read_write,
    "fifo": _fifo,
    "mei": _mei,
}
_DESCRIBERS = {entry.code: _BY_NAME[entry.text] for entry in FUNCTIONS}
