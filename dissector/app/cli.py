"""`vw3-decode`: decode Modbus serial captures the way tshark shows packets.

The pipeline is chosen once from the options (source -> framer -> pairing -> decoder -> annotator ->
filter -> sinks); the terminal is injected (`Environment`) so tests run the whole CLI on strings.
"""
from __future__ import annotations

import argparse
import contextlib
import copy
import gc
import io
import os
import sys
from collections.abc import Callable
from dataclasses import dataclass
from typing import BinaryIO, TextIO

from dissector.errors import ExitStatus, OutputError, ProfileError, UsageError
from dissector.framing.ascii import AsciiFramer
from dissector.render.filter_error import FilterError
from dissector.framing.rtu import RtuFramer
from dissector.app.options import PROG, DecodeOptions, build_parser, decode_options, parse_arguments, shown
from dissector.app.paths import decode_one
from dissector.model import Frame, Item
from dissector.render.capturefile import STDOUT, CaptureOutput, open_output
from dissector.pipeline import Annotator, Dissector
from dissector.app.profile_options import annotator_from_args
from dissector.devices.maps_refs import map_warnings
from dissector.app.rings import group_files
from dissector.app.samefile import refuse_same_files
from dissector.render.buses import Bus, Buses
from dissector.render.output import Output
from dissector.protocol.printable import printable
from dissector.render.timefmt import Clock
from dissector.render.summary import summary_line, summary_text
from dissector.app.inputs import (
    CopyEnd, choose_over_all, choose_profiles_first, comments_of, first_interface_units, input_line, inputs,
    is_pcapng_file, item_pieces, item_record, keep_interface, no_frame_warning, numbered_records, numbers_records,
    observe_records, profile_notes, record_numbers, several_captures, tell_comments, write_interface, write_units,
)
from dissector.sources.reader import SourceError
from dissector.sources.trail import RecordTrail
from dissector.framing.timing import GapChecker


@dataclass
class Environment:
    stdin: BinaryIO
    stdout: TextIO
    stderr: TextIO
    stdout_isatty: bool
    stderr_isatty: bool

    @classmethod
    def from_process(cls) -> Environment:
        """The process's streams. A closed stdin (cron, daemons) reads as empty; main() refuses to run
        with no stdout or stderr at all."""
        stdin = sys.stdin.buffer if sys.stdin is not None else io.BytesIO()
        return cls(
            stdin=stdin,
            stdout=sys.stdout,
            stderr=sys.stderr,
            stdout_isatty=sys.stdout.isatty(),
            stderr_isatty=sys.stderr.isatty(),
        )


