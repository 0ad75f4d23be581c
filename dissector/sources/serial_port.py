"""The serial source: a port (or pyserial URL) opened for listening only, with typed settings.

Nothing is ever written to the port, and RTS is left deasserted: RS-485 adapters that steer their
driver with RTS would otherwise drive the bus.
"""
from __future__ import annotations

import errno
import os
from dataclasses import dataclass

import serial

from dissector.errors import ExitStatus, LiveError

try:
    import termios

    # pyserial lets termios.error (not an OSError) through, e.g. when a tty refuses a setting.
    TERMIOS_ERRORS: tuple[type[Exception], ...] = (termios.error,)
except ImportError:  # Windows: no termios, and no error marking
    termios = None  # type: ignore[assignment]
    TERMIOS_ERRORS = ()

READ_TIMEOUT = 0.010
PARITIES = {"N": serial.PARITY_NONE, "E": serial.PARITY_EVEN, "O": serial.PARITY_ODD}
PORT_ERRORS: tuple[type[BaseException], ...] = (serial.SerialException, ValueError, OSError, *TERMIOS_ERRORS)


@dataclass(frozen=True)
class PortSettings:
    port: str
    baud: int = 19200
    parity: str = "E"
    stopbits: float = 1
    bytesize: int = 8

    def text(self) -> str:
        """As a manual writes it: `19200 8E1`."""
        stopbits = int(self.stopbits) if self.stopbits == int(self.stopbits) else self.stopbits
        return f"{self.baud} {self.bytesize}{self.parity}{stopbits}"


def open_port(settings: PortSettings) -> serial.SerialBase:
    try:
        port = serial.serial_for_url(settings.port, do_not_open=True)
        custom = _custom_speed(port, settings.baud)
        port.baudrate = STANDARD_SPEED if custom else settings.baud
        port.parity = PARITIES[settings.parity]
        port.stopbits = settings.stopbits
        port.bytesize = settings.bytesize
        port.timeout = READ_TIMEOUT
        port.rts = False
        port.open()
        if custom:
            # A tty left at a custom speed (14400 baud by the run before) refuses to be opened at one again
            # (pyserial: termios "Invalid argument"); from a standard speed it takes it.
            port.baudrate = settings.baud
            port.reset_input_buffer()  # (what came at the standard speed, as open() drops what came before)
    except PORT_ERRORS as error:
        why = reason(error)
        if why == NOT_A_TTY and os.path.isfile(settings.port):
            # `--live capture.pcap`: a file given where a port belongs
            why = "a file, not a serial port (decode a capture file without --live)"
        raise LiveError(f"cannot open {settings.port}: {why}", ExitStatus.BAD_INPUT) from None
    return port


STANDARD_SPEED = 38400  # a speed every POSIX tty knows (B38400), opened at before a custom one


def _custom_speed(port: serial.SerialBase, baud: int) -> bool:
    """Whether a POSIX port takes `baud` as a custom speed (no termios B constant: 14400, 28800, 76800)."""
    standard = getattr(port, "BAUDRATE_CONSTANTS", None)  # (pyserial's POSIX ports; not URLs nor Windows)
    return standard is not None and termios is not None and baud not in standard and not hasattr(
        termios, f"B{baud}")


NOT_A_TTY = "not a serial port (it takes no line settings)"


def reason(error: BaseException) -> str:
    """The system's words for a failure, without pyserial's nested "[Errno n]" repeats."""
    for candidate in (error.__context__, error):
        if isinstance(candidate, OSError) and candidate.strerror and "[Errno" not in candidate.strerror:
            return candidate.strerror
        # pyserial's "Could not configure port: (25, 'Inappropriate ioctl for device')": a file or a
        # device that is no terminal (/dev/null), where a port was meant
        if isinstance(candidate, TERMIOS_ERRORS) and candidate.args[:1] == (errno.ENOTTY,):
            return NOT_A_TTY
    if isinstance(error, TERMIOS_ERRORS) and len(error.args) == 2:
        return f"the port refused the settings: {error.args[1]}"
    return str(error)
