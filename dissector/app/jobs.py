"""`--parquet DIR [--jobs N | --scheduler tcp://HOST:PORT] FILE...`: captures decoded into a dataset.

The unit of work is a capture: one file, or the files of one `-b` ring buffer (`bus_00001_2026...pcap`,
`bus_00002_...`), decoded in order as one stream (a transaction cut between two files still pairs, and
frame numbers go on). Each capture is decoded by `decode_capture` wherever it runs: in this process,
in N worker processes (`--jobs N`), or on the workers of a Dask distributed cluster (`--scheduler`,
`pip install 'vw3-dissector[cluster]'`): the same function on the same files gives the same files,
so the dataset does not depend on how it ran. Each capture writes its own files (export/parquet.py),
so workers never share one.
"""
from __future__ import annotations

import argparse
import os
from typing import Any
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

from dissector.app.rings import group_files, missing_files
from dissector.devices.maps_refs import map_warnings
from dissector.errors import ExitStatus, ProfileError, UsageError
from dissector.framing.ascii import AsciiFramer
from dissector.framing.rtu import RtuFramer
from dissector.framing.linespeed import line_settings, settings_from_text
from dissector.sources.ethernet import RtuPorts
from dissector.sources.interfaces import packet_interfaces
from dissector.framing.timing import GapChecker
from dissector.model import Frame
from dissector.pipeline import Dissector
from dissector.render.bustiming import BusTiming
from dissector.sources.reader import SourceError, open_interface, open_source
from dissector.sources.trail import RecordTrail, item_comments

TIMED_FORMATS = frozenset(["pcap", "pcapng", "hexdump", "traffic", "tshark-x"])


@dataclass(frozen=True, slots=True)
class Capture:
    shown: str  # as the command line named it: the file, or the ring buffer's `folder/bus.pcap`
    files: tuple[str, ...]
    # The `capture` column, and what its output files are named after: `shown` made absolute here, not
    # on a worker whose working folder may differ. Names repeat across a plant's buses (line1/bus.pcap,
    # line2/bus.pcap): the path does not. One interface of a pcapng of several: `path#N` (N its ordinal).
    path: str
    interface: int | None = None  # a pcapng's interface (its ordinal), each its own bus (sources/interfaces.py)


@dataclass(frozen=True, slots=True)
class JobSettings:
    """What decoding a capture needs, picklable for a worker process or a Dask worker."""

    directory: str
    format: str | None = None
    mode: str | None = None
    timeout: float = 1.0
    baud: int | None = None  # --baud; None: what framing/linespeed.py says of each capture
    profile_args: argparse.Namespace | None = None  # None: -n (no device profile)
    ports: RtuPorts = RtuPorts()  # --tcp-port, --udp-port: RTU over TCP/UDP in a network capture
    several: bool = False  # several captures: a record's warning names its file, as the decode's (app/inputs.py)


@dataclass(slots=True)
class CaptureResult:
    capture: str
    rows: dict[str, int] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    error: str | None = None  # one line: the capture could not be read
    # One line: what damaged the capture after its first packets (sources/reader.py Source.defer_damage); its rows
    # before the damage are written, then the run is refused (exit 2), as a decode shows the packets before it.
    damage: str | None = None
    # A --map written in PLC references, as the traffic told it (devices/maps_refs.py): said once a run.
    map_warnings: list[str] = field(default_factory=list)


def group_captures(paths: list[str], ports: RtuPorts = RtuPorts()) -> list[Capture]:
    """Files of one ring buffer are one capture (app/rings.py); a pcapng with packets from several
    interfaces, one capture per interface (its bus, over every file of its ring)."""
    captures = []
    for shown, files in group_files(paths):
        buses = packet_interfaces(files[0], ports)
        if len(buses) > 1:
            captures += [Capture(f"{shown}: {bus.label()}", files, f"{os.path.abspath(shown)}#{bus.ordinal}",
                                 bus.ordinal) for bus in buses]
            continue
        captures.append(Capture(shown, files, os.path.abspath(shown)))
    return captures


