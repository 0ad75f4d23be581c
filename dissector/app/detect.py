"""--detect: find a bus's framing, baud rate and parity by listening at each usual setting.

At the wrong baud rate a UART samples bits at the wrong instants and delivers garbage bytes, in
which a CRC-valid RTU frame of the right length is a one-in-65536 accident, and a Modbus ASCII frame
(':', hex pairs, CR LF, its LRC good) rarer still. So each setting is scored by what the framer of
each mode tried there finds: the bytes in frames with a good check that hold no byte the UART
flagged. RTU is sent with 8 data bits; ASCII usually with 7 (7E1, its default, 7O1 or 7N2), so
without --mode both are tried, each at its own settings; --bytesize, when given, is the only
size tried (ASCII with 8 data bits: at 8E1, 8N1 and 8O1, scored on the same bytes as RTU).

Parity is the subtle part. A UART set to 8N1 listening to 8E1 delivers the same data bytes (it
takes the parity bit for the stop bit), and Linux delivers bytes with parity errors unchanged
unless asked otherwise (pyserial clears INPCK). On POSIX ports we therefore ask the kernel to mark
bytes received with a parity or framing error (INPCK with PARMRK: `FF 00 byte`, and a data byte FF
arrives as `FF FF`), and a frame holding a marked byte does not count. Ports that cannot mark
errors (socket://, rfc2217://, Windows) or cannot set parity and data bits at all (a pty) hear the
same bytes at the three parities of the right baud rate: any of them that heard at least half as
much as the best is taken as equally likely, the first of PARITY_ORDER wins (E, the Modbus
default), and the report says so.

When nothing is found, the bytes heard are looked at once more for frames of a framing that was not
scored there (RTU frames under --mode ascii, ASCII frames under --mode rtu or at 8 data bits, a 7-bit
line's ASCII heard by an 8-bit UART): the report then names the options that find them instead of
blaming the wiring.
"""
from __future__ import annotations

import argparse
import time
from dataclasses import dataclass
from typing import Protocol, TextIO

import serial

from dissector.app.live_options import mode_bytesize
from dissector.sources.serial_port import PARITIES, TERMIOS_ERRORS, PortSettings, open_port, termios
from dissector.framing.ascii import AsciiFramer
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame
from dissector.protocol.ascii import MODE_REACH, MODE_SAMPLE, holds_frame, rtu_pair_end, sample_mode

BAUDS = (9600, 19200, 38400, 57600, 115200)
PARITY_ORDER = ("E", "N", "O")  # also the order of preference when scores tie
# The usual (parity, stop bits) of each data size: Modbus asks for 2 stop bits without parity, which
# RTU buses seldom follow (8N1) and ASCII buses do (7N2). A receiver's stop bits barely matter: it
# checks the first one only.
FORMATS = {8: (("E", 1), ("N", 1), ("O", 1)), 7: (("E", 1), ("N", 2), ("O", 1))}
PROG = "vw3-decode"


@dataclass(frozen=True)
class Setting:
    """One UART setting --detect listens at."""

    baud: int
    parity: str
    bytesize: int = 8
    stopbits: int = 1

    def __str__(self) -> str:
        return f"{self.baud} {self.bytesize}{self.parity}{self.stopbits}"


class DetectError(ValueError):
    """Options --detect cannot honour (a data size no Modbus mode is sent with)."""


def framings(mode: str | None, bytesize: int | None) -> tuple[tuple[str, int], ...]:
    """The (mode, data bits) pairs to score: the mode given or both, at the size given or their own."""
    modes = (mode,) if mode else ("rtu", "ascii")
    if bytesize is not None and bytesize not in FORMATS:
        raise DetectError(
            f"--bytesize {bytesize}: Modbus is sent with 8 data bits (RTU, or ASCII) or 7 (ASCII)")
    if bytesize == 7 and mode == "rtu":
        raise DetectError("--bytesize 7: Modbus RTU is sent with 8 data bits")
    if bytesize == 7:
        modes = ("ascii",)
    return tuple((each, bytesize or mode_bytesize(each)) for each in modes)


