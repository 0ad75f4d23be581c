"""Live sniffing: read a serial port (or any pyserial URL), frame and show what crosses the bus.

The port is opened for listening only: nothing is ever written to it, and RTS is left deasserted
because RS-485 adapters that steer their driver with RTS would otherwise drive the bus.

Reads are short (READ_TIMEOUT), and each read becomes a Chunk stamped with the time the read
returned. The framer decides where frames end from lengths and CRCs, so a read holding a request
and its response, or half a frame, is fine. A frame the framer cannot close yet (it waits for
bytes that would make a longer reading possible, or for what follows a damaged frame) is closed
once the line has been silent for IDLE_FLUSH (or t3.5 if longer): on the wire, that silence ends
every RTU frame. But a gateway (socket://) or a stalled adapter may also pause inside a frame, and
a flush there would cut it into noise; so at IDLE_FLUSH the flush is first tried on a copy of the
framer, and done only if it closes a CRC-valid frame. Anything else (a damaged frame, noise, a
partial frame) waits for IDLE_FLUSH_LONG of silence.

What is heard is teed as it is heard: raw bytes to --raw (one unbuffered write per read), and each
item to the -w pcap (one record a frame or noise run, flushed) before it is displayed. So whatever
was shown is on disk, whatever stops the capture (Ctrl-C, SIGKILL, an unplugged adapter).
"""
from __future__ import annotations

import argparse
import copy
import signal
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import BinaryIO, TextIO

import serial
from rich.console import Console
from rich.text import Text

from dissector.errors import ExitStatus, LiveError, PortVanished
from dissector.framing.ascii import AsciiFramer
from dissector.sources.serial_port import PARITIES, PortSettings, open_port, reason
from dissector.model import Chunk, Frame, Item
from dissector.render.pcapwriter import PcapWriter
from dissector.app.live_options import PARITY_CHOICES
from dissector.pipeline import Annotator, Dissector
from dissector.app.live_view import LineSink, LiveStats, RichSink, Sink, json_line

PROG = "vw3-decode"
IDLE_FLUSH = 0.020
IDLE_FLUSH_LONG = 0.250
assert set(PARITIES) == set(PARITY_CHOICES)


def silence_threshold(baud: int) -> float:
    """max(t3.5, IDLE_FLUSH); t3.5 is fixed at 1.75 ms above 19200 baud (Serial Line Guide)."""
    t35 = 3.5 * 11 / baud if baud <= 19200 else 0.00175
    return max(t35, IDLE_FLUSH)


def port_settings(args: argparse.Namespace) -> PortSettings:
    return PortSettings(args.live, args.baud, args.parity, args.stopbits, args.bytesize)


class Tee:
    """The capture files: raw bytes per read, one pcap record per item, both on disk at once."""

    def __init__(self, pcap_path: str | None, raw_path: str | None) -> None:
        self.paths = [path for path in (pcap_path, raw_path) if path]
        self._pcap_path, self._raw_path = pcap_path, raw_path
        self._pcap_file: BinaryIO | None = None
        self._pcap: PcapWriter | None = None
        self._raw: BinaryIO | None = None
        path = pcap_path
        try:
            if pcap_path:
                self._pcap_file = open(pcap_path, "wb")
                self._pcap = PcapWriter(self._pcap_file)
            path = raw_path
            if raw_path:
                # Unbuffered: each read is one write(2), on disk before its frames are shown.
                self._raw = open(raw_path, "wb", buffering=0)
        except OSError as error:
            self.close()
            raise LiveError(f"cannot write {path}: {error.strerror or error}", ExitStatus.BAD_INPUT) from None

    def raw(self, data: bytes) -> None:
        if self._raw is not None:
            try:
                self._raw.write(data)
            except OSError as error:
                self._failed(self._raw_path, error)

    def items(self, items: list[Item]) -> None:
        if self._pcap is not None:
            try:
                for item in items:
                    self._pcap.write(item.raw, item.time)
            except OSError as error:
                self._failed(self._pcap_path, error)

    def _failed(self, path: str | None, error: OSError) -> None:
        # A full disk or a vanished mount: stop writing (files keep every whole record) and say so.
        self.close()
        raise LiveError(f"cannot write {path}: {error.strerror or error}", ExitStatus.ERROR)

    def close(self) -> None:
        streams = (self._pcap_file, self._raw)
        self._pcap_file = self._pcap = self._raw = None
        for stream in streams:
            if stream is not None:
                try:
                    stream.close()
                except OSError:
                    pass  # what could not be written was already reported


class StopFlag:
    """Set by SIGINT/SIGTERM: the read loop sees it within one read timeout and stops cleanly."""

    def __init__(self) -> None:
        self.signal: int | None = None
        self._previous: dict[int, object] = {}

    def __enter__(self) -> StopFlag:
        for signum in (signal.SIGINT, signal.SIGTERM):
            try:
                self._previous[signum] = signal.signal(signum, self._handle)
            except ValueError:  # not the main thread: the caller handles signals
                pass
        return self

    def _handle(self, signum: int, _frame: object) -> None:
        self.signal = signum

    def __exit__(self, *_exc: object) -> None:
        for signum, handler in self._previous.items():
            signal.signal(signum, handler)  # type: ignore[arg-type]


