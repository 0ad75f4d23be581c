"""What the HTML report draws, collected in one pass over the decoded items with bounded memory.

- Parameter trends: the parameter history's states (render/history.py, the one --stats counts and
  --watch prints): every value read (FC3/4/23 answers) or written and confirmed (FC6 echo, FC16/23
  request with a normal answer), as the device profile scaled it (`Register.scaled`, its unit), or the
  raw word for enumerations and bit fields (drawn as steps, with the profile's texts as labels), or
  the raw word when the map gives no scale. A status (`protected`, `non-existent`, or an exception the
  profile explains so) is no value: it opens an unreadable span, which the next value closes
  ("readable again"); both moments are marks on the chart and events on the timeline. A series is
  read as its slave's device now reads the words (Series.row): values drawn before profile `auto` chose
  a slave's device, or took a choice back, are read again from their words by the device chosen, so
  that standard input (one pass) draws what the file (named with the last choice throughout) draws.
- Points are downsampled per pixel column: each of at most COLUMNS columns of the capture's span
  keeps its first, lowest, highest and last point, so a spike or a dip of one sample survives, and a
  1 GB capture draws as fast as a small one. Values at one time are all drawn, in order (an FC23
  write and its read back: a step to the value read, the trend's last; Columns.points). The span is
  not known while streaming: columns start narrow and double in width (merging pairs) whenever the
  capture outgrows COLUMNS of them. The series kept (MAX_SERIES) are the first seen in the stream.
- Events: exceptions, protections, CRC errors, noise bursts, silences inside frames (the timing
  warnings), unanswered requests; counted per column for the timeline, the first MAX_EVENTS listed.
  Protection events are a frame's, its registers in their detail (moments.py); chart marks a register's.
  An exception is told with the meaning its slave's device gives the code (on standard input, for a
  frame decoded before profile `auto` chose the device: the meaning of the device chosen).
The x axis is the capture time (Unix seconds) when items are time-stamped, the frame number otherwise
(then `origin` is 0 and every x is the frame number itself: events at frames 2, 6, 10 say #2, #6, #10).
"""
from __future__ import annotations

from bisect import bisect_left, bisect_right
from dataclasses import dataclass, field
from typing import Any, Iterator

from dissector.decode.pairing import trusted_request
from dissector.model import Frame, Item, Kind, Register
from dissector.render.history import UNREADABLE, History
from dissector.render.pcapwriter import finer_than_micros
# (Columns, drawn and Y_DIGITS are the report's from here too: health.py, the codegen, the tests)
from dissector.render.report.columns import Y_DIGITS, Columns, compact_json as _json, drawn, new_columns
from dissector.render.report.groups import EventGroups
from dissector.render.report.meaning import device_meaning, event_text
from dissector.render.report.moments import Moments
from dissector.render.report.reading import MAX_LABELS, adopt, labelled, rehome, scales, shown_unit, summary_text
from dissector.render.stats_store import TABLE_NAMES, TABLES, table_label
from dissector.render.summary import noise_text

COLUMNS = 600
TIMED_WIDTH, UNTIMED_WIDTH = 1e-3, 1.0  # a column's first width: a millisecond timed, a frame untimed
MAX_SERIES = 400
MAX_MARKS = 200
MAX_EVENTS = 1000
EVENT_KINDS = ("exception", "protection", "crc", "noise", "silence", "unanswered")


@dataclass(slots=True)
class Series:
    slave: int
    address: int
    label: str | None = None  # as --address-style shows it (plc: 40001; stats_store.table_label), None: the address
    code: str | None = None
    name: str | None = None
    unit: str | None = None
    step: bool = False  # an enumeration or a bit field: the raw word, drawn as steps
    labels: dict[int, str] = field(default_factory=dict)
    # A value's text as the summary names it (reading.py summary_text), the last one named: the engine names
    # each value once (engine_point), so this is the value's text only for a series of one value (the
    # table of parameters with a single value: sections.py single_values)
    text: str | None = None
    columns: Any = field(default_factory=new_columns)
    # The map row the slave's device names the address with, whose reading of the words the points are
    # (reading.py adopt); None: no row, the points are the words themselves.
    row: Any = None
    reserved: bool = False  # made by provisional(), no state yet: its label is its first state's
    origins: int = 0  # bit t: a state of a code of protocol table t (FC4: input), by which rehome moves it
    values: int = 0
    status: str | None = None  # the open unreadable span's status, None when readable
    marks: list[tuple[float, str]] = field(default_factory=list)
    marks_dropped: int = 0


