"""`vw3-extcap --capture`: the live capture of `vw3-decode --live -w`, into Wireshark's fifo.

The engine is live_capture.py as it is: its capture thread reads the port, frames, and writes each
frame or noise run as one pcapng record (flushed) before anything else; here nothing is decoded
(Wireshark's plugin does it), so the hand-off to a display takes nothing (limit 0).

Stopping. Wireshark sends SIGTERM (Windows: TerminateProcess); the capture thread then closes what the
framer holds and the capture ends, exit 0. Wireshark may also just close the fifo (dumpcap ended: -c,
-a, a crash): a write then fails with EPIPE, and on a silent bus the fifo's write end polls POLLERR,
checked at every tick of the capture loop (10 ms), as is the parent process: if the Wireshark that
started us has gone (its pid is no longer our parent's), so do we. None of these is an error.
"""
from __future__ import annotations

import argparse
import errno
import io
import os
import select
import stat
import time
from collections.abc import Callable
from typing import BinaryIO, TextIO

from dissector.app.live import StopFlag, interface_description, live_framer
from dissector.app.live_capture import CaptureFiles, CaptureThread, Handoff, long_silence, silence_threshold
from dissector.errors import ExitStatus, LiveError
from dissector.framing.timing import LineTiming
from dissector.render.capturefile import STDOUT, CaptureOutput
from dissector.sources.serial_port import PortSettings, open_port

WAIT = 0.05  # how often the main thread looks at the stop flag
FIFO_PATIENCE = 30.0  # Wireshark (dumpcap) opens the fifo at once; this bounds a wait for nobody
RELEASE_PATIENCE = 5.0  # the same after an error, when Wireshark may be gone already


def open_fifo(path: str, stopped: Callable[[], bool], patience: float = FIFO_PATIENCE) -> BinaryIO | None:
    """The fifo opened for writing once its reader (dumpcap) has opened it; None if stopped first.

    Opened without blocking, then made blocking: a plain open() would wait, deaf to SIGTERM, for a
    reader that may never come; a blocking stream writes each record whole."""
    if not is_fifo(path):
        # Windows (Wireshark's named pipe waits for us), or a file given by hand.
        return open(path, "wb", buffering=0)  # noqa: SIM115
    deadline = time.monotonic() + patience
    while True:
        try:
            fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
        except OSError as error:
            if error.errno != errno.ENXIO:  # ENXIO: no reader yet
                raise
            if stopped() or time.monotonic() > deadline:
                return None
            time.sleep(0.01)
            continue
        os.set_blocking(fd, True)
        return io.FileIO(fd, "wb", closefd=True)


def is_fifo(path: str) -> bool:
    """A POSIX fifo (Windows reports its named pipes as fifos too, but they open as files)."""
    try:
        return os.name == "posix" and stat.S_ISFIFO(os.stat(path).st_mode)
    except OSError:
        return False


class FifoOutput(CaptureOutput):
    """The -w output of live_capture.py, on the fifo's stream, noting when the reader has gone."""

    def __init__(self, stream: BinaryIO, path: str, interface: tuple[str, str]) -> None:
        self.fifo = stream
        self.fifo_path = path
        self.reader_gone = False
        self._parent = os.getppid()
        self._poll = None
        if hasattr(select, "poll") and stat.S_ISFIFO(os.fstat(stream.fileno()).st_mode):
            self._poll = select.poll()
            self._poll.register(stream.fileno(), 0)  # POLLERR and POLLHUP are always reported
        super().__init__(STDOUT, "pcapng", None, flush=True, stdout=stream, interface=interface)

    @property
    def name(self) -> str:
        return self.fifo_path

    def _gone(self) -> BrokenPipeError:
        self.reader_gone = True
        return BrokenPipeError(errno.EPIPE, "Wireshark closed the fifo")

    def tick(self, now: float | None = None) -> None:
        if self._poll is not None and self._poll.poll(0):
            raise self._gone()
        if os.name == "posix" and os.getppid() != self._parent:
            raise self._gone()
        super().tick(now)

    def write(self, data: bytes, timestamp: float | None = None, comment: str | None = None) -> None:
        try:
            super().write(data, timestamp, comment)
        except BrokenPipeError:
            self.reader_gone = True
            raise

    def close(self) -> None:
        try:
            super().close()
        except BrokenPipeError:
            self.reader_gone = True
        finally:
            try:
                self.fifo.close()
            except OSError:
                pass


