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

from dissector.model import Chunk

# dumpcap's ring buffer names: PREFIX_NNNNN_YYYYMMDDHHMMSS.EXT
RING_NAME = re.compile(r"^(?P<prefix>.*)_(?P<number>\d{5,})_(?P<stamp>\d{14})(?P<suffix>\.[^./]*)?$")


def group_files(paths: list[str]) -> list[tuple[str, tuple[str, ...]]]:
    """(shown, files) per capture, in the order first named: a ring buffer's files (same folder, prefix
    and suffix) by file number, shown as `folder/PREFIX.EXT` (its one file's name when only one is
    given); any other path alone, as named."""
    rings: dict[tuple[str, str, str], list[tuple[int, str]]] = {}
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
        rings[key].append((int(match["number"]), path))
    groups = []
    for key in order:
        if len(key) == 2:
            groups.append((key[0], (key[0],)))
            continue
        folder, prefix, suffix = key  # type: ignore[misc]
        files = tuple(path for _number, path in sorted(rings[key]))  # type: ignore[index]
        groups.append((files[0] if len(files) == 1 else os.path.join(folder, prefix + suffix), files))
    return groups


class RingSource:
    """The Sources (sources/reader.py) of a ring buffer's files as one: each file opened when the one
    before it ends. The first file's mode is the capture's (its framing); each file is opened as the
    first was (`open_file`), as --parquet does, so that a pcap's records stay readable in bulk."""

    def __init__(self, files: tuple[str, ...], open_file: Callable[[str], Any]) -> None:
        self.files = files
        self._open = open_file
        self.current = open_file(files[0])
        self.format, self.mode, self.name = self.current.format, self.current.mode, self.current.name
        self.streaming = False
        self._warnings: list[str] = []

    @property
    def recorded_until(self) -> Any:
        """The last file's (read last): when the capture ends."""
        return self.current.recorded_until

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
            for path in self.files[1:]:
                self._warnings += self.current.take_warnings()  # (a file's own, said as the next begins)
                self.current = self._open(path)
                yield self.current
        finally:
            self.close()

    def close(self) -> None:
        self.current.close()

    def __enter__(self) -> RingSource:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
