"""Device profiles: what a device on the bus does beyond the spec, loaded from data/profiles/*.toml.

A profile names the register map of the device (data/maps/*.csv, see maps.py) and its semantics: the
function codes it supports, its word limits, which functions it accepts as broadcast, what its exception
codes mean (and, for the SEL-749M, which relay counter each error increments), FC8 sub-functions that
differ from the spec, FC43 object meanings, and the value a read returns for a protected parameter.

Users choose profiles per slave (`--profile atv71`, `--profile 12=atv71 --profile 3=sel749m`) and add
maps (`--map FILE`, `--map 3=FILE`, `--map sel749m=FILE`). `build_annotator` turns those choices into the
Annotator (devices/annotator.py) the pipeline calls once per frame.
"""
from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

from dissector.devices.maps import ProfileError, RegisterMap, load_builtin_map, load_map_file
from dissector.devices.readfile import read_capped
from dissector.protocol.printable import printable
from dissector.protocol.spec import SPEC


__all__ = [
    "ADDRESS_STYLES",
    "BUILTIN_PROFILES",
    "Profile",
    "ProfileError",
    "load_profile",
]

BUILTIN_PROFILES = ("atv71", "sel749m", "generic")
AUTO = "auto"  # not a profile: each slave gets one from evidence in the capture (devices/selection.py)
DEFAULT_PROFILE = AUTO
FALLBACK_PROFILE = "generic"  # what `auto` gives a slave until evidence arrives
ADDRESS_STYLES = ("plc", "protocol")
# What FC4 (Read Input Registers) reads: input registers, a table of their own (Application Protocol 4.3:
# FC4's register 5 is not FC3's), or the holding registers, as FC3 does (one table: the ATV71's card).
INPUT_REGISTER_READS = ("separate", "holding")
_WHEN = ("quantity", "byte_count")


@dataclass(frozen=True, slots=True)
class ExceptionCause:
    error: str
    counters: tuple[str, ...]
    when: str | None


@dataclass(frozen=True, slots=True)
class ObjectMeaning:
    meaning: str
    format: str | None = None
    max_length: int | None = None  # the most bytes the device's value holds (ATV71 [DEVICE NAME]: 16)


@dataclass(frozen=True, slots=True)
class BitsDepend:
    registers: frozenset[int]
    on: int
    plain_when: frozenset[int]
    reason: str


@dataclass(slots=True)
class Profile:
    name: str
    title: str
    device: str
    origin: str
    map: str | None = None
    address_style: str = "protocol"
    functions: frozenset[int] | None = None
    inner_only: frozenset[int] = frozenset()
    broadcast: frozenset[int] | None = None
    protected_value: int | None = None
    input_registers: str = "separate"  # INPUT_REGISTER_READS: FC4's registers their own table, or holding
    all_protected_exception: int | None = None
    limits: dict[int, tuple[int, ...]] = field(default_factory=dict)
    exceptions: dict[int, str] = field(default_factory=dict)
    exception_causes: dict[tuple[int, int], tuple[ExceptionCause, ...]] = field(default_factory=dict)
    diagnostics: dict[int, str] = field(default_factory=dict)
    subfunctions: frozenset[int] | None = None  # the FC8 sub-functions it answers (None: every one the spec has)
    diagnostic_constants: dict[int, int] = field(default_factory=dict)  # FC8 counters' one documented value
    objects: dict[int, ObjectMeaning] = field(default_factory=dict)
    function_names: dict[int, str] = field(default_factory=dict)
    plc_base: dict[int, int] = field(default_factory=dict)
    plc_base_default: int = 40001
    bits_depend: tuple[BitsDepend, ...] = ()
    # [identify]: what tells profile `auto` a slave is this device (devices/selection.py).
    product_codes: tuple[str, ...] = ()  # FC43 ProductCode prefixes
    identifying_functions: frozenset[int] = frozenset()  # function codes only this device speaks
    traffic_fit: bool = False  # may be chosen because the traffic fits its map alone


