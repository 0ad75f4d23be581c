"""dumpcap's ring buffer (`-w bus.pcap -b ...`): the files `bus_00001_2026...pcap`, `bus_00002_...` of one
capture. Every output reads them as tshark reads their mergecap: one stream, by file number (a request at
the end of one file pairs with its answer at the start of the next, frame numbers go on). --parquet
(app/jobs.py) and a text, --json, -T or --stats decode (app/inputs.py) group the files by this one rule.
"""
from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterator
from typing import Any

from dissector.errors import SourceError
from dissector.model import Chunk
from dissector.sources.common import name_text

# dumpcap's ring buffer names: PREFIX_NNNNN_YYYYMMDDHHMMSS.EXT
RING_NAME = re.compile(r"^(?P<prefix>.*)_(?P<number>\d{5,})_(?P<stamp>\d{14})(?P<suffix>\.[^./]*)?$")


def group_files(paths: list[str]) -> list[tuple[str, tuple[str, ...]]]:
    """(shown, files) per capture, in the order first named: a ring buffer's files (same folder, prefix
    and suffix) by file number, shown as `folder/PREFIX.EXT` (its one file's name when only one is
    given); any other path alone, as named (its bytes that are not UTF-8 as \\xNN: sources/common.py
    name_text). Files of several dumpcap runs under one name (a capture restarted in the same folder
    numbers its files from 00001 again) are one capture a run (_runs), each shown as its first file's
    name: read by number alone, the runs' files were one stream, interleaved."""
    rings: dict[tuple[str, str, str], list[tuple[int, str, str]]] = {}
    order: list[tuple[str, str] | tuple[str, str, str]] = []
    for path in paths:
        folder, base = os.path.split(path)
        match = RING_NAME.match(base)
        if match is None:
            order.append((path, ""))
            continue
        key = (folder, match["prefix"], match["suffix"] or "")
        if key not in rings:
            rings[key] = []
            order.append(key)
        rings[key].append((int(match["number"]), match["stamp"], path))
    groups = []
    for key in order:
        if len(key) == 2:
            groups.append((name_text(key[0]), (key[0],)))
            continue
        folder, prefix, suffix = key  # type: ignore[misc]
        runs = _runs(rings[key])  # type: ignore[index]
        for files in runs:
            whole = len(files) > 1 and len(runs) == 1
            groups.append((name_text(os.path.join(folder, prefix + suffix) if whole else files[0]), files))
    return groups


def _runs(entries: list[tuple[int, str, str]]) -> list[tuple[str, ...]]:
    """The files of each dumpcap run among (number, stamp, path) of one name: by number when no number
    comes twice; else in time order (the stamp, then the number), a new run where the number does not go
    up (dumpcap started again: 00001). The same file named twice is two runs, as any file named twice is
    two captures."""
    numbers = [number for number, _stamp, _path in entries]
    if len(set(numbers)) == len(numbers):
        return [tuple(path for _number, _stamp, path in sorted(entries))]
    runs: list[list[str]] = []
    previous = None
    for number, _stamp, path in sorted(entries, key=lambda entry: (entry[1], entry[0], entry[2])):
        if previous is None or number <= previous:
            runs.append([])
        runs[-1].append(path)
        previous = number
    return [tuple(run) for run in runs]


def missing_files(before: str, after: str) -> list[str]:
    """The warning for ring files missing between two of one run (numbers not one apart): the stream
    jumps over them, so a request at the end of `before` may show unanswered, or paired with an answer
    in `after`, where its own answer was in a missing file."""
    first, last = (int(RING_NAME.match(os.path.basename(path))["number"]) for path in (before, after))  # type: ignore[index]
    if last - first <= 1:
        return []
    numbers = f"file {first + 1:05d} is" if last - first == 2 else f"files {first + 1:05d}..{last - 1:05d} are"
    return [f"{before}: the ring buffer's {numbers} missing before {os.path.basename(after)}: what it held is "
            "not decoded, and a request at the end of this file may show no response or pair with a later answer"]


