"""Live sniffing: read a serial port (or any pyserial URL), frame and show what crosses the bus.

The port is opened for listening only: nothing is ever written to it, and RTS is left deasserted
because RS-485 adapters that steer their driver with RTS would otherwise drive the bus.

Capture and display are apart (dumpcap and tshark): the capture thread (live_capture.py) reads, frames
and writes the files; this module, on the main thread, pairs, decodes, annotates and shows what it
hands on, and an output thread writes the lines (live_view.py). Neither can slow the capture.

Every line is final: a request's line waits for its answer, or for its --timeout to pass (pairing.py
states the rule), so the line shown live is the line the one-pass decode of the -w file gives
(`vw3-decode - < file`), pairing, response time and unanswered included. On a healthy bus a request is
shown when its response comes. A file read by name is read twice (app/preselect.py); live cannot look
ahead, so a frame decoded before profile `auto` chose its slave's device says it is provisional
(Frame.provisional) in every output, and ProfileNews says on stderr when the choice is made.

With the compiled engine (compiled_mode: not with VW3_PURE_PYTHON, Modbus ASCII or -c with --raw), the capture
thread only reads, stamps and writes --raw, and hands on the reads; the display frames, pairs, writes -w
and shows them through dissector/accel/livepath.py, which takes the capture thread's decisions (flush after a
silence, expire a request past --timeout) at the same reads, so the lines are the Python path's, shown
as soon. VW3_LIVE_TAPE records the reads, VW3_LIVE_REPLAY decodes a recording again (one thread, the
display keeping up), VW3_LIVE_REPORT says how many frames the engine framed:
tests/differential/test_live_compiled.py holds both paths byte-identical on the same reads.
"""
from __future__ import annotations

import argparse
import os
import signal
import time
from collections.abc import Callable
from typing import Any, BinaryIO, TextIO

from rich.text import Text

from dissector.app.live_capture import (
    IDLE_FLUSH,
    IDLE_FLUSH_LONG,
    CaptureFiles,
    CaptureThread,
    HANDOFF_READS_LIMIT,
    Handoff,
    Tape,
    long_silence,
    silence_threshold,
)
from dissector.app.detect import AsciiHeard
from dissector.app.live_options import BYTESIZE_GIVEN, PARITY_CHOICES, live_mode, mode_bytesize
from dissector.app.options import shown  # typed names are data: control characters escaped
from dissector.app.live_view import LineSink, LiveStats, OutputPump, RichSink, Sink, json_line
from dissector.devices.maps_refs import map_warnings
from dissector.errors import ExitStatus, LiveError
from dissector.framing.ascii import AsciiFramer
from dissector.framing.timing import LineTiming
from dissector.framing.rtu import RtuFramer
from dissector.model import Item, Stamp
from dissector.pipeline import Annotator, Dissector
from dissector.render.capturefile import STDOUT, CaptureOutput, open_output
from dissector.sources.serial_port import PARITIES, PortSettings, open_port
from dissector.sources.serial_times import ReadClock, char_time

PROG = "vw3-decode"
assert set(PARITIES) == set(PARITY_CHOICES)
__all__ = ["IDLE_FLUSH", "IDLE_FLUSH_LONG", "run_live", "silence_threshold"]
REPLAY_ENV = "VW3_LIVE_REPLAY"  # decode the reads of a tape (live_capture.TAPE_ENV) instead of the port's
REPORT_ENV = "VW3_LIVE_REPORT"  # say on stderr how much the engine framed (tests: the compiled path ran)
WAIT = 0.02  # the display wakes at least this often (timeouts, the stop flag, redraws)


def port_settings(args: argparse.Namespace) -> PortSettings:
    """The port's settings; without --bytesize, the mode's data bits (Serial Line Guide 2.5: RTU 8, ASCII 7)."""
    bytesize = args.bytesize if getattr(args, BYTESIZE_GIVEN, False) else mode_bytesize(getattr(args, "mode", None))
    return PortSettings(args.live, args.baud, args.parity, args.stopbits, bytesize)