class Sinks:
    """Where decoded items go: the display filter, then the printer, the pcap and the statistics."""

    def __init__(self, options: DecodeOptions, env: Environment, annotate: Annotator | None = None) -> None:
        args = options
        self.env = env
        self.json = args.output.json
        self.predicate: Callable[[dict], bool] | None = None
        self._last_time: float | None = None
        self.valid_frames = self.input_bytes = 0  # of the input being decoded
        if args.filter is not None:
            from dissector.render.filters import FilterContext, compile_filter

            # The time column's references (time_relative, time_delta) and the maps' codes.
            self.filter_context = FilterContext.of(annotate)  # the maps' codes, the profiles' names
            self.predicate = compile_filter(args.filter, self.filter_context)
        self.stats = None
        if args.stats or args.watch is not None or args.report is not None:
            # One parameter history for --stats, --watch and --report (render/history.py): the
            # statistics feed it, the watch and the report listen to it.
            from dissector.render.history import History
            from dissector.render.stats import StatsCollector

            self.stats = StatsCollector(getattr(annotate, "choices", None), History(annotate))
            self.stats.filtered = args.filter is not None or args.count is not None
        self.stats_shown = args.stats
        self.bus = None  # bus timing and slave health (render/bustiming.py), from every item heard
        self.health = None  # the report's response times over time (report/health.py)
        if args.stats or args.report is not None:
            from dissector.render.bustiming import BusTiming

            self.bus = BusTiming(args.timeout, warn=lambda text: env.stderr.write(f"{PROG}: warning: {text}\n"))
        if args.report is not None:
            from dissector.render.report.health import Health

            self.health = Health()
        # With -w -, standard output is the pcap: text goes to standard error (as tshark -w - -P).
        self.text_out = env.stderr if args.write == STDOUT else env.stdout
        text_isatty = env.stderr_isatty if args.write == STDOUT else env.stdout_isatty
        self.watch = None
        if args.watch is not None:
            from dissector.render.watch import watcher

            self.watch = watcher(args.watch, self.text_out.write, self.json, annotate, self.stats.history,  # type: ignore[union-attr]
                                 Clock(args.output.time_format))
        self.options = args
        self.current: Bus | None = None
        self.report = None
        if args.report is not None:
            from dissector.render.report import ReportFile

            # The report's counts are --stats' numbers, its parameters the same history's.
            # File names are data: a non-UTF-8 name (n\xff.pcap) or an ESC in one is shown escaped. A ring
            # buffer's files are one capture, named as its decode titles it (app/rings.py).
            names = [printable(name) for name, _files in group_files(list(args.files))]
            names += ["--hex"] if args.hex else []
            self.report = ReportFile(args.report, annotate, names, self.stats)  # type: ignore[arg-type]
        collector = self.report.collector if self.report is not None else None  # (one bus, unless interfaces)
        self.buses = Buses(Bus([], self.stats, self.bus, self.watch, collector, self.health), self._new_bus)
        # --report writes a file: the items are printed too when an item format is asked for
        # (--report r.html --json), never silently dropped.
        asked = args.output.records or args.output.detail or args.output.hexdump
        self.show = (not args.stats and not args.quiet and self.watch is None and (self.report is None or asked)
                     and (args.write is None or args.print_too))
        self.output = Output(args.output, self.text_out, text_isatty,
                             lambda text: env.stderr.write(f"{PROG}: {shown(text)}\n"))
        self.clock = self.output.clock
        self.pcap: CaptureOutput | None = None
        self.trail: RecordTrail | None = None  # the input's records (app/inputs.py observe_records)
        self.several = several_captures(args)  # (each input titled: its frames cited with its title)
        self.write_path = args.write
        self.copy_end = CopyEnd()  # -w: the record of no byte the copy closes with, at the input's end
        if args.write is not None:
            try:
                stdout = getattr(env.stdout, "buffer", None)
                first = args.files[0] if args.files and not args.hex else None
                interface = write_interface(first, "pcapng" if args.format in (None, "pcapng") else None, args)
                self.pcap = open_output(args.write, args.file_format, args.ring, False, stdout, interface,
                                        write_units(args.files, env.stdin, args.format), args.frame_records,
                                        first_interface_units(first, args.format, env.stdin))
            except ValueError as error:
                raise UsageError(str(error)) from None
            except OSError as error:
                raise UsageError(f"-w {args.write}: {error.strerror or error}") from None
        # The warnings that pcap loses a description's line speed, a pcapng's buses apart, a time resolution.
        self.speed_lost = self.buses_joined = self.resolution_lost = False
        self.extra: dict[str, object] | None = None
        self.frames_left: int | None = args.count  # -c: items (frames and noise runs) still to show
        self.wrote: str | None = None  # the report written (said last, on a terminal)
        self.done = False  # -c N reached

    def _new_bus(self, title: str | None, annotate: Annotator | None) -> Bus:
        from dissector.render.buses import new_bus  # another interface's counts

        return new_bus(self, annotate)

    def new_input(self, key: object, title: str | None, annotate: Annotator | None, mode: str, line: object,
                  units: int | None = None, packets: object = None) -> None:
        """An input of the bus `key` (render/buses.py: None, the files read as one stream; a pcapng's
        interface otherwise): its counts become the current ones; `units`: its time units a second, whose
        precision the time column, --watch's lines and -V show (tshark's: 9 decimals of a nanosecond pcap)."""
        from dissector.render.buses import header, title as bus_title
        from dissector.render.watch import printer

        # (several captures: a bus's evidence names the input it is in, and --watch titles its lines by it)
        cited = title if self.several else None
        bus = self.buses.switch(key, title, annotate, cited)
        heard, self.current = self.current, bus
        self.stats, self.bus, self.watch, self.health = bus.stats, bus.timing, bus.watch, bus.health
        self.clock.units, self.clock.packets = units, packets  # (packets: a network capture's, timefmt.py)
        if self.watch is not None:
            self.watch.clock.units, self.watch.clock.packets = units, packets  # (its lines' column, as the summary's)
        if self.report is not None:
            self.report.collector = bus.report
            bus.report.time_units(units)  # (the page's times: 9 decimals where microseconds cannot hold them)
        if self.bus is not None:
            if key is not None:  # (its warning names it)
                self.bus.warn = lambda text: self.env.stderr.write(f"{PROG}: warning: {shown(title)}: {text}\n")
            self.bus.new_input(mode, line, title, self.stats)  # (several files: counted as one bus, said)
        if self.watch is not None and (key is not None or heard not in (None, bus)):
            if self.json:
                self.watch.on_change = printer(self.text_out.write, True, None if cited else bus_title(bus))
            elif bus is not heard and cited is None:
                self.text_out.write(header(bus, heard is None))

    @property
    def plain_summary_only(self) -> bool:
        """Every item becomes one plain summary line, nothing else reads them."""
        return (
            self.show
            and self.predicate is None
            and self.stats is None
            and self.pcap is None
            and self.frames_left is None
            and self.output.plain_summary
        )

    @property
    def stats_only(self) -> bool:
        """--stats (or --stats --json) is all that reads the items: the compiled path may count them."""
        return (
            self.stats is not None
            and self.stats_shown
            and not self.show
            and self.predicate is None
            and self.watch is None
            and self.report is None
            and self.pcap is None
            and self.frames_left is None
        )

    def accept(self, items: list[Item]) -> None:
        heard = items  # noqa: F841 -- keeps the items -Y drops alive while these are written: a request's
        # response is a weak reference, and -V says "Response in frame: 2" of a response not shown
        for item in items:  # is there any Modbus in this input at all?
            self.input_bytes += item.length
            if isinstance(item, Frame) and item.crc_ok:
                self.valid_frames += 1
        predicate = self.predicate
        records: list[dict] | None = None
        numbers = record_numbers(self.trail, heard)  # (before -Y, as the pieces: every item's, in order)
        pieces = item_pieces(self.trail, heard)  # (before -Y: the trail forgets what is behind an item)
        if self.watch is not None:
            self.watch.observe(items)  # the time column never depends on -Y
        if self.show:
            self.clock.observe(items)  # time references are the capture's, whatever the filter shows
        if self.bus is not None:
            self.bus.add_items(items)  # the bus as it was, whatever -Y shows
        if self.health is not None:
            self.health.add_items(items)
        if predicate is not None:
            self._filter_times(items)
            # The filter reads the NDJSON form; keep it for --json rather than building it twice. With its
            # packet comments: -Y comment, as tshark's frame.comment (render/filter_fields.py RECORD_KEYS).
            noted = (pieces and comments_of(pieces)) or {}
            pairs = []
            for item, number in zip(items, numbers or [None] * len(items)):
                record = item_record(item, noted.get(id(item)), number)
                if predicate(record):
                    pairs.append((item, record))
            items = [item for item, _record in pairs]
            records = [record for _item, record in pairs]
        elif numbers is not None:
            records = numbered_records(items, numbers)
        if self.frames_left is not None:
            items = self._up_to_count(items)
            if records is not None:
                records = records[: len(items)]
        if self.pcap is not None:
            try:
                last = heard[-1] if heard else None  # (items come in the order of their bytes)
                settled = self.trail.settled(last.offset + last.length) if self.trail and last else None
                self.pcap.write_items(items, pieces, settled)
            except OSError as error:
                raise self._write_failed(error) from None
            self.copy_end.written(items, pieces)
        if self.stats is not None:
            report = self.report.collector if self.report is not None else None
            for item in items:
                if report is not None:
                    report.add(item)  # its events first: the history's (through stats) follow
                self.stats.add(item)
        if self.watch is not None:
            self.watch.done()
        if self.show:
            if self.clock.format == "d" or self.clock.deltas:
                self.clock.keep(items)
            self.output.write(items, self.extra, records, pieces and comments_of(pieces))
        if self.clock.packets is not None and heard:  # (the packets' times before these are asked no more)
            self.clock.packets.forget(heard[-1].offset)

    def restart_times(self) -> None:
        """A new input: its times count from its own first item (as the time column)."""
        if self.pcap is not None:
            try:
                self.pcap.release()  # its last noise run shares no record with the next input's bytes
            except OSError as error:
                raise self._write_failed(error) from None
        if self.predicate is not None:
            self.filter_context.first = None
            self._last_time = None

    def _filter_times(self, items: list[Item]) -> None:
        """time_relative and time_delta for -Y: from every item captured, whatever the filter keeps."""
        self._last_time = self.filter_context.captured(items, self._last_time, self.clock.packets)

    def _up_to_count(self, items: list[Item]) -> list[Item]:
        """Items up to and including the Nth of -c N; then the decoding stops. Every item counts, a noise
        run as a frame: each is a packet (a line here, a record of -w, a packet of the plugin), and
        tshark -c N stops at N packets."""
        assert self.frames_left is not None
        if len(items) < self.frames_left:
            self.frames_left -= len(items)
            return items
        items, self.frames_left, self.done = items[: self.frames_left], 0, True
        return items

    def abandon(self, refused: bool = False) -> None:
        """Close the files after a failure, keeping what was written; errors are the caller's.
        `refused`: an input was refused (SourceError): a -w file that holds no record and the report
        are removed, not left header-only or empty."""
        if self.report is not None:
            self.report, report = None, self.report
            report.abandon(refused)
        if self.pcap is not None:
            try:
                self.pcap.discard_if_empty() if refused else self.pcap.close()
            except OSError:
                pass
            self.pcap = None

    def _write_failed(self, error: OSError) -> OutputError:
        """-w failed (a full disk): the file was cut back to whole records; say what it keeps."""
        kept = f"; {self.pcap.kept}" if self.pcap is not None else ""
        return OutputError(f"-w {self.write_path}: {error.strerror or error}{kept}")

    def close(self) -> None:
        buses = self.buses.all()
        for bus in buses:
            if bus.stats is not None:
                bus.stats.history.finish()  # frames held until their slave's profile was chosen (read once)
        if self.pcap is not None:
            try:
                self.copy_end.close(self.pcap)
            except OSError as error:
                raise self._write_failed(error) from None
            pcap, self.pcap = self.pcap, None
            if pcap.clamped_total:
                clamped = pcap.clamped_total
                whose = "records' times" if clamped > 1 else "record's time"
                self.env.stderr.write(
                    f"{PROG}: warning: -w {shown(self.write_path)}: {clamped} {whose} outside "
                    f"what {pcap.format} holds, written at the nearest time it holds\n"
                )
        for bus in buses:
            if bus.watch is not None:
                bus.watch.finish()
                for line in bus.watch.unseen():  # (a watched address or code the input never had)
                    self.env.stderr.write(f"{PROG}: {shown(line)}\n")
        if self.report is not None:
            from dissector.render.buses import write_report_page

            report, self.report = self.report, None
            write_report_page(self, report, buses)
            self.wrote = report.path
        if self.stats is not None and self.stats_shown:
            from dissector.render.buses import write_stats

            for index, bus in enumerate(buses):
                write_stats(self, bus, index if self.buses.several else None)
        self.output.flush()


