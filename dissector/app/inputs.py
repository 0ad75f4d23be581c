"""The inputs of a file decode (cli.py decode_files): --hex bytes, then each FILE, a pcapng with packets
from several interfaces as one input per interface (sources/interfaces.py), and the interface a -w
pcapng keeps for each.
"""
from __future__ import annotations

import re

import contextlib
import struct
from itertools import islice
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from dissector.app.hexinput import HexInput
from dissector.app.options import PROG, DecodeOptions, shown
from dissector.app.paths import Fix
from dissector.app.profile_options import report_profiles
from dissector.app.rings import RingSource, group_files
from dissector.framing.linespeed import FROM_PCAPNG, LineSettings, line_settings, settings_from_text
from dissector.model import Chunk, Item, stamped_before
from dissector.render.capturefile import CaptureOutput
from dissector.render.pcapnghead import Interface, pcapng_interface
from dissector.render.pcapngwriter import resolution_text, tsresol
from dissector.render.pcapwriter import MICROS, NANOS, finer_than_micros
from dissector.sources.ethernet import RtuPorts
from dissector.sources.interfaces import PacketInterface, packet_interfaces
from dissector.sources.pcap import MAGICS, is_pcap
from dissector.sources.pcapng_blocks import IDB, SHB, _interface, is_pcapng
from dissector.sources.pcapng_blocks import Interface as RecordedInterface
from dissector.sources.reader import NOTATIONS, SourceError, open_interface, open_source
from dissector.sources.trail import Piece, RecordTrail, item_comments, observed

TIMED_FORMATS = frozenset(["pcap", "pcapng", "hexdump", "traffic", "tshark-x", "pymodbus"])  # formats whose records may carry times
TIMED_TEXTS = ("hexdump", "traffic", "tshark-x", "pymodbus")  # of those, texts: their times' digits say their precision

Input = tuple[str | None, Iterable[Chunk], str, Callable[[], list[str]], Callable[[], Any], bool, Fix,
              tuple[str | None, str | None], "PacketInterface | None", "Callable[[], Any] | None", int | None, Any,
              Callable[[], Any], "Callable[[Chunk], int | None] | None"]


def inputs(args: DecodeOptions, env: Any) -> Iterator[Input]:
    """(title, chunks, mode, take_warnings, recorded, timed, fix, (path, format), interface, again, units, packets,
    damage, numbering) per
    input: the files of one ring buffer are one input (app/rings.py), read as one stream, `path` its
    first; a pcapng file with packets from several interfaces is one input per interface, each its own bus
    (sources/interfaces.py), titled `file: interface name`; `recorded`: once read, when its last record was
    made (Source.recorded_until: the other interfaces' records too); `again`: the same input opened anew,
    for profile `auto` to read it twice (None: standard input, a FIFO, --hex: not read twice); `units`: its
    records' time units a second, whose precision the time column shows (None: not a pcap or pcapng); `packets`: a
    network capture's packet times, the time column's references (sources/ethernet.py PacketTimes; else None);
    `damage`: once read, what damaged the input after its first packets (Source.damage; None: nothing); `numbering`:
    a pcap's or pcapng's record number of the chunk read last (Source.packet_number; None: not one)."""
    from dissector.sources.common import rereadable

    captures = group_files(args.files)
    several = several_captures(args)
    if args.hex:
        typed = HexInput(args.hex, args.mode, NOTATIONS.get(args.format or ""))
        fix = typed.fix if typed.repairs else None
        # (timed: its arguments are records, whose ends the compiled timed path keeps; the raw path drops them)
        yield (("--hex" if several else None), typed.chunks, typed.mode, list, lambda: None, True, fix, (None, None),
               None, None, None, None, lambda: None, None)
    for shown_name, files in captures:
        path = files[0]
        buses = packet_interfaces(path, _ports(args)) if path != "-" and args.format in (None, "pcap", "pcapng") else []
        for bus in buses if len(buses) > 1 else [None]:
            source = _deferred(_open_input(files, bus, args, env.stdin if path == "-" else None))
            chunks: Iterable[Chunk] = source
            # The bar shares the terminal with nothing: items go elsewhere, or only a report, --stats or
            # --watch come at the end.
            quiet = (args.report is not None or args.stats) and not (args.output.detail or args.output.hexdump)
            if env.stderr_isatty and (quiet or not env.stdout_isatty) and path != "-" and not args.output.records:
                from dissector.render.progress import progress_for  # rich's progress bar: only for a terminal

                chunks = progress_for(source, shown_name, env.stderr, files)
            timed = source.format in TIMED_FORMATS
            title = shown_name if bus is None else f"{shown_name}: {bus.label()}"
            again = (lambda files=files, bus=bus: _deferred(_open_input(files, bus, args, None))) \
                if all(map(rereadable, files)) else None
            units = time_units(source, buses, bus, path, args.format)
            take_warnings = _named(source.take_warnings, shown_name, path) if several else source.take_warnings
            yield ((title if several or bus is not None else None), chunks, source.mode, take_warnings,
                   lambda source=source: source.recorded_until, timed, None, (path, source.format), bus,
                   again, units, getattr(source, "packet_times", None),
                   lambda source=source: getattr(source, "damage", None),
                   getattr(source, "number_of", None))