def live_char_time(args: argparse.Namespace) -> float:
    """Seconds a character of the port's settings takes (a read's bytes are timed by it)."""
    settings = port_settings(args)
    return char_time(settings.baud, settings.bytesize, settings.parity, settings.stopbits)


def live_framer(mode: str | None, baud: int) -> AsciiFramer | RtuFramer:
    """The capture thread's framer (vw3-decode --live, vw3-extcap). Modbus ASCII only with --mode
    ascii or 7 data bits (live_options.live_mode): a live stream cannot be sniffed before it starts (a hint
    says when its bytes are ASCII: app/detect.py AsciiHeard)."""
    return AsciiFramer(baud) if mode == "ascii" else RtuFramer(baud)


def interface_description(settings: PortSettings) -> str:
    """pcapng if_description: the serial settings, spelled out and as a manual writes them."""
    parity = {"E": "even", "O": "odd", "N": "no"}[settings.parity]
    stop = int(settings.stopbits) if settings.stopbits == int(settings.stopbits) else settings.stopbits
    return (
        f"serial port {settings.port}, {settings.baud} baud, {settings.bytesize} data bits, {parity} "
        f"parity, {stop} stop bit{'' if stop == 1 else 's'} ({settings.text()})"
    )


def capture_output(args: argparse.Namespace, stdout: BinaryIO | None) -> CaptureOutput | None:
    """The -w output of a live capture; LiveError when it cannot be created."""
    path = getattr(args, "write", None)
    if not path:
        return None
    settings = port_settings(args)
    try:
        return open_output(
            path, getattr(args, "file_format", None), getattr(args, "ring", None) or (), True, stdout,
            (settings.port, interface_description(settings)),
        )
    except ValueError as error:
        raise LiveError(str(error)) from None
    except OSError as error:
        raise LiveError(f"cannot write {path}: {error.strerror or error}") from None


# SIGHUP too: closing the SSH session or terminal a capture runs in ends it as dumpcap ends, files whole.
STOP_SIGNALS = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, name))


class StopFlag:
    """Set by SIGINT, SIGTERM or SIGHUP: the read loop sees it within one read timeout and stops cleanly."""

    def __init__(self) -> None:
        self.signal: int | None = None
        self._previous: dict[int, object] = {}

    def __enter__(self) -> StopFlag:
        for signum in STOP_SIGNALS:
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


class NullSink:
    failed: BaseException | None = None
    dropped = 0

    def show(self, items: list[Item]) -> None:
        pass

    def tick(self) -> None:
        pass

    def close(self) -> None:
        pass


def _make_sink(
    args: argparse.Namespace,
    out: TextIO,
    err: TextIO,
    is_terminal: bool,
    render_line: Callable[[Item], str],
    render_text: Callable[[Item], Text] | None,
    stats: LiveStats,
    annotate: Annotator | None = None,
) -> Sink:
    if getattr(args, "quiet", False):
        return NullSink()  # (-q: no items; the summary line at the end stays, as tshark -q's)
    if getattr(args, "write", None) == STDOUT:
        # Standard output is the pcap: lines only with -P, on standard error (as tshark -w - -P).
        if not getattr(args, "print_too", False):
            return NullSink()
        out, is_terminal = err, False
    sink = _items_sink(args, out, is_terminal, render_line, render_text, stats, annotate, err)
    text = getattr(args, "filter_text", None)
    if text is not None:
        from dissector.app.live_display import FilteredSink

        sink = FilteredSink(sink, text, annotate)
    return sink


