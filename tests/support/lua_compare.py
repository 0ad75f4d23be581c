"""Frame-by-frame comparison of the Lua plugin's tshark output with the Python decoder's items."""
from __future__ import annotations

import re
from typing import Any

from pathlib import Path

from lua_harness import LuaItem, PythonItem, lua_errors, lua_items, python_items, run_tshark

_PAIRING_NOTE = re.compile(r"^request #\d+ was not answered$")
WARNING_EXPERTS = ("vw3.expert.warning", "vw3.expert.malformed")
NOTE_EXPERTS = ("vw3.expert.note", "vw3.expert.no_request")


# Every key of vw3-decode --json the plugin mirrors (or, for "fields", "raw", "offset", "time",
# deliberately leaves to Wireshark's own bytes pane and frame fields). A new key fails the parity
# tests until the plugin shows it too.
FRAME_KEYS = frozenset([
    "frame", "kind", "offset", "length", "time", "raw", "mode", "slave", "function", "function_name",
    "crc_ok", "crc", "crc_expected", "broadcast", "start", "span_label", "write_span_label", "quantity", "subfunction",
    "subfunction_name", "registers", "bits", "objects", "exception_code", "exception_name",
    "exception_meaning", "request_frame", "response_time", "response_frame", "unanswered", "fields",
    "warnings", "notes", "profile", "profile_reason",
    # Read once, before profile `auto` chose the slave's device (issue 27): vw3.provisional in tshark's
    # single pass (-2 names every frame from the choice over the whole capture, as the file read twice).
    "provisional",
])
NOISE_KEYS = frozenset(["frame", "kind", "offset", "length", "time", "raw", "reason", "warnings"])
REGISTER_KEYS = frozenset(["address", "value", "code", "name", "unit", "scaled", "text", "status", "source",
                           "label", "words"])
OBJECT_KEYS = frozenset(["id", "name", "value", "text"])


def unknown_keys(python: list[PythonItem]) -> set[str]:
    """JSON keys the plugin does not know about (a feature added to the Python side only)."""
    unknown: set[str] = set()
    for item in python:
        data = item.data
        unknown |= set(data) - (NOISE_KEYS if data["kind"] == "noise" else FRAME_KEYS)
        for reg in data.get("registers", []):
            unknown |= {f"registers.{key}" for key in set(reg) - REGISTER_KEYS}
        for obj in data.get("objects", []):
            unknown |= {f"objects.{key}" for key in set(obj) - OBJECT_KEYS}
    return unknown


def _scaled(value: Any) -> float | None:
    # Wireshark shows a double with 15 significant digits (a float32 read as 3.4028234663852886e+38 shows
    # as 3.40282346638529e+38): both sides are compared at that precision.
    return None if value is None else float(f"{round(float(value), 9):.15g}")


def python_frame(item: PythonItem, records: dict[int, int]) -> dict[str, Any]:
    data = item.data
    out: dict[str, Any] = {
        "item": data["frame"],
        "length": data["length"],
        "kind": data["kind"],
        "slave": data["slave"],
        "function": data["function"],
        "function_name": data["function_name"],
        "span_label": data.get("span_label"),
        "write_span_label": data.get("write_span_label"),
        "subfunction_name": data.get("subfunction_name"),
        "exception_name": data.get("exception_name"),
        "exception_meaning": data.get("exception_meaning"),
        "crc_ok": data["crc_ok"],
        "crc": data["crc"],
        "crc_expected": data["crc_expected"],
        "broadcast": data["broadcast"],
        "start": data.get("start"),
        "quantity": data.get("quantity"),
        "subfunction": data.get("subfunction"),
        "exception_code": data.get("exception_code"),
        "request_frame": records.get(data["request_frame"]) if "request_frame" in data else None,
        "response_frame": records.get(data["response_frame"]) if "response_frame" in data else None,
        "unanswered": data.get("unanswered"),
        "provisional": data.get("provisional", False),
        # Microseconds: Wireshark holds times as doubles in Lua (pinfo.abs_ts), pcap gives microseconds.
        "response_time": None if data.get("response_time") is None else round(data["response_time"], 6),
        "registers": [
            (reg["address"], reg["value"], reg.get("code"), reg.get("status"), reg.get("text"), reg.get("label"),
             reg.get("name"), reg.get("unit"), reg.get("source"), _scaled(reg.get("scaled")), reg.get("words", 1))
            for reg in data.get("registers", [])
        ],
        "bits": [(bit["address"], bit["value"]) for bit in data.get("bits", [])],
        # (a value is a bytes literal's text, printable.bytes_text, in --json and the plugin's field alike)
        "objects": [(obj["id"], obj["name"], obj["value"], obj.get("text")) for obj in data.get("objects", [])],
        "warnings": list(data["warnings"]),  # (a malformed PDU's words too: grammar.shortfall)
        "notes": [text for text in data["notes"] if not _PAIRING_NOTE.match(text)],
        # profile auto: which profile named the frame's registers, and why
        "profile": (data.get("profile"), data.get("profile_reason")),
    }
    return out


def _int(text: str | None) -> int | None:
    if text is None or text == "":
        return None
    return int(text, 0)


def _bool(text: str | None) -> bool | None:
    if text is None:
        return None
    return text in ("1", "True", "true")


