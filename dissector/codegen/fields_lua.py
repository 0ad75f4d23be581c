"""The plugin's ProtoFields from the catalogue vw3-decode's filters read (data/fields.toml, loaded by
render/filter_fields.py): per field its name, constructor, title, base, value strings and meaning, as
lua/vw3.lua's DATA.fields, which lua/src/fields.lua turns into ProtoFields."""
from __future__ import annotations

from typing import Any

from dissector.errors import GenerateError
from dissector.render.filter_fields import CATALOGUE

# ProtoField constructors by their arguments: (abbr, title, base, values, mask, help) or (abbr, title, help)
INTEGER = frozenset({"uint8", "uint16", "uint32", "bool", "framenum"})
PLAIN = frozenset({"string", "bytes", "none", "double", "relative_time"})


def plugin_fields() -> list[dict[str, Any]]:
    """One table a plugin field, in the catalogue's order: {abbr, ftype, title, help, [base], [values]}."""
    out = []
    for entry in CATALOGUE:
        if "filter" not in entry:
            continue
        ftype = entry["ftype"]
        if ftype not in INTEGER | PLAIN or (ftype in PLAIN and ("base" in entry or "values" in entry)):
            raise GenerateError(f"data/fields.toml: {entry['filter']}: no ProtoField.{ftype} with those arguments")
        field = {"abbr": entry["filter"], "ftype": ftype, "title": entry["title"], "help": entry["help"]}
        for key in ("base", "values"):
            if key in entry:
                value = entry[key]
                # (a value-string table: TOML keys are strings, Wireshark's are the numbers)
                field[key] = {int(k): v for k, v in value.items()} if isinstance(value, dict) else value
        out.append(field)
    return out