def _items_sink(
    args: argparse.Namespace,
    out: TextIO,
    is_terminal: bool,
    render_line: Callable[[Item], str],
    render_text: Callable[[Item], Text] | None,
    stats: LiveStats,
    annotate: Annotator | None = None,
    err: TextIO | None = None,
) -> Sink:
    if getattr(args, "watch", None) is not None:
        from dissector.render.watch import WatchSink

        return WatchSink(args.watch, OutputPump(out), getattr(args, "json", False), annotate,
                         getattr(args, "time_format", "r"))
    display = getattr(args, "display", None)
    if display is not None and (display.detail or display.hexdump or display.fields is not None
                                or display.registers is not None):
        from dissector.app.live_display import TextSink

        return TextSink(out, display, err)  # as a file decode writes them (plain text, also on a terminal)
    if getattr(args, "json", False):
        return LineSink(out, json_line)
    if is_terminal:
        from dissector.render.output import quiet_console
        from dissector.render.theme import THEME

        console = quiet_console(out, theme=THEME, force_terminal=True, highlight=False)  # (| head: exit 0)
        render = render_text or (lambda item: Text(render_line(item), no_wrap=True))
        title = f"{args.live} at {port_settings(args).text()} (Ctrl-C to stop)"
        return RichSink(console, title, stats, render)
    return LineSink(out, render_line)


class ProfileNews:
    """Profile `auto` live: a stderr line when a slave's device is chosen (or the choice changes), so
    that the user knows from which frame its lines are no longer provisional."""

    def __init__(self, annotate: Annotator | None, err: TextIO | None) -> None:
        self.selector = getattr(annotate, "selector", None) if err is not None else None
        self.err = err
        self.told: dict[int, str] = {}
        self.provisional: set[int] = set()  # slaves shown provisional lines

    def __call__(self, shown: list[Item]) -> None:
        selector = self.selector
        if selector is None:
            return
        for item in shown:
            if getattr(item, "provisional", False):
                self.provisional.add(item.slave)  # type: ignore[union-attr]
        for slave, choice in selector.chosen().items():
            if self.told.get(slave) != choice.profile:
                self.told[slave] = choice.profile
                earlier = "; its earlier lines were provisional" if slave in self.provisional else ""
                self.err.write(f"{PROG}: profile {choice.text()}{earlier}\n")  # type: ignore[union-attr]
                self.err.flush()  # type: ignore[union-attr]


class Shown:
    """What the display does with what is shown: count it, give the time column and the filter every
    item heard, show it, and tell profile news."""

    def __init__(self, sink: Sink, stats: LiveStats, observe: Callable[[list[Item]], None] | None = None,
                 news: Callable[[list[Item]], None] | None = None, capture: CaptureThread | None = None,
                 heard: Callable[[bytes, bool], None] | None = None) -> None:
        self.sink, self.stats, self.observe, self.news = sink, stats, observe, news
        self.heard = heard  # (app/detect.py AsciiHeard: RTU assumed, told the bytes heard)
        # The compiled live path: the display writes -w (before it shows, as the capture thread does);
        # a failed write stops the capture, and nothing more is shown.
        self.capture = capture
        self.stopped = False

    def write(self, items: list[Item] | None = None,
              release: tuple[Stamp | None, int] | bool = False) -> list[Item] | None:
        """Write `items` (None: tick the files) or, with `release` (a time and the bytes read), the noise
        run the files hold if no item can join it (CaptureFiles.release): the items to show, None if
        the write failed (the capture stops)."""
        capture = self.capture
        if self.stopped:
            return None
        if capture is None:
            return items or []
        try:
            if release is not False:
                return capture.files.release(*release)  # type: ignore[misc]
            if items is None:
                capture.files.tick()
                return []
            return capture.files.items(items)
        except LiveError as error:
            capture.reason, capture.status = str(error), error.status
            capture.stop.set()
            self.stopped = True
        return None

    def release(self, now: Stamp | None, read: int = 0) -> None:
        """Show the noise run the files held, once written (CaptureFiles.release)."""
        if self.capture is not None:
            self.items([], (now, read))

    def items(self, shown: list[Item], release: tuple[Stamp | None, int] | bool = False) -> None:
        written = self.write(shown, release)
        if written is None:
            return
        shown = written
        for item in shown:
            self.stats.add(item)
        if self.observe is not None:
            self.observe(shown)  # the time column's references: every item heard, whatever -Y shows
        sink = self.sink
        sink_observe = getattr(sink, "observe", None)
        if sink_observe is not None:
            sink_observe(shown)
        sink.show(shown)
        if self.news is not None and shown:
            self.news(shown)

    def lines(self, data: bytes) -> None:
        """The engine's summary lines (UTF-8, each ending in a newline)."""
        if self.stopped:
            return
        lines = data.decode("utf-8").split("\n")
        del lines[-1]
        self.stats.add_lines(lines)
        self.sink.show_lines(lines)  # type: ignore[attr-defined]


