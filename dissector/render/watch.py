"""`--watch CODE[,CODE...]`: one line per change of a watched parameter, for files and live.

    frame  time  slave code old -> new (unit)

`--json` writes one object a change: `time` (seconds since the epoch, as the --json items' `time`),
`time_relative` (seconds since the first item, a network, RTAC or several-interface capture's first packet, as -T
fields' key), frame, slave, address, code, old, new, unit, and `provisional` when true; `-t` shapes the text
lines' time column only.

A watch line is a change of the parameter history (render/history.py): the state `--stats` counts in
`changes` and `--report` draws, so the three cannot disagree. A parameter's state is what the wire last
said of it (a parameter: a register of one table, input registers or holding registers, render/history.py):
a value read (FC3/4/23 answers) or written and confirmed (FC6 echo, FC16/23 request
confirmed by a normal answer), or a read status a device profile gave it: `protected`, `non-existent`
(16#8000 in a multi-register read, VW3 A3 303 p.38; or an exception the profile explains as "every
parameter read is non-existent or protected", said as `protected (exception 02)`). The first state seen
is not a change; an unchanged state prints nothing; a value after a status is the parameter readable
again. A broadcast write (slave 0) is shown each time, whatever came before: it writes every slave, whose
states it may or may not change, so its old state is `?` (JSON null) and it is marked `[broadcast: every
slave]` (JSON `"broadcast": true`). Values are named as the summary names them; a bit field (a status word) is shown as the manuals
write it, `16#0231`, with its bits named.

Names are checked: a code no map of the run knows is an error with the nearest known codes, and codes
need a profile (`-n` has none). A code is matched with the profile that applies to its slave. A file
is named with the profiles chosen over the whole file (app/preselect.py): no line waits. Read once
(standard input, live), a frame decoded before profile `auto` chose its slave's device is provisional:
its changes are written at once, as decoded, marked `[provisional]` (JSON `"provisional": true`), by
address when no device names them yet (`--watch CHCF` then shows address 8401, which a candidate
device names CHCF, as `--watch 8401` does). Once the device is chosen the history reads those frames
again (render/history.py) and the watched states become what the device says of them, silently: the
next line compares with that, so re-reading never makes a line of its own (p.38 read once: 16#8000
at 8400 before and after the choice is `non-existent` both times, no change).

A watched address or code the input never gave a register of is said at the end (`unseen()`, for stderr),
with where the capture carries that address as a bit (FC1/2/5/15: coils and discrete inputs, which are
not parameters of the history, so neither --stats nor --report count them): `--watch 172` on a capture
that reads coil 172 printed nothing and said nothing.
"""
from __future__ import annotations

import difflib
import json
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from dissector.errors import UsageError
from dissector.model import Frame, Item, Kind, Register
from dissector.protocol.printable import printable
from dissector.protocol.spec import SPEC
from dissector.protocol.table import bit_windows
from dissector.render.history import READ, UNREADABLE, UNREADABLE_STATUSES, WRITE_OBSERVED, History, wide_text
from dissector.render.stats_store import TABLES, homes_of, origins_of, table_label
from dissector.render.timefmt import Clock

BIT_WINDOWS = bit_windows()  # codes whose windows address bits (FC1, 2, 5, 15): not registers

@dataclass(frozen=True, slots=True)
class Change:
    time: float | None  # seconds since the epoch, as --json items have it (None: no timestamps)
    frame: int
    slave: int
    address: int
    code: str | None
    old: str
    new: str
    unit: str | None
    column: str = "-"  # the time column as -t formats it
    provisional: bool = False  # read before the slave's profile was chosen: its device may read it otherwise
    time_relative: float | None = None  # as -T fields' time_relative (since the first item, or packet)
    # The address as --address-style shows it (plc: 40001; an input register's else `input 5`), None: the address.
    label: str | None = None
    broadcast: bool = False  # a broadcast write: every slave written, whatever their states were (old: ?)
    # The input of its frame when several files are one bus (their frame numbers restart with each file).
    file: str | None = None
    units: int | None = None  # its capture's time units a second: the JSON time's digits (jsonout.exact_time)

    def line(self) -> str:
        name = self.code or self.label or str(self.address)
        unit = f" ({self.unit})" if self.unit else ""
        mark = (" [provisional]" if self.provisional else "") + (" [broadcast: every slave]" if self.broadcast else "")
        return f"{self.frame:>6} {self.column:>12} {self.slave:>3} {name} {self.old} -> {self.new}{unit}{mark}"

    def record(self) -> dict[str, object]:
        record: dict[str, object] = {
            "time": self.time, "time_relative": self.time_relative, "frame": self.frame, "slave": self.slave,
            "address": self.address,
            "code": self.code, "old": None if self.broadcast else self.old, "new": self.new, "unit": self.unit,
        }
        if self.label is not None:
            record["label"] = self.label
        if self.provisional:
            record["provisional"] = True
        if self.broadcast:
            record["broadcast"] = True
        if self.file is not None:
            record["file"] = self.file
        return record


