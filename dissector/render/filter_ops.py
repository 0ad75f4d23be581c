"""A display-filter test with functions or arithmetic in it (render/filter_expr.py, filter_functions.py):
its operands parsed, as tshark 4.0.17's grammar reads them,

    sum := product (+|- product)...   product := unary (*|/|% unary)...
    & below both (`value & 4 + 1` is `value & 5`)
    unary := -unary | +unary | {expression} | name(arguments)[slice] | field[slice] | literal

and compared. render/filters.py parses every other test itself: needs_expression tells which."""
from __future__ import annotations

import re
from dataclasses import replace
from typing import Any

from dissector.render.filter_expr import (
    ARITHMETIC, Operand, arithmetic, constant, counted, frame_level, frame_values, negative, typed,
)
from dissector.render.filter_fields import (
    ALIASES, FRAME_FIELDS, REGISTER_FIELDS, TIME_FILTER_FIELDS, pdu_values, unknown_pdu_key,
)
from dissector.render.filter_functions import call
from dissector.render.filter_error import FilterError
from dissector.render.filter_lexer import Token, tokenize
from dissector.render.filter_match import (
    as_bytes, compile_regex, in_members, item_elements, quantify, relate,
)
from dissector.render.filter_syntax import layer_holds_first, parse_layer
from dissector.render.filter_values import kind_of, type_name, unsigned_type
from dissector.render.glossary import field_type

Item = dict[str, Any]
COMPARISONS = ("==", "!=", "~=", "===", "<", "<=", ">", ">=")
_LITERALS = ("number", "string", "char", "bytes", "dashed")


def is_field(token: Any) -> bool:
    """A name that is a field (an unquoted word that is none stays the text or bytes it was)."""
    if token.kind != "name":
        return False
    name = ALIASES.get(token.value, token.value)
    if name.startswith("fields."):
        return unknown_pdu_key(name[7:]) is None
    return name in FRAME_FIELDS or name in REGISTER_FIELDS or name in TIME_FILTER_FIELDS


def needs_expression(tokens: list[Any], index: int) -> bool:
    """Does the test at `index` hold a function, arithmetic, or a field on the right of its comparison?"""
    def at(i: int, kind: str, *values: str) -> bool:
        return i < len(tokens) and tokens[i].kind == kind and (not values or tokens[i].value in values)

    def opens_operand(i: int) -> bool:  # {...}, -x, +x, a call or a field reference
        return (at(i, "punct", "{") or at(i, "op", "-", "+") or (at(i, "name") and at(i + 1, "punct", "("))
                or at(i, "reference"))

    if opens_operand(index):
        return True
    if not at(index, "name"):
        return False
    i = index + 1
    while at(i, "layer") or at(i, "slice"):  # (slave#1, raw[0:2][1])
        i += 1
    if at(i, "op", *ARITHMETIC) or (at(i, "op", "&") and at(i + 2, "op", *ARITHMETIC)):
        return True
    if at(i, "op", "&") and (opens_operand(i + 1) and not at(i + 1, "op", "-", "+")
                             or i + 1 < len(tokens) and is_field(tokens[i + 1])):
        return True  # (slave & ${slave}, value & value: a bitwise and of two operands, as tshark's)
    if not at(i, "op", *COMPARISONS):
        return False
    right = i + 1
    if opens_operand(right):
        return True
    if right < len(tokens) and is_field(tokens[right]):
        return True
    return right < len(tokens) and tokens[right].kind in _LITERALS and at(right + 1, "op", *ARITHMETIC)


# -- operands ----------------------------------------------------------------------------------
def parse_expression(p: Any) -> Operand:
    left = _parse_sum(p)
    while p.at("op", "&"):
        op = p.advance()
        left = arithmetic(p, op, left, _parse_sum(p))
    return left


def _parse_sum(p: Any) -> Operand:
    left = _parse_product(p)
    while p.at("op", "+", "-"):
        op = p.advance()
        left = arithmetic(p, op, left, _parse_product(p))
    return left


def _parse_product(p: Any) -> Operand:
    left = _parse_unary(p)
    while p.at("op", "*", "/", "%"):
        op = p.advance()
        left = arithmetic(p, op, left, _parse_unary(p))
    return left


