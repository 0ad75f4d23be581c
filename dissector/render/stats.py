"""Capture statistics (`--stats`): traffic per slave and function, and what happened to each parameter.

`StatsCollector.add(item)` takes the decoded items in stream order; `report()` gives a JSON-ready dict
(`--stats --json`), `render()` rich tables and `render_plain()` plain ones. Memory stays bounded by the
number of distinct (slave, function) pairs and (slave, table, address) parameters: response times are kept
as a histogram of nanoseconds (exact for the micro- and nanosecond stamps of pcap and pcapng, and a few
thousand entries where a capture has millions of answers). All pairs' histograms hold at most
stats_store.MAX_TALLY entries together: past it (random times at 247 slaves, the max-size mix, filled
1.3 GB at 1 GB of pcap) their times are rounded down to multiples of 2**k ns (stats_store.Coarse).

Counting rules (the table headers say the same):
- A frame whose CRC/LRC fails counts only as a CRC error of the (slave, function) its bytes name: its
  contents cannot be trusted, so it is neither a request nor a response nor an exception.
- requests: good requests, broadcasts included; `broadcasts` counts those to slave 0. responses: normal
  answers; exceptions: exception answers, by code. unanswered: requests the pairing stage found no
  answer for (broadcasts expect none; a request the capture ends within its timeout of: not known, not
  counted). Response times: answers (normal or exception) paired with their
  request and both timed, but an answer stamped before its request (time going backwards: pairing.py's
  warning; the bus timing counts them).
- Per parameter (slave, address, and its code when a profile names it), by the rules of the parameter
  history (render/history.py, which --watch and --report read too): `reads` counts the values read
  (FC3/4/23 responses); `unreadable` the reads a profile marked protected or non-existent (16#8000 on
  the ATV71: a marker, not a value) and the parameters of an exception the profile explains as "every
  parameter read is non-existent or protected" (p.38); `writes` the values a master asked to write
  (FC6/16/23 requests), `refused` those whose request got an exception. `last` is the latest state
  seen on the wire: a value read or confirmed written (FC6 echo; FC16/23 values of a request confirmed
  by a normal answer; a broadcast write, which nothing confirms), or a read status (`last` null,
  `last_text` and `last_status` the status); `changes` counts when that state differs from the
  previous one (the lines --watch prints). Registers without an address (an answer whose request is
  not in the capture) are counted in `registers_without_address`, not attached to a parameter.
- A 32-bit map row is one parameter at its address, its `last` the word pair (high word first), its
  text the summary's; a word of one without the other in its frame is no value: counted in
  `half_values` only (render/history.py).
- p95 is the nearest-rank 95th percentile: the smallest time with at least 95 % of the times <= it.
"""
from __future__ import annotations

import json
import math
from bisect import bisect_left
from itertools import accumulate
from dataclasses import dataclass, field, replace
from collections.abc import Callable, Iterator
from typing import Any

from rich.console import RenderableType

from dissector.model import Frame, Item, Kind, Noise
from dissector.render import tables
from dissector.render.describe import count_text
from dissector.render.pollcycle import PollCycle, describe_key
from dissector.render import history as history_rules
from dissector.render.history import UNREADABLE_STATUSES, History
from dissector.render.stats_store import (
    COUNT_REQUESTS, COUNT_RESPONSES, COUNT_UNANSWERED, MAX_PARAMETERS, TABLE_NAMES, TALLY_COUNTS, TALLY_TIMES, Coarse,
    ParameterRow, give_back, parameter_rows, stamp, table_label, table_reader,
)
from dissector.render.tables import Cell, TableSpec
from dissector.protocol.spec import SPEC



@dataclass(slots=True)
class FunctionStats:
    requests: int = 0
    broadcasts: int = 0
    responses: int = 0
    exceptions: dict[int, int] = field(default_factory=dict)
    unanswered: int = 0
    crc_errors: int = 0
    times: dict[int, int] = field(default_factory=dict)  # response time in ns -> how many


PERCENTILE = 0.95  # p95: the nearest-rank percentile of the response times
PLAIN_READS = frozenset([3, 4])  # reads whose exception can mean "every parameter read is unreadable"


def exception_counts(exceptions: dict[Any, int]) -> str:
    """`02:769 07:1`: codes in hex as the manuals and the notes write them (exception 02), for every
    table of --stats and --report alike; JSON keeps the numbers."""
    parts = []
    for code, count in sorted(exceptions.items(), key=lambda pair: int(pair[0])):
        code = int(code)
        parts.append(f"{code:02X}:{count}" if code >= 0 else f"?:{count}")
    return " ".join(parts)


