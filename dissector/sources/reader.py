"""Opening captures: a path (or "-" for stdin) in, a stream of model.Chunk out.

The format is read from the content, never from the file name: pcap and pcapng by their magic
numbers, a text hex dump or a Modbus ASCII byte stream by the shape of their first lines, anything
else as raw serial bytes. Text saved with a byte order mark (UTF-8, UTF-16, UTF-32: Notepad, PowerShell)
is judged and read as its text when it is in a text format (encoding.py). The framing mode (RTU or
ASCII) is then read from the first payload bytes.
`fmt` and `mode` override either guess.

Everything streams: files are read in chunk_size pieces and a pcap record becomes one Chunk (with
its timestamp and boundary=True), so memory does not grow with the capture. Problems that stop the
reading raise SourceError with one line for the user, at open time or during iteration; problems
the reading survives (a truncated last record, a skipped block) go to `Source.warnings`.
"""
from __future__ import annotations

import io
import os
import stat
import sys
from collections.abc import Callable, Iterator
from itertools import islice
from typing import BinaryIO

from dissector.protocol.ascii import MODE_REACH, MODE_SAMPLE, sample_mode  # (MODE_SAMPLE: codegen's)
from dissector.sources.common import Input, SourceError, WarningLog, rereadable
from dissector.sources.compressed import HEADER_BYTES, Decompressed, compression
from dissector.sources.dumps import dump_tool, read_dump, refuse_words, word_dump
from dissector.sources.ethernet import RtuPorts
from dissector.sources.encoding import Encoding, decoded, marked, text_input
from dissector.sources.hexdump import CONTROL, characters, looks_like_hexdump, read_hexdump
from dissector.sources.interfaces import network_chunks, packet_interfaces, several_interfaces
from dissector.sources.libmodbus import looks_like_libmodbus, read_libmodbus
from dissector.sources.packetdump import looks_like_packet_dump, read_packet_dump
from dissector.sources.notation import DECIMAL, HEX, Notation
from dissector.sources.pcap import PcapRecords, is_pcap, read_pcap
from dissector.sources.pymodbus_log import looks_like_pymodbus, read_pymodbus
from dissector.sources.pcapng import is_pcapng, read_pcapng
from dissector.sources.traffic import looks_like_traffic, read_traffic
from dissector.model import Chunk, Stamp

__all__ = ["FORMATS", "Source", "SourceError", "detect_format", "open_source"]

# --format values -> Source.format
FORMATS = {"raw": "raw", "pcap": "pcap", "pcapng": "pcapng", "hex": "hexdump", "hexdump": "hexdump",
           "decimal": "hexdump", "ascii": "ascii", "xxd": "xxd", "hexdump-C": "hexdump-C", "od": "od", "traffic": "traffic",
           "tshark-x": "tshark-x", "libmodbus": "libmodbus", "pymodbus": "pymodbus"}
# A format given for a one-frame-a-line dump also says how its numbers are written.
NOTATIONS = {"hex": HEX, "hexdump": HEX, "decimal": DECIMAL}
MODES = ("rtu", "ascii")
TEXT_FORMATS = frozenset({"hexdump", "xxd", "hexdump-C", "od", "traffic", "ascii", "tshark-x", "libmodbus",
                          "pymodbus"})  # read as text when a BOM says so
SNIFF_BYTES = 512  # enough to see a magic number or a few text lines
SNIFF_LINES = 4  # a text sample with this many lines is enough to judge
SNIFF_COMMENTS = 65536  # but a hex dump's header of comments is read to its first data line, this far
MIN_CHUNK = 256

Reader = Callable[[Input, WarningLog, int], Iterator[Chunk]]


def _read_raw(inp: Input, log: WarningLog, chunk_size: int) -> Iterator[Chunk]:
    while True:
        data = inp.read_some(chunk_size)
        if not data:
            return
        yield Chunk(data)


READERS: dict[str, Reader] = {
    "raw": _read_raw,
    "ascii": _read_raw,
    "pcap": read_pcap,
    "pcapng": read_pcapng,
    "hexdump": read_hexdump,
    "xxd": read_dump("xxd"),
    "hexdump-C": read_dump("hexdump-C"),
    "od": read_dump("od"),
    "words": refuse_words,  # hexdump's default, od -x: refused, naming the dumps that say their bytes
    "traffic": read_traffic,  # Modbus Poll / Modbus Slave traffic logs
    "tshark-x": read_packet_dump,  # tshark -x, vw3-decode -x
    "libmodbus": read_libmodbus,  # libmodbus debug output, mbpoll -v
    "pymodbus": read_pymodbus,  # pymodbus debug logs: send:/recv: lines
}


