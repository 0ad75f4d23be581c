"""What a live capture shows: running counters, and the three ways of showing items.

`LiveStats` counts what has been heard (per slave, CRC errors, unanswered requests, last response
time); it is plain data so tests compare exact numbers. The sinks write items as they come:
plain lines when the output is a pipe, NDJSON with --json, and a rich live view on a terminal
(a header of counters above the last frames, which scroll).

Lines go through an `OutputPump`: a thread that writes them, behind a bounded queue. A reader that
stops reading (a paused terminal, a slow pipe) blocks only that thread; once the queue is full, lines
are dropped and counted, and the counters and the final summary say how many were not shown.
"""
from __future__ import annotations

import json
import re
import threading
import time
from collections import Counter, deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Protocol, TextIO

from rich.console import Console, Group, RenderableType
from rich.live import Live
from rich.table import Table
from rich.text import Text

from dissector.protocol.rules import awaits_answer
from dissector.model import Frame, Item, Kind, Noise
from dissector.render.describe import count_text
from dissector.render.jsonout import item_to_dict

_SLAVE_KIND = re.compile(r" *\d+ +\S+ +(\d+) (\w+)")  # a summary line's slave and kind (-t r, d, dd)
_UNANSWERED = " [no response]  CRC ok"  # the end of an unanswered request's line (the engine's: no notes)
# The rich view redraws at most this often; a frame is still drawn within 50 ms of being framed.
REDRAW_INTERVAL = 0.04


@dataclass
class SlaveCounts:
    requests: int = 0
    responses: int = 0
    exceptions: int = 0
    crc_errors: int = 0
    unanswered: int = 0


@dataclass
class LiveStats:
    frames: int = 0
    noise_items: int = 0
    noise_bytes: int = 0
    crc_errors: int = 0
    unanswered: int = 0
    last_response_time: float | None = None
    not_shown: int = 0  # items the display dropped because it fell behind
    files: bool = False  # -w or --raw: the files hold what was not shown
    slaves: dict[int, SlaveCounts] = field(default_factory=dict)
    # Requests not yet known to be answered or unanswered: the pairer decides later (hold=False),
    # by setting `response` or `unanswered` on the request object we keep here.
    _open: list[Frame] = field(default_factory=list)

    def add(self, item: Item) -> None:
        if isinstance(item, Noise):
            self.noise_items += 1
            self.noise_bytes += item.length
            self._settle()
            return
        frame = item
        self.frames += 1
        counts = self.slaves.setdefault(frame.slave, SlaveCounts())
        if not frame.crc_ok:
            self.crc_errors += 1
            counts.crc_errors += 1
        if frame.kind is Kind.REQUEST:
            counts.requests += 1
            if awaits_answer(frame):  # (not a broadcast, nor FC8 04: no answer or unanswered ever settles those)
                self._open.append(frame)
        elif frame.kind is Kind.EXCEPTION:
            counts.exceptions += 1
        else:
            counts.responses += 1
        if frame.response_time is not None:
            self.last_response_time = frame.response_time
        self._settle()

    def add_lines(self, lines: list[str]) -> None:
        """Summary lines the engine wrote (dissector/accel/livepath.py): a valid frame each, its
        request paired or known unanswered (the engine writes nothing else). Counted by (slave, kind)
        in C (Counter), then per pair."""
        self.frames += len(lines)
        kinds = Counter(_SLAVE_KIND.match(line).groups() for line in lines)  # type: ignore[union-attr]
        for (slave_text, kind), count in kinds.items():
            slave = int(slave_text)
            counts = self.slaves.get(slave)
            if counts is None:
                counts = self.slaves[slave] = SlaveCounts()
            if kind == "request":
                counts.requests += count
            elif kind == "exception":
                counts.exceptions += count
            else:
                counts.responses += count
        for line in lines:
            if line.endswith(_UNANSWERED):
                self.unanswered += 1
                self.slaves[int(_SLAVE_KIND.match(line).group(1))].unanswered += 1  # type: ignore[union-attr]

    def finish(self) -> None:
        self._settle()

    def _settle(self) -> None:
        still_open = []
        for request in self._open:
            if request.unanswered:
                self.unanswered += 1
                self.slaves[request.slave].unanswered += 1
            elif request.response is None:
                still_open.append(request)
        self._open = still_open

    def summary(self, seconds: float) -> str:
        requests = sum(c.requests for c in self.slaves.values())
        responses = sum(c.responses for c in self.slaves.values())
        exceptions = sum(c.exceptions for c in self.slaves.values())
        return (
            f"{count_text(self.frames, 'frame')} ({count_text(requests, 'request')}, "
            f"{count_text(responses, 'response')}, {count_text(exceptions, 'exception')}) "
            f"from {count_text(len(self.slaves), 'slave')}, {count_text(self.crc_errors, 'CRC error')}, "
            f"{self.unanswered} unanswered, {count_text(self.noise_bytes, 'noise byte')} in {seconds:.1f} s"
        )

    def not_shown_text(self) -> str:
        """Why some lines are missing, and where they are; empty when none is."""
        if not self.not_shown:
            return ""
        where = ", the capture files hold them" if self.files else ", no capture file holds them (-w, --raw)"
        return f"{count_text(self.not_shown, 'item')} not shown (the display fell behind){where}"


class Sink(Protocol):
    failed: BaseException | None  # the output could not be written (BrokenPipeError: reader gone)
    dropped: int  # lines not shown because the output fell behind

    def show(self, items: list[Item]) -> None: ...

    def tick(self) -> None: ...

    def close(self) -> None: ...


