"""NDJSON output: one object per item (frame or noise). The schema is documented in README.md.

Later stages only add keys; the keys below are stable.
"""
from __future__ import annotations

import json
from json.encoder import encode_basestring_ascii as _json_string  # what json.dumps uses for str
from collections.abc import Sequence
from itertools import chain
from operator import attrgetter
from typing import Any, TextIO

from dissector.model import Bit, BitList, Frame, Item, Kind, Noise, Register, RegisterList
from dissector.protocol.spec import SPEC
from dissector.render.runs import AddressPieces, BitRuns, Pieces, interleave
from dissector.render.describe import value_names
from dissector.render.registers import MASKS, mask_register
from dissector.render.summary import check_untyped
from dissector.render.timefmt import MICRO_DIGITS, NANO_DIGITS, detail_digits, signed_text


def register_to_dict(register: Register) -> dict[str, Any]:
    # Spelled out rather than a loop over getattr: this runs once per register of every frame.
    out: dict[str, Any] = {"address": register.address, "value": register.value}
    if register.code is not None:
        out["code"] = register.code
    if register.name is not None:
        out["name"] = register.name
    if register.unit is not None:
        out["unit"] = register.unit
    if register.scaled is not None:
        out["scaled"] = register.scaled
    if register.text is not None:
        out["text"] = register.text
    if register.status is not None:
        out["status"] = register.status
    if register.source is not None:
        out["source"] = register.source
    if register.label is not None:
        out["label"] = register.label
    if register.words != 1:
        out["words"] = register.words  # 2: a 32-bit value read on this register and the next; 0: that next
    return out


def _noise_to_dict(noise: Noise) -> dict[str, Any]:
    return {
        "frame": noise.number,
        "kind": "noise",
        "offset": noise.offset,
        "length": noise.length,
        "time": noise.time,
        "raw": noise.raw.hex(),
        "reason": noise.reason,
        "warnings": list(noise.warnings),
    }


def _head(frame: Frame) -> dict[str, Any]:
    """The keys before `registers`."""
    out: dict[str, Any] = {
        "frame": frame.number,
        "kind": str(frame.kind),
        "offset": frame.offset,
        "length": frame.length,
        "time": frame.time,
        "raw": frame.raw.hex(),
        "mode": frame.mode,
        "slave": frame.slave,
        "function": frame.function,
        "function_name": frame.function_text or SPEC.function_name(frame.function),
        "crc_ok": frame.crc_ok,
        "crc": frame.crc,
        "crc_expected": frame.crc_expected,
        "broadcast": frame.broadcast,
    }
    if frame.notes and check_untyped(frame):  # --hex typed without its check: none received, none checked
        out["crc_ok"] = out["crc"] = None
        out["crc_typed"] = False
    if frame.start is not None:
        out["start"] = frame.start
    if frame.span_label is not None:
        out["span_label"] = frame.span_label
    if frame.write_span_label is not None:
        out["write_span_label"] = frame.write_span_label
    if frame.quantity is not None:
        out["quantity"] = frame.quantity
    if frame.subfunction is not None:
        out["subfunction"] = frame.subfunction
        out["subfunction_name"] = frame.subfunction_text or SPEC.diagnostics.get(frame.subfunction)
    choice = frame.profile_choice
    if choice is not None:
        out["profile"] = choice.profile
        out["profile_reason"] = choice.reason
    elif frame.profile is not None:
        out["profile"] = frame.profile
    if frame.provisional:
        out["provisional"] = True
    return out


def _tail(frame: Frame, out: dict[str, Any], with_bits: bool = True, lists: bool = True) -> dict[str, Any]:
    """The keys after `registers`, added to `out` (without `bits`, or `fields`, `warnings` and `notes`,
    when item_to_json writes those itself)."""
    bits = frame.bits if with_bits else None
    if bits is not None:
        if isinstance(bits, BitList):  # in bulk: no Bit object per coil
            out["bits"] = [{"address": address, "value": value} for address, value in zip(bits.addresses, bits.values)]
        else:
            out["bits"] = [{"address": bit.address, "value": bit.value} for bit in bits]
    if frame.objects is not None:
        out["objects"] = [
            {"id": obj.id, "name": obj.name, "value": obj.value}
            | ({"text": obj.text} if obj.text is not None else {})
            for obj in frame.objects
        ]
    if frame.kind is Kind.EXCEPTION:
        code = frame.exception_code
        out["exception_code"] = code
        out["exception_name"] = SPEC.exception_name(code)
        if frame.exception_text is not None:
            out["exception_meaning"] = frame.exception_text
    if frame.request is not None:
        out["request_frame"] = frame.request.number
        out["response_time"] = frame.response_time
    response = frame.response
    if response is not None:
        out["response_frame"] = response.number
    if frame.kind is Kind.REQUEST:
        out["unanswered"] = frame.unanswered
    if not lists:
        return out
    if frame.fields is not None:
        out["fields"] = _plain(frame.fields)
    out["warnings"] = list(frame.warnings)
    out["notes"] = list(frame.notes)
    return out


