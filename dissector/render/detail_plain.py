"""The plain -V text of one item, without the tree: what `vw3-decode -V` writes to a file or a pipe.

It gives render_plain(detail_tree(...)) byte for byte (tests/differential/test_render_fast.py) from
detail.py's line builders, and keeps the texts that repeat on a bus (a polled request's middle, a
block's address parts, a coil read's bits) so every frame does not pay for them again.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from dissector.model import BitList, Frame, Item, Kind, Register, RegisterList, Stamp
from dissector.render.detail import (
    PROVISIONAL_LINE,
    _EXCEPTION,
    _KIND_TEXT,
    _LINE_ADDRESS_HEADS,
    _LINE_LABEL_HEADS,
    _MIDDLES,
    _REGISTER_KEY,
    _WORDS,
    _build,
    _Detail,
    _head_key,
    _head_lines,
    _kept_text,
    _middle,
    _profile_line,
)
from dissector.render.summary import check_untyped
from dissector.render.pcapwriter import NANOS
from dissector.render.timefmt import MICRO_DIGITS, SECONDS, SINCE, arrival_line


def detail_text(item: Item, base: float | None = None, digits: int = MICRO_DIGITS) -> str:
    """The plain -V text of one item (render_plain(detail_tree(...)), without the tree); `digits`: its
    Arrival time's decimals (render/timefmt.py detail_digits)."""
    if type(item) is Frame:
        return plain_frame_text(item, base, digits)
    return "\n".join(_build(item, base, True, digits).texts)


# `, request (RTU)` and `\n    Modbus RTU` by (kind, mode): the fixed words of a frame's first lines.
_FRAME_WORDS: dict[tuple[Kind, str], tuple[str, str]] = {}


def _frame_words(kind: Kind, mode: str) -> tuple[str, str]:
    words = _FRAME_WORDS.get((kind, mode))
    if words is None:
        shown = mode.upper()
        words = _FRAME_WORDS[kind, mode] = (f", {_KIND_TEXT[kind]} ({shown})", f"\n    Modbus {shown}")
    return words


_RTU_WORDS = {kind: _frame_words(kind, "rtu") for kind in Kind}
# The middle (Slave to CRC) of a frame of registers by its bytes, its profile's words and span, its
# request's start, with the labels of plain columns or its Registers' keys kept beside it and compared:
# a polled block repeats its bytes (the polling mix: 64 distinct answers in 15,467). Up to 32 plain
# registers, 4 named (a drive's control word and setpoint repeat, its 9 status words less): longer
# blocks of random values would only fill the cache.
_BLOCK_MIDDLES: dict[tuple[Any, ...], tuple[Any, str]] = {}
_BLOCK_MIDDLES_MAX, _BLOCK_MIDDLE_REGISTERS, _NAMED_MIDDLE_REGISTERS = 1 << 12, 32, 4
# The middle of a frame of up to 64 bits (a module's coils and inputs, FC15's few) by its bytes, words,
# span and its bits' start and count (a coil read repeats its bytes until a coil is written).
_BIT_MIDDLES: dict[tuple[Any, ...], str] = {}
_BIT_MIDDLES_MAX, _BIT_MIDDLE_BITS = 1 << 10, 64  # (a 64-bit read's middle: ~1.2 kB)
# A longer block of plain columns (a relay's 40 registers, a meter's readings: new values every poll):
# its parts list with its head (Slave to span) and its lines' address parts in place, kept by the head's
# key, span and the block's start and size or labels; a poll's parts are a copy with its values put in.
_VALUE_PARTS: dict[tuple[Any, ...], list[Any]] = {}
_VALUE_PARTS_MAX = 1 << 10
_CRC_OK_TAILS: dict[int, str] = {}


def _block_middle(frame: Frame, registers: Sequence[Register], untyped: bool) -> str:
    """_middle's text for a frame of registers, kept (bounded: cleared when full)."""
    if type(registers) is RegisterList and registers.plain:
        start: int | None = registers.start
        lines: Any = registers.labels
    else:
        start = -1  # the addresses are in the registers' keys
        lines = tuple(map(_REGISTER_KEY, registers.registers() if type(registers) is RegisterList else registers))
    key = (frame.raw, frame.kind, frame.mode, frame.function_text, frame.subfunction_text, untyped,
           frame.span_label, start, frame.start, frame.quantity)  # (the window: detail_window)
    kept = _BLOCK_MIDDLES.get(key)
    if kept is not None and kept[0] == lines:
        return kept[1]
    if len(_BLOCK_MIDDLES) >= _BLOCK_MIDDLES_MAX:
        _BLOCK_MIDDLES.clear()
    part = _Detail(joined=True)
    _middle(part, frame)
    _BLOCK_MIDDLES[key] = (lines, text := "\n".join(part.texts))
    return text


