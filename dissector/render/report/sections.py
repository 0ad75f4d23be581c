"""The report's sections for bus health and navigation (issue 29): bus timing with the response times of
each slave against time and its outages as bands, the load per minute; events grouped with counts,
first and last (time and frame); the parameter index (named parameters first) and the compact table of
parameters that kept one value. Times are shown as the time column shows them (-t)."""
from __future__ import annotations

from collections.abc import Callable
from types import SimpleNamespace
from typing import Any

from dissector.render.bustiming import UNHEARD, gap_bins
from dissector.render.outages import frames_cited
from dissector.render.report.collect import ReportCollector
from dissector.render.stats_store import TABLE_NAMES, parameter_rows
from dissector.render.report.markup import _details, _esc, _ms, _table, cited
from dissector.render.pcapwriter import NANOS
from dissector.render.timefmt import Clock

MAX_GROUP_ROWS = 1000


def _clock(data: dict[str, Any], time_format: str, nanos: bool = False) -> Callable[[float], str]:
    """An absolute x (epoch seconds, or a frame number without timestamps) as -t shows it; `nanos`: with 9
    decimals, from the stamps' nanoseconds (microseconds cannot hold the capture's times: collect.py time_units)."""
    if not data["timed"]:
        return lambda x: cited(data, int(x))
    clock = Clock("r" if time_format in ("d", "dd") else time_format, first=data["origin"],
                  units=NANOS if nanos else None)
    return lambda x: clock.text(SimpleNamespace(time=x))  # type: ignore[arg-type]


def bus_section(data: dict[str, Any], bus: Any, health: Any, when: Callable[[float], str],
                anchor: str = "") -> list[str]:
    """Bus timing (bustiming.py) and the response-time charts; adds their series to `data`. `anchor`
    prefixes the ids (a page of several buses: html.py buses_pieces)."""
    parts = [f'<h2 id="{anchor}bus">Bus</h2>']
    if bus is None:
        return parts + ["<p>No bus timing for this report.</p>"]
    report = bus.report()
    origin = data["origin"]
    data["outages"] = [dict(outage, x0=round(outage["start"] - origin, 6), x1=round(outage["end"] - origin, 6))
                       for outage in report["outages"] if outage["start"] is not None]
    minutes = report["load_per_minute"]
    data["load"] = {"x": [round(entry["start"] - origin, 6) for entry in minutes],
                    "y": [round(entry["load"] * 100, 3) for entry in minutes]}
    if minutes:  # the last minute's step runs to its end, or the capture's
        end = min(minutes[-1]["start"] + 60.0, bus.first + report["span"])
        data["load"]["x"].append(round(end - origin, 6))
        data["load"]["y"].append(data["load"]["y"][-1])
    answers = {slave: quantiles.count for slave, quantiles in bus.responses.items()}
    data["responses"] = health.response_series(origin, data["column_width"], answers) if health is not None else []
    answered = {entry["slave"] for entry in data["responses"]}
    for slave in sorted({outage["slave"] for outage in data["outages"]} - answered):  # silent throughout
        data["responses"].append({"slave": slave, "answers": 0, "points": _no_points})
    data["responses"].sort(key=lambda entry: entry["slave"])
    if not report["timed"]:
        said = ("No bytes in this input (no frame, no noise): no load, gaps, turnaround or outages to measure"
                if bus.untimed_text() == UNHEARD else
                "No timestamps in this capture: load, gaps, turnaround and outages need a pcap, pcapng or timed dump")
        return parts + [f"<p>{said}.</p>"]
    load = report["load"]
    rows = [["line", bus.line_text(report)], ["load", "-" if load is None else f"{load * 100:.1f} %"]]
    framing = bus.framing_text()
    if framing is not None:  # an ASCII bus, or RTU and ASCII captures: what applies to the gaps
        rows.append(["framing", framing])
    if report["t35"] is not None:
        rows.append(["t3.5", f"{report['t35'] * 1000:.3f} ms"])
        rows.append(["gaps below t3.5", f"{report['gaps_below_t35']} of {(report['gaps'] or {}).get('count', 0)}"])
    bins = gap_bins(report["gap_histogram"])
    if bins:
        rows.append(["inter-frame gaps", ", ".join(bins)])
    turnaround = report["turnaround"]
    if turnaround is not None:
        rows.append(["master turnaround", f"median {_ms(turnaround['median'])} ms, p95 {_ms(turnaround['p95'])} ms, "
                                          f"max {_ms(turnaround['max'])} ms ({turnaround['count']})"])
    parts.append(_table(["", ""], rows, "bus"))
    if report["responses"]:
        parts.append(_table(
            ["slave", "answers", "median ms", "p95 ms", "max ms", "margin to --timeout ms", "over 90% of it"],
            [[entry["slave"], entry["count"], _ms(entry["median"]), _ms(entry["p95"]), _ms(entry["max"]),
              _ms(entry["margin"]), entry["close_to_timeout"]] for entry in report["responses"]], "numbers"))
    if report["outages"]:
        parts.append("<h3>Outages (two or more consecutive requests unanswered)</h3>" + _table(
            ["slave", "from", "to", "requests", "frames"],
            [[outage["slave"], when(outage["start"]), when(outage["end"]), outage["requests"],
              frames_cited(outage, "#")] for outage in report["outages"]], "numbers"))
    else:
        parts.append("<p>No outage: no slave left two consecutive requests unanswered.</p>")
    for entry in data["responses"]:
        parts.append(f'<div class="chart rtt" data-slave="{entry["slave"]}"><h3>Slave {entry["slave"]}: response '
                     f'time against time (ms), {entry["answers"]} answers, outages shaded</h3></div>')
    if data["load"]["x"]:
        parts.append('<div class="chart load"><h3>Bus load per minute (%)</h3></div>')
    return parts


