"""The plugin's ProtoFields from the catalogue vw3-decode's filters read (data/fields.toml, loaded by
render/filter_fields.py): per field its name, constructor, title, base, value strings and meaning, as
lua/vw3.lua's DATA.fields.fields, which lua/src/fields.lua turns into ProtoFields; and the plugin's expert
infos and preferences from the same file's [[expert]] and [[preference]] entries, as DATA.fields.experts and
DATA.fields.preferences; and a field per parameter of the built-in register maps, DATA.fields.parameters;
the fields that show each PDU field (data/pdu_fields.toml, with its plugin-only fields: each layout field's
`shown` in DATA.rules, codegen/rules_lua.py),
the value strings they name from the spec (DATA.fields.names) and the title of a start that is no window
(DATA.fields.start_words); and the Info column's forms vw3-decode gives each function code in each direction
(render/describe.py TEXT_FORMS: DATA.fields.info), with their limits and words."""
from __future__ import annotations

import re
import tomllib
from importlib import resources
from typing import Any

from dissector.errors import GenerateError
from dissector.protocol.spec import SPEC
from dissector.render.filter_fields import CATALOGUE, DERIVED_KEYS, owners_text

# ProtoField constructors by their arguments: (abbr, title, base, values, mask, help) or (abbr, title, help)
INTEGER = frozenset({"uint8", "uint16", "uint32", "bool", "framenum"})
PLAIN = frozenset({"string", "bytes", "none", "double", "relative_time"})


def plugin_fields() -> dict[str, Any]:
    """The plugin's fields and expert infos: {"fields": [...], "experts": [...], ...}."""
    return {"fields": proto_fields(), "experts": experts(), "preferences": preferences(),
            "parameters": parameter_fields(),
            "names": {"mei_types": SPEC.mei_types, "device_id_codes": SPEC.device_id_codes},
            "start_words": start_words(), "info": info_forms()}


def start_words() -> dict[int, dict[str, str]]:
    """{code: {title}}: how the tree names a start that is no window (FC24's FIFO pointer, which vw3-decode's
    Info text calls `pointer`, render/describe.py TEXT_FORMS): vw3-decode -V's label of the field
    (render/detail.py FUNCTION_LABELS)."""
    from dissector.render.describe import _FORMS
    from dissector.render.detail import FUNCTION_LABELS

    out = {}
    for (code, request), (_text, form) in sorted(_FORMS.items()):
        if not request or form != "pointer":
            continue
        titles = [label for (function, _key), label in FUNCTION_LABELS.items() if function == code]
        if len(titles) != 1:
            raise GenerateError(f"render/detail.py FUNCTION_LABELS: {len(titles)} labels for function {code}'s "
                                "pointer, not one")
        out[code] = {"title": titles[0]}
    return out


# The steps of describe.TEXT_FORMS the plugin interprets (lua/src/tree.lua summary): those of the frame's
# fields read from its bytes, `label` and `span` (its window, tree.lua span_text) and `single` (FC6's value,
# its register named by the device). A form of other steps keeps the plugin's own text, the window: the
# registers' values and bits are left out of its Info by design (its quick lanes keep one Info text for
# every answer to a window, and for a write's request met again with other values: vw3.records), and the
# window alone is that text already (SPAN_ALONE, no form then).
# FC23's request says both its windows (plain_span, write), its values left out as FC16's are: the text
# vw3-decode gives where it writes none (`read 0, write 5 (0)`).
PLUGIN_STEPS = frozenset({"hex", "dec", "count", "coil", "subfunction", "data", "fifo", "label", "span", "single",
                          "plain_span", "write"})
SPAN_ALONE = [("span",)]
# The describers of describe._BY_NAME the plugin has too (tree.lua BY_NAME), by name.
PLUGIN_BY_NAME = frozenset({"mei", "report_server_id", "file_record"})


