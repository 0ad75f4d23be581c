"""The report page: tables written here (readable without script), charts drawn by uPlot from one JSON
block. Everything is inline (uPlot 1.6.31, MIT, vendored in static/ from npm `uplot`), so the file opens
on an offline laptop and holds no http(s) reference.
"""
from __future__ import annotations

import json
from importlib import resources
from typing import Any, Iterator, TextIO

from dissector.errors import OutputError
from dissector.render.report.collect import EVENT_KINDS, ReportCollector
from dissector.render.report.markup import _esc, _ms, _table
from dissector.render.report.reading import unit_heading
from dissector.render.report.sections import (
    _clock, bus_section, event_groups, parameter_index, single_counts, single_values,
)
from dissector.render.stats import StatsCollector, exception_counts, merged_text, time_summary
from dissector.render.describe import count_text
from dissector.protocol.printable import printable
from dissector.render.stats_store import HOLDING_REGISTERS, TABLE_NAMES, give_back
from dissector.protocol.spec import SPEC

HISTOGRAM_BINS = 40
FLAT_BIN = 1e-4  # a histogram's bin width (s) when its times are all equal
_STAND_IN = "\0responses"
_STAND_IN_JSON = json.dumps(_STAND_IN)


def _static(name: str) -> str:
    return resources.files("dissector.render.report").joinpath("static", name).read_text("utf-8")


def _slaves(stats: StatsCollector) -> list[dict[str, Any]]:
    """Per slave: the --stats counts summed over its functions, and its response-time histogram."""
    slaves: dict[int, dict[str, Any]] = {}
    for (slave, _function), row in sorted(stats.all_functions().items()):
        entry = slaves.setdefault(
            slave,
            {"slave": slave, "requests": 0, "responses": 0, "exceptions": {}, "unanswered": 0,
             "crc_errors": 0, "times": {}},
        )
        entry["requests"] += row.requests
        entry["responses"] += row.responses
        entry["unanswered"] += row.unanswered
        entry["crc_errors"] += row.crc_errors
        for code, count in row.exceptions.items():
            entry["exceptions"][code] = entry["exceptions"].get(code, 0) + count
        times = entry["times"]
        if not times:  # (most slaves answer one function: its histogram as it is)
            times.update(row.times)
            continue
        for value, count in row.times.items():
            times[value] = times.get(value, 0) + count
    result = []
    for entry in slaves.values():
        times = entry.pop("times")
        entry["time"] = summary = time_summary(times)
        if summary is not None:
            low, high = summary["min"], summary["max"]
            width = (high - low) / HISTOGRAM_BINS or FLAT_BIN
            counts = [0] * HISTOGRAM_BINS
            for value, count in times.items():
                counts[min(HISTOGRAM_BINS - 1, int((value / 1e9 - low) / width))] += count
            summary["bins"] = [round((low + (index + 0.5) * width) * 1000, 4) for index in range(HISTOGRAM_BINS)]
            summary["counts"] = counts
        result.append(entry)
    return result


def render_report(
    collector: ReportCollector, stats: StatsCollector, title: str = "vw3-decode report",
    extras: dict[str, Any] | None = None,
) -> str:
    """`extras`: `bus` (BusTiming), `health` (report/health.py) and `time_format` (-t) when the CLI has them."""
    return "".join(report_pieces(collector, stats, title, extras))


def report_pieces(
    collector: ReportCollector, stats: StatsCollector, title: str = "vw3-decode report",
    extras: dict[str, Any] | None = None,
) -> Iterator[str]:
    """The page in pieces, in order (render_report joins them; write_report writes them one by one, so
    that a large report's points are never one string and its copies: issue 28, flat memory)."""
    pieces = _bus_pieces(collector, stats, extras or {})
    body = next(pieces)  # (made before the page's head is written, as it always was)
    yield _page_head(title, _NAV.format(anchor=""))
    yield body
    yield from pieces
    yield _page_tail(_static("report.js"))


