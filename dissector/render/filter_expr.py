"""Display-filter functions and arithmetic, as tshark 4.0.17 takes them (render/filters.py hands a test
here when one is in it: filter_ops.needs_expression):

    len(raw) == 8   count(value) > 1   upper(code) == "CHCF"   lower(function_name) contains "read"
    string(slave) == "12"   max(value) > 100   min(address, 8401) == 8401   abs(value - 20) == 8
    slave + 1 == 13   {value * 2} > 100   value - address < 0   response_time + 1 > 1.01   slave == 11 + 1

An operand has every value a field has in the item (one per element of a list: tshark's occurrences),
and an operation takes every pair; a comparison holds when some pair passes it (`!=`: every pair
differs, `===`: every pair is equal, `~=`: some pair differs). A register field reads one register at a
time, as elsewhere in the filter (the rule of render/filters.py), except in count(), max() and min(),
and where an operation or a comparison meets register fields on both sides (`value == address`,
`value - 1 == value`): those take every occurrence of the frame, as tshark's, each of one side with each
of the other (frame_level). Types are -G fields' (render/glossary.py):
whole numbers add, subtract, multiply, divide (dropping the fraction; by 0: no value), take a remainder
and a bitwise and (&, below + and -); decimals add, subtract, multiply and divide (by 0: an infinity, or
NaN, which compares equal to every number, as tshark's); times add and subtract; texts, bytes and
true/false none. A literal takes the type of what it meets: `{slave * 1.5}` is refused as tshark
refuses it. Costs stay bounded on hostile bytes: a text is at most a frame's, the pairs at most the
frame's occurrences squared (MAX_PAIRS)."""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field as dataclass_field, replace
from typing import Any

from dissector.render.filter_lexer import NUMBER, Token, number, parse_bytes
from dissector.render.filter_match import item_elements
from dissector.render.filter_values import bool_literal, kind_of, time_literal, type_name, uint_limit, unsigned_type

Item = dict[str, Any]
Values = Callable[[Item, dict[str, Any] | None], list[Any]]
ARITHMETIC = ("+", "-", "*", "/", "%")
MAX_PAIRS = 1 << 20  # an operation on more pairs of occurrences gives no value (never reached by a frame)
# Operations in one operand: each nests a call when it is computed (as parentheses nest the parser), so a
# longer chain is refused rather than run out of stack (`slave + 1 + 1 ...`).
MAX_OPERATIONS = 128


@dataclass(slots=True)
class Operand:
    """A value of the filter: a field, a function's result, arithmetic, or a literal not yet typed
    (`fold` types it: a literal's type is that of what it meets)."""

    text: str
    position: int
    ftype: str = "FT_NONE"  # its tshark type, as -G fields names it
    values: Values = lambda item, reg: []
    register: bool = False  # reads one register at a time
    fold: Callable[[str], list[Any]] | None = None  # a constant: its values for a type
    field: str | None = None  # a field as it is, which len(), count()... take
    function: str | None = None  # the function that gave it (alone it is no test)
    char: bool = False  # a character constant, which arithmetic refuses
    tokens: list[Token] = dataclass_field(default_factory=list)
    size: int = 0  # operations in it (MAX_OPERATIONS)


def counted(p: Any, operand: Operand, size: int, token: Token) -> Operand:
    """`operand` of `size` operations, refused past MAX_OPERATIONS."""
    if size > MAX_OPERATIONS:
        raise p.error(f"more than {MAX_OPERATIONS} operations in one operand: split the filter", token)
    operand.size = size
    return operand


def frame_level(left: Operand, right: Operand) -> tuple[Operand, Operand]:
    """Two operands that both read registers, over the whole frame, every occurrence of every register, as
    tshark takes two fields with several occurrences each: every value of one meets every value of the
    other (`value == address`, `value - address`), not register by register. Others as they are."""
    if not (left.register and right.register):
        return left, right

    def whole(operand: Operand) -> Operand:
        return replace(operand, values=lambda item, reg: frame_values(operand, item), register=False)

    return whole(left), whole(right)


