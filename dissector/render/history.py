"""The parameter history: the one place that says what a decoded frame tells of each parameter.

`--stats` (its per-parameter counts), `--watch` (its change lines) and `--report` (its trends, marks
and protection events) all read the parameters through one `History`: the events below go into one
store (render/stats_store.py: the compiled `_summary.Stats` or `ParameterTable`), which keeps each
parameter's counts and state and answers, event by event, whether the state changed. So a watch line is
a counted change, a report mark is a change into or out of a read status, and none of them can disagree
with another or with the registers `--json` shows for the same frame.

What a good frame (CRC/LRC ok) tells, per register with an address, in this order:
- a request to write (FC6/16/22/23): WRITE (WRITE_OBSERVED for a broadcast, which nothing will confirm);
- an exception: REFUSED for each register its write request asked to write; UNREADABLE for each
  register the profile lists in the exception itself (an exception the device documents as "every
  parameter read is non-existent or protected", VW3 A3 303 p.38: `--json` shows them with `value` null
  and their `status`);
- a normal answer: CONFIRM for the values it confirms written (FC6 echo, the FC16/23 request's values;
  FC23 writes before it reads), then READ for each value read (FC3/4/23), or UNREADABLE when the profile
  gave it a read status (`protected`, `non-existent`: 16#8000 in a multi-register read).
A Mask Write (FC22, [confirm] "mask") is a write of its register: its echo confirms the value the
parameter memory gave the register (memory.remember_mask, Annotator.masked; where the slave's device
follows no memory, the store's last value masked, or or_mask where and_mask is 0); where not known, the
write is counted and its parameter's state stays as it was, as for a write nothing confirmed.
A parameter is a register of one table (Application Protocol 4.3: FC4 reads input registers, FC3/6/16/22/23
holding registers: profiles.register_table), so input register 5 and holding register 5 are two
(kept by slave, address and table), unless the slave's device reads both with one table (profile
input_registers "holding", the ATV71: FC4's 8401 is FC3's CHCF; profiles.device_tables).
A parameter's state is its last value or read status; the first state seen is no change. A register
without an address (an answer whose request is not in the capture) is only counted.

A 32-bit map row (`type` uint32/int32/float32, README) is one parameter, at the row's address: the frame
that carries both its words (Register.words 2 on the first, 0 on the second) tells one event, whose value
is the 32-bit word pair as the row orders it (high word first: `last` in --stats --json) and whose text is
the summary's; listeners get a copy of the first register with that value. A word of such a row without
the other in its frame (a read of 101..102 over rows at 100 and 102) is half a value: no event, no
parameter of its own, only counted (`half_values`). The compiled store keeps 16-bit words only
(dissector/accel/_stats.h Param.last): a run whose maps have 32-bit rows keeps its history in the Python
store (`new_store(wide=True)`), and the engine then counts nothing itself (StatsCollector.engine_store).

A value counts as the device of its slave reads it. A file is named with the choices profile `auto`
made over all of it (app/preselect.py), from each slave's first frame. Read once (standard input, live),
a frame is named with the choice as it stood then: decoded before profile `auto` chose (Frame.provisional,
spec semantics only), or with a choice later traffic may still change (ProfileChoice.final false: a slave
settled without a device, or on the evidence of its registers, may yet send an FC43 ProductCode, or an
answer its device does not support). The history holds such frames back (held()) until the slave's
first frame named with a final choice (where it holds provisional frames only, below: its first frame
after it settled), and reads them again with the profile that frame was named with
(Frame.profile_choice; Annotator.reread: 16#8000 in a multi-register read is then the status
`non-existent` or `protected`, not the value 32768, FC4 reads the holding registers on the ATV71);
frames still held when the input ends are read with the slave's profile then, the file's (finish()).
Keyed on the frame, not on how far the annotator has gone, the compiled engine (which leaves a slave held
to the Python stages: holds(), Annotator.compilable) and the Python stages count alike however the
stream is batched. So `--stats` and `--report` count on a stream what they count on the
same file (p.38 read once: 8400 is unreadable 6 times, 0 changes; an FC43 ProductCode in a slave's 12th
frame: its 16#8000 in frame #6 `non-existent`, as the file says). Two cases hold nothing back and can
still differ from the file: past MAX_HELD frames held (all slaves together) each slave's held frames are
counted with the profile its last was named with and every frame from then on as it comes; and with
`--watch`, whose lines are written as frames come (holding is for outputs made at the end: a listener's
`at_end`). A choice changed after frames so counted names what was kept again (below: rename, rehome;
their 16#8000 stays a value, the order of states joined is unknown: stats_store.join), and --stats says
so under its profiles (late_choices). Listeners that show lines as they come (`--watch` live and on
standard input) hear a provisional frame at once as `provisional(frame, register, event)`, named as decoded,
and its re-read states later through `state()` with the frame still provisional: they write no line
for those (the change was shown provisional), so re-reading never invents a change; the report hears
every held frame so at once (its series kept in stream order) and its states when it is read again.
When profile `auto` chooses again later (a choice taken back), the values kept of that slave are
named again by the new device (`store.rename`), and listeners hear `renamed(slave)`. Where the new device
reads a table with another's code (the ATV71 chosen after FC4 reads: its FC4 reads the holding
registers), the parameters kept move to that table first (`store.rehome`, listeners' `rehomed(slave,
homes)`): --stats shows one CHCF, not an input register beside it. Taken back (`generic` after the ATV71),
what FC4 alone counted moves back to the input registers (the store keeps each parameter's codes' tables:
stats_store.homes_of), and a parameter both tables' codes counted parts into the story each told (the store
keeps those too: ParameterTable._part), as the file counts them.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, Protocol

from dissector.devices.maps import interpret_wide
from dissector.devices.memory import masked_value
from dissector.devices.profiles import HOLDING_REGISTERS, device_tables, load_profile_map
from dissector.model import Frame, Item, Kind, Register
from dissector.protocol.rules import Confirm, confirmed_by
from dissector.protocol.table import confirmed_registers, register_reads, register_writes
from dissector.render.stats_store import (
    CONFIRM, READ, REFUSED, TABLES, UNREADABLE, WRITE, WRITE_OBSERVED, new_store, slave_tables,
)

__all__ = ["CONFIRM", "READ", "REFUSED", "UNREADABLE", "WRITE", "WRITE_OBSERVED", "History", "Listener",
           "READ_FUNCTIONS", "UNREADABLE_STATUSES", "WRITE_FUNCTIONS"]

# Codes whose registers are values read or written, as the protocol table states them: {3, 4, 23} and {6, 16, 23}.
READ_FUNCTIONS = register_reads()
WRITE_FUNCTIONS = register_writes()
# How those writes are confirmed (data/modbus.toml [confirm]): FC6 by its echo, FC16/FC23 by a normal answer.
_BY_ECHO = confirmed_registers(Confirm.ECHO)
_BY_ANSWER = confirmed_registers(Confirm.ANSWER)
_BY_MASK = confirmed_by(Confirm.MASK)  # FC22: its echo confirms masks, the value is the memory's
# Register statuses a profile gives to a read that returned a marker rather than a value (p.38).
UNREADABLE_STATUSES = frozenset(["protected", "non-existent"])
_NOW = object()  # finish(): held frames read with their slave's profile now
# Frames held back at most, all slaves together (History.held; ~1.3 KB each: 21 MB of the plant mix's): past
# it, frames are counted as they come and a later choice may count otherwise than the file (the module's doc).
MAX_HELD = 16384


def _may_change(choice: Any) -> bool:
    """A frame named with `choice` (None: before any) may be named otherwise by a later choice."""
    return choice is None or not choice.final

class Listener(Protocol):
    def state(self, frame: Frame, register: Register, event: int, changed: bool) -> None:
        """A register that set its parameter's state (READ, UNREADABLE, CONFIRM, WRITE_OBSERVED); a 32-bit
        value is its first register (`words` 2) with `value` the 32-bit word pair (wide_pair)."""

    def renamed(self, slave: int) -> None:
        """This slave's profile changed: what was kept of it is to be read with the new one."""

    def rehomed(self, slave: int, homes: bytes) -> None:
        """Before renamed: its new device reads a table with another's code (History._rehome), what was kept
        moves to homes[t] of the protocol tables t of the codes that set it (as the store: stats_store.homes_of)."""


