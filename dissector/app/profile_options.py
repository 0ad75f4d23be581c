"""The device-profile options of the command line, turned into an annotator."""
from __future__ import annotations

import argparse
from typing import TextIO

from dissector.devices.annotator import Annotator
from dissector.devices.build import build_annotator
from dissector.devices.profiles import ADDRESS_STYLES, BUILTIN_PROFILES, DEFAULT_PROFILE


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
    return build_annotator(
        list(getattr(args, "profile", None) or []),
        list(getattr(args, "map", None) or []),
        getattr(args, "address_style", None),
    )


def report_profiles(annotate: object, stderr: TextIO, is_terminal: bool) -> None:
    """Profile `auto`: one line per slave saying which device it was taken for and why, for the person
    at the terminal (scripts read the choices from --stats; a redirected stderr stays free of them)."""
    if not is_terminal:
        return
    for line in getattr(annotate, "profile_report", lambda: [])():
        stderr.write(f"vw3-decode: {line}\n")