def _parse_unary(p: Any) -> Operand:
    if p.at("op", "-", "+"):
        op = p.advance()
        p._enter()
        operand = negative(p, op, _parse_unary(p))
        p.depth -= 1
        return operand
    token = p.token
    if p.at("punct", "{"):
        p.advance()
        p._enter()
        inner = parse_expression(p)
        p.depth -= 1
        if not p.at("punct", "}"):
            raise p.error(f"expected }} to close the {{ at column {token.position + 1}")
        p.advance()
        return inner
    if token.kind == "name" and p.tokens[p.index + 1].kind == "punct" and p.tokens[p.index + 1].value == "(":
        return _parse_call(p)
    if token.kind == "name" and is_field(token):
        return _parse_field(p)
    if token.kind == "reference":
        return parse_reference(p)
    if token.kind in _LITERALS or p.at("keyword", "true", "false"):
        p.advance()
        return constant(p, token)
    raise p.error(f"expected a field, a function, a number or a text, found {p._describe(token)}")


def _parse_call(p: Any) -> Operand:
    name = p.advance()
    opening = p.advance()
    p._enter()
    arguments = []
    while not p.at("punct", ")"):
        if p.token.kind == "end":
            raise p.error(f"expected ) to close the ( at column {opening.position + 1}")
        arguments.append(parse_expression(p))
        if not p.at("punct", ")"):
            if not p.at("punct", ","):
                raise p.error(f"expected , or ) in the arguments of {name.value}()")
            p.advance()
    p.advance()
    p.depth -= 1
    result = counted(p, call(p, name, arguments), max(argument.size for argument in arguments) + 1, name)
    if p.token.kind == "slice":  # lower(function_name)[0:4]: the bytes of the text, as a text field's slice
        if kind_of(result.ftype) not in ("str", "bytes"):
            raise p.error(f"{result.text} is {type_name(result.ftype)}: only texts and bytes take a slice")
        cut = p.parse_slice(result.text, "str")
        values = result.values
        result = Operand(result.text, result.position, "FT_BYTES",
                         lambda item, reg: [c for v in values(item, reg)
                                            if (c := cut(_bytes(v))) is not None],
                         register=result.register, function=result.function, size=result.size)
    return result


def parse_reference(p: Any) -> Operand:
    """`${slave}`, tshark 4.0's field reference: the field's value in the frame selected in Wireshark. A
    decode has none selected, as tshark has none: it holds no value, so a comparison with it never holds
    (slave == ${slave}, slave != ${slave}, all ...: no frame; not slave == ${slave}: every frame). A name
    that is no field is a display filter macro to tshark, and vw3-decode has none. A layer (${slave#1}) is
    read as slave#1's and changes nothing."""
    token = p.advance()
    written, hash_, layer = token.value.partition("#")
    name = Token("name", written, written, token.position + 2)
    if not is_field(name):  # a macro to tshark: its name is what comes before its arguments (${name:a;b})
        macro = token.value.partition(":")[0]
        if not re.fullmatch(r"[\w.]*", macro):
            raise p.error("invalid character in macro name (as tshark 4.0 says: vw3-decode has no display filter "
                          "macros; ${FIELD} is a field reference, as ${slave} or ${slave#1})", token)
        raise p.error(f"macro {macro!r} does not exist (as tshark 4.0 says: vw3-decode has no display filter "
                      f"macros; ${{FIELD}} is a field reference, as ${{slave}})", token)
    field, _ftype, register = p.resolve_field(name)
    if hash_:  # ${slave#1}: a layer, read as slave#1's (it changes nothing: the reference holds no value)
        at = name.position + len(written)
        try:
            layers = tokenize(hash_ + layer)
        except FilterError as error:
            raise FilterError(error.message, p.text, at + error.position) from None
        if len(layers) > 2:
            raise p.error(f"unexpected {layers[1].text!r} in the field reference {token.text}",
                          replace(layers[1], position=at + layers[1].position))
        layer_holds_first(p, replace(layers[0], position=at))
    return Operand(token.text, token.position, field_type(field), lambda item, reg: [], register=register,
                   tokens=[token])


def _bytes(value: Any) -> bytes:
    return value.encode() if isinstance(value, str) else value


