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


def pdu_keys() -> dict[str, tuple[str, ...]]:
    """`fields.KEY`: every key a PDU layout of the protocol table (protocol/table.py) parses -> the
    function codes (`exception`) whose frames have it, from the layouts' grammars, not a list kept here."""
    global _PDU_KEYS
    if _PDU_KEYS is None:
        from dissector.protocol import table

        found: dict[str, list[str]] = {}
        layouts = [(str(entry.code), layout) for entry in table.FUNCTIONS for layout in (entry.request, entry.response)]
        layouts += [("exception", table.EXCEPTION_LAYOUT), ("any", table.RAW_LAYOUT)]
        for owner, layout in layouts:
            grammar = layout.grammar
            while getattr(grammar, "subcons", None) is None and getattr(grammar, "subcon", None) is not None:
                grammar = grammar.subcon
            for sub in getattr(grammar, "subcons", ()):
                if sub.name and owner not in found.setdefault(sub.name, []):
                    found[sub.name].append(owner)
        _PDU_KEYS = {name: tuple(found[name]) for name in sorted(found)}
    return _PDU_KEYS


_PDU_KEYS: dict[str, tuple[str, ...]] | None = None


def unknown_pdu_key(key: str) -> str | None:
    """Why `fields.KEY` names nothing (with the nearest keys), or None when a layout has that key."""
    keys = pdu_keys()
    if key in keys:
        return None
    import difflib

    close = difflib.get_close_matches(key, list(keys), n=3)
    hint = f" (did you mean {', '.join('fields.' + name for name in close)}?)" if close else ""
    return f"no PDU layout has the key {key!r}{hint}; -G fields lists them"


def _owners(owners: tuple[str, ...]) -> str:
    if owners == ("any",):
        return "the undecoded PDU of an unknown function"
    codes = [owner for owner in owners if owner not in ("exception", "any")]
    words = [f"function{'s' if len(codes) > 1 else ''} {' '.join(codes)}"] if codes else []
    if "exception" in owners:
        words.append("exceptions")
    if "any" in owners:
        words.append("unknown functions")
    return "PDU key of " + " and ".join(words)


def field_listing() -> str:
    """`-Y help` (and `-G fields`): every field a filter and -T fields know, its type and meaning."""
    lines = ["Display filter and -T fields keys (-Y EXPR, -e KEY); register keys test one register at a time:"]
    groups = [("frame", FRAME_FIELDS), ("time", TIME_FILTER_FIELDS), ("register", REGISTER_FIELDS)]
    for group, fields in groups:
        for name, ftype in fields.items():
            lines.append(f"{name:<22} {group:<9} {_TYPE_WORDS[ftype]:<14} {FIELD_HELP.get(name, '')}")
    for key, owners in pdu_keys().items():  # fields.KEY: the keys of the protocol table's layouts
        lines.append(f"{'fields.' + key:<22} {'frame':<9} {'value':<14} {_owners(owners)}")
    lines.append(f"{'time_delta_displayed':<22} {'-T only':<9} {'number':<14} seconds since the item shown before")
    lines.append("operators: == != < <= > >= & in {..} a..b contains matches ~ and or not ( ); "
                 "values: 12 0x8000 16#8000 \"text\" true false")
    return "\n".join(lines) + "\n"