def frame_values(operand: Operand, item: Item) -> list[Any]:
    """Every value of the operand in the frame: of each of its registers for a register field."""
    if not operand.register:
        return operand.values(item, None)
    elements = item_elements(item)
    if not elements:
        return operand.values(item, None)
    return [value for element in elements for value in operand.values(item, element)]


def literal_value(p: Any, token: Token, ftype: str) -> Any:
    """What the literal `token` means for a value of `ftype`, or an error as tshark 4.0.17 refuses it."""
    kind = kind_of(ftype)
    if kind == "none":
        raise p.error(f"{token.text} has no type to take here: compare a field with it", token)
    if kind == "bool":
        return bool_literal(token, p.text, "it")
    if token.kind == "string":
        if kind == "str":
            return token.value
        if kind == "bytes":
            return token.data
        raise p.error(f"{token.text} is a string, and this is {type_name(ftype)}", token)
    if kind == "time":
        seconds = time_literal(token.text) if token.kind in ("number", "bytes") else None
        if seconds is None:
            raise p.error(f"{token.text} is not a valid time: seconds are written as 1.5 (no exponent, "
                          "hex or character; 9 decimals at most, as tshark)", token)
        return seconds
    if kind == "bytes":
        data = bytes([token.value]) if token.kind == "char" else parse_bytes(token)
        if data is None:
            raise p.error(f"{token.text} is no byte string: write its bytes in hex as 0c:03", token)
        return data
    if kind == "str":
        if token.kind == "char":
            return chr(token.value)
        raise p.error(f"{token.text} is no text: texts go in double quotes", token)
    value = token.value
    if token.kind == "bytes" and (NUMBER.fullmatch(token.text) or token.text[:2] in ("0b", "0B")):
        value = number(token.text, p.text, token.position)
    elif token.kind not in ("number", "char"):
        raise p.error(f"{token.text} is not a number", token)
    if kind == "int" and isinstance(value, float):
        raise p.error(f"{token.text} is not a whole number, and this is {type_name(ftype)} (as tshark "
                      "refuses it)", token)
    limit = uint_limit(ftype)
    if limit is not None and value > limit:
        raise p.error(f"{token.text} is too big for {type_name(ftype)}: at most {limit} (as tshark)", token)
    return value


def typed(p: Any, operand: Operand, ftype: str) -> Operand:
    """The operand with its literals typed `ftype` (a constant: its values computed once, now)."""
    if operand.fold is None:
        return operand
    values = operand.fold(ftype)
    return Operand(operand.text, operand.position, ftype, lambda item, reg: values)


def constant(p: Any, token: Token) -> Operand:
    return Operand(token.text, token.position, fold=lambda ftype: [literal_value(p, token, ftype)],
                   char=token.kind == "char", tokens=[token])


# -- arithmetic ------------------------------------------------------------------------------------
def _int_divide(a: int, b: int) -> int | None:
    if b == 0:
        return None
    quotient = abs(a) // abs(b)
    return quotient if (a < 0) == (b < 0) else -quotient  # (towards 0, as C and tshark)


def _int_remainder(a: int, b: int) -> int | None:
    quotient = _int_divide(a, b)
    return None if quotient is None else a - b * quotient


def _float_divide(a: float, b: float) -> float:
    """IEEE's, as tshark 4.0.17 divides decimals: by 0, an infinity, or NaN for 0 / 0 (filter_match.compare)."""
    if b != 0:
        return a / b
    if a == 0 or math.isnan(a):
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


OPERATIONS: dict[str, dict[str, Callable[[Any, Any], Any]]] = {
    "int": {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b, "/": _int_divide,
            "%": _int_remainder, "&": lambda a, b: a & b},
    # (no %: tshark 4.0.17 refuses it for a decimal, "FT_DOUBLE cannot %.")
    "float": {"+": lambda a, b: a + b, "-": lambda a, b: a - b, "*": lambda a, b: a * b, "/": _float_divide},
    "time": {"+": lambda a, b: a + b, "-": lambda a, b: a - b},
}


def _combine(operation: Callable[[Any, Any], Any], lefts: list[Any], rights: list[Any]) -> list[Any]:
    if len(lefts) * len(rights) > MAX_PAIRS:
        return []
    results = [operation(a, b) for a in lefts for b in rights]
    return [result for result in results if result is not None]