def _values_middle(frame: Frame, registers: RegisterList) -> str | None:
    """_middle's text for a block of plain columns with its start known, a CRC that checks and head
    bytes _head_key keeps (a read's answer, FC16/FC23 requests), else None."""
    crc = frame.crc
    if crc != frame.crc_expected or registers.start is None:
        return None
    key = _head_key(frame)
    if key is None:
        return None
    values = registers.values
    labels = registers.labels
    span = frame.span_label
    block = (key, span, registers.start, len(values)) if labels is None else (key, span, tuple(labels))
    kept = _VALUE_PARTS.get(block)
    if kept is None:
        part = _Detail(joined=True)
        _head_lines(part, frame)
        if span is not None:  # as _body_lines writes it
            part.texts.append(f"        PLC references{' (read)' if frame.function == 23 else ''}: {span}")
        if frame.write_span_label is not None:
            part.texts.append(f"        PLC references (write): {frame.write_span_label}")
        kept = [None] * (2 * len(values) + 2)
        kept[0] = "\n".join(part.texts)
        kept[1:-1:2] = _LINE_ADDRESS_HEADS(registers.addresses) if labels is None else _LINE_LABEL_HEADS(labels)
        if len(_VALUE_PARTS) >= _VALUE_PARTS_MAX:
            _VALUE_PARTS.clear()
        _VALUE_PARTS[block] = kept
    parts = kept.copy()
    parts[2:-1:2] = map(_WORDS.__getitem__, values)
    line = _CRC_OK_TAILS.get(crc)
    if line is None:
        line = _CRC_OK_TAILS[crc] = f"\n        CRC: 0x{crc:04X} [CRC ok]"  # 16-bit keys: bounded
    parts[-1] = line
    return "".join(parts)


def plain_frame_text(frame: Frame, base: float | None, digits: int = MICRO_DIGITS) -> str:
    """_build(frame, base, joined=True), joined, with no _Detail for what needs none: every frame
    pays this, so its fixed lines are one format and a polled request's middle one lookup."""
    kind, mode = frame.kind, frame.mode
    words = _RTU_WORDS[kind] if mode == "rtu" else _frame_words(kind, mode)
    time = frame.time
    head = None
    if time is None:
        head = f"Frame {frame.number}: {len(frame.raw)} bytes at offset {frame.offset}{words[0]}{words[1]}"
    elif type(time) is Stamp and (since := SINCE.get(type(base))) and digits == MICRO_DIGITS:  # arrival_line's
        whole, rest = divmod(time.ns, NANOS)  # type: ignore[attr-defined]
        micros = round(rest / 1000)  # whole_micros
        if micros == 1_000_000:
            whole, micros = whole + 1, 0
        second = SECONDS.get(whole)
        if second is not None:
            head = (f"Frame {frame.number}: {len(frame.raw)} bytes at offset {frame.offset}{words[0]}\n"
                    f"    Arrival time: {second}.{str(1_000_000 + micros)[1:]} UTC "  # micros:06d
                    f"({(time.ns - base.ns) / NANOS:.6f}{since}{words[1]}")  # type: ignore[attr-defined]
    if head is None:
        head = (f"Frame {frame.number}: {len(frame.raw)} bytes at offset {frame.offset}{words[0]}\n"
                f"{arrival_line(time, base, digits)}{words[1]}")  # type: ignore[arg-type]
    registers = frame.registers
    listed = type(registers) is RegisterList
    # (a RegisterList's own len() is a Python call)
    size = len(registers.values) if listed else 0 if registers is None else len(registers)  # type: ignore[union-attr]
    middle = None
    if kind is not _EXCEPTION and frame.objects is None:
        bits = frame.bits
        untyped = bool(frame.notes) and check_untyped(frame)
        if bits is None:
            if not size:
                key = (frame.raw, kind, mode, frame.function_text, frame.subfunction_text, untyped,
                       frame.span_label, frame.start, frame.quantity)  # as _build keeps it
                middle = _kept_text(_MIDDLES, key, _middle, frame)
            elif listed and registers.plain:  # type: ignore[union-attr]
                if size <= _BLOCK_MIDDLE_REGISTERS:
                    middle = _block_middle(frame, registers, untyped)  # type: ignore[arg-type]
                elif not untyped:
                    middle = _values_middle(frame, registers)  # type: ignore[arg-type]
            elif size <= _NAMED_MIDDLE_REGISTERS:
                middle = _block_middle(frame, registers, untyped)  # type: ignore[arg-type]
        elif not size and type(bits) is BitList and bits.count <= _BIT_MIDDLE_BITS:
            key = (frame.raw, kind, mode, frame.function_text, frame.subfunction_text, untyped,
                   frame.span_label, bits.start, bits.count, frame.quantity)  # (the window: detail_window)
            middle = _kept_text(_BIT_MIDDLES, key, _middle, frame, _BIT_MIDDLES_MAX)
    if middle is None:
        detail = _Detail(joined=True)
        _middle(detail, frame)
        middle = "\n".join(detail.texts)
    texts = [head, middle]
    add = texts.append
    request = frame.request
    if request is not None:
        if time is None:
            add("    Request in frame: %d" % request.number)
        else:
            asked = request.time
            if type(time) is Stamp and type(asked) is Stamp:
                add("    Request in frame: %d\n    Response time: %.3f ms"
                    % (request.number, (time.ns - asked.ns) / NANOS * 1000))  # type: ignore[attr-defined]
            elif asked is not None:
                add("    Request in frame: %d\n    Response time: %.3f ms"
                    % (request.number, frame.response_time * 1000))  # type: ignore[operator]
            else:
                add("    Request in frame: %d" % request.number)
    ref = frame.response_ref
    if ref is not None:
        response = ref()
        if response is not None:
            add("    Response in frame: %d" % response.number)
    if frame.unanswered:
        add("    No response")
    if frame.profile_choice is not None:
        add(_profile_line(frame.profile_choice))
    elif frame.provisional:
        add(PROVISIONAL_LINE)
    if frame.notes:
        texts.extend([f"    Note: {note}" for note in frame.notes])
    if frame.warnings:
        texts.extend([f"    Warning: {warning}" for warning in frame.warnings])
    return "\n".join(texts)