def _open(path: str, settings: JobSettings, interface: int | None) -> Any:
    """A file's Source whose damage after its first packets ends its chunks, kept in its `damage` (not raised)."""
    if interface is None:
        return open_source(path, settings.format, mode=settings.mode, ports=settings.ports).defer_damage()
    return open_interface(path, interface, settings.mode, ports=settings.ports).defer_damage()


def _files(files: tuple[str, ...], settings: JobSettings, interface: int | None,
           damaged: list[SourceError] | None = None) -> Iterator[tuple[str, Any]]:
    """(path, its Source, open) of each file of a capture, in order, until one damaged after the capture's first
    packets (its damage appended to `damaged`): the files after it are not read, as a decode's ring
    (app/rings.py RingSource.defer_damage). A file that cannot be opened after the first is damage too."""
    for index, path in enumerate(files):
        try:
            source = _open(path, settings, interface)
        except SourceError as error:
            if not index or damaged is None:
                raise
            damaged.append(error)
            return
        try:
            yield path, source
        finally:
            source.close()
        if source.damage is not None:
            if damaged is not None:
                damaged.append(source.damage)
            return


def _chunks(files: tuple[str, ...], settings: JobSettings, tables: object, result: CaptureResult,
            interface: int | None = None, recorded: list[Any] | None = None) -> Iterator[object]:
    """`recorded`: each file's Source.recorded_until, once read (the last says when the capture ends); damage
    after the capture's first packets ends it, said in result.damage."""
    offset = 0  # payload bytes of the files before: where each file starts in the capture's stream
    damaged: list[SourceError] = []
    before: str | None = None
    for path, source in _files(files, settings, interface, damaged):
        if before is not None:
            result.warnings.extend(missing_files(before, path))  # (a ring's file missing: said)
        before = path
        tables.files.append((offset, os.path.basename(path)))  # type: ignore[attr-defined]
        for chunk in source:
            offset += len(chunk.data)
            yield chunk
        warnings = source.take_warnings()
        if settings.several:  # (a several-interface file's name its file already: pcapng.py)
            warnings = [text if text.startswith(f"{path}: ") else f"{path}: {text}" for text in warnings]
        result.warnings.extend(warnings)
        if recorded is not None:
            recorded.append(source.recorded_until)
    if damaged:
        result.damage = str(damaged[0])


def _choose_profiles(annotate: object, files: tuple[str, ...], settings: JobSettings, mode: str, baud: int,
                     interface: int | None = None) -> None:
    """Profile `auto` over the capture's files first, as one stream (app/preselect.py, issue 27)."""
    if getattr(annotate, "selector", None) is None:
        return
    from dissector.app.preselect import choose_profiles

    def chunks() -> Iterator[object]:
        for _path, source in _files(files, settings, interface, []):
            yield from source

    choose_profiles(annotate, chunks(), mode, baud, settings.timeout)  # type: ignore[arg-type]


def _count(items: list[Any], heard: list[int]) -> None:
    for item in items:
        heard[0] += item.length
        heard[1] += isinstance(item, Frame) and bool(item.crc_ok)