class ReportCollector:
    at_end = True  # the page is written at the end: the history may hold frames back for it (History.held)

    def __init__(self, annotate: object = None, history: History | None = None) -> None:
        """`history`: the run's parameter history, fed by its owner (StatsCollector); None: one of its
        own, fed by add()."""
        self._device = getattr(annotate, "device", None)
        self._annotate = annotate
        self.owns_history = history is None
        self.history = History(annotate) if history is None else history
        self.history.listeners.append(self)
        self.timed: bool | None = None
        self.nanos = False  # times told with 9 decimals (time_units)
        self.origin: float | None = None
        self.width = 0.0
        self.limit = 0.0  # x beyond which the columns double
        self.series: dict[tuple[int, int, int], Series] = {}  # by (slave, address, table), as the history
        self.series_dropped = 0
        self.spans = 0  # unreadable spans opened (the compiled engine reads the statuses again when it grows)
        self.events: list[tuple[float, str, int | None, str, str | None]] = []  # (x, kind, slave, text, detail)
        self.events_dropped = 0
        self._event_numbers: list[int] = []  # each listed event's frame number, in order
        self.event_columns: dict[str, dict[int, int]] = {kind: {} for kind in EVENT_KINDS}
        self.event_counts: dict[str, int] = {kind: 0 for kind in EVENT_KINDS}
        self.first_x: float | None = None
        self.last_x: float | None = None
        self.number = 0  # the frame number of the item at hand (events name their frame)
        # Several files read as one bus number their frames each from 1: the report numbers them on, each
        # file's from the last number of the one before (`numbered`), and cites them back by file (`inputs`:
        # (numbered, file) each; markup.py cited).
        self.numbered = 0
        self.inputs: list[tuple[int, str]] = []
        # The frame whose registers the history is giving, with its x and column (the listener is
        # called once per register: the x axis is worked out once per frame); None after a doubling.
        self._at: Item | None = None
        self._at_x = 0.0
        self._at_col = 0
        self._at_rows: Any = None  # the map of its slave's device now (None: no device)
        self.groups = EventGroups()
        # Exceptions told before their slave's device was chosen: (event index or None, slave, function,
        # code, text told), retold with the device's meaning by data()
        self._pending: list[tuple[int, int, int, int, str, Frame | None]] = []  # (frame number, slave, ...)
        self._moments = Moments()  # the protection moments of the frame at hand, until flush()

    # -- the x axis -------------------------------------------------------------------------------
    def _double(self) -> None:
        """Columns twice as wide, once the capture outgrows COLUMNS of them (the most drawn: the
        width at the end is the one data() would choose), finished columns merged at once: a series
        holds COLUMNS + 1 columns at most (MAX_SERIES of them 15 MB; they were let grow to 3 x COLUMNS,
        45 MB, issue 28). Merging keeps a column's first, lowest, highest and last point whenever it
        runs, and all series share the origin: the page is the same."""
        self.width *= 2
        self._at = None
        self.limit = self.origin + COLUMNS * self.width  # type: ignore[operator]
        for series in self.series.values():
            columns = series.columns
            columns.close()
            if len(columns) > COLUMNS // 2:
                columns.compact(self.origin, self.width)  # type: ignore[arg-type]
        for counts in self.event_columns.values():
            merged: dict[int, int] = {}
            for col, count in counts.items():
                merged[col // 2] = merged.get(col // 2, 0) + count
            counts.clear()
            counts.update(merged)

    def time_units(self, units: int | None) -> None:
        """An input's time units a second (a pcap's, a pcapng interface's; None: none known): where
        microseconds cannot hold its times, the page tells times with 9 decimals (-V's rule: timefmt.detail_digits)."""
        self.nanos = self.nanos or bool(units and finer_than_micros(units))

    def new_input(self, title: str) -> None:
        """The next of several files read as one bus (render/buses.py): its frames numbered on."""
        self.numbered = self.number
        self.inputs.append((self.numbered, title))

    def _x(self, item: Item) -> float:
        self.number = number = item.number + self.numbered
        if self.timed is None:
            self.timed = item.time is not None
            self.width = TIMED_WIDTH if self.timed else UNTIMED_WIDTH
        x = (item.time if item.time is not None else 0.0) if self.timed else float(number)
        if self.origin is None:
            self.origin = x
            self.limit = x + COLUMNS * self.width
        while x >= self.limit:
            self._double()
        if self.first_x is None:
            self.first_x = x
        if self.last_x is None or x > self.last_x:  # a frame read again later (history.py) is no later
            self.last_x = x
        return x

    def _col(self, x: float) -> int:
        return max(0, int((x - self.origin) / self.width))  # type: ignore[operator]

    # -- collecting -------------------------------------------------------------------------------
    def add_items(self, items: list[Item]) -> None:
        for item in items:
            self.add(item)

    def add(self, item: Item) -> None:
        self.flush()
        self._at = None
        x = self._x(item)
        for warning in item.warnings:
            if warning.startswith("silence"):
                self._event(x, "silence", getattr(item, "slave", None), warning)
        if item.kind is Kind.NOISE:
            self._event(x, "noise", None, noise_text(item.length, item.offset))
            return
        frame: Frame = item  # type: ignore[assignment]
        if not frame.crc_ok:
            self._event(x, "crc", frame.slave, f"bad CRC, function {frame.function}, {frame.length} bytes")
            return
        kind = frame.kind
        if kind is Kind.REQUEST:
            if frame.unanswered and not frame.broadcast:
                self._event(x, "unanswered", frame.slave, f"function {frame.function} unanswered")
        elif kind is Kind.EXCEPTION:
            code = frame.exception_code
            if code is None:
                self._event(x, "exception", frame.slave, "exception")
            else:
                device = None if self._device is None else self._device(frame.slave)
                # (not a request that failed its check: the slave answered bytes the tap did not see,
                # so its meaning picks nothing from it, as the note's: explain.explain_exception)
                request = trusted_request(frame)
                told = event_text(frame.function, code, frame.exception_text if device is None else
                                  device_meaning(device, frame.function, code, request))
                if self._device is not None and self.history.held(frame):
                    # Decoded before profile `auto` chose the slave's device for good: no meaning yet (data() tells it)
                    # (its request kept: a refused read-only write, the causes it picks: meaning.py)
                    self._pending.append((self.number, frame.slave, frame.function, code, told, request))
                self._event(x, "exception", frame.slave, told)
        if self.owns_history:
            self.history.add(frame)

    def _event(self, x: float, kind: str, slave: int | None, text: str, detail: str | None = None,
               number: int | None = None) -> None:
        if number is None:  # the item at hand's (the engine's too): after the protection moments before it
            self.flush()
            number = self.number
        self.event_counts[kind] += 1
        self.groups.add(kind, slave, text, x, number, detail)
        counts = self.event_columns[kind]
        col = self._col(x)
        counts[col] = counts.get(col, 0) + 1
        numbers = self._event_numbers
        if len(numbers) < MAX_EVENTS or number < numbers[-1]:
            # In frame order, the file's: a held frame's protection comes when the history reads it again
            at = len(numbers) if not numbers or number >= numbers[-1] else bisect_right(numbers, number)
            numbers.insert(at, number)
            self.events.insert(at, (x, kind, slave, text, detail))
            if len(numbers) > MAX_EVENTS:  # (the first MAX_EVENTS frames' listed)
                numbers.pop()
                self.events.pop()
                self.events_dropped += 1
        else:
            self.events_dropped += 1

    def _moment(self, x: float, slave: int, series: Series, status: str | None, how: str = "") -> None:
        """A series' unreadable span opened (`status`) or closed (None) by the frame at hand (moments.py)."""
        key = (self.number, x, slave)
        if self._moments.key not in (None, key):
            self.flush()
        self._moments.add(key, series, status, how)

    def flush(self) -> None:
        """The protection events of the frame whose registers were given last (events keep their order)."""
        for number, x, slave, text, detail in self._moments.take():
            self._event(x, "protection", slave, text, detail, number)

    def _series(self, slave: int, table: int, register: Register) -> Series | None:
        key = (slave, register.address, table)
        series = self.series.get(key)  # type: ignore[arg-type]
        if series is None:
            if len(self.series) >= MAX_SERIES:
                self.series_dropped += 1
                return None
            series = self.series[key] = Series(slave, key[1], table_label(register.label, table, key[1]))  # type: ignore
        return series

    # -- the history's listener --------------------------------------------------------------------
    def provisional(self, frame: Frame, register: Register, event: int) -> None:
        """A register of a frame decoded before profile `auto` chose its slave's device (standard input):
        the history holds the frame back and gives its states later, in the slave's choice's frame;
        its series is made now, so that the series kept (MAX_SERIES) are those seen first in the stream,
        as from the file, whose frames give their states in the stream's order."""
        table = self.history.tables(frame.slave)[frame.function]
        key = (frame.slave, register.address, table)
        if key not in self.series and len(self.series) < MAX_SERIES:
            self.series[key] = Series(frame.slave, register.address, reserved=True)  # type: ignore[arg-type]
        if key in self.series:
            self.series[key].origins |= 1 << TABLES[frame.function]  # type: ignore[index]

    def state(self, frame: Frame, register: Register, event: int, changed: bool) -> None:
        """A register that set its parameter's state: a point, or an unreadable span's start or end."""
        if frame is self._at:
            x, col, rows = self._at_x, self._at_col, self._at_rows
        else:
            x = self._x(frame)  # the item's own x (add() saw it first: idempotent)
            col = self._col(x)
            rows = None if self._device is None else self._device(frame.slave).rows_for(frame.function)
            self._at, self._at_x, self._at_col, self._at_rows = frame, x, col, rows
        slave = frame.slave
        table = self.history.tables(frame.slave)[frame.function]
        series = self.series.get((slave, register.address, table)) or self._series(slave, table, register)  # type: ignore
        if series is None:
            return
        series.origins |= 1 << TABLES[frame.function]
        if series.reserved:
            series.reserved, series.label = False, table_label(register.label, table, series.address)
        if rows is None:  # no device: the names the decode gave
            if series.code is None and register.code is not None:
                series.code, series.name = register.code, register.name
        else:
            row = rows.get(register.address)
            if row is not series.row:
                adopt(series, row)
            if (register.code != (None if row is None else row.code) and (row is None or row.words == 1)
                    and register.words == 1):  # (a word pair is read by a 32-bit row only)
                # Named by another device (decoded before profile `auto` chose again, or with a choice
                # taken back since): a series holds one reading, the file's, named with the last choice
                register = self._named(frame, register)
        if event == UNREADABLE:
            status = register.status or "unreadable"
            if series.status != status:  # a span opens (the first state too: the chart starts unreadable)
                series.status = status
                self.spans += 1
                how = f" (exception {frame.exception_code:02X})" if frame.kind is Kind.EXCEPTION else ""
                self._mark(series, x, status + how)
                self._moment(x, slave, series, status, how)
            return
        if series.status is not None:
            self._readable_again(series, x)
        if register.words == 2 and register.scaled is None:
            return  # a 32-bit float with no number (nan, inf): nothing to draw
        y = self._y(series, register)
        series.values += 1
        series.columns.add(col, x, y)

    @staticmethod
    def _y(series: Series, register: Register) -> float:
        """The value drawn: scaled as the device reads it, else the raw word, named by labels where the map
        row is an enumeration or a bit field (a number not scaled keeps its unit); the register named by the
        slave's device now, whose map row the series adopted (reading.py adopt)."""
        series.text = summary_text(register)
        scaled = register.scaled
        if scaled is not None:
            if series.unit is None:
                series.unit = register.unit
            return float(scaled)
        text = register.text
        if not _names_word(series.row, register):  # a number the device does not scale: `10 (unscaled, in s)`
            if series.unit is None:
                series.unit = register.unit
        elif text is not None:  # an enumeration or a bit field: the profile names the word
            series.step = True
            labels = series.labels
            if register.value not in labels and len(labels) < MAX_LABELS:
                labels[register.value] = text  # type: ignore[index]
        return float(register.value)  # type: ignore[arg-type]

    def _named(self, frame: Frame, register: Register) -> Register:
        """The register as the slave's device now names it (Annotator.plain_register, as the engine's
        values), its status kept."""
        plain = getattr(self._annotate, "plain_register", None)
        if plain is None or register.value is None:
            return register
        named = plain(frame.slave, frame.function, register.address, register.value)
        named.status = register.status
        return named

    def _readable_again(self, series: Series, x: float) -> None:
        self._mark(series, x, f"readable again ({series.status} before)")
        self._moment(x, series.slave, series, None)
        series.status = None

    def engine_point(self, slave: int, function: int, address: int, value: int,
                     changed: bool = True) -> tuple[Series, float]:
        """For the compiled engine (dissector/accel/_report.h), which feeds the points of the values it
        counts itself and asks here once per value first seen (and for a series' first value): the
        series (made now: the engine checked MAX_SERIES) with what state() takes of the register, as
        the annotator names it (Annotator.plain_register), and its y. `changed`: the series' first value
        since the slave's device changed (or its first): its map row adopted (else it is already)."""
        plain = getattr(self._annotate, "plain_register", None)
        register = Register(address, value) if plain is None else plain(slave, function, address, value)
        table = self.history.tables(slave)[function]
        series = self.series.get((slave, address, table)) or self._series(slave, table, register)
        series.origins |= 1 << TABLES[function]  # (the engine tells a further origin itself: _report.h)
        if series.reserved:
            series.reserved, series.label = False, table_label(register.label, table, address)
        if self._device is None:
            if series.code is None and register.code is not None:
                series.code, series.name = register.code, register.name
        elif changed:
            row = self._device(slave).rows_for(function).get(address)
            if row is not series.row:
                adopt(series, row)
        return series, self._y(series, register)  # type: ignore[arg-type]

    def rehomed(self, slave: int, homes: bytes) -> None:
        """The slave's series moved to the tables its new device reads them with (History._rehome)."""
        rehome(self.series, slave, homes, getattr(self._annotate, "label", None))

    def renamed(self, slave: int) -> None:
        """The slave's profile changed: its series are read again as the new device reads them (raw words
        kept for unscaled series scaled, enumerations and bit fields become steps; a choice taken back:
        the other way)."""
        if self._device is None:
            return
        device = self._device(slave)
        for (owner, address, table), series in self.series.items():
            if owner == slave:
                row = device.table_rows(table).get(address)
                if row is not series.row:
                    adopt(series, row)

    @staticmethod
    def _mark(series: Series, x: float, text: str) -> None:
        if len(series.marks) < MAX_MARKS:
            series.marks.append((x, text))
        else:
            series.marks_dropped += 1

    # -- results ----------------------------------------------------------------------------------
    def data(self, points: bool = True) -> dict[str, Any]:
        """Everything the page's script draws, JSON-ready, x relative to `origin`. With points=False
        the parameters come without their x/y lists: `parameters_json` writes those one series at a
        time, so that the points of a large report are never all Python objects at once."""
        self.flush()
        if self.last_x is not None:
            while (self.last_x - (self.origin or 0.0)) / self.width >= COLUMNS:  # at most COLUMNS columns drawn
                self._double()
        self._retell()
        digits = self._digits()
        origin = self._shift()
        parameters = [self._parameter(key, series, points) for key, series in self.drawn_series()]
        columns = []
        width = self.width
        for kind in EVENT_KINDS:
            counts = self.event_columns[kind]
            start = (self.origin or 0.0) - origin  # columns count from the first item's x
            columns.append({"kind": kind, "x": [round(start + col * width, digits) for col in sorted(counts)],
                            "n": [counts[col] for col in sorted(counts)]})
        return {
            "timed": bool(self.timed),
            **({"inputs": [list(entry) for entry in self.inputs]} if len(self.inputs) > 1 else {}),
            "origin": origin,
            "span": 0.0 if self.first_x is None or self.last_x is None else round(self.last_x - origin, digits),
            "column_width": width,
            "parameters": parameters,
            "parameters_dropped": self.series_dropped,
            "events": [[round(x - origin, digits), kind, slave, text, *(() if detail is None else (detail,))]
                       for x, kind, slave, text, detail in self.events],
            "events_dropped": self.events_dropped,
            "event_counts": self.event_counts,
            "event_columns": columns,
        }

    def _retell(self) -> None:
        """Exceptions decoded before profile `auto` chose their slave's device (standard input) told as
        the file tells them: with the chosen device's meaning (meaning.py device_meaning: p.38's clause, a
        refused read-only write's, the causes the request picks)."""
        numbers, events = self._event_numbers, self.events
        for number, slave, function, code, told, request in self._pending:
            meaning = device_meaning(self._device(slave), function, code, request)  # type: ignore[misc]
            text = event_text(function, code, meaning)
            if text == told:
                continue
            for index in range(bisect_left(numbers, number), bisect_right(numbers, number)):
                if events[index][1] == "exception" and events[index][3] == told:  # (if listed)
                    events[index] = (*events[index][:3], text, None)
                    break
            self.groups.retell("exception", slave, told, text)
        self._pending.clear()

    def parameters_json(self) -> str:
        """The parameters with their points as a JSON array, encoded series by series (call data first)."""
        return "".join(self.parameters_json_pieces())

    def parameters_json_pieces(self) -> Iterator[str]:
        """parameters_json's text in pieces, a series each (html.py writes them one by one)."""
        yield "["
        for index, (key, series) in enumerate(self.drawn_series()):
            yield ("," if index else "") + self._parameter_json(key, series)
        yield "]"

    def _parameter_json(self, key: tuple[int, int, int], series: Series) -> str:
        # The columns write their points' JSON themselves (the compiled ones in C, _columns.h
        # drawn_json; None: a value json.dumps refuses): x and y come last, as _parameter puts them.
        entry = self._parameter(key, series, False)
        columns = series.columns
        columns.close()
        columns.compact(self.origin or 0.0, self.width)
        points = columns.drawn_json(self._shift(), self._digits())
        if points is None:
            return _json(self._parameter(key, series, True))
        return f'{_json(entry)[:-1]},"x":{points[0]},"y":{points[1]}}}'

    def _digits(self) -> int:
        return 6 if self.timed else 0

    def _shift(self) -> float:
        """What the data's x are relative to: the first item's time, or 0 (frame numbers as they are)."""
        return (self.origin or 0.0) if self.timed else 0.0

    def drawn_series(self) -> list[tuple[tuple[int, int, int], Series]]:
        """The series drawn, in the order of data()'s parameters."""
        return [(key, series) for key, series in sorted(self.series.items()) if series.values or series.marks]

    def _parameter(self, key: tuple[int, int, int], series: Series, points: bool) -> dict[str, Any]:
        origin, digits = self._shift(), self._digits()
        entry: dict[str, Any] = {
            "slave": key[0],
            "address": key[1],
            "table": TABLE_NAMES[key[2]],
            "label": series.label,
            "code": series.code,
            "name": series.name,
            "unit": shown_unit(series.row, series.unit),  # (as the table says it: `(unscaled, in s)`)
            "step": series.step,
            "labels": {str(value): text for value, text in sorted(series.labels.items())},
            "values": series.values,
            "marks": [[round(x - origin, digits), text] for x, text in series.marks],
            "marks_dropped": series.marks_dropped,
        }
        row = series.row
        if row is not None and scales(row) and row.decimals:  # (the tooltip's digits, as the table's `30.0 Hz`)
            entry["decimals"] = row.decimals
        if points:
            columns = series.columns
            columns.close()
            columns.compact(self.origin or 0.0, self.width)
            entry["x"], entry["y"] = drawn(columns, origin, digits)
        return entry


def _names_word(row: Any, register: Register) -> bool:
    """The register's text names its word (an enumeration or a bit field: steps and labels) rather than
    saying a number: as its map row reads words, or without a row (no device profile), when the text does
    not start with the number itself (watch.py value_text)."""
    if row is not None:
        return labelled(row)
    return register.text is not None and not register.text.startswith(f"{register.value} ")
