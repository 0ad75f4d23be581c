"""`--watch CODE[,CODE...]`: one line per change of a watched parameter, for files and live.

    time  slave code old -> new (unit)

A parameter's state is what the wire last said of it: a value read (FC3/4/23 answers) or written and
confirmed (FC6 echo, FC16/23 request confirmed by a normal answer), or a status a device profile gave
it: `protected`, `non-existent` (16#8000 in a multi-register read, VW3 A3 303 p.38), or an exception
to a read that covers it (`exception 02 (protected)`: the profile's reading of that exception for
this address). The first state seen is not a change; an unchanged state prints nothing; a value
after a status is the parameter readable again. Watched items are given as codes (case-insensitive)
or register addresses; the device profile names the codes, the watcher knows no device.
"""
from __future__ import annotations

import json
from collections.abc import Callable
from typing import Any
from dataclasses import dataclass

from dissector.errors import UsageError
from dissector.model import Frame, Item, Kind, Register
from dissector.render.stats import PLAIN_READS, UNREADABLE, wire_values



@dataclass(frozen=True, slots=True)
class Change:
    time: float | None  # seconds since the first item (None: no timestamps)
    frame: int
    slave: int
    address: int
    code: str | None
    old: str
    new: str
    unit: str | None

    def line(self) -> str:
        when = "-" if self.time is None else f"{self.time:.6f}"
        name = self.code or str(self.address)
        unit = f" ({self.unit})" if self.unit else ""
        return f"{when:>13} {self.slave:>3} {name} {self.old} -> {self.new}{unit}"

    def record(self) -> dict[str, object]:
        return {
            "time": self.time, "frame": self.frame, "slave": self.slave, "address": self.address,
            "code": self.code, "old": self.old, "new": self.new, "unit": self.unit,
        }


def parse_watch(text: str) -> tuple[frozenset[str], frozenset[int]]:
    codes: set[str] = set()
    addresses: set[int] = set()
    for token in text.split(","):
        token = token.strip()
        if not token:
            continue
        if token.isdigit():
            address = int(token)
            if address > 0xFFFF:
                raise UsageError(f"--watch: address {address} is beyond 65535")
            addresses.add(address)
        elif token.replace("_", "").isalnum():
            codes.add(token.upper())
        else:
            raise UsageError(f"--watch: {token!r} is neither a parameter code nor an address")
    if not codes and not addresses:
        raise UsageError("--watch: give parameter codes or addresses, e.g. --watch CHCF,HSP")
    return frozenset(codes), frozenset(addresses)


def value_text(register: Register) -> tuple[str, str | None]:
    """A register's value as the summary names it, and its unit (only a scaled value has one)."""
    status = register.status
    if status in UNREADABLE:
        return status, None  # type: ignore[return-value]
    if register.scaled is not None:
        text = register.text or str(register.scaled)
        unit = register.unit
        if unit and text.endswith(" " + unit):
            text = text[: -len(unit) - 1]
        return text, unit
    if register.text is not None:
        return f"{register.value} {register.text}", None
    return str(register.value), None