def exact_time(text: str, time: float | None, units: int | None) -> str:
    """An item's JSON `text` (or a --watch change's) with its "time" written to 9 decimals from its
    integer nanoseconds where microseconds cannot hold the capture's times (render/timefmt.py
    detail_digits: a nanosecond pcap, if_tsresol 10^-7 or 2^-10): a double near 1.7e9 s keeps ~0.2 us
    (1767225600.0090182 of .009018123). A JSON number still; others' times as json writes a float. The
    first "time" key is the one: only fixed keys and numbers come before it (frame, kind, offset, length)."""
    ns = getattr(time, "ns", None)
    if ns is None or detail_digits(units) == MICRO_DIGITS:
        return text
    shown = float.__repr__(time)  # type: ignore[arg-type]
    return text.replace(f'"time": {shown}', f'"time": {signed_text(ns, NANO_DIGITS, True)}', 1)


def item_to_dict(item: Item, fields: bool = True) -> dict[str, Any]:
    """The NDJSON object; fields=False leaves out `fields` (the PDU as parsed), which --parquet does not keep."""
    if isinstance(item, Noise):
        return _noise_to_dict(item)
    frame: Frame = item
    out = _head(frame)
    if frame.registers is not None:
        out["registers"] = [register_to_dict(register) for register in frame.registers]
    elif frame.function in MASKS and (mask := mask_register(frame)) is not None:
        out["registers"] = [mask]  # (FC22's register, its masks as -T registers shows them)
    if fields:
        return _tail(frame, out)
    _tail(frame, out, lists=False)
    out["warnings"] = list(frame.warnings)
    out["notes"] = list(frame.notes)
    return out


# Registers repeat (a polled block, the same status word): their JSON text is kept by content, so a
# repeated register costs a tuple and a lookup instead of a dict and its encoding. Bounded: cleared
# when full, so memory stays flat on values that never repeat.
_REGISTER_TEXTS: dict[tuple[Any, ...], str] = {}
_REGISTER_TEXTS_MAX = 1 << 16
_REGISTER_KEY = attrgetter(
    "address", "value", "code", "name", "unit", "scaled", "text", "status", "source", "label", "words"
)


def _register_json(register: Register) -> str:
    if (
        register.code is None and register.name is None and register.unit is None and register.scaled is None
        and register.text is None and register.status is None and register.source is None
    ):
        # No annotation (a relay's block, a meter's readings): formatted directly, as json.dumps would.
        address = "null" if register.address is None else register.address
        label = register.label
        if label is None:
            return f'{{"address": {address}, "value": {register.value}}}'
        return f'{{"address": {address}, "value": {register.value}, "label": {_json_string(label)}}}'
    key = _REGISTER_KEY(register)  # read in C; the type of `scaled` too: 1 and 1.0 write differently
    key = (key, type(key[5]))
    text = _REGISTER_TEXTS.get(key)
    if text is None:
        if len(_REGISTER_TEXTS) >= _REGISTER_TEXTS_MAX:
            _REGISTER_TEXTS.clear()
        text = _REGISTER_TEXTS[key] = json.dumps(register_to_dict(register))
    return text


def _scalar(value: Any) -> str:
    """json.dumps of a None, bool, int, float or str."""
    kind = type(value)
    if kind is int:
        return str(value)
    if kind is str:
        return _json_string(value)
    if value is None:
        return "null"
    if value is True:
        return "true"
    if value is False:
        return "false"
    if isinstance(value, float) and value == value and value not in (_INF, -_INF):
        return float.__repr__(value)  # what json writes for a float (a Stamp too)
    return json.dumps(value)


_INF = float("inf")
_KIND_JSON = {kind: _json_string(kind.value) for kind in Kind}


_FUNCTION_NAMES_JSON: dict[int, str] = {}  # spec names only: a profile's names vary per slave


