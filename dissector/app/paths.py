"""Which path decodes an input for app/cli.py's Sinks: the compiled engine's (dissector/accel: the plain
summary, --stats and --report counted in C, or frames made in C), or the Python stages'."""
from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from dissector.model import Chunk, Item
from dissector.pipeline import Dissector
from dissector.render.pcapwriter import MICROS, NANOS

Fix = Callable[[list[Item]], list[Item]] | None


def decode_chunks(
    chunks: Iterable[Chunk],
    dissector: Dissector,
    sinks: Any,
    warn: Callable[[], None] = lambda: None,
    fix: Callable[[list[Item]], list[Item]] = lambda items: items,
) -> None:
    dissector.fix = fix  # (before the frames are decoded and annotated: Dissector.fix; this input's only)
    try:
        for chunk in chunks:
            sinks.accept(dissector.feed(chunk))
            warn()
            if sinks.done:
                return
        sinks.accept(dissector.finish())
        warn()
    finally:
        dissector.fix = None


def _drop(lines: bytes) -> None:
    """The summary lines of --stats' compiled path: only its counts are shown."""


def counted_only(sinks: Any) -> bool:
    """--stats and --report (either or both) are all that read the items: the engine may count them
    and feed the report (timedpath.count_input)."""
    return (sinks.stats is not None and not sinks.show and sinks.predicate is None and sinks.watch is None
            and sinks.pcap is None and sinks.frames_left is None)


def decode_one(chunks: Iterable[Chunk], mode: str, timed: bool, fix: Fix, dissector: Dissector, sinks: Any,
               annotate: Any | None, warn: Callable[[], None]) -> None:
    if mode == "rtu" and not timed and fix is None and (sinks.plain_summary_only or sinks.stats_only):
        from dissector.accel import fastsummary

        if fastsummary.available():
            def engine_lines(write: Callable[[bytes], None]) -> Callable[[bytes], None]:
                def lines(data: bytes) -> None:
                    sinks.valid_frames += 1  # the engine shows valid transactions only
                    write(data)
                return lines

            if sinks.plain_summary_only:
                path = fastsummary.SummaryPath(dissector, annotate, sinks.accept,
                                               engine_lines(sinks.output.write_encoded))
                fastsummary.summarize(chunks, path, warn)
                return
            store = sinks.stats.engine_store(sinks.bus)
            if store is not None:  # the engine counts what it shows; its lines are not wanted
                frames = store.frames
                path = fastsummary.SummaryPath(dissector, annotate, sinks.accept, _drop, store)
                fastsummary.summarize(chunks, path, warn)
                sinks.valid_frames += store.frames - frames
                return
    if mode == "rtu" and timed and fix is None:
        from dissector.accel import framespath, timedpath

        # (the engine writes the column in us or ns: a capture's in other units, cut to its precision as
        # tshark's, are Python's lines; a network or several-interface capture's references are its packets',
        # timefmt.py Clock.packets, which timedpath.TimedPath gives the engine)
        if (sinks.plain_summary_only and sinks.clock.units in (None, MICROS, NANOS)
                and timedpath.summarize_input(chunks, dissector, sinks, annotate, warn)):
            return  # pcap, pcapng: the compiled path
        if counted_only(sinks) and timedpath.count_input(chunks, dissector, sinks, annotate, warn):
            return  # --stats, --report of a pcap counted in the engine
        # (-c N: the engine is given only bytes that cannot hold the Nth item, framespath._Counted)
        if framespath.decode(chunks, dissector, sinks, annotate, warn):
            return  # framed in C, shown by Python
    decode_chunks(chunks, dissector, sinks, warn, fix or (lambda items: items))