class Watcher:
    """Follows the watched parameters; `add(item)` in stream order, `on_change` gets each change."""

    def __init__(
        self,
        codes: frozenset[str],
        addresses: frozenset[int],
        on_change: Callable[[Change], None],
        statuses: Callable[[int, int], str | None] | None = None,
    ) -> None:
        self.codes = codes
        self.addresses = addresses
        self.on_change = on_change
        # What the profile concluded of an address after an exception (annotator knowledge).
        self.statuses = statuses
        self.base: float | None = None
        self._state: dict[tuple[int, int], str] = {}
        self._codes: dict[tuple[int, int], str | None] = {}

    def set_base(self, item: Item) -> None:
        if self.base is None and item.time is not None:
            self.base = item.time

    def add(self, item: Item) -> None:
        self.set_base(item)
        if item.kind is Kind.NOISE or not item.crc_ok:  # type: ignore[union-attr]
            return
        frame: Frame = item  # type: ignore[assignment]
        if frame.kind is Kind.EXCEPTION:
            self._exception(frame)
            return
        for registers, written in wire_values(frame):
            self._registers(frame, registers, written)

    def _watched(self, register: Register) -> bool:
        if register.address is None:
            return False
        if register.address in self.addresses:
            return True
        return register.code is not None and register.code.upper() in self.codes

    def _registers(self, frame: Frame, registers: list[Register] | None, written: bool) -> None:
        for register in registers or ():
            if not self._watched(register):
                continue
            key = (frame.slave, register.address)  # type: ignore[assignment]
            if register.code is not None:
                self._codes[key] = register.code  # type: ignore[index]
            text, unit = value_text(register) if not written else value_text(_as_written(register))
            self._set(frame, key, text, unit)  # type: ignore[arg-type]

    def _exception(self, frame: Frame) -> None:
        """An exception to a read: each watched address it covers is unreadable for that reason."""
        request = frame.request
        if request is None or request.function not in PLAIN_READS or request.start is None:
            return
        code = frame.exception_code
        start, quantity = request.start, request.quantity or 1
        for (slave, address), name in list(self._codes.items()) + self._plain_addresses(frame.slave):
            if slave != frame.slave or not 0 <= (address - start) & 0xFFFF < quantity:
                continue
            status = self.statuses(slave, name is not None, code) if self.statuses is not None else None
            text = f"exception {code:02X}" if code is not None else "exception"
            self._set(frame, (slave, address), f"{text} ({status})" if status else text, None)

    def _plain_addresses(self, slave: int) -> list[tuple[tuple[int, int], str | None]]:
        return [((slave, address), None) for address in self.addresses if (slave, address) not in self._codes]

    def _set(self, frame: Frame, key: tuple[int, int], text: str, unit: str | None) -> None:
        old = self._state.get(key)
        self._state[key] = text
        if old is None or old == text:
            return
        time = None if frame.time is None or self.base is None else frame.time - self.base
        self.on_change(
            Change(time, frame.number, key[0], key[1], self._codes.get(key), old, text, unit)
        )


def _as_written(register: Register) -> Register:
    """A written register has no read status: its value is what was written."""
    if register.status is None:
        return register
    copy = Register(register.address, register.value, register.code, register.name, register.unit,
                    register.scaled, register.text)
    return copy


def profile_statuses(annotate: object) -> Callable[[int, bool, int | None], str | None] | None:
    """The profile's reading of an exception to a read, per address (p.38: the exception that means
    every parameter read is non-existent or protected; a named one is protected)."""
    profile_for = getattr(annotate, "profile_for", None)
    if profile_for is None:
        return None

    def status(slave: int, named: bool, code: int | None) -> str | None:
        meaning = getattr(profile_for(slave), "all_protected_exception", None)
        if code is None or code != meaning:
            return None
        return "protected" if named else "non-existent"

    return status


def watcher(text: str, write: Callable[[str], None], as_json: bool, annotate: object) -> Watcher:
    codes, addresses = parse_watch(text)
    return Watcher(codes, addresses, printer(write, as_json), profile_statuses(annotate))


class WatchSink:
    """The live capture's sink under --watch: change lines instead of items, handed to a line pump
    (the live view's OutputPump: put(lines), close(), failed, dropped) as their frames arrive."""

    def __init__(self, text: str, pump: Any, as_json: bool, annotate: object) -> None:
        self._pump = pump
        self._lines: list[str] = []
        self.watcher = watcher(text, lambda line: self._lines.append(line.rstrip("\n")), as_json, annotate)

    @property
    def failed(self) -> BaseException | None:
        return self._pump.failed

    @property
    def dropped(self) -> int:
        return self._pump.dropped

    def show(self, items: list[Item]) -> None:
        for item in items:
            self.watcher.add(item)
        if self._lines:
            self._pump.put(self._lines)
            self._lines = []

    def tick(self) -> None:
        pass

    def close(self) -> None:
        self._pump.close()


def printer(write: Callable[[str], None], as_json: bool) -> Callable[[Change], None]:
    if as_json:
        return lambda change: write(json.dumps(change.record()) + "\n")
    return lambda change: write(change.line() + "\n")