def _annotator(args: argparse.Namespace) -> Annotator | None:
    if args.no_profile:
        return None
    return annotator_from_args(args)


def decode_files(args: DecodeOptions, env: Environment, annotate: Annotator | None) -> int:
    sinks = Sinks(args, env, annotate)
    try:
        damage = _decode_inputs(args, env, sinks, annotate)
        sinks.close()
        profile_notes(sinks.buses, annotate, env.stderr, env.stderr_isatty)
        # (a --map written in PLC references, told from the traffic: once per run, terminal or not)
        for warning in map_warnings([annotate, *(bus.annotate for bus in sinks.buses.all())]):
            env.stderr.write(f"{PROG}: warning: {shown(warning)}\n")
        if sinks.wrote is not None and env.stderr_isatty:
            env.stderr.write(f"{PROG}: wrote {shown(sinks.wrote)}\n")
        if damage is not None:  # (an input damaged after its first packets: they are shown, the run ends refused)
            raise damage
    except BrokenPipeError:
        sinks.abandon()
        raise  # the reader went away: main() ends quietly
    except OSError as error:
        sinks.abandon()
        raise OutputError(f"standard output: {error.strerror or error}") from None
    return ExitStatus.OK


def _decode_inputs(
    args: DecodeOptions, env: Environment, sinks: Sinks, annotate: Annotator | None
) -> SourceError | None:
    """The inputs decoded; the damage that ended one after its first packets (Source.damage), the inputs after it
    not read, or None."""
    devices: dict[object, Annotator | None] = {}  # per bus (pcapng interface) its annotator
    # The devices as they are before any frame, for a pcapng's other interfaces and a network capture's other
    # connections (~13 ms a copy; a pcap's second connection took up the first's evidence for profile auto).
    several = args.tcp_port or args.udp_port or any(map(is_pcapng_file, args.files))
    pristine = copy.deepcopy(annotate) if annotate is not None and several else None
    chosen_over_all = choose_over_all(args, env, annotate)
    try:
        for (title, chunks, mode, take_warnings, recorded, timed, fix, (path, source_format),
             bus, again, units, packets, damage, numbering) in inputs(args, env):
            if sinks.done:
                break
            line = input_line(path, source_format, args, bus)
            # An interface is a bus, the same in every file (ring files, as mergecap joins them); files read
            # as one stream are one bus's pieces.
            key = None if bus is None else (bus.label(), bus.ordinal)
            if pristine is not None:
                # Another bus's slave 12 is not the first bus's: a device of its own (as the run's before any
                # frame), its own profile choices (auto) and counts (--stats, --watch).
                annotate = devices.setdefault(key, annotate if not devices else copy.deepcopy(pristine))
            sinks.new_input(key, title, annotate, mode, line, units, packets)
            # no ==> header over nothing; with -Y none over a file with no match
            sinks.output.new_input(title if sinks.show else None, held=sinks.predicate is not None)
            sinks.restart_times()
            if sinks.pcap is not None:
                keep_interface(sinks, args, env, path, source_format, line, bus, units)
            sinks.extra = {"file": title} if title is not None else None

            def warn() -> None:
                for warning in take_warnings():
                    env.stderr.write(f"{PROG}: warning: {shown(warning)}\n")

            if not chosen_over_all:
                choose_profiles_first(annotate, args, chunks, mode, path, again, line.baud, fix)
            framer = AsciiFramer(line.baud) if mode == "ascii" else RtuFramer(line.baud)  # (its silences: evidence)
            dissector = Dissector(
                framer=framer,
                annotate=annotate,
                timeout=args.timeout,
                gaps=GapChecker(line.baud, mode) if timed else None,
                recorded=recorded,
            )
            sinks.valid_frames = sinks.input_bytes = 0
            chunks, sinks.trail = observe_records(chunks, source_format, sinks.pcap is not None,
                                                  numbering if numbers_records(args) else None)
            decode_one(chunks, mode, timed, fix, dissector, sinks, annotate, warn)
            tell_comments(sinks, path, env.stderr, title if bus is not None else None)
            sinks.copy_end.ended(None if sinks.done else recorded())  # (-c N: the copy ends at the Nth)
            # (-c N may stop in an input's first noise run, before its frames: not judged then.)
            if ((sinks.input_bytes or framer.cut_records) and not sinks.valid_frames and path is not None
                    and not sinks.done):
                # A PNG, a line read at the wrong speed: say so once, not only as noise and damage
                # (--hex bytes typed from a manual have their own notes: a CRC typo is spelled out).
                env.stderr.write(no_frame_warning(path, mode, sinks.input_bytes, framer.cut_records,
                                                  framer.cut_bytes))
            if damage() is not None:  # (its packets before the damage shown, as tshark shows them: then refused)
                return damage()  # type: ignore[no-any-return]
    except BaseException as error:
        sinks.abandon(isinstance(error, SourceError))
        raise
    return None


