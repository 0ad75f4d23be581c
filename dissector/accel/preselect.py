"""Profile `auto`'s first pass (app/preselect.py) through the compiled engine: the file's frames are
framed, paired and numbered in C, and the Python stages (framer, pairer, the selector) get only the
transactions the selector must see: a slave it still judges, a function code that identifies a device,
FC43 (identification objects), a function the slave's chosen profile does not support. The others change
nothing it keeps: a settled slave's counts only grow. The engine runs in `judge` mode (_judge.h), driven
by the timed path (timedpath.py), which hands the stream over and back as for the summary, so frame
numbers and the choices' reasons are the Python pass's; tests/differential/test_timed_summary.py and
test_preselect_compiled.py hold the choices equal.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from dissector.accel import fastsummary
from dissector.model import Chunk, Frame, Item
from dissector.protocol import table
from dissector.render.timefmt import Clock

_OBJECTS = frozenset(entry.code for entry in table.FUNCTIONS if entry.response.name == "mei_response")
_ALL = b"\xff" * 32


class _Framing:
    """What the timed path drives on the Python side here: the framer and the pairer, no decoding."""

    def __init__(self, framer: Any, pairer: Any) -> None:
        self.framer = framer
        self.pairer = pairer
        self.gaps = None
        self.slaves: set[int] = set()  # of the frames framed here since the engine last took the stream back

    def feed(self, chunk: Chunk) -> list[Item]:
        return self._seen(self.pairer.push(self.framer.feed(chunk)))

    def finish(self) -> list[Item]:
        return self._seen(self.pairer.push(self.framer.finish()) + self.pairer.finish())

    def _seen(self, items: list[Item]) -> list[Item]:
        self.slaves.update(item.slave for item in items if isinstance(item, Frame))
        return items


def judged(annotate: Any, rows: bytearray | None = None, slaves: Iterable[int] = range(1, 256)) -> bytes:
    """A bit per (slave, function code) whose frames the selector must see, 32 bytes a slave: made again
    in `rows` for `slaves` alone (the others' rows as they were)."""
    selector = annotate.selector
    forced = annotate.per_slave
    identifying = set(_OBJECTS)
    for profile, _rows in selector.candidates:
        identifying |= profile.identifying_functions
    rows = bytearray(256 * 32) if rows is None else rows
    for slave in slaves:
        if not 1 <= slave <= 255 or slave in forced:
            continue
        row = slave * 32
        if not selector.settled(slave):
            rows[row : row + 32] = _ALL
            continue
        rows[row : row + 32] = bytes(32)
        choice = selector.choice(slave)
        if choice is not None and choice.final:
            continue  # identified or forced: nothing changes it
        codes = set(identifying)
        profile = selector.profile(choice.profile) if choice is not None else None
        if profile is not None and profile.functions is not None:
            codes |= set(range(128)) - set(profile.functions)  # an answer it does not support
        for code in codes:
            rows[row + (code >> 3)] |= 1 << (code & 7)
    return bytes(rows)


def choose(annotate: Any, chunks: Iterable[Chunk], framer: Any, pairer: Any,
           judge: Callable[[list[Item]], None], timeout: float | None) -> bool:
    """Run the first pass over `chunks` here; False (nothing read) when the engine is not available."""
    from dissector.accel import timedpath
    from dissector.accel.records import blocks_from_chunks

    if not fastsummary.available() or not timedpath.usable(Clock()):
        return False
    framing = _Framing(framer, pairer)
    path = timedpath.TimedPath(framing, None, Clock(), judge, _no_lines, timeout)  # type: ignore[arg-type]
    rows = bytearray(256 * 32)
    path.judge = judged(annotate, rows)
    selector = annotate.selector
    made_for = (len(selector.candidates), selector.frozen)

    def again() -> None:
        # Only the slaves of the frames framed here can have changed (unless candidates were added): all
        # 255 made again at each hand-back cost 150 us, a file of frames the engine hands over one by one
        # (FC24, FC43) took 7x a normal capture's time (cost63).
        nonlocal made_for
        now = (len(selector.candidates), selector.frozen)
        slaves: Iterable[int] = range(1, 256) if now != made_for else framing.slaves
        made_for = now
        path.judge = judged(annotate, rows, slaves)
        framing.slaves.clear()

    path.on_hand_back = again
    timedpath.summarize_timed(blocks_from_chunks(chunks, framer.timing), path, lambda: None)
    return True


def _no_lines(lines: bytes) -> None:
    """The engine writes no line in judge mode."""
