"""`-G fields`: vw3-decode's fields in tshark 4.0's -G fields format, one tab-separated line each,

    P  name  abbrev                                            (the protocol)
    F  name  abbrev  type  parent  base  bitmask  blurb       (a field)

the abbrev being the key -Y and -e take. A key the plugin has a field for (data/fields.toml `filter`) is
typed and based as tshark lists that field, unless vw3-decode compares it otherwise (`kind` is text here,
a number there); `fields.KEY` as the protocol table's grammar reads it. `-Y help` is the readable listing
(filter_fields.field_listing)."""
from __future__ import annotations

from typing import Any

from dissector.render.filter_fields import CATALOGUE, FIELD_HELP, layout_fields, owners_text, pdu_keys

# The plugin's Proto (lua/src/fields.lua): tests/unit/test_glossary.py holds the two equal.
PROTOCOL = ("VW3 Modbus serial (Altivar 71, SEL-749M)", "vw3")
# The plugin's ProtoField constructor -> tshark's type, base column (an integer's comes from its base)
FTYPES = {"string": ("FT_STRING", ""), "bool": ("FT_BOOLEAN", "0"), "double": ("FT_DOUBLE", ""),
          "framenum": ("FT_FRAMENUM", ""), "relative_time": ("FT_RELATIVE_TIME", ""), "none": ("FT_NONE", ""),
          "bytes": ("FT_BYTES", "")}
# vw3-decode's own type -> what a field of it would be: a number may be whole or decimal
OWN_TYPES = {"number": "double", "str": "string", "bool": "bool", "list": "string", "struct": "none"}
# Which plugin constructors hold a value of each of vw3-decode's types
KINDS = {"number": ("uint", "double", "framenum", "relative_time"), "str": ("string",), "bool": ("bool",),
         "list": ("string",), "struct": ("none",)}


def _type(ftype: str, base: str | None) -> tuple[str, str]:
    if ftype.startswith("uint"):
        return f"FT_UINT{ftype[4:]}", f"BASE_{base or 'DEC'}"
    return FTYPES[ftype]


def _field(entry: dict[str, Any]) -> str:
    key, ftype = entry["key"], entry.get("ftype")
    if ftype is None or not ftype.startswith(KINDS[entry["type"]]):
        ftype = OWN_TYPES[entry["type"]]
    name = entry.get("title") or key.replace("_", " ").capitalize()
    return _line(name, key, *_type(ftype, entry.get("base")), FIELD_HELP[key])


def _line(name: str, abbrev: str, ftype: str, base: str, blurb: str) -> str:
    return "\t".join(["F", name, abbrev, ftype, PROTOCOL[1], base, "0x0", blurb])


def pdu_key_types() -> dict[str, str]:
    """fields.KEY -> a ProtoField constructor, from the grammar's fields of that name in every layout:
    uintN when each reads an integer (the widest), bytes when each reads bytes, none (a structure: a
    list, a sub-record, a choice) otherwise."""
    found: dict[str, set[str]] = {}
    for _owner, sub in layout_fields():
        inner = getattr(sub, "subcon", sub)
        kind = type(inner).__name__
        if kind == "FormatField":
            ftype = f"uint{8 * inner.length}"
        else:
            ftype = "bytes" if kind == "GreedyBytes" else "none"
        found.setdefault(sub.name, set()).add(ftype)
    types = {}
    for key, kinds in found.items():
        if all(kind.startswith("uint") for kind in kinds):
            types[key] = max(kinds, key=lambda kind: int(kind[4:]))
        else:
            types[key] = kinds.pop() if len(kinds) == 1 else "none"
    return types


def glossary() -> str:
    lines = ["\t".join(["P", *PROTOCOL])]
    lines += [_field(entry) for entry in CATALOGUE if "key" in entry]
    lines.append(_line("Time delta from previous displayed frame", "time_delta_displayed", "FT_DOUBLE", "",
                       "seconds since the item shown before (-T fields only)"))
    types = pdu_key_types()
    for key, owners in pdu_keys().items():  # fields.KEY: the keys of the protocol table's layouts
        lines.append(_line(f"PDU {key.replace('_', ' ')}", f"fields.{key}", *_type(types[key], None),
                           owners_text(owners)))
    return "\n".join(lines) + "\n"
