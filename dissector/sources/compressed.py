"""Compressed captures read as tshark reads them: a gzip file (`capture.pcap.gz`, a log rotated by logrotate)
is decompressed as it is read, whatever format is inside; bzip2 and xz too (Python's own modules, no
dependency), which tshark 4.0 does not open. zstd and lz4 (Wireshark 4.2+) need a module Python 3.11 lacks: one
line naming the tool that decompresses them.

A compressed input is recognised by its header, not its name, and more than the magic number is checked:
1f 8b alone is also a raw RTU capture starting with slave 31's exception to function 11."""
from __future__ import annotations

import bz2
import gzip
import lzma
import zlib
from typing import BinaryIO

from dissector.sources.common import SourceError, WarningLog

_XZ = b"\xfd7zXZ\x00"
_BZIP2_BLOCK = (b"\x31\x41\x59\x26\x53\x59", b"\x17\x72\x45\x38\x50\x90")  # a block, or an empty stream's end
_UNREAD = {b"\x28\xb5\x2f\xfd": ("zstd", "zstd -d"), b"\x04\x22\x4d\x18": ("lz4", "lz4 -d")}
HEADER_BYTES = 10  # enough to tell each kind


def compression(sample: bytes, name: str) -> str | None:
    """The compression of the input `name` whose first bytes are `sample`: gzip, bzip2 or xz; None if none."""
    # gzip: deflate (8), no reserved flag bit, XFL 0, 2 or 4, a known OS (RFC 1952 2.3.1)
    if (sample[:3] == b"\x1f\x8b\x08" and len(sample) >= HEADER_BYTES and not sample[3] & 0xE0
            and sample[8] in (0, 2, 4) and (sample[9] < 14 or sample[9] == 255)):
        return "gzip"
    if sample[:3] == b"BZh" and sample[3:4].isdigit() and sample[3:4] != b"0" and sample[4:10] in _BZIP2_BLOCK:
        return "bzip2"
    if sample.startswith(_XZ):
        return "xz"
    for magic, (kind, tool) in _UNREAD.items():
        if sample.startswith(magic):
            raise SourceError(f"{name}: compressed input ({kind}): decompress it first (`{tool} FILE`)")
    return None


class _Replay:
    """The bytes read to recognise the input, then the rest of it: what a decompressor reads."""

    def __init__(self, prefix: bytes, stream: BinaryIO) -> None:
        self._prefix = prefix
        self._stream = stream

    def readable(self) -> bool:
        return True

    def read(self, count: int = -1) -> bytes:
        if self._prefix:
            if count < 0:
                part, self._prefix = self._prefix + self._stream.read(), b""
                return part
            part, self._prefix = self._prefix[:count], self._prefix[count:]
            return part
        return self._stream.read(count)

    def fileno(self) -> int:
        return self._stream.fileno()

    def close(self) -> None:
        self._stream.close()


class Decompressed:
    """The decompressed bytes of a stream, read as any input is (read, read1). Data cut short or damaged ends
    the input there with a warning, the bytes before it decoded, as a pcap cut inside a record is; before any
    byte, it is an input that cannot be read (SourceError). fileno()
    is the compressed file's (its type: a regular file or a pipe)."""

    def __init__(self, kind: str, prefix: bytes, stream: BinaryIO, name: str, log: WarningLog) -> None:
        self.kind = kind
        self._name = name
        self._stream = stream
        self._log = log
        self._ended = False
        self._given = 0
        source = _Replay(prefix, stream)
        opener = {"gzip": gzip.GzipFile, "bzip2": bz2.BZ2File, "xz": lzma.LZMAFile}[kind]
        self._file = opener(fileobj=source, mode="rb") if kind == "gzip" else opener(source, mode="rb")

    def read(self, count: int = -1) -> bytes:
        """Up to `count` bytes (all with -1), fewer only at the end of the data."""
        parts: list[bytes] = []
        wanted = count
        while wanted:
            part = self.read1(wanted if wanted > 0 else 65536)
            if not part:
                break
            parts.append(part)
            wanted = max(wanted - len(part), 0) if wanted > 0 else -1
        return b"".join(parts)

    def read1(self, count: int = -1) -> bytes:
        if self._ended:
            return b""
        try:
            part = self._file.read1(count)
            self._given += len(part)
            return part
        except EOFError:
            problem = "ends early (a file cut short?)"
        except (OSError, zlib.error, lzma.LZMAError, ValueError) as error:
            if isinstance(error, OSError) and error.errno is not None:
                raise  # (a read error of the file itself: the reader's message)
            problem = f"is damaged ({_reason(error)})"
        self._ended = True
        if not self._given:  # (nothing to decode: the file is not read)
            raise SourceError(f"{self._name}: the {self.kind} data {problem}")
        self._log.warn("compressed", f"{self._name}: the {self.kind} data {problem}: the bytes before are decoded")
        return b""

    def fileno(self) -> int:
        return self._stream.fileno()

    def close(self) -> None:
        self._file.close()
        self._stream.close()


def _reason(error: BaseException) -> str:
    text = str(error) or type(error).__name__
    return text.splitlines()[0][:120]