def _named(take_warnings: Callable[[], list[str]], name: str, path: str) -> Callable[[], list[str]]:
    """Several captures: a warning (`record 2: only 5 of its 11 bytes were captured`) names its file, as the
    ==> title over its items does (a several-interface file's record warnings name it already: pcapng.py)."""
    return lambda: [warning if warning.startswith((f"{name}: ", f"{path}: ")) else f"{name}: {warning}"
                    for warning in take_warnings()]


def time_units(source: Any, buses: list[PacketInterface], bus: PacketInterface | None, path: str,
               fmt: str | None) -> int | None:
    """An input's time units a second, whose precision its time column shows (render/timefmt.py): a pcap's,
    a pcapng interface's (a file's are known before its first packet: --mode reads none at its opening),
    nanoseconds for a timed text whose first lines have some (as its -w copy has them: write_units);
    None for others (microseconds, rounded)."""
    if buses:
        return (bus or buses[0]).interface.units
    if source.format in TIMED_TEXTS:
        from dissector.sources.common import rereadable

        return NANOS if path != "-" and rereadable(path) and _text_nanoseconds(path, fmt) else None
    return source.time_units


def several_captures(args: DecodeOptions) -> bool:
    """Are several captures decoded (files, a ring buffer's files counting one, --hex one)? Each input is
    titled then, and numbers its frames from 1."""
    return len(group_files(args.files)) + bool(args.hex) > 1


def _open_input(files: tuple[str, ...], bus: PacketInterface | None, args: DecodeOptions, stdin: Any) -> Any:
    """A Source of one capture's files (a RingSource of several), or of one interface of them."""
    def open_file(path: str) -> Any:
        if bus is None:
            return open_source(path, args.format, mode=args.mode, stdin=stdin, ports=_ports(args))
        return open_interface(path, bus.ordinal, args.mode, tell_skipped=bus.first, where=f"{path}: {bus.label()}: ",
                              ports=_ports(args))

    return open_file(files[0]) if len(files) == 1 else RingSource(files, open_file)


def _ports(args: DecodeOptions) -> RtuPorts:
    """The TCP/UDP ports read as Modbus RTU in a network capture (sources/ethernet.py)."""
    return RtuPorts(args.tcp_port, args.udp_port)


def is_pcapng_file(path: str) -> bool:
    from dissector.sources.common import rereadable

    if not rereadable(path):  # (standard input, a FIFO: its bytes are the decode's, and it is one stream)
        return False
    try:
        with open(path, "rb") as file:
            return is_pcapng(file.read(4))
    except OSError:
        return False


def write_interface(path: str | None, source_format: str | None, args: DecodeOptions,
                    bus: PacketInterface | None = None) -> Interface | None:
    """The interface the -w file says its records were captured on: the input pcapng's (name and
    description, as editcap and tshark -w keep them; `bus`: the one interface decoded, of several), its
    description replaced by the speed decoded at when --baud is typed (framing/linespeed.py reads it back)."""
    from dissector.sources.common import rereadable

    kept = pcapng_interface(path) if rereadable(path) and source_format == "pcapng" else None  # (not a FIFO)
    if bus is not None:
        named = bus.interface
        kept = (named.name, named.description) if named.name or named.description else None
    if args.baud_given:
        return (kept[0] if kept is not None else None, f"{args.baud} baud (--baud)")
    return kept


