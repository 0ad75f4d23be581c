"""`-G fields`: vw3-decode's fields in tshark 4.0's -G fields format, one tab-separated line each,

    P  name  abbrev                                            (the protocol)
    F  name  abbrev  type  parent  base  bitmask  blurb       (a field)

the abbrev being the key -Y and -e take. A key the plugin has a field for (data/fields.toml `filter`) is
typed and based as tshark lists that field, unless vw3-decode compares it otherwise (`kind` is text here,
a number there); `fields.KEY` as the protocol table's grammar reads it. `-Y help` is the readable listing
(filter_fields.field_listing)."""
from __future__ import annotations

from typing import Any

from dissector.render.filter_fields import (
    CATALOGUE, FIELD_HELP, FRAME_FIELDS, OWN_FTYPES, owners_text, pdu_key_types, pdu_keys,
)

# The plugin's Proto (lua/src/fields.lua): tests/unit/test_glossary.py holds the two equal.
PROTOCOL = ("VW3 Modbus serial (Altivar 71, SEL-749M)", "vw3")
# The plugin's ProtoField constructor -> tshark's type, base column (an integer's comes from its base)
FTYPES = {"string": ("FT_STRING", ""), "bool": ("FT_BOOLEAN", "0"), "double": ("FT_DOUBLE", ""),
          "framenum": ("FT_FRAMENUM", ""), "relative_time": ("FT_RELATIVE_TIME", ""), "none": ("FT_NONE", ""),
          "bytes": ("FT_BYTES", "")}
# vw3-decode's own type -> what a field of it would be: a number may be whole or decimal
OWN_TYPES = {"number": "double", "str": "string", "bool": "bool", "list": "string", "struct": "none",
             "bytes": "bytes"}
# Which plugin constructors hold a value of each of vw3-decode's types
KINDS = {"number": ("uint", "double", "framenum", "relative_time"), "str": ("string",), "bool": ("bool",),
         "list": ("string",), "struct": ("none",),
         "bytes": ("bytes",)}


def _type(ftype: str, base: str | None) -> tuple[str, str]:
    if ftype.startswith("uint"):
        return f"FT_UINT{ftype[4:]}", f"BASE_{base or 'DEC'}"
    return FTYPES[ftype]


def _entry_type(entry: dict[str, Any]) -> tuple[str, str]:
    """The tshark type and base column of a catalogue key."""
    key, ftype = entry["key"], entry.get("ftype") or OWN_FTYPES.get(entry["key"])
    own = FRAME_FIELDS.get(key, entry["type"])  # (raw: bytes to -Y, text in the JSON)
    if ftype is None or not ftype.startswith(KINDS[own]):
        ftype = OWN_TYPES[own]
    return _type(ftype, entry.get("base"))


def _field(entry: dict[str, Any]) -> str:
    name = entry.get("title") or entry["key"].replace("_", " ").capitalize()
    return _line(name, entry["key"], *_entry_type(entry), FIELD_HELP[entry["key"]])


def field_type(key: str) -> str:
    """The tshark type -G fields lists for a key (FT_UINT16, FT_STRING...), as -Y's functions and
    arithmetic type it (render/filter_expr.py); FT_NONE for a name that is no key."""
    if key.startswith("fields."):
        return _type(pdu_key_types().get(key[7:], "none"), None)[0]
    if key == "time_delta_displayed":
        return FTYPES["relative_time"][0]
    if key == "comment":
        return FTYPES["string"][0]
    entry = _ENTRIES.get(key)
    return "FT_NONE" if entry is None else _entry_type(entry)[0]


_ENTRIES = {entry["key"]: entry for entry in CATALOGUE if "key" in entry}


def _line(name: str, abbrev: str, ftype: str, base: str, blurb: str) -> str:
    return "\t".join(["F", name, abbrev, ftype, PROTOCOL[1], base, "0x0", blurb])


def glossary() -> str:
    lines = ["\t".join(["P", *PROTOCOL])]
    lines += [_field(entry) for entry in CATALOGUE if "key" in entry]
    lines.append(_line("Comment", "comment", *FTYPES["string"], FIELD_HELP["comment"]))
    lines.append(_line("Time delta from previous displayed frame", "time_delta_displayed",
                       *FTYPES["relative_time"],
                       "seconds since the item shown before (-T fields only)"))
    types = pdu_key_types()
    for key, owners in pdu_keys().items():  # fields.KEY: the keys of the protocol table's layouts
        lines.append(_line(f"PDU {key.replace('_', ' ')}", f"fields.{key}", *_type(types[key], None),
                           owners_text(owners)))
    return "\n".join(lines) + "\n"
