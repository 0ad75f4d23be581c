"""The capture side of a live capture, apart from the display as dumpcap is apart from tshark.

One thread only reads the port, stamps each read, writes it to --raw (one unbuffered write), frames it
(lengths and CRCs: microseconds a frame, no decoding) and writes each frame or noise run to -w (one
record, one write) before handing the items on. It never waits for anyone: the hand-off to the
display is bounded, and when the display falls behind, display items are dropped and counted, never
capture bytes. So whatever stops the capture (Ctrl-C, SIGKILL, an unplugged adapter) and however slow
the reader of our output is, the files hold every byte read.

A frame the framer cannot close yet (it waits for bytes that would make a longer reading possible, or
for what follows a damaged frame) is closed once the line has been silent for IDLE_FLUSH (or t3.5 if
longer): on the wire, that silence ends every RTU frame. But a gateway (socket://) or a stalled
adapter may also pause inside a frame, and a flush there would cut it into noise; so at IDLE_FLUSH
the flush is first tried on a copy of the framer, and done only if it closes a CRC-valid frame.
Anything else (a damaged frame, noise, a partial frame) waits for IDLE_FLUSH_LONG of silence. A Modbus
ASCII frame ends at its LF, not at a silence: nothing is closed then (flush_due).

A read returns once its last byte has come, so each read is framed as its bytes' arrivals, each
byte at the read's stamp less the character times after it (sources/serial_times.py ReadClock: one
chunk that times each of its bytes): a frame's time, as everywhere else, is its first byte's. --raw and the tape (VW3_LIVE_TAPE) keep the
reads as made, stamps included.

Reads are stamped to the microsecond, and so are the byte times, as the pcap stores them, so that the
decode of the -w file computes the same response times, to the last bit, as the live display.
"""
from __future__ import annotations

import contextlib
import os
import stat

import copy
import struct
import threading
import time
from collections import deque
from dataclasses import dataclass, field
from typing import BinaryIO
from collections.abc import Iterator

import serial

from dissector.errors import ExitStatus, LiveError, PortVanished
from dissector.framing.timing import LineTiming, line_silence
from dissector.model import Frame, Item, Noise, Stamp, up_to_items
from dissector.pipeline import Framer
from dissector.render.capturefile import CaptureOutput, noise_comment
from dissector.render.pcapwriter import SNAPLEN
from dissector.render.describe import count_text
from dissector.sources.serial_port import reason
from dissector.sources.serial_times import ReadClock, char_time

IDLE_FLUSH = 0.020
IDLE_FLUSH_LONG = 0.250
HANDOFF_LIMIT = 20_000  # items waiting for decoding and display; beyond, they are dropped (counted)
# Reads waiting for the compiled live path's display (framer=None), which frames them and writes -w: a
# read dropped would cut a frame and leave a hole in -w, so the limit is only there to bound memory
# (about 100 s of a busy adapter's reads; the engine frames them far faster than they come).
HANDOFF_READS_LIMIT = 1_000_000


def silence_threshold(baud: int) -> float:
    """max(t3.5, IDLE_FLUSH); t3.5 is the line's (timing.LineTiming: fixed at 1.75 ms above 19200 baud)."""
    return max(LineTiming(baud).t35, IDLE_FLUSH)


def long_silence(baud: int) -> float:
    """max(t3.5, IDLE_FLUSH_LONG): the silence after which live closes a partial frame. Below about 154 baud
    t3.5 is the longer (770 ms at 50 baud), and a shorter silence does not cut a frame in the decode of the
    -w file (timing.silence_before), so live waits as long."""
    return max(LineTiming(baud).t35, IDLE_FLUSH_LONG)


def port_char_time(port: serial.SerialBase) -> float:
    """char_time of an open pyserial port (its parity is pyserial's letter, N for none)."""
    return char_time(port.baudrate, port.bytesize, port.parity, port.stopbits)