@dataclass
class Capture:
    """The read loop and what it needs; `run` returns why it stopped."""

    port: serial.SerialBase
    dissector: Dissector
    tee: Tee
    sink: Sink
    stats: LiveStats
    silence: float
    duration: float | None = None
    count: int | None = None
    silence_long: float = IDLE_FLUSH_LONG

    def flush_due(self, silent: float, tried: bool) -> bool:
        """Whether to close what the framer holds after `silent` seconds without bytes."""
        if silent >= self.silence_long:
            return True
        if tried or silent < self.silence:
            return False
        trial = copy.deepcopy(self.dissector.framer).finish()
        return any(isinstance(item, Frame) and item.crc_ok for item in trial)

    def deliver(self, items: list[Item]) -> bool:
        """Tee, count and show items; False once --count is reached."""
        if self.count is not None:
            room = self.count - self.stats.frames
            kept: list[Item] = []
            for item in items:
                if room <= 0:
                    break
                kept.append(item)
                room -= isinstance(item, Frame)
            items = kept
        self.tee.items(items)
        for item in items:
            self.stats.add(item)
        self.sink.show(items)
        return self.count is None or self.stats.frames < self.count

    def run(self, stop: StopFlag) -> str:
        port, dissector = self.port, self.dissector
        deadline = None if self.duration is None else time.monotonic() + self.duration
        last_data = time.monotonic()
        pending = False  # bytes fed since the last idle flush
        tried = False  # flush_due already tried a copy of the framer during this silence
        while True:
            if stop.signal is not None:
                return "interrupted"
            now = time.monotonic()
            if deadline is not None and now >= deadline:
                return "duration"
            try:
                data = port.read(max(1, port.in_waiting))
                if data and port.in_waiting:
                    data += port.read(port.in_waiting)
            except (serial.SerialException, OSError) as error:
                raise PortVanished(reason(error)) from None
            if data:
                stamp = time.time()
                last_data = time.monotonic()
                pending, tried = True, False
                self.tee.raw(data)
                if not self.deliver(dissector.feed(Chunk(data, time=stamp))):
                    return "count"
            elif pending:
                silent = time.monotonic() - last_data
                if self.flush_due(silent, tried):
                    pending = False
                    if not self.deliver(dissector.flush_idle()):
                        return "count"
                tried = tried or silent >= self.silence
            self.sink.tick()


class NullSink:
    def show(self, items: list[Item]) -> None:
        pass

    def tick(self) -> None:
        pass

    def close(self) -> None:
        pass


def _make_sink(
    args: argparse.Namespace,
    out: TextIO,
    is_terminal: bool,
    render_line: Callable[[Item], str],
    render_text: Callable[[Item], Text] | None,
    stats: LiveStats,
    annotate: Annotator | None = None,
) -> Sink:
    if getattr(args, "watch", None) is not None:
        from dissector.render.watch import WatchSink

        return WatchSink(args.watch, out, getattr(args, "json", False), annotate)
    if getattr(args, "json", False):
        return LineSink(out, json_line)
    if is_terminal:
        from dissector.render.theme import THEME

        console = Console(file=out, theme=THEME, force_terminal=True, highlight=False)
        render = render_text or (lambda item: Text(render_line(item), no_wrap=True))
        title = f"{args.live} at {port_settings(args).text()} (Ctrl-C to stop)"
        return RichSink(console, title, stats, render)
    return LineSink(out, render_line)


def run_live(
    args: argparse.Namespace,
    out: TextIO,
    err: TextIO,
    is_terminal: bool,
    render_line: Callable[[Item], str],
    annotate: Annotator | None,
    render_text: Callable[[Item], Text] | None = None,
) -> int:
    """Capture from args.live until --duration, --count, Ctrl-C or the port goes away."""
    if getattr(args, "detect", None) is not None:
        from dissector.app.detect import run_detect

        return run_detect(args, out, err)
    try:
        port = open_port(port_settings(args))
    except LiveError as error:
        err.write(f"{PROG}: {error}\n")
        return error.status
    try:
        tee = Tee(getattr(args, "write", None), args.raw)
    except LiveError as error:
        port.close()
        err.write(f"{PROG}: {error}\n")
        return error.status
    stats = LiveStats()
    err.write(f"{PROG}: listening on {args.live} at {port_settings(args).text()}\n")
    err.flush()
    # Modbus ASCII on the line only with --mode ascii: a live stream cannot be sniffed before it starts.
    framer = AsciiFramer() if getattr(args, "mode", None) == "ascii" else None
    dissector = Dissector(
        framer=framer, hold=False, annotate=annotate, timeout=getattr(args, "timeout", None)
    )
    sink = _make_sink(args, out, is_terminal, render_line, render_text, stats, annotate)
    capture = Capture(
        port, dissector, tee, sink, stats, silence_threshold(args.baud), args.duration, args.count
    )
    started = time.monotonic()
    status = ExitStatus.OK
    reason = ""
    try:
        with StopFlag() as stop:
            try:
                reason = capture.run(stop)
            except PortVanished as error:
                reason = f"{args.live} went away ({error})"
                status = ExitStatus.ERROR
            except LiveError as error:
                reason, status = str(error), error.status
            except BrokenPipeError:
                # The reader of our output (head, less) went away: stop, keep the files whole.
                reason = "output closed"
                capture.sink = sink = NullSink()
            if reason != "count":
                capture.deliver(dissector.finish())
    finally:
        tee.close()
        port.close()
        stats.finish()
        try:
            sink.close()
        except BrokenPipeError:
            pass
    seconds = time.monotonic() - started
    files = f"; wrote {', '.join(tee.paths)}" if tee.paths else ""
    if status != ExitStatus.OK:
        err.write(f"{PROG}: error: {reason}; capture files closed\n")
    err.write(f"{PROG}: {stats.summary(seconds)}{files}\n")
    err.flush()
    return status