def write_units(paths: list[str], stdin: Any = None, fmt: str | None = None) -> int:
    """The time units a -w copy writes: nanoseconds when a file decoded holds them (a nanosecond pcap, a
    pcapng interface finer than microseconds, or in units microseconds cannot hold: if_tsresol 2^-10 s,
    read to the nanosecond; a timed text whose first lines' times have nanoseconds, `date +%s.%N`), as
    tshark -w and editcap keep them; microseconds otherwise. Standard input is judged by what it holds
    already (peek: nothing read), its first interfaces; a FIFO is not read (microseconds)."""
    from dissector.sources.common import rereadable

    for path in paths:
        if path == "-":
            head = stdin_head(stdin)
            interfaces = stdin_interfaces(head)
        else:
            if not rereadable(path):  # (a FIFO's bytes are the decode's: none read here)
                continue
            try:
                with open(path, "rb") as file:
                    head = file.read(4)
            except OSError:
                continue
            interfaces = [bus.interface for bus in packet_interfaces(path)] if is_pcapng(head) else []
            if not is_pcap(head) and not interfaces and _text_nanoseconds(path, fmt):
                return NANOS
        units = [MAGICS.get(head[:4], ("", MICROS))[1], *(interface.units for interface in interfaces)]
        if any(finer_than_micros(unit) for unit in units):
            return NANOS
    return MICROS


TEXT_LINES = 16  # the lines of a timed text looked at: a logger writes every time alike


def _text_nanoseconds(path: str, fmt: str | None) -> bool:
    """Do the first lines of a hex dump or traffic log have times with nanoseconds?"""
    try:
        with open_source(path, fmt) as source:
            if source.format not in TIMED_TEXTS:
                return False
            return any(chunk.time is not None and getattr(chunk.time, "ns", 0) % 1000
                       for chunk in islice(source, TEXT_LINES))
    except (SourceError, OSError):
        return False  # (the decode says why)


STDIN_HEAD = 4096  # a pcapng's section and first interface blocks (tools write them at once)


def stdin_head(stdin: Any) -> bytes:
    """What standard input holds already (peek: nothing read; a terminal: nothing to wait for)."""
    piped = hasattr(stdin, "peek") and not stdin.isatty()
    return stdin.peek(STDIN_HEAD) if piped else b""


def stdin_interfaces(head: bytes) -> list[RecordedInterface]:
    """The interfaces a pcapng's first bytes describe, before any packet (none: another format)."""
    if not is_pcapng(head) or len(head) < 12:
        return []
    order = "<" if head[8:12] == b"\x4d\x3c\x2b\x1a" else ">"
    found, position = [], 0
    while position + 12 <= len(head):
        block_type, total = struct.unpack_from(order + "II", head, position)
        if total < 12 or total % 4 or position + total > len(head) or block_type not in (SHB, IDB):
            break
        if block_type == IDB:
            with contextlib.suppress(SourceError):
                found.append(_interface(head[position + 8 : position + total - 4], order, "standard input"))
        position += total
    return found


def first_interface_units(path: str | None, fmt: str | None, stdin: Any = None) -> int | None:
    """The time units a -w pcapng's first interface keeps (keep_interface's of the first input): a pcapng
    file's first interface with packets, standard input's finest described at its head; None for others."""
    if path is None or fmt not in (None, "pcapng"):
        return None
    if path == "-":
        return max((found.units for found in stdin_interfaces(stdin_head(stdin))), default=None)
    buses = packet_interfaces(path)  # ([] for a FIFO: not read here)
    return buses[0].interface.units if buses else None


