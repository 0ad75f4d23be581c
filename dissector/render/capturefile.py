"""The -w output: a pcap or pcapng file, standard output (`-w -`), or a ring buffer of files.

The format is pcapng with `-F pcapng` or a `.pcapng` suffix, pcap otherwise. Records are written
whole, one write(2) each on an unbuffered stream when `flush` (live), so every file is valid at any
instant and `-w - | wireshark -k -i -` sees each record as it is heard.

The ring buffer follows dumpcap's `-b`: `filesize:N` switches to the next file once a file holds N kB
(1000 bytes), `duration:S` once it has been open S seconds, `files:K` keeps only the newest K files.
Files are named as dumpcap names them, `prefix_NNNNN_YYYYmmddHHMMSS.suffix` from `-w prefix.suffix`
(number from 00001, local time of opening). A record is never split: each file is a valid capture.
"""
from __future__ import annotations

import os
import time
from collections import deque
from dataclasses import dataclass
from typing import BinaryIO, Protocol

from dissector.model import Item, Noise
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import PcapWriter

FORMATS = ("pcap", "pcapng")
STDOUT = "-"


def noise_comment(item: Item) -> str | None:
    """The pcapng comment of a record: why its bytes are not a frame."""
    if isinstance(item, Noise):
        return f"noise: {item.length} byte{'' if item.length == 1 else 's'}, {item.reason}"
    return None


class RecordWriter(Protocol):
    size: int

    def write(self, data: bytes, timestamp: float | None = None, comment: str | None = None) -> None: ...

    def close(self) -> None: ...


@dataclass(frozen=True)
class Ring:
    filesize: int | None = None  # kB (1000 bytes), as dumpcap
    duration: float | None = None  # seconds
    files: int | None = None

    @classmethod
    def parse(cls, specs: list[str]) -> Ring:
        """`-b` arguments; ValueError with the message for a bad one."""
        values: dict[str, float] = {}
        for spec in specs:
            key, _, text = spec.partition(":")
            if key not in ("filesize", "duration", "files") or not text:
                raise ValueError(f"-b {spec}: give filesize:KB, duration:SECONDS or files:COUNT")
            try:
                value = float(text) if key == "duration" else int(text)
            except ValueError:
                raise ValueError(f"-b {spec}: {text!r} is not a {'number' if key == 'duration' else 'whole number'}") from None
            if not 0 < value < float("inf"):
                raise ValueError(f"-b {spec}: must be more than 0")
            values[key] = value
        ring = cls(
            int(values["filesize"]) if "filesize" in values else None,
            values.get("duration"),
            int(values["files"]) if "files" in values else None,
        )
        if ring.filesize is None and ring.duration is None:
            # dumpcap refuses it too: without a switch condition there would be only one file.
            raise ValueError("-b needs filesize:KB or duration:SECONDS to switch files")
        return ring


def file_format(path: str, requested: str | None) -> str:
    if requested is not None:
        return requested
    return "pcapng" if path.lower().endswith(".pcapng") else "pcap"


def ring_name(path: str, number: int, opened: float) -> str:
    """dumpcap's name for the file number `number` of the ring `path`."""
    root, suffix = os.path.splitext(path)
    stamp = time.strftime("%Y%m%d%H%M%S", time.localtime(opened))
    return f"{root}_{number:05d}_{stamp}{suffix}"


class CaptureOutput:
    """Where -w records go. `write` raises OSError as the system says it (the caller words it)."""

    def __init__(
        self,
        path: str,
        fmt: str | None = None,
        ring: Ring | None = None,
        flush: bool = True,
        stdout: BinaryIO | None = None,
        interface: tuple[str, str] | None = None,
    ) -> None:
        self.path = path
        self.format = file_format(path, fmt)
        self.ring = ring
        self._flush = flush
        self._stdout = stdout
        self._interface = interface  # (if_name, if_description) for pcapng
        self._writer: RecordWriter | None = None
        self._number = 0
        self._opened = 0.0
        self.paths: list[str] = []  # every file written, in order (a ring's deleted ones too)
        self._kept: deque[str] = deque()
        self._open()

    @property
    def name(self) -> str:
        """What the summary says was written."""
        if self.path == STDOUT:
            return "standard output"
        if self.ring is not None and self.paths:
            return f"{self.paths[0]} .. {self.paths[-1]}" if len(self.paths) > 1 else self.paths[0]
        return self.path

    def _open(self) -> None:
        if self.path == STDOUT:
            if self._stdout is None:
                raise OSError("standard output is not a byte stream")
            stream: BinaryIO = self._stdout
            target = STDOUT
        else:
            self._opened = time.time()
            target = self.path
            if self.ring is not None:
                self._number += 1
                target = ring_name(self.path, self._number, self._opened)
            # Unbuffered when live: one record, one write(2), on disk before it is handed on.
            stream = open(target, "wb", buffering=0 if self._flush else -1)  # noqa: SIM115
            self.paths.append(target)
            self._kept.append(target)
        self._stream = stream
        try:
            if self.format == "pcapng":
                name, description = self._interface or (None, None)
                self._writer = PcapngWriter(stream, flush=self._flush, if_name=name, if_description=description)
            else:
                self._writer = PcapWriter(stream, flush=self._flush)
        except OSError:
            self._close_writer()
            raise
        if self.ring is not None and self.ring.files is not None:
            while len(self._kept) > self.ring.files:
                old = self._kept.popleft()
                try:
                    os.unlink(old)
                except FileNotFoundError:
                    pass

    def write(self, data: bytes, timestamp: float | None = None, comment: str | None = None) -> None:
        if self._writer is None:
            raise OSError("the capture file is closed")
        self.tick()
        self._writer.write(data, timestamp, comment)
        ring = self.ring
        if ring is not None and ring.filesize is not None and self._writer.size >= ring.filesize * 1000:
            self._next()

    def tick(self, now: float | None = None) -> None:
        """A ring with duration:S switches files on time, heard bytes or not (as dumpcap)."""
        ring = self.ring
        if ring is not None and ring.duration is not None and self._writer is not None:
            if (now if now is not None else time.time()) - self._opened >= ring.duration:
                self._next()

    def _next(self) -> None:
        self._close_writer()
        self._open()

    def _close_writer(self) -> None:
        writer, self._writer = self._writer, None
        if self.path == STDOUT:
            if self._stdout is not None:
                self._stdout.flush()
            return
        if writer is not None:
            writer.close()
        else:
            self._stream.close()

    def close(self) -> None:
        if self._writer is not None:
            self._close_writer()


def open_output(
    path: str,
    fmt: str | None,
    ring_specs: list[str] | tuple[str, ...],
    flush: bool,
    stdout: BinaryIO | None,
    interface: tuple[str, str] | None = None,
) -> CaptureOutput:
    """The -w output from the options; ValueError for bad -b options, OSError from the system."""
    ring = Ring.parse(list(ring_specs)) if ring_specs else None
    if ring is not None and path == STDOUT:
        raise ValueError("-b needs -w FILE, not standard output")
    if path == STDOUT and stdout is not None and stdout.isatty():
        # Binary records would garble the terminal (tshark and dumpcap refuse it too).
        raise ValueError("-w -: standard output is a terminal; pipe it (| wireshark -k -i -) or give a file")
    return CaptureOutput(path, fmt, ring, flush=flush, stdout=stdout, interface=interface)
