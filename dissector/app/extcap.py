"""`vw3-extcap`: the serial tap as a Wireshark capture interface (Wireshark's extcap protocol).

Wireshark runs every program of its extcap folders and asks, in turn:

    --extcap-interfaces [--extcap-version=4.0]     which interfaces (one per serial port, plus socket://)
    --extcap-interface I --extcap-dlts             their link type (147, USER0: map it to vw3)
    --extcap-interface I --extcap-config           the options of its dialog (port, baud, parity, ...)
    --extcap-interface I --extcap-capture-filter F whether a capture filter is valid (printed text: no)
    --extcap-interface I --capture --fifo F ...    capture: pcapng into the fifo until told to stop

The capture is `vw3-decode --live -w` (dissector/app/live_capture.py) with the fifo as its output:
one pcapng record per frame or noise run, written and flushed as heard, same time stamps, same noise
comments. Nothing is decoded here: the Lua plugin decodes in Wireshark. Wireshark stops a capture
with SIGTERM, or by closing the fifo; both end the capture cleanly (extcap_capture.py).

Whatever an extcap writes on standard error during a capture, Wireshark shows as an error, so this
program writes there only to fail: one line, then the fifo is released so that Wireshark reports it.
"""
from __future__ import annotations

import argparse
import os
import re
import sys
from collections.abc import Iterable
from dataclasses import dataclass
from typing import TextIO

from dissector import __version__
from dissector.app.live_options import PARITY_CHOICES, positive_seconds
from dissector.framing.linespeed import baud_rate  # the range vw3-decode --baud takes
from dissector.errors import ExitStatus, LiveError, UsageError

PROG = "vw3-extcap"
PREFIX = "vw3-"
SOCKET = "vw3-socket"  # RTU over TCP gateways (socket://host:port), or any pyserial URL
LINKTYPE = 147
BAUDS = (1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200)
_UNSAFE_NAME = re.compile(r"[^A-Za-z0-9._-]")
# The extcap grammar is `key {name=value}...`: braces, and line ends, cannot be in a value.
_UNSAFE_TEXT = re.compile(r"[{}\x00-\x1f\x7f]")


class Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{message} (see {PROG} --help)")


@dataclass(frozen=True)
class Interface:
    name: str  # what Wireshark calls it (-i vw3-ttyUSB0); safe in file names and preference names
    port: str  # the pyserial port or URL it opens ("" for the socket interface: --port gives it)
    display: str


def text(value: str) -> str:
    """A value safe inside the extcap grammar (port descriptions come from USB devices)."""
    return _UNSAFE_TEXT.sub(" ", value).strip()


def interface_name(device: str) -> str:
    return PREFIX + _UNSAFE_NAME.sub("_", os.path.basename(device.rstrip("/\\")) or device)


def serial_ports() -> list[tuple[str, str]]:
    """(device, description) of every serial port pyserial finds, sorted by device."""
    from serial.tools.list_ports import comports

    found = []
    try:
        ports = comports()
    except OSError:  # an unreadable /sys or registry: the socket interface is still offered
        return []
    for port in ports:
        description = port.description if port.description and port.description != "n/a" else ""
        found.append((port.device, description))
    return sorted(found)


def interfaces(ports: Iterable[tuple[str, str]]) -> list[Interface]:
    out = []
    for device, description in ports:
        name = interface_name(device)
        if name == SOCKET:
            continue
        about = f" ({text(description)})" if description and description != device else ""
        out.append(Interface(name, device, f"Modbus serial tap: {text(device)}{about}"))
    out.append(Interface(SOCKET, "", "Modbus serial tap: RTU over TCP gateway (socket://host:port)"))
    return out


def find_interface(name: str, ports: Iterable[tuple[str, str]]) -> Interface:
    for interface in interfaces(ports):
        if interface.name == name:
            return interface
    if name.startswith(PREFIX) and os.name == "posix":
        # A port pyserial does not list (a udev alias, a pty): its name under /dev.
        device = "/dev/" + name[len(PREFIX):]
        if os.path.exists(device):
            return Interface(name, device, device)
    raise UsageError(f"no interface {name!r} (see {PROG} --extcap-interfaces)")


def print_interfaces(out: TextIO, ports: Iterable[tuple[str, str]]) -> None:
    out.write(f"extcap {{version={__version__}}}\n")
    for interface in interfaces(ports):
        out.write(f"interface {{value={interface.name}}}{{display={interface.display}}}\n")


def print_dlts(out: TextIO) -> None:
    out.write(f"dlt {{number={LINKTYPE}}}{{name=USER0}}{{display=Modbus serial bytes as heard (map USER0 to vw3)}}\n")


