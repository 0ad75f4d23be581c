"""Long runs of lines or list items (a 2000-coil read, a 125-register block) written from cached pieces.

A run's item is a text that depends on the address (or label) followed by one that depends on the
value; both are kept by key, so a run costs a few C-level list operations and one join instead of an
f-string per item. Keys are 16-bit numbers or a profile's labels, so each cache stays small; it is
cleared when full all the same.
"""
from __future__ import annotations

from collections.abc import Iterable, Sequence
from itertools import chain, islice
from typing import Any

_MAX = 1 << 18


class Pieces:
    """template % key (or % (key, key)) by key, made on first sight."""

    __slots__ = ("template", "twice", "cache")

    def __init__(self, template: str, twice: bool = False) -> None:
        self.template = template
        self.twice = twice
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
            else:
                cache.update({key: template % key for key in missing})
            return list(map(cache.__getitem__, keys))


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