def stamp_now() -> Stamp:
    """The time now, to the microsecond: the Stamp the pcap reader makes of the record written."""
    return Stamp(time.time_ns() // 1000 * 1000)


class CaptureFiles:
    """--raw (bytes as read) and -w (one record an item, _records), both written before anything is shown."""

    def __init__(self, output: CaptureOutput | None, raw_path: str | None, timing: LineTiming | None = None) -> None:
        self.output = output
        self._timing = timing  # RTU's: where the line gave no silence after a noise run (_records)
        self._raw_path = raw_path
        self._raw: BinaryIO | None = None
        self.last_time: Stamp | None = None  # the time of the last item written (-c: where the capture stops)
        self._closed = False
        self._held: list[Item] = []  # a noise run waiting for the item after it (items)
        if raw_path:
            try:
                # Unbuffered: each read is one write(2), on disk before its frames are shown.
                self._raw = open(raw_path, "wb", buffering=0)  # noqa: SIM115
            except OSError as error:
                self.close()
                raise LiveError(f"cannot write {raw_path}: {error.strerror or error}") from None

    @property
    def names(self) -> list[str]:
        return [name for name in (self.output and self.output.name, self._raw_path) if name]

    def raw(self, data: bytes) -> None:
        if self._raw is not None:
            try:
                self._raw.write(data)
            except OSError as error:
                self._failed(self._raw_path, error)

    def items(self, items: list[Item]) -> list[Item]:
        """Write `items`; the ones to show now, written. A noise run last (RTU, -w) is held, neither
        written nor shown, until the item after it comes (_records may join them) or the line has been
        silent t3.5 after it (release): so the records do not hang on how the reads came in batches. The
        Python path writes its framer's items a read at a time, the compiled one the items it shows, a
        request with its answer: `answer 00 request` in one read (a busy machine) was one record `00
        request` in one, `00` a record of its own in the other, read back as a pause after the glitch."""
        if self._held:
            items, self._held = self._held + items, []
        if (items and self.output is not None and self._timing is not None and isinstance(items[-1], Noise)
                and items[-1].time is not None):
            self._held = [items.pop()]
        self._write(items)
        return items

    def release(self, now: Stamp | None, read: int = 0) -> list[Item]:
        """The noise run held (items), written, if no item can join it any more: no byte read after it
        (`read` bytes read in all) and the line silent t3.5 after it before `now` (no byte before it
        unread), or `now` None (the capture ends). A byte read after it starts the item it waits for
        (which the display may show later: a request with its answer)."""
        if not self._held:
            return []
        noise, timing = self._held[0], self._timing
        end = noise.offset + noise.length
        if now is not None and (read > end or timing is None or line_silence(
                noise.offset, noise.time, end, now, timing) < timing.t35):  # type: ignore[arg-type]
            return []
        held, self._held = self._held, []
        self._write(held)
        return held

    def _write(self, items: list[Item]) -> None:
        if items and isinstance(items[-1].time, Stamp):
            self.last_time = items[-1].time
        if self.output is not None:
            try:
                for data, stamp, comments in self._records(items):
                    self.output.write(data, stamp, "; ".join(comments) or None)
            except OSError as error:
                self._failed(self.output.name, error)

    def _records(self, items: list[Item]) -> list[tuple[bytes, float | None, list[str]]]:
        """A record an item, but a noise run shares one with the items of the batch after it the line gave
        no silence before (RTU): a record's end reads back as a pause (framing/rtu.py _followed), evidence
        of a frame's end the line did not give; live showed 5 bytes of noise right before an exception, their
        own record read back as a damaged exception. The decode of a file joins a noise run and the damaged
        frame after it too (capturefile.CaptureOutput.write_items); here the frame may be whole: live, no
        later record says where the noise stopped. The record is at its frame's time, the noise reads back
        at it. A noise run last in a batch waits for the next (items, release); every record is written
        before its items are shown."""
        records: list[tuple[bytes, float | None, list[str]]] = []
        after: Item | None = None  # the noise run the next item may join
        timing = self._timing
        for item in items:
            comment = noise_comment(item)
            if (after is not None and timing is not None and item.offset == after.offset + after.length
                    and item.time is not None and after.time is not None
                    and line_silence(after.offset, after.time, item.offset, item.time, timing) < timing.t35
                    and len(records[-1][0]) + item.length <= SNAPLEN):
                data, stamp, comments = records[-1]
                if isinstance(item, Noise):
                    comments = [*comments, comment or ""]
                else:  # at the frame's time: its response time and pairing read it (the noise has none)
                    stamp = item.time
                    shape = f"{'' if item.crc_ok else 'damaged '}frame ({count_text(item.length, 'byte')})"
                    comments = [*comments, f"then a {shape}"]
                records[-1] = (data + item.raw, stamp, comments)
            else:
                records.append((item.raw, item.time, [comment] if comment else []))
            after = item if isinstance(item, Noise) else None
        return records

    def tick(self) -> None:
        if self.output is not None:
            try:
                self.output.tick()
            except OSError as error:
                self._failed(self.output.name, error)

    def _failed(self, path: str | None, error: OSError) -> None:
        # A full disk or a vanished mount: stop writing (files keep every whole record) and say what
        # they keep.
        kept = ""
        if self.output is not None and path == self.output.name:
            kept = f"; {self.output.kept}"
        elif self._raw is not None:
            with contextlib.suppress(OSError, ValueError):
                info = os.fstat(self._raw.fileno())
                if stat.S_ISREG(info.st_mode):  # (a device such as /dev/full keeps nothing to count)
                    kept = f"; {path} keeps {count_text(info.st_size, 'byte')}"
        self.close()
        raise LiveError(f"cannot write {path}: {error.strerror or error}{kept}", ExitStatus.ERROR)

    def close_raw(self) -> None:
        """Close --raw only (the compiled live path: the display writes -w, and closes it)."""
        raw, self._raw = self._raw, None
        if raw is not None:
            try:
                raw.close()
            except OSError:
                pass

    def close(self, stopped: Stamp | None = None) -> None:
        """Close both; -w ends with a record of no byte at `stopped`, when the capture stopped (a file
        records no other sign of it): its decode judges the last request's wait as live does. Not after
        nothing: with no record before it, it would time nothing."""
        if not self._closed:
            with contextlib.suppress(LiveError):
                self.release(None)  # (its items are shown before: CaptureThread.end, live.display_once)
        output, raw = self.output, self._raw
        self._raw = None
        ended = stopped is not None and self.last_time is not None and not self._closed
        self._closed = True
        for stream in (output, raw):
            if stream is not None:
                try:
                    if stream is output and ended:
                        output.close_at(stopped)  # type: ignore[union-attr,arg-type]
                    else:
                        stream.close()
                except OSError:
                    pass  # what could not be written was already reported


@dataclass
class Handoff:
    """Capture thread -> display: batches of framed items and the time before which all is framed.

    `put` never blocks: beyond `limit` waiting items, a batch is dropped and counted."""

    limit: int = HANDOFF_LIMIT
    dropped: int = 0
    _batches: deque[list[Item]] = field(default_factory=deque)
    _waiting: int = 0
    _safe: float | None = None
    _closed: bool = False
    _cond: threading.Condition = field(default_factory=threading.Condition)

    def put(self, items: list[Item], safe: float | None) -> None:
        with self._cond:
            if items:
                if self._waiting + len(items) > self.limit:
                    self.dropped += len(items)
                else:
                    self._batches.append(items)
                    self._waiting += len(items)
            if safe is not None:
                self._safe = safe
            if items or safe is not None:
                self._cond.notify()

    def close(self) -> None:
        with self._cond:
            self._closed = True
            self._cond.notify()

    def take(self, timeout: float) -> tuple[list[Item], float | None, bool]:
        """(items in order, safe time, closed); waits up to `timeout` for anything new."""
        with self._cond:
            if not self._batches and not self._closed:
                self._cond.wait(timeout)
            items = [item for batch in self._batches for item in batch]
            self._batches.clear()
            self._waiting = 0
            return items, self._safe, self._closed and not self._batches


TAPE_ENV = "VW3_LIVE_TAPE"  # record every read of the port to this file (tests, bug reports)
_TAPE_EVENT = struct.Struct("<dqI")  # monotonic time, stamp (ns), length; then the bytes


class Tape:
    """Every read of a live capture as the capture loop saw it: its bytes (none: the read timed out),
    its stamp and the monotonic time then. Given back to run_live (VW3_LIVE_REPLAY), it repeats the
    capture's decisions exactly, so that two decodes of one capture can be compared byte for byte."""

    def __init__(self, path: str) -> None:
        self._file = open(path, "wb")  # noqa: SIM115

    @classmethod
    def from_environment(cls) -> Tape | None:
        path = os.environ.get(TAPE_ENV)
        return cls(path) if path else None

    def record(self, data: bytes, stamp: Stamp, now: float) -> None:
        self._file.write(_TAPE_EVENT.pack(now, stamp.ns, len(data)) + data)

    def close(self) -> None:
        self._file.close()

    @staticmethod
    def read(path: str) -> Iterator[tuple[bytes, Stamp, float]]:
        with open(path, "rb") as tape:
            data = tape.read()
        at = 0
        while at < len(data):
            now, ns, length = _TAPE_EVENT.unpack_from(data, at)
            at += _TAPE_EVENT.size
            yield data[at : at + length], Stamp(ns), now
            at += length


@dataclass
class CaptureThread:
    """Reads until stopped, --duration, --count or a failure; `reason` and `status` say which."""

    port: serial.SerialBase
    framer: Framer | None  # None: the display frames the reads (dissector/accel/livepath.py)
    files: CaptureFiles
    handoff: Handoff
    silence: float
    duration: float | None = None
    count: int | None = None
    silence_long: float = IDLE_FLUSH_LONG
    port_name: str = ""
    # Seconds a character takes (char_time): None, the port's (port_char_time)
    char_time: float | None = None
    reason: str = "interrupted"
    status: ExitStatus = ExitStatus.OK
    frames: int = 0  # items written (-c counts items: frames and noise runs)
    stop: threading.Event = field(default_factory=threading.Event)
    done: threading.Event = field(default_factory=threading.Event)
    _last_data: float = 0.0  # monotonic time of the last read that gave bytes
    _pending: bool = False  # bytes fed since the last idle flush
    _tried: bool = False  # flush_due already tried a copy of the framer during this silence
    _clock: ReadClock | None = None  # the framer's byte times (none without a framer: LivePath's)
    # -w ends with a record of no byte at the stop (CaptureFiles.close); not the extcap's: Wireshark stops
    # reading its fifo as it stops it, and its own file says when (dumpcap's interface statistics).
    closing_record: bool = True
    last_read: Stamp | None = None  # the stamp of the last read, with bytes or none
    last_bytes: Stamp | None = None  # the stamp of the last read that gave bytes (its last byte's time)
    read: int = 0  # bytes read in all (CaptureFiles.release)

    def start(self) -> None:
        threading.Thread(target=self._run, name="capture", daemon=True).start()

    def flush_due(self, silent: float, tried: bool) -> bool:
        """Whether to close what the framer holds after `silent` seconds without bytes. Never in Modbus
        ASCII: a frame ends at its LF, and may hold a second's silence (timing.ASCII_LIMIT); the decode of
        the -w file cuts neither a frame nor a noise run at a silence (framing/stream.py _add_noise), so
        live holds them as it does (a partial frame is closed when the capture ends)."""
        if not self.framer.silence_cuts:  # type: ignore[union-attr]
            return False
        if silent >= self.silence_long:
            return True
        if tried or silent < self.silence:
            return False
        trial = copy.deepcopy(self.framer).finish(silence=True)  # type: ignore[union-attr]
        return any(isinstance(item, Frame) and item.crc_ok for item in trial)

    def deliver(self, items: list[Item], safe: float | None) -> bool:
        """Write, then hand on; False once --count items are written."""
        if self.count is not None:
            items = up_to_items(items, self.count - self.frames)[0]
        self.frames += len(items)  # (-c counts items: frames and noise runs)
        going = self.count is None or self.frames < self.count
        shown = self.files.items(items)
        if not going:  # (nothing follows: the noise run held is written now)
            shown += self.files.release(None)
        self.handoff.put(shown, safe)
        return going

    def safe_time(self, now: float) -> float:
        """No frame still to come starts before this: the held bytes' time, or now."""
        held = getattr(self.framer, "held_since", None)
        return now if held is None else min(now, held)

    def stopped_at(self) -> Stamp | None:
        """When the capture stopped: no byte before it went unread (ReadClock.promise of the last read, or
        the last byte's time if later). After -c, the last item's: the bytes after it are not written."""
        if self.reason == "count":
            return self.files.last_time
        read, data = self.last_read, self.last_bytes
        if read is None:
            return None
        promised = ReadClock.promise(read)
        return data if data is not None and promised.ns < data.ns else promised

    def _run(self) -> None:
        try:
            self._loop()
        except PortVanished as error:
            self.reason, self.status = f"{self.port_name} went away ({error})", ExitStatus.ERROR
        except LiveError as error:
            self.reason, self.status = str(error), error.status
        finally:
            self.end()

    def end(self) -> None:
        """The capture is over: what the framer holds is closed and written, the files closed."""
        try:
            # (what the framer holds is cut by a silence before the stop, by the line's rule, or by the stop:
            # StreamFramer.finish_at, as the decode of -w, whose closing record is at the stop, judges it)
            if self.framer is None:
                pass  # (the display frames: it finishes when the hand-off closes)
            elif self.reason != "count" and self.status == ExitStatus.OK:
                self.deliver(self.framer.finish_at(self.stopped_at()), None)
            elif self.status != ExitStatus.OK and not self.reason.startswith("cannot write"):
                self.deliver(self.framer.finish_at(self.stopped_at()), None)  # a vanished port: keep the bytes read
            if self.framer is not None and not self.reason.startswith("cannot write"):
                self.handoff.put(self.files.release(None), None)
        except LiveError as error:
            self.reason, self.status = str(error), error.status
        finally:
            if self.framer is None:
                self.files.close_raw()  # (-w is the display's: what it still frames goes there)
            else:
                self.files.close(self.stopped_at() if self.closing_record else None)
            self.handoff.close()
            self.done.set()

    def _loop(self) -> None:
        port = self.port
        deadline = None if self.duration is None else time.monotonic() + self.duration
        tape = Tape.from_environment()
        try:
            while not self.stop.is_set():
                if deadline is not None and time.monotonic() >= deadline:
                    self.reason = "duration"
                    return
                try:
                    data = port.read(max(1, port.in_waiting))
                    if data and port.in_waiting:
                        data += port.read(port.in_waiting)
                except (serial.SerialException, OSError) as error:
                    raise PortVanished(reason(error)) from None
                stamp = stamp_now()
                now = time.monotonic()
                if data:
                    self.files.raw(data)
                if tape is not None:
                    tape.record(data, stamp, now)
                if not self.step(data, stamp, now):
                    self.reason = "count"
                    return
                if self.framer is not None:
                    self.files.tick()  # (else the display's, which writes -w)
        finally:
            if tape is not None:
                tape.close()

    def step(self, data: bytes, stamp: Stamp, now: float) -> bool:
        """One read of the port (`data`, maybe none) stamped `stamp` at monotonic time `now`: frame it
        and hand the items on, or close what the framer holds after a silence; False once --count
        items are written. Without a framer (the compiled live path, dissector/accel/livepath.py)
        the read itself is handed on, and the display frames it."""
        self.last_read = stamp
        if data:
            self.last_bytes = stamp
            self.read += len(data)
        framer = self.framer
        if framer is None:
            self.handoff.put([(data, stamp, now)], None)  # type: ignore[list-item]
            return True
        clock = self._clock
        if clock is None:
            clock = self._clock = ReadClock(self.char_time or port_char_time(self.port))
        chunk = clock.chunk(data, stamp)
        if chunk is not None:
            self._last_data = now
            self._pending, self._tried = True, False
            return self.deliver(framer.feed(chunk), self.safe_time(stamp))
        safe = clock.promise(stamp)
        released = self.files.release(safe, self.read)
        if released:
            self.handoff.put(released, None)
        if self._pending:
            silent = now - self._last_data
            if self.flush_due(silent, self._tried):
                self._pending = False
                if not self.deliver(framer.finish(silence=True), safe):  # (the capture goes on: a silence cuts)
                    return False
            else:
                self.handoff.put([], self.safe_time(safe))
            self._tried = self._tried or silent >= self.silence
        else:
            self.handoff.put([], safe)
        return True
