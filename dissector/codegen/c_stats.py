"""The --stats and --report store's constants as C, for the part of accel/_tables.h that _stats.h, _bus.h and
_report.h read: the parameter events and what each does, the kinds of tallies and the engine's count keys
(render/stats_store.py), the bus timing's buckets and gap edges (render/bustiming.py). Stated once in
Python, where the pure-Python stages (the reference under VW3_PURE_PYTHON=1) read them too.
"""
from __future__ import annotations

from dissector.render import bustiming, pollcycle, stats_store
from dissector.render.report import collect

# The compiled store's Param.counts by PARAM_*: ParameterStats' counts (render/stats_store.py), in the order of
# the rows' count columns (ParameterRow: reads..refused at 3..6, changes at 9). (Kept out of stats_store's
# module: a tuple more there moved the cyclic collector's passes and --report's peak RSS by 1.1 MB.)
COUNTERS = ("reads", "unreadable", "writes", "refused", "changes")


def _enum(prefix: str, names: dict[str, int], count: str | None = None) -> str:
    items = [f"{prefix}{name} = {value}" for name, value in sorted(names.items(), key=lambda item: item[1])]
    return "enum { " + ", ".join(items + ([f"{count} = {len(names)}"] if count else [])) + " };"


def render() -> list[str]:
    tallies = {name[len("TALLY_"):]: value for name, value in vars(stats_store).items() if name.startswith("TALLY_")}
    counts = {name[len("COUNT_"):]: value for name, value in vars(stats_store).items() if name.startswith("COUNT_")}
    return [
        "/* The --stats store's events, tallies and count keys (render/stats_store.py) and bus timing's",
        " * buckets (render/bustiming.py), for _stats.h, _bus.h and _report.h. */",
        _enum("EVENT_", {name: getattr(stats_store, name) for name in stats_store.EVENTS}, "EVENTS"),
        _enum("PARAM_", {name.upper(): k for k, name in enumerate(COUNTERS)}, "PARAM_COUNTS"),
        "/* By event: {the PARAM_* count it adds one to (-1: none), 1 when it sets the state}. */",
        "#define EVENT_RULES {" + ", ".join(
            f"{{{'-1' if counter is None else f'PARAM_{counter.upper()}'}, {int(state)}}}"
            for _event, (counter, state) in sorted(stats_store.EVENT_RULES.items())) + "}",
        _enum("TALLY_", tallies, "TALLIES"),
        _enum("COUNT_", counts),
        "#define TALLY_UNBOUNDED (" + " | ".join(f"1 << {kind}" for kind in stats_store.UNBOUNDED_TALLIES) + ")",
        f"#define TALLY_MAX_SHIFT {stats_store.MAX_SHIFT}",
        f"#define RESOLUTION {bustiming.RESOLUTION!r}",
        f"#define MINUTE {bustiming.MINUTE!r}",
        f"#define CLOSE_MARGIN {bustiming.CLOSE_MARGIN!r}",
        "static const double gap_edges_ms[] = {" + ", ".join(map(repr, bustiming.GAP_EDGES_MS)) + "};",
        "/* --report's pixel columns before a doubling, their first widths, a y's places and series drawn at most",
        " * (render/report/collect.py) and a poll interval's step (s) (render/pollcycle.py), for _report.h,",
        " * _columns.h and _stats.h. */",
        f"#define COLUMNS {collect.COLUMNS}",
        f"#define TIMED_WIDTH {collect.TIMED_WIDTH!r}",
        f"#define UNTIMED_WIDTH {collect.UNTIMED_WIDTH!r}",
        f"#define Y_DIGITS {collect.Y_DIGITS}",
        f"#define MAX_SERIES {collect.MAX_SERIES}",
        f"#define POLL_STEP {pollcycle.STEP!r}",
    ]