def _is_text(sample: bytes) -> bool:
    """Printable characters, tabs and line ends: ASCII, and bytes from 80h up, which a text in UTF-8 or
    an 8-bit code page has in its comments (`# Drehzahl ändern`). A control byte makes it binary (every
    RTU frame has one: its function code)."""
    return bool(sample) and CONTROL.search(sample) is None


def _text_of(sample: bytes, complete: bool) -> tuple[Encoding, bytes, bool] | None:
    """(encoding, decoded sample, whether that is all) of an input whose BOM names an encoding it decodes
    in (encoding.py); else None."""
    encoding = marked(sample)
    text = decoded(sample, encoding, complete) if encoding is not None else None
    return (encoding, *text) if encoding is not None and text is not None else None


def detect_text(sample: bytes, complete: bool) -> tuple[str, str | None, Encoding | None]:
    """detect_format, and the encoding to read the input in: a BOM's (encoding.py), when the text after it
    is in a text format; else None, and the input is judged as the bytes it is (a binary capture that
    starts with FF FE stays binary)."""
    text = _text_of(sample, complete)
    if text is not None and _is_text(text[1]):  # (never judged by its magic numbers: they are not text)
        encoding, body, whole = text
        format, warning = detect_format(body, whole)
        if format != "raw":
            return format, warning, encoding
        if warning is not None:  # text in no format we read: its bytes, as any text's
            return "raw", warning.replace("the input is text", f"the input is text ({encoding.name})"), None
    return (*detect_format(sample, complete), None)


def detect_format(sample: bytes, complete: bool) -> tuple[str, str | None]:
    """(format, warning or None) for the first bytes of an input; `complete` when that is all of it."""
    if is_pcap(sample):
        return "pcap", None
    if is_pcapng(sample):
        return "pcapng", None
    if not _is_text(sample):
        return "raw", None
    text = characters(sample, complete)
    if text.lstrip().startswith(":"):
        return "ascii", None
    if looks_like_traffic(text, complete):
        return "traffic", None
    tool = dump_tool(text, complete)
    if tool is not None:
        return tool, None
    if word_dump(text):
        return "words", None
    if looks_like_packet_dump(text, complete):
        return "tshark-x", None
    if looks_like_hexdump(text, complete):
        return "hexdump", None
    if looks_like_libmodbus(text, complete):  # (its program's lines between the frames are no hex dump's)
        return "libmodbus", None
    if looks_like_pymodbus(text, complete):  # (before the hex dump's `most`: its 0x.. lines follow a logging prefix)
        return "pymodbus", None
    # Most lines of a format and a few not (a typo, a cut line, a note without `#`): that format, whose
    # reader names the line it refuses, rather than the text's characters decoded as bytes.
    if looks_like_traffic(text, complete, most=True):
        return "traffic", None
    if looks_like_hexdump(text, complete, most=True):
        return "hexdump", None
    if not sample.isascii() and text == sample.decode("latin-1"):  # not UTF-8: no more text than any binary
        return "raw", None
    return "raw", "the input is text, but neither a hex dump nor Modbus ASCII: decoded as raw bytes"


def _open(path: str, stdin: BinaryIO | None = None) -> tuple[BinaryIO, str, bool]:
    """(stream, display name, whether to close it)."""
    if path == "-":
        return (stdin if stdin is not None else sys.stdin.buffer), "standard input", False  # (the README's name)
    try:
        if stat.S_ISDIR(os.stat(path).st_mode):
            raise SourceError(f"{path}: is a directory, not a capture")
        return open(path, "rb"), path, True
    except FileNotFoundError:
        raise SourceError(f"{path}: no such file") from None
    except PermissionError:
        raise SourceError(f"{path}: permission denied") from None
    except OSError as error:
        raise SourceError(f"{path}: cannot open: {error.strerror or error}") from None


