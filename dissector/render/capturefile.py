"""The -w output: a pcap or pcapng file, standard output (`-w -`), or a ring buffer of files.

The format is pcapng with `-F pcapng` or a `.pcapng` suffix, pcap otherwise. Records are written
whole, one write(2) each on an unbuffered stream when `flush` (live), so every file is valid at any
instant and `-w - | wireshark -k -i -` sees each record as it is heard.

The ring buffer follows dumpcap's `-b`: `filesize:N` switches to the next file once a file holds N kB
(1000 bytes), `duration:S` once it has been open S seconds, `files:K` keeps only the newest K files.
Files are named as dumpcap names them, `prefix_NNNNN_YYYYmmddHHMMSS.suffix` from `-w prefix.suffix`
(number from 00001, local time of the file's first record). A record is never split: each file is a
valid capture. The next file is opened by the record that goes in it, so a filesize switch at the end
leaves no header-only file (that would count against files:K and push out a file with records).

Live, `duration:S` is wall-clock time, files switching with or without bytes heard (dumpcap). Decoding
a file, it is the records' time, as `editcap -i S` splits: windows of S seconds from the first record
(a record exactly at a window's end stays in it), a window without records makes no file.

A record is never torn either: records reach the file through `WholeRecords`, which on a failed write
(a full disk, a file size limit) cuts the file back to the last whole record and counts what it kept,
so the error can say so and the file still opens in Wireshark.
"""
from __future__ import annotations

import contextlib
import os
import stat
import time
from collections import deque
from dataclasses import dataclass
from typing import BinaryIO, Protocol

from dissector.framing.rules import spans_a_frame
from dissector.model import Item, Noise
from dissector.render.describe import count_text
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import MICROS, SNAPLEN, PcapWriter, split_time
from dissector.render.wholerecords import WholeRecords
from dissector.render.pcapnghead import Interface

FORMATS = ("pcap", "pcapng")
STDOUT = "-"


def noise_comment(item: Item) -> str | None:
    """The pcapng comment of a record: why its bytes are not a frame."""
    if isinstance(item, Noise):
        return f"noise: {count_text(item.length, 'byte')}, {item.reason}"
    return None


# Held by write_items: (bytes, time, vw3-decode's comments, the input's packet comments, end offset, whether
# it goes on an item begun in the record before: a -b ring keeps it in that record's file).
HeldRecord = tuple[bytes, float | None, list[str], list[str], int, bool]
# sources/trail.py: (end in the item, time, comments, where its record begins in the stream)
Piece = tuple[int, float | None, tuple[str, ...], int]

class RecordWriter(Protocol):
    size: int
    clamped: int

    def write(self, data: bytes, timestamp: float | None = None,
              comment: str | list[str] | None = None, original: int | None = None) -> None: ...

    def use_interface(self, name: str | None, description: str | None, units: int | None = None) -> None: ...

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


def _micros(timestamp: float) -> int:
    seconds, micros = split_time(timestamp)
    return seconds * 1_000_000 + micros


