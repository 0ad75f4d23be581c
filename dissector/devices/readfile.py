"""Reading a user's profile or map file whole, with a size cap: never a FIFO (it would wait for a
writer forever), a device (/dev/zero never ends) or a file larger than any real profile or map."""
from __future__ import annotations

import os
import stat
from pathlib import Path

from dissector.errors import ProfileError


def read_capped(path: str | Path, limit: int, what: str, kind: str | None = None) -> bytes:
    """The bytes of a regular file of at most `limit` bytes; ProfileError, one line, otherwise.
    `what` names it in errors (`map`), `kind` says what a too large file is not (`register map`)."""
    try:
        # O_NONBLOCK: opening a FIFO must not wait for its writer before fstat can refuse it.
        descriptor = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except (OSError, ValueError) as error:
        raise ProfileError(f"{path}: cannot read the {what}: {getattr(error, 'strerror', None) or error}") from None
    try:
        mode = os.fstat(descriptor).st_mode
        if not stat.S_ISREG(mode):
            kind = "a directory" if stat.S_ISDIR(mode) else "a FIFO" if stat.S_ISFIFO(mode) else "a device"
            raise ProfileError(f"{path}: {kind}, not a {what} file")
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(descriptor, min(1 << 20, limit + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as error:
        raise ProfileError(f"{path}: cannot read the {what}: {error.strerror or error}") from None
    finally:
        os.close(descriptor)
    if size > limit:
        raise ProfileError(f"{path}: larger than {limit >> 20} MiB, not a {kind or what}")
    return b"".join(chunks)