def _selector(out: TextIO, number: int, values: Iterable[tuple[str, str]], default: str) -> None:
    for value, display in values:
        flag = "{default=true}" if value == default else ""
        out.write(f"value {{arg={number}}}{{value={value}}}{{display={display}}}{flag}\n")


def print_config(out: TextIO, interface: Interface) -> None:
    """The dialog: every option of --capture, with vw3-decode --live's defaults."""
    if interface.name == SOCKET:
        port = ("{tooltip=socket://host:port of an RTU-over-TCP gateway, or any pyserial port or URL "
                "(rfc2217://host:port, /dev/ttyUSB0, COM3)}{required=true}")
    else:
        port = f"{{default={text(interface.port)}}}{{tooltip=The serial port (or any pyserial URL); never written to}}"
    out.write(f"arg {{number=0}}{{call=--port}}{{display=Port}}{{type=string}}{port}{{group=Serial port}}\n")
    out.write("arg {number=1}{call=--baud}{display=Baud rate}{type=selector}{default=19200}"
              "{tooltip=Bits per second on the bus}{group=Serial port}\n")
    _selector(out, 1, ((str(baud), str(baud)) for baud in BAUDS), "19200")
    out.write("arg {number=2}{call=--parity}{display=Parity}{type=selector}{default=E}"
              "{tooltip=Even is the Modbus default}{group=Serial port}\n")
    _selector(out, 2, (("E", "even"), ("N", "none"), ("O", "odd")), "E")
    out.write("arg {number=3}{call=--stopbits}{display=Stop bits}{type=selector}{default=1}{group=Serial port}\n")
    _selector(out, 3, (("1", "1"), ("1.5", "1.5"), ("2", "2")), "1")
    out.write("arg {number=4}{call=--bytesize}{display=Data bits}{type=selector}{default=8}"
              "{tooltip=8 for Modbus RTU, 7 for most Modbus ASCII buses}{group=Serial port}\n")
    _selector(out, 4, (("8", "8"), ("7", "7")), "8")
    out.write("arg {number=5}{call=--mode}{display=Framing}{type=selector}{default=rtu}{group=Serial port}\n")
    _selector(out, 5, (("rtu", "Modbus RTU"), ("ascii", "Modbus ASCII")), "rtu")
    out.write("arg {number=6}{call=--detect}{display=Find the baud rate and parity first (--detect)}"
              "{type=boolflag}{default=false}{tooltip=Listen at 9600..115200 baud x even/none/odd parity, "
              "RTU at 8 data bits and ASCII at 7, and capture at the setting and framing that hear valid "
              "frames; the settings above are then ignored}{group=Detect}\n")
    out.write("arg {number=7}{call=--detect-seconds}{display=Seconds at each setting}{type=double}"
              "{default=2}{range=0.1,60}{tooltip=30 settings are tried}{group=Detect}\n")
    out.write("arg {number=8}{call=--description}{display=Interface description}{type=string}"
              "{tooltip=Written in the capture file's interface description, before the port and its "
              "settings (pcapng if_description)}{group=Capture}\n")


def build_parser() -> Parser:
    parser = Parser(prog=PROG, allow_abbrev=False, description=(
        "Wireshark extcap program: the vw3-dissector serial tap as a Wireshark capture interface. "
        "Wireshark runs it from its extcap folder; `vw3-extcap --install` puts a launcher there."))
    parser.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    protocol = parser.add_argument_group("extcap protocol (Wireshark calls these)")
    protocol.add_argument("--extcap-interfaces", action="store_true", help="list the interfaces")
    protocol.add_argument("--extcap-version", nargs="?", const="", metavar="VERSION",
                          help="Wireshark's version (given with --extcap-interfaces)")
    protocol.add_argument("--extcap-interface", metavar="NAME", help="the interface of the other calls")
    protocol.add_argument("--extcap-dlts", action="store_true", help="list the interface's link types")
    protocol.add_argument("--extcap-config", action="store_true", help="list the interface's options")
    protocol.add_argument("--extcap-capture-filter", metavar="FILTER",
                          help="capture filters are not supported (an empty one is accepted)")
    protocol.add_argument("--capture", action="store_true", help="capture into --fifo")
    protocol.add_argument("--fifo", metavar="PATH", help="where the pcapng stream goes")
    options = parser.add_argument_group("capture options (the interface's dialog)")
    options.add_argument("--port", help="serial port or pyserial URL (default: the interface's port)")
    options.add_argument("--baud", type=baud_rate, default=19200, help="50..4,000,000, default 19200")
    options.add_argument("--parity", type=str.upper, choices=PARITY_CHOICES, default="E", help="default E")
    options.add_argument("--stopbits", type=float, choices=[1, 1.5, 2], default=1, help="default 1")
    options.add_argument("--bytesize", type=int, choices=[5, 6, 7, 8], default=8, help="default 8")
    options.add_argument("--mode", type=str.lower, choices=["rtu", "ascii"], default="rtu", help="default rtu")
    options.add_argument("--detect", action="store_true", help="find the baud rate and parity first")
    options.add_argument("--detect-seconds", type=positive_seconds, default=2.0, metavar="SECONDS",
                         help="seconds at each of the 30 settings --detect tries (default 2)")
    options.add_argument("--description", default="", help="pcapng interface description (before the settings)")
    install = parser.add_argument_group("installing")
    install.add_argument("--install", nargs="?", const="", metavar="DIR",
                         help="write the launcher Wireshark runs into DIR (default: the personal extcap "
                         "folder the installed tshark reports)")
    return parser