PUMP_LIMIT = 20_000  # lines waiting to be written; beyond, lines are dropped (and counted)


class OutputPump:
    """Writes lines on its own thread, each batch flushed; `put` never blocks."""

    def __init__(self, out: TextIO, limit: int | None = None) -> None:
        self._out = out
        self._limit = PUMP_LIMIT if limit is None else limit
        self._lines: deque[str] = deque()
        self._cond = threading.Condition()
        self._closing = False
        self.dropped = 0
        self.failed: BaseException | None = None  # BrokenPipeError when the reader went away
        self._thread = threading.Thread(target=self._run, name="output", daemon=True)
        self._thread.start()

    def put(self, lines: list[str]) -> None:
        with self._cond:
            room = self._limit - len(self._lines)
            if self.failed is not None:
                return
            if len(lines) > room:
                self.dropped += len(lines) - max(room, 0)
                lines = lines[: max(room, 0)]
            self._lines.extend(lines)
            self._cond.notify()

    def _run(self) -> None:
        while True:
            with self._cond:
                while not self._lines and not self._closing:
                    self._cond.wait()
                if not self._lines:
                    return
                batch = "".join(line + "\n" for line in self._lines)
                self._lines.clear()
            try:
                self._out.write(batch)
                self._out.flush()
            except (OSError, ValueError) as error:
                with self._cond:
                    self.failed = error
                    self._lines.clear()
                return

    def close(self) -> None:
        """Write what is queued (blocks while the reader does not read, as any writer would)."""
        with self._cond:
            self._closing = True
            self._cond.notify()
        self._thread.join()


class PumpedSink:
    """A sink whose lines an OutputPump writes: its failure and dropped lines are the pump's."""

    def __init__(self, out: TextIO) -> None:
        self._pump = OutputPump(out)

    @property
    def failed(self) -> BaseException | None:
        return self._pump.failed

    @property
    def dropped(self) -> int:
        return self._pump.dropped

    def tick(self) -> None:
        pass

    def close(self) -> None:
        self._pump.close()


class LineSink(PumpedSink):
    """One line per item (plain or NDJSON), written by an OutputPump."""

    def __init__(self, out: TextIO, render: Callable[[Item], str]) -> None:
        super().__init__(out)
        self._render = render

    def show(self, items: list[Item]) -> None:
        if items:
            self._pump.put([self._render(item) for item in items])

    def show_lines(self, lines: list[str]) -> None:
        """Lines written elsewhere (the engine's summary lines), in order with the items'."""
        if lines:
            self._pump.put(lines)


def json_line(item: Item) -> str:
    return json.dumps(item_to_dict(item))


def header_table(stats: LiveStats) -> Table:
    table = Table(expand=False, pad_edge=False, box=None)
    for name in ("slave", "requests", "responses", "exceptions", "CRC errors", "unanswered"):
        table.add_column(name, justify="right")
    for slave in sorted(stats.slaves):
        c = stats.slaves[slave]
        table.add_row(
            str(slave), str(c.requests), str(c.responses), str(c.exceptions), str(c.crc_errors),
            str(c.unanswered),
        )
    return table


def totals_text(stats: LiveStats) -> str:
    last = stats.last_response_time
    return (
        f"{count_text(stats.frames, 'frame')}, {count_text(stats.crc_errors, 'CRC error')}, "
        f"{stats.unanswered} unanswered, "
        f"{count_text(stats.noise_bytes, 'noise byte')}, last response time "
        + (f"{last * 1000:.1f} ms" if last is not None else "-")
        + (f"; {stats.not_shown_text()}" if stats.not_shown else "")
    )


class LiveView:
    """Header of counters above the last frames. A renderable: the Console draws it."""

    def __init__(self, title: str, stats: LiveStats, render: Callable[[Item], Text], rows: int) -> None:
        self.title = title
        self.stats = stats
        self._render = render
        self.lines: deque[Text] = deque(maxlen=max(rows, 1))

    def add(self, item: Item) -> None:
        self.lines.append(self._render(item))

    def __rich__(self) -> RenderableType:
        return Group(
            Text(self.title, style="bold"),
            header_table(self.stats),
            Text(totals_text(self.stats)),
            Text(""),
            *self.lines,
        )


class RichSink:
    """The live view on a terminal: redrawn when items arrive, at most every REDRAW_INTERVAL."""

    def __init__(
        self, console: Console, title: str, stats: LiveStats, render: Callable[[Item], Text]
    ) -> None:
        # Keep room for the header (title, column names, caption, a row per slave, a spacer).
        rows = max(console.size.height - 12, 5)
        self.view = LiveView(title, stats, render, rows)
        self._live = Live(self.view, console=console, auto_refresh=False, transient=False)
        self._live.start()
        self._dirty = True
        self._drawn = 0.0
        self.failed: BaseException | None = None
        self.dropped = 0  # the view keeps the last lines: a slow terminal delays it, drops nothing

    def show(self, items: list[Item]) -> None:
        for item in items:
            self.view.add(item)
        if items:
            self._dirty = True
            self.tick()

    def tick(self) -> None:
        now = time.monotonic()
        if self._dirty and now - self._drawn >= REDRAW_INTERVAL and self.failed is None:
            try:
                self._live.refresh()
            except (OSError, ValueError) as error:
                # The terminal is gone (EIO once the SSH session or window closed): the display stops
                # the capture, as when a reader of our output goes away; the files stay whole.
                self.failed = error
            self._dirty = False
            self._drawn = now

    def close(self) -> None:
        if self.failed is None:
            self._live.refresh()
        self._live.stop()