def parse_watch(text: str, known: dict[str, frozenset[int]] | None = None) -> tuple[frozenset[str], frozenset[int]]:
    """Codes (upper case) and addresses; `known`: every code the run's maps have (None: no profile)."""
    codes: set[str] = set()
    addresses: set[int] = set()
    for token in text.split(","):
        token = token.strip()
        if not token:
            continue
        if token.isdigit():
            address = int(token)
            # A protocol address (0..65535), or a 6-digit PLC reference (100001.., 300001.., 400001..465536).
            if address > 0xFFFF and not (len(token) == 6 and token[0] in "134" and int(token[1:]) <= 0x10000):
                raise UsageError(f"--watch: address {address} is beyond 65535 and no 6-digit PLC reference "
                                 "(such as 400001)")
            addresses.add(address)
        elif token.replace("_", "").isalnum():
            codes.add(token.upper())
        else:
            raise UsageError(f"--watch: {token!r} is neither a parameter code nor an address")
    if not codes and not addresses:
        raise UsageError("--watch: give parameter codes or addresses, e.g. --watch CHCF,HSP")
    for code in sorted(codes):
        if known is None:
            raise UsageError(f"--watch {code}: codes are the device profiles' names, and -n turns profiles off: "
                             "give register addresses")
        if code not in known:
            close = difflib.get_close_matches(code, list(known), n=3)
            hint = f" (did you mean {', '.join(close)}?)" if close else ""
            raise UsageError(f"--watch {code}: no map of this run has that parameter code{hint}")
    return frozenset(codes), frozenset(addresses)


def value_text(register: Register, bits: bool = False) -> tuple[str, str | None]:
    """A register's value as the summary and --stats' `last` name it, and its unit (only a scaled value has
    one); `bits`: a bit field as the manuals write a status word, `16#0231 (bit names)` (--watch's lines)."""
    status = register.status
    if status in UNREADABLE_STATUSES:
        return status, None  # type: ignore[return-value]
    if register.value is None:
        return register.text or "no value", None
    if register.words == 2 and register.scaled is None:  # a 32-bit float with no number (nan, inf)
        return register.text or "no value", None
    if register.scaled is not None:
        text = register.text or str(register.scaled)
        unit = register.unit
        if unit and text.endswith(" " + unit):
            text = text[: -len(unit) - 1]
        return text, unit
    if bits:
        return f"16#{register.value:04X} ({register.text})" if register.text else f"16#{register.value:04X}", None
    if register.text is not None:  # the map's text for the word (`IO (I/O profile)`, the ATV71's 3) says it
        return register.text, None
    return str(register.value), None


@dataclass(slots=True)
class _State:
    """What a watched parameter last was: a value (with the function it came by) or a status."""

    value: int | None
    function: int
    text: str
    unit: str | None
    profile: object  # the profile it was named with
    status: str | None = None  # the read status (the history's state) when it is not a value
    code: str | None = None  # provisional: the code it was decoded with (None: shown by address)
    wide: bool = False  # a 32-bit value: `value` is its word pair (render/history.py wide_pair)

    def differs(self, other: _State) -> bool:
        """A change as the parameter history counts one (render/stats_store.py)."""
        if self.status is not None or other.status is not None:
            return self.status != other.status
        return self.value != other.value


@dataclass(slots=True)
class _Pending:
    frame: Frame
    time_relative: float | None
    column: str
    key: tuple[int, int, int]  # (slave, table, address)
    old: _State | None  # None: a broadcast write (every slave's state, not known)
    new: _State


