"""How the display filter compares one value of an item (render.filters parses, this matches)."""
from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from dissector.devices.naming import plc_label
from dissector.render.filter_error import FilterError
from dissector.render.filter_fields import REGISTER_TEXTS
from dissector.protocol import table

Item = dict[str, Any]
Test = Callable[[Item, dict[str, Any] | None], bool]


def is_present(value: Any) -> bool:
    """Is the field there, as a bare field tests it in Wireshark: a false crc_ok is (frame 17 of
    noisy_bus, bad CRC, has vw3.crc_ok = 0), a null one or an empty list is not. A key the plugin adds only
    where true (data/fields.toml `only_true`: broadcast, unanswered, provisional) is absent where false:
    filter_fields.ONLY_TRUE, applied by the parser."""
    return value is not None and value != []


def compare(op: str, left: Any, right: Any) -> bool:
    if isinstance(left, float) and left != left or isinstance(right, float) and right != right:
        return op in ("==", "<=", ">=")  # (NaN, from 0 / 0: tshark 4.0.17 orders it as neither below nor above)
    try:
        if op == "==":
            return bool(left == right)
        if op == "!=":
            return bool(left != right)
        if op == "<":
            return bool(left < right)
        if op == "<=":
            return bool(left <= right)
        if op == ">":
            return bool(left > right)
        return bool(left >= right)
    except TypeError:  # a value of an unexpected type in the item: not a match
        return False


def compile_regex(pattern: str, text: str, position: int) -> re.Pattern[str]:
    """Case-insensitive as Wireshark's matches; a leading (?-i) asks for case."""
    flags = re.IGNORECASE
    if pattern.startswith("(?-i)"):
        pattern, flags = pattern[5:], 0
    try:
        return re.compile(pattern, flags)
    except re.error as error:
        raise FilterError(f"not a regular expression: {error}", text, position) from None


def is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def match_op(op: str, actual: Any, value: Any) -> bool:
    if actual is None:
        return False
    if isinstance(value, str) != isinstance(actual, str):
        return False
    if isinstance(value, bool) != isinstance(actual, bool):
        return False
    if isinstance(value, bytes):  # shorter first, then by the bytes (tshark: frame[0:2] > 0c is every frame)
        if not isinstance(actual, bytes):
            return False
        return compare(op, (len(actual), actual), (len(value), value))
    return compare(op, actual, value)


def relate(op: str, actual: Any, value: Any, unsigned: bool) -> bool | None:
    """match_op, or None where tshark 4.0.17 cannot compare: an unsigned value (`unsigned`: the left side's
    type, and the value not below 0) with a negative number (-slave is a signed one): no relation holds
    then, none fails (value > -slave, value < -slave and value ~= -slave hold nowhere; value != -slave,
    value === -slave and all value > -slave wherever value is)."""
    if unsigned and is_number(value) and value < 0 and is_number(actual) and actual >= 0:
        return None
    return match_op(op, actual, value)


def as_bytes(hex_text: Any) -> bytes | None:
    """The bytes of a value the item holds as hex text (raw, fields.data), None when it is none."""
    try:
        return bytes.fromhex(hex_text) if isinstance(hex_text, str) else None
    except ValueError:
        return None


def cut_bytes(data: bytes, ranges: list[tuple[int | None, bool, int | None, int | None]]) -> bytes | None:
    """The slice `ranges` of `data` joined, each (start, colon, length, last) as filters.parse_slice reads
    it; None (no field, as tshark's) when one does not fit."""
    out = b""
    for start, colon, length, last in ranges:
        start = start or 0
        if start < 0:
            start += len(data)
        if last is not None:  # first-last, both included
            end = last + 1 if last >= 0 else last + len(data) + 1
        elif colon:  # start:length, start: (to the end)
            end = len(data) if length is None else start + length
        else:  # one byte
            end = start + 1
        if start < 0 or end > len(data) or end <= start:
            return None
        out += data[start:end]
    return out


def any_bit_bytes(actual: Any, mask: bytes) -> bool:
    """tshark's `frame[0:2] & 0f`: some bit set in both, byte by byte over the shorter."""
    return isinstance(actual, bytes) and any(a & b for a, b in zip(actual, mask))


def latin1(actual: Any) -> str | None:
    """Bytes as a text of one character each (0x0c is \x0c), for matches, as Wireshark's on bytes."""
    return actual.decode("latin-1") if isinstance(actual, bytes) else None


def contains_text(actual: Any, value: str) -> bool:
    """tshark 4.0.17: a text contains no empty text (`code contains ""` holds nowhere; `matches ""` everywhere)."""
    return isinstance(actual, str) and value != "" and value in actual


def in_members(actual: Any, members: list[tuple[Any, Any]]) -> bool:
    if actual is None:
        return False
    for low, high in members:  # (a true/false field's members are true or false: crc_ok in {0..1})
        if low is None or high is None:  # (a bound that holds: filter_syntax.parse_set, under all)
            if (low is None or compare("<=", low, actual)) and (high is None or compare("<=", actual, high)):
                return True
            continue
        if isinstance(low, str) != isinstance(actual, str) or isinstance(low, bool) != isinstance(actual, bool):
            continue
        if low == high:
            if actual == low:
                return True
        elif compare("<=", low, actual) and compare("<=", actual, high):
            return True
    return False


def any_bit(actual: Any, mask: int) -> bool:
    return isinstance(actual, int) and not isinstance(actual, bool) and bool(actual & mask)


