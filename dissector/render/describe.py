"""Short human descriptions of a decoded frame, shared by the summary line and the detail tree."""
from __future__ import annotations

import re
import tomllib
from functools import cache
from importlib import resources
from typing import Any, Callable

from dissector.model import DeviceObject, Frame, Kind, Register
from dissector.protocol.spec import SPEC
from dissector.protocol.table import FUNCTIONS, Data

MAX_VALUES = 6  # register values a summary shows (the compiled engine reads these three in _tables.h)
MAX_BITS = 32  # bits a summary shows
MAX_FIFO_VALUES = 8  # FIFO values a summary shows
# An FC8 sub-function neither the spec nor the profile names, in the Info text and -V (the plugin's too:
# codegen/fields_lua.py info_forms)
UNKNOWN_SUBFUNCTION = "unknown sub-function"
_FUNCTION_NAMES = SPEC.functions

@cache
def pdu_fields() -> dict[str, Any]:
    """data/pdu_fields.toml, read once: the plugin's fields of each PDU field, which -V and --json follow."""
    return tomllib.loads(resources.files("dissector").joinpath("data/pdu_fields.toml").read_text(encoding="utf-8"))


@cache
def value_names() -> dict[str, dict[int, str]]:
    """{PDU field key: its values' names} (FC43's `mei_type`, `read_code`, `conformity`): the `values` that
    data/pdu_fields.toml gives the plugin's fields, so vw3-decode -V and --json name them as its tree does. A
    table is the spec's (data/modbus.toml [mei_types], [device_id_codes]) or one of its [names]."""
    tables = {"mei_types": SPEC.mei_types, "device_id_codes": SPEC.device_id_codes, **SPEC.names}
    names: dict[str, dict[int, str]] = {}
    for entry in pdu_fields()["field"]:
        if "values" in entry:
            for pdu in entry["pdu"]:
                names[pdu.split(".")[1]] = tables[entry["values"]]
    return names


def named_value(table: dict[int, str], value: int) -> str:
    """`Read Device Identification (14)`, `Unknown (9)`: a named value as Wireshark writes it."""
    return f"{table.get(value, 'Unknown')} ({value})"



def count_text(count: int, noun: str) -> str:
    """`1 byte`, `2 bytes`: a count and its noun, singular for one (the plugin's tree.lua count_text)."""
    return f"{count} {noun}" if count == 1 else f"{count} {noun}s"


def address_text(address: int | None, label: str | None = None) -> str:
    if label is not None:
        return label
    return "?" if address is None else str(address)


def span_text(frame: Frame) -> str:
    """`8400..8402 (3)` or `9001` for the frame's start and quantity; `8400 (0)` for a quantity of 0 (no
    register: the start the request names, never a range wrapped back to 8399). A window past 65535 shows
    its last address as asked (`65535..65539 (5)`), as the warning `span` says it, never wrapped to 3."""
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
    last = _label_for(frame, start + quantity - 1)
    return f"{first}..{last} ({quantity})"


def plain_span(start: int, quantity: int | None) -> str:
    """`8400..8402 (3)`, `8400` (one or no quantity), `8400 (0)` (no register: nothing wraps), as span_text."""
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


