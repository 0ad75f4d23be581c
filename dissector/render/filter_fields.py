"""The fields of display filters and -T fields: names, types, meanings, and their listing (-Y help,
-G fields). Kept apart from filters.py (the parser) so each stays small; filters.py re-exports them."""
from __future__ import annotations

# field -> type: number (integer or decimal), str, bool, list (of strings)
FRAME_FIELDS: dict[str, str] = {
    "frame": "number",
    "kind": "str",
    "offset": "number",
    "length": "number",
    "time": "number",
    "raw": "str",
    "mode": "str",
    "slave": "number",
    "function": "number",
    "function_name": "str",
    "crc_ok": "bool",
    "crc": "number",
    "crc_expected": "number",
    "crc_typed": "bool",
    "broadcast": "bool",
    "start": "number",
    "quantity": "number",
    "subfunction": "number",
    "subfunction_name": "str",
    "exception_code": "number",
    "exception_name": "str",
    "request_frame": "number",
    "response_frame": "number",
    "response_time": "number",
    "unanswered": "bool",
    "reason": "str",
    "warnings": "list",
    "notes": "list",
    "exception_meaning": "str",
    "span_label": "str",
    "profile": "str",
    "profile_reason": "str",
    "provisional": "bool",
    "file": "str",
    "registers": "struct",
    "bits": "struct",
    "objects": "struct",
    "fields": "struct",
}
# Numbers the time column shows, computed from the capture (FilterContext), as -T fields has them.
TIME_FILTER_FIELDS: dict[str, str] = {"time_relative": "number", "time_delta": "number"}
FIELD_HELP: dict[str, str] = {
    "frame": "item number, 1-based", "kind": "request, response, exception or noise",
    "offset": "byte offset of the item in the input", "length": "bytes in the item",
    "time": "seconds since the epoch of the item's first byte", "raw": "the item's bytes, lowercase hex",
    "mode": "rtu or ascii", "slave": "slave address (0: broadcast)", "function": "function code",
    "function_name": "function name", "crc_ok": "the CRC/LRC checks", "crc": "received check value",
    "crc_expected": "computed check value",
    "crc_typed": "false: a --hex frame typed without its check (computed, not received; crc_ok null)",
    "broadcast": "a request to slave 0",
    "start": "first address", "quantity": "count", "subfunction": "FC8 sub-function",
    "subfunction_name": "FC8 sub-function name", "exception_code": "exception code (alias: exception)",
    "exception_name": "the spec's exception name", "exception_meaning": "what it means on the device",
    "span_label": "the addresses as shown (PLC style)", "request_frame": "the request a response answers",
    "response_frame": "the response that answered a request", "response_time": "seconds after the request",
    "unanswered": "a request no response came to", "reason": "why noise is no frame",
    "warnings": "warnings (list of texts)", "notes": "notes (list of texts)",
    "file": "the input, when several are decoded", "registers": "register values (presence)",
    "profile": "profile auto: the profile the slave was given", "profile_reason": "profile auto: why",
    "provisional": "read once before profile auto chose the slave's device (live, stdin)",
    "bits": "coils and inputs (presence)", "objects": "FC43 objects (presence)",
    "fields": "the PDU's fields (presence); fields.KEY one of them",
    "time_relative": "seconds since the first item of the input",
    "time_delta": "seconds since the item captured before",
    "address": "register address (also as shown: 40001)", "value": "register value", "code": "parameter code",
    "name": "parameter name", "unit": "unit", "scaled": "scaled value", "text": "the value's text",
    "status": "ok, protected, non-existent or ambiguous", "source": "where the map row comes from",
    "label": "the address as shown (PLC style)",
}
REGISTER_FIELDS: dict[str, str] = {
    "address": "number",
    "value": "number",
    "code": "str",
    "name": "str",
    "unit": "str",
    "scaled": "number",
    "text": "str",
    "status": "str",
    "source": "str",
    "label": "str",
}

_TYPE_WORDS = {"number": "number", "str": "text", "bool": "true/false", "list": "list of texts",
               "struct": "structure", "any": "value"}


def field_listing() -> str:
    """`-Y help` (and `-G fields`): every field a filter and -T fields know, its type and meaning."""
    lines = ["Display filter and -T fields keys (-Y EXPR, -e KEY); register keys test one register at a time:"]
    groups = [("frame", FRAME_FIELDS), ("time", TIME_FILTER_FIELDS), ("register", REGISTER_FIELDS)]
    for group, fields in groups:
        for name, ftype in fields.items():
            lines.append(f"{name:<22} {group:<9} {_TYPE_WORDS[ftype]:<14} {FIELD_HELP.get(name, '')}")
    lines.append(f"{'fields.KEY':<22} {'frame':<9} {'value':<14} a key of the PDU as parsed (fields.start)")
    lines.append(f"{'time_delta_displayed':<22} {'-T only':<9} {'number':<14} seconds since the item shown before")
    lines.append("operators: == != < <= > >= & in {..} a..b contains matches ~ and or not ( ); "
                 "values: 12 0x8000 16#8000 \"text\" true false")
    return "\n".join(lines) + "\n"