def keep_interface(sinks: Any, args: DecodeOptions, env: Any, path: str | None, source_format: str | None,
                   line: LineSettings, bus: PacketInterface | None = None, units: int | None = None) -> None:
    """-w: the input's interface (and a pcapng's time units, `units`: its if_tsresol, as editcap and tshark
    -w keep it), and warnings, once, of what the copy cannot keep."""
    pcap = sinks.pcap
    assert pcap is not None
    kept = units if source_format == "pcapng" else None
    pcap.use_interface(write_interface(path, source_format, args, bus), kept)
    if kept is not None and not sinks.resolution_lost and (
            kept != pcap.units if pcap.format == "pcap" else kept != MICROS and tsresol(kept) is None):
        sinks.resolution_lost = True  # (pcap: microseconds or nanoseconds; pcapng: 10^-n or 2^-n up to 2^64)
        env.stderr.write(
            f"{PROG}: warning: -w {shown(args.write)}: {pcap.format} cannot hold the time resolution of "
            f"{shown(path or '')} (if_tsresol {resolution_text(kept)}): its times are written in "
            f"{'nanoseconds' if pcap.units == NANOS else 'microseconds'}"
            f"{' (write pcapng, -F pcapng, to keep it)' if pcap.format == 'pcap' else ''}\n")
    if sinks.pcap.format == "pcap" and line.source == FROM_PCAPNG and not sinks.speed_lost:
        # tshark -F pcap drops the interface silently; the line speed read there would be lost unseen.
        sinks.speed_lost = True
        name = shown(path if path is not None else "")
        env.stderr.write(
            f"{PROG}: warning: -w {shown(args.write)}: pcap has no interface description: the line speed "
            f"{line.baud} baud of {name} is not kept (write pcapng, -F pcapng, to keep it; or read it back "
            f"with --baud {line.baud})\n"
        )
    if sinks.pcap.format == "pcap" and bus is not None and not sinks.buses_joined:
        # Its buses' records one after the other in one stream: its decode pairs one bus's frames with
        # another's, where the input's decode keeps each bus apart (sources/interfaces.py).
        sinks.buses_joined = True
        env.stderr.write(
            f"{PROG}: warning: -w {shown(args.write)}: pcap has no interfaces: the buses of "
            f"{shown(path or '')} are written one after the other as one stream, which decodes as one bus "
            "(write pcapng, -F pcapng, to keep them apart)\n"
        )


class CopyEnd:
    """Where a -w copy of a decode ends: a record of no byte at the input's end (Source.recorded_until: an
    empty closing record of a live -w, another interface's records, a frame's last record) when that is
    later than the copy's last record, so that its readers judge the last request to the same end as the
    input's (pipeline.Dissector.finish), as live -w closes (live_capture.CaptureFiles.close). None after
    -c N (the copy ends at the Nth item, as tshark -c N -w), for an untimed input (raw bytes: no time to
    close at), nor when -Y kept nothing. -Y keeps it: the copy spans the capture it filtered."""

    def __init__(self) -> None:
        self.last: float | None = None  # the time of the copy's last record
        self.end: float | None = None  # when the last input read to its end was recorded until

    def written(self, items: list[Item], pieces: dict[int, list[Piece]] | None = None) -> None:
        """`pieces`: of the items written in several records (sources/trail.py), the last one's time."""
        for item in reversed(items):
            split = pieces.get(id(item)) if pieces else None
            time = split[-1][1] if split else item.time
            if time is not None:
                self.last = time
                return

    def ended(self, recorded: float | None) -> None:
        self.end = recorded

    def close(self, pcap: CaptureOutput) -> None:
        end, last = self.end, self.last
        if end is None or last is None or not stamped_before(last, end):
            pcap.close()
            return
        pcap.release()  # (the records it holds come before the end)
        pcap.close_at(end)  # (in the file being written: a -b ring opens no file for it)


def input_line(path: str | None, source_format: str | None, args: DecodeOptions,
               bus: PacketInterface | None) -> LineSettings:
    """The one line speed of an input, for the framer, the silence checks and the bus timing: --baud, else
    its pcapng interface's description (`bus`: the one interface decoded, of several), else 19200."""
    line = line_settings(path, source_format, args.baud if args.baud_given else None)
    if bus is not None and not args.baud_given:
        line = settings_from_text(" ".join(bus.interface.texts)) or line_settings(None, None, None)
    return line


def profile_notes(buses: Any, annotate: Any, stderr: Any, is_terminal: bool) -> None:
    """Profile `auto`'s notes on a terminal (profile_options.report_profiles): of several buses (a pcapng's
    interfaces, render/buses.py), each bus's own, named by its title as its warnings are."""
    if not buses.several:
        report_profiles(annotate, stderr, is_terminal)
        return
    if not is_terminal:
        return
    from dissector.render.buses import title

    for bus in buses.all():
        for line in getattr(bus.annotate, "profile_report", lambda: [])():
            stderr.write(f"{PROG}: {shown(title(bus))}: {shown(line)}\n")


def _deferred(source: Any) -> Any:
    """A source whose damage after its first packets ends it, kept for the decode to refuse it after showing them
    (sources/reader.py Source.defer_damage; a ring buffer's files raise it as they are read)."""
    defer = getattr(source, "defer_damage", None)
    return defer() if defer is not None else source