# The Info column of each form, as data (the C engine's info_text interprets it too, from the steps
# codegen/c_rules.py writes into accel/_tables.h): texts, and steps with the fields they print by name and a
# step's number (hex: its least digits). "none": not written by the C engine (handed over); "python": the
# texts come from the Python stages there (table.Compiled.texts) and from a describer of _BY_NAME here.
TEXT_FORMS: dict[str, list[str | tuple[str | int, ...]]] = {
    "none": [("none",)],
    "name": [("unspace",)],  # the name alone: the space after it taken back (rstrip)
    "span": [("span",)],
    "bits": [("span",), ": ", ("bits",)],
    "values": [("span",), ": ", ("values",)],
    "coil": [("label",), ("coil", "value")],
    "single": [("label",), ("single", "value")],
    "written": [("span",), " written"],
    "status": ["status 0x", ("hex", "status", 2)],  # FC7's byte
    # `1 event`, `2 events`: a count step's field and its noun (count_text)
    "counter": ["status 0x", ("hex", "status", 4), ", ", ("count", "event_count", "event")],
    "event_log": ["status 0x", ("hex", "status", 4), ", ", ("count", "event_count", "event"), ", ",
                  ("count", "message_count", "message")],
    # `00h Return Query Data data 0a0b… (+4 bytes)`, `0Bh Return Bus Message Count = 7`
    "diagnostics": [("hex", "subfunction", 2), "h ", ("subfunction", "subfunction"), ("data", "data")],
    # the address as sent, even PLC style
    "mask": [("dec", "address"), " AND 0x", ("hex", "and_mask", 4), " OR 0x", ("hex", "or_mask", 4)],
    "pointer": ["pointer ", ("dec", "address")],
    # PLC style: as its answer shows it; `write 5 (0)` writing none, as FC16's `5 (0)`
    "read_write": ["read ", ("plain_span",), ", write ", ("write", "write_start", "write_quantity")],
    # `10 values: 0 100 … (+2)`, `1 value: 7`, `0 values` (the step writes the colon before values it shows)
    "fifo": [("count", "fifo_count", "value"), ("fifo", "fifo_count", "values")],
    "python": [("none",)],
}
NOUN_STEPS = frozenset({"count"})  # the steps whose last argument is a noun they print, not a field
# The form of each describer (table.Function.text) in each direction, (request, response); a pair where it
# depends on the data the code carries (bits, registers). The others are described by _BY_NAME below.
DESCRIBER_FORMS: dict[str, tuple[str | tuple[str, str], str | tuple[str, str]]] = {
    "read": ("span", ("bits", "values")),
    "write_single_coil": ("coil", "coil"),
    "write_single_register": ("single", "single"),
    "simple": ("name", "status"),
    "comm_event_counter": ("name", "counter"),
    "comm_event_log": ("name", "event_log"),
    "diagnostics": ("diagnostics", "diagnostics"),
    "write_multiple": (("bits", "values"), "written"),
    "mask_write": ("mask", "mask"),
    "read_write": ("read_write", "values"),
    "fifo": ("pointer", "fifo"),
}
# A register read's answer whose window is unknown (no request) shows its values alone, without the `: `
# after its empty span (only the read's: a bit read's answer and FC23's keep it).
_VALUES_ALONE = ("read", "values")


def form_of(describer: str, request: bool, bits: bool) -> str | None:
    """The form (TEXT_FORMS) a describer gives in one direction; None: one of _BY_NAME's."""
    forms = DESCRIBER_FORMS.get(describer)
    if forms is None:
        return None
    form = forms[0 if request else 1]
    return form if isinstance(form, str) else form[0 if bits else 1]


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
    describe = _DESCRIBERS[request].get(function)
    detail = describe(frame, request) if describe else f"{count_text(len(frame.pdu) - 1, 'byte')} of data"
    if detail.startswith(": "):  # a bit read's answer without its request: no window before the bits
        return f"{name}{detail}"
    return f"{name} {detail}".rstrip()


def _coil(frame: Frame, value: int) -> str:
    return " = " + {0xFF00: "ON", 0x0000: "OFF"}.get(value, f"0x{value:04X}")


def _single(frame: Frame, value: int) -> str:
    """` HSP=50.9 Hz` where the register is named or read as a text, ` = 7` otherwise."""
    registers = frame.registers or []
    if registers and (registers[0].code or registers[0].text):
        return f" {register_text(registers[0])}"
    return f" = {value}"


def _plain_span(frame: Frame) -> str:
    """The window as sent (FC23's read part); PLC style as its answer shows it."""
    return span_text(frame) if frame.span_label is not None else plain_span(frame.start, frame.quantity)


def _write_span(frame: Frame, start: int, quantity: int) -> str:
    """FC23's written window as its read window is shown: PLC style by its label (annotator), else as sent."""
    label = frame.write_span_label
    if label is None:
        return plain_span(start, quantity)
    return label if quantity == 1 else f"{label} ({quantity})"


