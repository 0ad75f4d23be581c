"""NDJSON output: one object per item (frame or noise). The schema is documented in README.md.

Later stages only add keys; the keys below are stable.
"""
from __future__ import annotations

import json
from typing import Any, TextIO

from dissector.model import Frame, Item, Kind, Noise, Register
from dissector.protocol.spec import SPEC

_REGISTER_EXTRA = ("code", "name", "unit", "scaled", "text", "status", "source", "label")


def register_to_dict(register: Register) -> dict[str, Any]:
    out: dict[str, Any] = {"address": register.address, "value": register.value}
    for key in _REGISTER_EXTRA:
        value = getattr(register, key, None)
        if value is not None:
            out[key] = value
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


def item_to_dict(item: Item) -> dict[str, Any]:
    if isinstance(item, Noise):
        return _noise_to_dict(item)
    frame: Frame = item
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
    if frame.start is not None:
        out["start"] = frame.start
    if frame.span_label is not None:
        out["span_label"] = frame.span_label
    if frame.quantity is not None:
        out["quantity"] = frame.quantity
    if frame.subfunction is not None:
        out["subfunction"] = frame.subfunction
        out["subfunction_name"] = frame.subfunction_text or SPEC.diagnostics.get(frame.subfunction)
    if frame.registers is not None:
        out["registers"] = [register_to_dict(register) for register in frame.registers]
    if frame.bits is not None:
        out["bits"] = [{"address": bit.address, "value": bit.value} for bit in frame.bits]
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
    if frame.response is not None:
        out["response_frame"] = frame.response.number
    if frame.kind is Kind.REQUEST:
        out["unanswered"] = frame.unanswered
    if frame.fields is not None:
        out["fields"] = _plain(frame.fields)
    out["warnings"] = list(frame.warnings)
    out["notes"] = list(frame.notes)
    return out


def _plain(value: Any) -> Any:
    """Construct containers to JSON-friendly values (bytes as lowercase hex)."""
    if isinstance(value, dict):
        return {
            key: _plain(inner)
            for key, inner in value.items()
            if not key.startswith("_") and not (key == "trailing" and not inner) and inner is not None
        }
    if isinstance(value, list):
        return [_plain(inner) for inner in value]
    if isinstance(value, bytes):
        return value.hex()
    return value


def write_json(items: list[Item], stream: TextIO) -> None:
    dumps = json.dumps
    stream.write("".join(dumps(item_to_dict(item)) + "\n" for item in items))
