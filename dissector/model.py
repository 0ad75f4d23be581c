"""The frame model shared by every stage: framer -> pairing -> decoding -> annotator -> renderers.

Items are either a `Frame` (a CRC- or LRC-delimited Modbus ADU) or `Noise` (bytes that belong to no
frame). Every byte of an input ends up in exactly one item.
"""
from __future__ import annotations

import weakref
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from itertools import chain, islice
from typing import Any, overload

# The start of the noise reason the framers give an awaited answer cut by the end of the capture
# (RtuFramer._cut_answer); pairing notes it on the request.
CUT_ANSWER = "the capture ends inside the "


class Stamp(float):
    """A time in seconds since the epoch that keeps the integer nanoseconds its source wrote.

    pcap and pcapng store integer (micro/nano)seconds; as floats near 1.7e9 s their differences pick
    up noise (0.010157108306884766 for 10157 us). Two stamps subtract exactly from the integers, so
    response times and the time column show what the capture says. It is a float everywhere else.
    """

    ns: int

    def __new__(cls, ns: int) -> Stamp:
        stamp = super().__new__(cls, ns / 1_000_000_000)  # int / int rounds once, correctly
        stamp.ns = ns
        return stamp

    @classmethod
    def from_parts(cls, seconds: int, fraction: int, units: int) -> Stamp:
        """`fraction` in 1/`units` of a second, as pcap and pcapng store times."""
        return cls(seconds * 1_000_000_000 + fraction * 1_000_000_000 // units)

    def __sub__(self, other: object) -> float:
        if isinstance(other, Stamp):
            return (self.ns - other.ns) / 1_000_000_000
        return float.__sub__(self, other)  # type: ignore[operator]

    def __reduce__(self) -> tuple[type, tuple[int]]:
        return Stamp, (self.ns,)


def stamped_before(time: float, than: float) -> bool:
    """Is `time` earlier than `than` (time going backwards)? As floats, and by two Stamps' nanoseconds
    where their floats are equal (near 1.7e9 s a float cannot tell 100 ns apart)."""
    return time < than or time == than and time - than < 0


# (the time of the run of bytes with one time that holds an item's last byte, the characters from that run's first
# byte to the item's end): sent_in.
Tail = tuple[float, int]


class Kind(StrEnum):
    REQUEST = "request"
    RESPONSE = "response"
    EXCEPTION = "exception"
    NOISE = "noise"


class Note(str):
    """A note as JSON and -V keep it (the whole text), with the short form a summary line shows and
    whether it is a key event (a parameter that became protected or non-existent: highlighted)."""

    short: str
    key: bool

    def __new__(cls, text: str, short: str | None = None, key: bool = False) -> Note:
        note = super().__new__(cls, text)
        note.short = text if short is None else short
        note.key = key
        return note

    def __reduce__(self) -> tuple[type, tuple[str, str, bool]]:
        return Note, (str(self), self.short, self.key)


# What a device profile says about a register it read (Register.status); filters name these.
REGISTER_STATUSES = ("ok", "protected", "non-existent", "ambiguous")


@dataclass(slots=True)
class Register:
    """One 16-bit register value a frame carries, numbered from the request where needed.

    The annotation fields stay None until a device profile fills them in.
    """

    address: int | None
    value: int  # None only on an exception whose meaning tells the registers' status (p.38 exception 02)
    code: str | None = None
    name: str | None = None
    unit: str | None = None
    scaled: float | int | None = None
    text: str | None = None
    status: str | None = None
    source: str | None = None
    label: str | None = None  # display address (e.g. `40101` in PLC style); None: the number itself
    # A 32-bit map row spans two registers: its value is read on the first (`words` 2, `scaled`/`text`
    # of both words), the second says it continues it (`words` 0). 1: a register on its own.
    words: int = 1


class RegisterList(Sequence[Register]):
    """The registers of a block of values, read in bulk: no `Register` object until one is asked for.

    Decoding keeps the start and the values; a profile that only labels them (PLC-style addresses,
    no map row in the block) sets `labels` in bulk; -V and --json write such a block straight from
    these columns. Any other access makes the `Register` objects once and keeps them, so what a
    caller changes on one stays.
    """

    __slots__ = ("start", "values", "labels", "_registers")

    def __init__(self, start: int | None, values: list[int]) -> None:
        self.start = start
        self.values = values
        self.labels: list[str] | None = None  # display addresses, when a profile set them in bulk
        self._registers: list[Register] | None = None

    @property
    def plain(self) -> bool:
        """No Register object was made: the block is its address, value and label columns."""
        return self._registers is None

    @property
    def addresses(self) -> Sequence[int | None]:
        """Every register's address (wrapping past 65535), or None each when the start is unknown."""
        start, count = self.start, len(self.values)
        if start is None:
            return [None] * count
        if start + count <= 0x10000:
            return range(start, start + count)
        return [(start + index) & 0xFFFF for index in range(count)]

    def registers(self) -> list[Register]:
        """The Register objects, made on first use and kept."""
        registers = self._registers
        if registers is None:
            labels = self.labels
            if labels is None:
                registers = list(map(Register, self.addresses, self.values))
            else:
                registers = [
                    Register(address, value, label=label)
                    for address, value, label in zip(self.addresses, self.values, labels)
                ]
            self._registers = registers
        return registers

    def __len__(self) -> int:
        return len(self.values)

    @overload
    def __getitem__(self, index: int) -> Register: ...
    @overload
    def __getitem__(self, index: slice) -> list[Register]: ...
    def __getitem__(self, index: int | slice) -> Register | list[Register]:
        return self.registers()[index]

    def __iter__(self) -> Iterator[Register]:
        return iter(self.registers())

    def __eq__(self, other: object) -> bool:
        if isinstance(other, (RegisterList, list)):
            return self.registers() == list(other)
        return NotImplemented

    def __repr__(self) -> str:
        return f"RegisterList(start={self.start}, count={len(self.values)})"


@dataclass(slots=True)
class Bit:
    address: int | None
    value: int


# The 8 bits of each byte value, least significant first (Modbus packs coil N+0 in bit 0).
_BYTE_BITS = [tuple(byte >> index & 1 for index in range(8)) for byte in range(256)]


class BitList(Sequence[Bit]):
    """The bits of a packed status field, read in bulk: no `Bit` object until one is asked for.

    A 2000-coil read costs one table lookup per byte for `values`, and nothing at all when a view
    shows only the first few bits (the summary slices 32); `Bit` objects are made per item asked.
    """

    __slots__ = ("start", "packed", "count", "_values")

    def __init__(self, start: int | None, packed: bytes, count: int) -> None:
        self.start = start
        self.packed = packed
        self.count = count
        self._values: list[int] | None = None

    @property
    def values(self) -> list[int]:
        """Every bit value (0/1), in order."""
        values = self._values
        if values is None:
            values = self._values = list(islice(chain.from_iterable(map(_BYTE_BITS.__getitem__, self.packed)), self.count))
        return values

    @property
    def addresses(self) -> Sequence[int | None]:
        """Every bit's address (wrapping past 65535), or None each when the start is unknown."""
        start, count = self.start, self.count
        if start is None:
            return [None] * count
        if start + count <= 0x10000:
            return range(start, start + count)
        return [(start + index) & 0xFFFF for index in range(count)]

    def __len__(self) -> int:
        return self.count

    @overload
    def __getitem__(self, index: int) -> Bit: ...
    @overload
    def __getitem__(self, index: slice) -> list[Bit]: ...
    def __getitem__(self, index: int | slice) -> Bit | list[Bit]:
        if isinstance(index, slice):  # the summary's first 32: no more Bits than asked for
            start, packed = self.start, self.packed
            return [
                Bit(None if start is None else (start + position) & 0xFFFF, packed[position >> 3] >> (position & 7) & 1)
                for position in range(*index.indices(self.count))
            ]
        if index < 0:
            index += self.count
        if not 0 <= index < self.count:
            raise IndexError("bit index out of range")
        address = None if self.start is None else (self.start + index) & 0xFFFF
        return Bit(address, self.packed[index >> 3] >> (index & 7) & 1)

    def __iter__(self) -> Iterator[Bit]:
        return map(Bit, self.addresses, self.values)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, BitList):
            return list(self.addresses) == list(other.addresses) and self.values == other.values
        if isinstance(other, list):
            return list(self) == other
        return NotImplemented

    def __repr__(self) -> str:
        return f"BitList(start={self.start}, count={self.count})"


