"""One line per item, as tshark prints packets: number, time, slave, kind, info, CRC status."""
from __future__ import annotations

from typing import TYPE_CHECKING

from dissector.model import Frame, Item, Kind, Noise
from dissector.protocol.rules import TEXTS
from dissector.render.describe import count_text, info_text

if TYPE_CHECKING:
    from rich.text import Text

NOISE_PREVIEW = 16


def time_text(item: Item, base: float | None) -> str:
    if item.time is None:
        return "-"
    return f"{item.time - (base or 0.0):.6f}"


_UNTYPED = ("no CRC typed", "no LRC typed")  # hexinput's note for bytes typed without their check


def check_untyped(frame: Frame) -> bool:
    """A `--hex` frame typed without its CRC (LRC): the check was computed here, never received, so
    no output may call it received or ok (summary, -V, --json, -T fields, -x; issue 27)."""
    return frame.crc == frame.crc_expected and bool(frame.notes) and any(
        note.startswith(_UNTYPED) for note in frame.notes
    )


def typed_bytes(item: Item) -> bytes:
    """The bytes an item came as: a frame's without the check computed for it when none was typed
    (what -x shows; in ASCII the two LRC characters before the CR LF)."""
    raw = item.raw
    if not isinstance(item, Frame) or not check_untyped(item):
        return raw
    if item.mode == "ascii":
        return raw[:-4] + raw[-2:] if raw.endswith(b"\r\n") else raw[:-2]
    return raw[:-2]


def crc_text(frame: Frame) -> str:
    if frame.crc == frame.crc_expected:
        if check_untyped(frame):
            # The check was computed here, not received: nothing was checked.
            return "CRC computed (none typed)" if frame.mode == "rtu" else "LRC computed (none typed)"
        return "CRC ok" if frame.mode == "rtu" else "LRC ok"
    check = "LRC" if frame.mode == "ascii" else "CRC"
    width = 2 if frame.mode == "ascii" else 4
    return f"{check} BAD (received 0x{frame.crc:0{width}X}, expected 0x{frame.crc_expected:0{width}X})"


# A frame read once (live, standard input) before profile `auto` chose its slave's device: its values
# are named with spec semantics only and may read otherwise once the device is known (issue 27).
PROVISIONAL = "[provisional]"

NOTES_BUDGET = 240  # characters of notes (and of warnings) a summary line shows; the rest is counted
# (-V and JSON have them all)


# The start of the warning of slave 0's answer after a broadcast (pairing.py), which names the broadcast.
_BROADCAST_ANSWERED = TEXTS["broadcast_answered"].partition("{")[0]


def _answers_broadcast(frame: Frame) -> bool:
    return any(warning.startswith(_BROADCAST_ANSWERED) for warning in frame.warnings)


def tail_parts(frame: Frame) -> list[tuple[str, str]]:
    """Pairing and findings appended to the info column, as (text, style name) pieces.

    Notes show their short form (devices/story.py) and, past NOTES_BUDGET characters, only their
    number; key events (a parameter that became protected) are styled apart from the dim pairing."""
    parts: list[tuple[str, str]] = []
    request = frame.request
    if request is not None:
        rt = frame.response_time
        parts.append((f"[#{request.number}" + (f", {rt * 1000:.1f} ms]" if rt is not None else "]"), "vw3.pairing"))
    elif frame.kind is not Kind.REQUEST and not _answers_broadcast(frame):  # (its warning names the request)
        parts.append(("[no request]", "vw3.pairing"))
    if frame.broadcast:
        parts.append(("[broadcast]", "vw3.pairing"))
    if frame.unanswered:
        parts.append(("[no response]", "vw3.warning"))
    if frame.provisional:
        parts.append((PROVISIONAL, "vw3.warning"))
    _findings(parts, frame)
    return parts


def _findings(parts: list[tuple[str, str]], frame: Frame) -> None:
    _budgeted(parts, [(f"[{getattr(note, 'short', note)}]", note) for note in frame.notes], "note")
    _budgeted(parts, [(f"[warning: {warning}]", warning) for warning in frame.warnings], "warning")


def findings_text(frame: Frame) -> str:
    """The notes and warnings of the tail, each ` [...]`, within NOTES_BUDGET as tail_parts shows them:
    the texts the compiled path takes from the Python stages (accel/fastsummary.py)."""
    parts: list[tuple[str, str]] = []
    _findings(parts, frame)
    return "".join(f" {text}" for text, _style in parts)