class Watcher:
    """Follows the watched parameters through a parameter history; `add(item)` in stream order (the
    history is fed by its owner when shared), `on_change` gets each change, `finish()` at the end."""

    def __init__(
        self,
        codes: frozenset[str],
        addresses: frozenset[int],
        on_change: Callable[[Change], None],
        annotate: object = None,
        history: History | None = None,
        clock: Clock | None = None,
        live: bool = False,
        known: dict[str, frozenset[int]] | None = None,
    ) -> None:
        self.codes = codes
        self.addresses = addresses
        self.on_change = on_change
        self.annotate = annotate
        self._profile_for = getattr(annotate, "profile_for", None)
        self._device = getattr(annotate, "device", None)
        self.owns_history = history is None
        self.history = History(annotate) if history is None else history
        self.history.listeners.append(self)
        self.clock = clock if clock is not None else Clock()
        self.live = live
        # Addresses any profile of the run names with a watched code: followed for every slave, shown
        # when the slave's own profile gives them that code.
        self._candidates = frozenset(addresses).union(*(known.get(code, ()) for code in codes)) if known else addresses
        self._known = {code: known[code] for code in codes if code in known} if known else {}
        # By (slave, table, address), as the history keeps parameters; in the order last set (rehomed).
        self._state: dict[tuple[int, int, int], _State] = {}  # as the history holds it (re-read)
        self._shown: dict[tuple[int, int, int], _State] = {}  # as provisional lines showed it
        # By the same keys: bit t, a state set by a code of protocol table t (FC4: input; rehomed moves it by
        # those, as the store moves its parameters); and, where two tables' codes set them, by (slave, origin,
        # address), each one's last state (_State), which a choice taken back parts them into.
        self._origins: dict[tuple[int, int, int], int] = {}
        self._parts: dict[tuple[int, int, int], _State] = {}
        self._shown_origins: dict[tuple[int, int, int], int] = {}  # (of _shown)
        self._shown_parts: dict[tuple[int, int, int], _State] = {}
        self._column: tuple[Frame | None, str] = (None, "-")
        # The file being read when several are one bus (render/buses.py Buses.switch): lines name it.
        self.source: str | None = None
        # For unseen(): the watched addresses heard in a register window (whatever -Y keeps) or given a state,
        # the watched codes given a state, and each watched address's first request for it as a bit (the
        # request, the file it is in).
        self._heard: set[int] = set()
        self._coded: set[str] = set()
        self._as_bits: dict[int, tuple[Frame, str | None]] = {}

    @property
    def base(self) -> float | None:
        return self.clock.first

    def set_base(self, item: Item) -> None:
        """Every item captured, before any display filter (the time column's references)."""
        self.clock.observe([item])

    def observe(self, items: list[Item]) -> None:
        self.clock.observe(items)
        self._sight(items)

    def add(self, item: Item) -> None:
        """An item watched (after -Y); with a shared history its owner feeds the history itself."""
        if self.owns_history:
            self.clock.observe([item])
            self._sight([item])
            self.history.add(item)
        self.done()

    def _sight(self, items: list[Item]) -> None:
        """Where the watched addresses are in the items heard: a register window, or a request's bits."""
        watched = self.addresses - self._heard  # (an address heard as a register needs no more)
        if not watched:
            return
        for item in items:
            if item.kind is Kind.NOISE or not item.crc_ok:  # type: ignore[union-attr]
                continue
            frame: Frame = item  # type: ignore[assignment]
            start, quantity = frame.start, frame.quantity
            if start is None:
                continue
            bits = frame.function in BIT_WINDOWS
            if bits and frame.kind is not Kind.REQUEST:
                continue
            for address in watched:
                if start <= address < start + (quantity or 1):
                    if not bits:
                        self._heard.add(address)
                    elif address not in self._as_bits:
                        self._as_bits[address] = (frame, self.source)

    def unseen(self) -> list[str]:
        """At the end: a line for each watched address no register of the input had, and each watched code no
        register of the input was named with; where an address is a bit the capture carries, the first request
        for it (--watch follows registers only)."""
        lines = []
        for address in sorted(self.addresses - self._heard):
            line = f"--watch {address}: no register {address} in the capture"
            seen = self._as_bits.get(address)
            if seen is not None:
                frame, source = seen
                where = f"frame #{frame.number}" + (f" of {source}" if source is not None else "")
                who = "every slave (broadcast)" if frame.broadcast else f"slave {frame.slave}"
                line += (f" (bit {address}: {SPEC.function_name(frame.function)} to {who} in {where}; "
                         "--watch follows registers only)")
            lines.append(line)
        lines += [f"--watch {code}: no register named {code} in the capture"
                  for code in sorted(self.codes - self._coded)]
        return lines

    def done(self) -> None:
        """The items given so far are handled: write what may be written, forget -t d's references."""
        self.flush()
        self.clock.keep([])

    # -- the history's listener --------------------------------------------------------------------
    def state(self, frame: Frame, register: Register, event: int, changed: bool) -> None:
        address = register.address
        if address not in self._candidates:
            # A number is the protocol address or, under --address-style plc, the reference shown (40001),
            # as -Y 'address == 40001' takes either (filter_match.address_values).
            label = register.label
            if label is None or not label.isdigit() or int(label) not in self.addresses:
                return
        # (the slave's device's table: FC4 may read the holding registers, profiles.device_tables)
        key = (frame.slave, self.history.tables(frame.slave)[frame.function], address)  # type: ignore
        new = self._read(frame, register, event)
        self._seen(frame.slave, address, register.label, new.function, None)
        old = self._state.pop(key, None)  # type: ignore[arg-type]
        self._state[key] = new  # type: ignore[index]
        self._part(self._origins, self._parts, key, TABLES[frame.function], old, new)  # type: ignore[arg-type]
        if frame.provisional:
            return  # re-read once the device was chosen: its change (if any) was shown provisional
        self._shown.pop(key, None)  # type: ignore[arg-type]
        if event == WRITE_OBSERVED and frame.broadcast:
            self._emit(self._pending(frame, key, None, new))  # type: ignore[arg-type]
        elif changed and old is not None:
            self._emit(self._pending(frame, key, old, new))  # type: ignore[arg-type]

    def provisional(self, frame: Frame, register: Register, event: int) -> None:
        """A state of a frame read before the slave's device was chosen, as decoded: shown at once."""
        address = register.address
        if address not in self._candidates:
            return
        key = (frame.slave, self.history.tables(frame.slave)[frame.function], address)  # type: ignore
        new = self._read(frame, register, event, provisional=True)
        self._seen(frame.slave, address, register.label, new.function, register.code)
        # (shown by address where a candidate device's map names it with a watched code: that code is there)
        self._coded.update(code for code, where in self._known.items() if address in where)
        old = self._shown.pop(key, None)  # type: ignore[arg-type]
        self._shown[key] = new  # type: ignore[index]
        self._part(self._shown_origins, self._shown_parts, key, TABLES[frame.function], old, new)  # type: ignore
        if old is not None and old.differs(new):
            self._emit(self._pending(frame, key, old, new), provisional=True)  # type: ignore[arg-type]

    def _seen(self, slave: int, address: int, label: str | None, function: int, code: str | None) -> None:
        """A state given to a watched candidate: its address (or PLC label) and code are in the input."""
        self._heard.add(address)
        if label is not None and label.isdigit():
            self._heard.add(int(label))
        if self.codes:
            if code is None and self._device is not None:
                row = self._device(slave).rows_for(function).get(address)
                code = None if row is None else row.code
            if code is not None:
                self._coded.add(code.upper())

    @staticmethod
    def _part(origins: dict[tuple[int, int, int], int], parts: dict[tuple[int, int, int], _State],
              key: tuple[int, int, int], origin: int, old: _State | None, new: _State) -> None:
        """`new` set at `key` by a code of protocol table `origin` (`origins`): where codes of two tables set
        its states, each one's last kept in `parts` too (by slave, origin, address: rehomed parts them)."""
        bits = origins.get(key, 0)
        if bits | 1 << origin != 1 << origin:
            if bits & (bits - 1) == 0 and old is not None:  # its second table: the last is the first's
                parts[(key[0], bits.bit_length() - 1, key[2])] = old
            parts[(key[0], origin, key[2])] = new
        origins[key] = bits | 1 << origin

    def _pending(self, frame: Frame, key: tuple[int, int, int], old: _State | None, new: _State) -> _Pending:
        if self._column[0] is not frame:  # one text a frame: -t d takes the previous time once
            self._column = (frame, self.clock.text(frame))
        time = None if frame.time is None or self.clock.first is None else frame.time - self.clock.first
        return _Pending(frame, time, self._column[1], key, old, new)  # -t shapes the column only

    def renamed(self, slave: int) -> None:
        pass  # states keep their raw values: they are named again when written

    def rehomed(self, slave: int, homes: bytes) -> None:
        """The slave's states moved to the tables its new device reads them with (History._rehome), by the
        protocol tables of the codes that set them (`_origins`, as the store moves its parameters): of two
        states of one parameter, the later set is its state (each one's last kept: `_part`); one that two
        tables' codes set, where those are apart now (a choice taken back), parts into each one's last."""
        for states, origins, parts in ((self._state, self._origins, self._parts),
                                       (self._shown, self._shown_origins, self._shown_parts)):
            moving = {key: origins.pop(key) for key in [key for key in origins if key[0] == slave]}
            homed: dict[tuple[int, int, int], int] = {}  # the keys' origins after the move
            for key, bits in moving.items():
                tables = homes_of(bits, homes)
                for origin in origins_of(bits):
                    home = (slave, homes[origin] if len(tables) > 1 else min(tables), key[2])
                    homed[home] = homed.get(home, 0) | 1 << origin
            for key, bits in moving.items():  # states of one table's codes joining another's: their parts
                home = (slave, homes[bits.bit_length() - 1], key[2])
                if bits & (bits - 1) == 0 and key in states and homed[home] & (homed[home] - 1):
                    parts.setdefault((slave, bits.bit_length() - 1, key[2]), states[key])
            order = {key: index for index, key in enumerate(states)}
            for key in [key for key in order if key[0] == slave]:
                tables = homes_of(moving.get(key, 1 << key[1]), homes)
                home = (slave, min(tables), key[2])
                if len(tables) == 1 and home == key:
                    continue  # (it stays, where it was set)
                moved = states.pop(key)
                if len(tables) == 1:
                    if home not in order or order[home] < order[key]:
                        states.pop(home, None)
                        states[home] = moved
                    continue
                for origin in origins_of(moving[key]):
                    part = parts.pop((slave, origin, key[2]), None)
                    if part is not None:
                        states[(slave, homes[origin], key[2])] = part
            origins.update(homed)

    # -- writing -----------------------------------------------------------------------------------
    def flush(self) -> None:
        pass  # every line is written as its frame comes

    def finish(self) -> None:
        """The input ended: the history's frames still held are counted (no line: shown provisional)."""
        self.history.finish()

    def _emit(self, pending: _Pending, provisional: bool = False) -> None:
        slave, table, address = pending.key
        code = pending.new.code if provisional else self._code(slave, address, pending.new)
        label = self._label(slave, pending.new.function, address)
        if (address not in self.addresses and (label is None or int(label) not in self.addresses)
                and (code is None or code.upper() not in self.codes)):
            if not (provisional and code is None):
                return
            # No device yet: an address a candidate's map names with a watched code is shown by its
            # number, provisional, as --watch ADDRESS shows it (by address and by code agree).
        old = pending.old
        if provisional:  # as decoded, whatever the history knows by now (the same in any batch)
            (old_text, _), (new_text, unit) = (old.text if old else "?", None), (pending.new.text, pending.new.unit)
        else:
            old_text = self._text(slave, address, old)[0] if old else "?"
            new_text, unit = self._text(slave, address, pending.new)
        if old_text == new_text:
            return  # the same once named by the same device
        self.on_change(Change(pending.frame.time, pending.frame.number, slave, address, code, old_text, new_text,
                              unit, pending.column, provisional, pending.time_relative,
                              table_label(label, table, address), old is None, self.source, self.clock.units))

    def _label(self, slave: int, function: int, address: int) -> str | None:
        """The address as the summary shows it under --address-style (devices.naming.plc_label), or None."""
        label = getattr(self.annotate, "label", None)
        return None if label is None else label(slave, function, address)

    def _read(self, frame: Frame, register: Register, event: int, provisional: bool = False) -> _State:
        """`provisional`: as decoded (the profile and device the history knows by now may be later's)."""
        profile = None if provisional else self.history.named_by(frame)
        function = frame.function
        if event == UNREADABLE:
            status = register.status or "unreadable"
            if frame.kind is Kind.EXCEPTION and frame.exception_code is not None:
                status = f"{status} (exception {frame.exception_code:02X})"
            return _State(None, function, status, None, profile, register.status or "unreadable", register.code)
        if event != READ:
            register = _as_written(register)  # a written value has no read status
        bits = not provisional and self._bits(frame.slave, register.address, function)  # type: ignore[arg-type]
        text, unit = value_text(register, bits)
        return _State(register.value, function, text, unit, profile, None, register.code, register.words == 2)

    def _bits(self, slave: int, address: int, function: int) -> bool:
        if self._device is None:
            return False
        row = self._device(slave).rows_for(function).get(address)  # (FC4's: its input rows, if apart)
        return row is not None and bool(row.bits) and not row.enum

    def _code(self, slave: int, address: int, state: _State) -> str | None:
        if self._device is None:
            return None
        row = self._device(slave).rows_for(state.function).get(address)
        return None if row is None else row.code

    def _text(self, slave: int, address: int, state: _State) -> tuple[str, str | None]:
        """A state as the slave's device names it now (named again when its profile changed since)."""
        if state.value is None or self._profile_for is None or self._profile_for(slave) is state.profile:
            return state.text, state.unit
        if state.wide:  # a word pair: read by the device's 32-bit row, if it still has one there
            row = self._device(slave).rows_for(state.function).get(address) if self._device is not None else None
            if row is None or row.words != 2:
                return state.text, state.unit
            scaled, text = wide_text(row, state.value)
            return value_text(Register(address, state.value, scaled=scaled, text=text, unit=row.unit, words=2))
        register = self.annotate.plain_register(slave, state.function, address, state.value)  # type: ignore[attr-defined]
        return value_text(register, self._bits(slave, address, state.function))