def buses_pieces(buses: list[tuple[str, ReportCollector, StatsCollector, dict[str, Any]]],
                 title: str = "vw3-decode report") -> Iterator[str]:
    """The page of several buses (a pcapng's interfaces, render/buses.py), in pieces: each bus a section
    under its name as the decode titles it, with the sections one bus's page has, its own anchors and its
    own data block (report-data-N). The bus names are bus data (a pcapng's if_name): escaped as text."""
    links = " ".join(f'<a href="#b{index}">{_esc(printable(name))}</a>' for index, (name, *_rest) in enumerate(buses))
    yield _page_head(title, f"<nav>buses: {links}</nav>\n", _BUSES_STYLE)
    for index, (name, collector, stats, extras) in enumerate(buses):
        anchor = f"b{index}-"
        pieces = _bus_pieces(collector, stats, extras, anchor, f"report-data-{index}")
        body = next(pieces)
        yield (f'<section class="bus" id="b{index}"><h2 class="bus">{_esc(printable(name))}</h2>\n'
               + _NAV.format(anchor=anchor) + body)
        yield from pieces
        yield "</section>\n"
    yield _page_tail(_SCOPED.replace("REPORT_JS", _static("report.js")))


_NAV = ('<nav><a href="#{anchor}slaves">slaves</a> <a href="#{anchor}bus">bus</a> <a href="#{anchor}poll">poll '
        'cycle</a> <a href="#{anchor}events">events</a> <a href="#{anchor}parameters">parameters</a></nav>\n')
_BUSES_STYLE = ("<style>section.bus { border-top: 3px solid #555; margin-top: 2em; } "
                "h2.bus { border: 0; font-size: 1.35em; }</style>\n")
# report.js draws one bus: the block "report-data" and the charts of `document`. A page of several buses
# runs it once a bus, given a document whose look-ups stay in that bus's section (so one bus's page, and
# report.js, stay as they were); one bus's failure is shown and does not stop the others' charts.
_SCOPED = """(function () {
  var page = document, charts = 0;
  function draw(document) {
REPORT_JS  }
  page.querySelectorAll("section.bus").forEach(function (section, index) {
    try {
      draw({
        getElementById: function (id) { return page.getElementById(id === "report-data" ? "report-data-" + index : id); },
        querySelectorAll: function (selector) { return section.querySelectorAll(selector); },
        createElement: function (name) { return page.createElement(name); },
        createTextNode: function (text) { return page.createTextNode(text); },
        body: section
      });
    } catch (error) { window.onerror(String(error)); }
    charts += Number(section.getAttribute("data-charts") || 0);
  });
  page.body.setAttribute("data-charts", String(charts));
})();
"""


def _page_head(title: str, nav: str, style: str = "") -> str:
    return (
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
        f"<title>{_esc(title)}</title>\n<style>{_static('uPlot.min.css')}\n{_static('report.css')}</style>\n"
        "<script>window.reportErrors=[];window.onerror=function(m,s,l,c,e){window.reportErrors.push(String(m));"
        "var d=document.getElementById('errors');if(d){d.textContent=window.reportErrors.join('\\n');}};</script>\n"
        f"{style}</head><body><h1>{_esc(title)}</h1><pre id=\"errors\"></pre>" + nav
    )


def _page_tail(script: str) -> str:
    return (
        f"<script>/* uPlot 1.6.31, (c) Leon Sorokin, MIT licence */\n{_static('uPlot.iife.min.js')}</script>\n"
        f"<script>{script}</script>\n</body></html>\n"
    )


