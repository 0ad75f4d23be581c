"""The parts of a display filter tshark 4.0.17 reads with rules of their own, parsed for render/filters.py
(p is its parser): slices (`raw[0:2]`) and sets (`slave in {3, 4, 10..12}`)."""
from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from dissector.render.filter_fields import _TYPE_WORDS
from dissector.render.filter_lexer import Token, strtol
from dissector.render.filter_match import cut_bytes
from dissector.render.filter_values import negative_for_unsigned

# One range of a slice: start:length, start:, :length, first-last or an offset (a start < 0: from the end)
_RANGE = re.compile(r"\s*([-+]?\w+)?\s*(?:(:)\s*([-+]?\w+)?|-\s*([-+]?\w+))?\s*")


def parse_slice(p: Any, field: str, ftype: str) -> Callable[[bytes], bytes | None] | None:
    """`raw[0:2]` (start:length), `raw[0-1]` (first-last), `raw[:2]`, `raw[2:]`, `raw[-2:]`, `raw[4]`,
    several joined by commas (`raw[0,2:2]`), slices of slices (`raw[0:2][1]`), as tshark 4.0.17 reads
    them (blanks inside, numbers as C's strtol: 0x1, 01); None: no slice follows."""
    if p.token.kind != "slice":
        return None
    if ftype not in ("bytes", "str"):
        raise p.error(f"{field} is a {_TYPE_WORDS[ftype]}: only bytes (raw) and texts take a slice")
    cuts = []
    while p.token.kind == "slice":
        token = p.advance()
        ranges = [_slice_range(p, part, token) for part in token.text[1:-1].split(",")]
        cuts.append(ranges)

    def cut(data: bytes) -> bytes | None:
        for ranges in cuts:
            data = cut_bytes(data, ranges)
            if data is None:
                return None
        return data

    return cut


def _slice_range(p: Any, part: str, token: Token) -> tuple[int | None, bool, int | None, int | None]:
    """One range of a slice: (start, colon, length, last), refused as tshark 4.0.17 refuses it."""
    match = _RANGE.fullmatch(part)
    if match is None or not part.strip():
        raise p.error(f"{part.strip()!r} is not a valid range: a slice is [start:length], [first-last], "
                         "[start:], [:length] or [offset], as raw[0:2]", token)
    start_text, colon, length_text, last_text = match.groups()

    def value(text: str | None) -> int | None:
        if text is None:
            return None
        number = strtol(text)
        if number is None:
            raise p.error(f"{text!r} is not a valid number (in the slice {token.text})", token)
        if not -(1 << 31) <= number < 1 << 31:
            raise p.error(f"{text!r} causes an integer overflow (in the slice {token.text})", token)
        return number

    start, length, last = value(start_text), value(length_text), value(last_text)
    written = part.strip()
    if length is not None and length <= 0:
        raise p.error(f"Range {written} isn't valid because length {length} isn't positive", token)
    if last is not None and start is not None and start >= last:
        raise p.error(f"Range {written} isn't valid because {start} is greater or equal than {last}",
                         token)
    return start, colon is not None, length, last


def parse_set(p: Any, field: str, ftype: str) -> list[tuple[Any, Any]]:
    """`{a, b, c..d}`: a list of (low, high) pairs. As tshark 4.0.17 reads a set, members are separated
    by commas (`{3 4}`, `{3,}` and `{}` refused) and a range stands inside braces (`in 3..4` refused);
    a bound may be a field or a function's result (an Operand: filter_ops.set_test)."""
    if ftype == "list":
        raise p.error(f"in needs a number or text field; {field} is a {_TYPE_WORDS[ftype]}")
    if not p.at("punct", "{"):
        hint = ""
        low, dots, high = (p.tokens[p.index:] + [p.tokens[-1]] * 2)[:3]
        if dots.text == ".." and high.kind != "end":
            hint = f" (a range goes in a set: {{{low.text}..{high.text}}})"
        raise p.unexpected(f"expected {{ after in, a set such as {{3, 4, 8400..8402}}{hint}")
    opening = p.advance()
    members: list[tuple[Any, Any]] = []
    while True:
        if p.token.kind == "end":
            raise p.error(f"expected }} to close the {{ at column {opening.position + 1}")
        if p.at("punct", "}"):
            raise p.unexpected("a set holds values separated by commas, none after the last "
                                  "(as tshark 4.0)" if members else "a set holds at least one value")
        members.append(_parse_member(p, field, ftype))
        if p.at("punct", "}"):
            break
        if p.token.kind == "end":
            raise p.error(f"expected }} to close the {{ at column {opening.position + 1}")
        if not p.at("punct", ","):
            raise p.unexpected("set members are separated by commas, as tshark 4.0 takes them "
                                  "({3, 4})")
        p.advance()
    p.advance()
    members = [member for member in members if REFERENCE not in member]
    # A negative bound for an unsigned field, as in tshark 4.0.17: a member that holds no value; under all its
    # comparison holds for every value (None: the bound's; all slave in {-1..5} is all slave <= 5, as all
    # slave > -1 holds wherever slave is: filter_values.negative_for_unsigned).
    if getattr(p, "every", False):
        return [(None if negative_for_unsigned(field, low) else low, None if negative_for_unsigned(field, high)
                 else high) for low, high in members]
    return [member for member in members if not any(negative_for_unsigned(field, bound) for bound in member)]


REFERENCE = object()  # a member's bound that is a field reference (${slave}): it holds no value, nor its member


def _parse_bound(p: Any, field: str, ftype: str) -> Any:
    if p.token.kind == "reference":
        p.parse_reference()  # (a field, or refused as tshark refuses a macro)
        return REFERENCE
    if p.token.kind == "name" and (p.is_field(p.token) or p.tokens[p.index + 1].text == "(") or p.at("op", "-", "+"):
        return p.parse_member()  # (a field or a function, signed or not: value in {address, -slave}, filter_ops.set_test)
    value_token = p.token
    value = p.parse_value(field, ftype)
    p._check_choice(field, value, value_token)
    return value


def _parse_member(p: Any, field: str, ftype: str) -> tuple[Any, Any]:
    low = _parse_bound(p, field, ftype)
    if p.at("punct", ".."):
        if ftype not in ("number", "any", "bool"):
            raise p.error(f"ranges need numbers; {field} is a text")
        p.advance()
        return (low, _parse_bound(p, field, ftype))
    return (low, low)


def parse_layer(p: Any) -> bool:
    """`slave#1`, `slave#[1-2]`: the layers of a field, as tshark 4.0.17 reads them (p's token after the
    field's name); whether they hold the first, the only one vw3-decode has (an item is one vw3 layer).
    True when none follows."""
    if p.token.kind != "layer":
        return True
    return layer_holds_first(p, p.advance())


def layer_holds_first(p: Any, token: Token) -> bool:
    """Do the layers of `token` (#1, #[1-2]) hold the first? Refused as tshark 4.0.17 refuses them."""
    spec = token.text[1:]
    if spec[0] != "[":
        if int(spec) >= 1 << 31:
            raise p.error(f"{spec!r} causes an integer overflow (in the layer {token.text})", token)
        return int(spec) == 1
    ranges = [_slice_range(p, part, token) for part in spec[1:-1].split(",")]

    def holds_first(start: int | None, colon: bool, length: int | None, last: int | None) -> bool:
        first = (start or 0) + 2 * ((start or 0) < 0)  # (-1: the last layer, the first here)
        if last is not None:
            return first <= 1 <= last + 2 * (last < 0)
        if colon:
            return first <= 1 and (length is None or first + length > 1)
        return first == 1

    return any(holds_first(*one) for one in ranges)