def ring_name(path: str, number: int, opened: float) -> str:
    """dumpcap's name for the file number `number` of the ring `path`."""
    root, suffix = os.path.splitext(path)
    try:
        local = time.localtime(split_time(opened)[0])
    except (OverflowError, OSError, ValueError):  # a record's time no calendar holds: name it by now
        local = time.localtime()
    stamp = time.strftime("%Y%m%d%H%M%S", local)
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
        interface: Interface | None = None,
        units: int = MICROS,
        frame_records: bool = False,
        interface_units: int | None = None,
    ) -> None:
        self.path = path
        # --frame-records: an item is one record at its time, not the reads it came in (write_items)
        self._frame_records = frame_records
        self.units = units  # of its times (pcapng: of interfaces without their own): a nanosecond capture's, ns
        self.format = file_format(path, fmt)
        self.ring = ring
        self._flush = flush
        self._stdout = stdout
        self._interface = interface  # (if_name, if_description) for pcapng
        self._interface_units = interface_units  # its own (a copied pcapng interface's if_tsresol), or None
        self._writer: RecordWriter | None = None
        self._number = 0
        self._opened = 0.0
        self._in_file = 0  # records in the file being written
        self._full = False  # filesize reached: the next record opens the next file
        self._window_end: int | None = None  # decoding: microseconds where the file's duration window ends
        self.paths: list[str] = []  # every file written, in order (a ring's deleted ones too)
        self._kept: deque[str] = deque()
        self._records: WholeRecords | None = None
        self.clamped = 0  # records of closed files whose time the format could not hold
        # A noise run write_items holds for the item after it, and the record before it (release).
        self._held: HeldRecord | None = None
        self._last: HeldRecord | None = None
        # Records before _last not written yet: an item from inside a chunk takes the chunk's earlier bytes
        # into its first record (write_items); at most SNAPLEN bytes back.
        self._done: deque[HeldRecord] = deque()
        self._settled = -1  # a record ending there or before is out of _absorb's reach (write_items)
        self._open()

    @property
    def name(self) -> str:
        """What the summary says was written."""
        if self.path == STDOUT:
            return "standard output"
        if self.ring is not None and self.paths:
            return f"{self.paths[0]} .. {self.paths[-1]}" if len(self.paths) > 1 else self.paths[0]
        return self.path

    def _open(self, stamp: float | None = None) -> None:
        """Open the next file; `stamp`: the time its name says (its first record's), else now."""
        self._in_file = 0
        self._full = False
        if self.path == STDOUT:
            if self._stdout is None:
                raise OSError("standard output is not a byte stream")
            stream = WholeRecords(self._stdout, self._flush, truncate=False)
            target = STDOUT
        else:
            self._opened = time.time()
            target = self.path
            if self.ring is not None:
                self._number += 1
                target = ring_name(self.path, self._number, self._opened if stamp is None else stamp)
            # Unbuffered: WholeRecords batches whole records itself (one write(2) a record when live,
            # on disk before it is handed on).
            stream = WholeRecords(open(target, "wb", buffering=0), self._flush, truncate=True)  # noqa: SIM115
            self.paths.append(target)
            self._kept.append(target)
        self._stream = self._records = stream
        binary: BinaryIO = stream  # type: ignore[assignment]  (write, flush and close are what writers use)
        try:
            if self.format == "pcapng":
                name, description = self._interface or (None, None)
                self._writer = PcapngWriter(binary, flush=self._flush, if_name=name, if_description=description,
                                            units=self.units, if_units=self._interface_units)
            else:
                self._writer = PcapWriter(binary, flush=self._flush, units=self.units)
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

    def write(self, data: bytes, timestamp: float | None = None,
              comment: str | list[str] | None = None, continued: bool = False, original: int | None = None) -> None:
        """`comment`: a list is a comment each (pcapng); `continued`: the record goes on an item begun in the
        record before, in the same file (each file of a ring decodes as its part of the decode); `original`: the
        record's length on the line, when only its bytes `data` of it were captured (RecordWriter.write)."""
        if self._writer is None:
            raise OSError("the capture file is closed")
        ring = self.ring
        if ring is not None and not continued:
            if self._flush:  # live: times are now
                self.tick()
                if self._full:
                    self._next()
            else:
                self._switch_on(timestamp, ring)
        if original is None:
            self._writer.write(data, timestamp, comment)
        else:
            self._writer.write(data, timestamp, comment, original)
        self._in_file += 1
        if ring is not None and ring.filesize is not None and self._writer.size >= ring.filesize * 1000:
            self._full = True

    def _switch_on(self, timestamp: float | None, ring: Ring) -> None:
        """Decoding: the next file when this record's time or the file's size says so."""
        window = max(1, round(ring.duration * 1_000_000)) if ring.duration is not None else None
        if self._full:
            self._next(timestamp)
            if timestamp is not None and window is not None:  # a filesize switch restarts the window,
                self._window_end = _micros(timestamp) + window  # as dumpcap's timer restarts
            return
        if timestamp is None:
            return  # (no time: nothing to switch on)
        if self._in_file == 0 and self._number == 1:
            self._rename(timestamp)  # the first file, opened before any record, named for its first
        if window is None:
            return
        micros, end = _micros(timestamp), self._window_end
        if end is None:
            self._window_end = micros + window
        elif micros > end:
            self._window_end = end - (end - micros) // window * window  # the window holding it
            self._next(timestamp)

    def _rename(self, stamp: float) -> None:
        """The file opened before any record was known takes the name of its first record's time."""
        new = ring_name(self.path, self._number, stamp)
        old = self.paths[-1]
        if new != old:
            os.replace(old, new)
            self.paths[-1] = self._kept[-1] = new

    def use_interface(self, interface: Interface | None, units: int | None = None) -> None:
        """The interface the next records were captured on (the next input of a decode) and its time
        units (a pcapng's if_tsresol; None: the file's): pcapng describes it (a new interface block when it
        differs), pcap has no place for it."""
        if (interface, units) == (self._interface, self._interface_units):
            return
        self.release()  # a held noise run belongs to the input before
        self._interface, self._interface_units = interface, units
        if self._writer is not None:
            self._writer.use_interface(*(interface or (None, None)), units)

    def write_items(self, items: list[Item], pieces: dict[int, list[Piece]] | None = None,
                    settled: int | None = None) -> None:
        """Write items of a decode so that the file decodes back to the same items: a record an item,
        except that a noise run shares the record of the item after it when that is more noise or a
        damaged frame (one heard at the same time, within SNAPLEN bytes), or, ending the input, the
        record before it when alone it would be a frame by its shape (release).

        A reader takes a record's end for a pause of the line, evidence that a frame ends there
        (framing/rtu.py _followed), and the line gave none where a noise run stops: a record ending there
        made a frame of a CRC-valid tail of the noise (d1 | 03 17 02 00 00 c4 74, then the damaged frame
        01 e9 bb b8 2b), or of a damaged frame ending where the noise did, that the decode had found no
        frame. Before an intact frame the record ends all the same (each frame a record of its own, as
        Wireshark's mbrtu reads them): that frame is the framer's evidence there anyway.

        `pieces` (sources/trail.py, by id(item)): an item whose input's time changes inside it is written
        as the chunks it came in, each a record at its own time (a silence inside a frame reads back as
        one), an item from inside a timed chunk has its first record take the chunk's earlier bytes
        (_absorb: a copy of timed reads is its reads), and the input's packet comments go on the records
        of the bytes they were on, each an opt_comment.
        `settled` (sources/trail.py RecordTrail.settled): no item after these begins its first record before
        this stream offset; when none of these does either (none takes earlier bytes), the records ending
        there are out of _absorb's reach: they are written, not held back."""
        if pieces and self._frame_records:
            pieces = _whole_items(items, pieces)
        absorbing = pieces and any(split[0][3] < item.offset
                                   for item in items if (split := pieces.get(id(item))))
        self._settled = -1 if settled is None or absorbing else settled
        done = self._done
        while done and done[0][4] <= self._settled:
            data, time, own, users, _end, continued = done.popleft()
            self._write_record(data, time, own, users, continued)
        for item in items:
            split = pieces.get(id(item)) if pieces else None
            if isinstance(item, Noise) and item.part is not None:
                self._part(item, item.part.original - item.part.captured, split)
                continue
            lead = None
            if split is not None and split[0][3] < item.offset:
                lead = self._absorb(split[0][3], item.offset, split[0][0])
                if lead is None:  # (written already: one record, as before)
                    split = [(item.length, item.time, tuple(text for piece in split for text in piece[2]), 0)]
            if split is None:
                if self._held is None and type(item) is not Noise:  # (the usual: a frame, its own record)
                    self._record((item.raw, item.time, [], [], item.offset + item.length, False))
                else:
                    self._piece(item, 0, item.length, item.time, [])
                continue
            begin = 0
            for end, time, comments, _start in split:
                self._piece(item, begin, end, time, list(comments), lead if begin == 0 else None)
                begin = end

    def _part(self, item: Noise, lost: int, split: list[Piece] | None) -> None:
        """A record captured in part (framing/stream.py _cut_part) is written as it was read: its bytes, and its
        length on the line `lost` bytes more (as editcap -s writes it), so that the copy reads back as a cut
        again. Before, written whole, its bytes and the next record's read back as a CRC BAD frame. The stream
        was closed before it as at an input's end (the framer frames it so): what is held is written first,
        as release writes it, and nothing joins it."""
        self.release()
        users = [text for piece in split for text in piece[2]] if split else []
        self.write(item.raw, item.time, [*users, noise_comment(item) or ""], original=item.length + lost)

    def _absorb(self, anchor: int, offset: int, length: int) -> HeldRecord | None:
        """The records not yet written holding the bytes anchor..offset, taken out as one (one that begins
        before `anchor` cut there), to begin the record of the item after them (`length` bytes of it);
        None when they are not all there."""
        chain = [*self._done, *(record for record in (self._last, self._held) if record is not None)]
        taken: list[HeldRecord] = []
        while chain and chain[-1][4] > anchor:
            taken.insert(0, chain.pop())
        if not taken or taken[-1][4] != offset or offset - anchor + length > SNAPLEN:
            return None
        if any(after[4] - len(after[0]) != before[4] for before, after in zip(taken, taken[1:])):
            return None
        head = taken[0]
        cut = anchor - (head[4] - len(head[0]))
        if cut < 0:
            return None
        if cut:  # (a record of several chunks of one time)
            chain.append((head[0][:cut], head[1], head[2], head[3], anchor, head[5]))
            taken[0] = (head[0][cut:], head[1], [], [], head[4], True)
        self._held = None
        self._last = chain.pop() if chain else None
        self._done = deque(chain)
        return (b"".join(record[0] for record in taken), taken[0][1], [text for record in taken for text in record[2]],
                [text for record in taken for text in record[3]], offset, taken[0][5])

    def _piece(self, item: Item, begin: int, end: int, time: float | None, users: list[str],
               lead: HeldRecord | None = None) -> None:
        """The item's bytes begin..end, a record's worth, with the input's packet comments `users`; `lead`:
        the chunk's bytes before it (_absorb), which its record begins with."""
        noise = isinstance(item, Noise)
        data = item.raw[begin:end] if begin or end < item.length else item.raw
        first, last = begin == 0, end == item.length
        if lead is not None:  # (the noise after the read's first bytes: "then noise: ...", as release says it)
            own = [*lead[2], *([f"then {noise_comment(item)}"] if noise else [])]
            # (at the time of the read it begins with, the item's: the records taken may be of an earlier one)
            self._record((lead[0] + data, time, own, lead[3] + users, item.offset + end, lead[5]))
            return
        held = self._held
        if held is not None:
            self._held = None
            kept, timestamp, comments, notes, stop, continued = held
            if (first and item.offset == stop and time == timestamp and (noise or not item.crc_ok)
                    and len(kept) + len(data) <= SNAPLEN):
                joined = (kept + data, timestamp, comments, notes + users, stop + len(data), continued)
                if noise:
                    comments.append(noise_comment(item) or "")
                    if last:
                        self._held = joined
                    else:
                        self._record(joined)
                    return
                comments.append(f"then a damaged frame ({item.length} bytes)")
                self._record(joined)
                return
            self._record(held)
        own = [noise_comment(item) or ""] if noise and first else []
        record = (data, time, own, users, item.offset + end, not first)
        if noise and last:
            self._held = record
        else:
            self._record(record)

    def _record(self, record: HeldRecord) -> None:
        """Write the record held before this one and hold this one (release may add to it)."""
        last, self._last = self._last, record
        done = self._done
        if last is not None:
            if done or last[4] > self._settled:
                done.append(last)
            else:  # (out of _absorb's reach: write_items)
                self._write_record(last[0], last[1], last[2], last[3], last[5])
                return
        while done and done[0][4] <= record[4] - SNAPLEN:
            data, time, own, users, _end, continued = done.popleft()
            self._write_record(data, time, own, users, continued)

    def _write_record(self, data: bytes, time: float | None, own: list[str], users: list[str],
                      continued: bool) -> None:
        """A record with the input's packet comments, then vw3-decode's (one comment, "; " between)."""
        self.write(data, time, [*users, "; ".join(own)] if own else users, continued)

    def release(self) -> None:
        """Write the records write_items holds (the input ends, or the file is closed).

        A noise run ending the input that alone would be a frame by its shape (framing/rules.py
        spans_a_frame) goes at the end of the record before it (heard at the same time, right before it,
        within SNAPLEN bytes). The input's end says little of a frame there, unless it is the answer
        awaited (framing/rtu.py _followed), and the decode found none; a record's start and end would
        bound one (the record a damaged FC21 request, 1c 15 13 06 ... 09 b2, after cd 0b 14 e7). Not
        at a record's start, the reader decides its bytes at the end of the input, as the decode did."""
        while self._done:
            early = self._done.popleft()
            self._write_record(*early[:4], early[5])
        held, last = self._held, self._last
        self._held = self._last = None
        if held is not None and last is not None and self._joins(last, held):
            data, timestamp, comments, notes, _end, continued = last
            frame = [] if comments else [f"a frame ({count_text(len(data), 'byte')})"]
            noise = [f"then {comment}" for comment in held[2]]
            self._write_record(data + held[0], timestamp, [*comments, *frame, *noise], notes + held[3], continued)
            return
        for record in (last, held):
            if record is not None:
                self._write_record(*record[:4], record[5])

    @staticmethod
    def _joins(last: HeldRecord, noise: HeldRecord) -> bool:
        """May the noise run ending the input go at the end of the record before it (release)?"""
        data = noise[0]
        return (
            last[4] == noise[4] - len(data)
            and last[1] == noise[1]
            and len(last[0]) + len(data) <= SNAPLEN
            and spans_a_frame(data)
        )

    def tick(self, now: float | None = None) -> None:
        """Live, a ring with duration:S switches files on time, heard bytes or not (as dumpcap)."""
        ring = self.ring
        if ring is not None and ring.duration is not None and self._writer is not None and self._flush:
            if (now if now is not None else time.time()) - self._opened >= ring.duration:
                self._next()

    def _next(self, stamp: float | None = None) -> None:
        self._close_writer()
        self._open(stamp)

    @property
    def kept(self) -> str:
        """What the file being written holds after a failed write: whole records only."""
        records = self._records
        whole = max(0, records.whole - 1) if records is not None else 0  # the first write is the file header
        size = records.on_disk if records is not None else 0
        where = "standard output" if self.path == STDOUT else (self.paths[-1] if self.paths else self.path)
        return f"{where} keeps {count_text(whole, 'whole record')} ({count_text(size, 'byte')})"

    @property
    def clamped_total(self) -> int:
        return self.clamped + (self._writer.clamped if self._writer is not None else 0)

    def _close_writer(self) -> None:
        writer, self._writer = self._writer, None
        if writer is not None:
            self.clamped += writer.clamped
        if self.path == STDOUT:
            self._stream.flush()
            return
        if writer is not None:
            writer.close()
        else:
            self._stream.close()

    def close(self) -> None:
        if self._writer is not None:
            try:
                self.release()
            finally:
                self._close_writer()

    def close_at(self, stopped: float) -> None:
        """Live: close with a record of no byte at `stopped`, when the capture stopped, in the file being
        written (a ring does not open the next for it: it ends what the last file holds)."""
        if self._writer is not None:
            try:
                self._writer.write(b"", stopped)
            finally:
                self.close()

    def discard_if_empty(self) -> None:
        """Close; a file that holds no record is removed (a refused input leaves no header-only file).
        One that holds records keeps them, as tshark -w keeps what it wrote before a damaged packet."""
        if self._writer is not None:
            try:
                self.release()
            except OSError:
                self.close()
                raise
        records = self._records
        self.close()  # (counted after: records waiting in memory are written by closing)
        empty = records is not None and records.whole <= 1  # the first write is the file header
        if empty and self.path != STDOUT and self.paths and regular_file(self.paths[-1]):
            with contextlib.suppress(OSError):
                os.unlink(self.paths[-1])