def settings(bauds: tuple[int, ...], sizes: tuple[int, ...]) -> list[Setting]:
    """Every setting to listen at. The baud rate changes at every step: a pty (and the tests' buses)
    refuses a change of parity or data bits alone, and takes one that comes with a new baud rate."""
    return [
        Setting(baud, parity, size, stop)
        for size in sizes
        for parity, stop in FORMATS[size]
        for baud in bauds
    ]


@dataclass(frozen=True)
class Heard:
    """What a UART delivered at one setting; `errors` are offsets of bytes it flagged."""

    data: bytes
    errors: frozenset[int] = frozenset()
    marked: bool = False  # True when the source can flag errors at all
    failure: str | None = None  # the setting could not be applied


class Listener(Protocol):
    def listen(self, setting: Setting, seconds: float) -> Heard: ...


# What frames with a good check are called in the report, by mode.
FRAME_NOUNS = {"rtu": "CRC-valid frames", "ascii": "ASCII frames with a good LRC"}


@dataclass
class Score:
    where: Setting
    mode: str = "rtu"
    heard: int = 0
    frames: int = 0
    frame_bytes: int = 0
    flagged_frames: int = 0  # frames with a good check holding a byte flagged with an error
    errors: int = 0
    marked: bool = False
    failure: str | None = None
    # (mode, data bits) of frames the bytes hold that were not scored at this setting
    heard_as: tuple[str, int] | None = None

    @property
    def baud(self) -> int:
        return self.where.baud

    @property
    def parity(self) -> str:
        return self.where.parity

    @property
    def setting(self) -> str:
        return str(self.where)

    def describe(self) -> str:
        if self.failure is not None:
            return f"{self.setting}: could not be set ({self.failure})"
        errors = f"{self.errors} bytes flagged" if self.marked else "errors not reported by this port"
        flagged = f", {self.flagged_frames} more with flagged bytes" if self.flagged_frames else ""
        return (
            f"{self.setting}: {self.frames} {FRAME_NOUNS[self.mode]} ({self.frame_bytes} bytes){flagged}, "
            f"{self.heard} bytes heard, {errors}"
        )


def _framer(mode: str) -> AsciiFramer | RtuFramer:
    return AsciiFramer() if mode == "ascii" else RtuFramer()


def score(where: Setting, heard: Heard, mode: str = "rtu") -> Score:
    result = Score(where, mode, len(heard.data), errors=len(heard.errors), marked=heard.marked,
                   failure=heard.failure)
    framer = _framer(mode)
    items = framer.feed(Chunk(heard.data)) + framer.finish()
    for item in items:
        if not isinstance(item, Frame) or not item.crc_ok:
            continue
        if any(offset in heard.errors for offset in range(item.offset, item.offset + item.length)):
            result.flagged_frames += 1
            continue
        result.frames += 1
        result.frame_bytes += item.length
    return result


def heard_as(where: Setting, heard: Heard, scored: set[tuple[str, int]]) -> tuple[str, int] | None:
    """The framing whose frames the bytes hold, of those not scored at `where`; None if none.

    ASCII as heard; or, heard at 8 data bits, as a UART at 7 would have heard it (a 7E1, 7O1 or 7N2
    character is as long as an 8N1 one: an 8-bit UART delivers its parity or first stop bit as bit
    7); or RTU (an ASCII-only listen on a port that ignores data bits: a pty, a gateway). A byte
    the UART flagged is in no frame, as in score()."""
    data = bytes(0 if i in heard.errors else byte for i, byte in enumerate(heard.data))
    if ("ascii", where.bytesize) not in scored and holds_frame(data):
        return ("ascii", where.bytesize)
    if where.bytesize == 8 and ("ascii", 7) not in scored and holds_frame(bytes(b & 0x7F for b in data)):
        return ("ascii", 7)
    if ("rtu", 8) not in scored and score(where, heard).frames:
        return ("rtu", 8)
    return None


