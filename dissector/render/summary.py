"""One line per item, as tshark prints packets: number, time, slave, kind, info, CRC status."""
from __future__ import annotations

from typing import TYPE_CHECKING

from dissector.model import Frame, Item, Kind, Noise
from dissector.render.describe import info_text

if TYPE_CHECKING:
    from rich.text import Text

NOISE_PREVIEW = 16


def time_text(item: Item, base: float | None) -> str:
    if item.time is None:
        return "-"
    return f"{item.time - (base or 0.0):.6f}"


def crc_text(frame: Frame) -> str:
    if frame.crc == frame.crc_expected:
        return "CRC ok" if frame.mode == "rtu" else "LRC ok"
    check = "LRC" if frame.mode == "ascii" else "CRC"
    width = 2 if frame.mode == "ascii" else 4
    return f"{check} BAD (received 0x{frame.crc:0{width}X}, expected 0x{frame.crc_expected:0{width}X})"


def tail_text(frame: Frame) -> str:
    """Pairing and findings appended to the info column."""
    request = frame.request
    if not frame.notes and not frame.warnings and not frame.unanswered:
        if request is None:
            if frame.kind is Kind.REQUEST and not frame.broadcast:
                return ""
        elif frame.time is None:
            return f"[#{request.number}]"  # the common cases, kept cheap
    parts = []
    if frame.request is not None:
        rt = frame.response_time
        parts.append(f"[#{frame.request.number}" + (f", {rt * 1000:.1f} ms]" if rt is not None else "]"))
    elif frame.kind is not Kind.REQUEST:
        parts.append("[no request]")
    if frame.broadcast:
        parts.append("[broadcast]")
    if frame.unanswered:
        parts.append("[no response]")
    parts.extend(f"[{note}]" for note in frame.notes)
    parts.extend(f"[warning: {warning}]" for warning in frame.warnings)
    return " ".join(parts)


def noise_info(noise: Noise) -> str:
    preview = noise.raw[:NOISE_PREVIEW].hex(" ")
    more = "…" if noise.length > NOISE_PREVIEW else ""
    return f"{noise.length} bytes of noise at offset {noise.offset}: {preview}{more}"


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
        return f"{head}   - noise     {noise_info(item)}"
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
        text.append(noise_info(item), "vw3.noise")
        return text
    frame = item
    text.append(f"{frame.slave:>3} ", "vw3.slave")
    text.append(f"{frame.kind.value:<9} ", _KIND_STYLE[frame.kind])
    text.append(info_text(frame))
    tail = tail_text(frame)
    if tail:
        style = "vw3.warning" if frame.warnings or frame.unanswered else "vw3.pairing"
        text.append(" " + tail, style)
    text.append("  ")
    text.append(crc_text(frame), "vw3.crc.ok" if frame.crc_ok else "vw3.crc.bad")
    return text