@dataclass(slots=True)
class DeviceObject:
    """A FC43/14 device identification object."""

    id: int
    name: str
    value: str
    text: str | None = None


@dataclass(slots=True, eq=False, weakref_slot=True)
class Frame:
    offset: int
    raw: bytes
    time: float | None
    kind: Kind
    slave: int
    function: int
    crc: int
    crc_expected: int
    mode: str = "rtu"
    number: int = 0
    request: Frame | None = None
    # A weak link back, so a request and its response form no reference cycle: decoded frames are
    # then freed as soon as they are written, instead of waiting for (and slowing) the cycle collector.
    response_ref: weakref.ReferenceType[Frame] | None = None
    unanswered: bool = False
    broadcast: bool = False
    warnings: list[str] = field(default_factory=list)
    tail: Tail | None = None  # where its last byte was heard, when not in its first byte's run (sent_in)
    # Filled by dissector.decode.fields.decode_frame.
    decoded: bool = False
    fields: Any = None
    start: int | None = None
    quantity: int | None = None
    subfunction: int | None = None
    registers: Sequence[Register] | None = None  # a RegisterList for blocks of values
    bits: Sequence[Bit] | None = None  # a BitList for packed status fields
    objects: list[DeviceObject] | None = None
    notes: list[str] = field(default_factory=list)
    # Filled by a device profile where the device's words differ from the spec's.
    function_text: str | None = None  # e.g. SEL-749M 60h "Read Parameter Information"
    exception_text: str | None = None  # e.g. ATV71 exception 6 "write refused: ... Forced local"
    subfunction_text: str | None = None  # e.g. VW3 A3 303 FC8 0Fh "broadcast messages received"
    span_label: str | None = None  # the start..end addresses as displayed (4X style), when not the numbers
    write_span_label: str | None = None  # FC23's written window so (its own beside the read one, span_label)
    # Profile `auto`: the choice (devices.selection.ProfileChoice) that gave this frame's slave the device
    # annotating it, with its reason; None for forced profiles and slaves without evidence.
    profile_choice: Any = None
    profile: str | None = None  # the device profile that annotated the frame (forced, auto's choice, or generic)
    # Read once (live, standard input): profile `auto` had not chosen this slave's device yet and still
    # may, so its values were named with spec semantics only and may read otherwise later (issue 27).
    provisional: bool = False

    @property
    def response(self) -> Frame | None:
        ref = self.response_ref
        return ref() if ref is not None else None

    @property
    def crc_ok(self) -> bool:
        return self.crc == self.crc_expected

    @property
    def length(self) -> int:
        return len(self.raw)

    @property
    def pdu(self) -> bytes:
        """Function code and data, without address and check."""
        if self.mode == "ascii":
            return self.raw_binary[1:-1]
        return self.raw[1:-2]

    @property
    def raw_binary(self) -> bytes:
        """The ADU as binary bytes (for ASCII frames: the hex pairs decoded, LRC included)."""
        if self.mode == "ascii":
            # (the hex pairs end at the CR, which may be lost; a line ends with LF or the character 08/03 set)
            return bytes.fromhex(self.raw[1:].split(b"\r", 1)[0].rstrip(b"\n").decode("ascii"))
        return self.raw

    @property
    def exception_code(self) -> int | None:
        if self.kind is Kind.EXCEPTION:
            pdu = self.pdu
            return pdu[1] if len(pdu) > 1 else None
        return None

    @property
    def response_time(self) -> float | None:
        if self.request is None or self.time is None or self.request.time is None:
            return None
        return self.time - self.request.time