def _sniff(inp: Input) -> tuple[bytes, bool]:
    """The input's first bytes, and whether they are all of it.

    Reads as little as decides the question, so that a live pipe is not held back for long.
    """
    sample = b""
    regular = rereadable(inp)  # (a live feed is judged on what came: it is not held for a tree's 64 KiB)
    while True:
        wanted = max(SNIFF_BYTES, len(sample))  # (doubling: a long undecided text is judged a few times, not each 512 B)
        part = inp.stream.read1(wanted) if hasattr(inp.stream, "read1") else inp.stream.read(wanted)
        if not part:
            return sample, True
        sample += part
        if len(sample) >= 4 and not _is_text(sample):
            text = _text_of(sample, False)
            if text is None or not _is_text(text[1]):
                break
        if (sample.count(b"\n") >= SNIFF_LINES or len(sample) >= SNIFF_BYTES) and not _comments_only(sample) \
                and not (regular and _undecided(sample)):
            break
    return sample, False


def _comments_only(sample: bytes) -> bool:
    """Lines of text so far (the last maybe cut), each blank or a `#` comment, and room to read on: a hex
    dump's header, which says nothing of the format; its first data line does."""
    text = _text_of(sample, False)
    body = text[1] if text is not None else sample
    return (len(sample) < SNIFF_COMMENTS and _is_text(body)
            and all(not line.strip() or line.lstrip().startswith(b"#") for line in body.split(b"\n")))


def _undecided(sample: bytes) -> bool:
    """Text in no format we read so far, and room to read on: a packet's details before its bytes (tshark -V -x,
    Wireshark's Export Packet Dissections as plain text, saved to a file) put the first dump line a whole tree
    (~1 KB) in."""
    if len(sample) >= SNIFF_COMMENTS:
        return False
    text = _text_of(sample, False)
    body = text[1] if text is not None else sample
    if not _is_text(body):
        return False
    format, warning = detect_format(body, False)
    return format == "raw" and warning is not None


