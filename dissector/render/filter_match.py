"""How the display filter compares one value of an item (render.filters parses, this matches)."""
from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

Item = dict[str, Any]
Test = Callable[[Item, dict[str, Any] | None], bool]


def is_present(value: Any) -> bool:
    return value is not None and value is not False and value != "" and value != []


def compare(op: str, left: Any, right: Any) -> bool:
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


def is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def match_op(op: str, actual: Any, value: Any) -> bool:
    if actual is None:
        return False
    if isinstance(value, str) != isinstance(actual, str):
        return False
    if isinstance(value, bool) != isinstance(actual, bool):
        return False
    return compare(op, actual, value)


def contains_text(actual: Any, value: str) -> bool:
    return isinstance(actual, str) and value in actual


def in_members(actual: Any, members: list[tuple[Any, Any]]) -> bool:
    if actual is None or isinstance(actual, bool):
        return False
    for low, high in members:
        if isinstance(low, str) != isinstance(actual, str):
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