def _alike(best: Score, other: Score) -> bool:
    """Whether `other` (a parity of best's baud rate, mode and data size) explains the traffic as
    well as `best`."""
    return (
        other.baud == best.baud
        and other.mode == best.mode
        and other.where.bytesize == best.where.bytesize
        and 2 * other.frame_bytes >= best.frame_bytes
        and (not other.marked or other.errors <= best.errors)
    )


def rank(scores: list[Score]) -> list[Score]:
    """Best first: most bytes in clean frames, then fewest errors, then the order of preference.

    Parities of one baud rate often deliver the same bytes and differ only by which stretch of
    traffic each happened to hear. Without error marks (or with no more errors than the best), a
    parity of the best baud rate that heard at least half as much is as likely, and the preferred
    one (E first) goes to the front.
    """
    order = {id(s): i for i, s in enumerate(scores)}

    def key(s: Score) -> tuple[int, int, int, int]:
        return (-s.frame_bytes, s.errors, PARITY_ORDER.index(s.parity), order[id(s)])

    ranked = sorted(scores, key=key)
    best = ranked[0]
    if best.frame_bytes:
        preferred = min(
            (s for s in ranked if _alike(best, s)), key=lambda s: PARITY_ORDER.index(s.parity)
        )
        ranked.remove(preferred)
        ranked.insert(0, preferred)
    return ranked


def parity_alike(scores: list[Score]) -> list[Score]:
    """The other parities that rank() judged as likely as the chosen one, in order of preference."""
    best = scores[0]
    if not best.frame_bytes:
        return []
    most = max(scores, key=lambda s: (s.frame_bytes, -s.errors))
    alike = [s for s in scores[1:] if _alike(most, s)]
    return sorted(alike, key=lambda s: PARITY_ORDER.index(s.parity))


def detect(
    listener: Listener,
    seconds: float,
    bauds: tuple[int, ...] = BAUDS,
    tried: tuple[tuple[str, int], ...] = (("rtu", 8),),
) -> list[Score]:
    """Every (setting, mode)'s score, best first; the best has frame_bytes > 0 if anything was found.

    `tried` are the (mode, data bits) pairs to score (framings()); modes of one data size are scored
    on the same bytes. When nothing is found, each score says what else its bytes hold (heard_as).
    """
    sizes = tuple(dict.fromkeys(size for _, size in tried))
    scores = []
    heard: dict[int, tuple[Heard, set[tuple[str, int]]]] = {}
    for where in settings(bauds, sizes):
        result = listener.listen(where, seconds)
        scored = {(mode, size) for mode, size in tried if size == where.bytesize}
        modes = sorted(scored, key=tried.index)
        for mode, _ in modes[:1] if result.failure is not None else modes:  # one line for a failure
            scores.append(score(where, result, mode))
            heard[id(scores[-1])] = (result, scored)
    ranked = rank(scores)
    if not ranked[0].frame_bytes:
        for entry in ranked:
            result, scored = heard[id(entry)]
            if entry.failure is None:
                entry.heard_as = heard_as(entry.where, result, scored)
    return ranked


def unmark(data: bytes) -> tuple[bytes, frozenset[int]]:
    """Undo PARMRK marking: `FF FF` is a data FF, `FF 00 b` is byte b received with an error."""
    out = bytearray()
    errors = set()
    i, n = 0, len(data)
    while i < n:
        byte = data[i]
        if byte != 0xFF:
            out.append(byte)
            i += 1
        elif i + 1 < n and data[i + 1] == 0xFF:
            out.append(0xFF)
            i += 2
        elif i + 2 < n and data[i + 1] == 0x00:
            errors.add(len(out))
            out.append(data[i + 2])
            i += 3
        else:  # an escape cut by the end of the listening time
            break
    return bytes(out), frozenset(errors)