@dataclass(slots=True)
class CapturedPart:
    """A record captured in part (a snapshot length shorter than the frame: framing/stream.py _cut_part): what
    its bytes tell, which -w, --stats, the pairing and the summary read (its item's reason says it in words)."""
    captured: int
    original: int  # its length on the line
    check: str  # "CRC" or "LRC": the check its bytes cannot pass
    slave: int | None = None  # None: not captured
    function: int | None = None
    answers: int | None = None  # the request it answers (decode/pairing.py)


@dataclass(slots=True, eq=False)
class Noise:
    offset: int
    raw: bytes
    time: float | None
    number: int = 0
    reason: str = "no valid frame"
    kind: Kind = Kind.NOISE
    warnings: list[str] = field(default_factory=list)
    part: CapturedPart | None = None  # a record captured in part, not line noise
    tail: Tail | None = None  # as Frame.tail

    @property
    def length(self) -> int:
        return len(self.raw)


Item = Frame | Noise


def sent_in(item: Item, char_time: float) -> float:
    """Seconds from the item's first byte's time until its last byte has been sent: a request's response
    timeout starts then (pairing.py), and a gap or a turnaround after it (render/bustiming.py).

    Its characters' time at the line's speed, `length x char_time`, unless its last byte came later than that
    allows: a frame with silences inside it (a slow line's bytes coming a few characters apart, an adapter's
    reads) ends when its last byte does: at the time of the run of bytes with one time (a chunk: a record, a
    dump line, a read's bytes timed alike) that holds it, plus that byte's place in the run (`tail`: the run's
    time and its characters up to the item's end; a run that starts before the item counts from its own start, as
    its stamp is its first byte's).
    Never less than its characters' time: stamps saying the last byte came sooner than that (a capturing
    clock's jitter between records, a line faster than the speed assumed) cannot make the
    line carry the item faster than its speed, and an item ends no earlier than it did before tails were kept;
    the overlap warning (bustiming.py) is what says that the speed is wrong. Time going backwards inside an item
    likewise leaves its characters' time; a stamp far later inside it (a clock step) ends it there, as the stamps
    say. The engine's twin: _summary.c frame_sent (bus_add takes the result: _bus.h); the plugin's: stream.lua
    sent_in."""
    sent = item.length * char_time
    tail, time = item.tail, item.time
    if tail is not None and time is not None:
        last = (tail[0] - time) + tail[1] * char_time  # (two Stamps subtract exactly)
        if last > sent:
            return last
    return sent


def up_to_items(items: list[Item], room: int) -> tuple[list[Item], int]:
    """The first `room` items (-c's cut: frames and noise runs alike, each a packet, as tshark -c counts
    packets), and the room left."""
    kept = items[: max(room, 0)]
    return kept, room - len(kept)


@dataclass(slots=True)
class Chunk:
    """Bytes as a source delivers them, with the time the first byte was seen (None when unknown)."""

    data: bytes
    time: float | None = None
    # True when the source knows a frame boundary follows (one frame per pcap record, say).
    boundary: bool = False