def _live(args: argparse.Namespace, env: Environment) -> int:
    # The display options as a file decode checks and honours them (-Y, -V, -x, -T fields): one
    # line for a contradiction or a bad filter, before the port is opened.
    checked = argparse.Namespace(**vars(args))
    checked.raw = checked.duration = None  # live options, which the file checks refuse
    checked.port_format = []  # (the port's frame format: --parity, --stopbits, --bytesize)
    options = decode_options(checked)
    args.display, args.filter_text = options.output, options.filter
    annotate = _annotator(args)
    if options.filter is not None:
        from dissector.render.filters import FilterContext, compile_filter

        compile_filter(options.filter, FilterContext.of(annotate))
    if options.watch is not None:
        from dissector.render.watch import known_codes, parse_watch

        parse_watch(options.watch, known_codes(annotate))
    # The time column as for files (-t): from the first item heard, or the one heard before, whatever
    # -Y shows (live.display observes every item heard).
    clock = Clock(args.time_format)

    def column(item: Item) -> str:
        return clock.text(item)

    from dissector.app.live import run_live  # pyserial is loaded only for a live capture

    is_terminal = args.color == "always" or (args.color == "auto" and env.stdout_isatty)
    return run_live(
        args,
        env.stdout,
        env.stderr,
        is_terminal,
        lambda item: summary_line(item, column=column(item)),
        annotate,
        lambda item: summary_text(item, column=column(item)),
        clock.observe,
    )


