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
from dissector.model import Chunk, Item
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

    def feed(self, chunk: Chunk) -> list[Item]:
        return self.pairer.push(self.framer.feed(chunk))

    def finish(self) -> list[Item]:
        return self.pairer.push(self.framer.finish()) + self.pairer.finish()


def judged(annotate: Any) -> bytes:
    """A bit per (slave, function code) whose frames the selector must see, 32 bytes a slave."""
    selector = annotate.selector
    forced = annotate.per_slave
    identifying = set(_OBJECTS)
    for profile, _rows in selector.candidates:
        identifying |= profile.identifying_functions
    rows = bytearray(256 * 32)
    for slave in range(1, 256):
        if slave in forced:
            continue
        if not selector.settled(slave):
            rows[slave * 32 : slave * 32 + 32] = _ALL
            continue
        choice = selector.choice(slave)
        if choice is not None and choice.final:
            continue  # identified or forced: nothing changes it
        codes = set(identifying)
        profile = selector.profile(choice.profile) if choice is not None else None
        if profile is not None and profile.functions is not None:
            codes |= set(range(128)) - set(profile.functions)  # an answer it does not support
        for code in codes:
            rows[slave * 32 + (code >> 3)] |= 1 << (code & 7)
    return bytes(rows)


def choose(annotate: Any, chunks: Iterable[Chunk], framer: Any, pairer: Any,
           judge: Callable[[list[Item]], None], timeout: float | None) -> bool:
    """Run the first pass over `chunks` here; False (nothing read) when the engine is not available."""
    from dissector.accel import timedpath
    from dissector.accel.records import blocks_from_chunks

    if not fastsummary.available() or not timedpath.usable(Clock()):
        return False
    path = timedpath.TimedPath(_Framing(framer, pairer), None, Clock(), judge, _no_lines, timeout)  # type: ignore[arg-type]
    path.judge = judged(annotate)

    def again() -> None:
        path.judge = judged(annotate)

    path.on_hand_back = again
    timedpath.summarize_timed(blocks_from_chunks(chunks, framer.timing), path, lambda: None)
    return True


def _no_lines(lines: bytes) -> None:
    """The engine writes no line in judge mode."""
