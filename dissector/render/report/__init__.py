"""`--report FILE`: one self-contained HTML page of a capture (see collect.py and html.py)."""
from __future__ import annotations

import os

from dissector.errors import UsageError
from dissector.render.capturefile import regular_file
from dissector.render.report.collect import ReportCollector
from dissector.render.report.html import buses_pieces, render_report, write_pieces, write_report
from dissector.render.stats import StatsCollector

__all__ = ["ReportCollector", "ReportFile", "render_report", "write_report"]


class ReportFile:
    """The report being collected and the file it goes to, opened first so that a bad path fails
    before the capture is decoded (as -w does)."""

    def __init__(self, path: str, annotate: object, titles: list[str], stats: StatsCollector | None = None) -> None:
        self.path = path
        # The run's statistics and their parameter history (render/history.py): the report draws
        # what they count.
        self.stats = stats if stats is not None else StatsCollector(getattr(annotate, "choices", None))
        self.collector = ReportCollector(annotate, self.stats.history)
        self.title = "vw3-decode report: " + ", ".join(titles) if titles else None
        try:
            self.stream = open(path, "w", encoding="utf-8")
        except OSError as error:
            raise UsageError(f"--report {path}: {error.strerror or error}") from None

    def write(self, stats: StatsCollector, extras: dict | None = None) -> None:
        write_report(self.stream, self.path, self.collector, stats, self.title, extras)

    def write_buses(self, buses: list[tuple[str, ReportCollector, StatsCollector, dict]]) -> None:
        """The page of several buses (render/buses.py): per bus its name, collector, statistics and extras."""
        write_pieces(self.stream, self.path, buses_pieces(buses, self.title or "vw3-decode report"))

    def abandon(self, discard: bool = False) -> None:
        """Close the file; `discard`: the input was refused, and the report (written only at the end)
        is removed rather than left empty."""
        try:
            self.stream.close()
        except OSError:
            pass
        if discard and regular_file(self.path):  # not a symlink, not /dev/stdout
            try:
                os.unlink(self.path)
            except OSError:
                pass