# What each step of TEXT_FORMS writes (the C engine's STEP_*): of the frame, or of the field it names.
_OF_FRAME: dict[str, Callable[[Frame], str]] = {
    "unspace": lambda frame: "", "span": span_text, "label": span_text, "plain_span": _plain_span,
    "bits": bits_text, "values": values_text,
}
_OF_FIELD: dict[str, Callable[[Frame, Any], str]] = {
    "coil": _coil, "single": _single, "dec": lambda frame, value: str(value),
    # FC8's sub-function as the profile names it, else the spec
    "subfunction": lambda frame, sub: frame.subfunction_text or SPEC.diagnostics.get(sub, UNKNOWN_SUBFUNCTION),
    "data": lambda frame, data: _data(data),
}


def _step(step: tuple[str | int, ...]) -> Callable[[Frame], str]:
    what, args = step[0], step[1:]
    if what in _OF_FRAME:
        return _OF_FRAME[what]
    if what in _OF_FIELD:
        of = _OF_FIELD[what]
        return lambda frame: of(frame, frame.fields[args[0]])
    if what == "hex":
        return lambda frame: f"{frame.fields[args[0]]:0{args[1]}X}"
    if what == "count":  # (its second argument is the noun, not a field)
        return lambda frame: count_text(frame.fields[args[0]], str(args[1]))
    if what == "write":  # FC23's: its values, or where none are sent its window (`5 (0)`, `40006 (0)`), never nothing
        return lambda frame: values_text(frame) or _write_span(frame, frame.fields[args[0]], frame.fields[args[1]])
    if what == "fifo":  # the values sent (the first MAX_FIFO_VALUES), whatever their count says
        return lambda frame: _fifo(frame.fields[args[1]])
    raise ValueError(f"describe: no step {what!r}")


def _fifo(values: list[int]) -> str:
    """`: 0 100 200`, then how many more past MAX_FIFO_VALUES (`… (+2)`, as values_text); nothing for none."""
    if not values:
        return ""
    text = ":" + "".join(f" {value}" for value in values[:MAX_FIFO_VALUES])
    return text + f" … (+{len(values) - MAX_FIFO_VALUES})" if len(values) > MAX_FIFO_VALUES else text


def _after_colon(text: str) -> str:
    return ": " + text if text else ""


def _interpreter(form: str, values_alone: bool) -> Callable[[Frame, bool], str]:
    """A describer of a form: its steps called for their texts, joined with its texts."""
    steps = TEXT_FORMS[form]
    texts = [""]  # the texts before, between and after the steps that are calls
    calls = []
    for step in steps:
        if isinstance(step, str):
            texts[-1] += step
        else:
            calls.append(_step(step))
            texts.append("")
    strip = ": " if values_alone else ""  # (str.lstrip("") strips nothing)
    if len(calls) == 1:
        (one,), (head, tail) = calls, texts
        if not head and not tail:
            return lambda frame, request: one(frame)
        return lambda frame, request: head + one(frame) + tail
    if len(calls) == 2:
        (first, second), (head, middle, tail) = calls, texts
        if middle == ": ":  # (no colon before values of none: `8401 (0)`, as `0 values`)
            return lambda frame, request: (head + first(frame) + _after_colon(second(frame))
                                           + tail).lstrip(strip)
        return lambda frame, request: (head + first(frame) + middle + second(frame) + tail).lstrip(strip)
    return lambda frame, request: "".join([text + call(frame) for text, call in zip(texts, calls)]) + texts[-1]


MAX_DATA_BYTES = 16  # bytes of echoed data a summary shows (-V and JSON show them all)


def _data(data: bytes) -> str:
    """FC8's data: ` = 7` for a word, else ` data 0a0b… (+4 bytes)`, nothing for none."""
    if len(data) == 2:
        return f" = {int.from_bytes(data, 'big')}"
    return f" data {_hex_preview(data)}" if data else ""