class Source:
    """An iterable of Chunk (once), with `format`, `mode`, `name` and `warnings`.

    Iteration may raise SourceError. `warnings` grows while iterating; `take_warnings()` returns
    the ones not taken yet, for a caller that prints them as they come.
    """

    def __init__(
        self, chunks: Iterator[Chunk], head: list[Chunk], format: str, mode: str, name: str,
        log: WarningLog, closer: Callable[[], None],
    ) -> None:
        self.format = format
        self.mode = mode
        self.name = name
        self._chunks = chunks
        self._head = head
        self._log = log
        self._closer = closer
        self._taken = 0
        self._defer = False
        # (chunk, record number) of the chunks read ahead, in order (number_of)
        self._numbered: list[tuple[Chunk, int | None]] = list(zip(head, getattr(head, "numbers", ())))
        # Not a regular file (standard input, a pipe, a FIFO): bytes come as they are written, and a
        # reader must not wait for more than what is there before it shows what it has.
        self.streaming = True

    @property
    def warnings(self) -> list[str]:
        return self._log.messages

    def defer_damage(self) -> Source:
        """Damage after the input's first packet (a pcapng's corrupt block) ends its chunks and is kept in `damage`
        rather than raised at their end: the decode shows the packets before it, then refuses the input
        (app/cli.py), as tshark shows them before its error. Before, nothing was shown."""
        self._defer = True
        return self

    @property
    def damage(self) -> SourceError | None:
        """Once read: what damaged the input after its first packet; None: nothing."""
        return getattr(self._chunks, "damage", None)

    def _damaged(self) -> None:
        """Raise the damage that ended the chunks, unless deferred (defer_damage)."""
        if self.damage is not None and not self._defer:
            raise self.damage

    @property
    def recorded_until(self) -> Stamp | None:
        """Once read: when the capture's last record was made, one no chunk holds too (a pcapng's other
        interfaces', an empty one: sources/pcapng.py PcapngChunks); None: its last chunk says."""
        return getattr(self._chunks, "recorded_until", None)

    @property
    def packet_number(self) -> int | None:
        """A pcap's or pcapng's: the record number (tshark's frame.number) of the chunk given last; None for others."""
        return getattr(self._chunks, "packet_number", None)

    def number_of(self, chunk: Chunk) -> int | None:
        """The record number (tshark's frame.number) of `chunk`, the next given (read ahead, or the last read)."""
        numbered = self._numbered
        if numbered:
            if numbered[0][0] is chunk:
                return numbered.pop(0)[1]
            numbered.clear()  # (not taken in order: no longer known)
        return self.packet_number

    @property
    def packet_total(self) -> int | None:
        """Once read, a pcap's or pcapng's records (a ring's next file numbers on from them); None for others."""
        return getattr(self._chunks, "packet_total", None)

    @property
    def packet_times(self) -> object:
        """A network capture's packet times (sources/ethernet.py PacketTimes); None for others."""
        return getattr(self._chunks, "packet_times", None)

    @property
    def time_units(self) -> int | None:
        """The time units a second of a pcap's or pcapng's records (the time column's decimals:
        render/timefmt.py column_digits); None: not a binary capture, or one with no record. A pcapng none
        of whose packets was read yet (--mode: no sample) reads its first now (replayed first): its
        interfaces are described before it. (Asked before its chunks are read.)"""
        units = getattr(self._chunks, "time_units", None)
        if units is None and self.format == "pcapng" and not self._head:
            self._head = HeadChunks()
            for chunk in islice(self._chunks, 1):
                self._head.append(chunk)
                self._head.numbers.append(self.packet_number)
            self._numbered = list(zip(self._head, self._head.numbers))
            units = getattr(self._chunks, "time_units", None)
        return units

    def take_warnings(self) -> list[str]:
        new = self._log.messages[self._taken :]
        self._taken = len(self._log.messages)
        return new

    def __iter__(self) -> Iterator[Chunk]:
        try:
            head, self._head = self._head, []
            yield from head
            yield from self._chunks
            self._damaged()
        finally:
            self._log.close()
            self.close()

    def parts(self) -> tuple[list[Chunk], Iterator[Chunk]]:
        """Instead of iterating: the chunks read to choose the mode, and the reader of the rest (a
        pcap's reads it in bulk: accel/records.py). Call finished() after the last."""
        head, self._head = self._head, []
        return head, self._chunks

    def finished(self) -> None:
        """The end of reading through parts(), as of iterating."""
        self._log.close()
        self.close()
        self._damaged()

    def close(self) -> None:
        self._closer()

    def __enter__(self) -> Source:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def open_source(
    path: str,
    fmt: str | None = None,
    chunk_size: int = 65536,
    mode: str | None = None,
    stdin: BinaryIO | None = None,
    ports: RtuPorts = RtuPorts(),
) -> Source:
    """Open a capture. `fmt`: one of FORMATS (decimal: a hex dump's lines in decimal); `mode`: rtu or ascii;
    `ports`: the TCP/UDP ports whose payloads are Modbus RTU in a pcap or pcapng of a network link.

    Raises SourceError with a one-line message for anything that cannot be read.
    """
    if fmt is not None and fmt not in FORMATS:
        raise SourceError(f"unknown format {fmt!r}: choose from {', '.join(sorted(FORMATS))}")
    if mode is not None and mode not in MODES:
        raise SourceError(f"unknown mode {mode!r}: choose rtu or ascii")
    chunk_size = max(chunk_size, MIN_CHUNK)
    stream, name, owned = _open(path, stdin)
    closer = stream.close if owned else (lambda: None)
    try:
        return _start(stream, name, fmt, mode, chunk_size, closer, ports)
    except BaseException:
        closer()
        raise


def sampled_mode(chunks: Iterator[Chunk]) -> tuple[str, list[Chunk]]:
    """The mode the first payload bytes decide (protocol/ascii.py sample_mode: MODE_SAMPLE bytes, more
    where they are line noise), and the chunks read for that (replayed first). Each chunk is judged as it
    comes: a stream is decoded as soon as its bytes tell. A pcap's or pcapng's chunks read are HeadChunks: their
    record numbers kept (Source.number_of)."""
    numbered = getattr(chunks, "packet_number", None) is not None
    head: list[Chunk] = HeadChunks() if numbered else []
    sample = b""
    for chunk in chunks:
        head.append(chunk)
        if numbered:
            head.numbers.append(chunks.packet_number)  # type: ignore[attr-defined]
        sample += chunk.data[: MODE_REACH - len(sample)]
        mode = sample_mode(sample, False)  # (never None once MODE_REACH bytes have come)
        if mode is not None:
            return mode, head
    return sample_mode(sample, True), head


class HeadChunks(list):  # type: ignore[type-arg]
    """Chunks read ahead (sampled_mode) with the record number of each (sources/trail.py: -T fields' `record`)."""

    def __init__(self) -> None:
        super().__init__()
        self.numbers: list[int | None] = []