def percentile(sorted_values: list[float], fraction: float) -> float:
    """Nearest rank: the smallest value with at least `fraction` of the values <= it."""
    rank = max(1, math.ceil(fraction * len(sorted_values)))
    return sorted_values[rank - 1]


class StatsCollector:
    def __init__(self, profiles: Callable[[], list[Any]] | None = None, history: History | None = None) -> None:
        # Which slave got which device profile and why (the annotator's choices(): objects with
        # slave, profile, reason, frame), asked once at the end; None without an annotator that says.
        self.profiles = profiles
        self.functions: dict[tuple[int, int], FunctionStats] = {}  # the Python stages' frames
        self.times = Coarse()  # their response times' histograms, within MAX_TALLY entries together
        # The parameter history (render/history.py), shared with --watch and --report: per (slave,
        # address) the compiled store (C) or its Python twin, in stream order (stats_store).
        self.history = History() if history is None else history
        self.store = self.history.store
        self.frames = 0
        self.noise_items = 0
        self.noise_bytes = 0
        # Records captured in part (framing/stream.py _cut_part): bytes a snapshot length cut, not line noise.
        self.part_items = 0
        self.part_bytes = 0
        self.first_time: float | None = None
        self.last_time: float | None = None
        self.poll = PollCycle()
        self.bus: Any | None = None  # the BusTiming that went into the compiled store with the rest
        # The inputs' names when several were decoded: counted as one bus (as mergecap joins them), which
        # the header line and the JSON (`merged_captures`) say.
        self.captures: list[str] = []
        self.attached = False  # the times, the poll cycle and the bus are counted in the compiled store
        # Items were left out (-Y, -c N): the profiles of the slaves counted only, as tshark -z with a filter
        # (profile `auto` chose over the whole input; a slave filtered out has no other row either).
        self.filtered = False

    def engine_store(self, bus: Any | None = None) -> Any | None:
        """The compiled store, for the engine to count the transactions it shows itself (the compiled
        path of --stats), with the poll cycle, the first and last times, the response times and the
        bus timing `bus` (render/bustiming.py) kept there too, for the rest of the run: the Python
        stages' items go there as well, in stream order. None when the store is not compiled, or
        when what Python counted already cannot go there (requests in the poll cycle, a bus that
        heard items).

        The routing rule of --stats and --report (app/paths.py, accel/timedpath.py take the engine's
        path only with this store): the engine counts when the store is compiled, which it is not under
        VW3_PURE_PYTHON, nor when the run's maps have 32-bit rows (stats_store.new_store `wide`: a
        32-bit value is one parameter of a word pair, the compiled store keeps 16-bit words), so a map
        with 32-bit rows is counted by the Python stages, engine built or not."""
        if not hasattr(self.store, "poll"):
            return None
        if not self.attached:
            if not self.poll.empty or (bus is not None and not bus.fresh):
                return None
            self.poll = PollCycle(self.store)
            for time in (self.first_time, self.last_time):
                if time is not None:
                    self.store.stamp(time)
            for (slave, function), stats in self.functions.items():
                for key, count in stats.times.items():
                    for _ in range(count):
                        self.store.response(slave, function, key)
                stats.times.clear()
            if bus is not None:
                bus.attach(self.store)
            self.bus = bus
            self.attached = True
        elif bus is not self.bus:
            return None
        return self.store

    # -- collecting ---------------------------------------------------------------------------
    def _function(self, slave: int, function: int) -> FunctionStats:
        key = (slave, function)
        stats = self.functions.get(key)
        if stats is None:
            stats = self.functions[key] = FunctionStats(times=self.times.histogram())
        return stats

    def add(self, item: Item) -> None:
        if item.time is not None:
            if self.attached:
                self.store.stamp(item.time)
            elif self.first_time is None:
                self.first_time = item.time
            self.last_time = item.time
        if isinstance(item, Noise):
            if item.part is not None:
                self.part_items += 1
                self.part_bytes += item.length
            else:
                self.noise_items += 1
                self.noise_bytes += item.length
            return
        self.frames += 1
        stats = self._function(item.slave, item.function)
        if not item.crc_ok:
            stats.crc_errors += 1
            if item.kind is not Kind.REQUEST:
                self.poll.add_answer(item)  # (a damaged answer to its request: that cycle missed)
            return
        self.history.add(item)
        if item.kind is Kind.REQUEST:
            self._add_request(item, stats)
            return
        if item.kind is Kind.EXCEPTION:
            code = item.exception_code if item.exception_code is not None else -1
            stats.exceptions[code] = stats.exceptions.get(code, 0) + 1
            self.poll.add_answer(item)
        else:
            stats.responses += 1
        response_time = item.response_time
        if response_time is not None and response_time >= 0:
            key = round(response_time * 1e9)
            if self.attached:
                self.store.response(item.slave, item.function, key)  # beside the engine's (TALLY_TIMES)
            else:
                self.times.add(stats.times, key)

    def _add_request(self, frame: Frame, stats: FunctionStats) -> None:
        stats.requests += 1
        self.poll.add_request(frame)
        if frame.broadcast:
            stats.broadcasts += 1
        if frame.unanswered:
            stats.unanswered += 1

    # -- results ------------------------------------------------------------------------------
    def all_functions(self) -> dict[tuple[int, int], FunctionStats]:
        """Per (slave, function) the Python stages' counts plus the engine's (sums: the order of frames does
        not matter); the response times are the Python stages' or, attached, all of them the compiled store's
        (TALLY_TIMES). The engine counts only when attached, in the store's TALLY_COUNTS: per
        slave << 8 | function, exceptions by their code, requests, responses, unanswered by the COUNT_* keys."""
        merged = dict(self.functions)
        engine = self.store.tallies(TALLY_COUNTS) if self.attached else {}
        times = self.store.tallies(TALLY_TIMES) if self.attached else {}
        for owner in sorted(engine):  # (in order: the callers' sorts of the pairs then find them sorted)
            counts = engine[owner]
            slave, function = divmod(owner, 256)
            own = merged.get((slave, function))
            # (what the COUNT_* keys leave are the exception codes; every output sorts them)
            stats = FunctionStats(requests=counts.pop(COUNT_REQUESTS, 0), responses=counts.pop(COUNT_RESPONSES, 0),
                                  unanswered=counts.pop(COUNT_UNANSWERED, 0), exceptions=counts,
                                  times=times.pop(owner, {}))  # (every response time is in the store, both sides')
            if own is not None:
                stats.requests += own.requests
                stats.responses += own.responses
                stats.unanswered += own.unanswered
                stats.broadcasts, stats.crc_errors = own.broadcasts, own.crc_errors
                for code, count in own.exceptions.items():
                    stats.exceptions[code] = stats.exceptions.get(code, 0) + count
            merged[(slave, function)] = stats
        if self.attached:  # (pairs the Python stages alone counted)
            for (slave, function), stats in self.functions.items():
                if merged[(slave, function)] is stats:
                    merged[(slave, function)] = replace(stats, times=times.get(slave << 8 | function, {}))
        return merged

    def report(self, with_parameters: bool = True, poll_rows: int | None = None) -> dict[str, Any]:
        """The JSON form (--stats --json); without parameters for the tables, which show a few rows
        of the parameter rows instead of a dict per parameter, and the timings of `poll_rows` poll keys
        at most (those a table shows)."""
        give_back()
        functions = []
        counted = sorted(self.all_functions().items())
        for (slave, function), stats in counted:
            response_time = time_summary(stats.times)
            functions.append(
                {
                    "slave": slave,
                    "function": function,
                    "function_name": SPEC.function_name(function),
                    "requests": stats.requests,
                    "broadcasts": stats.broadcasts,
                    "responses": stats.responses,
                    "exceptions": {str(code): count for code, count in sorted(stats.exceptions.items())},
                    "unanswered": stats.unanswered,
                    "crc_errors": stats.crc_errors,
                    "response_time": response_time,
                }
            )
        parameters = list(self.parameter_dicts()) if with_parameters else None
        slaves = {slave for (slave, _function), _stats in counted}
        first_time, last_time = self.first_time, self.last_time
        if self.attached:
            state = self.store.bus_state()
            first_time, last_time = stamp(state["first_seen"]), stamp(state["last_seen"])
            if self.bus is not None:
                self.bus.take_back()
        return {
            "frames": self.frames + self.store.frames,
            "noise": {"items": self.noise_items, "bytes": self.noise_bytes},
            "captured_in_part": {"items": self.part_items, "bytes": self.part_bytes},
            "duration": None if first_time is None or last_time is None else last_time - first_time,
            "registers_without_address": self.history.registers_without_address,
            "half_values": self.history.half_values,
            # Parameters are kept up to MAX_PARAMETERS; the register events of further ones are counted.
            "parameter_limit": MAX_PARAMETERS,
            "parameter_events_dropped": self.store.dropped,
            "functions": functions,
            "parameters": parameters,
            "poll_cycle": self.poll.report(poll_rows),
            **({"merged_captures": list(self.captures)} if len(self.captures) > 1 else {}),
            # Slaves whose frames a stream counted before a choice made later (render/history.py MAX_HELD)
            **({"counted_before_choice": [{"slave": slave, "frame": frame} for slave, frame in
                                          sorted(self.history.late_choices.items())]}
               if self.history.late_choices else {}),
            "profiles": [
                {"slave": choice.slave, "profile": choice.profile, "reason": choice.reason, "frame": choice.frame,
                 **({"file": choice.source} if getattr(choice, "source", None) is not None else {})}
                for choice in (self.profiles() if self.profiles is not None else [])
                if not self.filtered or choice.slave in slaves
            ],
        }

    def parameter_dicts(self) -> Iterator[dict[str, Any]]:
        """The parameters of the JSON form, one at a time (write_json streams them)."""
        label = getattr(self.history.annotate, "label", None)
        for row in parameter_rows(self.store):
            slave, address, code, reads, unreadable, writes, refused, last, last_text, changes, table = row
            # --address-style plc: the address as the summary shows it, `label`
            shown = None if label is None else label(slave, table_reader(table), address)
            yield {
                "slave": slave,
                "address": address,
                "table": TABLE_NAMES[table],
                **({"label": shown} if shown is not None else {}),
                "code": code,
                "reads": reads,
                "unreadable": unreadable,
                "writes": writes,
                "refused": refused,
                "last": last,
                "last_text": last_text if last_text is not None or last is None else str(last),
                # The last state was a read status (then last is null and last_text the status).
                "last_status": last_text if last is None and last_text in UNREADABLE_STATUSES else None,
                "changes": changes,
            }

    def write_json(self, write: Callable[[str], object], extra: dict[str, Any] | None = None,
                   name: dict[str, Any] | None = None) -> None:
        """The JSON form (and `extra` keys; `name` keys first: the bus's `file`, render/buses.py) as one
        line, its parameters written in batches, never one string of them all (64 slaves' worth of
        parameters was a 643 MB line)."""
        report = {**(name or {}), **self.report(with_parameters=False)}
        report.update(extra or {})
        head, tail = json.dumps(report).split('"parameters": null', 1)
        write(head + '"parameters": [')
        batch: list[str] = []
        separator = ""
        for parameter in self.parameter_dicts():
            batch.append(json.dumps(parameter))
            if len(batch) == 1024:
                write(separator + ", ".join(batch))
                batch.clear()
                separator = ", "
        write((separator + ", ".join(batch) if batch else "") + "]" + tail + "\n")

    def blocks(self) -> list[str | TableSpec]:
        """The summary line and the tables, for the rich or the plain writer."""
        report = self.report(with_parameters=False, poll_rows=MAX_POLL_ROWS)  # (timings of the rows shown)
        blocks: list[str | TableSpec] = []
        summary = (
            f"{count_text(report['frames'], 'frame')}, {count_text(report['noise']['bytes'], 'noise byte')} in "
            f"{count_text(report['noise']['items'], 'run')}"
        )
        if report["captured_in_part"]["items"]:  # (not line noise: a snapshot length cut them, CRC unchecked)
            cut = report["captured_in_part"]
            summary += f", {count_text(cut['items'], 'record')} captured in part ({count_text(cut['bytes'], 'byte')})"
        if report["registers_without_address"]:
            without = count_text(report['registers_without_address'], 'register value')
            summary += f", {without} without an address"
        if report["half_values"]:
            half = count_text(report['half_values'], 'register value')
            summary += f", {half} one word of a 32-bit value without the other"
        if report["parameter_events_dropped"]:
            dropped = count_text(report['parameter_events_dropped'], 'register value')
            summary += (f", {dropped} of parameters beyond the first "
                        f"{MAX_PARAMETERS:,} not tracked")
        if len(self.captures) > 1:
            summary += f", from {merged_text(self.captures)}"
        blocks += [summary, ""]
        # (slave 0's requests are its broadcasts, said once in the caption: a `1 (1 broadcast)` cell widened
        # its column past the others' numbers)
        broadcasts = " (to slave 0: broadcasts)" if any(row["broadcasts"] for row in report["functions"]) else ""
        traffic = TableSpec(
            "Traffic per slave and function",
            ["slave", "function", "req", "resp", "exceptions", "no reply", "bad CRC"],
            [True, False, True, True, False, True, True],
            caption=f"req: requests{broadcasts}, resp: normal responses, exceptions: code:count (hex code)",
            squeeze={1: 28},  # keeps the table within 80 columns on a terminal
        )
        times = TableSpec(
            "Response times (ms)", ["slave", "function", "count", "min", "median", "p95", "max"],
            [True, False, True, True, True, True, True], squeeze={1: 28},
        )
        for row in report["functions"]:
            function = f"{row['function']} {row['function_name']}"
            exceptions = exception_counts(row["exceptions"])
            traffic.rows.append([
                str(row["slave"]), function, str(row["requests"]), str(row["responses"]),
                (exceptions, "vw3.exception") if exceptions else "",
                (str(row["unanswered"]), "vw3.warning") if row["unanswered"] else "0",
                (str(row["crc_errors"]), "vw3.crc.bad") if row["crc_errors"] else "0",
            ])
            timing = row["response_time"]
            if timing is not None:
                times.rows.append([str(row["slave"]), function, str(timing["count"]),
                                   *(_ms(timing[key]) for key in ("min", "median", "p95", "max"))])
        if report["profiles"]:
            late = report.get("counted_before_choice")
            caption = None if not late else "; ".join(
                f"slave {row['slave']}: its frames before #{row['frame']} counted as named then, not with this choice"
                for row in late) + (f" (read once, the history holds {history_rules.MAX_HELD:,} frames at most "
                                    "for a choice, none with --watch): the file's counts may differ")
            profiles = TableSpec("Device profiles", ["slave", "profile", "why"], [True, False, False], caption=caption)
            for choice in report["profiles"]:  # (a reason names the frame that decided it: said once)
                profiles.rows.append([str(choice["slave"]), choice["profile"], choice["reason"]])
            blocks += [profiles, ""]
        blocks += [traffic, "", times, ""]
        if report["poll_cycle"]:
            blocks += [_poll_table(report["poll_cycle"], self.poll_addresses), ""]
        blocks.append(_parameter_table(self.store, self.parameter_address))
        return blocks

    def parameter_address(self, slave: int, address: int, table: int, last: int | None = None) -> str:
        """A parameter's address (`last`: to that one, a run's) as the summary shows it: PLC style, the
        references of its table (40001, 30001: devices.naming's plc_label through the annotator); else the
        address, an input register's marked `input` (holding registers, most parameters, stay bare)."""
        label = getattr(self.history.annotate, "label", None)
        function = table_reader(table)
        if label is not None and label(slave, function, address) is not None:
            return label(slave, function, address) + ("" if last is None else f"..{label(slave, function, last)}")
        text = str(address) if last is None else f"{address}..{last}"
        return table_label(None, table, text) or text

    def poll_addresses(self, row: dict[str, Any]) -> str:
        """A poll key's addresses as the summary shows them (PLC style: 40001..40016 (16))."""
        label = getattr(self.history.annotate, "label", None)
        start = row.get("start")
        if label is None or start is None or label(row["slave"], row["function"], start) is None:
            return describe_key(row)

        def span(first: int, quantity: int | None) -> str:
            text = label(row["slave"], row["function"], first)
            if quantity is None or quantity == 1:
                return text
            if quantity == 0:
                return f"{text} (0)"  # no register: what the request says, nothing wrapped
            return f"{text}..{label(row['slave'], row['function'], first + quantity - 1)} ({quantity})"

        text = span(start, row.get("quantity"))
        if row.get("write_start") is not None:
            return f"read {text}, write {span(row['write_start'], row['write_quantity'])}"
        return text

    def render(self) -> RenderableType:
        """For a terminal: rich tables, each within 80 columns."""
        return tables.rich(self.blocks())

    def render_plain(self) -> str:
        """For a pipe or a file: the same tables as plain text, full width."""
        return tables.plain(self.blocks())