def search(pattern: re.Pattern[str], actual: Any) -> bool:
    return isinstance(actual, str) and pattern.search(actual) is not None


def label_number(label: Any) -> int | None:
    return int(label) if isinstance(label, str) and label.isdigit() else None


def carried(item: Item, reg: dict[str, Any]) -> bool:
    """Is `reg` one of the registers the item carries (not a bit, nor an address it only names)?"""
    registers = item.get("registers")
    if not registers or "value" not in reg:  # (an address only named has no value key: item_elements)
        return False
    return not item.get("bits") or any(element is reg for element in registers)


def register_value(item: Item, reg: dict[str, Any] | None, field: str) -> Any:
    """`field` of one register of the item as tshark reads the plugin's vw3.reg.FIELD: a text key the
    register lacks is "" (filter_fields.REGISTER_TEXTS), None where there is no such occurrence."""
    if reg is None:
        return None
    value = reg.get(field)
    if value is None and field in REGISTER_TEXTS and carried(item, reg):
        return ""
    return value


def address_values(reg: dict[str, Any] | None) -> tuple[Any, ...]:
    """The protocol address and, where a profile shows PLC-style references, the number shown."""
    if reg is None:
        return ()
    shown = label_number(reg.get("label"))
    return (reg.get("address"),) if shown is None else (reg.get("address"), shown)


def address_of(item: Item, reg: dict[str, Any] | None) -> Any:
    return None if reg is None else reg.get("address")


def address_test(op: str, value: Any) -> Test:
    if op == "!=":  # neither the address sent nor the one shown
        return lambda item, reg: bool(address_values(reg)) and not any(
            match_op("==", v, value) for v in address_values(reg)
        )
    return lambda item, reg: any(match_op(op, v, value) for v in address_values(reg))


# The codes whose request or answer carries bits: their windows' addresses are bits', which carry no label
# (the plugin's DATA.bit_windows, from the same table.bit_windows).
BIT_WINDOWS = table.bit_windows()


def _label_base(first: str, start: int) -> int | None:
    """The PLC base whose label of `start` is `first` (`40001` for 49999 at 9998 and for 410000 at 9999), so
    a window's other addresses are labelled as its registers are (naming.plc_label: 49999, then 410000)."""
    number = label_number(first)
    if number is None:
        return None
    # (a label past its top first: 465535 at 65534 is 40001's, as 40001 labels the window's wrapped 0)
    for base in ((number - start + 9) // 10, number - start):
        if base >= 0 and plc_label(base, start) == first:
            return base
    return None


MAX_SYNTHESIZED = 2000  # address-only entries made for one window (the spec's largest read quantity)
# The requests that write a window of their own (FC23: write_start, write_quantity): its addresses are named too.
WRITE_WINDOWS = table.write_windows()


def item_elements(item: Item) -> list[dict[str, Any]]:
    """The registers and bits of an item, plus address-only entries for addresses it names."""
    registers = item.get("registers") or []
    bits = item.get("bits")
    elements: list[dict[str, Any]] = registers + bits if bits else registers
    start, quantity = item.get("start"), item.get("quantity")
    if not (is_number(start) and is_number(quantity)) or item.get("kind") == "exception":
        return elements
    if elements and len(elements) == quantity and elements[0].get("address") == start:
        return elements  # a read response: its values already cover start..start+quantity-1
    known = {element.get("address") for element in elements}
    span = item.get("span_label")
    labelled = isinstance(span, str) and item.get("function") not in BIT_WINDOWS
    base = _label_base(span.split("..", 1)[0], int(start)) if labelled else None  # type: ignore[union-attr]
    windows = [(int(start), int(quantity))]
    fields, write = item.get("fields"), WRITE_WINDOWS.get(item.get("function"))
    if write and item.get("kind") == "request" and isinstance(fields, dict) and all(
            is_number(fields.get(name)) for name in write):
        windows.append((int(fields[write[0]]), int(fields[write[1]])))
    synthesized: list[dict[str, Any]] = []
    for first, count in windows:
        # A quantity of 0 (a malformed read, FC23 writing none) still names its start address, as tshark's
        # reference_num (and FC16's of quantity 0 here).
        for address in range(first, first + min(max(count, 1), MAX_SYNTHESIZED)):
            if address & 0xFFFF not in known:
                known.add(address & 0xFFFF)
                synthesized.append({"address": address & 0xFFFF} if base is None
                                   else {"address": address & 0xFFFF, "label": plc_label(base, address & 0xFFFF)})
    return elements + synthesized if synthesized else elements


class And:
    """All of `tests`; `split` = (frame-level part, register-level part) when it has both."""

    __slots__ = ("tests", "split")

    def __init__(self, tests: list[Test]) -> None:
        self.tests = tests
        self.split: tuple[And, And] | None = None

    def __call__(self, item: Item, reg: dict[str, Any] | None) -> bool:
        return all(test(item, reg) for test in self.tests)


def quantify(test: Test) -> Callable[[Item], bool]:
    """Some register (or, for a frame without any, no register at all) makes `test` true."""
    split = test.split if isinstance(test, And) else None
    if split is not None:
        frame_part, register_part = split

        def some_split(item: Item) -> bool:
            if not frame_part(item, None):
                return False
            elements = item_elements(item)
            if not elements:
                return register_part(item, None)
            return any(register_part(item, element) for element in elements)

        return some_split

    def some(item: Item) -> bool:
        elements = item_elements(item)
        if not elements:
            return test(item, None)
        return any(test(item, element) for element in elements)

    return some
