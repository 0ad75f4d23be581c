"""`--parquet DIR`: the bus as three tables any engine reads (DuckDB, Polars, pandas, Spark).

DIR/frames/, DIR/registers/ and DIR/events/ each get one file per capture, `NAME-HASH.parquet` (the
capture's file name and 8 hex digits of its absolute path, so captures of the same name in two folders do
not overwrite each other, and a capture decoded again replaces its own files). Every row starts with
`capture`, that absolute path (what tells line1/bus.pcap from line2/bus.pcap), and `file`, the name of
the file of a ring buffer it came from. Rows are made from the
NDJSON records (`render.jsonout.item_to_dict`) and `-T registers`' rows (`render.registers`), so the
dataset says what `--json` says. Types are real: times are `timestamp[us, UTC]`, response times
`double` seconds, codes `string`, absent values null. The schema (SCHEMAS) is in README.md.

pyarrow is an optional dependency: `pip install 'vw3-dissector[data]'`.
"""
from __future__ import annotations

import bisect
import hashlib
import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from dissector.errors import UsageError
from dissector.model import Item, Stamp
from dissector.render.history import UNREADABLE_STATUSES
from dissector.render.describe import count_text
from dissector.render.jsonout import item_to_dict
from dissector.render.registers import register_rows
from dissector.render.stats_store import register_table

ROWS_PER_GROUP = 1 << 16  # rows kept before a row group is written: memory stays flat
TABLES = ("frames", "registers", "events")
NOUNS = ("frame", "register", "event")  # (each table's row, for the line said of a capture)


def rows_text(rows: dict[str, int]) -> str:
    """`12 frames, 1 register, 0 events`: the rows written to each table, singular for one (describe.count_text)."""
    return ", ".join(count_text(rows[table], noun) for table, noun in zip(TABLES, NOUNS))


def need_pyarrow() -> Any:
    """The pyarrow module, or a UsageError naming the extra that brings it."""
    try:
        import pyarrow
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise UsageError("--parquet needs pyarrow: pip install 'vw3-dissector[data]'") from None
    return pyarrow


def schemas() -> dict[str, Any]:
    pa = need_pyarrow()
    time = pa.timestamp("us", tz="UTC")
    text = pa.string()
    common = [("capture", text), ("file", text)]
    return {
        "frames": pa.schema(common + [
            ("frame", pa.int64()), ("kind", text), ("time", time), ("offset", pa.int64()), ("length", pa.int32()),
            ("mode", text), ("slave", pa.int16()), ("function", pa.int16()), ("function_name", text),
            ("crc_ok", pa.bool_()), ("crc", pa.int32()), ("crc_expected", pa.int32()), ("broadcast", pa.bool_()),
            ("start", pa.int32()), ("quantity", pa.int32()), ("subfunction", pa.int32()),
            ("exception_code", pa.int16()), ("exception_name", text), ("exception_meaning", text),
            ("request_frame", pa.int64()), ("response_time", pa.float64()), ("response_frame", pa.int64()),
            ("unanswered", pa.bool_()), ("reason", text), ("raw", pa.binary()),
            ("warnings", pa.list_(text)), ("notes", pa.list_(text)), ("comments", pa.list_(text)),
        ]),
        "registers": pa.schema(common + [
            ("frame", pa.int64()), ("time", time), ("slave", pa.int16()), ("function", pa.int16()),
            ("access", text), ("address", pa.int32()), ("label", text), ("code", text), ("name", text),
            ("value", pa.int64()), ("scaled", pa.float64()), ("unit", text), ("status", text), ("text", text),
            ("words", pa.int8()),  # --json's `words` (absent there: 1); null for a coil or input bit
            ("write", text), ("exception_code", pa.int16()),  # -T registers' (registers.write_outcome)
        ]),
        "events": pa.schema(common + [
            ("kind", text), ("time", time), ("end", time), ("frame", pa.int64()), ("last_frame", pa.int64()),
            ("slave", pa.int16()), ("function", pa.int16()), ("address", pa.int32()), ("code", text),
            ("status", text), ("exception_code", pa.int16()), ("requests", pa.int64()), ("bytes", pa.int64()),
            ("text", text),
        ]),
    }


