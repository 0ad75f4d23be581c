"""The live-capture options, apart from live.py so that parsing a command line does not load pyserial."""
from __future__ import annotations

import argparse

from dissector.framing.linespeed import baud_rate  # --baud's range, for files and live alike

PARITY_CHOICES = ("E", "N", "O")
BYTESIZE_GIVEN = "bytesize_given"  # set by --bytesize: --detect then tries that size only


def mode_bytesize(mode: str | None) -> int:
    """The data bits of a mode's character (Serial Line Guide 2.5: RTU 8, ASCII 7)."""
    return 7 if mode == "ascii" else 8


def live_mode(args: argparse.Namespace) -> str | None:
    """The framing of a live capture: --mode, else Modbus ASCII when the port is set to 7 data bits (RTU's
    binary needs 8: Serial Line Guide 2.5; --detect's framings() holds the same rule), else None (RTU, which
    a live stream cannot be sniffed for before it starts: app/detect.py AsciiHeard hints instead)."""
    mode = getattr(args, "mode", None)
    if mode is None and getattr(args, BYTESIZE_GIVEN, False) and args.bytesize == mode_bytesize("ascii"):
        return "ascii"
    return mode


class GivenBytesize(argparse.Action):
    """Stores --bytesize and notes that it was given (its default, 8, is RTU's: --detect tries
    ASCII at 7 data bits unless told otherwise)."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: object, option_string: str | None = None) -> None:
        setattr(namespace, self.dest, values)
        setattr(namespace, BYTESIZE_GIVEN, True)


def positive_int(text: str) -> int:
    # A baud rate of 0 divided by zero in the timing checks of a timed file (a traceback).
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value <= 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be more than 0")
    return value


def positive_seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not 0 < value < float("inf"):  # also refuses nan
        raise argparse.ArgumentTypeError(f"{text!r} must be a number of seconds more than 0")
    return value


class Autostop(argparse.Action):
    """tshark's and dumpcap's `-a duration:S` and `-a packets:N`: what --duration and -c say (given twice, the
    later wins, as with those). Their other conditions (filesize, files) are refused by name, never ignored."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace,
                 values: object, option_string: str | None = None) -> None:
        name, _, value = str(values).partition(":")
        try:
            if name == "duration":
                namespace.duration = positive_seconds(value)
            elif name == "packets":
                namespace.count = positive_int(value)
            else:
                raise argparse.ArgumentTypeError(f"{str(values)!r}: stops are duration:S and packets:N "
                                                 "(a -w ring buffer's size is -b filesize:KB,files:N)")
        except argparse.ArgumentTypeError as error:
            raise argparse.ArgumentError(self, str(error)) from None


# --timeout's range: the texts say it in whole milliseconds (`the 1000 ms timeout`), as the plugin's timeout
# preference takes it; an answer a day after its request answers nothing (1e300 made --stats' margin column
# a 300-digit number, 1e-300 said "the 0 ms timeout").
TIMEOUT_RANGE = (0.001, 86_400.0)


def timeout_seconds(text: str) -> float:
    value = positive_seconds(text)
    low, high = TIMEOUT_RANGE
    if not low <= value <= high:
        raise argparse.ArgumentTypeError(f"{text!r} is outside 0.001..86400 seconds (1 ms to a day)")
    return value


def add_live_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("live capture")
    group.add_argument(
        "--live",
        metavar="PORT",
        help="listen on a serial port or pyserial URL (/dev/ttyUSB0, COM3, socket://host:port, "
        "rfc2217://host:port); never writes to it",
    )
    group.add_argument("--baud", type=baud_rate, default=19200, help="baud rate (50..4,000,000, default 19200)")
    group.add_argument(
        "--parity", type=str.upper, choices=PARITY_CHOICES, default="E",
        help="parity: E (default, the Modbus default), N or O",
    )
    group.add_argument("--stopbits", type=float, choices=[1, 1.5, 2], default=1, help="default 1")
    group.add_argument(
        "--bytesize", type=int, choices=[5, 6, 7, 8], default=mode_bytesize("rtu"), action=GivenBytesize,
        help="data bits, default 8, 7 with --mode ascii (--detect tries 8 for RTU and 7 for ASCII unless given)",
    )
    group.add_argument("--raw", metavar="FILE", help="also write every byte heard to FILE, as heard")
    group.add_argument("--duration", type=positive_seconds, metavar="SECONDS", help="stop after SECONDS")
    group.add_argument("-a", action=Autostop, metavar="duration:S|packets:N",
                       help="stop live as tshark -a does: after S seconds (--duration), after N items (-c)")
    group.add_argument(
        "-c", "--count", type=positive_int, metavar="N",
        help="stop after N items, frames and noise runs alike, each a packet (live, or shown from files: after -Y, where tshark -c counts the packets read)",
    )
    group.add_argument(
        "--detect", nargs="?", type=positive_seconds, const=2.0, metavar="SECONDS",
        help="find the framing, baud rate and parity: listen SECONDS (default 2) at each of "
        "9600..115200 x 8E1/8N1/8O1 (RTU) and 7E1/7N2/7O1 (ASCII; --mode and --bytesize narrow "
        "this) and print the command line to use",
    )
