"""The parameter history: the one place that says what a decoded frame tells of each parameter.

`--stats` (its per-parameter counts), `--watch` (its change lines) and `--report` (its trends, marks
and protection events) all read the parameters through one `History`: the events below go into one
store (render/stats_store.py: the compiled `_summary.Stats` or `ParameterTable`), which keeps each
parameter's counts and state and answers, event by event, whether the state changed. So a watch line is
a counted change, a report mark is a change into or out of a read status, and none of them can disagree
with another or with the registers `--json` shows for the same frame.

What a good frame (CRC/LRC ok) tells, per register with an address, in this order:
- a request to write (FC6/16/23): WRITE (WRITE_OBSERVED for a broadcast, which nothing will confirm);
- an exception: REFUSED for each register its write request asked to write; UNREADABLE for each
  register the profile lists in the exception itself (an exception the device documents as "every
  parameter read is non-existent or protected", VW3 A3 303 p.38: `--json` shows them with `value` null
  and their `status`);
- a normal answer: CONFIRM for the values it confirms written (FC6 echo, the FC16/23 request's values;
  FC23 writes before it reads), then READ for each value read (FC3/4/23), or UNREADABLE when the profile
  gave it a read status (`protected`, `non-existent`: 16#8000 in a multi-register read).
A parameter's state is its last value or read status; the first state seen is no change. A register
without an address (an answer whose request is not in the capture) is only counted.

A value is read with the profile its slave had when it arrived. When profile `auto` chooses (or takes
back) a slave's profile later, the values kept of that slave are named again by the new device
(`store.rename`), and listeners hear `renamed(slave)`: what the outputs show is never the raw word of
one profile beside the scaled value of another.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, Protocol

from dissector.model import Frame, Item, Kind, Register
from dissector.protocol.rules import Confirm
from dissector.protocol.table import confirmed_registers, register_reads, register_writes
from dissector.render.stats_store import CONFIRM, READ, REFUSED, UNREADABLE, WRITE, WRITE_OBSERVED, new_store

__all__ = [
    "CONFIRM", "READ", "REFUSED", "UNREADABLE", "WRITE", "WRITE_OBSERVED", "History", "Listener",
    "READ_FUNCTIONS", "UNREADABLE_STATUSES", "WRITE_FUNCTIONS",
]

# Codes whose registers are values read or written, as the protocol table states them: {3, 4, 23} and {6, 16, 23}.
READ_FUNCTIONS = register_reads()
WRITE_FUNCTIONS = register_writes()
# How those writes are confirmed (data/modbus.toml [confirm]): FC6 by its echo, FC16/FC23 by a normal answer.
_BY_ECHO = confirmed_registers(Confirm.ECHO)
_BY_ANSWER = confirmed_registers(Confirm.ANSWER)
# Register statuses a profile gives to a read that returned a marker rather than a value (p.38).
UNREADABLE_STATUSES = frozenset(["protected", "non-existent"])


class Listener(Protocol):
    def state(self, frame: Frame, register: Register, event: int, changed: bool) -> None:
        """A register that set its parameter's state (READ, UNREADABLE, CONFIRM, WRITE_OBSERVED)."""

    def renamed(self, slave: int) -> None:
        """This slave's profile changed: what was kept of it is to be read with the new one."""


class History:
    def __init__(self, annotate: object = None, store: Any = None) -> None:
        self.store = new_store() if store is None else store
        self.registers_without_address = 0
        self.listeners: list[Listener] = []
        self._profile_for: Callable[[int], object] | None = getattr(annotate, "profile_for", None)
        self._namer: Callable[[int], Any] | None = getattr(annotate, "namer", None)
        self._choice_frame: Callable[[int], int | None] | None = getattr(annotate, "choice_frame", None)
        self._annotate = annotate
        self.annotate = annotate  # for the outputs' names (PLC-style labels)
        self._renamed: dict[int, int] = {}  # slave -> the choice frame its values were named again for

    def add(self, item: Item) -> None:
        """A decoded item, in stream order (noise and damaged frames tell nothing of parameters)."""
        if item.kind is Kind.NOISE or not item.crc_ok:  # type: ignore[union-attr]
            return
        frame: Frame = item  # type: ignore[assignment]
        slave = frame.slave
        if self._choice_frame is not None:
            chosen = self._choice_frame(slave)
            if chosen is not None and frame.number >= chosen and self._renamed.get(slave) != chosen:
                # The first frame named with the profile chosen in frame `chosen`: what was kept of
                # this slave before (here, or by the compiled engine in the same store) is named again.
                self._renamed[slave] = chosen
                self._rename(slave)
        kind = frame.kind
        function = frame.function
        stale = self._stale(slave, frame.number)
        registers = frame.registers
        if stale and registers:
            registers = self._fresh(frame, registers)
        if kind is Kind.REQUEST:
            if function in WRITE_FUNCTIONS and registers:
                # A broadcast write: no answer will confirm it, the request is all there is.
                self._events(frame, registers, WRITE_OBSERVED if frame.broadcast else WRITE)
            return
        request = frame.request
        written = None
        if request is not None and request.crc_ok and request.registers and request.function in WRITE_FUNCTIONS:
            written = request.registers
            if self._stale(slave, request.number):
                written = self._fresh(request, written)
        if kind is Kind.EXCEPTION:
            if written:
                self._events(frame, written, REFUSED)
            if registers:
                self._reads(frame, registers)
            return
        # Writes first: FC23 performs its write before its read.
        if function in _BY_ECHO:
            if registers:
                self._events(frame, registers, CONFIRM, confirmed=True)
        elif function in _BY_ANSWER and written:
            self._events(frame, written, CONFIRM, confirmed=True)
        if function in READ_FUNCTIONS and registers:
            self._reads(frame, registers)

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

    def _fresh(self, frame: Frame, registers: list[Register]) -> list[Register]:
        """Registers named as the slave's device (chosen since) names them; statuses kept."""
        plain = getattr(self._annotate, "plain_register", None)
        device = getattr(self._annotate, "device", None)
        if plain is None or device is None:
            return registers
        rows = device(frame.slave).rows
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

    def _events(self, frame: Frame, registers: list[Register], event: int, confirmed: bool = False) -> None:
        param = self.store.param
        slave = frame.slave
        listeners = self.listeners if event in (CONFIRM, WRITE_OBSERVED) else None
        for register in registers:
            address = register.address
            if address is None:
                if not confirmed:  # an answer without its request confirms nothing: not even counted
                    self.registers_without_address += 1
                continue
            changed = param(slave, address, event, register.value, register.code, register.text)
            if listeners:
                for listener in listeners:
                    listener.state(frame, register, event, changed)

    def _reads(self, frame: Frame, registers: list[Register]) -> None:
        # The hot loop of --stats: one store call a register.
        param = self.store.param
        slave = frame.slave
        listeners = self.listeners
        for register in registers:
            address = register.address
            if address is None:
                self.registers_without_address += 1
                continue
            status = register.status
            if status in UNREADABLE_STATUSES:
                event = UNREADABLE
                changed = param(slave, address, UNREADABLE, 0, register.code, status)
            else:
                event = READ
                changed = param(slave, address, READ, register.value, register.code, register.text)
            if listeners:
                for listener in listeners:
                    listener.state(frame, register, event, changed)

    def _rename(self, slave: int) -> None:
        if self._namer is not None:
            self.store.rename({slave: self._namer(slave)})
        for listener in self.listeners:
            listener.renamed(slave)
