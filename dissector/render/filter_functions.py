"""The display-filter functions of tshark 4.0.17, checked and computed as it does (render/filter_ops.py
parses a call, render/filter_expr.py has the operands):

    len(F)      the length of each value: a text's bytes (UTF-8), a byte string's, an integer type's
                width (slave: 1, value: 2, frame: 4), 0 for a decimal number, a time or true/false
    count(F)    how many values F has in the frame (none: no value, so count(F) == 0 is never true)
    upper(F) lower(F)   a text field in ASCII capitals or small letters
    string(F)   a number field as text: 12, a decimal with 17 digits (2.1000000000000001), as tshark's
    max(A, ...) min(A, ...)   the largest or smallest value of all the arguments' values, all of one type
    abs(A)      each value without its sign

len, count, upper, lower and string take a field as it is (no slice, literal or function), as tshark;
max, min and abs also take literals, functions and arithmetic. Names are case-sensitive (LEN is none)."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

from dissector.render.filter_expr import Operand, frame_values, typed
from dissector.render.filter_values import kind_of, type_name, wire_size

Item = dict[str, Any]
FUNCTIONS = ("len", "count", "upper", "lower", "string", "max", "min", "abs")
_ONE_ARGUMENT = ("len", "count", "upper", "lower", "string", "abs")
_ASCII_UPPER = {code: code - 32 for code in range(ord("a"), ord("z") + 1)}
_ASCII_LOWER = {code: code + 32 for code in range(ord("A"), ord("Z") + 1)}


def call(p: Any, name: Any, arguments: list[Operand]) -> Operand:
    """The operand `name(arguments)` gives; an error where tshark 4.0.17 refuses the call."""
    if name.value not in FUNCTIONS:
        raise p.error(f"function {name.value!r} does not exist ({', '.join(FUNCTIONS)})", name)
    if not arguments:
        raise p.error(f"{name.value}() needs at least 1 argument", name)
    if name.value in _ONE_ARGUMENT and len(arguments) > 1:
        raise p.error(f"{name.value}() takes 1 argument", name)
    text = f"{name.value}({', '.join(argument.text for argument in arguments)})"
    if name.value in ("max", "min"):
        return _extreme(p, name, text, arguments)
    argument = arguments[0]
    if name.value == "abs":
        return _absolute(p, text, argument)
    if argument.field is None:
        raise p.error(f"only a field can be given to {name.value}() (as tshark), not {argument.text}", name)
    values, ftype = argument.values, argument.ftype
    if name.value == "count":  # (the whole frame's, as tshark's)
        return Operand(text, name.position, "FT_UINT32", function="count",
                       values=per_frame(lambda item: [n] if (n := len(frame_values(argument, item))) else []))
    if name.value == "len":
        size = wire_size(ftype)
        return Operand(text, name.position, "FT_UINT32",
                       lambda item, reg: [_length(v, size) for v in values(item, reg)],
                       register=argument.register, function="len")
    if name.value in ("upper", "lower"):
        if kind_of(ftype) != "str":
            raise p.error(f"{name.value}() takes a text field; {argument.text} is {type_name(ftype)}", name)
        table = _ASCII_UPPER if name.value == "upper" else _ASCII_LOWER
        return Operand(text, name.position, "FT_STRING",
                       lambda item, reg: [v.translate(table) for v in values(item, reg)
                                          if isinstance(v, str)],
                       register=argument.register, function=name.value)
    if kind_of(ftype) not in ("int", "float"):  # string()
        raise p.error(f"string() takes a number field; {argument.text} is {type_name(ftype)} (as tshark)",
                      name)
    shown = str if kind_of(ftype) == "int" else "{:.17g}".format
    return Operand(text, name.position, "FT_STRING",
                   lambda item, reg: [shown(v) for v in values(item, reg) if _is_number(v)],
                   register=argument.register, function="string")


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _length(value: Any, size: int) -> int:
    if isinstance(value, str):
        return len(value.encode())
    if isinstance(value, (bytes, list)):
        return len(value)
    return size  # (a number: its type's width; a true/false 0)


def _extreme(p: Any, name: Any, text: str, arguments: list[Operand]) -> Operand:
    """max() and min(): every argument of the first one's type; the result is the frame's."""
    first = next((argument for argument in arguments if argument.fold is None), None)
    if first is None:
        raise p.error(f"{name.value}() needs a field among its arguments (a literal has no type alone)", name)
    arguments = [typed(p, argument, first.ftype) for argument in arguments]
    for argument in arguments:
        if argument.ftype != first.ftype:
            raise p.error(f"the arguments of {name.value}() have one type: {first.text} is {first.ftype}, "
                          f"{argument.text} {argument.ftype} (as tshark)", name)
    if kind_of(first.ftype) == "none":  # (true/false are ordered, false first, as tshark 4.0.17's)
        raise p.error(f"{first.text} cannot be ordered: {name.value}() takes numbers, texts, bytes or "
                      "true/false", name)
    pick: Callable[..., Any] = max if name.value == "max" else min

    def values(item: Item) -> list[Any]:
        found = [value for argument in arguments for value in frame_values(argument, item)
                 if value is not None]
        return [pick(found)] if found else []

    return Operand(text, name.position, first.ftype, per_frame(values), function=name.value)


def per_frame(compute: Callable[[Item], list[Any]]) -> Callable[[Item, Any], list[Any]]:
    """The values of a frame-wide function, computed once per item: a test on each register that
    compares with it (count(value) == value) costs the registers once, not their square."""
    last: list[Any] = [None, []]

    def values(item: Item, reg: dict[str, Any] | None) -> list[Any]:
        if last[0] is not item:
            last[0], last[1] = item, compute(item)
        return last[1]

    return values


def _absolute(p: Any, text: str, argument: Operand) -> Operand:
    if argument.fold is not None:
        raise p.error(f"abs({argument.text}) is a constant: give it a field", argument.tokens[0])
    if kind_of(argument.ftype) not in ("int", "float", "time"):
        raise p.error(f"{argument.text} is not a valid argument to abs(): it is {type_name(argument.ftype)}",
                      argument.tokens[0] if argument.tokens else None)
    values = argument.values
    if kind_of(argument.ftype) == "time":
        # tshark 4.0.17 gives no value for a negative time (abs(vw3.response_time - 1) > 0.99: no frame)
        return Operand(text, argument.position, argument.ftype,
                       lambda item, reg: [v for v in values(item, reg) if v >= 0], register=argument.register,
                       function="abs")
    return Operand(text, argument.position, argument.ftype,
                   lambda item, reg: [abs(v) for v in values(item, reg)], register=argument.register,
                   function="abs")
