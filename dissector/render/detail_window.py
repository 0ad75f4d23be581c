"""Three things -V says as the plugin's tree does (lua/src/show.lua), kept out of detail.py's line builders:

- the window a response takes from its request (data/modbus.toml [lift] `request.start`, `request.quantity`:
  a read's answer, FC23's, FC24's), which its bytes do not hold: `[Start address: 10]`, `[Quantity: 2]`,
  FC24's `[FIFO pointer address: 0]` (the start named as detail.FUNCTION_LABELS names it, as the plugin's
  START_WORDS); none where the request is not known;
- the hex of a field the plugin shows in decimal and hex (data/pdu_fields.toml base DEC_HEX: a status word,
  a mask, FC8's more-follows byte) written at the field's width in the frame, data/modbus.toml [layouts]
  (`Status: 0 (0x0000)` for FC11's 16-bit status word, `AND mask: 242 (0x00F2)`, `More follows: 0 (0x00)`,
  FC17's `Server id: 1 (0x01)`, each word of FC24's FIFO values and FC20's record `[0]: 1 (0x0001)`),
  as Wireshark writes a field's hex; other numbers keep their shortest hex (`Start address: 100 (0x64)`);
- the quantity of one that FC5's, FC6's and FC22's window has without its bytes counting it, `[Quantity: 1]`
  after the address (implied_quantity), as --json's `quantity`.
"""
from __future__ import annotations

from dissector.model import Frame, Kind
from dissector.render.describe import pdu_fields
from dissector.render.filter_fields import CATALOGUE
from dissector.protocol.spec import SPEC
from dissector.protocol.table import TABLE, layout_for, lift_of

_DIGITS = {"u8": 2, "u16": 4, "odd": 2, "words": 4}  # hex digits of a layout field type (`odd`: a register's
# lone byte; `words`: each word of a list, FC24's FIFO values, FC20's and FC21's record words)


def _widths() -> tuple[dict[tuple[int, Kind, str], int], dict[str, int]]:
    """({(function, kind, key): digits} of the DEC_HEX fields of each code's layout, {key: digits} of those
    of a part a field switches to (FC43's device id answer), where no two parts disagree)."""
    wanted: dict[str, set[str]] = {}  # layout: its DEC_HEX fields
    shows = pdu_fields()["pdu"]  # (data/fields.toml's fields of PDU fields: FC17's server id)
    for entry in [*pdu_fields().get("field", ()), *CATALOGUE]:
        if entry.get("base") in ("DEC_HEX", "HEX"):
            for pdu in entry.get("pdu", shows.get(entry.get("filter"), ())):
                layout, _, key = pdu.partition(".")
                wanted.setdefault(layout, set()).add(key)
    digits: dict[str, dict[str, int]] = {}  # layout: {key: digits}
    for layout, keys in wanted.items():
        for spec in SPEC.layouts.get(layout) or SPEC.parts.get(layout, ()):
            key, _, kind = spec.partition(":")
            kind = kind.partition("(")[0].partition("?")[0]  # (`u8?(byte_count)`: a u8 where there is room)
            if key in keys and kind in _DIGITS:
                digits.setdefault(layout, {})[key] = _DIGITS[kind]
    top: dict[tuple[int, Kind, str], int] = {}
    for function in TABLE:
        for kind in (Kind.REQUEST, Kind.RESPONSE):
            for key, width in digits.get(layout_for(function, kind).name, {}).items():
                top[function, kind, key] = width
    tops = {layout_for(function, kind).name for function in TABLE for kind in (Kind.REQUEST, Kind.RESPONSE)}
    nested: dict[str, int] = {}
    for layout, keys in digits.items():
        if layout not in tops:
            for key, width in keys.items():
                nested[key] = width if nested.get(key, width) == width else 0
    return top, {key: width for key, width in nested.items() if width}


HEX_WIDTHS, NESTED_HEX_WIDTHS = _widths()


def hex_width(frame: Frame, key: str) -> int:
    """The hex digits -V writes a top-level int field of `frame` with (0: its shortest hex)."""
    return HEX_WIDTHS.get((frame.function, frame.kind, key), 0)


def window_lines(frame: Frame, labels: dict[tuple[int, str], str]) -> list[str]:
    """`[Start address: N]` (or the function's own word) and `[Quantity: N]` of a response's window where its
    request gave it (`labels`: detail.FUNCTION_LABELS); without its request, the quantity its byte count
    gives ([lift] unpaired_unit), as --json's `quantity` and the plugin's tree."""
    if frame.kind is not Kind.RESPONSE:
        return []
    lift = lift_of(frame.function, frame.kind)
    if lift is None:
        return []
    lines = []
    if lift.start == "request.start" and frame.start is not None:
        title = next((label for (function, _key), label in labels.items() if function == frame.function),
                     "Start address")
        lines.append(f"        [{title}: {frame.start}]")
    if lift.quantity == "request.quantity" and frame.quantity is not None:
        lines.append(f"        [Quantity: {frame.quantity}]")
    return lines


def implied_quantity(frame: Frame) -> tuple[str, str] | None:
    """(the field it follows, `[Quantity: 1]`) where a frame's window is one address its bytes do not count
    (data/modbus.toml [lift] `quantity = 1`: FC5, FC6, FC22), as the plugin's tree shows it (show.lua
    add_window); None elsewhere."""
    lift = lift_of(frame.function, frame.kind)
    if lift is None or type(lift.quantity) is not int or frame.quantity is None or lift.start is None:
        return None
    return lift.start, f"        [Quantity: {frame.quantity}]"