# A parameter is a register of one table (Application Protocol 4.3: input registers and holding registers
# are tables of their own; FC4's register 5 is not FC3's): the PLC reference class its code's registers
# are in, as data/modbus.toml [plc_references] states it (FC4: 30001, 3X), else holding registers (4X).
# Holding registers are 0: a store's parameter of no table given (the compiled store's default too).
# A device may read both with one table (profile input_registers "holding": device_tables).
HOLDING_REGISTERS, INPUT_REGISTERS = 0, 1


def register_table(function: int) -> int:
    """The table (INPUT_REGISTERS, HOLDING_REGISTERS) of the registers a code reads or writes."""
    return INPUT_REGISTERS if SPEC.plc_references.get(function, 0) // 10000 == 3 else HOLDING_REGISTERS


# Each code's table, as the compiled store takes them (_stats.h Stats.tables, stats_store.new_store).
TABLES = bytes(register_table(code) for code in range(256))
# ... on a device whose FC4 reads its holding registers (profile input_registers "holding": the ATV71).
ONE_TABLE = bytes(HOLDING_REGISTERS for _code in range(256))


def device_tables(profile: Profile | None) -> bytes:
    """Each code's register table on a slave of this profile (None: the protocol's, TABLES)."""
    return ONE_TABLE if getattr(profile, "input_registers", None) == "holding" else TABLES


# -- loading ------------------------------------------------------------------------------------------
class _Reader:
    """Typed access to one TOML table, with errors that name the file and the key."""

    def __init__(self, origin: str) -> None:
        self.origin = origin

    def fail(self, message: str) -> ProfileError:
        return ProfileError(f"{self.origin}: {message}")

    def string(self, data: dict[str, Any], key: str, default: str | None = None) -> str | None:
        value = data.get(key, default)
        if value is not None and not isinstance(value, str):
            raise self.fail(f"{key} must be a string")
        # A profile's texts are shown: control characters escaped (the map's file name is a path).
        return value if value is None or key == "map" else printable(value)

    def integer(self, value: Any, what: str, low: int = 0, high: int = 0xFFFF) -> int:
        if isinstance(value, str):
            try:
                value = int(value, 0)
            except ValueError:
                raise self.fail(f"{what}: {value!r} is not a number") from None
        if not isinstance(value, int) or isinstance(value, bool) or not low <= value <= high:
            raise self.fail(f"{what}: {value!r} is not a number in {low}..{high}")
        return value

    def codes(self, data: dict[str, Any], key: str) -> frozenset[int] | None:
        value = data.get(key)
        if value is None:
            return None
        if not isinstance(value, list):
            raise self.fail(f"{key} must be a list of numbers")
        return frozenset(self.integer(item, key, 0, 255) for item in value)

    def table(self, data: dict[str, Any], key: str) -> dict[str, Any]:
        value = data.get(key, {})
        if not isinstance(value, dict):
            raise self.fail(f"[{key}] must be a table")
        return value

    def code_names(self, data: dict[str, Any], key: str, high: int = 255) -> dict[int, str]:
        out = {}
        for code, text in self.table(data, key).items():
            if not isinstance(text, str):
                raise self.fail(f"[{key}] {code} must be a string")
            out[self.integer(code, f"[{key}] key", 0, high)] = printable(text)
        return out


def _limits(reader: _Reader, data: dict[str, Any]) -> dict[int, tuple[int, ...]]:
    out = {}
    for code, value in reader.table(data, "limits").items():
        function = reader.integer(code, "[limits] key", 1, 255)
        values = value if isinstance(value, list) else [value]
        if not values or len(values) > 2:
            raise reader.fail(f"[limits] {code} must be a number or [read, write]")
        out[function] = tuple(reader.integer(item, f"[limits] {code}", 1, 0xFFFF) for item in values)
    return out