def stop_time(capture: CaptureThread, live: Any) -> Stamp | None:
    """When the capture stopped: live's finish judges the last request's wait to then, as the decode of
    the -w file does to its closing record (CaptureThread.stopped_at); -c reached on the compiled path,
    its Nth item's time (LivePath._stop_at: the capture thread reads on until told)."""
    if live is not None and live.done:
        return live.cut_time  # type: ignore[no-any-return]
    return capture.stopped_at()


def display(capture: CaptureThread, handoff: Handoff, dissector: Dissector, sink: Sink, stats: LiveStats,
            stop: StopFlag, observe: Callable[[list[Item]], None] | None = None,
            news: Callable[[list[Item]], None] | None = None, live: Any = None,
            shown: Shown | None = None) -> str | None:
    """Pair, decode and show what the capture hands on until it ends; a reason if the display stops it.
    With `live` (dissector/accel/livepath.py LivePath), the capture hands on its reads, and `live`
    frames and shows them."""
    if shown is None:
        shown = Shown(sink, stats, observe, news, capture if live is not None else None)
    while True:
        if stop.signal is not None:
            capture.stop.set()
        reason, closed = display_once(capture, handoff, dissector, shown, WAIT, live)
        if reason is not None or closed:
            return reason


def display_once(capture: CaptureThread, handoff: Handoff, dissector: Dissector, shown: Shown, wait: float,
                 live: Any = None) -> tuple[str | None, bool]:
    """What the capture handed on (waiting up to `wait` for it): (why the display stops, closed)."""
    items, safe, closed = handoff.take(wait)
    if shown.heard is not None:  # (the bytes heard: the reads on the compiled path, else the items framed)
        shown.heard(b"".join(item[0] if live is not None else item.raw for item in items), closed)
    sink = shown.sink
    if live is not None:
        if items and not shown.stopped:
            live.feed(items)
            if live.done:  # -c reached: the capture stops, as its thread stops itself on the Python path
                capture.reason = "count"
                capture.stop.set()
                shown.release(None)
            else:  # (as the capture thread at each read: CaptureThread.step, which counts the bytes read)
                shown.release(ReadClock.promise(items[-1][1]), capture.read)
        if closed and not shown.stopped:
            dissector.pairer.end = stop_time(capture, live)
            live.finish()
            shown.release(None)
        shown.write()  # (a -w ring switches files on time)
        sink.show([])
    else:
        out = dissector.push(items) if items else []
        if closed:
            dissector.pairer.end = stop_time(capture, live)
            out += dissector.finish()
        elif safe is not None:
            out += dissector.expire(safe)
        shown.items(out)
    shown.stats.not_shown = handoff.dropped + sink.dropped
    sink.tick()
    if sink.failed is not None:
        # The reader of our output (head, less) went away: stop, keep the files whole.
        capture.stop.set()
        capture.done.wait()
        return "output closed", closed
    return None, closed


def _live_path(compiled: str, dissector: Dissector, annotate: Annotator | None, clock: Any, shown_: Shown,
               args: argparse.Namespace) -> Any:
    from dissector.accel.livepath import LivePath

    return LivePath(dissector, annotate, clock, shown_.items, shown_.lines, getattr(args, "timeout", None),
                    silence_threshold(args.baud), long_silence(args.baud), compiled == "summary",
                    getattr(args, "count", None), live_char_time(args))