def _whole_items(items: list[Item], pieces: dict[int, list[Piece]]) -> dict[int, list[Piece]]:
    """`pieces` as --frame-records writes them: each item one piece at its own time, its comments all on it,
    taking no bytes of the read before it (Wireshark's mbrtu reads a frame only whole in one record; the
    silences inside a frame, which a tap's reads tell, are not kept)."""
    whole = {}
    for item in items:
        split = pieces.get(id(item))
        if split is not None:
            whole[id(item)] = [(item.length, item.time, tuple(text for piece in split for text in piece[2]),
                                item.offset)]
    return whole


def regular_file(path: str) -> bool:
    """A name that may be removed after a refused input: a regular file itself, not a symlink (-w
    link.pcap removed the link, -w /dev/stdout would remove /dev/stdout) nor a device (/dev/null)."""
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False


def open_output(
    path: str,
    fmt: str | None,
    ring_specs: list[str] | tuple[str, ...],
    flush: bool,
    stdout: BinaryIO | None,
    interface: Interface | None = None,
    units: int = MICROS,
    frame_records: bool = False,
    interface_units: int | None = None,
) -> CaptureOutput:
    """The -w output from the options; ValueError for bad -b options, OSError from the system."""
    ring = Ring.parse(list(ring_specs)) if ring_specs else None
    if ring is not None and path == STDOUT:
        raise ValueError("-b needs -w FILE, not standard output")
    if path == STDOUT and stdout is not None and stdout.isatty():
        # Binary records would garble the terminal (tshark and dumpcap refuse it too).
        raise ValueError("-w -: standard output is a terminal; pipe it (| wireshark -k -i -) or give a file")
    return CaptureOutput(path, fmt, ring, flush=flush, stdout=stdout, interface=interface, units=units,
                         frame_records=frame_records, interface_units=interface_units)