def _causes(reader: _Reader, data: dict[str, Any]) -> dict[tuple[int, int], tuple[ExceptionCause, ...]]:
    grouped: dict[tuple[int, int], list[ExceptionCause]] = {}
    entries = data.get("exception_causes", [])
    if not isinstance(entries, list):
        raise reader.fail("exception_causes must be an array of tables ([[exception_causes]])")
    for index, entry in enumerate(entries, start=1):
        what = f"exception_causes #{index}"
        if not isinstance(entry, dict):
            raise reader.fail(f"{what} must be a table")
        functions = reader.codes(entry, "functions")
        if not functions:
            raise reader.fail(f"{what} needs functions")
        code = reader.integer(entry.get("code"), f"{what} code", 0, 255)
        error = reader.string(entry, "error")
        if not error:
            raise reader.fail(f"{what} needs an error text")
        counters = entry.get("counters", [])
        if not isinstance(counters, list) or not all(isinstance(item, str) for item in counters):
            raise reader.fail(f"{what} counters must be a list of strings")
        when = reader.string(entry, "when")
        if when is not None and when not in _WHEN:
            raise reader.fail(f"{what} when must be one of {', '.join(_WHEN)}")
        cause = ExceptionCause(error, tuple(counters), when)
        for function in sorted(functions):
            grouped.setdefault((function, code), []).append(cause)
    return {key: tuple(value) for key, value in grouped.items()}


def _objects(reader: _Reader, data: dict[str, Any]) -> dict[int, ObjectMeaning]:
    out = {}
    for key, entry in reader.table(data, "objects").items():
        object_id = reader.integer(key, "[objects] key", 0, 255)
        if not isinstance(entry, dict) or not isinstance(entry.get("meaning"), str):
            raise reader.fail(f"[objects.{key}] needs a meaning string")
        form = reader.string(entry, "format")
        if form not in (None, "MMmm"):
            raise reader.fail(f"[objects.{key}] format {form!r} is unknown (known: MMmm)")
        longest = entry.get("max_length")
        out[object_id] = ObjectMeaning(entry["meaning"], form, None if longest is None else reader.integer(
            longest, f"[objects.{key}] max_length", 1, 255))
    return out


def _bits_depend(reader: _Reader, data: dict[str, Any]) -> tuple[BitsDepend, ...]:
    out = []
    for index, entry in enumerate(data.get("bits_depend", []), start=1):
        what = f"bits_depend #{index}"
        if not isinstance(entry, dict):
            raise reader.fail(f"{what} must be a table")
        registers = entry.get("registers")
        plain = entry.get("plain_when")
        if not isinstance(registers, list) or not isinstance(plain, list):
            raise reader.fail(f"{what} needs registers and plain_when lists")
        out.append(
            BitsDepend(
                registers=frozenset(reader.integer(item, f"{what} registers") for item in registers),
                on=reader.integer(entry.get("on"), f"{what} on"),
                plain_when=frozenset(reader.integer(item, f"{what} plain_when") for item in plain),
                reason=reader.string(entry, "reason") or "bits not named",
            )
        )
    return tuple(out)


_KNOWN_KEYS = frozenset(
    [
        "name", "title", "device", "map", "address_style", "functions", "inner_only", "broadcast",
        "protected_value", "input_registers", "all_protected_exception", "limits", "exceptions",
        "exception_causes",
        "diagnostics", "subfunctions", "diagnostic_constants", "objects", "function_names", "plc_base", "bits_depend", "identify",
    ]
)


# The shipped profiles are a few kB; a profile file beyond this is not one (`--profile /dev/zero.toml`).
MAX_PROFILE_BYTES = 1 << 20