class Stopped(Exception):
    """SIGTERM arrived before the capture started."""


def detected(settings: PortSettings, seconds: float, stop: StopFlag) -> tuple[PortSettings, str]:
    """The settings and framing (rtu, ascii) --detect finds on the port (vw3-decode --detect's
    scoring). Both framings at their own data sizes: the dialog says its settings are then ignored."""
    from dissector.app.detect import Heard, Setting, SerialListener, detect, framings, nothing_found

    port = open_port(settings)

    class Listener(SerialListener):
        def listen(self, setting: Setting, seconds: float) -> Heard:
            if stop.signal is not None:
                raise Stopped
            return super().listen(setting, seconds)

    try:
        scores = detect(Listener(port), seconds, tried=framings(None, None))
    except OSError as error:
        raise LiveError(f"{settings.port} went away during --detect ({error})", ExitStatus.ERROR) from None
    finally:
        port.close()
    best = scores[0]
    if best.frame_bytes == 0:
        # The dialog's framing and data bits are ignored under --detect: vw3-decode's options are named.
        advice = f"vw3-decode --live {settings.port} --detect"
        raise LiveError(f"--detect on {settings.port}: {nothing_found(scores, advice)}", ExitStatus.ERROR)
    where = best.where
    return PortSettings(settings.port, where.baud, where.parity, where.stopbits, where.bytesize), best.mode


def description(args: argparse.Namespace, settings: PortSettings) -> str:
    """vw3-decode --live -w's interface description, after the user's, and how the settings came."""
    text = interface_description(settings) + (", found by --detect" if args.detect else "")
    return f"{args.description.strip()}: {text}" if args.description.strip() else text


def capture(args: argparse.Namespace, port_name: str, err: TextIO, prog: str) -> int:
    """Capture from `port_name` into args.fifo until Wireshark stops us; exit status 0, or one line
    on err."""
    with StopFlag() as stop:
        output: FifoOutput | None = None
        try:
            settings = PortSettings(port_name, args.baud, args.parity, args.stopbits, args.bytesize)
            mode = args.mode
            if args.detect:
                settings, mode = detected(settings, args.detect_seconds, stop)
            port = open_port(settings)
        except Stopped:
            return ExitStatus.OK  # Wireshark is stopping: nobody is left to read the fifo
        except LiveError as error:
            err.write(f"{prog}: {error}\n")
            err.flush()
            return release(args.fifo, error.status, lambda: stop.signal is not None)
        try:
            stream = open_fifo(args.fifo, lambda: stop.signal is not None)
            if stream is None:
                return ExitStatus.OK  # stopped, or nobody came to read
            output = FifoOutput(stream, args.fifo, (settings.port, description(args, settings)))
            rtu = None if mode == "ascii" else LineTiming(settings.baud)  # (CaptureFiles._records)
            thread = CaptureThread(port, live_framer(mode, settings.baud), CaptureFiles(output, None, rtu),
                                   Handoff(limit=0), silence_threshold(settings.baud),
                                   silence_long=long_silence(settings.baud), port_name=settings.port,
                                   closing_record=False)
            thread.start()
            while not thread.done.wait(WAIT):
                if stop.signal is not None:
                    thread.stop.set()
            if thread.status != ExitStatus.OK and not output.reader_gone:
                # Said before the fifo closes: tshark takes its end as the capture's and may be gone
                # before a line written after it.
                err.write(f"{prog}: error: {thread.reason}\n")
                err.flush()
        except BrokenPipeError:
            return ExitStatus.OK  # the reader went before the header was written
        except OSError as error:
            err.write(f"{prog}: cannot write {args.fifo}: {error.strerror or error}\n")
            return ExitStatus.ERROR
        finally:
            if output is not None:
                output.close()
            port.close()
    return ExitStatus.OK if output.reader_gone else thread.status


def release(fifo: str | None, status: int, stopped: Callable[[], bool] = lambda: False) -> int:
    """After an error before the capture starts: open and close the fifo, so that Wireshark, waiting
    for the capture, reads its end and shows our error line instead of waiting on. dumpcap opens it
    as we start; a Wireshark that has stopped meanwhile is not waited for long."""
    if fifo and is_fifo(fifo):
        try:
            stream = open_fifo(fifo, stopped, patience=RELEASE_PATIENCE)
        except OSError:
            return status
        if stream is not None:
            stream.close()
    return status