def _head_json(frame: Frame) -> str:
    """json.dumps(_head(frame)) without its braces, formatted directly (held equal by the tests)."""
    raw = frame.raw
    crc, expected = frame.crc, frame.crc_expected
    time = frame.time
    function = frame.function
    if frame.function_text is None:
        name = _FUNCTION_NAMES_JSON.get(function)
        if name is None:
            name = _FUNCTION_NAMES_JSON[function] = _json_string(SPEC.function_name(function))
    else:
        name = _json_string(frame.function_text)
    mode = frame.mode
    text = (
        f'"frame": {frame.number}, "kind": {_KIND_JSON[frame.kind]}, "offset": {frame.offset}, '
        f'"length": {len(raw)}, "time": {"null" if time is None else _scalar(time)}, "raw": "{raw.hex()}", '
        f'"mode": {_MODE_JSON.get(mode) or _scalar(mode)}, "slave": {frame.slave}, "function": {function}, '
        f'"function_name": {name}, '
        f'"crc_ok": {"true" if crc == expected else "false"}, "crc": {crc}, "crc_expected": {expected}, '
        f'"broadcast": {"true" if frame.broadcast else "false"}'
    )
    if frame.notes and check_untyped(frame):  # as _head: none received, none checked
        text = text.replace(f'"crc_ok": true, "crc": {crc}, ', '"crc_ok": null, "crc": null, ', 1)
        text += ', "crc_typed": false'
    start = frame.start
    if start is not None:
        text += f', "start": {start}' if type(start) is int else f', "start": {_scalar(start)}'
    if frame.span_label is not None:
        text += f', "span_label": {_json_string(frame.span_label)}'
    if frame.write_span_label is not None:
        text += f', "write_span_label": {_json_string(frame.write_span_label)}'
    quantity = frame.quantity
    if quantity is not None:
        text += f', "quantity": {quantity}' if type(quantity) is int else f', "quantity": {_scalar(quantity)}'
    if frame.subfunction is not None:
        name = frame.subfunction_text or SPEC.diagnostics.get(frame.subfunction)
        text += f', "subfunction": {_scalar(frame.subfunction)}, "subfunction_name": {_scalar(name)}'
    choice = frame.profile_choice
    if choice is not None:
        text += f', "profile": {_json_string(choice.profile)}, "profile_reason": {_json_string(choice.reason)}'
    elif frame.profile is not None:
        text += f', "profile": {_json_string(frame.profile)}'
    if frame.provisional:
        text += ', "provisional": true'
    return text


_MODE_JSON = {"rtu": '"rtu"', "ascii": '"ascii"'}


# Long lists from cached pieces (runs.py): `{"address": N, "value": ` by address, `V}, ` by value.
_ADDRESS_HEADS = AddressPieces('{"address": %d, "value": ')
_VALUE_TAILS = Pieces("%d}, ")
_LABELLED_VALUES = Pieces('%d, "label": ')
_LABEL_TAILS = Pieces("%s}, ", convert=_json_string)  # by label, its JSON string made once
_BIT_RUNS = BitRuns('{"address": %d, "value": ', "0}, ", "1}, ")


def _plain_registers_json(registers: RegisterList) -> str:
    """The `registers` list of a block no profile annotated beyond labels, straight from its columns."""
    values = registers.values
    if not values:
        return "[]"
    labels = registers.labels
    if registers.start is None:
        template = ", ".join(['{"address": null, "value": %d}'] * len(values))
        return "[" + template % tuple(values) + "]"
    heads = _ADDRESS_HEADS(registers.addresses)
    if labels is None:
        return "[" + interleave((heads, _VALUE_TAILS(values)), len(values))[:-2] + "]"
    tails = _LABEL_TAILS(labels)
    return "[" + interleave((heads, _LABELLED_VALUES(values), tails), len(values))[:-2] + "]"


def _bits_json(bits: Sequence[Bit]) -> str:
    """json.dumps of the `bits` list, formatted in bulk (a 2000-coil read is one join)."""
    if isinstance(bits, BitList):
        if not bits.count:
            return "[]"
        if bits.start is not None and bits.start + bits.count <= 0x10000:
            return "[" + _BIT_RUNS(bits.start, bits.packed, bits.count)[:-2] + "]"
        addresses, values, known = bits.addresses, bits.values, False
    else:
        addresses, values = [bit.address for bit in bits], [bit.value for bit in bits]
        known = None not in addresses
    if not values:
        return "[]"
    if not known:
        return json.dumps([{"address": address, "value": value} for address, value in zip(addresses, values)])
    template = ", ".join(['{"address": %d, "value": %d}'] * len(values))
    return "[" + template % tuple(chain.from_iterable(zip(addresses, values))) + "]"


_INTS = {int}


def _json_value(value: Any) -> str:
    """json.dumps(_plain(value)), with the common field values (ints, bytes, lists of words) formatted directly."""
    kind = type(value)
    if kind is int:
        return str(value)
    if kind is bytes:
        return f'"{value.hex()}"'
    if kind is str:
        return _json_string(value)
    if isinstance(value, list) and value and set(map(type, value)) == _INTS:  # a ListContainer too; no bools
        return "[" + ", ".join(map(str, value)) + "]"
    return json.dumps(_plain(value))