def microseconds(time: float | None) -> int | None:
    if time is None:
        return None
    if isinstance(time, Stamp):
        return (time.ns + 500) // 1000  # (rounded, as the text's times and --json's are)
    return round(time * 1_000_000)


def file_stem(capture_path: str) -> str:
    """`NAME-HASH` of an absolute capture path: its file name and 8 hex digits of the path."""
    base = os.path.basename(capture_path) or "capture"
    digest = hashlib.sha1(capture_path.encode()).hexdigest()[:8]
    safe = "".join(char if char.isalnum() or char in "._-" else "_" for char in base)
    return f"{safe}-{digest}"


class _Table:
    """Rows of one table, written as row groups of a ParquetWriter opened on first need."""

    def __init__(self, path: str, schema: Any) -> None:
        self.path = path
        self.schema = schema
        self.names = tuple(schema.names)
        # What a row without the column gets: null, but an empty list for a list column (a noise run's
        # record has no `notes`: it has none, as a frame with none has [], never "unknown").
        import pyarrow as pa

        self.absent = tuple([] if pa.types.is_list(column.type) else None for column in schema)
        self.pending: list[tuple[Any, ...]] = []  # rows in schema order, made into columns per row group
        self.rows = 0
        self.writer: Any = None

    def add(self, row: dict[str, Any]) -> None:
        pending = self.pending
        pending.append(tuple(map(row.get, self.names, self.absent)))  # absent keys: null, or []
        if len(pending) >= ROWS_PER_GROUP:
            self.flush()

    def flush(self) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq

        if self.writer is None:
            self.writer = pq.ParquetWriter(self.path + ".part", self.schema, compression="zstd")
        if not self.pending:
            return
        schema = self.schema
        arrays = [pa.array(column, type=schema.field(index).type) for index, column in enumerate(zip(*self.pending))]
        self.writer.write_table(pa.Table.from_arrays(arrays, schema=schema))
        self.rows += len(self.pending)
        self.pending = []

    def close(self) -> None:
        self.flush()  # a table with no row is still a file with its schema: queries find every table
        self.writer.close()
        os.replace(self.path + ".part", self.path)  # readers never see half a file

    def abandon(self) -> None:
        if self.writer is not None:
            try:
                self.writer.close()
            finally:
                if os.path.exists(self.path + ".part"):
                    os.remove(self.path + ".part")


