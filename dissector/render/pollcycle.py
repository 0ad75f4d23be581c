"""The poll cycle: each request a master repeats (same slave, function and addresses), its period,
jitter and misses. Shared by `--stats` and `--report`.

A request's key is its bytes without the check (the same slave, function, addresses and, for a
write, the same values would be too strict: a PLC writes a changing setpoint in a fixed slot), so
the key is (slave, function, start, quantity) and for FC23 the write window too; FC8's its sub-function;
FC43's its MEI type, and for Read Device Identification (14) its read device id code and object id (a
basic and an extended identification are two polls). Only good requests count; broadcasts are cycles
as well.

Rules (the table captions say the same):
- period: the median interval between consecutive occurrences (timestamps needed);
- an interval of 1.5 periods or more skipped cycles: round(interval / period) - 1 of them;
- jitter: the largest deviation from the period of the intervals that skipped nothing, and its
  standard deviation (JSON);
- misses: skipped cycles plus occurrences that got no normal answer (unanswered, exception, bad CRC).
An interval that goes back in time (a clock step, records out of order) is left out.
Intervals are kept as a histogram of 100 us steps, so memory does not grow with the capture (a PLC
polls at a few distinct intervals; the keys' histograms hold MAX_TALLY entries together at most, then
their steps are rounded down to multiples of 2**k: stats_store.Coarse); keys beyond MAX_KEYS are
counted, not followed.
Several files read as one bus number their frames each from 1: the rows are in the order of time, by
file (the keys are made in the stream's order: how many there were as each file began says its file)
then first frame.
"""
from __future__ import annotations

import math
from bisect import bisect_left, bisect_right
from itertools import accumulate
from dataclasses import dataclass, field
from typing import Any

from dissector.model import Frame
from dissector.protocol.table import DEVICE_ID, FUNCTIONS, write_windows
from dissector.render.describe import device_id_request_text, mei_name, plain_span, subfunction_text
from dissector.render.stats_store import MAX_KEYS, TALLY_INTERVALS, Coarse

_WRITE_WINDOWS = write_windows()  # requests that write a window of their own (FC23): part of the key
_MEI = frozenset(entry.code for entry in FUNCTIONS if entry.text == "mei")  # (FC43: keyed by what it reads)

MIN_REPEATS = 3  # fewer occurrences are not a cycle
STEP = 1e-4  # interval histogram resolution: 100 us (a few thousand entries at most)
SKIP_FACTOR = 1.5

Key = tuple[int, ...]


@dataclass(slots=True)
class _Poll:
    first_number: int
    count: int = 0
    last_time: float | None = None
    failed: int = 0  # occurrences without a normal answer
    intervals: dict[int, int] = field(default_factory=dict)  # interval in STEP units -> count


