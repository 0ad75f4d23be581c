"""Long runs of lines or list items (a 2000-coil read, a 125-register block) written from cached pieces.

A run's item is a text that depends on the address (or label) followed by one that depends on the
value; both are kept by key, so a run costs a few C-level list operations and one join instead of an
f-string per item. Keys are 16-bit numbers or a profile's labels, so each cache stays small; it is
cleared when full all the same.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from itertools import chain, islice
from operator import or_
from typing import Any

_MAX = 1 << 18


class Pieces:
    """template % key (or % (key, key), or % convert(key)) by key, made on first sight."""

    __slots__ = ("template", "twice", "convert", "cache")

    def __init__(self, template: str, twice: bool = False, convert: Callable[[Any], Any] | None = None) -> None:
        self.template = template
        self.twice = twice
        self.convert = convert
        self.cache: dict[Any, str] = {}

    def __call__(self, keys: Iterable[Any]) -> list[str]:
        cache = self.cache
        try:
            return list(map(cache.__getitem__, keys))
        except KeyError:
            if len(cache) >= _MAX:
                cache.clear()
            template = self.template
            missing = set(keys).difference(cache)
            if self.twice:
                cache.update({key: template % (key, key) for key in missing})
            elif self.convert is not None:
                convert = self.convert
                cache.update({key: template % convert(key) for key in missing})
            else:
                cache.update({key: template % key for key in missing})
            return list(map(cache.__getitem__, keys))


class AddressPieces:
    """template % address for 16-bit addresses, from a table filled 256 addresses at a time: a run of
    consecutive addresses is one slice of it."""

    __slots__ = ("template", "table", "filled")

    def __init__(self, template: str) -> None:
        self.template = template
        self.table: list[str] = [""] * 0x10000
        self.filled = bytearray(0x100)

    def _fill(self, blocks: Iterable[int]) -> None:
        filled, template = self.filled, self.template
        for block in blocks:
            if not filled[block]:
                base = block << 8
                self.table[base : base + 0x100] = [template % address for address in range(base, base + 0x100)]
                filled[block] = 1

    def __call__(self, addresses: Sequence[int]) -> list[str]:
        if type(addresses) is range and addresses.step == 1:  # a block that does not wrap: one slice
            start, stop = addresses.start, addresses.stop
            if start >= stop:
                return []
            self._fill(range(start >> 8, ((stop - 1) >> 8) + 1))
            return self.table[start:stop]
        self._fill({address >> 8 for address in addresses})
        return list(map(self.table.__getitem__, addresses))


def interleave(columns: Sequence[Iterable[str]], count: int) -> str:
    """columns[0][0] + columns[1][0] + ... + columns[0][1] + ...: `count` items of one piece per column."""
    width = len(columns)
    parts: list[Any] = [None] * (width * count)
    for index, column in enumerate(columns):
        parts[index::width] = column  # any iterable of exactly `count` texts
    return "".join(parts)


def bit_texts(pieces: Sequence[tuple[str, ...]], packed: bytes, count: int) -> Iterable[str]:
    """The text of each of the first `count` bits of `packed` (least significant first), from a table
    of 256 tuples of 8 texts, one tuple per byte value."""
    return islice(chain.from_iterable(map(pieces.__getitem__, packed)), count)


def byte_table(zero: str, one: str) -> list[tuple[str, ...]]:
    """The texts of the 8 bits of every byte value, least significant first (Modbus packs coil N+0 in bit 0)."""
    return [tuple(one if byte >> index & 1 else zero for index in range(8)) for byte in range(256)]


class BitRuns:
    """The texts of a run of bits at consecutive addresses, eight at a time: the text of the 8 bits of
    one byte depends on that byte and the first bit's address only, so a coil read of N bits costs
    N / 8 lookups instead of 2N pieces to interleave (item text: head % address + zero or one)."""

    __slots__ = ("head", "zero", "one", "cache")

    def __init__(self, head: str, zero: str, one: str) -> None:
        self.head, self.zero, self.one = head, zero, one
        # address << 8 | byte -> text: an int key, not a tuple (a quarter of an entry's ~330 bytes: the
        # max-size mix fills the cache, -V and --json peaked at 97 MB at 1 GB with tuples)
        self.cache: dict[int, str] = {}

    def _make(self, address: int, byte: int, width: int) -> str:
        head, zero, one = self.head, self.zero, self.one
        return "".join([head % (address + index) + (one if byte >> index & 1 else zero) for index in range(width)])

    def __call__(self, start: int, packed: bytes, count: int) -> str:
        """The text of bits start..start+count-1 (no wrap past 65535: the caller checks)."""
        whole = count >> 3
        cache = self.cache
        keys = list(map(or_, range(start << 8, (start + 8 * whole) << 8, 8 << 8), packed[:whole]))
        texts = list(map(cache.get, keys))
        if None in texts:
            if len(cache) >= _MAX:
                cache.clear()
            for index, key in enumerate(keys):
                text = texts[index]
                if text is None:
                    text = texts[index] = cache[key] = self._make(key >> 8, key & 0xFF, 8)
        rest = count & 7
        if rest:  # a last byte of fewer than 8 bits: made each time, it is at most 7 items
            texts.append(self._make(start + 8 * whole, packed[whole], rest))
        return "".join(texts)