def _as_written(register: Register) -> Register:
    """A written register has no read status: its value is what was written."""
    if register.status is None:
        return register
    return Register(register.address, register.value, register.code, register.name, register.unit,
                    register.scaled, register.text)


def known_codes(annotate: object) -> dict[str, frozenset[int]] | None:
    """Every code the run's maps name (upper case) -> its addresses; None without profiles (-n)."""
    codes = getattr(annotate, "codes", None)
    return None if codes is None else codes()


def watcher(
    text: str, write: Callable[[str], None], as_json: bool, annotate: object, history: History | None = None,
    clock: Clock | None = None, live: bool = False,
) -> Watcher:
    known = known_codes(annotate)
    codes, addresses = parse_watch(text, known)
    return Watcher(codes, addresses, printer(write, as_json), annotate, history, clock, live, known)


class WatchSink:
    """The live capture's sink under --watch: change lines instead of items, handed to a line pump
    (the live view's OutputPump: put(lines), close(), failed, dropped) as their frames arrive."""

    def __init__(self, text: str, pump: Any, as_json: bool, annotate: object, time_format: str = "r") -> None:
        self._pump = pump
        self._lines: list[str] = []
        self.watcher = watcher(text, lambda line: self._lines.append(line.rstrip("\n")), as_json, annotate,
                               clock=Clock(time_format), live=True)

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

    def unseen(self) -> list[str]:
        """At the capture's end, as a file's decode says them (Watcher.unseen)."""
        return self.watcher.unseen()


def printer(write: Callable[[str], None], as_json: bool, file: str | None = None) -> Callable[[Change], None]:
    """`file`: the bus's title, of several (render/buses.py), as --json's items name their input. A change's
    own file (several files one bus) is its JSON `file`, and a `==> FILE <==` line over its file's first
    line, as the summary titles each file's items."""
    if as_json:
        from dissector.render.jsonout import exact_time

        extra = {} if file is None else {"file": file}
        return lambda change: write(exact_time(json.dumps(change.record() | extra), change.time, change.units) + "\n")
    titled: list[str | None] = [None]

    def line(change: Change) -> None:
        if change.file is not None and change.file != titled[0]:
            titled[0] = change.file
            write(f"==> {printable(change.file)} <==\n")
        write(change.line() + "\n")

    return line
