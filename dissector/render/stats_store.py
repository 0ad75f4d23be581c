"""Where `--stats` keeps its per-parameter counts: the compiled store (`_summary.Stats`, written in C
in dissector/accel/_stats.h) when the extension is built, this module's `ParameterTable` otherwise.

Both take the same events in stream order, one per register a frame carries, so that the compiled
summary path (which counts the transactions it shows inside the engine) and the Python stages (which
count the frames they show through `param`) update one parameter table: a parameter's last value and
its changes follow the order of the stream whichever side saw each frame.

Events (StatsCollector's rules, render/stats.py):
- READ: a value read (FC3/4/23 answer): reads + 1, a value seen;
- UNREADABLE: a read the profile marked protected or non-existent (16#8000, or an exception the profile
  explains so, p.38): unreadable + 1, the state becomes that status (`text` is the status);
- WRITE: a value a request asks to write: writes + 1;
- WRITE_OBSERVED: a broadcast write, which nothing will confirm: writes + 1, a value seen;
- REFUSED: a write whose request got an exception: refused + 1;
- CONFIRM: a value written and confirmed (FC6 echo, FC16/23 request of a normal answer): a value seen.
A register's code is kept when it has one; CONFIRM sets it on a parameter's first sight only.
A parameter's state is its last value or read status; `param` answers whether the state changed (the
first state is no change), and `changes` counts those: the same changes `--watch` prints.
`rename({slave: namer})` names the kept values of slaves whose profile was chosen after they were read;
`rehome(slave, homes)` moves a slave's parameters to the tables its new device reads them with (SlaveTables),
and parts one that codes of two protocol tables counted where those are apart again (ParameterTable._part).
"""
from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterator
from itertools import chain
from dataclasses import dataclass, replace
from typing import Any

from dissector.devices.profiles import (
    HOLDING_REGISTERS, INPUT_REGISTERS, TABLES, device_tables, register_table,
)
from dissector.protocol.table import register_reads

try:
    from dissector.accel._summary import Stats as CompiledStore
except ImportError:  # built without a C compiler
    CompiledStore = None

# The events (the compiled store's EVENT_*, generated into dissector/accel/_tables.h).
EVENTS = ("READ", "UNREADABLE", "WRITE", "WRITE_OBSERVED", "REFUSED", "CONFIRM")
READ, UNREADABLE, WRITE, WRITE_OBSERVED, REFUSED, CONFIRM = range(len(EVENTS))
# What an event does to its parameter (the rules above): the count it adds one to (None: none) and whether
# it sets the state (a value or a status seen). ParameterTable.param and the compiled store (_stats.h
# param_count, EVENT_RULES generated into _tables.h) both read it.
EVENT_RULES: dict[int, tuple[str | None, bool]] = {
    READ: ("reads", True), UNREADABLE: ("unreadable", True), WRITE: ("writes", False),
    WRITE_OBSERVED: ("writes", True), REFUSED: ("refused", False), CONFIRM: (None, True),
}
# The compiled store's histograms (Stats.tallies(), dissector/accel/_bus.h; TALLY_* generated into
# _tables.h): response times by (slave << 8 | function), gaps, turnarounds, response times by slave, load
# per minute, poll intervals by key order, and the engine's counts by (slave << 8 | function): exceptions
# by their code, requests, responses and unanswered requests by the COUNT_* keys (StatsCollector.all_functions).
TALLY_TIMES, TALLY_GAPS, TALLY_TURNAROUND, TALLY_RESPONSES, TALLY_MINUTES, TALLY_INTERVALS, TALLY_COUNTS = range(7)
COUNT_REQUESTS, COUNT_RESPONSES, COUNT_UNANSWERED = 256, 257, 258  # past the exception codes
UNBOUNDED_TALLIES = (TALLY_MINUTES, TALLY_COUNTS)  # never coarsened: sums, counts by name
MAX_KEYS = 50_000  # requests the poll cycle follows (render/pollcycle.py), in either store
# Parameters kept at most: a plant's devices have a few thousand each; a flood of writes over every
# address of 64 slaves (4 M parameters) took 2 GB. Events of further parameters are counted (`dropped`)
# and the outputs say so; kept parameters keep every event.
MAX_PARAMETERS = 1 << 18
# Histogram entries of one kind (response times of every slave and function, poll intervals of every
# key, ...) kept at most: random times on a bus of 247 slaves (the max-size mix) kept 1.3 GB at 1 GB of
# pcap. Past it the kind's keys are rounded down to multiples of 2**shift (Coarse): a real bus, whose
# times cluster, stays exact.
MAX_TALLY = 1 << 16
MAX_SHIFT = 62  # _bus.h TALLY_MAX_SHIFT