def _bus_pieces(collector: ReportCollector, stats: StatsCollector, extras: dict[str, Any], anchor: str = "",
                block: str = "report-data") -> Iterator[str]:
    """One bus's sections (the first piece, made before any is written), then its data block's pieces.
    `anchor` prefixes its ids (a page of several buses), `block` is its data block's id."""
    bus, health = extras.get("bus"), extras.get("health")
    give_back()  # (the decoding's freed memory: the page's objects are made next)
    data = collector.data(points=False)
    when = _clock(data, extras.get("time_format", "r"), collector.nanos)
    summary = stats.report(with_parameters=False)  # parameters: the collector draws its own
    slaves = _slaves(stats)
    data["slaves"] = [
        {"slave": entry["slave"], "time": entry["time"]} for entry in slaves
    ]
    parts: list[str] = []
    duration = summary["duration"]
    heard = summary["frames"] or summary["noise"]["items"]  # (nothing: no time to tell, nor any x axis)
    parts.append(
        f"<p class=\"summary\">{count_text(summary['frames'], 'frame')}, "
        f"{count_text(summary['noise']['bytes'], 'noise byte')} in {count_text(summary['noise']['items'], 'run')}"
        + (f", {duration:.3f} s" if duration is not None else ", no timestamps (x axis: frame number)" if heard else "")
        + (f", from {_esc(merged_text(stats.captures))}" if len(stats.captures) > 1 else "")  # one bus, said
        + "</p>"
    )
    # -- slaves
    parts.append(f'<h2 id="{anchor}slaves">Slaves</h2>')
    if summary["profiles"]:
        parts.append("<h3>Device profiles</h3>" + _table(["slave", "profile", "why"], [
            [choice["slave"], choice["profile"], choice["reason"]]  # (it names the frame that decided it)
            for choice in summary["profiles"]
        ]))
    rows = []
    for entry in slaves:
        exceptions = exception_counts(entry["exceptions"])
        time = entry["time"] or {}
        rows.append([entry["slave"], entry["requests"], entry["responses"], exceptions, entry["unanswered"],
                     entry["crc_errors"], _ms(time.get("min")), _ms(time.get("median")),
                     _ms(time.get("p95")), _ms(time.get("max"))])
    parts.append(_table(["slave", "requests", "responses", "exceptions (code:count)", "unanswered",
                         "CRC errors", "min ms", "median ms", "p95 ms", "max ms"], rows, "numbers"))
    for entry in slaves:
        if entry["time"] is not None:
            parts.append(
                f'<div class="chart rt" data-slave="{entry["slave"]}"><h3>Slave {entry["slave"]}: response '
                f'times (ms), {entry["time"]["count"]} answers</h3></div>'
            )
    parts.extend(bus_section(data, bus, health, when, anchor))
    function_rows = [
        [row["slave"], f"{row['function']} {row['function_name']}", row["requests"], row["responses"],
         exception_counts(row["exceptions"]), row["unanswered"],
         row["crc_errors"]]
        for row in summary["functions"]
    ]
    parts.append("<details><summary>per function</summary>" + _table(
        ["slave", "function", "requests", "responses", "exceptions", "unanswered", "CRC errors"],
        function_rows, "numbers") + "</details>")
    # -- poll cycle
    parts.append(f'<h2 id="{anchor}poll">Poll cycle</h2>')
    poll = summary["poll_cycle"]
    if poll:
        parts.append(_table(
            ["slave", "function", "addresses", "count", "period ms", "jitter ms", "skipped", "no answer", "misses"],
            [[row["slave"], f"{row['function']} {SPEC.function_name(row['function'])}", stats.poll_addresses(row),
              row["count"], _ms(row["period"]), _ms(row["jitter"]), row["skipped"], row["no_answer"],
              row["misses"]] for row in poll],
            "numbers",
        ))
        parts.append('<p class="note">Requests repeated 3 times or more. period: median interval; jitter: '
                     'largest deviation from it; skipped: cycles missing (intervals of 1.5 periods or more); '
                     'no answer: unanswered or refused; misses: both.</p>')
    else:
        parts.append("<p>No request repeats 3 times or more.</p>")
    # -- events
    parts.append(f'<h2 id="{anchor}events">Events</h2>')
    counts = data["event_counts"]
    parts.append("<p>" + ", ".join(f"{kind}: {counts[kind]}" for kind in EVENT_KINDS) + "</p>")
    parts.append('<div class="chart timeline"></div>')
    parts.extend(event_groups(collector, data, when))
    # -- parameters
    parts.append(f'<h2 id="{anchor}parameters">Parameters</h2>')
    single = single_values(collector, data)
    parts.extend(parameter_index(data, single, anchor, single_counts(stats.store, data, single)))
    exact = [series.marks for _key, series in collector.drawn_series()]  # (data's x are rounded to us)
    for index, parameter in enumerate(data["parameters"]):
        if index in single:
            continue
        code = parameter["code"]
        shown = parameter.get("label") or str(parameter["address"])  # as --address-style shows it
        head = f"{code} ({shown})" if code else shown
        extra = ", ".join(filter(None, [parameter["name"], unit_heading(parameter["unit"]),
                                         "steps" if parameter["step"] else None]))
        marks = "".join(
            f'<li class="mark" data-x="{x}">{_esc(when(at))}: {_esc(text)}</li>'
            for (x, text), (at, _text) in zip(parameter["marks"], exact[index])
        )
        if parameter["marks_dropped"]:
            marks += f"<li>… {parameter['marks_dropped']} more</li>"
        parts.append(
            f'<div class="chart trend" id="{anchor}p{index}" data-index="{index}" data-code="{_esc(code or "")}">'
            f'<h3>Slave {parameter["slave"]}: <span class="code">{_esc(head)}</span> '
            f'<small>{_esc("; ".join(filter(None, [extra, str(parameter["values"]) + " values"])))}</small></h3>'
            + (f'<ul class="marks">{marks}</ul>' if marks else "")
            + "</div>"
        )
    if data["parameters_dropped"]:
        parts.append(f"<p class=\"note\">Only the first {len(data['parameters'])} parameters are drawn; "
                     f"{data['parameters_dropped']} values of others are in --stats.</p>")
    drawn = {(parameter["slave"], parameter["address"], parameter["table"])  # (their points are written
             for parameter in data.pop("parameters")}  # series by series)
    data["clock"] = extras.get("time_format", "r")
    data["first"] = collector.first_x
    if health is not None:  # slave:address of the series drawn that requests asked to write, as the
        # parameter table counts them: setpoints, drawn as steps, since one holds until the next write
        # (report.js asks of no other: the max-size mix's 26,402 were 1.7 MB of text, 260 kB of the page)
        # (Holding registers only: no code writes an input register.)
        writes = stats.store.writes
        data["written"] = sorted("%d:%d" % (slave, address) for slave, address, table in drawn
                                 if table == TABLE_NAMES[HOLDING_REGISTERS] and writes(slave, address))
    # The response-time series come as JSON text (health.py): written in where their key is, the last
    # occurrence of the stand-in (only "clock", "first" and "written" come after it).
    responses = data.get("responses")
    if responses is not None:
        data["responses"] = _STAND_IN
    head = json.dumps(data, separators=(",", ":"), allow_nan=False)
    # Every `<` as \u003c (only JSON strings hold one): neither `</script>` nor `<!--` from a map's
    # text can end the block or swallow the page's scripts (piece by piece: the same text).
    yield "\n".join(parts)
    del parts
    yield f'\n<script type="application/json" id="{block}">'
    if responses is None:
        yield head[:-1].replace("<", "\\u003c")
    else:
        at = head.rindex(_STAND_IN_JSON)
        yield head[:at].replace("<", "\\u003c") + "["
        for index, entry in enumerate(responses):
            x, y = entry["points"]()  # (health.py: made now, one slave's at a time)
            yield ("," if index else "") + f'{{"slave":{entry["slave"]},"answers":{entry["answers"]},"x":{x},"y":{y}}}'
            del x, y
        yield "]" + head[at + len(_STAND_IN_JSON):-1].replace("<", "\\u003c")
    del responses
    yield ',"parameters":'
    for piece in collector.parameters_json_pieces():
        yield piece.replace("<", "\\u003c")
    yield "}</script>\n"


def write_report(
    stream: TextIO, path: str, collector: ReportCollector, stats: StatsCollector, title: str | None = None,
    extras: dict[str, Any] | None = None,
) -> None:
    """Write and close the report (opened by the caller before decoding, so a bad path fails first)."""
    write_pieces(stream, path, report_pieces(collector, stats, title or "vw3-decode report", extras))


def write_pieces(stream: TextIO, path: str, pieces: Iterator[str]) -> None:
    """Write a page piece by piece and close its file (a page of one bus or of several)."""
    try:
        with stream:
            for piece in pieces:
                stream.write(piece)
    except OSError as error:
        raise OutputError(f"--report {path}: {error.strerror or error}") from None