def _budgeted(parts: list[tuple[str, str]], texts: list[tuple[str, str]], what: str) -> None:
    """The first text always, more while they fit in NOTES_BUDGET characters, then their number."""
    used = 0
    for index, (text, item) in enumerate(texts):
        if used and used + len(text) > NOTES_BUDGET:
            rest = len(texts) - index
            parts.append((f"[+{rest} more {what}{'s' if rest > 1 else ''}]", "vw3.pairing"))
            return
        used += len(text)
        if what == "warning":
            parts.append((text, "vw3.warning"))
        else:
            parts.append((text, "vw3.key" if getattr(item, "key", False) else "vw3.note"))


def tail_text(frame: Frame) -> str:
    """Pairing and findings appended to the info column."""
    request = frame.request
    if not frame.notes and not frame.warnings and not frame.unanswered and not frame.provisional:
        if request is None:
            if frame.kind is Kind.REQUEST and not frame.broadcast:
                return ""
        elif frame.time is None:
            return f"[#{request.number}]"  # the common cases, kept cheap
    return " ".join(text for text, _ in tail_parts(frame))


def noise_text(length: int, offset: int) -> str:
    """`1 byte of noise at offset 8`, `4 bytes of noise at offset 0`."""
    return f"{count_text(length, 'byte')} of noise at offset {offset}"


def noise_info(noise: Noise) -> str:
    preview = noise.raw[:NOISE_PREVIEW].hex(" ")
    more = "…" if noise.length > NOISE_PREVIEW else ""
    if not preview:  # (a record captured in part with none of its bytes: nothing to list after a colon)
        return noise_text(noise.length, noise.offset)
    return f"{noise_text(noise.length, noise.offset)}: {preview}{more}"


def part_mark(noise: Noise) -> str:
    """` [captured in part (5 of its 9 bytes; slave 2, function 3): its CRC cannot be checked]` on the summary
    line of a record captured in part (framing/stream.py _cut_part), as tshark marks such a packet `[Packet size
    limited during capture]`; -V, --json and -T fields give it as the reason."""
    return f" [{noise.reason}]" if noise.part is not None else ""


_KIND_COLUMN = {kind: f"{kind.value:<9}" for kind in Kind}


def summary_line(item: Item, base: float | None = None, column: str | None = None) -> str:
    """`column`: the time column already formatted (render.timefmt.Clock); else relative to `base`."""
    time = item.time
    if column is not None:
        head = f"{item.number:>6} {column:>12}"
    elif time is None:
        head = f"{item.number:>6}            -"
    else:
        head = f"{item.number:>6} {time - (base or 0.0):>12.6f}"
    if isinstance(item, Noise):
        return f"{head}   - noise     {noise_info(item)}{part_mark(item)}"
    frame = item
    tail = tail_text(frame)
    return (
        f"{head} {frame.slave:>3} {_KIND_COLUMN[frame.kind]} {info_text(frame)}"
        f"{' ' + tail if tail else ''}  {crc_text(frame)}"
    )


_KIND_STYLE = {
    Kind.REQUEST: "vw3.request",
    Kind.RESPONSE: "vw3.response",
    Kind.EXCEPTION: "vw3.exception",
    Kind.NOISE: "vw3.noise",
}


def summary_text(item: Item, base: float | None = None, column: str | None = None) -> Text:
    """The same line as summary_line, styled for a terminal."""
    from rich.text import Text  # only a terminal needs rich: piped output starts faster without it
    text = Text(no_wrap=True, overflow="ellipsis")
    text.append(f"{item.number:>6} ", "vw3.number")
    text.append(f"{column if column is not None else time_text(item, base):>12} ", "vw3.time")
    if isinstance(item, Noise):
        text.append("  - noise     ", "vw3.noise")
        text.append(noise_info(item) + part_mark(item), "vw3.noise")
        return text
    frame = item
    text.append(f"{frame.slave:>3} ", "vw3.slave")
    text.append(f"{frame.kind.value:<9} ", _KIND_STYLE[frame.kind])
    text.append(info_text(frame))
    for part, style in tail_parts(frame):
        text.append(" ")
        text.append(part, style)
    text.append("  ")
    text.append(crc_text(frame), ("vw3.note" if check_untyped(frame) else "vw3.crc.ok") if frame.crc_ok else "vw3.crc.bad")
    return text
