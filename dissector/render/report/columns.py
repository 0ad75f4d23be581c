"""--report's pixel columns of one series (collect.py's trends, health.py's response times): each column of
the x axis keeps its first, lowest, highest and last point; the compiled twin is dissector/accel/_columns.h."""
from __future__ import annotations

import json
import os
from array import array
from operator import itemgetter
from typing import Any

Y_DIGITS = 6  # a y not whole is drawn rounded to this many places

try:  # the same columns in C (dissector/accel/_columns.h): add() runs once per register value
    from dissector.accel._summary import Columns as CompiledColumns
except ImportError:  # built without a C compiler
    CompiledColumns = None

class Columns:
    """Per-column first/min/max/last points of one series, 8 doubles a column (fx fy nx ny mx my lx ly)
    in a flat array: a few hundred series of 1,600 columns stay within a few tens of MB."""

    __slots__ = ("done", "col")

    def __init__(self) -> None:
        self.done = array("d")
        self.col = -1  # the column the last 8 doubles are, while it is open; -1 once closed

    def add(self, col: int, x: float, y: float) -> None:
        done = self.done
        if col != self.col:
            self.col = col
            done.extend((x, y, x, y, x, y, x, y))
            return
        base = len(done) - 8
        if y < done[base + 3]:
            done[base + 2] = x
            done[base + 3] = y
        elif y > done[base + 5]:
            done[base + 4] = x
            done[base + 5] = y
        done[base + 6] = x
        done[base + 7] = y

    def close(self) -> None:
        """End the current column (the column width is about to change)."""
        self.col = -1

    def __len__(self) -> int:
        return len(self.done) // 8

    def values(self) -> bytes:
        """The doubles as bytes, 8 a column (the compiled columns' too)."""
        return self.done.tobytes()

    def load(self, values: bytes | array) -> None:
        self.done = array("d", values)

    def compact(self, origin: float, width: float) -> None:
        """Merge the finished columns that fall in one column of `width` (widths only grow by
        doubling, so each old column lies within one new column)."""
        done, out = self.done, array("d")
        last = None
        for index in range(0, len(done), 8):
            col = int((done[index] - origin) / width)
            if col != last:
                out.extend(done[index : index + 8])
                last = col
                continue
            base = len(out) - 8
            if done[index + 3] < out[base + 3]:
                out[base + 2], out[base + 3] = done[index + 2], done[index + 3]
            if done[index + 5] > out[base + 5]:
                out[base + 4], out[base + 5] = done[index + 4], done[index + 5]
            out[base + 6], out[base + 7] = done[index + 6], done[index + 7]
        self.done = out

    def levels(self) -> tuple[float, float, float] | None:
        """The first, lowest and highest y kept, None when empty."""
        ys = self.done[1::2]
        return (ys[0], min(ys), max(ys)) if ys else None

    def drawn_json(self, origin: float, digits: int, scale: float = 0.0, places: int = 0) -> tuple[str, str]:
        """drawn()'s two lists as the page's JSON text (the compiled columns write it themselves)."""
        xs, ys = drawn(self, origin, digits, scale, places)
        return compact_json(xs), compact_json(ys)

    def points(self) -> tuple[list[float], list[float]]:
        """Each column's points in the order of their x, none before the last x kept (a time that went
        back), a run of equal values by its ends only.

        Several values at one x are all drawn, the first first and the last last: an FC23 read/write
        writes a register and reads it back in one transaction, at its answer's time, and the trend steps
        from the value written to the value read back, the parameter's state after it (what the summary
        line and --stats' `last` say), as an IO graph shows two samples of one time. Of a column's first,
        lowest, highest and last point (sorted by x, those at one x kept in that order), a lowest or
        highest point equal to the first or the last is that point, not drawn twice; the last point is
        drawn after the others even when it equals the first (a value left and come back to)."""
        done = self.done
        xs: list[float] = []
        ys: list[float] = []
        for index in range(0, len(done), 8):
            first, low, high, last = ((done[index + k], done[index + k + 1]) for k in (0, 2, 4, 6))
            ends = [first]
            if low != first and low != last:
                ends.append(low)
            if high != first and high != last and high != low:
                ends.append(high)
            if last != first or len(ends) > 1:
                ends.append(last)
            if len(ends) > 1:
                ends.sort(key=itemgetter(0))  # by x, stable: points at one x keep the order above
            for x, y in ends:
                if xs and (x < xs[-1] or (x == xs[-1] and y == ys[-1])):
                    continue
                # A run of equal values needs only its ends.
                if len(ys) >= 2 and ys[-1] == y and ys[-2] == y:
                    xs[-1] = x
                    continue
                xs.append(x)
                ys.append(y)
        return xs, ys

def drawn(columns: Any, origin: float, digits: int, scale: float = 0.0,
          places: int = 0) -> tuple[list[float], list[float | int]]:
    """The points of `columns` (either store's) as the page writes them: x relative to `origin`, y an int
    when whole; with a `scale`, each y times it rounded to `places` (health.py: seconds as ms). The compiled
    columns write these as JSON only (drawn_json): their points are Columns.points of their doubles."""
    if not isinstance(columns, Columns):
        python = Columns()
        python.load(columns.values())
        columns = python
    xs, ys = columns.points()
    if scale:
        return [round(x - origin, digits) for x in xs], [round(y * scale, places) for y in ys]
    return [round(x - origin, digits) for x in xs], [_number(y) for y in ys]


def new_columns() -> Any:
    """The compiled columns when the extension is built (and VW3_PURE_PYTHON is not set)."""
    if CompiledColumns is not None and not os.environ.get("VW3_PURE_PYTHON"):
        return CompiledColumns()
    return Columns()


def compact_json(value: Any) -> str:
    return json.dumps(value, separators=(",", ":"), allow_nan=False)


def _number(y: float) -> float | int:
    return int(y) if y.is_integer() else round(y, Y_DIGITS)
