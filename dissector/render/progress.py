"""A rich progress bar on stderr while a long file is decoded (only when stderr is a terminal)."""
from __future__ import annotations

import os
from collections.abc import Iterable, Iterator
from typing import TextIO

from rich.console import Console
from rich.progress import BarColumn, DownloadColumn, Progress, TextColumn, TimeRemainingColumn

from dissector.model import Chunk

MIN_SIZE = 4 << 20  # smaller files decode in well under a second: no bar


def progress_for(chunks: Iterable[Chunk], path: str, stream: TextIO,
                 files: tuple[str, ...] = ()) -> Iterable[Chunk]:
    """`files`: those `chunks` come from, when not `path` alone (a ring buffer's: app/rings.py)."""
    try:
        size = sum(os.path.getsize(name) for name in files or (path,))
    except OSError:
        return chunks
    if size < MIN_SIZE:
        return chunks
    return _with_bar(chunks, path, size, stream)


def _with_bar(chunks: Iterable[Chunk], path: str, size: int, stream: TextIO) -> Iterator[Chunk]:
    progress = Progress(
        TextColumn("[bold]{task.description}"),
        BarColumn(),
        DownloadColumn(),
        TimeRemainingColumn(),
        console=Console(file=stream, force_terminal=True),  # the caller saw a terminal
        transient=True,
    )
    with progress:
        task = progress.add_task(os.path.basename(path), total=size)
        for chunk in chunks:
            yield chunk
            # Payload bytes: pcap record headers are not counted, so the bar may stop short of 100%.
            progress.advance(task, len(chunk.data))