def merged_text(captures: list[str]) -> str:
    """What --stats says of several inputs: one bus, as mergecap would join them (tshark reads one file)."""
    from dissector.protocol.printable import printable

    names = ", ".join(printable(name) for name in captures[:5]) + (f", ... (+{len(captures) - 5})" if len(captures) > 5 else "")
    return (f"{len(captures)} captures counted as one bus, as mergecap would join them (decode each alone "
            f"for its own traffic and timing): {names}")


GROUP_MIN = 3  # neighbouring addresses with the same story shown as one row from this many on
MAX_PARAMETER_ROWS = 60
MAX_POLL_ROWS = 60


def _poll_table(rows: list[dict[str, Any]], addresses: Callable[[dict[str, Any]], str] = describe_key) -> TableSpec:
    table = TableSpec(
        "Poll cycle (requests repeated 3 times or more)",
        ["slave", "function", "addresses", "count", "period", "jitter", "misses"],
        [True, False, False, True, True, True, True],
        caption="period: median interval (ms); jitter: largest deviation from it (ms); misses: cycles "
        "skipped (intervals of 1.5 periods or more) + requests without a normal answer",
        squeeze={1: 28, 2: 24},
    )
    for row in rows[:MAX_POLL_ROWS]:
        misses = str(row["misses"])
        table.rows.append([
            str(row["slave"]), f"{row['function']} {SPEC.function_name(row['function'])}", addresses(row),
            str(row["count"]),
            "-" if row["period"] is None else _ms(row["period"]),
            "-" if row["jitter"] is None else _ms(row["jitter"]),
            (misses, "vw3.warning") if row["misses"] else misses,
        ])
    if len(rows) > MAX_POLL_ROWS:
        table.rows.append(["", f"... (+{len(rows) - MAX_POLL_ROWS} more)", "", "", "", "", ""])
    return table