def _replay(path: str, capture: CaptureThread, handoff: Handoff, dissector: Dissector, shown_: Shown,
            live: Any) -> None:
    """The reads of a tape (VW3_LIVE_REPLAY) as the capture made them, each shown before the next is
    made: a display that keeps up, on one thread, so that a capture's decode can be repeated exactly."""
    try:
        for data, stamp, now in Tape.read(path):
            if data:
                capture.files.raw(data)
            if not capture.step(data, stamp, now):
                capture.reason = "count"
                break
            display_once(capture, handoff, dissector, shown_, 0, live)
            if live is not None and live.done:
                break  # (-c reached: display_once said it)
    except LiveError as error:
        capture.reason, capture.status = str(error), error.status
    finally:
        capture.end()
    while not display_once(capture, handoff, dissector, shown_, 0, live)[1]:
        pass


def compiled_mode(args: argparse.Namespace, is_terminal: bool, clock: Any) -> str | None:
    """How the engine takes part in this live capture: "summary" (it writes the summary lines),
    "frames" (it frames and pairs, the Python stages show; -w is written from those items; always with
    -c, cut at the Nth frame before the Python stages decode it: livepath.py), or None (the Python
    stages do it all: VW3_PURE_PYTHON, no extension, Modbus ASCII, and -c with --raw: the capture
    thread stops at the read its framer reaches the count with, which the engine, holding a request
    until its answer, may reach later)."""
    count = getattr(args, "count", None)
    if live_mode(args) == "ascii" or (count is not None and getattr(args, "raw", None)):
        return None
    from dissector.accel import livepath

    if not livepath.available():
        return None
    display = getattr(args, "display", None)
    plain = display is None or not (display.detail or display.hexdump or display.fields is not None
                                    or display.registers is not None)
    if (plain and count is None and not is_terminal and not getattr(args, "write", None) and not getattr(args, "json", False) and getattr(args, "watch", None) is None
            and getattr(args, "filter_text", None) is None and clock is not None and livepath.summary_usable(clock)):
        return "summary"
    return "frames"


