"""--detect: find a bus's baud rate and parity by listening at each usual setting.

At the wrong baud rate a UART samples bits at the wrong instants and delivers garbage bytes, in
which a CRC-valid frame of the right length is a one-in-65536 accident. So each setting is scored
by what the framer finds: the bytes in CRC-valid frames that hold no byte the UART flagged.

Parity is the subtle part. A UART set to 8N1 listening to 8E1 delivers the same data bytes (it
takes the parity bit for the stop bit), and Linux delivers bytes with parity errors unchanged
unless asked otherwise (pyserial clears INPCK). On POSIX ports we therefore ask the kernel to mark
bytes received with a parity or framing error (INPCK with PARMRK: `FF 00 byte`, and a data byte FF
arrives as `FF FF`), and a frame holding a marked byte does not count. Ports that cannot mark
errors (socket://, rfc2217://, Windows) hear the same bytes at the three parities of the right baud
rate: any of them that heard at least half as much as the best is taken as equally likely, the
first of PARITY_ORDER wins (E, the Modbus default), and the report says so.
"""
from __future__ import annotations

import argparse
import time
from dataclasses import dataclass
from typing import Protocol, TextIO

import serial

from dissector.sources.serial_port import PARITIES, TERMIOS_ERRORS, PortSettings, open_port, termios
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame

BAUDS = (9600, 19200, 38400, 57600, 115200)
PARITY_ORDER = ("E", "N", "O")  # also the order of preference when scores tie
PROG = "vw3-decode"


@dataclass(frozen=True)
class Heard:
    """What a UART delivered at one setting; `errors` are offsets of bytes it flagged."""

    data: bytes
    errors: frozenset[int] = frozenset()
    marked: bool = False  # True when the source can flag errors at all
    failure: str | None = None  # the setting could not be applied


class Listener(Protocol):
    def listen(self, baud: int, parity: str, seconds: float) -> Heard: ...


@dataclass
class Score:
    baud: int
    parity: str
    heard: int = 0
    frames: int = 0
    frame_bytes: int = 0
    flagged_frames: int = 0  # CRC-valid frames holding a byte flagged with an error
    errors: int = 0
    marked: bool = False
    failure: str | None = None

    @property
    def setting(self) -> str:
        return f"{self.baud} 8{self.parity}1"

    def describe(self) -> str:
        if self.failure is not None:
            return f"{self.setting}: could not be set ({self.failure})"
        errors = f"{self.errors} bytes flagged" if self.marked else "errors not reported by this port"
        flagged = f", {self.flagged_frames} more with flagged bytes" if self.flagged_frames else ""
        return (
            f"{self.setting}: {self.frames} CRC-valid frames ({self.frame_bytes} bytes){flagged}, "
            f"{self.heard} bytes heard, {errors}"
        )


def score(baud: int, parity: str, heard: Heard) -> Score:
    result = Score(baud, parity, len(heard.data), errors=len(heard.errors), marked=heard.marked,
                   failure=heard.failure)
    framer = RtuFramer()
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


def _alike(best: Score, other: Score) -> bool:
    """Whether `other` (a parity of best's baud rate) explains the traffic as well as `best`."""
    return (
        other.baud == best.baud
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
    order = {(s.baud, s.parity): i for i, s in enumerate(scores)}

    def key(s: Score) -> tuple[int, int, int, int]:
        return (-s.frame_bytes, s.errors, PARITY_ORDER.index(s.parity), order[(s.baud, s.parity)])

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
    parities: tuple[str, ...] = PARITY_ORDER,
) -> list[Score]:
    """Every setting's score, best first; the best has frame_bytes > 0 if anything was found."""
    scores = []
    for baud in bauds:
        for parity in parities:
            scores.append(score(baud, parity, listener.listen(baud, parity, seconds)))
    return rank(scores)


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

    def listen(self, baud: int, parity: str, seconds: float) -> Heard:
        port = self.port
        try:
            # pyserial reconfigures the tty once per attribute. A tty that cannot do parity (a
            # pty) refuses a change of parity alone, so the parity goes first and the baud rate
            # setter, which always reconfigures everything, gives the verdict.
            try:
                port.parity = PARITIES[parity]
            except (serial.SerialException, ValueError, OSError, *TERMIOS_ERRORS):
                pass
            port.baudrate = baud
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
    return f"{PROG} --live {port} --baud {best.baud} --parity {best.parity}"


def run_detect(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Listen args.detect seconds per setting on args.live; print the command line to use."""
    from dissector.app.options import shown  # typed names are data: control characters escaped
    from dissector.errors import ExitStatus, LiveError

    try:
        port = open_port(PortSettings(args.live, args.baud, args.parity, args.stopbits, args.bytesize))
    except LiveError as error:
        err.write(f"{PROG}: {shown(error)}\n")
        return error.status
    seconds = float(args.detect)
    err.write(
        f"{PROG}: listening on {shown(args.live)} for {seconds:g} s at each of {len(BAUDS) * 3} settings\n"
    )
    err.flush()
    try:
        scores = detect(SerialListener(port), seconds)
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
        err.write(
            f"{PROG}: no CRC-valid frame heard at any setting (is there traffic? are A and B "
            "swapped?)\n"
        )
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
