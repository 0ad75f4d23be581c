"""The device-profile options of the command line, turned into an annotator."""
from __future__ import annotations

import argparse

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
            f"Built-in: {', '.join(BUILTIN_PROFILES)} (default {DEFAULT_PROFILE}), or a .toml file"
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
        help="show register addresses as sent (protocol) or as 4X references (plc); default per profile",
    )


def annotator_from_args(args: argparse.Namespace) -> Annotator:
    return build_annotator(
        list(getattr(args, "profile", None) or []),
        list(getattr(args, "map", None) or []),
        getattr(args, "address_style", None),
    )
