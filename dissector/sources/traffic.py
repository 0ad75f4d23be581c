"""Traffic logs of Modbus masters and slave simulators (Modbus Poll, Modbus Slave): one frame a line.

    Tx:000000-0C 03 20 D0 00 03 0E EF           counter after the direction (older versions)
    000001-Rx:0C 03 06 80 00 00 03 00 02 17 E4  counter before it (newer versions)
    Tx:000002-10:15:30.125-0C 03 20 D0 ...      with a time stamp: a time of day,
    000003-2024-05-01 10:15:30.125-Rx:0C 03 ... an ISO date and time, or [ ] around either

Tx is what the program sent, Rx what it received; for a master that is request and response, for a
slave simulator the other way round, so the direction is not used to decide what a frame is: the
framer does, as for any capture. A line with a direction but no bytes (a timeout) is skipped; any
other line is an error. Times follow the hex-dump reader's rules (a time of day counts from midnight).
"""
from __future__ import annotations

import re
from collections.abc import Iterator

from dissector.model import Chunk, Stamp
from dissector.sources.common import Input, SourceError, WarningLog
from dissector.sources.hexdump import HexLineError, _timestamp, text_lines

_LINE = re.compile(
    r"\s*(?:(?P<before>\d{1,10})-)?(?P<stamp1>[^TR]*?)-?\s*(?P<direction>[TR]x)\s*:\s*"
    r"(?:(?P<after>\d{1,10})-)?(?:(?P<stamp2>.*?)-)?(?P<hex>(?:[0-9A-Fa-f]{2}\s*)*)\s*",
    re.IGNORECASE,
)


def parse_traffic_line(line: str) -> tuple[Stamp | None, bytes] | None:
    """(time, bytes) of a traffic line; None when it carries no bytes; ValueError if not one."""
    if not line.strip():
        return None
    match = _LINE.fullmatch(line.rstrip("\r\n"))
    if match is None:
        raise ValueError(f"not a Tx:/Rx: traffic line: {line.strip()[:60]!r}")
    stamp_text = (match.group("stamp1") or match.group("stamp2") or "").strip().strip("-").strip()
    time = None
    if stamp_text:
        try:
            time, used = _timestamp(stamp_text.replace("T", " ").split())
        except HexLineError as error:
            raise ValueError(str(error)) from None
        if not used or used != len(stamp_text.split()):
            raise ValueError(f"not a time stamp: {stamp_text[:40]!r}")
    data = bytes.fromhex("".join(match.group("hex").split()))
    return (time, data) if data else None


def looks_like_traffic(text: str, complete: bool) -> bool:
    lines = text.splitlines()
    if not complete and not text.endswith(("\n", "\r")):
        lines = lines[:-1]
    found = False
    for line in lines:
        try:
            found = parse_traffic_line(line) is not None or found
        except ValueError:
            return False
    return found


def read_traffic(inp: Input, log: WarningLog, chunk_size: int) -> Iterator[Chunk]:
    for number, line in text_lines(inp, chunk_size):
        try:
            parsed = parse_traffic_line(line)
        except ValueError as error:
            raise SourceError(f"{inp.name} line {number}: {error}") from None
        if parsed is not None:
            time, data = parsed
            yield Chunk(data, time, True)
