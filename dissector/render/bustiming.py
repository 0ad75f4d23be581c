"""Bus timing and slave health from a time-stamped capture: what an RS-485 troubleshooter measures.

Times are those of each item's first byte (pcap records, hex-dump lines, live reads); an item ends when
its last byte has been sent, `length x character time` later (11 bits a character in RTU, 10 in ASCII, or
what the pcapng interface description says: `19200 8N2`), or later where its last byte came later: a frame
with silences inside it ends at the time of the record (run of bytes with one time) holding its last byte
plus that byte's place in it (model.sent_in; a slow line's frames come in pieces a few characters apart).
The load counts its characters only. From there:
- load: the fraction of the time the line carries characters (frames and noise), overall and per
  minute of the capture (the last minute over the time it covers);
- inter-frame gaps: the silence between the end of one item and the start of the next, as a
  histogram, with the gaps shorter than t3.5 counted (the Serial Line Guide's frame separator:
  3.5 character times up to 19200 baud, 1.75 ms above); a negative gap is a timestamp earlier than
  the previous item's end (an adapter that stamps bursts) and counts as below t3.5 (a wrong --baud is
  said when items overlap, not counting an item stamped at the time of the one before: a later part of
  its record, whose start the stamp does not give). t3.5 is an RTU
  rule: a Modbus ASCII frame runs from ':' to CR LF (Serial Line Guide 2.5.2), so no silence
  separates ASCII frames and their gaps are not judged (`t35`, `gaps_below_t35` null when every
  capture of the bus is ASCII); the ASCII rule, up to 1 s between a frame's characters, is
  framing/timing.py's check, a warning on the frame;
- master turnaround: from the end of an answer (response or exception) to the start of the next
  request: median, p95, max;
- response times per slave against `--timeout`: the margin is timeout - the longest wait, and a response
  is close to it past 90% of it, where the wait is counted from when the request was sent (its first byte's
  time and its length at this speed, as pairing.py's timeout rule: a master starts its timeout then); the
  response time shown is first byte to first byte (tshark's time since request);
- outages: two or more consecutive requests to a slave left unanswered (broadcasts expect nothing,
  nor does a request the spec's server never answers, FC8 04 Force Listen Only Mode, unless an
  exception answered it: such a request is neither one of them nor ends them), from the first such
  request to the last, with their count and frames.
Time going backwards (a pcap whose records go back, a clock step; the summary shows those times as
they are) is left out of the figures, never averaged in: an item stamped before the item before it
has no gap and no turnaround and starts a new stretch of time (the load is the busy time over the
stretches' spans added up), and a response stamped before its request (pairing.py's warning) has no
response time here, nor in --stats' response times; `backwards` counts both.
Percentiles are nearest-rank (the median of an even count the mean of the middle two, as --stats)
over 10 us buckets, so memory does not grow with the capture (a kind of them, gaps, turnarounds or
the response times of every slave, holds MAX_TALLY buckets at most: past it they are 2**k times wider,
stats_store.Coarse).
An input without timestamps has no timing: its `bus` says `timed: false`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

from dissector.framing.timing import DEFAULT_BAUD, LineTiming, mode_bits
from dissector.model import Item, Kind, sent_in, stamped_before
from dissector.protocol.rules import awaits_answer
from dissector.framing.linespeed import LineSettings
from dissector.render.describe import count_text
from dissector.render.outages import Outage, Run, frames_cited
from dissector.render.stats_store import Coarse

RESOLUTION = 1e-5  # percentile buckets: 10 us


def _awaits_nothing(frame: Any) -> bool:
    """A request no answer is expected of: a broadcast, or one the spec's server never answers ([pairing]
    never_answered: FC8 04) that no exception answered. Its silence is no outage, nor does it end one."""
    return frame.kind is Kind.REQUEST and (
        frame.broadcast or (not awaits_answer(frame) and frame.response is None)
    )
GAP_EDGES_MS = (1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0)
MINUTE = 60.0
# Serial Line Guide 2.5.2: ':' starts an ASCII frame, CR LF ends it; up to 1 s between its characters.
ASCII_FRAMING = ("Modbus ASCII, ':' to CR LF: no silence separates frames, so t3.5 and t1.5 (RTU rules) "
                 "are not applied and the line speed only times the characters (load, gaps); a frame's "
                 "characters may be up to 1 s apart (a longer silence is warned on its frame)")
MIXED_FRAMING = "RTU and Modbus ASCII captures: gaps below t3.5 counted in the RTU captures only"
CLOSE_MARGIN = 0.9  # a response slower than this part of the timeout is close to it
# Why an input has no timing: its items have no times (a raw .bin), or it has no item at all (a pcap whose
# records are all empty, or that has none: times of nothing on the line are no timing either).
UNTIMED = "no timestamps in this input: load, gaps, turnaround and outages need a pcap, pcapng or timed dump"
UNHEARD = "no bytes in this input (no frame, no noise): no load, gaps, turnaround or outages to measure"


class Quantiles:
    """Counts in RESOLUTION buckets; nearest-rank percentiles, exact min and max. `coarse`: the kind of
    histogram they are (the response times of every slave are one), within MAX_TALLY entries."""

    __slots__ = ("buckets", "count", "low", "high", "coarse")

    def __init__(self, coarse: Coarse | None = None) -> None:
        self.coarse = Coarse() if coarse is None else coarse
        self.buckets: dict[int, int] = self.coarse.histogram()
        self.count = 0
        self.low = math.inf
        self.high = -math.inf

    def add(self, value: float) -> None:
        self.coarse.add(self.buckets, round(value / RESOLUTION))
        self.count += 1
        if value < self.low:
            self.low = value
        if value > self.high:
            self.high = value

    def _nth(self, rank: int) -> float:
        seen = 0
        for key in sorted(self.buckets):
            seen += self.buckets[key]
            if seen >= rank:
                return min(max(key * RESOLUTION, self.low), self.high)
        return self.high

    def percentile(self, fraction: float) -> float | None:
        if not self.count:
            return None
        return self._nth(max(1, math.ceil(fraction * self.count)))

    def median(self) -> float | None:
        """The middle value, or the mean of the middle two (as --stats' response times)."""
        count = self.count
        if not count:
            return None
        half = count // 2
        return self._nth(half + 1) if count % 2 else (self._nth(half) + self._nth(half + 1)) / 2

    def summary(self) -> dict[str, float] | None:
        if not self.count:
            return None
        return {
            "count": self.count,
            "min": _round(self.low),
            "median": _round(self.median()),  # type: ignore[arg-type]
            "p95": _round(self.percentile(0.95)),  # type: ignore[arg-type]
            "max": _round(self.high),
        }


def _round(seconds: float) -> float:
    return round(seconds, 6)


def _quantiles(low: float, high: float, buckets: dict[int, int] | None) -> Quantiles:
    """The compiled store's Quantiles: its min and max, and its buckets (tallies), whose sum is the count."""
    quantiles = Quantiles()
    quantiles.low, quantiles.high = low, high
    quantiles.buckets = buckets or {}
    quantiles.count = sum(quantiles.buckets.values())
    return quantiles


# The engine's numbers for the kinds of frame (codegen/c_rules.py generates _tables.h's KIND_* from them).
_KINDS = {Kind.REQUEST: 1, Kind.RESPONSE: 2, Kind.EXCEPTION: 3}


class Backwards:
    """Time going backwards, as BusTiming.add meets it: the items stamped before the item before them and
    the responses stamped before their request (counted only in BusTiming: their response time goes
    nowhere, the compiled store included); the time of the item before; where the items' stretch of
    forward time starts (the first item's, else the last step back's), its latest end so far, and the
    spans of the stretches before it. (One field of BusTiming: a dataclass field costs its import.)"""

    __slots__ = ("items", "responses", "previous", "stretch", "reach", "spanned")

    def __init__(self) -> None:
        self.items = self.responses = 0
        self.previous: float | None = None
        self.stretch: float | None = None
        self.reach = self.spanned = 0.0


@dataclass(slots=True)
class BusTiming:
    timeout: float = 1.0
    settings: LineSettings = field(default_factory=lambda: LineSettings(DEFAULT_BAUD))
    mode: str = "rtu"
    timed: bool = False
    untimed_items: int = 0
    first: float | None = None
    last_end: float | None = None
    busy: float = 0.0  # seconds of characters on the line
    minutes: dict[int, float] = field(default_factory=dict)  # minute index -> busy seconds
    gaps: Quantiles = field(default_factory=Quantiles)
    gap_histogram: list[int] = field(default_factory=lambda: [0] * (len(GAP_EDGES_MS) + 1))
    gaps_below_t35: int = 0
    # Negative gaps of an item stamped at the very time of the item before it: a later part of the same
    # record, read or dump line (its stamp is its first byte's), whose own start is unknown. They say
    # nothing of the line speed, so overlap_warning leaves them out (a tap's glitch byte after each frame).
    same_stamp_overlaps: int = 0
    turnaround: Quantiles = field(default_factory=Quantiles)
    responses: dict[int, Quantiles] = field(default_factory=dict)
    _response_tally: Coarse = field(default_factory=Coarse)  # the histograms of all of `responses`
    close_to_timeout: dict[int, int] = field(default_factory=dict)  # responses later than 90% of it
    waits: dict[int, float] = field(default_factory=dict)  # per slave the longest wait after a request was sent
    # The seconds the last request took to send: an answer follows its request (the pairing's order), so
    # this is its request's, the engine's too (_bus.h `sent`: its items come in the stream's order).
    _sent: float = 0.0
    outages: list[Outage] = field(default_factory=list)
    _runs: dict[int, Run] = field(default_factory=dict)
    _answer_end: float | None = None  # end of the last item when it was an answer
    backwards: Backwards = field(default_factory=Backwards)  # time going backwards
    # The compiled store (_summary.Stats, dissector/accel/_bus.h) that keeps all of the above while the
    # engine counts --stats (StatsCollector.engine_store): items go there, take_back() brings it here.
    store: Any = None
    inputs: int = 0  # files decoded (new_input): several are one bus, as mergecap joins them
    titles: list[str] = field(default_factory=list)  # their names, as new_input has them
    _input_base: int = 0  # the input the compiled store's count of them starts at (attach)
    modes: set[str] = field(default_factory=set)  # the framing of each (new_input): t3.5 judges RTU gaps only
    # Told once, at the end, of a line speed at which the items overlap (overlap_warning; a wrong --baud).
    warn: Callable[[str], object] | None = None

    def new_input(self, mode: str, settings: LineSettings | None = None, title: str | None = None,
                  stats: Any = None) -> None:
        """A new file: its gaps do not continue the previous file's (one capture's ring files do).
        `title`: its name when several are decoded, kept in `stats.captures` too (--stats' header)."""
        self.mode = mode
        self.inputs += 1
        self.modes.add(mode)
        if title is not None:
            self.titles.append(title)
        if title is not None and stats is not None:
            stats.captures.append(title)
        if stats is not None:  # (the poll cycle orders its rows by file too)
            stats.poll.new_input()
        if settings is not None:
            self.settings = settings
        self.last_end = None
        self._answer_end = None
        if self.store is not None:
            self.store.bus_line(self.char_time, self._gap_floor, self.timeout, True)

    @property
    def fresh(self) -> bool:
        """Nothing heard yet (the compiled store can take over)."""
        return self.store is None and not self.timed and not self.untimed_items and self.last_end is None

    def attach(self, store: Any) -> None:
        self.store = store
        self._input_base = self.inputs - 1  # (its count of inputs starts at 0 here: -1 before any)
        store.bus_line(self.char_time, self._gap_floor, self.timeout, False)

    def take_back(self) -> None:
        """The compiled store's state, here (once the items are all heard)."""
        from dissector.render.stats_store import (
            TALLY_GAPS, TALLY_MINUTES, TALLY_RESPONSES, TALLY_TURNAROUND, stamp,
        )

        store, self.store = self.store, None
        if store is None:
            return
        state = store.bus_state()
        self.timed, self.untimed_items, self.busy = state["timed"], state["untimed"], state["busy"]
        self.first, self.last_end, self._answer_end = stamp(state["first"]), state["last_end"], state["answer_end"]
        back = self.backwards
        back.items, back.previous, back.stretch = state["backwards"], stamp(state["previous"]), stamp(state["stretch"])
        back.reach, back.spanned = state["reach"], state["spanned"]
        self.gaps_below_t35, self.gap_histogram = state["below_t35"], state["histogram"]
        self.same_stamp_overlaps = state["same_stamp_overlaps"]
        self.gaps = _quantiles(*state["gaps"], store.tallies(TALLY_GAPS).get(0))
        self.turnaround = _quantiles(*state["turnaround"], store.tallies(TALLY_TURNAROUND).get(0))
        buckets = store.tallies(TALLY_RESPONSES)
        self.responses = {slave: _quantiles(low, high, buckets.get(slave))
                          for slave, low, high, _close, _wait in state["responses"]}
        self.close_to_timeout = {slave: close for slave, _l, _h, close, _w in state["responses"] if close}
        self.waits = {slave: wait for slave, _l, _h, _c, wait in state["responses"]}
        base = self._input_base
        self._runs = {slave: Run(stamp(start), stamp(end), requests, first, last, offset, base + one,
                                  base + other)
                      for slave, start, end, requests, first, last, offset, one, other in state["runs"]}
        self.outages = [Outage(slave, stamp(start), stamp(end), requests, first, last, offset, base + one,
                               base + other)
                        for slave, start, end, requests, first, last, offset, one, other in state["outages"]]
        self.minutes = store.tallies(TALLY_MINUTES).get(0, {})

    @property
    def char_time(self) -> float:
        return self.settings.char_bits(self.mode) / self.settings.baud

    @property
    def t35(self) -> float:
        return LineTiming(self.settings.baud, "rtu").t35

    @property
    def _gap_floor(self) -> float:
        """The gap below which the capture at hand's gaps are counted: t3.5 in RTU, none in ASCII."""
        return -math.inf if self.mode == "ascii" else self.t35

    @property
    def framings(self) -> str:
        """`rtu`, `ascii`, or `mixed` (RTU and ASCII captures counted as one bus), from the captures decoded."""
        modes = self.modes or {self.mode}
        return "mixed" if len(modes) > 1 else "ascii" if modes == {"ascii"} else "rtu"

    def add_items(self, items: list[Item]) -> None:
        for item in items:
            self.add(item)

    def add(self, item: Item) -> None:
        time = item.time
        if self.store is not None:
            sent = sent_in(item, self.char_time)
            if item.kind is Kind.NOISE:
                self.store.bus_item(time, item.length, sent, 0, 0, False, False, False, None, item.number,
                                    item.offset)
            else:
                frame: Any = item
                response_time = frame.response_time
                if response_time is not None and response_time < 0:
                    response_time = self._backwards(frame)
                # (a request that awaits nothing goes as a broadcast: the store's bus_add skips its outage run)
                self.store.bus_item(time, frame.length, sent, _KINDS[frame.kind], frame.slave, _awaits_nothing(frame),
                                    frame.unanswered, frame.crc_ok, response_time, frame.number, frame.offset)
            return
        if time is None:
            self.untimed_items += 1
            return
        self.timed = True
        duration = item.length * self.char_time
        sent = sent_in(item, self.char_time)
        end = time + sent
        back = self.backwards
        previous = back.previous
        same_stamp = previous is not None and time - previous == 0  # (Stamps subtract exactly, as _bus.h)
        if self.first is None:
            self.first = back.stretch = time
            back.reach = end
        elif time <= previous and stamped_before(time, previous):  # type: ignore[operator]  # (the call only then)
            back.items += 1  # time goes backwards: a new stretch
            back.spanned += back.reach - back.stretch  # type: ignore[operator]
            back.stretch, back.reach = time, end
            self.last_end = self._answer_end = None  # no gap, no turnaround to it
        elif end > back.reach:
            back.reach = end
        back.previous = time
        self.busy += duration
        minute = int((time - self.first) // MINUTE)
        self.minutes[minute] = self.minutes.get(minute, 0.0) + duration
        previous = self.last_end
        if previous is not None:
            gap = time - previous
            self.gaps.add(gap)
            if gap < self._gap_floor:
                self.gaps_below_t35 += 1
            if same_stamp and round(gap / RESOLUTION) < 0:  # (a negative bucket: overlaps() counts it)
                self.same_stamp_overlaps += 1
            milliseconds = gap * 1000
            index = 0
            while index < len(GAP_EDGES_MS) and milliseconds >= GAP_EDGES_MS[index]:
                index += 1
            self.gap_histogram[index] += 1
        self.last_end = end if previous is None or end > previous else previous
        kind = item.kind
        if kind is Kind.NOISE:
            return
        frame = item
        if kind is Kind.REQUEST:
            self._sent = sent
            if self._answer_end is not None:
                self.turnaround.add(time - self._answer_end)
            self._answer_end = None
            if not _awaits_nothing(frame):
                self._request(frame, time)
            return
        self._answer_end = end
        response_time = frame.response_time  # type: ignore[union-attr]
        if response_time is not None and response_time < 0:
            response_time = self._backwards(frame)
        if response_time is not None and frame.crc_ok:  # type: ignore[union-attr]  # as --stats counts them
            slave = frame.slave  # type: ignore[union-attr]
            quantiles = self.responses.get(slave)
            if quantiles is None:
                quantiles = self.responses[slave] = Quantiles(self._response_tally)
            quantiles.add(response_time)
            wait = response_time - self._sent  # (as pairing.py _late subtracts)
            if slave not in self.waits or wait > self.waits[slave]:
                self.waits[slave] = wait
            if wait > CLOSE_MARGIN * self.timeout:
                self.close_to_timeout[slave] = self.close_to_timeout.get(slave, 0) + 1

    def _backwards(self, frame: Any) -> None:
        """A response stamped before its request: counted (as --stats counts answers: CRC ok), no time."""
        if frame.crc_ok:
            self.backwards.responses += 1
        return None

    def _request(self, frame: Any, time: float) -> None:
        slave = frame.slave
        run = self._runs.get(slave)
        if frame.unanswered:
            here = self.inputs - 1
            if run is None:
                self._runs[slave] = Run(time, time, 1, frame.number, frame.number, frame.offset, here, here)
            else:
                run.end, run.requests = time, run.requests + 1
                run.last_frame, run.last_input = frame.number, here
            return
        if run is not None:
            self._close(slave)

    def _close(self, slave: int) -> None:
        run = self._runs.pop(slave)
        if run.requests >= 2:
            self.outages.append(Outage(slave, run.start, run.end, run.requests, run.first_frame, run.last_frame,
                                       run.offset, run.first_input, run.last_input))

    def finish(self) -> None:
        self.take_back()
        for slave in sorted(self._runs):
            self._close(slave)
        # in the order of time: several files read as one bus number their frames each from 1
        self.outages.sort(key=lambda outage: (outage.first_input, outage.first_frame, outage.slave))
        warn, self.warn = self.warn, None  # once
        if warn is not None and (text := self.overlap_warning()) is not None:
            warn(text)

    # -- results ------------------------------------------------------------------------------------
    def span(self) -> float | None:
        if self.first is None or self.last_end is None:
            return None
        back = self.backwards
        return back.spanned + (self.last_end - back.stretch)  # type: ignore[operator]

    def load(self) -> float | None:
        span = self.span()
        if not span:
            return None
        return min(1.0, self.busy / span)

    def load_per_minute(self) -> list[dict[str, float]]:
        span = self.span() or 0.0
        out = []
        for minute in sorted(self.minutes):
            covered = min(MINUTE, span - minute * MINUTE)
            if covered <= 0:
                continue
            out.append({"start": _round(self.first + minute * MINUTE),  # type: ignore[operator]
                        "load": round(min(1.0, self.minutes[minute] / covered), 6)})
        return out

    def report(self) -> dict[str, Any]:
        """The `bus` object of --stats --json."""
        self.finish()
        settings = self.settings
        ascii_only = self.framings == "ascii"
        turnaround = self.turnaround.summary()
        histogram = []
        edges = (0.0, *GAP_EDGES_MS)
        for index, count in enumerate(self.gap_histogram):
            upper = GAP_EDGES_MS[index] if index < len(GAP_EDGES_MS) else None
            histogram.append({"from_ms": None if index == 0 else edges[index], "to_ms": upper, "count": count})
        responses = []
        for slave in sorted(self.responses):
            summary = self.responses[slave].summary() or {}
            responses.append({
                "slave": slave, **summary, "margin": _round(self.timeout - self.waits[slave]),
                "close_to_timeout": self.close_to_timeout.get(slave, 0),
            })
        return {
            "timed": self.timed,
            "baud": settings.baud,
            "baud_source": settings.source,
            "bits_per_char": settings.char_bits(self.mode),
            "t35": None if ascii_only else _round(self.t35),
            "timeout": self.timeout,
            "span": None if self.span() is None else _round(self.span()),  # type: ignore[arg-type]
            "load": None if self.load() is None else round(self.load(), 6),  # type: ignore[arg-type]
            "load_per_minute": self.load_per_minute(),
            "gaps": self.gaps.summary(),
            "gaps_below_t35": self.gaps_below_t35 if self.timed and not ascii_only else None,
            # items starting before the previous one ends at this speed: a wrong --baud (a warning says so)
            "overlaps": self.overlaps() if self.timed else None,
            "gap_histogram": histogram if self.timed else [],
            "turnaround": None if turnaround is None else
            {key: turnaround[key] for key in ("count", "median", "p95", "max")},
            "responses": responses,
            "outages": [outage.as_dict(self.cited_titles()) for outage in self.outages],
            # time going backwards: items stamped before the item before them, responses before their request
            "backwards": {"items": self.backwards.items, "responses": self.backwards.responses} if self.timed else None,
        }

    def cited_titles(self) -> list[str] | None:
        """The files' names when several are read as one bus (each numbers its frames from 1), else None."""
        titles = self.titles
        return titles if len(titles) > 1 and len(titles) == self.inputs else None

    def untimed_text(self) -> str:
        """Why an input has no timing (report()'s `timed` false): UNHEARD when it gave no item, UNTIMED else."""
        self.take_back()
        return UNTIMED if self.timed or self.untimed_items else UNHEARD

    def overlaps(self) -> int:
        """Items that start before the previous one ends at this line speed (by more than half a
        percentile bucket, 5 us): a negative gap, so a negative turnaround too; not those stamped at the
        very time of the item before (same_stamp_overlaps: one record's later items)."""
        self.take_back()
        return sum(count for key, count in self.gaps.buckets.items() if key < 0) - self.same_stamp_overlaps

    def overlap_warning(self) -> str | None:
        """One line when the captured frames overlap at the line speed used (a wrong --baud: the bus
        timing is then impossible), None otherwise."""
        count = self.overlaps() if self.timed else 0
        if not count:
            return None
        settings = self.settings
        typed = settings.source == "--baud"
        what = f"--baud {settings.baud}" if typed else f"{settings.baud} baud ({settings.source})"
        hint = "" if typed or "--baud" in settings.source else " (--baud sets it)"
        return (f"{what}: {count_text(count, 'frame')} would overlap the one before at {settings.baud} baud: "
                f"the line is faster?{hint}")

    def line_text(self, data: dict[str, Any]) -> str:
        """The line's speed and character (`data`: report()'s); an ASCII character's bits said when assumed."""
        framing, bits = self.framings, f"{data['bits_per_char']} bits a character"
        if self.settings.bits is None and framing == "ascii":
            bits += " (start, 7 data, parity or a second stop, stop)"
        elif self.settings.bits is None and framing == "mixed":
            bits = f"{mode_bits('rtu')} bits a character in RTU, {mode_bits('ascii')} in ASCII"
        return f"{data['baud']} baud ({data['baud_source']}), {bits}"

    def framing_text(self) -> str | None:
        """What applies to the gaps when the bus is not all RTU (None: it is; t3.5 then says it all)."""
        framing = self.framings
        if framing == "ascii":
            return ASCII_FRAMING
        return MIXED_FRAMING if framing == "mixed" else None

    def render_plain(self, clock: Any = None) -> str:
        """The `Bus timing` section of --stats; `clock(seconds)` shows a time as the time column."""
        data = self.report()
        show = clock or (lambda seconds: f"{seconds:.6f}")
        lines = ["", "Bus timing"]
        rule = f"t3.5 {data['t35'] * 1000:.3f} ms, " if data["t35"] is not None else ""
        lines.append(f"line: {self.line_text(data)}, {rule}timeout {data['timeout'] * 1000:g} ms")
        if (framing := self.framing_text()) is not None:
            lines.append(f"framing: {framing}")
        if self.inputs > 1:
            lines.append(f"{self.inputs} captures counted as one bus: gaps and turnarounds restart at each "
                         "capture, the load is over the span from the first item to the last")
        if not data["timed"]:
            lines.append(self.untimed_text())
            return "\n".join(lines) + "\n"
        minutes = data["load_per_minute"]
        busiest = max(minutes, key=lambda entry: entry["load"]) if minutes else None
        load = data["load"]
        text = "load: " + ("-" if load is None else f"{load * 100:.1f} %")
        if busiest is not None and len(minutes) > 1:
            text += f" (busiest minute {busiest['load'] * 100:.1f} % from {show(busiest['start'])})"
        lines.append(text)
        gaps = data["gaps"]
        if gaps is not None:
            below = "" if data["gaps_below_t35"] is None else f", {data['gaps_below_t35']} below t3.5"
            lines.append(
                f"inter-frame gaps: {gaps['count']}{below}; min {gaps['min'] * 1000:.3f}"
                f" median {gaps['median'] * 1000:.3f} p95 {gaps['p95'] * 1000:.3f} max {gaps['max'] * 1000:.3f} ms"
            )
            lines.append("  " + ", ".join(gap_bins(data["gap_histogram"])))
        turnaround = data["turnaround"]
        if turnaround is not None:
            lines.append(
                f"master turnaround (answer end to next request, ms): median {turnaround['median'] * 1000:.3f}"
                f" p95 {turnaround['p95'] * 1000:.3f} max {turnaround['max'] * 1000:.3f} ({turnaround['count']})"
            )
        if data["responses"]:
            lines.append("slave  responses  median ms  p95 ms  max ms  margin to timeout ms  >90% of timeout")
            for entry in data["responses"]:
                lines.append(
                    f"{entry['slave']:>5}  {entry['count']:>9}  {entry['median'] * 1000:>9.1f}  {entry['p95'] * 1000:>6.1f}"
                    f"  {entry['max'] * 1000:>6.1f}  {entry['margin'] * 1000:>20.1f}  {entry['close_to_timeout']:>15}"
                )
        backwards = data["backwards"]
        if backwards["items"] or backwards["responses"]:
            lines.append(f"time going backwards, left out of the timing: {count_text(backwards['items'], 'item')} "
                         f"stamped earlier than the item before, {count_text(backwards['responses'], 'response')} "
                         "earlier than its request")
        if data["outages"]:
            lines.append("outages (two or more consecutive requests unanswered)")
            for outage in data["outages"]:
                lines.append(
                    f"  slave {outage['slave']} silent {show(outage['start'])} - {show(outage['end'])}, "
                    f"{outage['requests']} requests unanswered (frames {frames_cited(outage)})"
                )
        else:
            lines.append("outages: none")
        return "\n".join(lines) + "\n"


def time_text(time_format: str, first: float | None) -> Any:
    """Times of the bus section as the time column shows them (-t; deltas read as relative)."""
    from types import SimpleNamespace

    from dissector.render.timefmt import Clock

    clock = Clock("r" if time_format in ("d", "dd") else time_format, first=first)
    return lambda seconds: clock.text(SimpleNamespace(time=seconds))  # type: ignore[arg-type]


def gap_bins(histogram: list[dict[str, Any]]) -> list[str]:
    """The gap histogram's non-empty bins as text: `2-5 ms: 8`."""
    bins = []
    for entry in histogram:
        if entry["count"]:
            low, high = entry["from_ms"], entry["to_ms"]
            label = f"<{high:g}" if low is None else (f">={low:g}" if high is None else f"{low:g}-{high:g}")
            bins.append(f"{label} ms: {entry['count']}")
    return bins