def _fields_json(fields: dict[str, Any]) -> str:
    """json.dumps(_plain(fields)) for a frame's fields, without building the plain copy."""
    texts = []
    add = texts.append
    keys = _KEYS_JSON
    for key, inner in fields.items():
        if inner is None or key[0] == "_":
            continue
        name = keys.get(key)
        if name is None:
            name = keys[key] = _json_string(key) + ": "
        if type(inner) is int:  # the common case, inline
            add(f"{name}{inner}")
            names = value_names().get(key)
            if names is not None:  # (FC43's `"mei_type_name": "Read Device Identification"` beside the number)
                add(f"{_json_string(key + '_name')}: {_json_value(names.get(inner))}")
        elif key != "trailing" or inner:
            add(name + _json_value(inner))
    return "{" + ", ".join(texts) + "}"


_KEYS_JSON: dict[str, str] = {}  # `"start": ` by key (a grammar's names: few)
# The `"fields": {...}` text of a frame without registers, bits or objects, by its bytes, kind and mode
# (what decoding reads them from; -V keeps such a frame's middle by the same): bounded, cleared when full.
_FIELDS_TEXTS: dict[tuple[bytes, Kind, str], str] = {}
_FIELDS_TEXTS_MAX = 1 << 14


def item_to_json(item: Item, extra: dict[str, Any] | None = None) -> str:
    """json.dumps(item_to_dict(item) | extra), byte for byte, with registers', bits' and fields' texts
    made directly (registers' reused) instead of through dicts."""
    if isinstance(item, Noise):
        record = _noise_to_dict(item)
        if extra:
            record.update(extra)
        return json.dumps(record)
    frame: Frame = item
    registers = frame.registers
    bits = frame.bits
    fields = frame.fields
    if registers is None and bits is None and fields is None:
        record = _tail(frame, _head(frame))
        if extra:
            record.update(extra)
        return json.dumps(record)
    # Spliced from json.dumps' texts of the parts in the order item_to_dict gives them; with its
    # default separators (", " and ": ") the result is exact. The head is never empty and the last part
    # always holds warnings and notes.
    parts = [_head_json(frame)]
    if registers is not None:
        if type(registers) is RegisterList and registers.plain:
            parts.append('"registers": ' + _plain_registers_json(registers))
        else:
            parts.append('"registers": [' + ", ".join([_register_json(register) for register in registers]) + "]")
    elif frame.function in MASKS and (mask := mask_register(frame)) is not None:
        parts.append('"registers": ' + json.dumps([mask]))  # (as item_to_dict)
    if bits is not None:
        parts.append('"bits": ' + _bits_json(bits))
    if frame.objects is not None or frame.kind is Kind.EXCEPTION:
        middle = _tail(frame, {}, with_bits=False, lists=False)
        if middle:
            parts.append(json.dumps(middle)[1:-1])
    else:  # the common case, directly: the pairing keys
        request = frame.request
        if request is not None:
            parts.append(f'"request_frame": {request.number}, "response_time": {_scalar(frame.response_time)}')
        response = frame.response
        if response is not None:
            parts.append(f'"response_frame": {response.number}')
        if frame.kind is Kind.REQUEST:
            parts.append('"unanswered": true' if frame.unanswered else '"unanswered": false')
    if fields is not None:
        if registers is None and bits is None and frame.objects is None:
            # A frame without values (a polled request, a write's echo): its fields are its bytes'.
            key = (frame.raw, frame.kind, frame.mode)
            text = _FIELDS_TEXTS.get(key)
            if text is None:
                if len(_FIELDS_TEXTS) >= _FIELDS_TEXTS_MAX:
                    _FIELDS_TEXTS.clear()
                text = _FIELDS_TEXTS[key] = '"fields": ' + _fields_json(fields)
            parts.append(text)
        else:
            parts.append('"fields": ' + _fields_json(fields))
    if extra:
        last: dict[str, Any] = {"warnings": list(frame.warnings), "notes": list(frame.notes)}
        last.update(extra)
        parts.append(json.dumps(last)[1:-1])
    else:
        parts.append(
            f'"warnings": [{", ".join(map(_json_string, frame.warnings))}], '
            f'"notes": [{", ".join(map(_json_string, frame.notes))}]'
        )
    return "{" + ", ".join(parts) + "}"


def _plain(value: Any) -> Any:
    """Construct containers to JSON-friendly values (bytes as lowercase hex)."""
    if isinstance(value, dict):
        out = {}
        for key, inner in value.items():
            if key.startswith("_") or (key == "trailing" and not inner) or inner is None:
                continue
            out[key] = _plain(inner)
            names = value_names().get(key)
            if names is not None and type(inner) is int:  # the value's name beside it (null: none known)
                out[key + "_name"] = names.get(inner)
        return out
    if isinstance(value, list):
        if value and type(value[0]) is int:  # register values: a list of ints, nothing to convert
            return list(value)
        return [_plain(inner) for inner in value]
    if isinstance(value, bytes):
        return value.hex()
    return value


def write_json(items: list[Item], stream: TextIO) -> None:
    stream.write("".join(item_to_json(item) + "\n" for item in items))
