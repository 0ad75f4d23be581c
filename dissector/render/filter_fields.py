"""The fields of display filters and -T fields: names, types, meanings, and their listing (-Y help;
-G fields: render/glossary.py). Kept apart from filters.py (the parser) so each stays small; filters.py
re-exports them."""
from __future__ import annotations

import tomllib
from importlib import resources
from collections.abc import Iterator
from typing import Any

# The catalogue of fields (data/fields.toml), shared with the Wireshark plugin (codegen/fields_lua.py
# makes its ProtoFields from the same entries): each [[field]] with a vw3-decode key gives its group, type
# (number: integer or decimal, str, bool, list of strings, struct: presence) and meaning.
CATALOGUE: list[dict[str, Any]] = tomllib.loads(
    resources.files("dissector").joinpath("data/fields.toml").read_text(encoding="utf-8"))["field"]


def _group(group: str) -> dict[str, str]:
    return {entry["key"]: entry["type"] for entry in CATALOGUE if "key" in entry and entry.get("group", "frame") == group}


# The ProtoField type of keys the plugin has no field for whose catalogue type does not tell it: raw is hex
# text in the JSON, bytes to -Y (as tshark's frame: contains 0c:03, raw[0:2]); length counts bytes; the
# times are tshark's frame.time_epoch, time_relative, time_delta (-T fields writes them as those), which
# tshark 4.0.17 types FT_RELATIVE_TIME (a time takes 1.5, not 0x1, 1e-3 or '\x01'; + and - only).
OWN_FTYPES = {"raw": "bytes", "length": "uint32", "time": "relative_time", "time_relative": "relative_time",
              "time_delta": "relative_time", "time_delta_displayed": "relative_time"}
# Keys the catalogue has not, each read from another key of the record: a pcapng packet comment, tshark's
# frame.comment (one occurrence each), is the JSON's `comments` (app/inputs.py comments_of puts them there).
RECORD_KEYS = {"comment": "comments"}
# field -> type, per group
FRAME_FIELDS: dict[str, str] = _group("frame") | {"raw": "bytes", "comment": "list"}
# Numbers the time column shows, computed from the capture (FilterContext), as -T fields has them.
TIME_FILTER_FIELDS: dict[str, str] = _group("time")
REGISTER_FIELDS: dict[str, str] = _group("register")
# A register's text keys: the plugin gives each register a frame carries every one of them, empty (a hidden
# item) where the register has none, so that tshark -T fields lines them up; to tshark's -Y that empty
# occurrence is a value (`vw3.reg.code == ""`, `vw3.reg.code == vw3.reg.name`), so -T fields and -Y read ""
# there too (filter_match.register_value). Bits and the addresses a frame only names have none.
REGISTER_TEXTS = frozenset(key for key, ftype in REGISTER_FIELDS.items() if ftype == "str")
# Present only where true in the plugin (vw3.unanswered): where false, no occurrence in -T fields and
# absent to -Y (`broadcast` alone and `broadcast == false` match no frame a plain request), as tshark has it.
ONLY_TRUE = frozenset(entry["key"] for entry in CATALOGUE if entry.get("only_true"))
# Other names of fields, as -Y help lists them (`alias: exception`): -Y and -e take them alike.
ALIASES: dict[str, str] = {"exception": "exception_code"}
# Names a Wireshark user types, the plugin's (data/fields.toml `filter`) and tshark's own mbrtu and modbus
# fields', -> vw3-decode's key, which -Y's error names (`vw3.slave`: "vw3-decode names it slave"). Only
# named, not taken: where the semantics differ (mbrtu.crc16 reads the CRC's bytes high byte first, 0x3477
# where crc is 0x7734; modbus.reference_num is on requests only, start on their answers too) a silent alias
# would filter other frames than the user's Wireshark does.
FOREIGN_NAMES: dict[str, str] = {
    entry["filter"]: entry["key"] for entry in CATALOGUE if "key" in entry and "filter" in entry
} | {
    "frame.number": "record", "frame.time_epoch": "time", "frame.time": "time", "frame.len": "length",
    "frame.cap_len": "length", "frame.comment": "comment", "mbrtu.unit_id": "slave", "mbrtu.crc16": "crc",
    "modbus.func_code": "function", "modbus.exception_code": "exception_code", "modbus.request_frame": "request_frame",
    "modbus.response_time": "response_time", "modbus.reference_num": "start", "modbus.word_cnt": "quantity",
    "modbus.bit_cnt": "quantity", "modbus.regnum16": "address", "modbus.regval_uint16": "value",
    "modbus.diagnostic_code": "subfunction", "modbus.byte_cnt": "fields.byte_count", "modbus.and_mask": "fields.and_mask",
    "modbus.or_mask": "fields.or_mask", "modbus.data": "fields.data", "modbus.mei": "fields.mei_type",
    "modbus.event": "fields.event_list", "modbus.ev_count": "fields.event_count",
}
# field -> its meaning as -Y help and -G fields list it (with what only vw3-decode's filters take, as
# `alias: exception`)
FIELD_HELP: dict[str, str] = {
    entry["key"]: entry["help"] + (f" ({entry['note']})" if "note" in entry else "")
    for entry in CATALOGUE if "key" in entry
} | {"comment": "a pcapng packet comment (tshark's frame.comment), one occurrence each"}