def info_forms() -> dict[str, Any]:
    """The Info column's forms (render/describe.py TEXT_FORMS) that the plugin says as vw3-decode does: by
    direction and function code, their steps (texts, and steps as lists; a describer of describe._BY_NAME:
    its name), and the limits and words they use."""
    from dissector.render import describe

    forms: dict[str, dict[int, str]] = {"request": {}, "response": {}}
    steps: dict[str, list[Any]] = {}
    for (code, request), (text, form) in sorted(describe._FORMS.items()):
        if form is None and text in PLUGIN_BY_NAME:  # (its steps: the describer's name)
            forms["request" if request else "response"][code] = steps[text] = text
        if form is None or describe.TEXT_FORMS[form] == SPAN_ALONE or not all(
                isinstance(step, str) or step[0] in PLUGIN_STEPS for step in describe.TEXT_FORMS[form]):
            continue
        forms["request" if request else "response"][code] = form
        steps[form] = [step if isinstance(step, str) else list(step) for step in describe.TEXT_FORMS[form]]
    return {"forms": forms, "steps": steps, "max_data_bytes": describe.MAX_DATA_BYTES,
            "max_fifo_values": describe.MAX_FIFO_VALUES, "unknown_subfunction": describe.UNKNOWN_SUBFUNCTION}


def _catalogue() -> dict[str, Any]:
    return tomllib.loads(resources.files("dissector").joinpath("data/fields.toml").read_text(encoding="utf-8"))


def _pdu_catalogue() -> dict[str, Any]:
    """data/pdu_fields.toml: read here only (vw3-decode reads data/fields.toml at each start)."""
    return tomllib.loads(resources.files("dissector").joinpath("data/pdu_fields.toml").read_text(encoding="utf-8"))


def experts() -> list[dict[str, str]]:
    """One table an expert info, in the catalogue's order: {name, filter, title, group, severity}."""
    keys = ("name", "filter", "title", "group", "severity")
    out = []
    for entry in _catalogue()["expert"]:
        if set(entry) != set(keys):
            raise GenerateError(f"data/fields.toml: expert {entry.get('name')}: needs exactly {', '.join(keys)}")
        out.append({key: entry[key] for key in keys})
    return out


def preferences() -> list[dict[str, Any]]:
    """One table a preference, in the catalogue's order: {name, type, title, help, default | choices}."""
    out = []
    for entry in _catalogue()["preference"]:
        wanted = {"name", "type", "title", "help", "choices" if entry.get("type") == "enum" else "default"}
        if entry.get("type") not in ("string", "uint", "bool", "enum") or set(entry) != wanted:
            raise GenerateError(f"data/fields.toml: preference {entry.get('name')}: needs exactly {', '.join(sorted(wanted))}")
        out.append(dict(entry))
    return out


def proto_fields() -> list[dict[str, Any]]:
    """One table a plugin field, in the catalogue's order, then the decode's derived keys' (derived_fields):
    {abbr, ftype, title, help, [base], [values]}."""
    out = []
    for entry in CATALOGUE + _pdu_catalogue()["field"] + derived_fields():
        if "filter" not in entry:
            continue
        ftype = entry["ftype"]
        if ftype not in INTEGER | PLAIN or (ftype in PLAIN and ("base" in entry or "values" in entry)):
            raise GenerateError(f"data/fields.toml: {entry['filter']}: no ProtoField.{ftype} with those arguments")
        field = {"abbr": entry["filter"], "ftype": ftype, "title": entry["title"], "help": entry["help"]}
        if "name" in entry:
            field["name"] = entry["name"]  # (a filter two fields share, of two widths: vw3.status)
        if ftype in PLAIN:
            field["plain"] = True  # (its constructor takes (abbr, title, help))
        for key in ("base", "values"):
            if key in entry:
                value = entry[key]
                # (a value-string table: TOML keys are strings, Wireshark's are the numbers)
                field[key] = {int(k): v for k, v in value.items()} if isinstance(value, dict) else value
        out.append(field)
    names = [pf_name(entry) for entry in CATALOGUE + _pdu_catalogue()["field"] + derived_fields() if "filter" in entry]
    for name in {name for name in names if names.count(name) > 1}:
        raise GenerateError(f"data/pdu_fields.toml: two fields named {name}: give one a `name`")
    # (Wireshark's filters take a shared name's type from the field registered last, lua/src/fields.lua: the
    # widest last, or a filter of a wider value is refused, `"0xffff" too big for this field`)
    widest: dict[str, int] = {}
    for field in out:
        width = int(field["ftype"][4:]) if field["ftype"].startswith("uint") else 0
        if width < widest.get(field["abbr"], 0):
            raise GenerateError(f"data/pdu_fields.toml: {field['abbr']}: list its widest field last")
        widest[field["abbr"]] = width
    return out