FILTER_REFUSED = "capture filters are not supported on a serial bus: use a display filter (vw3.slave == 12)"


def run(argv: list[str] | None, out: TextIO, err: TextIO) -> int:
    try:
        args = build_parser().parse_args(argv)
    except UsageError as error:
        err.write(f"{PROG}: {error}\n")
        return release(argv, ExitStatus.BAD_INPUT)
    try:
        if args.install is not None:
            from dissector.app.extcap_install import install

            out.write(f"{PROG}: wrote {install(args.install or None)}\n")
            return ExitStatus.OK
        if args.extcap_interfaces:
            print_interfaces(out, serial_ports())
            return ExitStatus.OK
        if args.extcap_version is not None and args.extcap_interface is None:
            out.write(f"extcap {{version={__version__}}}\n")
            return ExitStatus.OK
        if args.extcap_interface is None:
            raise UsageError(f"give --extcap-interfaces, or --extcap-interface NAME with --extcap-dlts, "
                             f"--extcap-config, --extcap-capture-filter or --capture (see {PROG} --help)")
        interface = find_interface(args.extcap_interface, serial_ports())
        if args.extcap_dlts:
            print_dlts(out)
            return ExitStatus.OK
        if args.extcap_config:
            print_config(out, interface)
            return ExitStatus.OK
        if args.capture:
            if args.fifo is None:
                raise UsageError("--capture needs --fifo PATH")
            if args.extcap_capture_filter and args.extcap_capture_filter.strip():
                raise UsageError(FILTER_REFUSED)
            port = args.port or interface.port
            if not port:
                raise UsageError(f"{SOCKET} needs the gateway's address: --port socket://HOST:PORT")
            from dissector.app.extcap_capture import capture  # pyserial's port code only to capture

            return capture(args, port, err, PROG)
        if args.extcap_capture_filter is not None:
            # Wireshark's filter check: any text printed marks the filter invalid and is shown.
            if args.extcap_capture_filter.strip():
                out.write(FILTER_REFUSED + "\n")
            return ExitStatus.OK
        raise UsageError(f"nothing to do for {interface.name}: give --extcap-dlts, --extcap-config or --capture")
    except (UsageError, LiveError) as error:
        err.write(f"{PROG}: {error}\n")
        return release(argv, error.status)


def release(argv: list[str] | None, status: int) -> int:
    """A bad command line for a capture still releases the fifo (extcap_capture.release)."""
    arguments = sys.argv[1:] if argv is None else argv
    if "--capture" not in arguments:
        return status
    fifo = None
    for index, argument in enumerate(arguments):
        if argument == "--fifo" and index + 1 < len(arguments):
            fifo = arguments[index + 1]
        elif argument.startswith("--fifo="):
            fifo = argument[len("--fifo="):]
    from dissector.app.extcap_capture import release as release_fifo

    return release_fifo(fifo, status)


def main(argv: list[str] | None = None) -> int:
    if sys.stdout is None or sys.stderr is None:
        return ExitStatus.ERROR
    for stream in (sys.stdout, sys.stderr):
        # Wireshark reads UTF-8 whatever the locale (a Windows pipe would otherwise get the ANSI code
        # page, and a USB description outside it would end in a traceback).
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(encoding="utf-8", errors="replace")
    try:
        status = run(argv, sys.stdout, sys.stderr)
        sys.stdout.flush()
    except KeyboardInterrupt:
        return ExitStatus.ERROR
    except BrokenPipeError:
        return ExitStatus.ERROR
    return status


if __name__ == "__main__":
    sys.exit(main())