def _parse_field(p: Any) -> Operand:
    token = p.advance()
    field, ftype, register = p.resolve_field(token)
    if not parse_layer(p):  # (slave#2: a layer no item has, no value)
        p.parse_slice(field, ftype)
        return Operand(token.text, token.position, field_type(field), lambda item, reg: [], register=register,
                       field=field, tokens=[token])
    tshark_type = field_type(field)
    if field.startswith("fields."):  # a repeated field: each element a value
        key = field[7:]

        def elements(item: Item, reg: dict[str, Any] | None) -> list[Any]:
            found = pdu_values(item.get("fields"), key)
            if tshark_type == "FT_BYTES":  # (hex text in the item)
                return [data for v in found if (data := as_bytes(v)) is not None]
            return found

        return Operand(token.text, token.position, tshark_type, elements, field=field, tokens=[token])
    cut = p.parse_slice(field, ftype)
    get = p.field_getter(field, ftype, register, cut)
    if cut is not None:
        tshark_type = "FT_BYTES"
    if ftype == "list":  # warnings, notes: each text a value
        return Operand(token.text, token.position, tshark_type, lambda item, reg: list(get(item, reg) or ()),
                       register=register, field=field, tokens=[token])
    return Operand(token.text, token.position, tshark_type,
                   lambda item, reg: [] if (value := get(item, reg)) is None or value == [] else [value],
                   register=register, field=field if cut is None else None, tokens=[token])


# -- the test ------------------------------------------------------------------------------------
def parse_expression_test(p: Any) -> tuple[Any, bool]:
    """A test with functions or arithmetic: (test, whether it reads one register at a time)."""
    start = p.token
    every = p.every  # (inside `all RELATION`: render/filter_quantifiers.py)
    left = parse_expression(p)
    if left.fold is not None:
        raise p.error("the left side of a comparison must hold a field (a constant on the left is refused, "
                      "as tshark)", start)
    token = p.token
    if p.at("op", *COMPARISONS):
        p.advance()
        right = typed(p, parse_expression(p), left.ftype)
        text_and_bytes = {left.ftype, right.ftype} == {"FT_STRING", "FT_BYTES"}
        if kind_of(right.ftype) != kind_of(left.ftype) and not text_and_bytes:
            raise p.error(f"{left.text} and {right.text} are not type compatible ({left.ftype}, "
                          f"{right.ftype})", token)
        return _comparison(token.value, left, right, every)
    if p.at("keyword", "contains", "matches") or p.at("op", "~"):
        if every:
            raise p.error(f"all with contains or matches takes a field, not {left.text}", token)
        return _search(p, token, left)
    if p.at("keyword", "in"):
        raise p.error(f"only a field can be tested for membership in a set (as tshark), not {left.text}")
    if start.kind == "reference" and p.tokens[p.index - 1] is start:
        raise p.error(f"{start.text} is a field reference, no test: compare a field with it, as "
                      f"{start.value} == {start.text} (tshark: neither a field nor a protocol name)", start)
    if left.function is not None:
        raise p.error(f"{left.text} alone tests nothing: compare it, as {left.text} > 0 (tshark cannot test "
                      "whether a function is present)", start)
    values = left.values  # arithmetic alone: some value is not 0, as tshark's
    return (lambda item, reg: any(value for value in values(item, reg))), left.register


def _comparison(op: str, left: Operand, right: Operand, every: bool = False) -> tuple[Any, bool]:
    """Some pair passes `op`; `~=` some pair differs; `!=` none is equal and `===` none differs, of a
    left and a right that have values (over the frame's registers when one reads a register's); under
    `all` (`every`) no pair fails `op`."""
    left, right = frame_level(left, right)  # (every occurrence of one with every one of the other, as tshark)
    lefts, rights = left.values, right.values
    register = left.register or right.register
    wanted = {"~=": "!=", "!=": "==", "===": "!="}.get(op, op)
    unsigned = unsigned_type(left.ftype)  # (value > -slave: no pair relates, filter_match.relate)

    def some(item: Item, reg: dict[str, Any] | None) -> bool:
        found = lefts(item, reg)
        if every and op not in ("!=", "==="):  # (a pair that fails op)
            return bool(found) and any(relate(op, x, y, unsigned) is False for y in rights(item, reg) for x in found)
        return bool(found) and any(relate(wanted, x, y, unsigned) for y in rights(item, reg) for x in found)

    if op not in ("!=", "===") and not every:
        return some, register

    def present(item: Item, reg: dict[str, Any] | None) -> bool:
        return bool(lefts(item, reg)) and bool(rights(item, reg))

    if register:  # over the registers of the frame, as filters.py's != and ===
        some_present, some_against = quantify(present), quantify(some)
        return (lambda item, reg: some_present(item) and not some_against(item)), False
    return (lambda item, reg: present(item, reg) and not some(item, reg)), False