def run(argv: list[str] | None, env: Environment) -> int:
    parser = build_parser()
    try:
        # argparse writes usage, errors, --help and --version itself: to the injected terminal.
        with contextlib.redirect_stdout(env.stdout), contextlib.redirect_stderr(env.stderr):
            args = parse_arguments(parser, argv)
    except SystemExit as exit_:
        return ExitStatus.BAD_INPUT if exit_.code else ExitStatus.OK
    except UsageError as error:
        env.stderr.write(f"{PROG}: {shown(error)}\n")
        return ExitStatus.BAD_INPUT
    args.files = [*args.read, *args.files]
    if getattr(args, "glossary", None):
        from dissector.render.glossary import glossary  # -G fields: tshark's tab-separated lines

        env.stdout.write(glossary())
        return ExitStatus.OK
    if "help" in (args.filter or []):
        from dissector.render.filters import field_listing  # -Y help: the same fields, to read

        env.stdout.write(field_listing())
        return ExitStatus.OK
    try:
        refuse_same_files(args, env.stdin, env.stdout)
        if args.live or args.detect is not None:
            if args.live is None:
                raise UsageError("--detect needs --live PORT")
            if args.files or args.hex:
                raise UsageError("--live takes no FILE or --hex")
            if args.report is not None or args.stats:
                raise UsageError("--report and --stats read files: capture with -w FILE, then report on it")
            if args.parquet is not None or args.jobs != 1 or args.scheduler is not None:
                raise UsageError("--parquet reads files: capture with -w FILE, then --parquet DIR FILE")
            if args.output_format == "registers":
                raise UsageError("-T registers reads files: capture with -w FILE, then -T registers FILE")
            if args.tcp_port or args.udp_port:
                raise UsageError("--tcp-port and --udp-port read network captures; --live reads the serial line itself")
            return _live(args, env)
        if not args.files and not args.hex:
            raise UsageError(f"give a capture FILE, - for stdin, --hex BYTES or --live PORT (see {PROG} --help)")
        options = decode_options(args)
        if args.parquet is not None:
            from dissector.app.jobs import parquet_main

            return parquet_main(args, env.stdout, env.stderr, PROG)
        return decode_files(options, env, _annotator(args))
    except (UsageError, SourceError, ProfileError, FilterError) as error:
        _flush_quietly(env.stdout)
        env.stderr.write(f"{PROG}: {shown(error)}\n")
        return ExitStatus.BAD_INPUT
    except OutputError as error:
        env.stderr.write(f"{PROG}: {shown(error)}\n")
        return ExitStatus.ERROR