def _start(
    stream: BinaryIO, name: str, fmt: str | None, mode: str | None, chunk_size: int,
    closer: Callable[[], None], ports: RtuPorts = RtuPorts(),
) -> Source:
    log = WarningLog()
    sample, complete = _sniff_or_fail(stream, name)
    while len(sample) < HEADER_BYTES and not complete:  # (a pipe may give a header's first bytes alone)
        part = Input(stream, name).read_some(HEADER_BYTES)
        sample, complete = sample + part, not part
    kind = compression(sample, name) if fmt != "raw" else None  # (--format raw: the line's bytes, as they are)
    if kind is not None:
        stream = Decompressed(kind, sample, stream, name, log)
        sample, complete = _sniff_or_fail(stream, name)
        inner = compression(sample, name)
        if inner is not None:
            raise SourceError(f"{name}: compressed twice ({kind}, then {inner}): decompress it first")
    warning = None
    encoding = None
    if fmt is None:
        format, warning, encoding = detect_text(sample, complete)
    else:
        format = FORMATS[fmt]
        text = _text_of(sample, complete) if format in TEXT_FORMATS else None
        encoding = text[0] if text is not None else None
    if not sample:
        log.warn("empty", f"{name}: the input is empty")
    inp = Input(stream, name, prefix=sample)
    if encoding is not None:
        inp = text_input(inp, encoding)
    if fmt in NOTATIONS:
        chunks = read_hexdump(inp, log, chunk_size, Notation(NOTATIONS[fmt], fixed=True))
    elif format == "pcap":
        chunks = read_pcap(inp, log, chunk_size, ports)
    elif format == "pcapng":
        chunks = read_pcapng(inp, log, chunk_size, ports=ports, shared=several_interfaces(name))
    else:
        chunks = READERS[format](inp, log, chunk_size)
    head: list[Chunk] = []
    if mode is None:
        mode, head = ("ascii", []) if format == "ascii" else sampled_mode(chunks)
    if format == "raw" and mode == "ascii" and fmt is None:
        # (text that starts mid-frame or after line noise: ASCII by its frames, which no warning contradicts)
        format, warning = "ascii", None
    if warning is not None:
        log.warn("format", f"{name}: {warning}")
    source = Source(chunks, head, format, mode, name, log, closer)
    source.streaming = not _regular(stream)
    return source


def _sniff_or_fail(stream: BinaryIO, name: str) -> tuple[bytes, bool]:
    try:
        return _sniff(Input(stream, name))
    except OSError as error:
        raise SourceError(f"{name}: cannot read: {error.strerror or error}") from None


def _regular(stream: BinaryIO) -> bool:
    try:
        return stat.S_ISREG(os.fstat(stream.fileno()).st_mode)
    except (OSError, ValueError, AttributeError, io.UnsupportedOperation):
        return False


def open_interface(  # type: ignore[no-untyped-def]
    path: str, ordinal: int, mode: str | None, chunk_size: int = 65536, tell_skipped: bool = True,
    where: str = "", ports: RtuPorts = RtuPorts(),
):
    """A Source (sources/reader.py) of the packets of one interface of the pcapng file `path`
    (`tell_skipped`: this bus warns of the interfaces carrying no serial bytes; one bus of the file does;
    `where`: said before its warnings that number a record, the bus's title); of a network capture's
    connection on the RTU `ports` (the `ordinal`-th of packet_interfaces')."""
    chunk_size = max(chunk_size, MIN_CHUNK)
    connection, span, beside = None, None, False
    if ports != RtuPorts():
        buses = packet_interfaces(path, ports)
        bus = next((bus for bus in buses if bus.ordinal == ordinal), None)
        connection, span = (bus.connection, bus.span) if bus is not None else (None, None)
        beside = any(bus.connection is not None for bus in buses)  # (a network interface's packets: its buses')
    stream = open(path, "rb")
    try:
        log = WarningLog()
        if connection is not None:
            chunks = network_chunks(stream, path, log, chunk_size, ports, connection, span, where)
            form = "pcap" if isinstance(chunks, PcapRecords) else "pcapng"
        else:
            chunks = read_pcapng(Input(stream, path), log, chunk_size, only=ordinal, tell_skipped=tell_skipped,
                                 where=where, ports=ports, beside=beside)
            form = "pcapng"
        head: list = []
        if mode is None:  # as reader.py decides it: the first payload bytes, replayed first
            mode, head = sampled_mode(chunks)
        source = Source(chunks, head, form, mode, path, log, stream.close)
        source.streaming = False
        return source
    except BaseException:
        stream.close()
        raise