def run_live(
    args: argparse.Namespace,
    out: TextIO,
    err: TextIO,
    is_terminal: bool,
    render_line: Callable[[Item], str],
    annotate: Annotator | None,
    render_text: Callable[[Item], Text] | None = None,
    observe: Callable[[list[Item]], None] | None = None,
) -> int:
    """Capture from args.live until --duration, --count, Ctrl-C or the port goes away."""
    if getattr(args, "detect", None) is not None:
        from dissector.app.detect import run_detect

        return run_detect(args, out, err)
    replay = os.environ.get(REPLAY_ENV)  # a capture's reads again (live_capture.Tape), not the port
    try:
        port = None if replay else open_port(port_settings(args))
    except LiveError as error:
        err.write(f"{PROG}: {shown(error)}\n")
        return error.status
    try:
        rtu = None if live_mode(args) == "ascii" else LineTiming(args.baud)  # (-w: CaptureFiles._records)
        files = CaptureFiles(capture_output(args, getattr(out, "buffer", None)), args.raw, rtu)
    except LiveError as error:
        if port is not None:
            port.close()
        err.write(f"{PROG}: {shown(error)}\n")
        return error.status
    stats = LiveStats(files=bool(files.names))
    mode = live_mode(args)
    inferred = " (Modbus ASCII: 7 data bits carry no RTU)" if mode != getattr(args, "mode", None) else ""
    err.write(f"{PROG}: listening on {shown(args.live)} at {port_settings(args).text()}{inferred}\n")
    err.flush()
    framer = live_framer(mode, args.baud)
    timeout = getattr(args, "timeout", None)
    clock = getattr(observe, "__self__", None)  # (app/cli.py: the time column's Clock.observe)
    compiled = compiled_mode(args, is_terminal, clock)
    if compiled is not None:
        # The capture thread only reads; the display frames (dissector/accel/livepath.py).
        dissector = Dissector(framer=framer, hold=True, annotate=annotate, timeout=timeout, live=True)
        framer = None  # type: ignore[assignment]
    else:
        # The framer is the capture thread's; the dissector pairs, decodes and annotates what it frames.
        dissector = Dissector(hold=True, annotate=annotate, timeout=timeout, live=True,
                              char_time=framer.timing.char_time)
    handoff = Handoff(HANDOFF_READS_LIMIT) if compiled is not None else Handoff()
    capture = CaptureThread(
        port, framer, files, handoff, silence_threshold(args.baud), args.duration, args.count,  # type: ignore[arg-type]
        silence_long=long_silence(args.baud), port_name=args.live, char_time=live_char_time(args),
    )
    started = time.monotonic()
    sink: Sink = NullSink()
    live = None
    try:
        with StopFlag() as stop:
            if not replay:
                capture.start()  # first: a sink that fails (a reader gone) must not leave done unset
            sink = _make_sink(args, out, err, is_terminal, render_line, render_text, stats, annotate)
            news = ProfileNews(annotate, err)
            heard = None if mode is not None else AsciiHeard(err)
            shown_ = Shown(sink, stats, observe, news, capture if compiled is not None else None, heard)
            if compiled is not None:
                live = _live_path(compiled, dissector, annotate, clock, shown_, args)
            if replay:
                _replay(replay, capture, handoff, dissector, shown_, live)
            else:
                display(capture, handoff, dissector, sink, stats, stop, observe, news, live, shown_)
    finally:
        capture.stop.set()
        if not replay:
            capture.done.wait()
        if port is not None:
            port.close()
        files.close(stop_time(capture, live))  # (the compiled path's -w: the display wrote it to the end)
        stats.finish()
        try:
            sink.close()
        except (BrokenPipeError, OSError):
            pass
    try:
        _summary(err, live, compiled, stats, handoff, sink, started, files, capture, annotate)
    except (OSError, ValueError):
        pass  # stderr is gone (the terminal closed: SIGHUP); the files are whole, closed above
    return capture.status


def _summary(err: TextIO, live: Any, compiled: str | None, stats: LiveStats, handoff: Handoff, sink: Sink,
             started: float, files: CaptureFiles, capture: CaptureThread, annotate: Annotator | None) -> None:
    """The capture's last lines on stderr: an error if it failed, a --map written in PLC references (as a
    file decode says it, once, devices/maps_refs.py), then what it saw and wrote."""
    if live is not None and os.environ.get(REPORT_ENV):
        err.write(f"{PROG}: live path: engine ({compiled}), {live.engine_items} frames from the engine, "
                  f"{live.python_items} items from the Python stages\n")
    stats.not_shown = handoff.dropped + sink.dropped
    seconds = time.monotonic() - started
    names = files.names
    status = capture.status
    # After a failure the error says what the files keep; "wrote" is for a capture that ended well.
    written = f"; wrote {shown(', '.join(names))}" if names and status == ExitStatus.OK else ""
    if status != ExitStatus.OK:
        err.write(f"{PROG}: error: {shown(capture.reason)}; capture files closed\n")
    for warning in map_warnings([annotate]):
        err.write(f"{PROG}: warning: {shown(warning)}\n")
    watching = getattr(sink, "inner", sink)  # (-Y in front of --watch: live_display.FilteredSink)
    for line in getattr(watching, "unseen", list)():  # a watched address or code never heard, as a file says it
        err.write(f"{PROG}: {shown(line)}\n")
    hidden = stats.not_shown_text()
    err.write(f"{PROG}: {stats.summary(seconds)}{written}{'; ' + hidden if hidden else ''}\n")
    err.flush()