def observe_records(chunks: Iterable[Chunk], source_format: str | None,
                    writing: bool, numbering: Callable[[Chunk], int | None] | None = None
                    ) -> tuple[Iterable[Chunk], RecordTrail | None]:
    """The chunks through a trail of their records (sources/trail.py): with -w (its times and comments), of a
    pcapng (its packet comments), or `numbering` (a pcap's or pcapng's record numbers, -T fields' `record`:
    Source.packet_number); as they are otherwise (no other input has comments)."""
    if not writing and source_format != "pcapng" and numbering is None:
        return chunks, None
    trail = RecordTrail(times=writing, numbering=numbering)
    return observed(chunks, trail), trail


def numbers_records(args: DecodeOptions) -> bool:
    """Does an output show or test the items' record numbers (-T fields -e record, -Y record: a filter naming
    it, or a string holding the word, which costs a lookup per item and changes nothing)?"""
    fields = args.output.fields
    named = args.filter is not None and re.search(r"\brecord\b", args.filter) is not None
    return named or (fields is not None and "record" in fields.fields)


def record_numbers(trail: RecordTrail | None, items: list[Item]) -> list[int | None] | None:
    """Each item's record number (tshark's frame.number of the pcap or pcapng record holding its last byte, where
    Wireshark shows it: sources/trail.py record_of) where the trail numbers them (numbers_records); else None."""
    if trail is None or trail.numbering is None:
        return None
    return [trail.record_of(item) for item in items]


def item_record(item: Item, comments: list[str] | None, number: int | None) -> dict:
    """The item's NDJSON dict (as -Y reads it), with its packet comments (`comments`) and record number (`record`)
    where it has some."""
    from dissector.render.jsonout import item_to_dict

    record = item_to_dict(item)
    if comments is not None:
        record["comments"] = comments
    if number is not None:
        record["record"] = number
    return record


def numbered_records(items: list[Item], numbers: list[int | None]) -> list[dict] | None:
    """The items' NDJSON dicts with their record numbers (`record`, -T fields -e record); None where none has one."""
    if all(number is None for number in numbers):
        return None
    return [item_record(item, None, number) for item, number in zip(items, numbers)]


def item_pieces(trail: RecordTrail | None, items: list[Item]) -> dict[int, list[Piece]] | None:
    """The pieces of the items (heard, in order) that are not one record without comments, by id(item)."""
    if trail is None or trail.idle:
        return None
    return trail.split(items)


def comments_of(pieces: dict[int, list[Piece]]) -> dict[int, list[str]]:
    """The packet comments of the items that have some, by id(item) (render/output.py Output.write)."""
    found = {key: item_comments(split) for key, split in pieces.items()}
    return {key: texts for key, texts in found.items() if texts}


RECORDS_TOLD = 5  # record numbers a line about packet comments names


def tell_comments(sinks: Any, path: str | None, stderr: Any, bus: str | None = None) -> None:
    """After an input with packet comments: a -w pcap has no place for them (a warning), and a display
    that does not show them (the summary, -x, -T fields) says where they are; a line a file (a ring
    buffer's files number their records each); -V, --json and a pcapng -w show or keep them. `bus`: the
    title of a pcapng interface read as its own bus, which numbers its own records (named, else "record 1"
    sends the reader to the first bus's)."""
    trail = sinks.trail
    if trail is None or not trail.comments:
        return
    files: dict[str | None, list[tuple[int, int]]] = {}
    for name, record, comments in trail.records:
        files.setdefault(name, []).append((record, comments))
    for name, counts in files.items():
        name = name or bus or (path if path not in (None, "-") else "--hex" if path is None else "standard input")
        count = sum(comments for _record, comments in counts)
        numbers = sorted({record for record, _comments in counts})
        records = ", ".join(map(str, numbers[:RECORDS_TOLD])) + (", ..." if len(numbers) > RECORDS_TOLD else "")
        what = (f"{count} packet comment{'s' if count != 1 else ''} "
                f"(record{'s' if len(numbers) != 1 else ''} {records})")
        if sinks.pcap is not None and sinks.pcap.format == "pcap":
            stderr.write(f"{PROG}: warning: -w {shown(sinks.write_path)}: pcap has no packet comments: the "
                         f"{what} of {shown(name)} {'is' if count == 1 else 'are'} not kept (write pcapng, "
                         "-F pcapng, to keep them)\n")
        elif sinks.show and not (sinks.options.output.detail or sinks.options.output.json):
            stderr.write(f"{PROG}: {shown(name)}: {what}: -V and --json show them\n")


