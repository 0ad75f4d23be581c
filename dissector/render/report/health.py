"""What the report adds for slave health (issue 29), collected from every item heard, bounded memory:

- per slave, its response times against time, downsampled per pixel column (first, lowest, highest and
  last point of each column, as the parameter trends: a single slow answer survives; doubled and merged
  as they are, COLUMNS + 1 columns a slave at most), drawn with the slave's outages
  (render/bustiming.py) as bands;
- the bus load per minute (bustiming);
- events grouped (groups.py).
"""
from __future__ import annotations

import json
from typing import Any

from dissector.model import Item, Kind
from dissector.render.report.collect import COLUMNS, TIMED_WIDTH, drawn, new_columns


class Health:
    """Response times per slave over time; fed every item in order."""

    def __init__(self) -> None:
        self.origin: float | None = None
        self.width = TIMED_WIDTH
        self.limit = 0.0
        self.series: dict[int, Any] = {}

    def add_items(self, items: list[Item]) -> None:
        for item in items:
            if item.kind is Kind.NOISE:
                continue
            frame = item
            if not frame.crc_ok or frame.kind is Kind.REQUEST:  # type: ignore[union-attr]
                continue
            seconds = frame.response_time  # type: ignore[union-attr]
            if seconds is not None and seconds >= 0:  # (stamped before its request: left out, as bustiming does)
                self._point(frame.slave, frame.time, seconds)  # type: ignore[union-attr, arg-type]

    def _point(self, slave: int, x: float, y: float) -> None:
        if self.origin is None:
            self.origin = x
            self.limit = x + COLUMNS * self.width
        while x >= self.limit:
            self._double()
        columns = self.series.get(slave)
        if columns is None:
            columns = self.series[slave] = new_columns()
        columns.add(max(0, int((x - self.origin) / self.width)), x, y)

    def _double(self) -> None:
        """As ReportCollector._double: at COLUMNS columns, merged at once (they were let grow to 3 x COLUMNS,
        247 slaves' 32 MB at 1 GB, issue 28)."""
        self.width *= 2
        self.limit = self.origin + COLUMNS * self.width  # type: ignore[operator]
        for columns in self.series.values():
            columns.close()
            if len(columns) > COLUMNS // 2:
                columns.compact(self.origin, self.width)  # type: ignore[arg-type]

    def response_series(self, origin: float, width: float, answers: dict[int, int]) -> list[dict[str, Any]]:
        """Per slave its answers and `points`: a call that gives x (relative to the report's origin) and y
        (ms), in the report's columns, as the page's JSON text of each list. html.py calls it as it
        writes the slave's series: one slave's text at a time (247 slaves' took 13 MB at once, issue 28).
        `answers`: per slave the answers with a response time, as bustiming counts them (the same answers
        make this slave's points: a good CRC and a response time; counted once, there)."""
        return [{"slave": slave, "answers": answers[slave],
                 "points": lambda columns=self.series[slave]: self._drawn_json(columns, origin, width)}
                for slave in sorted(self.series)]

    def _drawn_json(self, columns: Any, origin: float, width: float) -> tuple[str, str]:
        columns.close()
        columns.compact(origin, max(width, self.width))
        points = columns.drawn_json(origin, 6, 1000.0, 3)
        if points is None:  # a value json.dumps refuses: its error
            points = [json.dumps(values, allow_nan=False) for values in drawn(columns, origin, 6, 1000.0, 3)]
        return points[0], points[1]
