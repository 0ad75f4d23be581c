"""A -w file's stream written a whole record at a time (render/capturefile.py): on a failed write (a full
disk, a file size limit) the file is cut back to the last whole record, so it still opens in Wireshark.
"""
from __future__ import annotations

import os
import stat
from typing import BinaryIO

FLUSH_BYTES = 1 << 16  # records are written in batches of about this much when not live


class WholeRecords:
    """A binary stream written a whole record (or file header) per `write`; never leaves part of one.

    Records wait in memory up to FLUSH_BYTES (every one is written at once when `live`); a failed
    write(2), or a short one, cuts the file back to the end of the last record it held whole
    (ftruncate, for a regular file this opened) and raises the error. `whole` counts the writes on disk.
    """

    def __init__(self, stream: BinaryIO, live: bool, truncate: bool) -> None:
        self._stream = stream
        self._live = live
        self._truncate = truncate
        self._pending = bytearray()
        self._ends: list[int] = []  # end of each waiting write in _pending
        self.on_disk = 0  # bytes of whole writes in the file
        self.whole = 0  # writes wholly in the file

    def write(self, data: bytes) -> int:
        self._pending += data
        self._ends.append(len(self._pending))
        if self._live or len(self._pending) >= FLUSH_BYTES:
            self.flush()
        return len(data)

    def flush(self) -> None:
        pending, ends = self._pending, self._ends
        if not pending:
            return
        self._pending, self._ends = bytearray(), []
        done = 0
        try:
            with memoryview(pending) as view:
                while done < len(pending):
                    wrote = self._stream.write(view[done:])
                    if not wrote:  # a stream that takes nothing and says nothing: as good as full
                        raise OSError(28, os.strerror(28))
                    done += wrote
            flush = getattr(self._stream, "flush", None)
            if flush is not None:
                flush()
        except OSError:
            kept = [end for end in ends if end <= done]
            self._cut(self.on_disk + (kept[-1] if kept else 0))
            self.whole += len(kept)
            self.on_disk += kept[-1] if kept else 0
            raise
        self.whole += len(ends)
        self.on_disk += len(pending)

    def _cut(self, size: int) -> None:
        if not self._truncate:
            return
        try:
            fileno = self._stream.fileno()
            if stat.S_ISREG(os.fstat(fileno).st_mode):
                os.ftruncate(fileno, size)
        except (OSError, ValueError):
            pass  # nothing more can be done; the error being raised says the write failed

    def close(self) -> None:
        try:
            self.flush()
        finally:
            self._stream.close()