class PollCycle:
    def __init__(self, store: Any | None = None) -> None:
        # The compiled store (_summary.Stats) when the compiled path counts: keys, counts, misses and
        # intervals are kept there, where the engine counts the requests it shows itself.
        self.store = store
        self._polls: dict[Key, _Poll] = {}
        self._intervals = Coarse()  # the keys' interval histograms, within MAX_TALLY entries together
        self.untracked = 0  # requests of keys beyond MAX_KEYS
        self._inputs: list[int] = []  # the keys made as each file began (new_input)

    @property
    def empty(self) -> bool:
        return not self._polls and not self.untracked

    def new_input(self) -> None:
        """A file begins (BusTiming.new_input): the keys made from here on are its."""
        self._inputs.append(len(self.store.polls()) if self.store is not None else len(self._polls))

    def add_request(self, frame: Frame) -> None:
        """A good request (CRC ok); its pairing (unanswered) must be final, as the sinks see it."""
        key = request_key(frame)
        if self.store is not None:
            self.store.poll(key, frame.number, frame.unanswered, frame.time)
            return
        poll = self._polls.get(key)
        if poll is None:
            if len(self._polls) >= MAX_KEYS:
                self.untracked += 1
                return
            poll = self._polls[key] = _Poll(frame.number, intervals=self._intervals.histogram())
        poll.count += 1
        if frame.unanswered:
            poll.failed += 1
        time = frame.time
        if time is not None:
            if poll.last_time is not None:
                interval = time - poll.last_time
                if interval >= 0:  # (time going backwards: none)
                    self._intervals.add(poll.intervals, round(interval / STEP))
            poll.last_time = time

    def add_answer(self, frame: Frame) -> None:
        """An exception (or a damaged answer) to a request: that cycle missed."""
        request = frame.request
        if request is None or not request.crc_ok:
            return
        if self.store is not None:
            self.store.poll_fail(request_key(request))
            return
        poll = self._polls.get(request_key(request))
        if poll is not None:
            poll.failed += 1

    def report(self, timed_rows: int | None = None) -> list[dict[str, Any]]:
        """Rows of the keys repeated MIN_REPEATS times or more, by first frame; `timed_rows`: only the
        first that many get their period, jitter and skipped cycles (a table shows no more)."""
        rows = []
        polls: list[tuple[Key, _Poll]] = list(self._polls.items())
        if self.store is not None:  # (its intervals are tallies: the same _timing works them out)
            intervals = self.store.tallies(TALLY_INTERVALS) if timed_rows != 0 else {}
            polls = [(key, _Poll(first, count, None, failed, intervals.get(order, {})))
                     for order, (key, first, count, failed) in enumerate(self.store.polls())]
        inputs = self._inputs  # (by file, then first frame: each file numbers its frames from 1)
        ordered = sorted(enumerate(polls),
                         key=lambda entry: (bisect_right(inputs, entry[0]), entry[1][1].first_number))
        for _order, (key, poll) in ordered:
            if poll.count < MIN_REPEATS:
                continue
            mei = key[1] in _MEI and len(key) > 2  # (its MEI type, read code, object id: no addresses)
            diagnostic = len(key) == 3 and not mei  # (FC8's sub-function: no address either)
            window = () if mei or diagnostic else key
            row: dict[str, Any] = {
                "slave": key[0],
                "function": key[1],
                "start": window[2] if len(window) > 2 else None,
                "quantity": window[3] if len(window) > 3 else None,
                "write_start": window[4] if len(window) > 4 else None,
                "write_quantity": window[5] if len(window) > 5 else None,
                "count": poll.count,
                "no_answer": poll.failed,
                "period": None,
                "jitter": None,
                "jitter_sd": None,
                "skipped": 0,
            }
            if mei:
                row.update(zip(("mei_type", "read_code", "object_id"), key[2:]))
            if diagnostic:
                row["subfunction"] = key[2]
            if timed_rows is None or len(rows) < timed_rows:
                row.update(_timing(poll.intervals))
            row["misses"] = row["skipped"] + poll.failed
            rows.append(row)
        return rows


def request_key(frame: Frame) -> Key:
    window = _WRITE_WINDOWS.get(frame.function)
    if window is not None:
        try:
            fields = frame.fields
            return (frame.slave, frame.function, frame.start, frame.quantity, fields[window[0]], fields[window[1]])
        except (KeyError, TypeError):
            pass
    if frame.start is not None:
        return (frame.slave, frame.function, frame.start, frame.quantity if frame.quantity is not None else 1)
    if frame.subfunction is not None:
        return (frame.slave, frame.function, frame.subfunction)
    if frame.function in _MEI and frame.fields is not None:
        fields = frame.fields
        if fields.mei_type == DEVICE_ID:
            return (frame.slave, frame.function, DEVICE_ID, fields.body.read_code, fields.body.object_id)
        return (frame.slave, frame.function, fields.mei_type)
    return (frame.slave, frame.function)


def _timing(intervals: dict[int, int]) -> dict[str, Any]:
    if not intervals:
        return {}
    steps = sorted(intervals)
    seen = list(accumulate(intervals[step] for step in steps))  # how many are at most each step
    # The median interval: with skipped cycles a minority, it is the cycle.
    median = steps[bisect_left(seen, (seen[-1] + 1) // 2)]
    if median <= 0:
        return {"period": 0.0}
    cut = bisect_left(steps, SKIP_FACTOR * median)  # (from there on, skipped cycles)
    kept = steps[:cut]
    variance = sum((step - median) ** 2 * intervals[step] for step in kept) / seen[cut - 1]
    return {
        "period": median * STEP,
        "jitter": max(abs(kept[0] - median), abs(kept[-1] - median)) * STEP,
        "jitter_sd": math.sqrt(variance) * STEP,
        "skipped": sum((round(step / median) - 1) * intervals[step] for step in steps[cut:]),
    }


def describe_key(row: dict[str, Any]) -> str:
    """`3102..3105 (4)`, `read 3201..3202, write 8501..8502`, or '' for a request without addresses."""
    start, quantity = row.get("start"), row.get("quantity")
    if row.get("read_code") is not None:  # (FC43/14: what it reads, as its summary says it)
        return device_id_request_text(row["read_code"], row["object_id"])
    if row.get("mei_type") is not None:
        return mei_name(row["mei_type"])
    if row.get("subfunction") is not None:  # (as the summary names it: `0Bh Return Bus Message Count`)
        return subfunction_text(row["subfunction"])
    if start is None:
        return ""
    text = _span(start, quantity)
    if row.get("write_start") is not None:
        return f"read {text}, write {_span(row['write_start'], row['write_quantity'])}"
    return text


_span = plain_span