ParameterRow = tuple[int, int, Any, int, int, int, int, Any, Any, int, int]

# A parameter is a register of one table: profiles.register_table (input registers and holding registers,
# Application Protocol 4.3; imported above, and from here by the outputs) and profiles.device_tables (a
# device that reads both with one table).


class SlaveTables:
    """slave -> each code's register table on the slave's device now (device_tables), asked again each
    time: the device may change under profile `auto`. Both stores and every output key parameters through
    it, so the first of them to ask after a slave's device changed sees the change: where the new device
    reads a table with another's code than the old one did (profile `auto` choosing the ATV71 after FC4
    reads: its FC4 reads the holding registers; or taking it back), `moved(slave, homes)` moves what was
    kept before the first event counted with the new tables (homes: each table's new table, by table)."""

    __slots__ = ("device", "given", "moved")

    def __init__(self, device: Callable[[int], Any]) -> None:
        self.device = device
        self.given: dict[int, bytes] = {}  # the tables last given for each slave
        self.moved: Callable[[int, bytes], None] | None = None

    def __call__(self, slave: int) -> bytes:
        return self.named(slave, device_tables(self.device(slave).profile))

    def named(self, slave: int, tables: bytes) -> bytes:
        """The slave's tables are `tables` (its device's now, or the one a frame counted late was named
        with: History._named_tables): what was kept with others moves, as a stream saw it move."""
        given = self.given.get(slave)
        if given is not tables:
            self.given[slave] = tables
            homes = table_homes(tables)
            # (back to separate tables too: what an ATV71 counted in one table of FC4 reads is an input
            # register again when `auto` takes that choice back)
            if given is not None and self.moved is not None and homes != table_homes(given):
                self.moved(slave, homes)
        return tables


def slave_tables(annotate: object) -> SlaveTables | None:
    """The run's SlaveTables; None without devices (the protocol's tables)."""
    device = getattr(annotate, "device", None)
    return None if device is None else SlaveTables(device)


# Each table as --stats names it (its --json `table`; the text marks an input register's address so).
TABLE_NAMES = {HOLDING_REGISTERS: "holding", INPUT_REGISTERS: "input"}


def table_label(label: str | None, table: int, address: int | str) -> str | None:
    """A parameter's address as the outputs show it: `label` (--address-style plc: 40001, 30001), else an
    input register's marked `input 5` (holding register 5 is another parameter), else None: the address."""
    return label if label is not None or table == HOLDING_REGISTERS else f"{TABLE_NAMES[table]} {address}"


def table_reader(table: int) -> int:
    """The code that reads a table's registers (FC3, FC4): whose PLC-style label (40001, 30001) they have."""
    return min(code for code in register_reads() if register_table(code) == table)


def table_homes(tables: bytes) -> bytes:
    """By table, the table its registers are on a device of these tables (device_tables): the one its
    reader code reads there (the ATV71's input registers are its holding registers)."""
    return bytes(tables[table_reader(table)] for table in sorted(TABLE_NAMES))


IDENTITY_HOMES = table_homes(TABLES)  # the protocol's: every table its own


def give_back() -> None:
    """The memory the decoding freed (the engine's tables, the input's buffers) back to the system, before
    an output is built from the counts: glibc keeps a freed heap resident, and the output's Python
    objects come from fresh arenas, so a peak was the decoding's and the output's together (--report,
    max-size 1.6M frames: 102 MB decoded, 114 MB writing the page; trimmed first: 98 MB writing it,
    issue 28). Nothing where the C library has no malloc_trim."""
    try:
        import ctypes

        ctypes.CDLL(None).malloc_trim(0)
    except (OSError, AttributeError):
        pass


