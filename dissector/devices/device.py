"""What the annotator knows of one slave: its profile, merged register map and precomputed checks.

Built on a slave's first frame (or when its profile is chosen), so the per-frame work is lookups.
"""
from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass, field

from dissector.devices.maps import ReferenceRows, RegisterDef, RegisterMap, overlay
from dissector.devices.profiles import (
    INPUT_REGISTERS, TABLES, BitsDepend, Profile, load_profile_map, register_table,
)

# What the annotator last knew of a parameter: (value, frame number, how). value None: unreadable
# (how is then its status); how "read" or "written" otherwise. Plain tuples: this is the hot path.
Seen = tuple[int | None, int, str]


@dataclass(frozen=True, slots=True)
class MapLayer:
    """Rows from a --map file, for every slave, one slave, or the slaves of one profile."""

    rows: RegisterMap
    slave: int | None = None
    profile: str | None = None


@dataclass(slots=True)
class Device:
    """Everything one slave needs, computed once."""

    profile: Profile
    rows: RegisterMap
    plain: dict[int, RegisterDef]  # rows without bit labels, for bits_depend
    depend: dict[int, BitsDepend]
    plc: dict[int, int] | None  # PLC base per function (None: protocol addresses)
    plc_default: int
    # Parameters are followed only where it tells something: protection, or bits that depend on a value.
    track: bool
    # Requests that need no check at all (supported, no device limit): the common case costs one lookup.
    unchecked: frozenset[int]
    # Supported functions with a device limit: checked inline before the full (slower) check.
    limited: dict[int, tuple[int, ...]]
    wide: bool = False  # the map has 32-bit rows
    seen: dict[int, Seen] = field(default_factory=dict)
    # The memory of the input registers (FC4's), where they are a table of their own (profile input_registers
    # "separate": input register 5 is not holding register 5); None: FC4 reads the holding registers, `seen`.
    input_seen: dict[int, Seen] | None = None
    labels: dict[int, dict[int, str]] = field(default_factory=dict)
    # The rows naming the input registers (FC4's) apart from `rows`: a --map in PLC references with 3X rows
    # on a device whose input registers are a table of their own; None: `rows` name FC4's registers too.
    inputs: RegisterMap | None = None
    # Exception explanations depend on the request's bytes alone: a PLC that polls a protected block
    # draws the same exception again and again.
    explained: dict[object, object] = field(default_factory=dict)

    def base(self, function: int) -> int:
        return self.plc.get(function, self.plc_default)  # type: ignore[union-attr]

    def rows_for(self, function: int) -> RegisterMap:
        """The rows naming the registers `function` reads or writes: its table's."""
        return self.table_rows(TABLES[function])

    def table_rows(self, table: int) -> RegisterMap:
        """The rows naming the registers of a table (profiles.register_table's INPUT_REGISTERS, ...)."""
        return self.inputs if self.inputs is not None and table == INPUT_REGISTERS else self.rows

    def memory(self, function: int) -> dict[int, Seen]:
        """The parameter memory of the registers `function` reads or writes: its table's."""
        if self.input_seen is not None and register_table(function) == INPUT_REGISTERS:
            return self.input_seen
        return self.seen

    def engine_check(self, function: int) -> tuple[int, ...] | None:
        """The compiled engine's request check of a code (Annotator.summary_facts): () none, the device's
        limits, or None: every request is the annotator's (a check the engine lacks, or a memory of its own,
        input_seen, which the engine does not keep: it keeps `seen`)."""
        if self.track and self.memory(function) is not self.seen:
            return None
        return () if function in self.unchecked else self.limited.get(function)


def layered_rows(profile: Profile, base: RegisterMap, layers: list[MapLayer]) -> tuple[RegisterMap, RegisterMap | None]:
    """A profile's map `base` with the --map layers that apply laid over it; and the rows of its input
    registers apart (a layer in PLC references with 3X rows, on a device whose FC4 reads a table of its own),
    None when the rows name them too (lua/src/device.lua layered_rows)."""
    rows = inputs = base
    split = False
    one_table = profile.input_registers == "holding"
    for layer in layers:
        extra = (layer.rows.inputs or None) if isinstance(layer.rows, ReferenceRows) else None
        if extra and one_table:
            # FC4 reads the holding registers (the ATV71): a 3X row names the register FC3 reads too,
            # and where a 4X row of the layer names the same one, the 4X row wins.
            rows = overlay(overlay(rows, extra), layer.rows)
            continue
        rows = overlay(rows, layer.rows)  # (a copy: the base map is shared)
        # An address map names a register whatever the table; a map in references, its 3X rows FC4's.
        inputs = overlay(inputs, extra if extra is not None else layer.rows)
        split = split or extra is not None
    return rows, inputs if split else None


class DeviceBuilder:
    """Devices from profiles and --map layers; each profile's map is read once."""

    def __init__(self, layers: list[MapLayer], address_style: str | None) -> None:
        self.layers = list(layers)
        self.address_style = address_style
        self._base_maps: dict[str, RegisterMap] = {}

    def build(self, profile: Profile, slave: int | None) -> Device:
        base = self._base_maps.get(profile.name)
        if base is None:
            base = self._base_maps[profile.name] = load_profile_map(profile)
        rows, inputs = layered_rows(profile, base, [
            layer for layer in self.layers
            if (layer.slave is None or layer.slave == slave) and (layer.profile is None or layer.profile == profile.name)
        ])
        depend: dict[int, BitsDepend] = {}
        plain: dict[int, RegisterDef] = {}
        for rule in profile.bits_depend:
            for address in rule.registers:
                if address in rows:
                    depend[address] = rule
                    plain[address] = dataclasses.replace(rows[address], bits={}, memo={})
        style = self.address_style or profile.address_style
        supported = profile.functions if profile.functions is not None else frozenset(range(256))
        return Device(
            profile=profile,
            rows=rows,
            plain=plain,
            depend=depend,
            plc=dict(profile.plc_base) if style == "plc" else None,
            plc_default=profile.plc_base_default,
            track=profile.protected_value is not None or bool(depend),
            unchecked=_unchecked(supported, profile.inner_only, frozenset(profile.limits)),
            wide=any(row.words == 2 for table in (rows, inputs or {}) for row in table.values()),
            inputs=inputs,
            input_seen=None if profile.input_registers == "holding" else {},
            limited={
                function: limits
                for function, limits in profile.limits.items()
                if function in supported and function not in profile.inner_only
            },
        )


@functools.lru_cache(maxsize=64)
def _unchecked(supported: frozenset[int], inner_only: frozenset[int], limited: frozenset[int]) -> frozenset[int]:
    """Device.unchecked, one set for the slaves of one profile (a set of 256 codes is 16 KB: 247 slaves of
    the generic profile kept 4 MB of them; issue 28)."""
    return frozenset(supported - inner_only - limited)