_TYPE_WORDS = {"number": "number", "str": "text", "bool": "true/false", "list": "list of texts",
               "struct": "structure", "any": "value", "bytes": "byte string"}


def layout_fields() -> Iterator[tuple[str, Any]]:
    """(owner, named field of its grammar) for every PDU layout of the protocol table (protocol/table.py):
    owner a function code, `exception` or `any` (the undecoded PDU of an unknown function)."""
    from dissector.protocol import table

    layouts = [(str(entry.code), layout)
               for entry in table.FUNCTIONS for layout in (entry.request, entry.response)]
    layouts += [("exception", table.EXCEPTION_LAYOUT), ("any", table.RAW_LAYOUT)]
    for owner, layout in layouts:
        grammar = layout.grammar
        while getattr(grammar, "subcons", None) is None and getattr(grammar, "subcon", None) is not None:
            grammar = grammar.subcon
        for sub in getattr(grammar, "subcons", ()):
            if sub.name:
                yield owner, sub


# Keys the decode adds to a PDU's fields beyond its layout's (decode/fields.py) -> (the function codes whose frames
# have them, each element's value -T fields writes and -Y tests, its type): FC12's events by their bytes, as
# tshark's Modbus/TCP writes modbus.event (FT_UINT8, one occurrence an event); --json keeps their names.
DERIVED_KEYS = {"event_list": ("12", "byte", "uint8")}


def pdu_values(fields: Any, key: str) -> list[Any]:
    """The values of `fields.KEY` in a record's fields: a list's elements (a repeated field), a derived key's
    elements' values (DERIVED_KEYS), none when absent."""
    value = fields.get(key) if isinstance(fields, dict) else None
    found = value if isinstance(value, list) else [] if value is None else [value]
    derived = DERIVED_KEYS.get(key)
    return found if derived is None else [element.get(derived[1]) for element in found if isinstance(element, dict)]


def pdu_keys() -> dict[str, tuple[str, ...]]:
    """`fields.KEY`: every key a PDU layout of the protocol table parses -> the function codes
    (`exception`) whose frames have it, from the layouts' grammars, not a list kept here."""
    global _PDU_KEYS
    if _PDU_KEYS is None:
        found: dict[str, list[str]] = {}
        for owner, sub in layout_fields():
            if owner not in found.setdefault(sub.name, []):
                found[sub.name].append(owner)
        for key, (owner, _value, _type) in DERIVED_KEYS.items():
            found[key] = [owner]
        _PDU_KEYS = {name: tuple(found[name]) for name in sorted(found)}
    return _PDU_KEYS


_PDU_KEYS: dict[str, tuple[str, ...]] | None = None