def _hex_preview(data: bytes) -> str:
    if len(data) <= MAX_DATA_BYTES:
        return data.hex()
    return f"{data[:MAX_DATA_BYTES].hex()}… (+{count_text(len(data) - MAX_DATA_BYTES, 'byte')})"


def mei_name(mei_type: int) -> str:
    """`Read Device Identification`, `MEI 9`: an FC43 frame's MEI type as the summary names it."""
    return SPEC.mei_types.get(mei_type, f"MEI {mei_type}")


def device_id_request_text(read_code: int, object_id: int) -> str:
    """`basic, from object 0`: what an FC43/14 request asks (its summary's, --stats' poll row's)."""
    return f"{SPEC.device_id_codes.get(read_code, str(read_code))}, from object {object_id}"


def subfunction_text(sub: int, name: str | None = None) -> str:
    """`0Bh Return Bus Message Count`: an FC8 sub-function as the summary writes it (`name`: the profile's)."""
    return f"{sub:02X}h {name or SPEC.diagnostics.get(sub, UNKNOWN_SUBFUNCTION)}"


def _mei(frame: Frame, request: bool) -> str:
    fields = frame.fields
    mei = mei_name(fields.mei_type)
    if fields.mei_type != 14:
        return mei
    if request:
        return f"{mei}, {device_id_request_text(fields.body.read_code, fields.body.object_id)}"
    code = SPEC.device_id_codes.get(fields.body.read_code, str(fields.body.read_code))
    objects = "".join(f" {obj.name}={_object_value(obj)}" for obj in frame.objects or [])
    # (More Follows FF: the server sends the rest from the next object id on, 6.21)
    more = f" (more follows from object {fields.body.next_object_id})" if fields.body.more_follows == 0xFF else ""
    return f"{mei}, {code}:{objects}{more}"


_VERSION = re.compile(r"V\d+\.\d+")


def _object_value(obj: DeviceObject) -> str:
    """The value as sent; a revision the profile decoded (`0201` -> `V2.1`) shows decoded."""
    if obj.text is not None and _VERSION.fullmatch(obj.text):
        return obj.text
    return f"'{obj.value}'"  # (its quotes and backslashes escaped: printable.bytes_text)


def _report_server_id(frame: Frame, request: bool) -> str:
    fields = frame.fields
    if request or fields.get("server_id") is None:  # (byte count 0: none, data/modbus.toml ?(byte_count))
        return ""
    if fields.run_indicator is None:  # (byte count 1: the id alone, data/modbus.toml ?(byte_count-1))
        return f"server id {fields.server_id}"
    data = fields.additional_data
    text = repr(data) if isinstance(data, str) else count_text(len(data), "byte")
    return f"server id {_server_id(fields.server_id)}, run {fields.run_indicator}, {text}"


def _server_id(server_id: int | str | bytes) -> str:
    """A one-byte id as its number; a longer one (decode/fields.py reads it up to the run indicator) as its
    text where printable (`'Pymodbus'`), else its bytes (`12 34 56`)."""
    if isinstance(server_id, int):
        return str(server_id)
    return repr(server_id) if isinstance(server_id, str) else server_id.hex(" ").upper()


def _file_record(frame: Frame, request: bool) -> str:
    fields = frame.fields
    groups = fields.get("subrequests") or fields.get("subresponses") or fields.get("records") or []
    return f"{len(groups)} record group(s)"


# The describers that are no form of TEXT_FORMS, by name; the protocol table says which function code uses
# which (table.Function.text), and its data (bits, registers) which of a describer's forms it takes.
_BY_NAME = {"report_server_id": _report_server_id, "file_record": _file_record, "mei": _mei}
_FORMS = {(entry.code, request): (entry.text, form_of(entry.text, request, entry.data is Data.BITS))
          for entry in FUNCTIONS for request in (True, False)}
_DESCRIBERS = tuple({code: _BY_NAME.get(text) or _interpreter(form, (text, form) == _VALUES_ALONE)
                     for (code, request), (text, form) in _FORMS.items() if request is direction}
                    for direction in (False, True))  # [request]: the describers by function code
