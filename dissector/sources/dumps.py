"""Dumps of a raw byte stream made by `xxd`, `hexdump -C` (also `xxd -u`, `-g N`, `-a`) and `od -t x1`.

    00000000: 0c03 20d0 0003 0eef 0c03 0680 0000 0300  .. .............        xxd
    00000000  0c 03 20 d0 00 03 0e ef  0c 03 06 80 00 00 03 00  |.. .............|   hexdump -C
    *                                                    the line above repeats up to the next offset
    00000013                                             hexdump -C: the length, on a line of its own
    000000 0c 03 20 d0 00 03 0e ef 0c 03 06 80 00 00 03 00      od -A x -t x1 (od -t x1: octal offsets,
    0000020 02 17 e4                                              -A d: decimal; -t x1z: a >...< column)

The offset column says where each line's bytes belong: a `*` (both tools squeeze repeated lines)
is expanded, and a line that does not continue where the previous one ended is an error, since
bytes would be missing or doubled. The character column is ignored. The bytes are a stream, not one
frame a line: chunks carry no boundary and no time. The last line, cut short by the end of the input (no
line end: the dump copied while written), gives its whole bytes with a warning, as a hex dump's
(hexdump.read_lines).
"""
from __future__ import annotations

import re
from collections.abc import Callable, Iterator

from dissector.model import Chunk
from dissector.sources.common import Input, SourceError, WarningLog
from dissector.sources.hexdump import cut_short, ended_lines

_XXD = re.compile(r"([0-9a-fA-F]{6,16}): ((?:[0-9a-fA-F]{2})+(?: (?:[0-9a-fA-F]{2})+)*)(?:  .*)?")
_HEXDUMP_C = re.compile(r"([0-9a-fA-F]{8,16})  ((?:[0-9a-fA-F]{2} {1,2})*[0-9a-fA-F]{2}) *(?:\|.*\|)?")
_OFFSET_ONLY = re.compile(r"[0-9a-fA-F]{8,16}")
# od's offsets are in the radix -A chose (hex, 6 digits; octal by default or decimal, 7): read as hex, `000010` was the
# bytes 00 00 10 of a one-frame-a-line hex dump, every line's offset put into the stream (hunt 58).
_OD = re.compile(r"([0-9a-fA-F]{6,16})((?: [0-9a-fA-F]{2})+)(?: +>.*<)? *")
_OD_OFFSET_ONLY = re.compile(r"[0-9a-fA-F]{6,16}")
RADIXES = (8, 10, 16)  # (the order a 7-digit offset is tried in: od's default octal first)
# Bytes all the `*` lines of one dump may stand for. A squeezed run is idle line or one repeated
# poll; 16 MiB of it is far more than a dump pasted as text holds, and decodes in about a second.
# Beyond, a few bytes of text would cost minutes (58 bytes claimed 192 MiB), so the dump is refused.
MAX_EXPANSION = 1 << 24


def _parse(line: str, tool: str, radix: int = 16) -> tuple[int, bytes] | None:
    """(offset, bytes) of a dump line; (offset, b"") for an offset alone; None for `*`."""
    text = line.rstrip("\r\n")
    if text.strip() == "*":
        return None
    match = {"xxd": _XXD, "hexdump-C": _HEXDUMP_C, "od": _OD}[tool].fullmatch(text)
    alone = {"hexdump-C": _OFFSET_ONLY, "od": _OD_OFFSET_ONLY}.get(tool)
    if match is None and alone is not None and alone.fullmatch(text.strip()):
        return _offset(text.strip(), radix), b""
    if match is None:
        raise ValueError(f"not a {tool} line: {text[:60]!r}")
    return _offset(match.group(1), radix), bytes.fromhex(match.group(2).replace(" ", ""))


def _offset(text: str, radix: int) -> int:
    try:
        return int(text, radix)
    except ValueError:
        raise ValueError(f"offset {text!r} is not a number in base {radix}, as the dump's offsets before") from None


