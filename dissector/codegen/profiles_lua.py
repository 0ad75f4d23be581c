"""The plugin's built-in device profiles and their register maps as Lua data (DATA.profiles, written by
codegen/lua.py plugin_data), from the same profiles and maps the Python annotator loads."""
from __future__ import annotations

from typing import Any

from dissector.devices import access, maps

def profile_data() -> dict[str, Any]:
    """Built-in device profiles with their register maps, as the Python annotator loads them."""
    from dissector.devices import selection
    from dissector.devices.profiles import (
        AUTO, BUILTIN_PROFILES, DEFAULT_PROFILE, FALLBACK_PROFILE, load_profile, load_profile_map,
    )

    profiles = {}
    for name in BUILTIN_PROFILES:
        profile = load_profile(name)
        profiles[profile.name] = profile_table(profile, load_profile_map(profile))
    candidates = [name for name in BUILTIN_PROFILES if name != FALLBACK_PROFILE]
    return {
        "profiles": profiles,
        "default_profile": DEFAULT_PROFILE,
        # Profile `auto` (devices/selection.py): the fallback until evidence, the candidates in the order
        # build_annotator judges them, and how many of a slave's answers (frames) its traffic is judged on.
        "selection": {
            "auto": AUTO,
            "fallback": FALLBACK_PROFILE,
            "candidates": candidates,
            # The candidate a function code identifies: the first, in the candidates' order, that claims it,
            # and the code's name on it (its number where it has none).
            "identifying": {
                code: [name, profiles[name]["function_names"].get(code, str(code))]
                for name in reversed(candidates) for code in profiles[name]["identify"]["functions"]
            },
            # The ProductCode prefixes that identify a candidate, [prefix, candidate] in the candidates' order.
            "product_codes": [
                [code, name] for name in candidates for code in profiles[name]["identify"]["product_codes"]
            ],
            "fit_answers": selection.FIT_ANSWERS,
            "fit_frames": selection.FIT_FRAMES,
            "fit_reads": selection.FIT_READS,
            "product_code_object": selection.PRODUCT_CODE,
        },
        # A map row's cells that contradict each other, in the order judged (maps.CONFLICTS: lua/src/maps.lua).
        "map_conflicts": [list(conflict) for conflict in maps.CONFLICTS],
    }


def profile_table(profile: Any, rows: dict[int, Any]) -> dict[str, Any]:
    from dissector.devices import checks, explain

    causes = {
        # (its counters apart too: a refused read-only write's note names them, explain._read_only_note)
        function * 256 + code: [
            {"text": explain.cause_text(cause), "when": cause.when, "counters": list(cause.counters)}
            for cause in entries
        ]
        for (function, code), entries in sorted(profile.exception_causes.items())
    }
    return {
        "name": profile.name,
        "title": profile.title,
        "device": profile.device,
        "address_style": profile.address_style,
        # (FC4 reads the holding registers: a reference map's 3X rows join its 4X rows, lua/src/device.lua)
        "one_table": profile.input_registers == "holding",
        "functions": profile.functions,
        "inner_only": profile.inner_only,
        "broadcast": profile.broadcast,
        "broadcast_allowed": checks.broadcast_allowed(profile),  # (as the device's broadcast warning lists them)
        "protected_value": profile.protected_value,
        "all_protected_exception": profile.all_protected_exception,
        # (its meaning to a read of registers, with p.38's clause: explain.device_meaning)
        "all_protected_read": explain.device_meaning(profile, min(explain.REGISTER_READS), profile.all_protected_exception)
        if profile.all_protected_exception is not None else None,
        "limits": {code: list(values) for code, values in sorted(profile.limits.items())},
        "exceptions": dict(sorted(profile.exceptions.items())),
        "documented": explain.documented(profile),  # (as the undocumented exception's note lists them)
        "exception_causes": causes,
        "diagnostics": dict(sorted(profile.diagnostics.items())),
        "subfunctions": profile.subfunctions,
        "diagnostic_constants": dict(sorted(profile.diagnostic_constants.items())),
        "objects": {
            key: {"meaning": meaning.meaning, "format": meaning.format, "max_length": meaning.max_length}
            for key, meaning in sorted(profile.objects.items())
        },
        "function_names": dict(sorted(profile.function_names.items())),
        "plc_base": dict(sorted(profile.plc_base.items())),
        "plc_base_default": profile.plc_base_default,
        "bits_depend": [
            {
                "registers": sorted(rule.registers),
                "on": rule.on,
                "plain_when": rule.plain_when,
                "reason": rule.reason,
            }
            for rule in profile.bits_depend
        ],
        "map": {address: row_table(row) for address, row in sorted(rows.items())},
        "identify": {
            "product_codes": list(profile.product_codes),
            "functions": profile.identifying_functions,
            "traffic_fit": profile.traffic_fit,
        },
    }


def row_table(row: Any) -> dict[str, Any]:
    out: dict[str, Any] = {"code": row.code}
    for key in ("name", "unit", "scale", "source"):
        if getattr(row, key) is not None:
            out[key] = getattr(row, key)
    if row.enum:
        out["enum"] = dict(sorted(row.enum.items()))
    if row.bits:
        out["bits"] = dict(sorted(row.bits.items()))
    if row.signed:
        out["signed"] = True
    if row.decimals:
        out["decimals"] = row.decimals
    if row.scale_unknown:
        out["scale_unknown"] = True
    if row.ambiguous_8000:
        out["ambiguous_8000"] = True
    if row.access == access.READ_ONLY:
        out["read_only"] = True
    if row.words != 1:
        out["words"], out["kind"] = row.words, row.kind
    if row.swapped:
        out["swapped"] = True
    return out