class ProvisionalListener(Listener, Protocol):
    def provisional(self, frame: Frame, register: Register, event: int) -> None:
        """A register of a provisional frame, named as decoded (its state() comes once it is re-read)."""


class History:
    def __init__(self, annotate: object = None, store: Any = None) -> None:
        # slave -> each code's register table on its device now (its FC4 may read the holding registers),
        # which moves what the store and the listeners keep when it changes (_rehome)
        tables = slave_tables(annotate)
        self._slave_tables: Callable[[int], bytes] = tables or (lambda slave: TABLES)
        # (slave, tables) while a frame named before its slave's choice is applied (_named_tables)
        self._naming: tuple[int, bytes] | None = None
        self.store = new_store(wide_maps(annotate), tables) if store is None else store
        if tables is not None:
            tables.moved = self._rehome
        self.registers_without_address = 0
        # Registers that are one word of a 32-bit map row whose other word is not in their frame.
        self.half_values = 0
        self._device: Callable[[int], Any] | None = getattr(annotate, "device", None)
        self.listeners: list[Listener] = []
        self._profile_for: Callable[[int], object] | None = getattr(annotate, "profile_for", None)
        self._namer: Callable[[int], Any] | None = getattr(annotate, "namer", None)
        self._choice_frame: Callable[[int], int | None] | None = getattr(annotate, "choice_frame", None)
        self._annotate = annotate
        self.annotate = annotate  # for the outputs' names (PLC-style labels)
        self._renamed: dict[int, int] = {}  # slave -> the choice frame its values were named again for
        self._rehomed = 0  # moves made (_rehome)
        self._held: dict[int, list[Frame]] = {}  # slave -> its frames held back (held()), until its final choice
        self._held_frames = 0  # in _held, all slaves (MAX_HELD)
        # The frame past MAX_HELD held frames from which none is held but provisional ones (None: not reached),
        # and the slaves whose frames were counted before a choice that changed later (late_choices)
        self.overflow: int | None = None
        self._unsure: set[int] = set()
        self.late_choices: dict[int, int] = {}  # slave -> that choice's frame
        self._selector = getattr(annotate, "selector", None)
        self._forced = getattr(annotate, "per_slave", None) or {}
        holds = getattr(annotate, "holds", None)
        if holds is not None:
            holds.append(self.holds)  # (the compiled engine asks: Annotator.compilable)
        self._masked: dict[int, int | None] = {}  # the annotator's Mask Write values (Annotator.masked)
        # While a held slave's frames are read again (_replay): its registers' values as its device's parameter
        # memory holds them, by (table, address), None a read status: the value a Mask Write gives (_mask)
        self._replayed: dict[tuple[int, int], int | None] | None = None
        if getattr(annotate, "masked", 0) is None:
            annotate.masked = self._masked  # type: ignore[union-attr]

    def add(self, item: Item) -> None:
        """A decoded item, in stream order (noise and damaged frames tell nothing of parameters)."""
        if item.kind is Kind.NOISE:
            return
        frame: Frame = item  # type: ignore[assignment]
        slave = frame.slave
        late = not frame.provisional and self._late(frame)
        if self._held and not frame.provisional and not late and slave in self._held:
            # The slave's first frame named with a final choice (past MAX_HELD or under --watch, where
            # only provisional frames are held: its first once it settled): its held frames are read
            # with the profile this frame was named with, whatever came since.
            self._release(slave, frame.profile_choice)
        if not frame.crc_ok:
            return
        if self._choice_frame is not None:
            chosen = self._choice_frame(slave)
            if chosen is not None and frame.number >= chosen and self._renamed.get(slave) != chosen:
                # The first frame named with the profile chosen in frame `chosen`: what was kept of
                # this slave before (here, or by the compiled engine in the same store) is named again.
                self._renamed[slave] = chosen
                if slave in self._unsure:  # (counted before it: the file may count them otherwise)
                    self.late_choices[slave] = chosen
                rehomed = self._rehomed
                self.tables(slave)  # a device of other tables moves them first (SlaveTables: _rehome names them)
                if self._rehomed == rehomed:
                    self._rename(slave)
        if frame.provisional or late:
            if self._watching:
                self._apply(frame, provisional=True)
            self._held.setdefault(slave, []).append(frame)
            self._held_frames += 1
            if late and self._held_frames > MAX_HELD:
                self._overflow(frame.number)
            return
        self._counted(slave, frame.profile_choice)
        self._apply(frame)

    def _counted(self, slave: int, choice: Any) -> None:
        """Frames of `slave` named with `choice` are counted: if profile `auto` may still change it, a
        later change cannot count them again (late_choices)."""
        if self._choosing(slave) and _may_change(choice):
            self._unsure.add(slave)

    def _choosing(self, slave: int) -> bool:
        """Profile `auto` chooses this slave's device as the stream goes: not frozen on a first pass, and
        neither slave 0 (broadcasts: named with the device the slaves share) nor a slave given a profile."""
        selector = self._selector
        return selector is not None and not selector.frozen and slave != 0 and slave not in self._forced

    def held(self, frame: Frame) -> bool:
        """The history holds `frame` back until its slave's choice is final (or the input ends): it was
        named before profile `auto` chose (provisional), or with a choice later traffic may still change."""
        return frame.provisional or self._late(frame)

    def _holding(self, slave: int) -> bool:
        """Frames of this slave named now would be held: profile `auto` chooses as the stream goes (not
        frozen on a first pass: _choosing), for outputs made at the end only (no --watch), and not past the cap."""
        return (self._choosing(slave) and self.overflow is None
                and all(getattr(each, "at_end", False) for each in self.listeners))

    def _overflow(self, number: int) -> None:
        """Past MAX_HELD frames held: each settled slave's are counted now, with the profile its last one
        was named with, and every frame from now on as it comes (provisional ones still wait)."""
        self.overflow = number
        for slave, frames in list(self._held.items()):
            if not frames[-1].provisional:
                self._release(slave, frames[-1].profile_choice)

    def _late(self, frame: Frame) -> bool:
        """A frame (not provisional) named with a choice that its slave's later traffic may still change."""
        return _may_change(frame.profile_choice) and self._holding(frame.slave)

    def holds(self, slave: int) -> bool:
        """The compiled engine leaves this slave's frames to the Python stages (Annotator.compilable): the
        history would hold them, its choice as it stands now not final."""
        final = getattr(self._annotate, "final", None)
        return final is not None and self._holding(slave) and not final(slave)

    def _release(self, slave: int, choice: object) -> None:
        frames = self._held.pop(slave)
        self._held_frames -= len(frames)
        if choice is not _NOW:
            self._counted(slave, choice)
        changed = getattr(self._annotate, "changed", None)
        if changed is not None:
            changed.add(slave)  # (the compiled engine asks again: it may take the slave's frames now)
        self._replay(frames, choice)

    def tables(self, slave: int) -> bytes:
        """Each code's register table for the slave's parameters: its device's now (SlaveTables), or, while
        a frame named before the slave's choice is applied, the tables of the profile it was named with."""
        naming = self._naming
        if naming is not None and naming[0] == slave:
            return naming[1]
        return self._slave_tables(slave)

    def _named_tables(self, frame: Frame, profile: object, told: bool, held: bool) -> bytes | None:
        """The tables a frame is counted in, when it was named before its slave's profile was chosen
        (held: `profile`, the profile it is read again with; else, and `told` as decoded, the one it was
        named with, Frame.profile_choice): those of that profile, as a stream that saw the frame before the choice
        counted it; the choice's frame moves them (add, _rehome). Without this, a choice decoded in the
        same batch (the annotator ahead of the history) put them in the new device's tables at once,
        and the counts hung on how the input was cut (fastsummary_fuzz --stats seed 41435). None: now."""
        chosen = getattr(self._annotate, "chosen_profile", None)
        if chosen is None:
            return None
        if held:
            if profile is None:
                return None
        elif told or self._stale(frame.slave, frame.number):
            profile = chosen(frame.profile_choice)
        else:
            return None
        named = getattr(self._slave_tables, "named", None)
        tables = device_tables(profile)
        # (as a stream that saw the frame then: what was kept with other tables moves now, and back at the choice)
        return tables if named is None else named(frame.slave, tables)

    def finish(self) -> None:
        """The input ended: the frames still held are read with their slave's profile now."""
        for slave in list(self._held):
            self._release(slave, _NOW)

    def _replay(self, frames: list[Frame], choice: object) -> None:
        chosen = getattr(self._annotate, "chosen_profile", None)
        profile = None if chosen is None or choice is _NOW else chosen(choice)
        # (a held Mask Write was decoded before its device kept a memory: its value is the replay's)
        device = None if self._device is None else self._device(frames[0].slave)
        tracks = device is not None and device.track and (profile is None or device.profile is profile)
        self._replayed = {} if tracks else None
        try:
            for frame in frames:
                self._apply(frame, profile=profile, held=True)
        finally:
            self._replayed = None

    @property
    def _watching(self) -> list[Any]:
        return [listener for listener in self.listeners if hasattr(listener, "provisional")]

    def _apply(self, frame: Frame, provisional: bool = False, profile: object = None, held: bool = False) -> None:
        """What `frame` tells of each parameter; `provisional`: only told to the listeners that show
        provisional lines, with the registers as decoded (the store keeps nothing); `held`: a held
        frame, read again with `profile` (None: the slave's now)."""
        tables = self._named_tables(frame, profile, provisional, held)
        if tables is None:
            self._tell_apply(frame, provisional, profile, held)
            return
        self._naming = (frame.slave, tables)
        try:
            self._tell_apply(frame, provisional, profile, held)
        finally:
            self._naming = None

    def _tell_apply(self, frame: Frame, provisional: bool, profile: object, held: bool) -> None:
        slave = frame.slave
        kind = frame.kind
        function = frame.function
        registers = frame.registers
        if not provisional:
            if held:
                registers = self._reread(frame, profile)
            elif registers and self._stale(slave, frame.number):
                registers = self._fresh(frame, registers)
        if function in _BY_MASK:
            self._mask(frame, provisional)
            return
        if kind is Kind.REQUEST:
            if function in WRITE_FUNCTIONS and registers:
                # A broadcast write: no answer will confirm it, the request is all there is.
                self._events(frame, registers, WRITE_OBSERVED if frame.broadcast else WRITE, provisional=provisional)
            return
        request = frame.request
        written = None
        if request is not None and request.crc_ok and request.registers and request.function in WRITE_FUNCTIONS:
            written = request.registers
            if not provisional:
                if held or request.provisional:
                    written = self._reread(request, profile)
                elif self._stale(slave, request.number):
                    written = self._fresh(request, written)
        if kind is Kind.EXCEPTION:
            if written:
                self._events(frame, written, REFUSED, provisional=provisional)
            if registers:
                self._reads(frame, registers, provisional)
            return
        # Writes first: FC23 performs its write before its read.
        if function in _BY_ECHO:
            if registers:
                self._events(frame, registers, CONFIRM, confirmed=True, provisional=provisional)
        elif function in _BY_ANSWER and written:
            self._events(frame, written, CONFIRM, confirmed=True, provisional=provisional)
        if function in READ_FUNCTIONS and registers:
            self._reads(frame, registers, provisional)

    def _mask(self, frame: Frame, provisional: bool) -> None:
        """A Mask Write's events, as an FC6 write's of the value it gives its register (the module's doc)."""
        request = frame if frame.kind is Kind.REQUEST else frame.request
        fields = None if request is None or not request.crc_ok else request.fields
        if fields is None or getattr(fields, "and_mask", None) is None:
            return  # (an answer without its request, or malformed: nothing of a parameter known)
        value = fields.or_mask if fields.and_mask == 0 else None
        if frame.kind is Kind.RESPONSE:
            masked, memory, table = self._masked, self._replayed, self.tables(frame.slave)[frame.function]
            if memory is not None and not provisional:  # (as memory.remember_mask reckons it)
                masked.pop(frame.number, None)
                known = masked_value(memory.get((table, fields.address)), fields.and_mask, fields.or_mask)
            elif frame.number in masked:  # (the slave's parameter memory reckoned it)
                known = masked.get(frame.number) if provisional else masked.pop(frame.number)
            else:  # no memory: the parameter's last value, as the store holds it
                last = self.store.last(frame.slave, fields.address, table)
                known = masked_value(last, fields.and_mask, fields.or_mask)
            if known is not None:
                self._events(frame, [self._named(frame, fields.address, known)], CONFIRM, confirmed=True,
                             provisional=provisional)
            return
        if frame.kind is Kind.EXCEPTION:
            event = REFUSED
        elif frame.broadcast and value is not None:
            event = WRITE_OBSERVED
        else:
            event = WRITE
        self._events(frame, [self._named(frame, fields.address, value or 0)], event, provisional=provisional)

    def _named(self, frame: Frame, address: int, value: int) -> Register:
        """A register as the slave's device names it (plain: no note applies)."""
        plain = getattr(self._annotate, "plain_register", None)
        return Register(address, value) if plain is None else plain(frame.slave, frame.function, address, value)

    def named_by(self, frame: Frame) -> object:
        """The profile the registers listeners get were named with: the slave's profile now."""
        return None if self._profile_for is None else self._profile_for(frame.slave)

    def _stale(self, slave: int, number: int) -> bool:
        """Frame `number` was named before the slave's profile was chosen (the choice came later in the
        same batch of items, or the request an answer confirms came before that answer decided)."""
        if self._choice_frame is None:
            return False
        chosen = self._choice_frame(slave)
        return chosen is not None and number < chosen

    def _reread(self, frame: Frame, profile: object) -> Any:
        """A held frame's registers as its slave's device reads them (Annotator.reread)."""
        reread = getattr(self._annotate, "reread", None)
        return frame.registers if reread is None else reread(frame, profile)

    def _fresh(self, frame: Frame, registers: list[Register]) -> list[Register]:
        """Registers of a frame named before its slave's profile changed (later in the same batch of
        items), named as the slave's device now names them; statuses kept (the stream path, which saw
        the frame before the change, counted them so: both paths count alike)."""
        plain = getattr(self._annotate, "plain_register", None)
        device = getattr(self._annotate, "device", None)
        if plain is None or device is None:
            return registers
        rows = device(frame.slave).rows_for(frame.function)
        fresh = []
        for register in registers:
            address = register.address
            row = None if address is None else rows.get(address)
            if row is None or row.words != 1 or register.value is None or register.status in UNREADABLE_STATUSES:
                if row is not None and register.code is None:
                    register = dataclasses.replace(register, code=row.code, name=row.name)
                fresh.append(register)
                continue
            named = plain(frame.slave, frame.function, address, register.value)
            named.status = register.status
            fresh.append(named)
        return fresh

    def _events(self, frame: Frame, registers: list[Register], event: int, confirmed: bool = False,
                provisional: bool = False) -> None:
        if provisional:
            if event in (CONFIRM, WRITE_OBSERVED):
                self._tell(frame, registers, event)
            return
        param = self.store.param
        slave = frame.slave
        table = self.tables(slave)[frame.function]
        origin = TABLES[frame.function]  # (where a later device's tables move it: SlaveTables)
        registers = self._values(slave, registers, function=frame.function)
        listeners = self.listeners if event in (CONFIRM, WRITE_OBSERVED) else None
        memory = self._replayed if event == CONFIRM else None
        for register in registers:
            address = register.address
            if address is None:
                if not confirmed:  # an answer without its request confirms nothing: not even counted
                    self.registers_without_address += 1
                continue
            changed = param(slave, address, event, register.value, register.code, register.text, table, origin)
            if memory is not None:
                memory[(table, address)] = register.value
            if listeners:
                for listener in listeners:
                    listener.state(frame, register, event, changed)

    def _reads(self, frame: Frame, registers: list[Register], provisional: bool = False) -> None:
        if provisional:
            self._tell(frame, registers, None)
            return
        # The hot loop of --stats: one store call a register.
        param = self.store.param
        slave = frame.slave
        table = self.tables(slave)[frame.function]
        origin = TABLES[frame.function]  # (where a later device's tables move it: SlaveTables)
        registers = self._values(slave, registers, function=frame.function)
        listeners = self.listeners
        memory = self._replayed
        for register in registers:
            address = register.address
            if address is None:
                self.registers_without_address += 1
                continue
            status = register.status
            if status in UNREADABLE_STATUSES:
                event = UNREADABLE
                changed = param(slave, address, UNREADABLE, 0, register.code, status, table, origin)
            else:
                event = READ
                changed = param(slave, address, READ, register.value, register.code, register.text, table, origin)
            if memory is not None:
                memory[(table, address)] = register.value if event == READ else None
            if listeners:
                for listener in listeners:
                    listener.state(frame, register, event, changed)

    def _tell(self, frame: Frame, registers: list[Register], event: int | None) -> None:
        """A provisional frame's states, as decoded, to the listeners that show them (None: reads)."""
        listeners = self._watching
        for register in self._values(frame.slave, registers, counted=False, function=frame.function):
            if register.address is None:
                continue
            told = event
            if told is None:
                told = UNREADABLE if register.status in UNREADABLE_STATUSES else READ
            for listener in listeners:
                listener.provisional(frame, register, told)

    def _values(self, slave: int, registers: Any, function: int, counted: bool = True) -> Any:
        """The registers as the parameters' values: a 32-bit value once, its first register with the word
        pair as its value; a word of a 32-bit row without the other left out (counted in half_values
        when `counted`). The registers as they are when the slave's map has no 32-bit row."""
        device = None if self._device is None else self._device(slave)
        if device is None or not device.wide:
            return registers
        rows = device.rows_for(function)
        values: list[Register] = []
        for index, register in enumerate(registers):
            words = register.words
            address = register.address
            if address is None:
                values.append(register)
                continue
            if words == 0:  # a second word: told with its first
                continue
            if words == 2:
                second = registers[index + 1]
                pair = wide_pair(rows.get(address), register.value, second.value)
                values.append(dataclasses.replace(register, value=pair))
                continue
            row = rows.get(address)
            if row is not None and row.words == 2:  # a first word alone
                if register.status in UNREADABLE_STATUSES:
                    values.append(register)  # an exception the profile explains: the whole value is unreadable
                elif counted:
                    self.half_values += 1
                continue
            before = rows.get((address - 1) & 0xFFFF)
            if before is not None and before.words == 2:  # a second word
                with_first = index > 0 and registers[index - 1].address == (address - 1) & 0xFFFF
                if counted and not (with_first and register.status in UNREADABLE_STATUSES):
                    self.half_values += 1  # (unreadable with its first: told with it)
                continue
            values.append(register)
        return values

    def _rehome(self, slave: int, homes: bytes) -> None:
        """The slave's new device reads a table with another's code (SlaveTables): its parameters kept
        before move there, with the listeners' states, and are named by the new device."""
        self._rehomed += 1
        self.store.rehome(slave, homes)
        for listener in self.listeners:
            listener.rehomed(slave, homes)
        self._rename(slave)

    def _rename(self, slave: int) -> None:
        if self._namer is not None:
            self.store.rename({slave: self._wide_namer(slave, self._namer(slave))})
        for listener in self.listeners:
            listener.renamed(slave)

    def _wide_namer(self, slave: int, namer: Callable[[int, int], Any]) -> Callable[[int, int], Any]:
        """The slave's namer, reading a 32-bit row's kept value (a word pair) as the row does."""
        if self._device is None or not self._device(slave).wide:
            return namer
        device = self._device(slave)

        def name(address: int, value: int, table: int = HOLDING_REGISTERS) -> Any:  # (table: the parameter's)
            row = device.table_rows(table).get(address)
            if row is None or row.words != 2:
                return namer(address, value, table)
            return wide_text(row, value)[1], row.code

        return name


def wide_pair(row: Any, first: int, second: int) -> int:
    """A 32-bit value's words, in the order they came on the wire, as one number, high word first (the
    row's `order`; ABCD when no row names it now)."""
    high, low = (second, first) if row is not None and row.swapped else (first, second)
    return high << 16 | low


def wide_text(row: Any, pair: int) -> tuple[float | int | None, str]:
    """The scaled value and text a 32-bit row gives a word pair (wide_pair), as the summary shows it."""
    high, low = pair >> 16 & 0xFFFF, pair & 0xFFFF
    return interpret_wide(row, *((low, high) if row.swapped else (high, low)))


def wide_maps(annotate: object) -> bool:
    """A map of the run (a profile's, in use or that `auto` may choose, or a --map file) has 32-bit rows."""
    profiles = getattr(annotate, "profiles", None)
    if profiles is None:
        return False
    maps = [load_profile_map(profile) for profile in profiles()]
    maps += [table for layer in getattr(annotate, "layers", ()) for table in (layer.rows, getattr(
        layer.rows, "inputs", {}))]
    return any(row.words == 2 for rows in maps for row in rows.values())