@dataclass(slots=True)
class CaptureTables:
    """The three tables of one capture; `add` takes its items in stream order."""

    directory: str
    capture: str  # the `capture` column: the capture's absolute path
    stem: str
    tables: dict[str, _Table] = field(default_factory=dict)
    # slave -> each code's register table on its device (stats_store.slave_tables; None: the protocol's)
    register_tables: Callable[[int], bytes] | None = None
    # (first byte offset in the capture's stream, file name) per file, in order: an item is in the file
    # its first byte came from (the framer and the pairer hand items on later than their bytes).
    files: list[tuple[int, str]] = field(default_factory=list)
    _state: dict[tuple[int, int], str] = field(default_factory=dict)  # readable / protected / non-existent
    _common: dict[str, str | None] = field(default_factory=dict)  # capture and file of the item at hand

    def __post_init__(self) -> None:
        for name, schema in schemas().items():
            folder = os.path.join(self.directory, name)
            os.makedirs(folder, exist_ok=True)
            self.tables[name] = _Table(os.path.join(folder, self.stem + ".parquet"), schema)

    def file_of(self, offset: int) -> str | None:
        files = self.files
        if not files:
            return None
        index = bisect.bisect_right(files, (offset, "\uffff")) - 1
        return files[max(index, 0)][1]

    def add(self, items: Iterable[Item], comments: dict[int, list[str]] | None = None) -> None:
        """`comments`: the input's packet comments of the items that have some, by id(item) (--json's)."""
        frames, registers = self.tables["frames"], self.tables["registers"]
        for item in items:
            common = {"capture": self.capture, "file": self.file_of(item.offset)}
            self._common = common
            record = item_to_dict(item, fields=False)  # the NDJSON record but its `fields`, not stored
            time = microseconds(item.time)
            row = dict(record, **common, time=time)
            row["raw"] = item.raw
            if comments and id(item) in comments:
                row["comments"] = comments[id(item)]
            frames.add(row)
            if "registers" in record or "bits" in record:
                words = [element.get("words", 1) for element in record.get("registers") or []]
                for index, register in enumerate(register_rows(record, item)):  # (registers first, then bits)
                    register["words"] = words[index] if index < len(words) else None
                    register.update(common, time=time)
                    registers.add(register)
                    self._status(register, time)
            self._events(record, time)

    def _event(self, kind: str, time: int | None, file: str | None = None, **values: Any) -> None:
        common = {"capture": self.capture, "file": file} if file is not None else self._common
        self.tables["events"].add({**common, "kind": kind, "time": time, **values})

    def _status(self, row: dict[str, Any], time: int | None) -> None:
        """A parameter that turns unreadable (its status) or readable again: reads and exceptions."""
        if row["access"] not in ("read", "exception") or row["address"] is None or row["status"] is None:
            return  # (no status: none judged, as of a frame that failed its check: it tells nothing)
        slave, function = row["slave"], row["function"]
        tables = self.register_tables
        table = register_table(function) if tables is None else tables(slave)[function]
        key = (slave, table, row["address"])  # a parameter, as the history's
        status = row["status"]
        before = self._state.get(key)
        now = status if status in UNREADABLE_STATUSES else "readable"
        if now == before or (now == "readable" and before is None):
            self._state[key] = now
            return
        self._state[key] = now
        kind = "readable-again" if now == "readable" else now
        self._event(kind, time, frame=row["frame"], slave=row["slave"], function=row["function"],
                    address=row["address"], code=row["code"], status=status,
                    text=f"{row['code'] or row['address']} {kind}" + (f" (before: {before})" if before else ""))

    def _events(self, record: dict[str, Any], time: int | None) -> None:
        frame, slave, function = record["frame"], record.get("slave"), record.get("function")
        kind = record["kind"]
        if kind == "noise":
            self._event("noise", time, frame=frame, bytes=record["length"], text=record["reason"])
        elif not record["crc_ok"]:
            self._event("crc", time, frame=frame, slave=slave, function=function,
                        text=f"CRC received 0x{record['crc']:04X}, expected 0x{record['crc_expected']:04X}")
        elif kind == "exception":
            self._event("exception", time, frame=frame, slave=slave, function=function,
                        exception_code=record["exception_code"],
                        text=record.get("exception_meaning") or record["exception_name"])
        for warning in record["warnings"]:
            if warning.startswith("silence"):
                self._event("silence", time, frame=frame, slave=slave, function=function, text=warning)

    def outages(self, outages: Iterable[Any]) -> None:
        for outage in outages:
            self._event("outage", microseconds(outage.start), file=self.file_of(outage.offset), end=microseconds(outage.end), frame=outage.first_frame,
                        last_frame=outage.last_frame, slave=outage.slave, requests=outage.requests,
                        text=f"slave {outage.slave}: {outage.requests} requests unanswered")

    def close(self) -> dict[str, int]:
        for table in self.tables.values():
            table.close()
        return {name: table.rows for name, table in self.tables.items()}

    def abandon(self) -> None:
        """Remove what this capture wrote. Its table folders stay: another capture's worker may have made
        them and be about to write there (remove_empty_tables, once every worker is done)."""
        for table in self.tables.values():
            table.abandon()


def remove_empty_tables(directory: str) -> None:
    """The table folders no capture wrote into (every capture refused): a refused run leaves no dataset."""
    for name in schemas():
        try:
            os.rmdir(os.path.join(directory, name))  # only when empty: captures' files stay
        except OSError:
            pass