def parse_profile(text: str, origin: str) -> Profile:
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ProfileError(f"{origin}: {error}") from None
    except RecursionError:  # [[[[...]]]] nested thousands deep: tomllib recurses once a level
        raise ProfileError(f"{origin}: arrays or tables nested too deep for a profile") from None
    reader = _Reader(origin)
    unknown = sorted(set(data) - _KNOWN_KEYS)
    if unknown:
        raise reader.fail(f"unknown key {unknown[0]!r}")
    name = reader.string(data, "name")
    if not name:
        raise reader.fail("needs a name")
    style = reader.string(data, "address_style", "protocol")
    if style not in ADDRESS_STYLES:
        raise reader.fail(f"address_style {style!r} is not one of {', '.join(ADDRESS_STYLES)}")
    plc = reader.table(data, "plc_base")
    plc_default = reader.integer(plc.get("default", 40001), "[plc_base] default", 0, 999999)
    # The Modbus convention (0X coils, 1X inputs, 3X input registers) unless the profile says otherwise.
    plc_base = dict(SPEC.plc_references)
    plc_base.update(
        (reader.integer(key, "[plc_base] key", 1, 255), reader.integer(value, f"[plc_base] {key}", 0, 999999))
        for key, value in plc.items()
        if key != "default"
    )
    identify = reader.table(data, "identify")
    unknown = sorted(set(identify) - {"product_codes", "functions", "traffic_fit"})
    if unknown:
        raise reader.fail(f"unknown key {unknown[0]!r} in [identify]")
    product_codes = identify.get("product_codes", [])
    if not isinstance(product_codes, list) or not all(isinstance(code, str) and code for code in product_codes):
        raise reader.fail("[identify] product_codes must be a list of strings")
    traffic_fit = identify.get("traffic_fit", False)
    if not isinstance(traffic_fit, bool):
        raise reader.fail("[identify] traffic_fit must be true or false")
    protected = data.get("protected_value")
    all_protected = data.get("all_protected_exception")
    input_registers = reader.string(data, "input_registers", INPUT_REGISTER_READS[0])
    if input_registers not in INPUT_REGISTER_READS:
        choices = ", ".join(INPUT_REGISTER_READS)
        raise reader.fail(f"input_registers {input_registers!r} is not one of {choices}")
    return Profile(
        name=name,
        title=reader.string(data, "title") or name,
        device=reader.string(data, "device") or name,
        origin=origin,
        map=reader.string(data, "map"),
        address_style=style,
        functions=reader.codes(data, "functions"),
        inner_only=reader.codes(data, "inner_only") or frozenset(),
        broadcast=reader.codes(data, "broadcast"),
        protected_value=None if protected is None else reader.integer(protected, "protected_value"),
        input_registers=input_registers,  # type: ignore[arg-type]
        all_protected_exception=(
            None if all_protected is None
            else reader.integer(all_protected, "all_protected_exception", 0, 255)
        ),
        limits=_limits(reader, data),
        exceptions=reader.code_names(data, "exceptions"),
        exception_causes=_causes(reader, data),
        diagnostics=reader.code_names(data, "diagnostics", 0xFFFF),
        subfunctions=reader.codes(data, "subfunctions"),
        diagnostic_constants={
            reader.integer(code, "[diagnostic_constants] key", 0, 0xFFFF):
                reader.integer(value, f"[diagnostic_constants] {code}")
            for code, value in reader.table(data, "diagnostic_constants").items()
        },
        objects=_objects(reader, data),
        function_names=reader.code_names(data, "function_names"),
        plc_base=plc_base,
        plc_base_default=plc_default,
        bits_depend=_bits_depend(reader, data),
        product_codes=tuple(product_codes),
        identifying_functions=reader.codes(identify, "functions") or frozenset(),
        traffic_fit=traffic_fit,
    )


def load_profile(name: str) -> Profile:
    """A built-in profile by name (`atv71`), or a profile file (`my-device.toml`)."""
    if name in BUILTIN_PROFILES:
        origin = f"data/profiles/{name}.toml"
        text = resources.files("dissector").joinpath(origin).read_text(encoding="utf-8")
        return parse_profile(text, origin)
    if name.endswith(".toml"):
        data = read_capped(name, MAX_PROFILE_BYTES, "profile")
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            raise ProfileError(f"{name}: cannot read the profile: not UTF-8 text") from None
        return parse_profile(text, name)
    raise ProfileError(
        f"unknown profile {name!r} (built-in: {', '.join(BUILTIN_PROFILES)}; or a .toml file)"
    )


def load_profile_map(profile: Profile) -> RegisterMap:
    if profile.map is None:
        return {}
    if profile.origin.startswith("data/profiles/"):
        return load_builtin_map(profile.map)
    # A user's profile names its map relative to the profile file.
    return load_map_file(Path(profile.origin).parent / profile.map)
