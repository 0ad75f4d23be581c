"""Text hex dumps: one frame (or one read of the line) a line.

    # comment lines and trailing comments are ignored
    0C 03 20 D0 00 03 0E EF
    0C0306800000030002 17E4          spaces are optional, but each group is whole bytes
    1700000000.125  0C 83 02 51 32   optional leading timestamp

    02:04:00:00:00:50:F0:05          colon hex, 0x0C 0x03 ..., or decimal lists: see notation.py
    TX: 1, 3, 0, 22, 0, 2, 37, 207   a TX:/RX: label (NModbus logs) before the bytes is skipped

A leading timestamp is recognised only in shapes a hex group can never take (a hex group has no
'.', '-' or ':'): seconds with a decimal point (`12.5`, `1700000000.125`), an ISO 8601 date-time
(`2024-05-01T10:00:00.125`, `2024-05-01 10:00:00.125`, naive means UTC), or a time of day
(`10:00:00.125`, seconds since midnight); a date-time's or time of day's fraction may follow ','
(`10:00:00,125`, as Python's logging writes it). A date or time of day that does not exist
(`2024-02-30`, `24:00:00`, `10:00:60`: no leap second, as datetime) refuses the line. A stamp may be
wrapped in [ ] or followed by ':'. A line that is only `10:00:00` is the colon-hex bytes 10 00 00, not a
time without data.

A time of day has no date, so a log that runs past midnight would go back a day: a time of day more
than 12 hours earlier than the one before it is on the next day (`23:59:59.900` then `00:00:00.010`
is 110 ms later, Days). A time of day less than that earlier stays on the same day, time going
backwards as the log says (a clock step: shown as it is, left out of --stats' timing). Seconds and
date-times are absolute: kept as they are.

Whether the input is a hex dump is judged on its first lines; when the first line is longer than the
sample (a whole capture on one line), on the part of it the sample holds. The last line of an input,
when no line end closes it and it reads as a line cut short (`0C 03 2`), is the input cut short: its
whole bytes are decoded, with a warning (read_lines).
"""
from __future__ import annotations

import codecs
import math
import re
from collections.abc import Callable, Iterator
from datetime import datetime, timedelta, timezone

from dissector.errors import MalformedInput
from dissector.model import Chunk, Stamp
from dissector.sources.common import Input, SourceError, WarningLog, outside_time_range
from dissector.sources.notation import RefusedList, Notation, NotationError, split_list

MAX_LINE = 1 << 20  # a whole capture pasted on one line is a hex dump too; memory stays bounded
_EPOCH = datetime(1970, 1, 1, tzinfo=timezone.utc)
DAY_NS = 86_400 * 1_000_000_000

_SECONDS = re.compile(r"\d+\.\d+")
_DATE = re.compile(r"\d{4}-\d{2}-\d{2}")
# A date-time's or time of day's fraction after '.' or ',' (ISO 8601 allows both; Python's logging writes
# `2024-05-01 10:00:00,125`).
_DATETIME = re.compile(r"\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}([.,]\d+)?(Z|[+-]\d{2}:?\d{2})?")
_TIME_OF_DAY = re.compile(r"(\d{2}):(\d{2}):(\d{2}(?:[.,]\d+)?)")
_HEX = re.compile(r"(?:[0-9A-Fa-f]{2})+")
_LABEL = re.compile(r"[TR]X:", re.IGNORECASE)
CONTROL = re.compile(rb"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")  # bytes no text has (tab, CR and LF aside)
_CUT_TOKEN = re.compile(r"[\[{]?(?:0[xX])?[0-9A-Fa-f:]{2,}")


class TimeOfDay(Stamp):
    """A time of day without a date (`10:00:00.125`): nanoseconds since midnight, until Days places it
    on its day."""


class Days:
    """The days of an input's times of day: one that is more than 12 hours earlier than the time of day
    before it is on the next day (the log ran past midnight); any other is on the day of the one before.
    Other times (seconds, date-times) pass as they are."""

    def __init__(self) -> None:
        self.days = 0
        self.last: int | None = None  # the time of day before, ns since its midnight

    def place(self, time: Stamp | None) -> Stamp | None:
        if not isinstance(time, TimeOfDay):
            return time
        if self.last is not None and time.ns < self.last - DAY_NS // 2:
            self.days += 1
        self.last = time.ns
        return Stamp(time.ns + self.days * DAY_NS)


class HexLineError(MalformedInput):
    """A hex dump line that is not hex bytes."""