def _search(p: Any, token: Any, left: Operand) -> tuple[Any, bool]:
    """contains and matches on a function's text (upper(code) contains "CH") or bytes."""
    kind = kind_of(left.ftype)
    word = "contains" if p.at("keyword", "contains") else "matches"
    p.advance()
    if kind not in ("str", "bytes"):
        raise p.error(f"{left.text} is {type_name(left.ftype)}: it cannot take {word} (as tshark)", token)
    values = left.values
    if word == "matches":
        if p.token.kind != "string":
            raise p.error("matches takes a regular expression in double quotes (as tshark)")
        pattern_token = p.advance()
        pattern = compile_regex(pattern_token.value, p.text, pattern_token.position)
        return (lambda item, reg: any(pattern.search(v if isinstance(v, str) else v.decode("latin-1"))
                                      for v in values(item, reg))), left.register
    if p.token.kind not in ("string", "char", "bytes", "name", "number"):
        raise p.error(f"{word} takes a text or bytes, not {p._describe(p.token)}")
    wanted = typed(p, constant(p, p.advance()), left.ftype).values({}, None)[0]
    if not wanted and (left.ftype == "FT_STRING" or left.field == "raw"):  # (as filter_match.contains_text)
        return (lambda item, reg: False), left.register
    return (lambda item, reg: any(wanted in v for v in values(item, reg))), left.register


# -- sets with fields among their members ------------------------------------------------------------
def parse_member(p: Any, field: str) -> Operand:
    """A set's member that is a field or a function's result (`value in {address, 40}`, `slave in
    {max(slave)}`), as tshark 4.0.17 takes one: one entity, no arithmetic (`{value + 1}` refused)."""
    token = p.token
    if p.at("op", "-", "+"):  # (-slave, +slave: one sign before a field, a function or a reference, as tshark's)
        sign = p.advance()
        if not (p.token.kind == "reference" or p.token.kind == "name" and (
                is_field(p.token) or p.tokens[p.index + 1].kind == "punct" and p.tokens[p.index + 1].value == "(")):
            raise p.unexpected(f"a sign in a set goes before a field or a function, as {sign.value}slave")
        operand = negative(p, sign, parse_reference(p) if p.token.kind == "reference" else _parse_entity(p))
    else:
        operand = _parse_entity(p)
    if kind_of(operand.ftype) != kind_of(field_type(field)):
        raise p.error(f"{field} and {operand.text} are not of compatible types ({field_type(field)}, "
                      f"{operand.ftype}), as tshark says", token)
    return operand


def is_negative(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and value < 0


def _parse_entity(p: Any) -> Operand:
    """A field or a function's result at p's token."""
    if p.tokens[p.index + 1].kind == "punct" and p.tokens[p.index + 1].value == "(":
        return _parse_call(p)
    return _parse_field(p)


def set_test(get: Any, register: bool, members: list[tuple[Any, Any]], every: bool, unsigned: bool = False) -> Any:
    """`field in {SET}` with a field among the members, as tshark 4.0.17: over every occurrence of the frame
    (each of the field's with each of a member's), some member holding (`all`: holding for every occurrence
    of the field, each member apart). A range's bound must have one value (none: the member holds nothing;
    several: tshark 4.0.17 aborts, vw3-decode's member holds nothing). An `unsigned` field relates to no
    negative member (`value in {-slave}`, filter_match.relate): it holds nothing, and fails nothing under all."""
    def lefts(item: Item) -> list[Any]:
        elements = item_elements(item) if register else []
        return [v for element in elements or [None] if (v := get(item, element)) is not None and v != []]

    def bounds(bound: Any, item: Item) -> list[Any]:
        return frame_values(bound, item) if isinstance(bound, Operand) else [bound]

    def passes(member: tuple[Any, Any], values: list[Any], item: Item) -> bool:
        low, high = member
        if low is high and isinstance(low, Operand):  # a single member: each pair compared, as == and ===
            others = frame_values(low, item)
            if every:
                return bool(values) and bool(others) and all(
                    relate("==", x, y, unsigned) is not False for x in values for y in others)
            return any(relate("==", x, y, unsigned) for x in values for y in others)
        lows, highs = bounds(low, item), bounds(high, item)
        if len(lows) != 1 or len(highs) != 1:
            return False
        if unsigned and (is_negative(lows[0]) or is_negative(highs[0])):  # (value in {-slave..5})
            if not every:
                return False
            lows, highs = [None if is_negative(lows[0]) else lows[0]], [None if is_negative(highs[0]) else highs[0]]
        inside = [in_members(x, [(lows[0], highs[0])]) for x in values]
        return bool(inside) and all(inside) if every else any(inside)

    return lambda item, reg: any(passes(member, values, item) for values in [lefts(item)] for member in members)
