"""pymodbus debug logs (pymodbus_apply_logging_config(logging.DEBUG), or any logging set to DEBUG): the
bytes its transport wrote and read, one `send:` or `recv:` line each, in pymodbus's `0x..` notation.

    2026-12-07 14:53:39,224 DEBUG transport:357 send: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
    2026-12-07 14:53:39,225 DEBUG transport:308 recv: 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xda 0xd4 extra data:
    2026-12-07 14:53:39,225 DEBUG base:76 Processing: 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xda 0xd4
    DEBUG:pymodbus.logging:send: 0x7 0x3 ...        (logging.basicConfig's format: untimed)

Only `send:` and `recv:` are the wire (its async transport's, which a server and an async client use; a sync
client logs no bytes but the framer's, and is said to): `Processing:` is the framer's buffer (bytes a recv line gave, again),
`extra data:` (`old_data:` in earlier 3.x versions) after a recv the bytes held over from before it (given by an
earlier recv), and pymodbus's
other lines (connecting, decoded PDUs, tracebacks) are passed over. Each line is timed by the stamp it starts
with (logging's `2026-12-07 14:53:39,225`: to the millisecond, when the call returned). A send is a whole frame
(pymodbus writes a frame at once); a recv is what one read returned, maybe part of a frame, so a run of
recv lines ends a frame only where the program turns to sending (or the log ends): the line after decides.
The direction decides nothing more: the framer tells a request from an answer, as for any capture.

A client and a server logging in one process (a test bench) log each frame twice: the sender's send line and
the other end's recv of the same bytes. Such a log's every recv run reads back the bytes sent since the run before
(_Mirror), and pymodbus decodes them as a request (the server reading its client's) and as a response (the client
reading its server's): once both are seen, such runs are the other end's reads, passed over, the frame the send's,
at its time. Until then they are held (the first request of a log begun after both ends connected was shown twice
before). A recv run of other bytes (a device's answer, a request from another process) says the log is not of
that kind: a one-end log keeps its echoes (an FC6 answer is its request's bytes again), and so does a gateway
that forwards the exact bytes it read (its first recv reads what no send gave). Without decode lines, the ends'
own lines (the server's `Server listening.`, the client's `Connecting to ...`) tell the same.
"""
from __future__ import annotations

import re
from collections.abc import Iterator

from dissector.model import Chunk, Stamp
from dissector.protocol import table
from dissector.protocol.crc import crc_bytes
from dissector.sources.common import Input, SourceError, WarningLog
from dissector.sources.hexdump import Days, HexLineError, StampedLines, _timestamp, cut_short, ended_lines