class RingSource:
    """The Sources (sources/reader.py) of a ring buffer's files as one: each file opened when the one
    before it ends. The first file's mode is the capture's (its framing); each file is opened as the
    first was (`open_file`), as --parquet does, so that a pcap's records stay readable in bulk."""

    def __init__(self, files: tuple[str, ...], open_file: Callable[[str], Any]) -> None:
        self.files = files
        self._open = open_file
        self.current = open_file(files[0])
        self.format, self.mode, self.name = self.current.format, self.current.mode, self.current.name
        self._units = self.current.time_units
        self.streaming = False
        self._warnings: list[str] = []
        self._defer = False  # (defer_damage)
        self._packets_before = 0  # the records of the files before the current one (packet_number)
        self._damage: SourceError | None = None  # a file the ring could not open, after the files before it

    @property
    def recorded_until(self) -> Any:
        """The last file's (read last): when the capture ends."""
        return self.current.recorded_until

    @property
    def packet_number(self) -> int | None:
        """The record number of the chunk given last, counted on from the files before (as in their mergecap -a,
        tshark's frame.number); None: not a pcap or pcapng."""
        number = getattr(self.current, "packet_number", None)
        return None if number is None else self._packets_before + number

    @property
    def packets_before(self) -> int:
        """The records of the files before the current one (its numbers go on from them)."""
        return self._packets_before

    def number_of(self, chunk: Chunk) -> int | None:
        """The record number of `chunk`, the next given (sources/reader.py Source.number_of), counted on."""
        number = self.current.number_of(chunk) if hasattr(self.current, "number_of") else None
        return None if number is None else self._packets_before + number

    @property
    def time_units(self) -> Any:
        """The first file's (dumpcap writes every file of a ring alike)."""
        return self._units

    def defer_damage(self) -> RingSource:
        """Damage in a file after the capture's first packets (a pcapng's corrupt block; a file that cannot be read
        at all, after the files before it) ends the capture there, kept in `damage` rather than raised: the decode
        shows the packets before it, then refuses the capture in one line (app/cli.py), as a single file's
        (sources/reader.py Source.defer_damage); the files after it are not read. Before, the ring was refused
        with nothing shown. Damage before the capture's first packet (in its first file) is raised as before."""
        self._defer = True
        self._defer_file(self.current)
        return self

    def _defer_file(self, source: Any) -> None:
        defer = getattr(source, "defer_damage", None) if self._defer else None
        if defer is not None:
            defer()

    @property
    def damage(self) -> SourceError | None:
        """Once read: what damaged the capture after its first packets (None: nothing)."""
        return self._damage or getattr(self.current, "damage", None)

    def take_warnings(self) -> list[str]:
        taken, self._warnings = self._warnings + self.current.take_warnings(), []
        return taken

    def __iter__(self) -> Iterator[Chunk]:
        for source in self.sources():
            yield from source

    def sources(self) -> Iterator[Any]:
        """Instead of iterating: each file's Source in turn, for a reader that takes a Source's parts
        (accel/records.py reads a pcap's records in bulk), its offsets and times going on across them."""
        try:
            yield self.current
            for before, path in zip(self.files, self.files[1:]):
                if self.damage is not None:  # (deferred: the capture ends at the damage)
                    return
                self._warnings += self.current.take_warnings()  # (a file's own, said as the next begins)
                self._warnings += missing_files(before, path)
                try:
                    opened = self._open(path)
                except SourceError as error:
                    if not self._defer:
                        raise
                    self._damage = error
                    return
                self._packets_before += getattr(self.current, "packet_total", 0) or 0
                self.current.close()
                self.current = opened
                self._defer_file(opened)
                yield self.current
        finally:
            self.close()

    def close(self) -> None:
        self.current.close()

    def __enter__(self) -> RingSource:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