@dataclass(slots=True)
class ParameterStats:
    code: str | None = None
    reads: int = 0
    unreadable: int = 0
    writes: int = 0
    refused: int = 0
    last: int | None = None
    last_text: str | None = None  # as the summary names it (scaled with its unit, enumeration text)
    changes: int = 0
    status: str | None = None  # the last state is this read status, not a value
    seen: bool = False  # a state (value or status) was seen
    order: int = 0  # when its state was last set (the store's count of states set): merges keep the later
    origins: int = 0  # bit t: counted of a code whose protocol table is t (FC4: input), where rehome finds its home


def origins_of(origins: int) -> list[int]:
    """The protocol tables of a parameter's `origins` (ParameterStats.origins), in order."""
    return [table for table in range(origins.bit_length()) if origins >> table & 1]


def homes_of(origins: int, homes: bytes) -> set[int]:
    """The tables a parameter's codes read on a device of these homes (SlaveTables, table_homes): one, where
    it moves (rehome); two, where its codes' tables are apart there."""
    return {homes[table] for table in origins_of(origins)}


def join(kept: ParameterStats, moved: ParameterStats) -> None:
    """`moved`'s story joined to `kept`'s (the same parameter, kept in two tables, or a part's): counts and
    changes summed, the state the later set, one change more where the two last states differ (their
    stories joined one after the other)."""
    kept.origins |= moved.origins
    first, later = (kept, moved) if kept.order <= moved.order else (moved, kept)
    for counter in ("reads", "unreadable", "writes", "refused", "changes"):
        setattr(kept, counter, getattr(kept, counter) + getattr(moved, counter))
    if first.seen and later.seen and differ(first, later):
        kept.changes += 1
    if later is moved and moved.seen:
        kept.last, kept.last_text, kept.status, kept.order = moved.last, moved.last_text, moved.status, moved.order
        kept.seen = True
    if kept.code is None:
        kept.code = moved.code


def apply_event(stats: ParameterStats, created: bool, event: int, value: int, code: str | None,
                text: str | None, order: int) -> bool:
    """ParameterTable.param's event told to `stats` (`order`: its state's, if it sets one): changed?"""
    if code is not None and (event != CONFIRM or created):
        stats.code = code
    counter, sets_state = EVENT_RULES[event]
    if counter is not None:
        setattr(stats, counter, getattr(stats, counter) + 1)
    if not sets_state:
        return False
    if event == UNREADABLE:  # 16#8000 stands for "no value", not a value: the state is the status
        changed = stats.seen and stats.status != text
        stats.status = text
    else:
        changed = stats.seen and (stats.status is not None or value != stats.last)
        stats.status = None
        stats.last = value
        stats.last_text = text
    stats.seen = True
    stats.order = order
    if changed:
        stats.changes += 1
    return changed


def differ(first: ParameterStats, later: ParameterStats) -> bool:
    """Two states differ (as ParameterTable.param counts a change): a status from another, or from a value,
    or two values."""
    if first.status is not None or later.status is not None:
        return first.status != later.status
    return first.last != later.last