def arithmetic(p: Any, op: Token, left: Operand, right: Operand) -> Operand:
    """`left op right`, typed and checked as tshark 4.0.17 does."""
    for side in (left, right):
        _no_character(p, side)
    text = f"{left.text} {op.value} {right.text}"
    size = left.size + right.size + 1
    if left.fold is not None and right.fold is not None:  # both constant: typed by what the whole meets
        def fold(ftype: str) -> list[Any]:
            operation = _operation(p, op, ftype, text)
            return _combine(operation, left.fold(ftype), right.fold(ftype))  # type: ignore[misc]

        folded = Operand(text, left.position, fold=fold, tokens=left.tokens + right.tokens)
        return counted(p, folded, size, op)
    ftype = left.ftype if left.fold is None else right.ftype
    left, right = typed(p, left, ftype), typed(p, right, ftype)
    left, right = frame_level(left, right)
    if kind_of(left.ftype) != kind_of(right.ftype):
        raise p.error(f"{left.text} and {right.text} are not type compatible ({left.ftype}, "
                      f"{right.ftype})", op)
    operation = _operation(p, op, ftype, left.text)
    if unsigned_type(left.ftype):
        operation = _unsigned(op.value, operation)
    left_values, right_values = left.values, right.values
    combined = Operand(text, left.position, ftype,
                       lambda item, reg: _combine(operation, left_values(item, reg), right_values(item, reg)),
                       register=left.register or right.register)
    return counted(p, combined, size, op)


UINT32 = 0xFFFFFFFF


def _unsigned(op: str, signed: Callable[[Any, Any], Any]) -> Callable[[Any, Any], Any]:
    """`op` on an unsigned left value as tshark 4.0.17 computes it: in 32 bits, no value where it overflows,
    a negative right side (-slave, a signed number) read as its 32 bits (value + -slave: 0xfffffffe where
    value is 0, no value from 2 up); a left value below 0 (value - 20 is signed there) as `signed`."""
    def run(a: Any, b: Any) -> Any:
        if a < 0:
            return signed(a, b)
        if b < 0:
            b += UINT32 + 1
            if op == "-":  # (b > a: tshark subtracts signed, and b is past 2^31)
                return None
        result = signed(a, b)
        return None if result is not None and op in "+*" and result > UINT32 else result

    return run


def _operation(p: Any, op: Token, ftype: str, text: str) -> Callable[[Any, Any], Any]:
    operation = OPERATIONS.get(kind_of(ftype), {}).get(op.value)
    if operation is None:
        raise p.error(f"{text} is {type_name(ftype)}: it cannot {op.value} (as tshark)", op)
    return operation


def negative(p: Any, op: Token, operand: Operand) -> Operand:
    """-x (and +x, which is x)."""
    _no_character(p, operand)
    if operand.fold is None and kind_of(operand.ftype) not in OPERATIONS:
        raise p.error(f"{operand.text} is {type_name(operand.ftype)}: it cannot take a sign (as tshark)", op)
    if op.value == "+":
        return operand
    text = f"-{operand.text}"
    if operand.fold is not None:
        inner = operand.fold

        def fold(ftype: str) -> list[Any]:
            if kind_of(ftype) not in OPERATIONS:  # (warnings == - "a")
                raise p.error(f"{operand.text} cannot be negated: this is {type_name(ftype)}", op)
            return [-value for value in inner(ftype)]

        return counted(p, Operand(text, op.position, fold=fold, tokens=operand.tokens), operand.size + 1, op)
    values = operand.values
    # (a number or a time: checked above; an unsigned one becomes a signed 32-bit one, as tshark 4.0.17's)
    ftype = "FT_INT32" if unsigned_type(operand.ftype) else operand.ftype
    negated = Operand(text, op.position, ftype,
                      lambda item, reg: [-value for value in values(item, reg)], register=operand.register)
    return counted(p, negated, operand.size + 1, op)


def _no_character(p: Any, operand: Operand) -> None:
    if operand.char:  # (as tshark 4.0.17: 'a' is a number in a comparison, no operand of arithmetic)
        raise p.error(f"{operand.text} is not a valid arithmetic operand (a character constant)",
                      operand.tokens[0])