# `send: 0x7 0x3 ...`, `recv: 0x7 ... extra data: 0x..` (also upper case, as pymodbus 2 wrote them), after the
# logging prefix: a space, or the `:` of basicConfig's `DEBUG:pymodbus.logging:send: ...`.
_WIRE = re.compile(r"(?:^|[\s:])(send|recv): ?(.*)$", re.IGNORECASE)
_BYTE = re.compile(r"0x([0-9A-Fa-f]{1,2})")
_NUMBER = re.compile(r"0x[0-9A-Fa-f]*")
# What follows the bytes: pymodbus 3.6 on `extra data: 0x..`, earlier 3.x `old_data: 0x.. addr=None`.
_LABEL = re.compile(r"(?:extra|[A-Za-z_]\w*[:=])")
_BUFFER = re.compile(r"\bProcessing: 0x")
# pymodbus's own line format (its pymodbus_apply_logging_config), for a log whose first lines carry no bytes.
# What pymodbus says of the end that logs: a decoded request was read by a server, a decoded response by a client.
_DECODED = re.compile(r"\bdecoded PDU .* -> \w*?(Request|Response)\(")
_SERVER, _CLIENT = re.compile(r"\bServer listening\.|\bAwaiting connections "), re.compile(r"\bConnecting to ")
_OWN = re.compile(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d,\d{3} (?:DEBUG|INFO |WARNING|ERROR|CRITICAL) \w+:\d+ .*")


def wire_line(line: str) -> tuple[str, list[str], bool] | None:
    """("send" or "recv", the byte tokens, whether a label follows them: they are whole) of a line with bytes
    pymodbus wrote or read, else None. A token neither a number nor a label is kept, for the reader to name."""
    found = _WIRE.search(line.rstrip("\r\n"))
    if found is None:
        return None
    tokens = found.group(2).split()
    if not tokens or _BYTE.fullmatch(tokens[0]) is None:
        return None
    count = next((index for index, token in enumerate(tokens) if not _NUMBER.fullmatch(token)), len(tokens))
    labelled = count < len(tokens) and _LABEL.match(tokens[count]) is not None
    return found.group(1).lower(), tokens[:count] if labelled else tokens, labelled


def looks_like_pymodbus(text: str, complete: bool) -> bool:
    """Does `text` (the input's first bytes; its last line left out unless `complete`) hold a send:/recv:
    line, or a line in pymodbus's own log format?"""
    lines = text.splitlines()
    if not complete and not text.endswith(("\n", "\r")):
        lines = lines[:-1]
    return any(wire_line(line) is not None or _OWN.fullmatch(line) for line in lines)


def _bytes(tokens: list[str], where: str) -> bytes:
    for token in tokens:
        if _BYTE.fullmatch(token) is None:
            raise SourceError(f"{where}: {token[:24]!r} is not a byte in pymodbus's 0x.. notation")
    return bytes(int(token, 16) for token in tokens)


def _time(line: str, where: str) -> Stamp | None:
    """The stamp the line starts with (logging's date and time, or a time of day), None for none."""
    try:
        return _timestamp(line.split()[:2])[0]
    except HexLineError as error:  # (one that does not exist, `2026-02-30 ...`: the line is refused, as a dump's)
        raise SourceError(f"{where}: {error}") from None


def read_pymodbus(inp: Input, log: WarningLog, chunk_size: int) -> StampedLines:
    return StampedLines(_chunks(inp, log, chunk_size))


def _chunks(inp: Input, log: WarningLog, chunk_size: int) -> Iterator[Chunk]:
    days = Days()
    run: list[Chunk] = []  # recv lines' bytes, until the next wire line says whether a frame ends there
    sent = bytearray()  # the bytes of the send lines since the last recv run
    mirror = _Mirror()
    found = buffered = False
    for number, line, ended in ended_lines(inp, chunk_size):
        wire = wire_line(line)
        if wire is None:
            buffered = buffered or _BUFFER.search(line) is not None
            _ends(line, mirror.ends if run else mirror.startup)
            continue
        direction, tokens, labelled = wire
        if not ended and not labelled:  # the last number may be cut (`0xd` of `0xda`): not read
            data = _bytes(tokens[:-1], f"{inp.name} line {number}")
            log.warn("truncated input", cut_short(inp.name, number, data, tokens[-1]))
        else:
            data = _bytes(tokens, f"{inp.name} line {number}")
        found = True
        chunk = Chunk(data, days.place(_time(line, f"{inp.name} line {number}")), True)  # type: ignore[arg-type]
        if direction == "send":
            if run:
                yield from mirror.run(run, sent)
                run, sent = [], bytearray()
            if data and not sent:
                yield from mirror.sending(data)
            if data:
                sent += data
                yield from mirror.give([chunk])
        elif data:
            run.append(Chunk(data, chunk.time, False))
            if not sent.startswith(b"".join(piece.data for piece in run)):  # (no read-back: held no longer)
                mirror.mirrored = False if mirror.mirrored is None else mirror.mirrored
                yield from mirror.give(run[:-1])
                del run[:-1]
    if run:
        yield from mirror.run(run, sent)
    yield from mirror.give([], True)
    if not found and buffered:
        log.warn("empty", f"{inp.name}: no send: or recv: line, only the framer's Processing: buffers, which repeat "
                          "bytes and hold no request sent (pymodbus's sync clients log no more): log an async client "
                          "or the server, or capture the line")
    elif not found:  # (--format pymodbus on another text: every line passed over, said, not silent)
        log.warn("empty", f"{inp.name}: no send: or recv: line of a pymodbus debug log")


HELD_RUNS = 64  # read-backs held undecided at most (memory bounded): past them the log is one end's


class _Mirror:
    """Does the log show both ends of one link (the module's docstring)? `mirrored`: None while not known. The
    chunks after a recv run reading back the sends before it are held while it is not known."""

    def __init__(self) -> None:
        self.mirrored: bool | None = None
        self.startup: set[str] = set()  # the ends the ends' own lines show
        self.ends: set[str] = set()  # the ends decoding the read-backs (what the decode lines after a run say)
        self.kinds: set[str] = set()  # what read-backs were decoded as
        self.held: list[tuple[list[Chunk], bool]] = []  # (chunks, a read-back's) in order
        self.candidates = 0
        self.backs: list[bytes] = []  # the read-backs' bytes while it is not known (_one_end)
        self.phases = {0, 1}  # where a log of both ends of echoes only could pair its read-backs (_one_end)
        self.decoded: set[str] = set()  # what the last read-back was decoded as

    def run(self, run: list[Chunk], sent: bytearray) -> Iterator[Chunk]:
        """A recv run, a frame ending after its last chunk (the program turns to sending, or the log ends)."""
        chunks = [*run[:-1], Chunk(run[-1].data, run[-1].time, True)]
        ends, self.ends = self.ends, set()
        if b"".join(chunk.data for chunk in run) != sent:
            self.mirrored = False if self.mirrored is None else self.mirrored
            yield from self.give(chunks)
            return
        if self.mirrored is None:
            self.kinds |= ends
            self.held.append((chunks, True))
            self.candidates += 1
            if len(self.kinds) == 2 or (not self.kinds and len(self.startup) == 2) or _sent_by_a_server(sent):
                self.mirrored = True  # (no decode line: the ends' own lines, or the bytes read back)
            elif self._one_end(bytes(sent), ends):
                self.mirrored = False
            yield from self.give([])
        elif not self.mirrored:
            yield from self.give(chunks)

    def _one_end(self, data: bytes, ends: set[str]) -> bool:
        """Do the read-backs so far (the last `data`, decoded as `ends`) say the log is one end's, whose echoes
        (an FC5/FC6/FC8 answer repeats its request) read back its sends? Both ends of echoes send and read back
        each frame twice, the request and its echo: in pairs of equal bytes, decoded as a request then a response.
        Two read-backs in a row decoded alike, or no pairing left (`A B C`: neither A=B nor B=C: sending), are one
        end's: it is known at its second reply or third send, not held up to HELD_RUNS (late through a live pipe:
        tail -f log | vw3-decode -)."""
        decoded, self.decoded = self.decoded, ends
        backs = self.backs
        backs.append(data)
        if len(backs) > 1 and backs[-1] != backs[-2]:
            self.phases.discard(len(backs) % 2)  # (the pair of the two last cannot be one frame's)
        return not self.phases or (len(ends) == 1 and ends == decoded)

    def sending(self, data: bytes) -> Iterator[Chunk]:
        """The first send after a read-back run, `data`: the next read-back's first bytes. Not the bytes read back
        last, it pairs with none of them (_one_end); what is held once that tells."""
        backs = self.backs
        if self.mirrored is None and backs and len(backs) == self.candidates and not backs[-1].startswith(data):
            self.phases.discard((len(backs) + 1) % 2)
            if not self.phases:
                self.mirrored = False
                yield from self.give([])

    def give(self, chunks: list[Chunk], end: bool = False) -> Iterator[Chunk]:
        """`chunks` when nothing is held, else after what is held; what is held once it is known (or at the end)."""
        if self.mirrored is None and (end or self.candidates > HELD_RUNS):
            self.mirrored = len(self.kinds | self.startup) == 2
        if self.mirrored is None:
            if chunks:
                self.held.append((chunks, False))
            return
        for held, read_back in self.held:
            if not (read_back and self.mirrored):
                yield from held
        self.held.clear()
        yield from chunks


def _sent_by_a_server(data: bytearray) -> bool:
    """Are the bytes read back, sent since the run before, an RTU frame (its CRC good) no answer repeats whole: an
    exception, or a function whose answer does not repeat its request (a read: protocol/table.py `echo`) or not
    whole (FC15/FC16 answer 8 bytes of a longer request)? A one-end log reads back only its requests' echoes:
    these were read by the other end of the link, in the same log (a log of both ends without decode lines nor
    the ends' own lines showed each frame twice)."""
    if len(data) < 4 or crc_bytes(bytes(data[:-2])) != data[-2:]:
        return False
    if data[1] & 0x80:
        return True
    entry = table.TABLE.get(data[1])
    if entry is None:
        return False
    return not entry.echo or entry.request.length != entry.response.length


def _ends(line: str, ends: set[str]) -> None:
    """The end a line of pymodbus's own shows logging (a server, a client), added to `ends`."""
    decoded = _DECODED.search(line)
    if decoded is not None:
        ends.add(decoded.group(1))
    elif _SERVER.search(line):
        ends.add("Request")
    elif _CLIENT.search(line):
        ends.add("Response")