def decode_capture(capture: Capture, settings: JobSettings) -> CaptureResult:
    """Decode one capture into DIR/frames, DIR/registers and DIR/events (runs in any process)."""
    from dissector.app.profile_options import annotator_from_args
    from dissector.export.parquet import CaptureTables, file_stem
    from dissector.render.stats_store import slave_tables

    result = CaptureResult(capture.shown)
    try:
        annotate = annotator_from_args(settings.profile_args) if settings.profile_args is not None else None
    except ProfileError as error:
        result.error = str(error)
        return result
    try:
        tables = CaptureTables(settings.directory, capture.path, file_stem(capture.path),
                               register_tables=slave_tables(annotate))
    except OSError as error:  # DIR/frames and the others could not be made
        result.error = f"--parquet {settings.directory}: {error.strerror or error}"
        return result
    bus = BusTiming(settings.timeout)
    # (frames that overlap at the line speed used: said as the decode says it, the capture named among several)
    bus.warn = lambda text: result.warnings.append(f"{capture.shown}: {text}" if settings.several else text)
    try:
        with _open(capture.files[0], settings, capture.interface) as first:
            mode, source_format = first.mode, first.format  # the first file's, as one stream's
        # The one line speed of this capture, as a single-process decode of it gets (framing/linespeed.py).
        line = line_settings(capture.files[0], source_format, settings.baud)
        if capture.interface is not None and settings.baud is None:  # (that interface's own description)
            texts = next((bus.interface.texts for bus in packet_interfaces(capture.files[0], settings.ports)
                          if bus.ordinal == capture.interface), ())
            line = settings_from_text(" ".join(texts)) or line_settings(None, None, None)
        bus.new_input(mode, line)
        framer = AsciiFramer(line.baud) if mode == "ascii" else RtuFramer(line.baud)
        recorded: list[Any] = []
        dissector = Dissector(framer=framer, annotate=annotate, timeout=settings.timeout,
                              gaps=GapChecker(line.baud, mode) if source_format in TIMED_FORMATS else None,
                              recorded=lambda: recorded[-1] if recorded else None)
        _choose_profiles(annotate, capture.files, settings, mode, line.baud, capture.interface)
        chunks = _chunks(capture.files, settings, tables, result, capture.interface, recorded)
        # A pcapng's packet comments (sources/trail.py), on the frames of their records, as --json's `comments`.
        trail = RecordTrail(times=False) if source_format == "pcapng" else None
        heard = [0, 0]  # the input's bytes in items, its frames with a good check: is there Modbus at all?
        for chunk in chunks if trail is None else trail.observe(chunks):  # type: ignore[arg-type]
            items = dissector.feed(chunk)  # type: ignore[arg-type]
            tables.add(items, _comments(trail, items))
            bus.add_items(items)
            _count(items, heard)
        items = dissector.finish()
        tables.add(items, _comments(trail, items))
        bus.add_items(items)
        _count(items, heard)
        bus.finish()
        if (heard[0] or framer.cut_records) and not heard[1]:  # (as the decode says it: app/cli.py)
            from dissector.app.inputs import no_frame_text

            result.warnings.append(no_frame_text(capture.files[0], mode, heard[0], framer.cut_records,
                                                 framer.cut_bytes, capture.shown))
        tables.outages(bus.outages)
        result.rows = tables.close()
        result.map_warnings = map_warnings([annotate])
    except SourceError as error:
        tables.abandon()
        result.error = str(error)
    except OSError as error:
        tables.abandon()
        result.error = f"--parquet {settings.directory}: writing {capture.shown}: {error.strerror or error}"
    except BaseException:  # Ctrl-C or a worker's end: no half-written .part files left behind
        tables.abandon()
        raise
    return result


def _comments(trail: RecordTrail | None, items: list[Any]) -> dict[int, list[str]] | None:
    """The packet comments of the items (in order) that have some, by id(item)."""
    if trail is None or trail.idle:
        return None
    found = {id(item): item_comments(trail.pieces(item)) for item in items}
    return {key: texts for key, texts in found.items() if texts}


def check_scheduler(address: str) -> None:
    """Refuse a --scheduler that is no tcp://HOST:PORT (or tls://) at once, not after a 30 s wait."""
    from urllib.parse import urlsplit

    try:
        parts = urlsplit(address)
        known = parts.scheme in ("tcp", "tls") and parts.hostname and parts.port is not None and parts.port > 0
    except ValueError:  # (a port past 65535, an unclosed [)
        known = False
    if not known:
        raise UsageError(f"--scheduler {address!r}: not an address of the form tcp://HOST:PORT")


def run_captures(captures: list[Capture], settings: JobSettings, jobs: int, scheduler: str | None,
                 report: Callable[[CaptureResult], None]) -> None:
    """Decode every capture here, in `jobs` processes, or on a Dask cluster; results as they end."""
    if scheduler is not None:
        check_scheduler(scheduler)
        try:
            from distributed import Client, as_completed
        except ImportError:
            raise UsageError("--scheduler needs dask distributed: pip install 'vw3-dissector[cluster]'") from None
        try:
            client = Client(scheduler, timeout=30)
        except (OSError, TimeoutError, ValueError) as error:
            raise UsageError(f"--scheduler {scheduler}: cannot connect: {error}") from None
        try:
            futures = [client.submit(decode_capture, capture, settings, pure=False) for capture in captures]
            for future in as_completed(futures):
                report(future.result())
        finally:
            client.close()
        return
    if jobs <= 1 or len(captures) <= 1:
        for capture in captures:
            report(decode_capture(capture, settings))
        return
    import concurrent.futures
    import multiprocessing

    # spawn, not fork: a worker must not inherit a parent's threads or open outputs.
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=jobs, mp_context=context) as pool:
        futures = [pool.submit(decode_capture, capture, settings) for capture in captures]
        for future in concurrent.futures.as_completed(futures):
            report(future.result())


