"""The device-profile options of the command line, turned into an annotator."""
from __future__ import annotations

import argparse
from pathlib import Path
from typing import TextIO

from dissector.devices.annotator import Annotator
from dissector.devices.build import build_annotator
from dissector.devices.profiles import ADDRESS_STYLES, BUILTIN_PROFILES, DEFAULT_PROFILE
from dissector.errors import ProfileError

# A slave address a profile or a map can be for (Modbus over serial line 2.2: 0 is the broadcast address,
# which no device has and none answers at; 248..255 are reserved).
FIRST_SLAVE, LAST_SLAVE = 1, 247


def add_profile_arguments(parser: argparse.ArgumentParser) -> None:
    group = parser.add_argument_group("device profiles")
    group.add_argument(
        "--profile",
        action="append",
        default=[],
        metavar="[SLAVE=]NAME",
        help=(
            "device profile for every slave (NAME) or one slave (SLAVE=NAME); repeatable. "
            f"Built-in: {', '.join(BUILTIN_PROFILES)}, or a .toml file; default {DEFAULT_PROFILE}: each slave "
            "gets one from evidence in the capture (identification, function codes, registers read)"
        ),
    )
    group.add_argument(
        "--map",
        action="append",
        default=[],
        metavar="[SLAVE=|PROFILE=]FILE",
        help="register map CSV adding or overriding rows, for all slaves, one slave or one profile",
    )
    group.add_argument(
        "--address-style",
        choices=ADDRESS_STYLES,
        default=None,
        help="show addresses as sent (protocol) or as PLC references, 0X/1X/3X/4X (plc); default per profile",
    )


def annotator_from_args(args: argparse.Namespace) -> Annotator:
    profiles = list(getattr(args, "profile", None) or [])
    maps = list(getattr(args, "map", None) or [])
    check_slaves("--profile", profiles)
    check_slaves("--map", [spec for spec in maps if not Path(spec).exists()])  # (a file whose name holds '=')
    return build_annotator(profiles, maps, getattr(args, "address_style", None))


def check_slaves(option: str, specs: list[str]) -> None:
    """Refuse `SLAVE=...` for an address no device has: 0, the broadcast address (a profile for it would
    name the writes every slave takes, as one device's), or past 247."""
    for spec in specs:
        target, sep, _rest = spec.partition("=")
        target = target.strip()
        if not sep or not (target.isascii() and target.isdigit()):
            continue  # (build_annotator says what is wrong with those)
        slave = int(target, 10)
        if slave == 0:
            raise ProfileError(f"{option} {spec!r}: slave 0 is the broadcast address, which no device has "
                               f"(a slave is {FIRST_SLAVE}..{LAST_SLAVE})")
        if slave > LAST_SLAVE:
            raise ProfileError(f"{option} {spec!r}: slave {slave} is outside {FIRST_SLAVE}..{LAST_SLAVE}")


def report_profiles(annotate: object, stderr: TextIO, is_terminal: bool) -> None:
    """Profile `auto`: one line per slave saying which device it was taken for and why, for the person
    at the terminal (scripts read the choices from --stats; a redirected stderr stays free of them)."""
    if not is_terminal:
        return
    for line in getattr(annotate, "profile_report", lambda: [])():
        stderr.write(f"vw3-decode: {line}\n")
