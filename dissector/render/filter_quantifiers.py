"""tshark 4.0.17's quantifiers: `any` or `all` before a relation (`all value > 2`, `any code != "CHCF"`),
for render/filters.py (p is its parser).

A quantifier says which occurrences of the field must pass: `any` some, `all` every one (and there is
one), whatever the operator says alone: `any a != b` is `a ~= b`, `all a == b` is `a === b`, `any a ===
b` is `a == b`. Lowercase only, and directly before the relation (`all (...)`, `all not ...`, `ALL`
refused, as tshark refuses them)."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

from dissector.render.filter_match import is_present, quantify

Item = dict[str, Any]
Test = Callable[[Item, dict[str, Any] | None], bool]
_EQUAL = {"==": "==", "===": "==", "!=": "!=", "~=": "!="}  # (!== is read as ~=)
_QUANTIFIED = {("any", "=="): "==", ("any", "!="): "~=", ("all", "=="): "===", ("all", "!="): "!="}
_RELATIONS = ("==", "!=", "~=", "===", "<", "<=", ">", ">=")


def parse_quantified(p: Any) -> tuple[Test, bool]:
    """`any RELATION` or `all RELATION` at p's token."""
    word = p.advance()
    start = p.token
    if start.kind == "keyword" and start.value in ("any", "all", "not") or p.at("op", "!") or p.at("punct", "("):
        raise p.error(f"{p._describe(start)} was unexpected in this context: {word.value} takes a relation "
                      f"such as {word.value} value > 2", start)
    operator = _operator(p)
    if operator is None:
        raise p.error(f"{word.value} takes a relation such as {word.value} value > 2 (a field alone, or "
                      "a bit test, is none)", start)
    if operator.kind == "op" and operator.value in _EQUAL:  # the quantifier replaces the operator's own
        operator.value = _QUANTIFIED[word.value, _EQUAL[operator.value]]
        return p.parse_primary()
    if word.value == "any":
        return p.parse_primary()
    p.every = True  # read by what parses the relation: list and fields.KEY elements, expressions
    p.presence = None
    try:
        test, register = p.parse_primary()
    finally:
        p.every = False
    if not register:
        return test, register
    return every_of(test, p.presence or (lambda item, reg: True)), False


def every_of(test: Test, present: Test) -> Test:
    """A frame test: some register has the field (`present`), and every one that has it passes `test`."""
    some_present = quantify(present)
    some_failing = quantify(lambda item, reg: present(item, reg) and not test(item, reg))
    return lambda item, reg: some_present(item) and not some_failing(item)


def _operator(p: Any) -> Any:
    """The operator token of the relation at p's token (outside parentheses and braces), or None."""
    depth = 0
    for token in p.tokens[p.index:]:
        if token.kind == "punct" and token.value in ("(", "{"):
            depth += 1
        elif token.kind == "punct" and token.value in (")", "}"):
            if depth == 0:
                return None
            depth -= 1
        elif depth == 0 and (token.kind == "end" or token.kind == "keyword" and token.value in ("and", "or")
                             or token.kind == "op" and token.value in ("&&", "||")):
            return None
        elif depth == 0 and (token.kind == "op" and token.value in _RELATIONS
                             or token.kind == "keyword" and token.value in ("in", "contains", "matches")
                             or token.kind == "op" and token.value == "~"):
            return token
    return None


def every_present(get: Callable[..., Any]) -> Test:
    """Is the field read by `get` present (an occurrence `all` asks about)?"""
    return lambda item, reg: is_present(get(item, reg))


def elements_pass(every: bool, values: Any, passes: Callable[[Any], Any]) -> bool:
    """Some element of a list field passes (`warnings contains "x"`); under `all`, every one does."""
    values = list(values or ())
    return bool(values) and all(passes(v) for v in values) if every else any(passes(v) for v in values)
