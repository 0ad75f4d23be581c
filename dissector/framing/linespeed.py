"""A capture's line speed: `--baud` when typed, else what a pcapng's interface says, else 19200.

One function for every path that decodes a file: the framer (a silence of t3.5 between reads is
evidence of a frame's end), the t1.5 check of silences inside frames, `--stats`' and the report's bus
timing, profile `auto`'s first pass; in one process, in `--parquet --jobs` workers and on Dask
workers alike. A file read at two speeds would judge its silences differently depending on how it ran.

`vw3-decode --live -w x.pcapng` states the port's settings in the interface's description
(`serial port /dev/ttyUSB0, 9600 baud, ... (9600 8E1)`); other tools write `19200 8N1` or
`38400 baud` there or in its name. Both texts are read; the first statement found wins.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from dissector.framing.timing import DEFAULT_BAUD, mode_bits
from dissector.sources.pcapng import first_interface

_SETTINGS = re.compile(r"\b(\d{2,7})[ /,]+([5-8])([NEOMS])(1\.5|1|2)\b")
_BAUD = re.compile(r"\b(\d{2,7}) ?(?:baud|bd|bps)\b", re.I)
MIN_BAUD = 50  # the slowest standard rate: below it a text's number is not a line speed (`00 baud`)
MAX_BAUD = 4_000_000  # above what RS-485 transceivers and USB adapters run a Modbus serial line at
FROM_PCAPNG = "pcapng interface description"


@dataclass(frozen=True, slots=True)
class LineSettings:
    baud: int
    bits: float | None = None  # bits a character; None: the mode's (11 RTU, 10 ASCII)
    source: str = "assumed"  # "--baud", "pcapng interface description", "assumed: --baud sets it"

    def char_bits(self, mode: str) -> float:
        return self.bits if self.bits is not None else mode_bits(mode)


def baud_rate(text: str) -> int:
    """`--baud`: a whole number of baud a Modbus serial line runs at (50..4,000,000), else the one line
    argparse shows (a rate of 0 divided by zero; 10**20 gave a t3.5 of 0 and no error)."""
    import argparse

    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number of baud") from None
    if not MIN_BAUD <= value <= MAX_BAUD:
        raise argparse.ArgumentTypeError(
            f"{text if len(text) <= 24 else text[:24] + '...'} baud is no Modbus serial line speed "
            f"({MIN_BAUD}..{MAX_BAUD:,})")
    return value


def settings_from_text(text: str) -> LineSettings | None:
    """The line settings a text states: `19200 8E1`, or `9600 baud`; None when it states none."""
    match = _SETTINGS.search(text)
    if match is not None and int(match.group(1)) >= MIN_BAUD:
        baud, data, parity, stop = match.groups()
        bits = 1 + int(data) + (parity != "N") + float(stop)
        return LineSettings(int(baud), bits if bits != int(bits) else int(bits), FROM_PCAPNG)
    match = _BAUD.search(text)
    if match is not None and int(match.group(1)) >= MIN_BAUD:
        return LineSettings(int(match.group(1)), None, FROM_PCAPNG)
    return None


def line_settings(path: str | None, source_format: str | None, baud: int | None) -> LineSettings:
    """The line of the input `path` read as `source_format`: `baud` (`--baud`, None when not typed)
    when given, else what a pcapng file's first interface states, else 19200 (as the simulator's)."""
    if baud is not None:
        return LineSettings(baud, None, "--baud")
    if path is not None and path != "-" and source_format == "pcapng":  # (standard input: read once)
        interface = first_interface(path)
        settings = settings_from_text(" ".join(interface.texts)) if interface is not None else None
        if settings is not None:
            return settings
    return LineSettings(DEFAULT_BAUD, None, "assumed: --baud sets it")