class ParameterTable:
    """The pure-Python store (no C extension): the same events and rows as `_summary.Stats`."""

    frames = 0  # frames counted by the compiled engine: none here

    def __init__(self, max_params: int = MAX_PARAMETERS) -> None:
        self._parameters: dict[tuple[int, int, int], ParameterStats] = {}  # by (slave, address, table)
        self._max_params = max_params
        self.dropped = 0  # events of parameters beyond max_params, not kept
        self._states = 0  # states set so far (ParameterStats.order)
        # By (slave, address, origin): the story of each protocol table's codes of a parameter two count (_part)
        self._parts: dict[tuple[int, int, int], ParameterStats] = {}

    def param(self, slave: int, address: int, event: int, value: int, code: str | None, text: str | None,
              table: int = HOLDING_REGISTERS, origin: int | None = None) -> bool:
        """`table`: the register table on the slave's device now; `origin`: the code's in the protocol
        (register_table; None: `table`)."""
        key = (slave, address, table)
        stats = self._parameters.get(key)
        created = stats is None
        if stats is None:
            if len(self._parameters) >= self._max_params:
                self.dropped += 1
                return False
            stats = self._parameters[key] = ParameterStats()
        bit = 1 << (table if origin is None else origin)
        if stats.origins | bit != bit:  # codes of two protocol tables count it: each keeps its story too
            self._part(slave, address, stats, bit, event, value, code, text)
        stats.origins |= bit
        changed = apply_event(stats, created, event, value, code, text, self._states + 1)
        if EVENT_RULES[event][1]:
            self._states += 1
        return changed

    def _part(self, slave: int, address: int, stats: ParameterStats, bit: int, event: int, value: int,
              code: str | None, text: str | None) -> None:
        """The event of a parameter two protocol tables' codes count (an ATV71's 8502 read by FC4 and
        written by FC6) told to its origin's part too (`_parts`, by slave, address, origin): the story that
        code's table alone tells, which the parameter parts into if the choice is taken back (rehome)."""
        parts = self._parts
        if stats.origins & (stats.origins - 1) == 0:  # its second origin: the story so far is the first's
            parts[(slave, address, stats.origins.bit_length() - 1)] = replace(stats)
        key = (slave, address, bit.bit_length() - 1)
        part = parts.get(key)
        if created := part is None:
            part = parts[key] = ParameterStats(origins=bit)
        apply_event(part, created, event, value, code, text, self._states + 1)

    def rehome(self, slave: int, homes: bytes) -> None:
        """The slave's parameters moved to the tables homes gives (by table) the tables their codes read in
        the protocol (SlaveTables, `homes_of`); one whose codes' tables are apart now (an ATV71's 8502 read
        by FC4 and written by FC6, the choice taken back) parts into the stories each told (`_part`).
        Two parameters in one table are one story (`_join`)."""
        parameters, parts = self._parameters, self._parts
        moving = sorted((key, stats) for key, stats in parameters.items() if key[0] == slave)
        for key, _stats in moving:
            del parameters[key]
        for (_slave, address, table), stats in moving:
            tables = homes_of(stats.origins, homes)
            pieces = [parts.pop((slave, address, origin), None) for origin in origins_of(stats.origins)]
            if len(tables) < 2 or None in pieces:  # (one home: the parts stay its own)
                parts.update({(slave, address, piece.origins.bit_length() - 1): piece for piece in pieces if piece})
                self._join((slave, address, tables.pop() if len(tables) == 1 else table), stats)
                continue
            for piece in pieces:
                self._join((slave, address, homes[piece.origins.bit_length() - 1]), piece)  # type: ignore[union-attr]

    def _join(self, key: tuple[int, int, int], moved: ParameterStats) -> None:
        """`moved` kept at `key`; joined to the parameter kept there: one story (join), its parts kept
        where their origins are two now."""
        kept = self._parameters.setdefault(key, moved)
        if kept is moved:
            return
        origins = kept.origins | moved.origins
        if origins & (origins - 1):
            parts = self._parts
            for stats in (kept, moved):
                if stats.origins & (stats.origins - 1) == 0:  # one origin: its story is that origin's
                    part = (key[0], key[1], stats.origins.bit_length() - 1)
                    if part in parts:
                        join(parts[part], replace(stats))
                    else:
                        parts[part] = replace(stats)
        join(kept, moved)

    def rename(self, namers: dict[int, Any]) -> None:
        for (slave, address, table), stats in self._parameters.items():
            namer = namers.get(slave)
            if namer is None:
                continue
            # (the parameter's table: a map in references names input registers apart, Device.table_rows)
            text, code = namer(address, 0 if stats.status is not None or stats.last is None else stats.last, table)
            stats.code = code  # the new device's, None where it names nothing (not the old one's)
            if stats.status is None and stats.last is not None:
                stats.last_text = text

    def parameters(self) -> list[ParameterRow]:
        """By (slave, address, table); last_text the last value's text, None when nothing names it; the
        table last (register_table)."""
        return [
            (slave, address, s.code, s.reads, s.unreadable, s.writes, s.refused,
             None if s.status is not None else s.last, s.status if s.status is not None else s.last_text, s.changes,
             table)
            for (slave, address, table), s in sorted(self._parameters.items())
        ]

    def last(self, slave: int, address: int, table: int = HOLDING_REGISTERS) -> int | None:
        """The parameter's last value; None where its state is a read status, or none (not seen, not kept)."""
        stats = self._parameters.get((slave, address, table))
        return None if stats is None or stats.status is not None else stats.last

    def writes(self, slave: int, address: int, table: int = HOLDING_REGISTERS) -> int:
        """The writes counted of that parameter (0: none, or not kept)."""
        stats = self._parameters.get((slave, address, table))
        return 0 if stats is None else stats.writes

    def table(self, max_rows: int, group_min: int) -> tuple[list[list[ParameterRow]], int, int, tuple[int, ...]]:
        """--stats' parameter table (render/stats.py _parameter_table): the rows of the first `max_rows`
        pieces, a piece being a run of `group_min` or more parameters with the same story (the next
        address of the slave's table, the same counts, all named or all unnamed) or one parameter; how many
        pieces in all; how many parameters; the sums of reads, unreadable, writes, refused, changes."""
        rows = self.parameters()
        pieces: list[list[ParameterRow]] = []
        expanded = first = 0
        for index, row in enumerate(rows):
            following = rows[index + 1] if index + 1 < len(rows) else None
            if (following is not None and following[0] == row[0] and following[10] == row[10]
                    and following[1] == row[1] + 1
                    and following[3:7] == row[3:7] and following[9] == row[9]
                    and (following[2] is None) == (row[2] is None)):
                continue
            end = index + 1
            grouped = end - first >= group_min
            for start in [first] if grouped else range(first, end):
                if len(pieces) < max_rows:
                    pieces.append(rows[start : end if grouped else start + 1])
            expanded += 1 if grouped else end - first
            first = end
        totals = tuple(sum(row[k] for row in rows) for k in (3, 4, 5, 6, 9))
        return pieces, expanded, len(rows), totals

    @property
    def parameter_count(self) -> int:
        return len(self._parameters)


