"""How a trend reads its register's words (collect.py Series.row): as the map row of its slave's device
now, the one the file's decode, named with the last choice of profile `auto` throughout, reads them with.
When that row changes (the device chosen after values were drawn, or a choice taken back: standard input,
one pass), `adopt` reads the points kept again from their words, and the series' names, unit and steps.
A word is drawn as steps, named by labels, only where its row is an enumeration or a bit field: a row that
reads a number (scaled, signed, or with a unit and no scale) draws the number with its unit (`summary_text`
says it as the summary and --watch do, for the table of parameters with a single value)."""
from __future__ import annotations

from array import array
from typing import Any

from dissector.devices.maps import interpret
from dissector.model import Register
from dissector.protocol.rules import text as say_text
from dissector.render.stats_store import homes_of, table_label, table_reader
from dissector.render.watch import value_text

MAX_LABELS = 64  # an enumeration's or bit field's texts kept for the chart's axis


def remap(columns: Any, convert: Any) -> None:
    """Every y of `columns` through `convert` (a profile chosen later scales raw words); each column's
    lowest and highest points are found again, since a signed reading reorders them."""
    done = array("d", columns.values())
    for index in range(0, len(done), 8):
        points = [(done[index + k], convert(done[index + k + 1])) for k in (0, 2, 4, 6)]
        low = min(points, key=lambda point: point[1])
        high = max(points, key=lambda point: point[1])
        for k, (x, y) in enumerate((points[0], low, high, points[3])):
            done[index + 2 * k], done[index + 2 * k + 1] = x, y
    columns.load(done)


def adopt(series: Any, row: Any) -> None:
    """`row` (the map row the slave's device now names the series' address with; None: it names nothing
    there) becomes the series' reading: its names, its unit, and the points kept, each read again from its
    word as the row reads it (a profile chosen, or taken back, after values were drawn: they are drawn as
    the file, named with the last choice, draws them)."""
    old, series.row = series.row, row
    if old is not None and row is not None and old == row:  # the same row of a device built again
        return
    series.code, series.name = (None, None) if row is None else (row.code, row.name)
    series.unit, series.step, series.labels = None, False, {}
    columns = series.columns
    if not len(columns):
        return
    if (old is not None and old.words != 1) or (row is not None and row.words != 1):
        return  # a 32-bit value is read from two words: its points stay as they were read
    words: list[int] = []

    def again(y: float) -> float:
        word = word_of(old, y)
        words.append(word)
        return reading(row, word)[0] if scales(row) else float(word)  # type: ignore[return-value]

    remap(columns, again)
    if words:  # (the last column's last point: the last value)
        scaled, text = reading(row, words[-1])
        series.text = summary_text(Register(None, words[-1], unit=None if row is None else row.unit,
                                            scaled=scaled, text=text))
    if not labelled(row):
        series.unit = None if row is None else row.unit
        return
    for word in words:
        text = reading(row, word)[1]
        if text is not None:
            series.step = True
            if word not in series.labels and len(series.labels) < MAX_LABELS:
                series.labels[word] = text


def labelled(row: Any) -> bool:
    """The row names words rather than reading numbers: an enumeration or a bit field (drawn as steps)."""
    return row is not None and bool(row.enum or row.bits)


def summary_text(register: Register) -> str:
    """A value as the summary names it, with its unit (watch.py value_text: `4.0 kHz`, `Cd (command)`, a
    status word's bit names, an unscaled value's own text)."""
    text, unit = value_text(register)
    return text if unit is None else f"{text} {unit}"


def shown_unit(row: Any, unit: str | None) -> str | None:
    """The unit a trend's data gives (report.js: its axis label, each tooltip's `value unit`): what the
    value's text says after its number (watch.py value_text), `(unscaled, in s)` where the device's
    settings choose the row's scale (map scale `?`, maps.interpret: ACC/DEC), as the table says `10
    (unscaled, in s)`; else the unit."""
    if unit is None or row is None or not getattr(row, "scale_unknown", False):
        return unit
    return _unscaled(unit)


def _unscaled(unit: str) -> str:
    return say_text("unscaled", value=0, unit=unit).split(" ", 1)[1]  # (what follows the number, `0`)


def unit_heading(unit: str | None) -> str | None:
    """A trend's unit (shown_unit) as its heading says it: `in Hz`; unscaled, `unscaled, in s`."""
    if unit is None:
        return None
    return unit[1:-1] if unit.startswith(_UNSCALED) else f"in {unit}"


_UNSCALED = _unscaled("\0").split("\0")[0]  # `(unscaled, in `


def scales(row: Any) -> bool:
    """The row reads a word as a number (Register.scaled, maps.interpret): a scale, or a signed word."""
    return row is not None and not row.enum and not row.bits and (row.scale is not None or row.signed)


def reading(row: Any, word: int) -> tuple[float | int | None, str | None]:
    """The scaled value and text `row` reads `word` as (maps.interpret; None: no row, neither)."""
    if row is None:
        return None, None
    known = row.memo.get(word)
    return interpret(row, word) if known is None else known


def word_of(row: Any, y: float) -> int:
    """The word a point's y was read from with `row` (None, or a row that does not scale: y is the word)."""
    if not scales(row) or row.scale is None:
        return int(y) & 0xFFFF  # (a signed word without a scale: its value)
    guess = round(y / row.scale)
    for word in (guess, guess - 1, guess + 1):
        if interpret(row, word & 0xFFFF)[0] == y:
            return word & 0xFFFF
    return guess & 0xFFFF


def rehome(series: dict[tuple[int, int, int], Any], slave: int, homes: bytes, label: Any) -> None:
    """The slave's series (by slave, address, table) moved to the table homes gives the protocol tables of the
    codes that drew them (Series.origins; History._rehome: as the store moves its parameters), joined to the
    series kept there; `label`: the annotator's PLC-style labels (--address-style plc), or None. A series two
    tables' codes drew, where those are apart now (a choice taken back), stays: its points cannot be parted."""
    for key in [key for key in series if key[0] == slave]:
        tables = homes_of(series[key].origins or 1 << key[2], homes)
        if len(tables) != 1 or min(tables) == key[2]:
            continue
        moved, home = series.pop(key), (slave, key[1], min(tables))
        moved.label = table_label(label and label(slave, table_reader(home[2]), key[1]), home[2], key[1])
        if home in series:
            join(series[home], moved)
        else:
            series[home] = moved


def join(kept: Any, moved: Any) -> None:
    """`moved` (a series of the same parameter, kept in another table before its slave's device was chosen:
    History._rehome) joined to `kept`: its points, marks and counts; each column's points in the order of
    their first x (Columns.points draws them so)."""
    done = array("d", kept.columns.values())
    more = array("d", moved.columns.values())
    groups = sorted((done[at : at + 8] for at in range(0, len(done), 8)), key=lambda group: group[0])
    groups = sorted(groups + [more[at : at + 8] for at in range(0, len(more), 8)], key=lambda group: group[0])
    kept.columns.load(array("d", [value for group in groups for value in group]))
    kept.columns.close()  # (its last group may be another column's now)
    kept.values += moved.values
    kept.origins |= moved.origins
    kept.marks = sorted(kept.marks + moved.marks, key=lambda mark: mark[0])
    kept.marks_dropped += moved.marks_dropped
    for value, text in moved.labels.items():
        if len(kept.labels) < MAX_LABELS:
            kept.labels.setdefault(value, text)
    if kept.code is None:
        kept.code, kept.name, kept.unit, kept.step = moved.code, moved.name, moved.unit, moved.step
    if kept.text is None:
        kept.text = moved.text
