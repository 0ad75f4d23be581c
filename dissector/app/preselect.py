"""Profile `auto` over a whole file before its decode (issue 27): a value is named with the profile of
its slave, never raw beside scaled ones because the evidence came a few frames later.

The first pass frames and pairs the input exactly as the decode will (the same framer, baud and
timeout, so frame numbers and the choices' reasons agree) and hands the frames to the selector only;
nothing is annotated or rendered. Only the frames of a slave still being judged are decoded (registers
and identification objects are what the evidence is made of); a settled slave's frames can change its
choice by their function code alone (an identifying code, an unsupported one) or by an identification
(FC43), so the rest is framing and pairing. Memory stays flat: nothing is kept but the selector's
per-slave counts. Then the annotator is frozen on those choices for the decode.

Inputs read twice: regular files and --hex. Standard input and pipes are read once, as a live line
is: a slave's frames are named as its choice stands when they are decoded (the stderr line says where
it was made), which is what tshark's single pass does with the plugin too; the frames decoded before
the choice are marked provisional (Frame.provisional: `[provisional]`, `"provisional": true`).
"""
from __future__ import annotations

from collections.abc import Callable, Iterable

from dissector.decode.fields import decode_frame
from dissector.decode.pairing import Pairer
from dissector.devices.annotator import Annotator
from dissector.framing.ascii import AsciiFramer
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk, Frame, Item
from dissector.protocol import table

_OBJECTS = frozenset(entry.code for entry in table.FUNCTIONS if entry.response.name == "mei_response")


def choose_profiles(
    annotate: Annotator, chunks: Iterable[Chunk], mode: str, baud: int | None, timeout: float | None,
    fix: Callable[[list[Item]], list[Item]] | None = None,
) -> None:
    """The first pass over `chunks`; the annotator is then frozen on the choices it made. `fix`: --hex's
    typed bytes put back (app/hexinput.py HexInput.fix): a CRC typed bad is no evidence."""
    selector = annotate.selector
    if selector is None:
        return
    annotate.thaw()
    framer = (AsciiFramer if mode == "ascii" else RtuFramer)(*([] if baud is None else [baud]))
    pairer = Pairer(timeout=timeout, char_time=framer.timing.char_time)
    forced = annotate.per_slave
    settled = selector.settled
    observe = selector.observe

    def judge(items: list[Item]) -> None:
        for item in items if fix is None else fix(items):
            if not isinstance(item, Frame):
                continue
            slave = item.slave
            if slave in forced:
                continue
            if not settled(slave) or item.function in _OBJECTS:
                decode_frame(item)
            observe(item)

    if mode == "rtu" and fix is None:
        from dissector.accel import preselect as compiled  # the same pass, framed in C (issue 28)

        if compiled.choose(annotate, chunks, framer, pairer, judge, timeout):
            annotate.freeze()
            return
    for chunk in chunks:
        judge(pairer.push(framer.feed(chunk)))
    judge(pairer.push(framer.finish()) + pairer.finish())
    annotate.freeze()