def lua_frame(item: LuaItem) -> dict[str, Any]:
    fields = item.fields
    kind = lua_kind(item)
    return {
        "item": _int(fields.get("item")),
        "length": item.length,
        "kind": kind,
        "slave": _int(fields.get("slave")),
        "function": _int(fields.get("function")),
        "function_name": fields.get("function_name"),
        "span_label": fields.get("span_label"),
        "write_span_label": fields.get("write_span_label"),
        "subfunction_name": fields.get("subfunction_name"),
        "exception_name": fields.get("exception_name"),
        "exception_meaning": fields.get("exception_meaning"),
        "crc_ok": _bool(fields.get("crc_ok")),
        "crc": _int(fields.get("crc")),
        "crc_expected": _int(fields.get("crc_expected")),
        "broadcast": bool(_bool(fields.get("broadcast"))),
        "start": _int(fields.get("start")),
        "quantity": _int(fields.get("quantity")),
        "subfunction": _int(fields.get("subfunction")),
        "exception_code": _int(fields.get("exception_code")),
        "request_frame": _int(fields.get("request_frame")),
        "response_frame": _int(fields.get("response_frame")),
        # (present only when true)
        "unanswered": bool(_bool(fields.get("unanswered"))) if kind == "request" else None,
        "provisional": bool(_bool(fields.get("provisional"))),
        "response_time": None if fields.get("response_time") is None else round(float(fields["response_time"]), 6),
        "registers": [
            (_int(reg.get("address")), _int(reg.get("value")), reg.get("code"),
             reg.get("status"),  # (text, as vw3-decode's: ok, protected, non-existent, ambiguous)
             reg.get("text"), reg.get("label"), reg.get("name"), reg.get("unit"), reg.get("source"),
             _scaled(reg.get("scaled")), _int(reg.get("words")) if "words" in reg else 1)
            for reg in item.registers
        ],
        "bits": [(_int(bit.get("address")), _int(bit.get("value"))) for bit in item.bits],
        "objects": [
            (_int(obj.get("id")), obj.get("name"), obj.get("value"), obj.get("text"))
            for obj in item.objects
        ],
        "warnings": list(item.texts.get("warning", [])),
        "notes": item.texts.get("note", []),
        # (the profile that annotated the frame, as --json's `profile`; the reason only where `auto` chose)
        "profile": (fields.get("profile"), fields.get("profile_reason")),
    }


KIND_NAMES = {"1": "request", "2": "response", "3": "exception", "4": "noise"}


def lua_kind(item: LuaItem) -> str | None:
    """The item's kind by name (vw3.kind is an integer with value strings); None: no item (a record note)."""
    kind = item.fields.get("kind")
    return KIND_NAMES.get(kind, kind)


def lua_shown(lua: list[LuaItem]) -> list[LuaItem]:
    """The plugin's frames and noise runs (not the trees that only say where a record's bytes went)."""
    return [item for item in lua if lua_kind(item) is not None]


def compare(python: list[PythonItem], lua: list[LuaItem], ignore: frozenset[str] = frozenset()) -> list[str]:
    """Every difference, as one line each; empty when the two sides agree. `ignore`: keys not compared.

    Items are matched by their offset in the byte stream (vw3.offset, vw3-decode's "offset"): a frame
    that a capture tool cut across records is shown in the record that completes it, from its own bytes.
    Links (request and response frames) are compared as the records the plugin shows the linked items in.
    """
    lua = lua_shown(lua)
    shown_in = {_int(item.fields.get("item")): item.record for item in lua}
    records = {item.data["frame"]: shown_in.get(item.data["frame"]) for item in python}
    differences: list[str] = [f"vw3-decode --json has a key the plugin lacks: {key}" for key in
                              sorted(unknown_keys(python))]
    py_frames = {item.data["offset"]: item for item in python if item.data["kind"] != "noise"}
    lua_frames = {_int(item.fields.get("offset")): item for item in lua if lua_kind(item) != "noise"}
    for key in sorted(set(py_frames) | set(lua_frames)):
        where = f"stream offset {key}"
        if key not in lua_frames:
            differences.append(f"{where}: only Python has a frame: {py_frames[key].data['raw']}")
            continue
        if key not in py_frames:
            differences.append(f"{where} (record {lua_frames[key].record}): only Lua has a frame "
                               f"({lua_kind(lua_frames[key])})")
            continue
        expected = python_frame(py_frames[key], records)
        got = lua_frame(lua_frames[key])
        for name, value in expected.items():
            if name not in ignore and got.get(name) != value:
                differences.append(f"{where} (record {lua_frames[key].record}) {name}: Python {value!r}, "
                                   f"Lua {got.get(name)!r}")
    py_noise = {
        item.stream_offset + index
        for item in python
        if item.data["kind"] == "noise"
        for index in range(item.data["length"])
    }
    lua_noise = {
        _int(item.fields.get("offset")) + index
        for item in lua
        if lua_kind(item) == "noise"
        for index in range(item.length)
    }
    for offset in sorted(py_noise ^ lua_noise)[:20]:
        side = "Python" if offset in py_noise else "Lua"
        differences.append(f"stream offset {offset}: noise only in {side}")
    python_count = len({item.data["frame"] for item in python})
    if python_count != len(lua):
        differences.append(f"{python_count} items in vw3-decode --json, {len(lua)} shown by the plugin")
    return differences


def tshark_fields(pcap: Path, fields: list[str]) -> list[str]:
    """The plugin's `-T fields` rows for `fields` (tshark's own arguments), with no Lua error."""
    got = run_tshark(pcap, *fields)
    assert got.returncode == 0 and not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    return got.stdout.splitlines()


def assert_same_as_vw3_decode(pcap: Path) -> None:
    """The plugin's items are vw3-decode's, frame for frame."""
    differences = compare(python_items(pcap), lua_items(pcap)[0])
    assert not differences, "\n".join(differences[:40])