def event_groups(collector: ReportCollector, data: dict[str, Any], when: Callable[[float], str]) -> list[str]:
    collector.flush()  # (data() did: the last frame's protection events are in)
    groups = collector.groups.rows()
    if not groups:
        return []
    rows = [[group.kind, "" if group.slave is None else group.slave, _details(group.label, group.detail), group.count,
             f"{when(group.first_x)} {cited(data, group.first_frame)}" if data["timed"]
             else cited(data, group.first_frame),
             (f"{when(group.last_x)} {cited(data, group.last_frame)}" if data["timed"] else cited(data, group.last_frame))
             if group.count > 1 else ""]
            for group in groups[:MAX_GROUP_ROWS]]
    parts = [_table(["kind", "slave", "event", "count", "first", "last"], rows, "events")]
    more = len(groups) - MAX_GROUP_ROWS + collector.groups.ungrouped
    if more > 0:
        parts.append(f'<p class="note">… {more} more kinds of events (counted in the timeline)</p>')
    return parts


def single_values(collector: ReportCollector, data: dict[str, Any]) -> dict[int, str]:
    """Parameters drawn from one value throughout and never unreadable: index -> the value as the summary
    names it (Series.text; `4.0 kHz`, where the value drawn is 4)."""
    single = {}
    for index, parameter in enumerate(data["parameters"]):
        if parameter["marks"] or not parameter["values"]:
            continue
        table = next(table for table, name in TABLE_NAMES.items() if name == parameter["table"])
        series = collector.series.get((parameter["slave"], parameter["address"], table))
        if series is None:
            continue
        levels = series.columns.levels()
        if levels is not None and levels[1] == levels[2]:
            single[index] = series.text if series.text is not None else _number(levels[0])
    return single


def single_counts(store: Any, data: dict[str, Any], single: dict[int, str]) -> dict[int, tuple[int, int]]:
    """The reads and writes --stats counts of each parameter with a single value (index -> (reads, writes)):
    the table says them apart, as --stats does (a parameter only written was `readings 1`, --stats `reads 0`)."""
    if not single:
        return {}
    wanted = {(data["parameters"][index]["slave"], data["parameters"][index]["address"],
               data["parameters"][index]["table"]): index for index in single}
    counts = {}
    for row in parameter_rows(store):  # (slave, address, code, reads, unreadable, writes, ..., table)
        index = wanted.get((row[0], row[1], TABLE_NAMES[row[-1]]))
        if index is not None:
            counts[index] = (row[3], row[5])
    return counts


def _number(value: float) -> str:
    return str(int(value) if value.is_integer() else value)


def parameter_index(data: dict[str, Any], single: dict[int, str], anchor: str = "",
                    counts: dict[int, tuple[int, int]] | None = None) -> list[str]:
    """Links to every trend, named parameters first; the one-value parameters as a table, with the reads
    and writes `counts` gives them (single_counts; a parameter --stats no longer keeps: `-`)."""
    counts = counts or {}
    parameters = data["parameters"]
    if not parameters:
        return ["<p>No parameter values in this capture.</p>"]
    order = sorted(range(len(parameters)), key=lambda index: (parameters[index]["code"] is None,
                                                               parameters[index]["slave"], parameters[index]["address"]))
    links = []
    for index in order:
        parameter = parameters[index]
        shown = parameter.get("label") or str(parameter["address"])  # as --address-style shows it
        name = parameter["code"] or shown
        target = f"{anchor}single" if index in single else f"{anchor}p{index}"
        title = _esc(f"slave {parameter['slave']}, {shown}: {parameter['name'] or ''}")
        links.append(f'<a href="#{target}" title="{title}">{_esc(name)}</a>')
    parts = ['<p class="index">' + " ".join(links) + "</p>"]
    if single:
        parts.append(f'<h3 id="{anchor}single">Parameters with a single value</h3>' + _table(
            ["slave", "address", "code", "name", "value", "reads", "writes"],
            [[parameters[index]["slave"], parameters[index].get("label") or parameters[index]["address"],
              parameters[index]["code"] or "",
              parameters[index]["name"] or "", single[index], *counts.get(index, ("-", "-"))]
             for index in order if index in single], "single"))
    return parts


def _no_points() -> tuple[str, str]:
    """The response times of a slave silent throughout (health.py's points: JSON text): none."""
    return "[]", "[]"
