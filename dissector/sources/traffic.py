"""Traffic logs of Modbus masters and slave simulators (Modbus Poll, Modbus Slave): one frame a line.

    Tx:000000-0C 03 20 D0 00 03 0E EF           counter after the direction (older versions)
    000001-Rx:0C 03 06 80 00 00 03 00 02 17 E4  counter before it (newer versions)
    Tx:000002-10:15:30.125-0C 03 20 D0 ...      with a time stamp: a time of day,
    000003-2024-05-01 10:15:30.125-Rx:0C 03 ... an ISO date and time, or [ ] around either

Tx is what the program sent, Rx what it received; for a master that is request and response, for a
slave simulator the other way round, so the direction is not used to decide what a frame is: the
framer does, as for any capture. A line with a direction but no bytes (a timeout) is skipped; any
other line is an error, but the last one cut short by the end of the input (hexdump.read_lines). Times follow the hex-dump reader's rules (a time of day counts from midnight,
and is on the next day when it is more than 12 hours earlier than the one before: hexdump.Days).
"""
from __future__ import annotations

import re
from collections.abc import Iterator

from dissector.model import Chunk, Stamp
from dissector.sources.common import Input, WarningLog
from dissector.sources.hexdump import (
    HexLineError, StampedLines, TimeRangeError, _cut_line, _timestamp, read_lines,
)

# Found with search(), then the line is cut in plain steps: one regular expression with optional
# parts on both sides backtracked exponentially on lines of spaces (50 s for 400 characters).
_DIRECTION = re.compile(r"([TR]x)\s?:", re.IGNORECASE)
_COUNTER = re.compile(r"\d{1,10}-")
_BYTES = re.compile(r"(?:[0-9A-Fa-f]{2})+")


def _time(text: str) -> Stamp | None:
    text = text.strip().strip("-").strip()
    if not text:
        return None
    tokens = text.replace("T", " ").split()
    try:
        time, used = _timestamp(tokens)
    except TimeRangeError:
        raise  # a time stamp, refused for its range
    except HexLineError as error:
        raise ValueError(str(error)) from None
    if time is None or used != len(tokens):
        raise ValueError(f"not a time stamp: {text[:40]!r}")
    return time


def parse_traffic_line(line: str) -> tuple[Stamp | None, bytes] | None:
    """(time, bytes) of a traffic line; None when it carries no bytes; ValueError if not one."""
    text = line.strip()
    if not text:
        return None
    marker = _DIRECTION.search(text)
    if marker is None:
        raise ValueError(f"not a Tx:/Rx: traffic line: {text[:60]!r}")
    before = text[: marker.start()].strip()
    after = text[marker.end() :].strip()
    counter = _COUNTER.match(before)
    if counter is not None:
        before = before[counter.end() :]
    counter = _COUNTER.match(after)
    if counter is not None:
        after = after[counter.end() :]
    stamp, _dash, hex_text = after.rpartition("-")  # a time stamp between counter and bytes
    groups = hex_text.split()
    if not all(_BYTES.fullmatch(group) for group in groups):
        raise ValueError(f"not a Tx:/Rx: traffic line: {text[:60]!r}")
    time = _time(before)
    if time is None:
        time = _time(stamp)
    data = bytes.fromhex("".join(groups))
    return (time, data) if data else None


def looks_like_traffic(text: str, complete: bool, most: bool = False) -> bool:
    """Are the lines of `text` (the input's first bytes, the last left out unless `complete`) traffic
    lines, with bytes on at least one? All of them; with `most`, more of them than not (a stray line
    in a log: reading it names the line)."""
    lines = text.splitlines()
    unended = not text.endswith(("\n", "\r"))
    if not complete and unended:
        lines = lines[:-1]
    found = refused = 0
    for number, line in enumerate(lines, start=1):
        try:
            found += parse_traffic_line(line) is not None
        except TimeRangeError:
            return True  # a traffic line whose time reading refuses
        except ValueError:
            if complete and unended and number == len(lines) and _cut_line(line, number, _parse) is not None:
                continue  # the input's last line, cut short: reading it says so
            if not most:
                return False
            refused += 1
    return found > refused


def _parse(line: str, _number: int) -> tuple[Stamp | None, bytes] | None:
    return parse_traffic_line(line)


def read_traffic(inp: Input, log: WarningLog, chunk_size: int) -> StampedLines:
    return read_lines(inp, log, chunk_size, _parse)