def pdu_key_types() -> dict[str, str]:
    """fields.KEY -> a ProtoField constructor, from the grammar's fields of that name in every layout:
    uintN when each reads an integer or an array of them (fields.values: a repeated field, the widest),
    bytes when each reads bytes, none (a structure: a sub-record, a choice) otherwise."""
    found: dict[str, set[str]] = {}
    for _owner, sub in layout_fields():
        inner = getattr(sub, "subcon", sub)
        if type(inner).__name__ == "Array":
            inner = inner.subcon
        kind = type(inner).__name__
        if kind == "FormatField":
            ftype = f"uint{8 * inner.length}"
        else:
            ftype = "bytes" if kind == "GreedyBytes" else "none"
        found.setdefault(sub.name, set()).add(ftype)
    types = {key: ftype for key, (_owner, _value, ftype) in DERIVED_KEYS.items()}
    for key, kinds in found.items():
        if all(kind.startswith("uint") for kind in kinds):
            types[key] = max(kinds, key=lambda kind: int(kind[4:]))
        else:
            types[key] = kinds.pop() if len(kinds) == 1 else "none"
    return types


def whole_number(field: str) -> bool:
    """Does tshark refuse 1.0 and 1e0 for the field (an integer or frame number: vw3.item == 1e0)?"""
    if field.startswith("fields."):
        return pdu_key_types().get(field[7:], "").startswith("uint")
    ftype = FTYPES.get(field) or OWN_FTYPES.get(field, "")
    return ftype.startswith("uint") or ftype == "framenum"


FTYPES = {entry["key"]: entry["ftype"] for entry in CATALOGUE if "key" in entry and "ftype" in entry}


def unknown_pdu_key(key: str) -> str | None:
    """Why `fields.KEY` names nothing (with the nearest keys), or None when a layout has that key."""
    keys = pdu_keys()
    if key in keys:
        return None
    import difflib

    close = difflib.get_close_matches(key, list(keys), n=3)
    hint = f" (did you mean {', '.join('fields.' + name for name in close)}?)" if close else ""
    return f"no PDU layout has the key {key!r}{hint}; -G fields lists them"


def foreign_name(name: str) -> str | None:
    """vw3-decode's key for a Wireshark field name (FOREIGN_NAMES; the plugin's vw3.X of a PDU key X, such as
    vw3.byte_count, is fields.X; frame.X is X where vw3-decode has one), None for a name it has no key for."""
    if name in FOREIGN_NAMES:
        return FOREIGN_NAMES[name]
    last = name.rsplit(".", 1)[-1]
    if name.startswith("vw3.") and name.count(".") == 1 and last in pdu_keys():
        return "fields." + last
    if name.startswith("frame.") and last in FRAME_FIELDS | TIME_FILTER_FIELDS:
        return last
    return None


def owners_text(owners: tuple[str, ...]) -> str:
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
    """`-Y help`: every field a filter and -T fields know, its type and meaning, to read."""
    lines = ["Display filter and -T fields keys (-Y EXPR, -e KEY); register keys test one register at a time:"]
    groups = [("frame", FRAME_FIELDS), ("time", TIME_FILTER_FIELDS), ("register", REGISTER_FIELDS)]
    for group, fields in groups:
        for name, ftype in fields.items():
            lines.append(f"{name:<22} {group:<9} {_TYPE_WORDS[ftype]:<14} {FIELD_HELP.get(name, '')}")
    for key, owners in pdu_keys().items():  # fields.KEY: the keys of the protocol table's layouts
        lines.append(f"{'fields.' + key:<22} {'frame':<9} {'value':<14} {owners_text(owners)}")
    lines.append(f"{'time_delta_displayed':<22} {'-T only':<9} {'number':<14} seconds since the item shown before")
    lines.append("operators: == != (all_ne: has it, none equal) ~= !== (any_ne: some differs) === (all_eq) "
                 "< <= > >= & in {3, 4, 8400..8402} "
                 "contains matches ~ and or not ( ); values: 12 0x8000 16#8000 13.5e-3 \"text\" true false, "
                 "bytes "
                 "0c:03 (raw contains 0c:03, raw[0:2] == 0c03), 'a'; a field "
                 "alone tests its presence (crc_ok: checked, good or bad; crc_ok == 1: good); functions "
                 "len() count() upper() lower() string() max() min() abs(), arithmetic + - * / % "
                 "({slave + 1} == 13)")
    return "\n".join(lines) + "\n"