def parameter_rows(store: Any) -> Iterator[ParameterRow]:
    """Every parameter's row (ParameterTable.parameters) by (slave, address, table), from either store's table():
    with no limit on pieces and every run of the same story one piece."""
    return chain.from_iterable(store.table(sys.maxsize, 0)[0])


class Coarse:
    """The histograms of one kind of tally ({key: count}, one per owner), which hold at most `limit`
    entries together: past it, every key is rounded down to a multiple of 2**shift, shift growing by
    one until they fit (the compiled store's Tallies, dissector/accel/_bus.h, do the same). The result
    depends on the values only, not on their order: the smallest shift at which they all fit."""

    __slots__ = ("limit", "shift", "mask", "entries", "histograms")

    def __init__(self, limit: int | None = None) -> None:
        self.limit = MAX_TALLY if limit is None else limit
        self.shift = 0
        self.mask = -1  # keys & mask: rounded down to a multiple of 2**shift
        self.entries = 0
        self.histograms: list[dict[int, int]] = []

    def histogram(self) -> dict[int, int]:
        """A new owner's histogram, kept within the kind's limit."""
        histogram: dict[int, int] = {}
        self.histograms.append(histogram)
        return histogram

    def add(self, histogram: dict[int, int], key: int) -> None:
        key &= self.mask
        count = histogram.get(key)
        if count is not None:
            histogram[key] = count + 1
            return
        histogram[key] = 1
        self.entries += 1
        while self.limit and self.entries > self.limit and self.shift < MAX_SHIFT:
            self.shift += 1
            mask = self.mask = -(1 << self.shift)
            entries = 0
            for histogram in self.histograms:
                merged: dict[int, int] = {}
                for key, count in histogram.items():
                    key &= mask
                    merged[key] = merged.get(key, 0) + count
                histogram.clear()
                histogram.update(merged)
                entries += len(merged)
            self.entries = entries


def stamp(time: tuple[float, int | None] | None) -> float | None:
    """A time the compiled store gives back, (float, ns or None), as the Python stages had it."""
    if time is None:
        return None
    from dissector.model import Stamp

    return time[0] if time[1] is None else Stamp(time[1])


def new_store(wide: bool = False, tables: Callable[[int], bytes] | None = None) -> Any:
    """The compiled store when the extension is built (and VW3_PURE_PYTHON is not set); the Python one when
    `wide`, the run's maps having 32-bit rows: their values are word pairs, and the compiled store keeps a
    16-bit word a parameter (_stats.h Param.last), so --stats and --report are then counted by the Python
    stages (StatsCollector.engine_store: the engine counts only into a compiled store). `tables`: each
    slave's (slave_tables), which the compiled store asks for the transactions the engine counts."""
    if CompiledStore is not None and not wide and not os.environ.get("VW3_PURE_PYTHON"):
        return CompiledStore(MAX_KEYS, MAX_PARAMETERS, MAX_TALLY, TABLES, tables)
    return ParameterTable()