class TimeRangeError(HexLineError):
    """A time stamp in shape, refused for its value (a date or time of day that does not exist, a time
    outside what every output can show): the input is a dump (the sniffers say so) and reading it
    refuses the line."""


def _strip_stamp(token: str) -> str:
    if token.startswith("[") and token.endswith("]"):
        token = token[1:-1]
    if token.endswith(":") and not _HEX.fullmatch(token[:-1]):
        token = token[:-1]
    return token


def _timestamp(tokens: list[str]) -> tuple[Stamp | None, int]:
    """(time, tokens used) for a leading timestamp; (None, 0) when the line starts with data."""
    time, used = _stamp(tokens)
    if time is not None:
        outside = outside_time_range(time.ns)
        if outside is not None:
            raise TimeRangeError(outside)
    return time, used


def _stamp(tokens: list[str]) -> tuple[Stamp | None, int]:
    if not tokens:
        return None, 0
    first = _strip_stamp(tokens[0])
    if _SECONDS.fullmatch(first):
        if not math.isfinite(float(first)):  # 400 digits make inf: no time (and no JSON) can hold it
            raise HexLineError(f"timestamp {first[:24]}... is out of range")
        return Stamp(_nanoseconds(first)), 1
    if _DATETIME.fullmatch(first):
        return _epoch(first), 1
    if _DATE.fullmatch(first.lstrip("[")) and len(tokens) > 1:
        joined = _strip_stamp(f"{tokens[0]}T{tokens[1]}")
        if _DATETIME.fullmatch(joined):
            return _epoch(joined), 2
    match = _TIME_OF_DAY.fullmatch(first)
    if match:
        return _time_of_day(first, *match.groups()), 1
    return None, 0


def _time_of_day(text: str, hours: str, minutes: str, seconds: str) -> TimeOfDay:
    """The time of day `text`, its fields in range as a date-time's must be (datetime's own words). A leap
    second (23:59:60) is refused as well: a date-time refuses it, and the computer clocks loggers read
    never show it (they repeat or smear a second)."""
    for value, field, limit in ((hours, "hour", 23), (minutes, "minute", 59), (seconds, "second", 59)):
        if int(value.replace(",", ".").partition(".")[0]) > limit:
            raise TimeRangeError(f"bad time of day {text!r}: {field} must be in 0..{limit}")
    return TimeOfDay((int(hours) * 3600 + int(minutes) * 60) * 1_000_000_000 + _nanoseconds(seconds))


def _nanoseconds(decimal: str) -> int:
    """`12.5` (or `12,5`) -> 12_500_000_000, exactly (digits past the ninth are dropped)."""
    whole, _dot, fraction = decimal.replace(",", ".").partition(".")
    return int(whole) * 1_000_000_000 + int((fraction + "000000000")[:9])