def _mark_errors(port: serial.SerialBase) -> bool:
    """Ask a POSIX tty to mark bytes with parity or framing errors; False where it cannot."""
    fd = getattr(port, "fd", None)
    if termios is None or not isinstance(fd, int):
        return False
    attributes = termios.tcgetattr(fd)
    attributes[0] = (attributes[0] | termios.INPCK | termios.PARMRK) & ~(termios.IGNPAR | termios.ISTRIP)
    termios.tcsetattr(fd, termios.TCSANOW, attributes)
    return True


@dataclass
class SerialListener:
    """Listens on an open pyserial port, reconfigured for each setting; never writes to it."""

    port: serial.SerialBase

    def listen(self, setting: Setting, seconds: float) -> Heard:
        port = self.port
        try:
            # pyserial reconfigures the tty once per attribute. A tty that cannot do parity or 7 data
            # bits (a pty) refuses a change of those alone, so they go first and the baud rate
            # setter, which always reconfigures everything, gives the verdict.
            for name, value in (("parity", PARITIES[setting.parity]), ("bytesize", setting.bytesize),
                                ("stopbits", setting.stopbits)):
                try:
                    setattr(port, name, value)
                except (serial.SerialException, ValueError, OSError, *TERMIOS_ERRORS):
                    pass
            port.baudrate = setting.baud
            marked = _mark_errors(port)
        except (serial.SerialException, ValueError, OSError, *TERMIOS_ERRORS) as error:
            return Heard(b"", failure=str(error))
        port.reset_input_buffer()  # bytes heard at the previous setting
        data = bytearray()
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            data += port.read(max(1, port.in_waiting))
        if marked:
            clean, errors = unmark(bytes(data))
            return Heard(clean, errors, True)
        return Heard(bytes(data))


def command_line(port: str, best: Score) -> str:
    """The vw3-decode --live line that captures at `best` (its defaults left out: RTU, the mode's data
    bits (8, 7 for ASCII), 1 stop bit)."""
    where = best.where
    mode = " --mode ascii" if best.mode == "ascii" else ""
    size = f" --bytesize {where.bytesize}" if where.bytesize != mode_bytesize(best.mode) else ""
    stop = f" --stopbits {where.stopbits}" if where.stopbits != 1 else ""
    return f"{PROG} --live {port}{mode} --baud {where.baud} --parity {where.parity}{size}{stop}"


# What detect() looked for, for the report when nothing was found.
_LOOKED_FOR = {
    ("rtu",): "CRC-valid frame",
    ("ascii",): "Modbus ASCII frame with a good LRC",
    ("rtu", "ascii"): "CRC-valid RTU frame or Modbus ASCII frame with a good LRC",
}
# The options that score what heard_as() found, and what it is called.
_FOUND = {
    ("ascii", 8): ("Modbus ASCII frames with a good LRC", "--mode ascii --bytesize 8"),
    ("ascii", 7): ("Modbus ASCII frames sent with 7 data bits", "--mode ascii"),
    ("rtu", 8): ("CRC-valid RTU frames", "--mode rtu"),
}


def nothing_found(scores: list[Score], detect_with: str = "detect with") -> str:
    """Why --detect found nothing: the bytes hold frames of a framing it did not score (the options
    that score it, after `detect_with`), or no frame at all (the wiring, or a silent bus)."""
    modes = tuple(mode for mode in ("rtu", "ascii") if any(s.mode == mode for s in scores))
    looked_for = _LOOKED_FOR[modes]
    other = next((s for s in scores if s.heard_as is not None), None)
    if other is not None and other.heard_as is not None:
        what, options = _FOUND[other.heard_as]
        return (f"no {looked_for} heard at any setting, but the bytes heard at {other.setting} hold "
                f"{what} ({detect_with} {options})")
    return f"no {looked_for} heard at any setting (is there traffic? are A and B swapped?)"