def _flush_quietly(stream: TextIO) -> None:
    try:
        stream.flush()
    except OSError:
        pass


def main(argv: list[str] | None = None) -> int:
    # Decoding allocates many small objects that live until written: collect young ones less often.
    gc.set_threshold(10_000, 20, 20)
    gc.freeze()
    if sys.stdout is None or sys.stderr is None:
        if sys.stderr is not None:
            sys.stderr.write(f"{PROG}: standard output is closed\n")
        return ExitStatus.ERROR
    for stream in (sys.stdout, sys.stderr):
        # An ASCII-only locale cannot encode `…` or a map's `°C`: written as escapes, not a traceback.
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None:
            with contextlib.suppress(ValueError, OSError):
                reconfigure(errors="backslashreplace")
    env = Environment.from_process()
    try:
        status = run(argv, env)
    except KeyboardInterrupt:
        env.stderr.write(f"{PROG}: interrupted\n")
        return 130
    except BrokenPipeError:
        # The reader (head, less) went away: stop quietly, as tshark does.
        _silence_stdout()
        return ExitStatus.OK
    if status == ExitStatus.ERROR:
        _silence_stdout()  # what could not be written must not fail again at exit
    return int(status)


def _silence_stdout() -> None:
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


if __name__ == "__main__":
    sys.exit(main())