def _epoch(text: str) -> Stamp:
    try:
        moment = datetime.fromisoformat(text)
    except ValueError as error:
        raise TimeRangeError(f"bad timestamp {text!r}: {error}") from None
    if moment.tzinfo is None:
        moment = moment.replace(tzinfo=timezone.utc)
    return Stamp((moment - _EPOCH) // timedelta(microseconds=1) * 1000)


def parse_line(line: str, notation: Notation | None = None, where: str = "") -> tuple[float | None, bytes] | None:
    """(time, data) for a line, None for a blank or comment line; HexLineError when malformed.

    `notation` carries what earlier lines of the same input showed (hex or decimal)."""
    text = line.split("#", 1)[0].strip()
    if not text:
        return None
    tokens = text.split()
    if len(tokens) == 1 and _TIME_OF_DAY.fullmatch(tokens[0]):
        time, used = None, 0  # `10:00:00` alone (or `99:99:99`): colon hex, not a time without data
    else:
        time, used = _timestamp(tokens)
    label = used < len(tokens) and _LABEL.fullmatch(tokens[used]) is not None
    used += label
    if used == len(tokens):
        raise HexLineError(f"{tokens[-1]!r} without data" if label else "a timestamp without data")
    try:
        data = (notation if notation is not None else Notation()).read(" ".join(tokens[used:]), where)
    except RefusedList:
        raise
    except NotationError as error:
        raise HexLineError(str(error)) from None
    if not data:
        raise HexLineError("a timestamp without data")
    return time, data


def looks_like_hexdump(text: str, complete: bool, most: bool = False) -> bool:
    """Do the lines of `text` (the input's first bytes) parse, with data on at least one? All of them;
    with `most`, more of them than not, a line of mostly bytes with a typo in it counting as a dump's (a
    log with a typo or a stray line in it is still a hex dump, and reading it names the line).

    The last line is left out unless `complete`: it may be cut where the sample ends. When no line
    is whole, the part of the first one the sample holds is judged, without its last (cut) number.
    A byte list refused for its meaning (notation.RefusedList) or a time stamp for its value counts:
    reading it says why.
    """
    lines = text.splitlines()
    cut = ""
    unended = not text.endswith(("\n", "\r"))
    if not complete and unended and lines:
        cut = lines.pop()
    notation = Notation()

    def parse(line: str, number: int) -> tuple[Stamp | None, bytes] | None:
        return parse_line(line, notation, f"line {number}")

    found = refused = 0
    for number, line in enumerate(lines, start=1):
        try:
            parsed = parse(line, number)
        except (RefusedList, TimeRangeError):
            return True
        except HexLineError:
            if complete and unended and number == len(lines) and _cut_line(line, number, parse) is not None:
                continue  # the input's last line, cut short: reading it says so
            if not most:
                return False
            if _mostly_bytes(line):
                found += 1  # a byte list with a typo in it (`... 02 CE 2`, `EF // retry`): a dump's line
            else:
                refused += 1
            continue
        found += parsed is not None
    if found or refused or not cut or "#" in cut:
        return found > refused
    return _cut_line_is_hex(cut, notation)


# A word of a byte list: whole hex bytes (`0C`, `0C03`), colon or 0x hex (`0C:03`, `0x0C`).
_BYTE_WORD = re.compile(r"(?:0[xX])?(?:[0-9A-Fa-f]{2})+(?::[0-9A-Fa-f]{2})*|0[xX][0-9A-Fa-f]")


def _mostly_bytes(line: str) -> bool:
    """A line that does not read, but whose words are mostly bytes (two at least): a dump line with a typo
    or a note in it, not a line of some other text."""
    words = split_list(line.split("#", 1)[0])
    bytes_ = sum(1 for word in words if _BYTE_WORD.fullmatch(word))
    return bytes_ >= 2 and bytes_ * 2 > len(words)


def _last_word(line: str) -> tuple[str, str]:
    """(what comes before the last word of a line, that word): where a line cut short was cut."""
    line = line.rstrip()
    end = max(line.rfind(" "), line.rfind(","), line.rfind("\t"))
    return line[: max(end, 0)].rstrip(" ,\t"), line[end + 1 :]


def _cut_line_is_hex(cut: str, notation: Notation) -> bool:
    """The first line, cut by the sample's end: its whole numbers parse, and the cut one could."""
    head, last = _last_word(cut)
    if head:
        try:
            return parse_line(head, notation, "line 1") is not None
        except (RefusedList, TimeRangeError):
            return True
        except HexLineError:
            return False
    return bool(_CUT_TOKEN.fullmatch(last))


def _lines(inp: Input, chunk_size: int) -> Iterator[tuple[bytes, bool]]:
    """(line, whether a line end closes it): only the last line of an input may have none."""
    pending = b""
    while True:
        block = inp.read_some(chunk_size)
        if not block:
            if pending:
                yield pending, False
            return
        pending += block
        lines = pending.split(b"\n")
        pending = lines.pop()
        if len(pending) > MAX_LINE:
            raise SourceError(f"{inp.name}: a line longer than {MAX_LINE} bytes: not a hex dump")
        for line in lines:
            yield line, True


def characters(text: bytes, complete: bool = True) -> str:
    """The characters of a text's bytes: UTF-8, else an 8-bit code page's (Latin-1: what is not ASCII
    is in comments, which are dropped); a UTF-8 character cut by a sample's end (not `complete`) is
    left out."""
    try:
        return codecs.getincrementaldecoder("utf-8")().decode(text, final=complete)
    except UnicodeDecodeError:
        return text.decode("latin-1")


def ended_lines(inp: Input, chunk_size: int) -> Iterator[tuple[int, str, bool]]:
    """(line number, text, whether a line end closes it) of a text input; SourceError at the first line
    with a control byte (binary data). Characters beyond ASCII are taken (comments); the line's reader
    refuses them elsewhere."""
    for number, (raw, ended) in enumerate(_lines(inp, chunk_size), start=1):
        if CONTROL.search(raw):
            raise SourceError(f"{inp.name} line {number}: binary data in a hex dump")
        yield number, characters(raw), ended


# The last characters of a line cut short: part of a byte, a number or a time stamp (`0C 03 2`, `10:00:0`).
_CUT_TAIL = re.compile(r"[0-9A-Fa-fxXTtRrZ:.,+\-\[\]{}]+")
_STAMP_PART = re.compile(r"[0-9:.,+\-TZ\[\] ]*")  # what a time stamp cut before its bytes leaves


LineParser = Callable[[str, int], "tuple[Stamp | None, bytes] | None"]  # (line, its number) -> (time, bytes)


def _cut_line(line: str, number: int, parse: LineParser) -> tuple[Stamp | None, bytes, str] | None:
    """(time, whole bytes, the rest) of the input's last line when it has no line end and what it holds
    is a line cut short: all but its last word reads, and that word is part of a number or a time.
    None when it is not (a bad line is an error wherever it is; one with a comment was not cut before it)."""
    if "#" in line:
        return None
    text = line.rstrip()
    head, rest = _last_word(text)
    if not _CUT_TAIL.fullmatch(rest):
        return None
    if not head:
        return None, b"", rest
    try:
        parsed = parse(head, number)
    except ValueError:
        # (a time stamp alone, or part of one: nothing whole came before the cut)
        return (None, b"", text.strip()) if _STAMP_PART.fullmatch(head) else None
    if parsed is None:
        return None, b"", rest
    return parsed[0], parsed[1], rest


def cut_short(name: str, number: int, data: bytes, rest: str) -> str:
    """The warning for the input's last line cut short: what of it is decoded, what is not."""
    shown = rest if len(rest) <= 24 else rest[:24] + "..."
    whole = f"{len(data)} whole byte" if len(data) == 1 else f"{len(data)} whole bytes"
    if not data:
        kept = f"it holds no whole byte ({shown!r} is not read)"
    else:
        kept = f"its {whole} {'is' if len(data) == 1 else 'are'} decoded" + (f", the rest ({shown!r}) is not"
                                                                          if rest else "")
    return f"{name} line {number} is cut short (the input ends inside it, without a line end): {kept}"


class StampedLines:
    """The chunks of a one-frame-a-line text, and `recorded_until`: once read, the time of its last timed
    line, where its decode ends (pipeline.Dissector.feed), as a pcap's last record says (-w's copy closes
    there: app/inputs.py CopyEnd)."""

    def __init__(self, chunks: Iterator[Chunk]) -> None:
        self._chunks = chunks
        self.recorded_until: Stamp | None = None

    def __iter__(self) -> StampedLines:
        return self

    def __next__(self) -> Chunk:
        chunk = next(self._chunks)
        if chunk.data and chunk.time is not None:  # (as Dissector.feed's end)
            self.recorded_until = chunk.time  # type: ignore[assignment]
        return chunk


def read_lines(inp: Input, log: WarningLog, chunk_size: int, parse: LineParser) -> StampedLines:
    """One chunk per line that `parse` finds bytes in; a line it refuses (ValueError) ends the read
    with the line's number. Times of day are placed on their days (Days).

    The last line, when no line end closes it and it reads as a line cut short (the logger stopped while
    writing it, the file was copied while written), is the input cut short: its whole bytes are decoded,
    with a warning, as a pcap's cut record is (tshark: "cut short in the middle of a packet")."""
    return StampedLines(_parsed_lines(inp, log, chunk_size, parse))


def _parsed_lines(inp: Input, log: WarningLog, chunk_size: int, parse: LineParser) -> Iterator[Chunk]:
    days = Days()
    for number, line, ended in ended_lines(inp, chunk_size):
        try:
            parsed = parse(line, number)
        except ValueError as error:
            cut = None if ended else _cut_line(line, number, parse)
            if cut is None:
                raise SourceError(f"{inp.name} line {number}: {error}") from None
            time, data, rest = cut
            log.warn("truncated input", cut_short(inp.name, number, data, rest))
            if data:
                yield Chunk(data, days.place(time), False)
            return
        if parsed is not None:
            time, data = parsed
            yield Chunk(data, days.place(time), True)  # type: ignore[arg-type]


def read_hexdump(
    inp: Input, log: WarningLog, chunk_size: int, notation: Notation | None = None
) -> StampedLines:
    """One chunk per line with bytes; `notation` fixes hex or decimal (--format), else learned. Times
    of day are placed on their days (Days); a last line cut short as read_lines says."""
    known = notation if notation is not None else Notation()
    return read_lines(inp, log, chunk_size, lambda line, number: parse_line(line, known, f"line {number}"))