def derived_fields() -> list[dict[str, Any]]:
    """A field per key the decode adds to a PDU's fields beyond its layout's (render/filter_fields.py
    DERIVED_KEYS: FC12's fields.event_list), as vw3.<key>, the plugin's name of fields.<key> (filter_fields
    foreign_name), of its elements' type, its help vw3-decode's -G fields blurb; base DEC, -G fields' base of
    fields.<key>, so -T fields writes the values as vw3-decode's (modbus.event's). Titled by what one
    occurrence is, an element of the list (`Event`, as -V labels an element's event), as tshark titles its
    field of one occurrence an element (modbus.event: `Event`) and the plugin its own (`FIFO value`): a
    column or the status bar then names one event, not the list. lua/src/tree.lua adds it."""
    from dissector.render.detail import field_label

    return [{"filter": f"vw3.{key}", "ftype": ftype, "title": field_label(key.removesuffix("_list")), "base": "DEC",
             "help": owners_text((owner,))} for key, (owner, _value, ftype) in DERIVED_KEYS.items()]


def pf_name(entry: dict[str, Any]) -> str:
    """The plugin's pf key of a field (lua/src/fields.lua): its `name`, else its filter without `vw3.`, dots
    as `_`."""
    return entry.get("name") or entry["filter"][4:].replace(".", "_")


def pdu_fields() -> dict[str, list[str]]:
    """The fields that show each PDU field, {"LAYOUT.FIELD": [pf name, ...]} (pf_name), a text field's string field first; every field of every layout and part
    (data/modbus.toml) is shown so or listed in data/pdu_fields.toml's pdu_shown, a switch by the part it
    chose."""
    from dissector.protocol.shapes import PARTS, SHAPES, Type

    pdu = _pdu_catalogue()
    out: dict[str, list[str]] = {}
    for entry in CATALOGUE + pdu["field"]:
        for name in entry.get("pdu", pdu["pdu"].get(entry.get("filter"), ())):
            out.setdefault(name, []).append(pf_name(entry))
            if entry["ftype"] == "string":  # (a text's string field first, its bytes' after)
                out[name].insert(0, out[name].pop())
    shown = set(pdu["pdu_shown"])
    every = {f"{owner}.{field.name}": field for shapes in (SHAPES, PARTS) for owner, shape in shapes.items()
             for field in shape}
    for name, field in every.items():
        if field.type is Type.SWITCH:
            continue
        if (name in out) == (name in shown):
            raise GenerateError(f"data/fields.toml: PDU field {name}: "
                                + ("shown twice (pdu and pdu_shown)" if name in out else "no field shows it"))
    for name in (out.keys() | shown) - every.keys():
        raise GenerateError(f"data/fields.toml: {name}: no such PDU field (data/modbus.toml [layouts], [parts])")
    return out


def parameter_fields() -> list[dict[str, Any]]:
    """The per-parameter fields (vw3.atv71.rfr, vw3.sel749m.ia, ...): one per row of the built-in register maps
    that has a code, its scaled value (or its value where the map gives no scale), so that an IO graph or a
    column can follow one parameter: {profile, address (the row's in DATA.profiles[profile].map), abbr, title},
    by profile and address; of two rows whose codes give the same abbr, the first. Rows of maps given in the
    plugin's preferences have none (fields exist before any file is read)."""
    from dissector.devices.profiles import BUILTIN_PROFILES, load_profile, load_profile_map

    out, taken = [], set()
    for name in BUILTIN_PROFILES:
        profile = load_profile(name)
        for address, row in sorted(load_profile_map(profile).items()):
            if row.code is None:
                continue
            # (the code's bytes lower-cased, each byte not a letter, digit or _ as _: as Lua's gsub("[^%w_]"))
            code = re.sub(rb"[^0-9A-Za-z_]", b"_", row.code.encode("utf-8").lower()).decode("ascii")
            abbr = f"vw3.{profile.name}.{code}"
            if code == "" or abbr in taken:
                continue
            taken.add(abbr)
            title = row.code if row.name is None else f"{row.name} ({row.code})"
            if row.unit is not None:
                title += ", " + row.unit
            out.append({"profile": profile.name, "address": address, "abbr": abbr, "title": title})
    return out