def _od_radix(text: str, position: int, squeezed: bool) -> int | None:
    """The radix of od's offsets, from the first one after 0: the one that says `position` (after a `*`,
    where the position is not known, the first radix it is a number in and past the position: `0000096`
    is -A d's). Six digits are -A x's alone: a hex dump missing a line is not read as octal."""
    radixes = (16,) if len(text) == 6 else RADIXES  # (od -A x writes 6 digits, -A o and -A d 7)
    if squeezed:
        return next((radix for radix in radixes if (_fits(text, radix) or 0) > position), None)
    return next((radix for radix in radixes if _fits(text, radix) == position), None)


def _fits(text: str, radix: int) -> int | None:
    try:
        return int(text, radix)
    except ValueError:
        return None


# The start of a dump line cut short: its offset, the hex it holds (the last number maybe cut), and where
# the cut line stops: at its end, or in the character column after the hex.
_CUT = {"xxd": re.compile(r"([0-9a-fA-F]{6,16}):((?: [0-9a-fA-F]+)*)(?: .*)?"),
        "hexdump-C": re.compile(r"([0-9a-fA-F]{8,16})((?: {1,2}[0-9a-fA-F]+)*)(?: +\|.*)? *"),
        "od": re.compile(r"([0-9a-fA-F]{6,16})((?: [0-9a-fA-F]+)*)(?: +>.*)? *")}
_CUT_OFFSET = re.compile(r"[0-9a-fA-F]{1,16}:?")


def _cut(line: str, tool: str, radix: int = 16) -> tuple[int | None, bytes, str] | None:
    """(offset, whole bytes, the cut digit) of the input's last line when it is one of the tool's lines cut
    short (no line end: the dump was copied while written); None when it is no such line."""
    text = line.rstrip("\r\n")
    if _CUT_OFFSET.fullmatch(text.strip()):
        return None, b"", text.strip()
    match = _CUT[tool].fullmatch(text)
    if match is None:
        return None
    groups = match.group(2).split()
    if any(len(group) % 2 for group in groups[:-1]):
        return None  # half a byte before the last number: not a cut
    digits = "".join(groups)
    offset = _fits(match.group(1), radix)
    if offset is None:
        return None
    return offset, bytes.fromhex(digits[: len(digits) & ~1]), digits[len(digits) & ~1 :]


def dump_tool(text: str, complete: bool) -> str | None:
    """"xxd", "hexdump-C" or "od" when every line of the sample is one of that tool's lines, else None (the
    input's last line may be one cut short). od's lines at offset 0 are its (no frame starts 00 00 00):
    the reader tells the radix of its offsets, and refuses a dump whose offsets do not go on in one."""
    lines = text.splitlines()
    unended = not text.endswith(("\n", "\r"))
    if not complete and unended:
        lines = lines[:-1]
    lines = [line for line in lines if line.strip()]
    if not lines:
        return None
    for tool in ("xxd", "hexdump-C", "od"):
        try:
            parsed = [_parse(line, tool) for line in lines[:-1]]
            try:
                parsed.append(_parse(lines[-1], tool))
            except ValueError:
                if not (complete and unended and len(lines) > 1 and _cut(lines[-1], tool) is not None):
                    raise
        except ValueError:
            continue
        if parsed[0] is not None and parsed[0][1] and (parsed[0][0] == 0 or _marked(lines, tool)):
            return tool
    return None


def _marked(lines: list[str], tool: str) -> bool:
    """Do the lines carry the tool's own marks, which no plain hex dump has (xxd's colon after the offset,
    which its lines parsed with; hexdump -C's |...| column on every line of bytes)? Then a dump whose
    first line is not at offset 0 (its head cut off) is still the tool's, and its reader says which bytes
    are missing, where a plain hex dump reader would stumble on the offsets or the character column."""
    if tool == "xxd":
        return True
    data_lines = [line for line in lines if line.strip() != "*" and not _OFFSET_ONLY.fullmatch(line.strip())]
    return bool(data_lines) and all(line.rstrip().endswith("|") for line in data_lines)


