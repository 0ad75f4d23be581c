"""What a live capture shows, as a file decode shows it: -Y, -V, -x, -T fields and -T registers.

The options are checked as for files (options.decode_options: contradictions refused in one line, a
bad filter exit 2 before the port is opened), then the display sink is wrapped:
- `FilteredSink`: -Y, with the time references (time_relative, time_delta) of every item heard, and
  the codes of the run's maps for its suggestions; the live view's counters still count everything;
- `TextSink`: items written by the file decode's own writer (render/output.py Output: the detail tree,
  hex dumps, -T fields and -T registers lines), line by line through the live view's output pump.
"""
from __future__ import annotations

import io
from collections.abc import Callable
from typing import Any, TextIO

from dissector.app.live_view import PumpedSink
from dissector.model import Item
from dissector.render.filters import FilterContext, compile_filter
from dissector.render.jsonout import item_to_dict
from dissector.render.output import Output, OutputOptions


class TextSink(PumpedSink):
    """Items written by the file decode's own writer, line by line through the pump."""

    def __init__(self, out: TextIO, options: OutputOptions, err: TextIO | None = None) -> None:
        super().__init__(out)
        self._text = io.StringIO()
        notice = None if err is None else (lambda text: (err.write(f"vw3-decode: {text}\n"), err.flush()))
        self.output = Output(options, self._text, False, notice)

    def observe(self, items: list[Item]) -> None:
        """Every item heard, before -Y: the time column's references."""
        self.output.clock.observe(items)

    def show(self, items: list[Item]) -> None:
        if items:
            if self.output.clock.format == "d" or self.output.clock.deltas:
                self.output.clock.keep(items)
            self.output.write(items)
        self.output.flush()
        text = self._text.getvalue()
        if text:
            self._text.seek(0)
            self._text.truncate()
            self._pump.put(text[:-1].split("\n") if text.endswith("\n") else text.split("\n"))


class FilteredSink:
    """-Y in front of any live sink."""

    def __init__(self, inner: Any, text: str, annotate: object = None) -> None:
        self.inner = inner
        self.context = FilterContext.of(annotate)
        self.predicate: Callable[[dict], bool] = compile_filter(text, self.context)
        self._last: float | None = None

    @property
    def failed(self) -> BaseException | None:
        return self.inner.failed

    @property
    def dropped(self) -> int:
        return self.inner.dropped

    def observe(self, items: list[Item]) -> None:
        context = self.context
        previous: dict[int, float | None] = {}
        for item in items:
            if item.time is None:
                continue
            if context.first is None:
                context.first = item.time
            previous[item.number] = self._last
            self._last = item.time
        context.previous = previous
        observe = getattr(self.inner, "observe", None)
        if observe is not None:
            observe(items)

    def show(self, items: list[Item]) -> None:
        predicate = self.predicate
        self.inner.show([item for item in items if predicate(item_to_dict(item))])

    def tick(self) -> None:
        self.inner.tick()

    def close(self) -> None:
        self.inner.close()
