"""--stats, --watch and --report of several buses: a pcapng with packets from several interfaces is one
input per interface, each its own bus (app/inputs.py), so each has its own statistics, parameter history,
bus timing, watched states and report (its collector and response times over time) here: slave 12 of bus
A is not slave 12 of bus B (its response times, its parameters' values and its outages are its own).
Several FILES stay one bus's pieces, as mergecap would join them: files read as one stream are one bus,
and an interface is one bus over every file that has it (the ring files of a two-line capture: two buses).

Sinks (app/cli.py) reads the current bus's `stats`, `timing`, `watch`, `report` and `health`;
`Buses.switch` makes a bus current at each input, and the results are written bus by bus, each under
its title as the decode shows it (`==> two.pcapng: /dev/pts/1 <==`, --json's `file`, a section of the
report's page). One bus (the usual case) writes exactly what it wrote before.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from dissector.protocol.printable import printable


@dataclass(slots=True)
class Bus:
    names: list[str]  # its inputs' titles: one interface (file: interface), or the files read as one stream
    stats: Any  # render/stats.py StatsCollector (its History), or None
    timing: Any  # render/bustiming.py BusTiming, or None
    watch: Any  # render/watch.py Watcher, or None
    report: Any = None  # render/report/collect.py ReportCollector (--report), or None
    health: Any = None  # render/report/health.py Health (--report), or None
    annotate: Any = None  # its annotator: its devices, profile `auto`'s choices (their notes on stderr)


class Buses:
    """The buses heard, in order. `make(title, annotate)` makes a new bus's (stats, timing, watch), given
    the annotator of that bus (its own devices: app/cli.py copies the pristine one per interface)."""

    def __init__(self, first: Bus, make: Callable[[str | None, Any], Bus]) -> None:
        self.make = make
        self.first = first
        self.known: dict[Any, Bus] = {}
        self.reading: dict[Any, str | None] = {}  # by bus key, the file read last (several files one bus)

    def switch(self, key: Any, title: str | None, annotate: Any, cited: str | None) -> Bus:
        """The bus of an input: `key` None for a file read as one stream (every such file is one bus),
        (interface name, ordinal) for one interface of a pcapng, the same in every file that has it. The
        first bus heard takes the first counts made (the run's annotator's). `cited`: the input's title
        when several captures are decoded (a bus may hear several, each numbering its frames from 1)."""
        bus = self.known.get(key)
        if bus is None:
            bus = self.first if not self.known else self.make(title, annotate)
            self.known[key] = bus
            bus.annotate = annotate
        if title is not None and title not in bus.names:
            bus.names.append(title)
        # Several captures read as one bus (files read as one stream, or an interface of several pcapng
        # files) number their frames each from 1 (the summary titles each): the evidence cited of them
        # names its input (profile `auto`'s reasons, --watch lines, the parameter memory's frames of the
        # inputs before: memory.cite_from, the report's frames).
        before = self.reading.get(key)
        self.reading[key] = cited
        if before is not None and before != cited:
            from dissector.devices.memory import cite_from

            cite_from(getattr(annotate, "_devices", {}).values(), before)
        selector = getattr(annotate, "selector", None)
        if selector is not None:
            selector.source = cited
        if bus.watch is not None:
            bus.watch.source = cited
        if bus.report is not None and cited is not None:
            bus.report.new_input(cited)
        return bus

    @property
    def several(self) -> bool:
        return len(self.known) > 1

    def all(self) -> list[Bus]:
        return list(self.known.values()) or [self.first]


def title(bus: Bus) -> str:
    """A bus's name: its interface's input title, or its files' names (counted as one bus)."""
    return ", ".join(bus.names) if bus.names else "--hex"


def header(bus: Bus, first: bool) -> str:
    """A bus's title over its results, as tail(1) and the decode's `==> FILE <==` show an input."""
    return ("" if first else "\n") + f"==> {printable(title(bus))} <==\n"


def new_bus(sinks: Any, annotate: Any) -> Bus:
    """Another interface's counts (app/cli.py Sinks makes the first): its own statistics and parameter
    history (its annotator's devices and profile choices), bus timing, watch and report, as the Sinks
    counts."""
    args, stats, timing, watch, report, health = sinks.options, None, None, None, None, None
    if sinks.stats is not None:
        from dissector.render.history import History
        from dissector.render.stats import StatsCollector

        stats = StatsCollector(getattr(annotate, "choices", None), History(annotate))
        stats.filtered = sinks.stats.filtered
    if sinks.bus is not None:
        from dissector.render.bustiming import BusTiming

        timing = BusTiming(args.timeout)
    if sinks.watch is not None:
        from dissector.render.timefmt import Clock
        from dissector.render.watch import watcher

        history = stats.history  # type: ignore[union-attr]  # (--watch makes the statistics too)
        watch = watcher(args.watch, sinks.text_out.write, sinks.json, annotate, history, Clock(args.output.time_format))
    if sinks.report is not None:
        from dissector.render.report.collect import ReportCollector
        from dissector.render.report.health import Health

        report, health = ReportCollector(annotate, stats.history), Health()  # type: ignore[union-attr]
    return Bus([], stats, timing, watch, report, health)


def write_report_page(sinks: Any, report: Any, buses: list[Bus]) -> None:
    """--report: one bus's page as it always was, or a page of several buses, each a section under its
    title (render/report/html.py buses_pieces), each drawn from its own counts and clock."""
    def extras(bus: Bus) -> dict[str, Any]:
        return {"bus": bus.timing, "health": bus.health, "time_format": sinks.clock.format}

    if len(buses) == 1:
        report.write(buses[0].stats, extras(buses[0]))
    else:
        report.write_buses([(title(bus), bus.report, bus.stats, extras(bus)) for bus in buses])


def write_stats(sinks: Any, bus: Bus, index: int | None) -> None:
    """--stats of a bus; `index`: its place among several buses, each written under its title (--json:
    one line a bus, its `file` first)."""
    stats, timing, write = bus.stats, bus.timing, sinks.text_out.write
    if sinks.json:
        name = {"file": title(bus)} if index is not None else None
        stats.write_json(write, {"bus": timing.report()} if timing is not None else None, name)
        return
    sinks.output.flush()
    console = sinks.output.console
    if index is not None:
        if console is not None:
            from rich.text import Text

            sinks.output.rule(Text(printable(title(bus))))
        else:
            write(header(bus, index == 0))
    if console is not None:
        sinks.output.print_fitted(stats.render())
    else:  # piped: plain tables at full width, no rich layout cost
        write(stats.render_plain())
    if timing is not None:
        from dissector.render.bustiming import time_text

        write(timing.render_plain(time_text(sinks.clock.format, timing.first)))