def _name(path: str) -> str:
    """A path as its bytes: an undecodable byte as \\xNN (the \\udcNN Python holds it as means nothing to a user)."""
    return os.fsencode(path).decode("utf-8", "backslashreplace")


def _need_utf8(path: str, message: str) -> None:
    """Refuse a path (made absolute, as the dataset stores it) that pyarrow cannot take as a string."""
    try:
        os.path.abspath(path).encode("utf-8")
    except UnicodeEncodeError:
        raise UsageError(message) from None


def parquet_main(args: argparse.Namespace, stdout: object, stderr: object, prog: str) -> int:
    """The --parquet run: one line per capture written, errors one line each; exit 2 if any failed."""
    from dissector.app.options import baud_given, shown
    from dissector.export.parquet import need_pyarrow, remove_empty_tables, rows_text

    need_pyarrow()
    if not args.files:
        raise UsageError("--parquet reads capture FILEs (standard input and --hex cannot be shared with workers)")
    if "-" in args.files:
        raise UsageError("--parquet reads capture FILEs, not standard input")
    for path in args.files:
        if not os.path.isfile(path):
            raise UsageError(f"{path}: no such file")
        _need_utf8(path, f"{_name(path)}: its path is not UTF-8 text, which the dataset's file column holds:"
                         " rename it or decode it from a UTF-8 folder")
    _need_utf8(args.parquet, f"--parquet {_name(args.parquet)}: the folder's path is not UTF-8 text, which"
                             " pyarrow writes to: give another folder")
    created = not os.path.exists(args.parquet)
    if not created and not os.path.isdir(args.parquet):
        raise UsageError(f"--parquet {args.parquet}: not a directory (DIR is the dataset's folder)")
    try:
        os.makedirs(args.parquet, exist_ok=True)
    except OSError as error:
        raise UsageError(f"--parquet {args.parquet}: {error.strerror or error}") from None
    ports = RtuPorts(args.tcp_port, args.udp_port)
    captures = group_captures(list(args.files), ports)
    settings = JobSettings(
        directory=os.path.abspath(args.parquet), format=args.format, mode=args.mode, timeout=args.timeout,
        baud=args.baud if baud_given(args) else None, profile_args=None if args.no_profile else args, ports=ports,
        several=len(captures) > 1,
    )
    failed = 0
    said: list[str] = []  # the map warnings of every capture, each once, after the run (as a file decode)

    def report(result: CaptureResult) -> None:
        nonlocal failed
        said.extend(text for text in result.map_warnings if text not in said)
        for warning in result.warnings:
            stderr.write(f"{prog}: warning: {shown(warning)}\n")  # type: ignore[attr-defined]
        if result.error is not None:
            failed += 1
            stderr.write(f"{prog}: {shown(result.error)}\n")  # type: ignore[attr-defined]
            return
        stdout.write(f"{shown(result.capture)}: {rows_text(result.rows)}\n")  # type: ignore[attr-defined]
        if result.damage is not None:  # (its rows before the damage written: then refused, as a decode)
            failed += 1
            stderr.write(f"{prog}: {shown(result.damage)}\n")  # type: ignore[attr-defined]

    run_captures(captures, settings, args.jobs, args.scheduler, report)
    for warning in said:
        stderr.write(f"{prog}: warning: {shown(warning)}\n")  # type: ignore[attr-defined]
    if failed:
        remove_empty_tables(settings.directory)
    if failed and created:
        try:
            os.rmdir(args.parquet)  # nothing was written: the refused run leaves no empty folder
        except OSError:
            pass
    return ExitStatus.BAD_INPUT if failed else ExitStatus.OK
