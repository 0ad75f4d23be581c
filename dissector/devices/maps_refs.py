"""A --map written in PLC references (40001 for register 0, as many manuals tell users to add) names
nothing the bus reads, silently: this tells it from the traffic, not from the map alone (a SunSpec device
really has registers at 40000 and up).

For each slave and each --map layer that applies to it, over the slave's first JUDGED frames that carry
registers (each distinct register once, by its reference base): the layer names `own` of them at their
address, and of those no map names, `shifted` at address + the PLC base of their function (the profile's
[plc_base]: 40001, FC4 30001 by the Modbus convention) or one less (the off-by-one variant). When
shifted > own the map's addresses look like references: said once, as a note on the frame that decides it
(the plugin's note there is the same, lua/src/device.lua check_references) and on stderr after the run.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

from dissector.devices.annotator import Annotator, MapLayer
from dissector.devices.device import Device
from dissector.devices.maps import MESSAGES, ReferenceRows, RegisterMap
from dissector.devices.naming import wide_before
from dissector.model import Frame, RegisterList
from dissector.protocol.printable import printable

JUDGED = 32  # frames with registers a slave is judged on (then the compiled path may take it again)
VARIANTS = (0, 1)  # the PLC base itself, and one less (40000 for register 0)


@dataclass(slots=True)
class _Tally:
    """One slave under one layer: distinct (base, address) keys seen."""

    own: set[tuple[int, int]] = field(default_factory=set)  # the layer names it at its address
    unnamed: set[tuple[int, int]] = field(default_factory=set)  # no map names it
    shifted: tuple[dict[tuple[int, int], int], ...] = field(default_factory=lambda: ({}, {}))  # by variant: key -> offset


def reference_base(device: Device, function: int) -> int:
    """The PLC base of a function's registers on this device's profile, whatever the address style."""
    profile = device.profile
    return profile.plc_base.get(function, profile.plc_base_default)


def names(rows: RegisterMap, address: int) -> bool:
    """A map names this register: a row of its own, or the second word of a 32-bit row."""
    return address in rows or wide_before(rows, address) is not None


def offsets_text(offsets: Sequence[int]) -> str:
    return " or ".join(str(offset) for offset in sorted(set(offsets), reverse=True))


def reference_note(path: str, slave: int, tally: _Tally, rows: RegisterMap) -> str | None:
    """The note when the tally says the layer's addresses look like references, else None. Where they are
    the references themselves (not one less) and the map has no `reference` column, it says that column
    would read them as they are."""
    best = max(VARIANTS, key=lambda variant: (len(tally.shifted[variant]), -variant))
    shifted = tally.shifted[best]
    if not shifted or len(shifted) <= len(tally.own):
        return None
    column = MESSAGES["references_column"] if best == 0 and not isinstance(rows, ReferenceRows) else ""
    return MESSAGES["references"].format(
        map=printable(path), unnamed=len(tally.unnamed), slave=slave, shifted=len(shifted),
        offset=offsets_text(list(shifted.values())), column=column,
    )


class ReferenceCheck:
    """The judgment, per slave: observe() each annotated frame, notes() what was said."""

    def __init__(self, paths: list[str], layers: list[MapLayer]) -> None:
        # (a layer whose highest address is below every base could never match: not judged)
        # (a map in references' 3X rows counted: ReferenceRows.inputs)
        self.layers = [(path, layer, max([*layer.rows, *getattr(layer.rows, "inputs", ())], default=-1))
                       for path, layer in zip(paths, layers)]
        self.frames: dict[int, int] = {}  # slave -> frames with registers judged
        self.tallies: dict[tuple[int, int], _Tally] = {}
        self.said: list[str] = []
        self.done: set[tuple[int, int]] = set()  # (slave, layer index) said
        self.closed: set[int] = set()  # slaves judged on JUDGED frames, or told of every layer
        self._applying: dict[tuple[int, str], list[tuple[int, str, MapLayer]]] = {}  # (slave, profile) ->

    def applies(self, device: Device, slave: int) -> list[tuple[int, str, MapLayer]]:
        """The layers (index, path, layer) that apply to this slave under its device's profile and could
        name a register at a reference base (FC3's or FC4's, or one less) past its address."""
        key = (slave, device.profile.name)
        found = self._applying.get(key)
        if found is None:
            low = min(reference_base(device, function) for function in (3, 4)) - VARIANTS[-1]
            found = self._applying[key] = [
                (index, path, layer) for index, (path, layer, high) in enumerate(self.layers)
                if high >= low and (layer.slave is None or layer.slave == slave)
                and (layer.profile is None or layer.profile == device.profile.name)
            ]
        return found

    def open(self, device: Device, slave: int) -> bool:
        """Frames of this slave are still judged (the compiled path leaves them to the annotator)."""
        return slave not in self.closed and any(
            (slave, index) not in self.done for index, _path, _layer in self.applies(device, slave))

    def observe(self, frame: Frame, device: Device) -> None:
        registers = frame.registers
        slave = frame.slave
        if not registers or slave == 0 or frame.provisional or not frame.crc_ok or not self.open(device, slave):
            return
        count = self.frames[slave] = self.frames.get(slave, 0) + 1
        if count >= JUDGED:
            self.closed.add(slave)
        base = reference_base(device, frame.function)
        rows = device.rows_for(frame.function)
        # (a block's addresses, not its Register objects: made, they would be kept, RegisterList.plain)
        addresses = registers.addresses if isinstance(registers, RegisterList) else [r.address for r in registers]
        for index, path, layer in self.applies(device, slave):
            key = (slave, index)
            if key in self.done:
                continue
            tally = self.tallies.setdefault(key, _Tally())
            mine = layer.rows
            if getattr(mine, "inputs", None) and rows is device.inputs:
                mine = mine.inputs  # (a map in references: FC4's registers are its 3X rows)
            for address in addresses:
                if address is None:
                    continue
                seen = (base, address)
                if names(mine, address):
                    tally.own.add(seen)
                elif not names(rows, address):
                    tally.unnamed.add(seen)
                    for variant in VARIANTS:
                        offset = base - variant
                        if address + offset <= 0xFFFF and names(mine, address + offset):
                            tally.shifted[variant][seen] = offset
            note = reference_note(path, slave, tally, mine)
            if note is not None:
                frame.notes.append(note)
                self.said.append(note)
                del self.tallies[key]
                self.done.add(key)


class CheckedAnnotator(Annotator):
    """The annotator with the reference check (build_annotator makes one when a --map is given)."""

    def __init__(self, *args: object, paths: list[str], **kwargs: object) -> None:
        super().__init__(*args, **kwargs)  # type: ignore[arg-type]
        self.references = ReferenceCheck(paths, self.layers)

    def __call__(self, frame: Frame) -> None:
        super().__call__(frame)
        slave = frame.slave
        if slave == 0 or slave in self.references.closed or not frame.registers:
            return
        device = self.device(slave)
        was_open = self.references.open(device, slave)
        self.references.observe(frame, device)
        if was_open and not self.references.open(device, slave):
            self.changed.add(slave)  # the compiled path may show it again (fastsummary.forget_changed)

    def compilable(self, slave: int) -> bool:
        if not super().compilable(slave):
            return False
        return slave == 0 or not self.references.open(self.device(slave), slave)

    def map_warnings(self) -> list[str]:
        """What the check said, once each, for stderr after the run."""
        return list(self.references.said)


def map_warnings(annotators: Sequence[object]) -> list[str]:
    """The reference check's warnings of a run's annotators (one per bus: a pcapng's interfaces), each text
    once, for stderr after the decode."""
    out: list[str] = []
    seen: set[int] = set()
    for annotator in annotators:
        if annotator is None or id(annotator) in seen:
            continue
        seen.add(id(annotator))
        for text in getattr(annotator, "map_warnings", lambda: [])():
            if text not in out:
                out.append(text)
    return out