def _parameter_table(store: Any, address_text: Callable[..., str]) -> TableSpec:
    """One row per parameter, or per range of neighbouring addresses with the same story (same counts,
    all named or all unnamed); capped at MAX_PARAMETER_ROWS rows, then a total of them all: the runs
    are found by the store (stats_store.ParameterTable.table, or the compiled one's), which makes rows
    of the parameters shown only."""
    table = TableSpec(
        "Parameters",
        ["slave", "address", "code", "reads", "unreadable", "writes", "refused", "last", "changes"],
        [True, True, False, True, True, True, True, False, True],
        squeeze={7: 24},  # long enumeration texts and bit lists are cut on a terminal only
    )
    pieces, expanded, count, (reads, unreadable, writes, refused, changes) = store.table(MAX_PARAMETER_ROWS, GROUP_MIN)
    shown = len(pieces)
    table.rows.extend(_parameter_row(members, address_text) for members in pieces)
    if expanded > shown:
        table.rows.append(["", f"... (+{expanded - shown} more rows)", "", "", "", "", "", "", ""])
    if count > 1:
        table.rows.append(["all", f"{count} params", "", str(reads), str(unreadable), str(writes), str(refused), "",
                           str(changes)])
    return table


def _parameter_row(members: list[ParameterRow], address_text: Callable[..., str]) -> list[Cell]:
    """`address_text(slave, address, table, last=None)`: StatsCollector.parameter_address."""
    first, last = members[0], members[-1]
    if len(members) == 1:
        address, code = address_text(first[0], first[1], first[10]), first[2] or ""
    else:
        address = f"{address_text(first[0], first[1], first[10], last[1])} ({len(members)})"
        code = f"{first[2]}..{last[2]}" if first[2] else ""
    texts = {row[8] if row[8] is not None or row[7] is None else str(row[7]) for row in members}
    last_value = texts.pop() if len(texts) == 1 else "(various)"
    return [str(first[0]), address, code, *(str(value) for value in first[3:7]), last_value or "", str(first[9])]


def time_summary(times: dict[int, int]) -> dict[str, float | int] | None:
    """count, min, median, p95 (nearest rank) and max, in seconds, of a histogram of ns."""
    if not times:
        return None
    values = sorted(times)
    seen = list(accumulate(times[value] for value in values))  # how many are at most each value
    count = seen[-1]

    def nth(rank: int) -> int:  # the rank-th smallest time (1-based)
        return values[bisect_left(seen, rank)]

    half = count // 2
    median = nth(half + 1) if count % 2 else (nth(half) + nth(half + 1)) / 2
    return {
        "count": count,
        "min": values[0] / 1e9,
        "median": median / 1e9,
        "p95": nth(max(1, math.ceil(PERCENTILE * count))) / 1e9,
        "max": values[-1] / 1e9,
    }


def _ms(seconds: float) -> str:
    return f"{seconds * 1000:.1f}"

