"""libmodbus debug output (modbus_set_debug; `mbpoll -v`, which is libmodbus): one frame a line, as it
prints them while it talks on the bus.

    debug enabled                            the program's own lines: passed over
    [01][03][00][00][00][02][C4][0B]         a frame it sent (in [ ])
    Waiting for a confirmation...
    <01><03><04><00><00><00><01><3B><F3>     a frame it received (in < >)
    <01><03><04><00>ERROR Connection timed out: select     (its error, on stderr, after the bytes heard)

A master sends requests and receives answers, a server (`Waiting for an indication...`) the other way
round, so the brackets do not say what a frame is: the framer does, as for any capture. Told by a line of
bytes, or before any (a pipe is judged on its first lines) by libmodbus's `Opening /dev/ttyUSB0 at 19200
bauds (E, 8, 1)` or mbpoll's first line with -v, `debug enabled`. Each line of
bytes is a record (what the program read as one message: a part of one when it gave up), untimed. A line
is bytes only when it is all groups of two hex digits in one kind of bracket (an error message may follow
the bytes heard): `[10]: 	5`, mbpoll's value of reference 10, is not. Other lines are passed over."""
from __future__ import annotations

import re
from collections.abc import Iterator

from dissector.model import Chunk
from dissector.sources.common import Input, WarningLog
from dissector.sources.hexdump import StampedLines, cut_short, ended_lines

_SENT = r"(?:\[[0-9A-Fa-f]{2}\])+"
_HEARD = r"(?:<[0-9A-Fa-f]{2}>)+"
_LINE = re.compile(rf"\s*({_SENT}|{_HEARD})(?:\s*|ERROR\b.*)")
# Lines that come before any frame: libmodbus's opening of an RTU port, mbpoll -v's first line.
_OPENING = re.compile(r"Opening \S.* at \d+ bauds \([NEO], [5-8], [12]\)\s*")
_MBPOLL = "debug enabled"
# The input's last line, cut short inside a group: the whole groups before it are read.
_CUT = re.compile(rf"\s*({_SENT}|{_HEARD})?(\[[0-9A-Fa-f]?|<[0-9A-Fa-f]?)")


def line_bytes(line: str) -> bytes | None:
    """The bytes of a line of libmodbus debug output, None for any other line."""
    found = _LINE.fullmatch(line)
    return bytes.fromhex(re.sub(r"[\[\]<>]", "", found.group(1))) if found is not None else None


def looks_like_libmodbus(text: str, complete: bool) -> bool:
    """Does `text` (the input's first bytes; its last line left out unless `complete`) hold a line of bytes?"""
    lines = text.splitlines()
    if not complete and not text.endswith(("\n", "\r")):
        lines = lines[:-1]
    return (bool(lines) and lines[0].strip() == _MBPOLL) or any(
        line_bytes(line) is not None or _OPENING.fullmatch(line) for line in lines)


def read_libmodbus(inp: Input, log: WarningLog, chunk_size: int) -> StampedLines:
    return StampedLines(_chunks(inp, log, chunk_size))


def _chunks(inp: Input, log: WarningLog, chunk_size: int) -> Iterator[Chunk]:
    found = False
    for number, line, ended in ended_lines(inp, chunk_size):
        data = line_bytes(line)
        if data is not None:
            found = True
            yield Chunk(data, None, True)
            continue
        cut = None if ended else _CUT.fullmatch(line.rstrip())
        if cut is not None:
            data = line_bytes(cut.group(1)) if cut.group(1) else b""
            log.warn("truncated input", cut_short(inp.name, number, data, cut.group(2)))
            if data:
                found = True
                yield Chunk(data, None, True)
    if not found:  # (--format libmodbus on another text: every line passed over, said, not silent)
        log.warn("empty", f"{inp.name}: no line of libmodbus debug output ([01][03]... sent, <01><03>... received)")