def choose_over_all(args: DecodeOptions, env: Any, annotate: Any) -> bool:
    """Profile `auto` over every file of the run before the first is decoded, where each can be read twice:
    the files are one bus's (their evidence is pooled, cited by file), so the same bytes are named alike
    whatever the files' order; a file decoded before the evidence of a later one was named by its own
    alone. False (each input chooses before its own decode): one input, standard input or a FIFO among
    them, or a pcapng's several interfaces (a device each: their own choices)."""
    from dissector.sources.common import rereadable

    if getattr(annotate, "selector", None) is None or not several_captures(args) \
            or not all(map(rereadable, args.files)):  # (before any is opened: standard input is read once)
        return False
    if args.format in (None, "pcapng") and any(len(packet_interfaces(path)) > 1 for path in args.files):
        return False
    selector = annotate.selector
    listed = inputs(args, env)
    try:
        for (title, chunks, mode, _warnings, _recorded, _timed, fix, (path, source_format), bus,
             again, _units, _packets, _damage, _numbering) in listed:
            selector.source = title  # (the evidence names the file it is in, as the decode cites it)
            try:
                choose_profiles_first(annotate, args, chunks, mode, path, again,
                                      input_line(path, source_format, args, bus).baud, fix)
            finally:
                close = getattr(chunks, "close", None)
                if close is not None:
                    close()
    except SourceError:  # (the decode refuses it where it reaches it: the inputs before it are decoded)
        annotate.freeze()
    finally:
        listed.close()
    return True


def choose_profiles_first(annotate: Any, args: DecodeOptions, chunks: Iterable[Chunk], mode: str,
                          path: str | None, again: Callable[[], Any] | None, baud: int,
                          fix: Callable[[list[Any]], list[Any]] | None = None) -> None:
    """Profile `auto`: the choices made over the whole input first, where it can be read twice (`again`:
    inputs; `fix`: --hex's typed bytes put back, preselect.choose_profiles)."""
    if getattr(annotate, "selector", None) is None:
        return
    from dissector.app.preselect import choose_profiles

    if path is None:  # --hex: its chunks are a list
        choose_profiles(annotate, chunks, mode, baud, args.timeout, fix)  # type: ignore[arg-type]
    elif again is not None:
        with again() as reread:
            choose_profiles(annotate, reread, mode, baud, args.timeout)  # type: ignore[arg-type]
    else:
        annotate.thaw()  # type: ignore[union-attr]


def no_frame_warning(path: str, mode: str, input_bytes: int, cut_records: int, cut_bytes: int) -> str:
    """The warning line for an input with no valid frame (no_frame_text)."""
    return f"{PROG}: warning: {no_frame_text(path, mode, input_bytes, cut_records, cut_bytes)}\n"


def no_frame_text(path: str, mode: str, input_bytes: int, cut_records: int, cut_bytes: int,
                  name: str | None = None) -> str:
    """What is said of an input with no valid frame: every record captured in part (a snapshot length), else
    not Modbus or another format or line speed (a PNG, a line read at the wrong speed). `name`: the input's
    as shown, where it is not `path` (one interface of a pcapng, --parquet's capture)."""
    from dissector.render.describe import count_text

    name = shown(name if name is not None else path if path != "-" else "standard input")
    if cut_bytes == input_bytes:  # (every record captured in part: no other format)
        return (f"{name}: no frame can be checked: every record was captured in part "
                f"({count_text(cut_records, 'record')}, {count_text(cut_bytes, 'byte')}: a snapshot length "
                f"shorter than the frames), their {'LRC' if mode == 'ascii' else 'CRC'}s cut off: capture again "
                "with a larger snapshot length")
    hint = " (it holds Modbus ASCII frames: try --mode ascii)" if mode == "rtu" and holds_ascii(path) else ""
    return (f"{name}: no valid Modbus {mode.upper()} frame in {input_bytes} bytes (every item "
            f"is noise or a frame with a bad check): not a Modbus capture, or another format or line speed?{hint}")


ASCII_HINT_BYTES = 1 << 16  # how much of a file the --mode ascii hint reads again (once, after the run)


def holds_ascii(path: str) -> bool:
    """Whether the start of a file read as RTU holds a whole Modbus ASCII frame (an ASCII line behind more
    noise than mode detection samples): the hint names --mode ascii. Standard input, a FIFO cannot be read
    again (opened again, a FIFO would wait for a writer)."""
    from dissector.sources.common import rereadable
    from dissector.protocol.ascii import holds_frame

    if not rereadable(path):
        return False
    try:
        with open(path, "rb") as file:
            return holds_frame(file.read(ASCII_HINT_BYTES))
    except OSError:
        return False
