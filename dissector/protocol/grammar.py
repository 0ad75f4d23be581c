"""Parsing and building PDU data with the Construct grammar of each (function code, direction).

The grammars are the layouts of protocol/layouts.py, chosen by the protocol table (protocol/table.py).
Unknown function codes fall back to raw `data`.
"""
from __future__ import annotations

import struct
from typing import Any

from construct import Construct, ConstructError, Container, StreamError

from dissector.errors import MalformedInput, NeedData
from dissector.model import Kind
from dissector.protocol.table import EXCEPTION_LAYOUT, FUNCTIONS, RAW_LAYOUT

# The grammar of each (function code, direction): the protocol table's, nothing kept here.
GRAMMARS: dict[tuple[int, Kind], Construct] = {
    (entry.code, kind): entry.layout(kind).grammar for entry in FUNCTIONS for kind in (Kind.REQUEST, Kind.RESPONSE)
}
EXCEPTION = EXCEPTION_LAYOUT.grammar
RAW = RAW_LAYOUT.grammar


def _compile(grammar: Construct) -> Construct:
    # Compiled parsers are about 3x faster; building always goes through the declarative form.
    try:
        return grammar.compile()
    except Exception:  # construct refuses some constructs; the interpreted form is equivalent
        return grammar


_COMPILED: dict[int, Construct] = {}


def grammar_for(function: int, kind: Kind) -> Construct:
    if kind is Kind.EXCEPTION:
        return EXCEPTION
    return GRAMMARS.get((function, kind), RAW)


def _compiled(grammar: Construct) -> Construct:
    compiled = _COMPILED.get(id(grammar))
    if compiled is None:
        compiled = _COMPILED[id(grammar)] = _compile(grammar)
    return compiled


class GrammarError(MalformedInput):
    """The PDU does not fit its grammar: a field out of its range, bytes left over."""


class TruncatedPdu(GrammarError, NeedData):
    """The PDU ends before its grammar does: too short, or a count pointing past the end."""


def _grammar_error(error: ConstructError) -> GrammarError:
    kind = TruncatedPdu if isinstance(error, StreamError) else GrammarError
    return kind(_short_error(error))


def parse_pdu(function: int, kind: Kind, data: bytes) -> Container:
    """Parse the PDU data that follows the function code. Raises GrammarError with the failing path."""
    grammar = grammar_for(function, kind)
    try:
        return _compiled(grammar).parse(data)
    except (ConstructError, struct.error, ValueError, IndexError, OverflowError, EOFError):
        # The compiled parsers fail with plain Python errors, or without the path (a linked instance's
        # `(???)`); the interpreted grammar names it.
        try:
            return grammar.parse(data)
        except ConstructError as error:
            raise _grammar_error(error) from None


def build_pdu(function: int, kind: Kind, fields: dict[str, Any]) -> bytes:
    """Encode PDU data (without function code) from fields; used by the simulator and tests."""
    return grammar_for(function, kind).build(fields)


def _short_error(error: ConstructError) -> str:
    text = str(error).strip().splitlines()[-1] if str(error).strip() else type(error).__name__
    path = getattr(error, "path", None)
    if path:
        return f"{text} at {path}"
    return text