def _first_radix(line: str, position: int, squeezed: bool) -> int | None:
    """od's radix once a line's offset is not 0 (0 meanwhile: any radix reads it); None: no radix fits."""
    match = _OD.fullmatch(line.rstrip("\r\n"))
    text = match.group(1) if match else line.strip()
    if text == "*" or _fits(text, 16) in (0, None):
        return 0
    return _od_radix(text, position, squeezed)


# The first line of a dump in 16-bit words (BSD hexdump's default, od -x): `0000000 030c d020 ...`.
_WORDS = re.compile(r"0{6,16}(?: [0-9a-fA-F]{4})+ *")


def word_dump(text: str) -> bool:
    """Is the text a dump in 16-bit words? Their bytes are in the dumping machine's order (030c for 0c 03 on
    a little-endian one), which the text does not say: read as a hex dump, it gave swapped or invented bytes."""
    first = next((line for line in text.splitlines() if line.strip()), "")
    return _WORDS.fullmatch(first.rstrip("\r\n")) is not None


def refuse_words(inp: Input, log: WarningLog, chunk_size: int) -> Iterator[Chunk]:
    raise SourceError(f"{inp.name} line 1: a dump in 16-bit words (hexdump's default, od -x), whose byte order is"
                      " the dumping machine's: dump the bytes with hexdump -C, od -t x1 or xxd")
    yield  # (a reader: a generator)


def _repeated(line: bytes, count: int, chunk_size: int) -> Iterator[Chunk]:
    """`count` copies of a squeezed line, in chunks of about chunk_size bytes (not one a line)."""
    per_chunk = max(1, chunk_size // len(line))
    block = line * min(per_chunk, count)
    while count >= per_chunk:
        yield Chunk(block)
        count -= per_chunk
    if count:
        yield Chunk(line * count)


def read_dump(tool: str) -> Callable[[Input, WarningLog, int], Iterator[Chunk]]:
    def read(inp: Input, log: WarningLog, chunk_size: int) -> Iterator[Chunk]:
        position = expanded = 0
        repeat: bytes | None = None  # the line a `*` repeats
        squeezed = False
        cut: tuple[int | None, bytes, str] | None = None
        radix: int | None = 0 if tool == "od" else 16  # (0: od's, not told yet: by its first offset after 0)
        for number, line, ended in ended_lines(inp, chunk_size):
            if not line.strip():
                continue
            if radix == 0:
                radix = _first_radix(line, position, squeezed)
                if radix is None:
                    raise SourceError(f"{inp.name} line {number}: offset {line.split()[0]} does not follow the"
                                      f" {position} bytes before (bytes missing or repeated)")
            try:
                parsed = _parse(line, tool, radix or 16)
            except ValueError as error:
                cut = None if ended else _cut(line, tool, radix or 16)
                if cut is None:
                    raise SourceError(f"{inp.name} line {number}: {error}") from None
                log.warn("truncated input", cut_short(inp.name, number, cut[1], cut[2]))
                if cut[0] is None:
                    return
                parsed = cut[0], cut[1]
            if parsed is None:
                squeezed = True
                continue
            offset, data = parsed
            if squeezed and repeat:
                gap = offset - position
                if gap < 0 or gap % len(repeat):
                    raise SourceError(f"{inp.name} line {number}: offset {offset:#x} does not follow the * above")
                expanded += gap
                if expanded > MAX_EXPANSION:
                    raise SourceError(
                        f"{inp.name} line {number}: the * lines stand for {expanded} bytes by offset {offset:#x}, "
                        f"over the {MAX_EXPANSION >> 20} MiB a dump may expand to: convert it back to bytes "
                        "and decode those"
                    )
                yield from _repeated(repeat, gap // len(repeat), chunk_size)
                position = offset
            squeezed = False
            if offset != position:
                raise SourceError(
                    f"{inp.name} line {number}: offset {offset:#x} where {position:#x} was expected "
                    "(bytes missing or repeated)"
                )
            if data:
                yield Chunk(data)
                position += len(data)
                repeat = data

    return read