def run_detect(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Listen args.detect seconds per setting on args.live; print the command line to use."""
    from dissector.app.options import shown  # typed names are data: control characters escaped
    from dissector.errors import ExitStatus, LiveError

    try:
        tried = framings(getattr(args, "mode", None), given_bytesize(args))
    except DetectError as error:
        err.write(f"{PROG}: --detect: {error}\n")
        return ExitStatus.BAD_INPUT
    try:
        port = open_port(PortSettings(args.live, args.baud, args.parity, args.stopbits, args.bytesize))
    except LiveError as error:
        err.write(f"{PROG}: {shown(error)}\n")
        return error.status
    seconds = float(args.detect)
    count = len(settings(BAUDS, tuple(dict.fromkeys(size for _, size in tried))))
    err.write(f"{PROG}: listening on {shown(args.live)} for {seconds:g} s at each of {count} settings\n")
    err.flush()
    try:
        scores = detect(SerialListener(port), seconds, tried=tried)
    except (serial.SerialException, OSError) as error:
        err.write(f"{PROG}: error: {shown(args.live)} went away ({shown(error)})\n")
        return ExitStatus.ERROR
    except KeyboardInterrupt:
        err.write(f"{PROG}: detection interrupted\n")
        return ExitStatus.ERROR
    finally:
        port.close()
    for entry in scores:
        err.write(f"  {entry.describe()}\n")
    best = scores[0]
    if best.frame_bytes == 0:
        err.write(f"{PROG}: {nothing_found(scores)}\n")
        return ExitStatus.ERROR
    alike = parity_alike(scores)
    if alike:
        others = ", ".join(s.setting for s in alike)
        why = (
            "this port does not report parity errors"
            if not best.marked
            else "no more parity or framing errors were flagged there"
        )
        err.write(
            f"{PROG}: {others} heard frames as well as {best.setting} ({why}): "
            f"{best.parity} was chosen as the Modbus default\n"
        )
    out.write(command_line(args.live, best) + "\n")
    out.flush()
    return 0


def given_bytesize(args: argparse.Namespace) -> int | None:
    """--bytesize when the user gave it; None when it is the default (each mode's own is tried)."""
    from dissector.app.live_options import BYTESIZE_GIVEN

    return args.bytesize if getattr(args, BYTESIZE_GIVEN, False) else None


# The sizes of the sample AsciiHeard judges at: an answer of sample_mode's holds for any longer sample, so a
# few looks, the last at MODE_REACH bytes, are enough.
HINT_SIZES = (MODE_SAMPLE, 2 * MODE_SAMPLE, 4 * MODE_SAMPLE, 8 * MODE_SAMPLE, MODE_REACH)


def ascii_heard(sample: bytes) -> tuple[str, int] | None:
    """The Modbus ASCII framing whose frames the first bytes an RTU capture heard hold, or None: ASCII as
    heard (a file of these bytes is decoded as ASCII: sample_mode), or a 7-bit line heard by an 8-bit UART
    (heard_as) where no two RTU frames came."""
    if holds_frame(sample) and sample_mode(sample, True) == "ascii":
        return ("ascii", 8)
    if holds_frame(bytes(byte & 0x7F for byte in sample)) and rtu_pair_end(sample) is None:
        return ("ascii", 7)
    return None


class AsciiHeard:
    """--live without --mode at 8 data bits frames RTU (live_options.live_mode). When the first bytes heard
    hold Modbus ASCII (ascii_heard), one line on `err` names the options that decode them, as --detect's
    report does (_FOUND); the capture goes on as RTU (its lines and files are written as they come). Fed the
    bytes the display takes in (app/live.py display_once), judged as they reach each of HINT_SIZES and at
    the end."""

    def __init__(self, err: TextIO) -> None:
        self.err = err
        self.sample = b""
        self.done = False

    def __call__(self, data: bytes, closed: bool = False) -> None:
        if self.done:
            return
        before = len(self.sample)
        self.sample += data[: MODE_REACH - before]
        if not closed and not any(before < size <= len(self.sample) for size in HINT_SIZES):
            return
        self.done = closed or len(self.sample) >= MODE_REACH
        found = ascii_heard(self.sample)
        if found is not None:
            what, options = _FOUND[found]
            self.err.write(f"{PROG}: the bytes heard hold {what}, framed here as RTU: "
                           f"capture with {options}\n")
            self.err.flush()
            self.done = True
