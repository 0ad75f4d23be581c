"""Display filters (`-Y EXPR`), evaluated on the NDJSON dict of an item (render.jsonout.item_to_dict).

Syntax, close to Wireshark's:

    slave == 12 and code == "CHCF"          comparisons: == != ~= < <= > >= (also eq ne any_ne lt le gt ge),
                                            === (all_eq: every occurrence equal), !== (any_ne, as ~=)
    raw contains 0c:03   raw[0:2] == 0c03   raw is the item's bytes, as tshark's frame: hex bytes (0c:03
                                            0c-03 0c.03 0c03), slices [start:length] [first-last] [:n]
                                            [n:] [-2:] [4], a string its characters' bytes ("\\x0c")
    function in {3, 4, 23}                  sets: members separated by commas, ranges inside braces
    address in {8400..8402, 8501}           ({3 4} and in 3..4 refused, as tshark 4.0.17 refuses them);
    value in {address, slave..600}          a member may be a field or a function, as tshark's
    warnings contains "byte count"          substring of a string, or of any element of a list
    notes matches "became (protected|non-existent)"   regular expression (also ~), case-insensitive
                                            as Wireshark's; (?-i) at the start makes it case-sensitive
    value & 0x8000                          bit test: some bit of the mask is set; value & 0x8000 == 0
                                            compares the masked value, as Wireshark's bitwise and
    code[0:2] == "CH"                       a text's slice is its bytes (UTF-8), as Wireshark's
    crc_ok   not unanswered   exception     a bare field: present, as in Wireshark (a false crc_ok is)
    not / !   and / &&   or / ||   ( )      strings in double quotes (\\" \\\\ \\n \\t \\xhh \\ooo escapes),
                                            0x.. hex, 0b1100, 014 (octal, as Wireshark's), 16#8000
                                            (IEC, as the notes print values), 13.5e-3
                                            (not for a whole-number field: tshark refuses frame == 1e0),
                                            true / false (a true/false field also takes a whole number:
                                            0 false, any other true, as tshark's), 'a' '\\x0c' (a character:
                                            its number)
    len(raw) == 8   count(value) > 1        functions and arithmetic, as tshark 4.0.17's: len count upper
    {slave + 1} == 13   value - 1 > 2       lower string max min abs; + - * / % & (render/filter_expr.py)
    all value > 2   any code != "CHCF"    quantifiers before a relation, as tshark 4.0.17's: every
                                            occurrence, or some (render/filter_quantifiers.py)

Field names are the keys `-T fields` takes (`-Y help` lists them). Frame fields: frame, kind, offset,
length, time, raw, mode, slave, function, function_name, crc_ok, crc, crc_expected, broadcast, start,
quantity, subfunction, subfunction_name, exception_code (alias: exception), exception_name,
exception_meaning, span_label, write_span_label, request_frame, response_frame, response_time, unanswered,
reason, warnings, notes, file; `fields.KEY` for a key of the PDU as the grammar parsed it (`fields.start`,
`fields.byte_count`; fields.data bytes, as raw; fields.values a repeated number); `registers`, `bits`,
`objects`, `fields` alone test presence.
`time` is the JSON's (seconds since the epoch), compared with a number or a date and time in quotes as
tshark's frame.time is (`time >= "2026-12-05 10:00"`, local time: render/filter_dates.py);
`time_relative` the seconds since the first item of the input, and `time_delta` since the item captured
before (a network or several-interface capture's: since its first packet, and the packet before), as the
time column shows them (tshark's frame.time_relative and frame.time_delta): times, typed as tshark types
those (FT_RELATIVE_TIME), take seconds in decimals (1.5, not 1e-3 or 0x1). A value of an enumerated field
that does not exist is an error naming the nearest ones: kind, mode, status, code (the parameter codes of
the run's maps), profile, function_name, exception_name, exception_meaning and subfunction_name (the spec's
names and those of the run's profiles); so is a `fields.KEY` whose KEY no layout of the protocol table has
(`-G fields` lists them).

Register fields: address, value, code, name, unit, scaled, text, status, source, label. A frame carries
several registers, so these tests ask "is there a register such that...". The rule:

    The register fields of a filter are tested on ONE register at a time, within the nearest enclosing
    `not` (or the whole filter): the frame matches when SOME register makes that part true.

(One relation with register fields on both sides, `value == address`, `value - 1 == value`, is tshark's:
every occurrence of one side meets every occurrence of the other, over the frame: render/filter_expr.py.)
So `code == "CHCF" and status == "protected"` needs both on the same register (CHCF read as protected),
not CHCF somewhere and a protected register elsewhere; `slave == 12 and code == "CHCF"` is "a register
CHCF in a frame of slave 12". `not code == "CHCF"` is "no register is CHCF" (the `not` closes the
scope). `code != "CHCF"` is Wireshark's (since 3.6, also `all_ne`): "some register has a code and none is
CHCF", a scope of its own, while `code ~= "CHCF"` (`any_ne`) is "some register is not CHCF". The registers of a
frame are its `registers` and `bits` (whose address and value these fields test too), plus the
addresses a frame names without carrying a value (a read request's start..start+quantity-1, a FC16
confirmation): `address == 8401` matches the read request, its response and writes of 8401; those
address-only entries have no value, code or status. Where a profile shows PLC-style references
(`40001`), `address` also takes the number shown: `address == 40001` matches the register sent as 0.

A test on a field the item lacks (a noise item's slave, a request's value) is false, `!=` and `~=`
included, as in Wireshark. A register's text keys (code, name, unit, text, status, source, label) are ""
on a register that has none, as -T fields writes them and tshark reads the plugin's hidden empty items:
`code == ""` finds the frames carrying an unnamed register, `code == name` one unnamed register (both
empty), a bare `code` every frame carrying registers; `code matches "."` one named. A bare field tests presence, as in Wireshark 4.0: `crc_ok` is every frame
whose check was made (a bad one too: `crc_ok == 1` is the good ones), `not crc_ok` noise and --hex frames
typed without it; broadcast, unanswered and provisional exist only where true, as the plugin adds them. Errors raise FilterError, whose message shows the expression with a caret under the token.
"""
from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from dissector.render.filter_error import FilterError  # noqa: F401 (re-exported)
from dissector.render.filter_fields import foreign_name
from dissector.render.filter_fields import (  # noqa: F401 (re-exported: fields.py and -Y help use them)
    ALIASES, _TYPE_WORDS, FIELD_HELP, FRAME_FIELDS, ONLY_TRUE, RECORD_KEYS, REGISTER_FIELDS, REGISTER_TEXTS,
    TIME_FILTER_FIELDS,
    field_listing,
    pdu_key_types, pdu_values, unknown_pdu_key, whole_number,
)
from dissector.render.filter_context import (  # noqa: F401
    CHOICES, NUMBERED, SHOWN_CHOICES, SPEC_NAMES, FilterContext, numbered_choices,
)
from dissector.render.filter_match import (
    And,
    address_of,
    address_test,
    address_values,
    any_bit,
    compile_regex,
    any_bit_bytes,
    as_bytes,
    latin1,
    contains_text,
    in_members,
    is_number,
    match_op,
    is_present,
    quantify,
    register_value,
    search,
)

from dissector.render.filter_expr import Operand
from dissector.render.filter_ops import (
    is_field, needs_expression, parse_expression_test, parse_member, parse_reference, set_test,
)
from dissector.render.filter_syntax import parse_layer, parse_set, parse_slice
from dissector.render.filter_quantifiers import elements_pass, every_of, every_present, parse_quantified
from dissector.render.filter_values import (
    TIME_TYPES, bool_literal, kind_of, negative_for_unsigned, time_literal, type_name, uint_limit, unsigned_type,
)
from dissector.render.glossary import field_type
from dissector.render.filter_lexer import NUMBER, Token, number, parse_bytes, tokenize  # noqa: F401

_COMPARISONS = ("==", "!=", "~=", "===", "<", "<=", ">", ">=")
MAX_DEPTH = 64  # nested parentheses and `not`: deeper is certainly a mistake, and recursion is bounded


Item = dict[str, Any]
Test = Callable[[Item, dict[str, Any] | None], bool]


class _Parser:
    def __init__(self, text: str, context: FilterContext | None = None) -> None:
        self.context = context or FilterContext()
        self.text = text
        self.tokens = tokenize(text)
        self.index = 0
        self.depth = 0
        self.every = False  # inside `all RELATION`: every occurrence must pass (filter_quantifiers.py)
        self.member_of = ""  # the field of the set being parsed (its members: parse_member)
        self.presence: Test | None = None
        self.protocol = False  # the field tested is raw as a whole: tshark's frame, a protocol

    @property
    def token(self) -> Token:
        return self.tokens[self.index]

    def advance(self) -> Token:
        token = self.tokens[self.index]
        if token.kind != "end":
            self.index += 1
        return token

    def error(self, message: str, token: Token | None = None) -> FilterError:
        token = token or self.token
        return FilterError(message, self.text, token.position)

    def unexpected(self, why: str) -> FilterError:
        """tshark's refusal of a token out of place (`"13" was unexpected in this context.`), and why."""
        what = "the end of the filter" if self.token.kind == "end" else f"{self.token.text!r}"
        return self.error(f"{what} was unexpected in this context: {why}")

    def at(self, kind: str, *values: str) -> bool:
        token = self.token
        return token.kind == kind and (not values or token.value in values)

    # -- grammar ------------------------------------------------------------------------------
    def parse(self) -> tuple[Test, bool]:
        if self.token.kind == "end":
            raise self.error("empty filter: give an expression such as slave == 12")
        test = self.parse_or()
        if self.token.kind != "end":
            raise self.error(f"unexpected {self._describe(self.token)}: expected and, or or the end")
        return test

    def parse_or(self) -> tuple[Test, bool]:
        parts = [self.parse_and()]
        while self.at("keyword", "or") or self.at("op", "||"):
            self.advance()
            parts.append(self.parse_and())
        if len(parts) == 1:
            return parts[0]
        tests = [test for test, _uses in parts]
        return (lambda item, reg: any(test(item, reg) for test in tests)), any(u for _t, u in parts)

    def parse_and(self) -> tuple[Test, bool]:
        parts = [self.parse_not()]
        while self.at("keyword", "and") or self.at("op", "&&"):
            self.advance()
            parts.append(self.parse_not())
        if len(parts) == 1:
            return parts[0]
        tests = [test for test, _uses in parts]
        conjunction = And(tests)
        frame_tests = [test for test, uses in parts if not uses]
        register_tests = [test for test, uses in parts if uses]
        if frame_tests and register_tests:
            # Frame-level tests are checked once per frame, before any per-register work.
            conjunction.split = (And(frame_tests), And(register_tests))
        return conjunction, bool(register_tests)

    def _enter(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise self.error(f"expression nested more than {MAX_DEPTH} levels deep")

    def parse_not(self) -> tuple[Test, bool]:
        if self.at("keyword", "not") or self.at("op", "!"):
            self.advance()
            self._enter()
            test, uses = self.parse_not()
            self.depth -= 1
            if uses:  # the scope of "some register" closes here: not (some register ...)
                inner = quantify(test)
                return (lambda item, reg: not inner(item)), False
            return (lambda item, reg: not test(item, reg)), False
        return self.parse_primary()

    def parse_primary(self) -> tuple[Test, bool]:
        token = self.token
        if self.at("punct", "("):
            self.advance()
            self._enter()
            result = self.parse_or()
            self.depth -= 1
            if not self.at("punct", ")"):
                raise self.error(f"expected ) to close the ( at column {token.position + 1}")
            self.advance()
            return result
        if self.at("keyword", "any", "all"):
            return parse_quantified(self)
        if needs_expression(self.tokens, self.index):  # functions, arithmetic, a field on the right
            return parse_expression_test(self)
        if token.kind != "name":
            raise self.error(f"expected a field name, found {self._describe(token)}")
        return self.parse_test()

    def parse_test(self) -> tuple[Test, bool]:
        name_token = self.advance()
        field, ftype, register = self.resolve_field(name_token)
        if not parse_layer(self):  # (slave#2: a layer no item has, so no test on it holds)
            _test, register = self._parse_field_test(field, ftype, register)
            return (lambda item, reg: False), register
        return self._parse_field_test(field, ftype, register)

    def _parse_field_test(self, field: str, ftype: str, register: bool) -> tuple[Test, bool]:
        self.protocol = False
        if field.startswith("fields."):
            return self.parse_pdu_key_test(field, field[7:])
        cut = self.parse_slice(field, ftype)
        text_cut = cut is not None and ftype == "str"  # (a text's slice is bytes of its UTF-8, as tshark's)
        self.protocol = field == "raw" and cut is None
        get = self.field_getter(field, ftype, register, cut)
        self.presence = every_present(get)  # (the occurrences `all` asks about: filter_quantifiers.py)
        return self.parse_operation(field, "bytes" if text_cut else ftype, get, register)

    def resolve_field(self, name_token: Token) -> tuple[str, str, bool]:
        """(field, type, whether a register's) of the name at `name_token`; an unknown name is an error."""
        field = ALIASES.get(name_token.value, name_token.value)
        if field.startswith("fields."):
            problem = unknown_pdu_key(field[7:])
            if problem is not None:
                raise self.error(f"unknown field {name_token.text!r}: {problem}", name_token)
            return field, "any", False
        if "." in field:
            # tshark's frame.number, the plugin's vw3.slave, mbrtu.unit_id...: said by the name vw3-decode gives them
            ours = foreign_name(field)
            hint = f" (vw3-decode names it {ours})" if ours is not None else ""
            raise self.error(f"unknown field {name_token.text!r}: only fields.KEY names a key inside a value"
                             f"{hint}", name_token)
        if field in FRAME_FIELDS:
            return field, FRAME_FIELDS[field], False
        if field in REGISTER_FIELDS:
            return field, REGISTER_FIELDS[field], True
        if field in TIME_FILTER_FIELDS:
            return field, TIME_FILTER_FIELDS[field], False
        if field == "time_delta_displayed":
            raise self.error("time_delta_displayed depends on what is shown, so it cannot choose it: "
                             "use time_delta", name_token)
        raise self.error(f"unknown field {name_token.text!r}{self._suggest(name_token.text)}", name_token)

    def field_getter(self, field: str, ftype: str, register: bool, cut: Callable[[bytes], bytes | None] | None
                     ) -> Callable[[Item, dict[str, Any] | None], Any]:
        """How to read `field` (sliced by `cut`) of an item, or of one register of it."""
        context = self.context
        text_cut = cut is not None and ftype == "str"

        def get(item: Item, reg: dict[str, Any] | None) -> Any:
            if register:
                value = register_value(item, reg, field)
                return value if not text_cut or not isinstance(value, str) else cut(value.encode())
            if field in TIME_FILTER_FIELDS:
                return context.seconds(item, field)
            value = item.get(RECORD_KEYS.get(field, field))
            if ftype == "bytes":  # (hex text in the item)
                value = as_bytes(value)
                return value if cut is None or value is None else cut(value)
            if text_cut:
                return cut(value.encode()) if isinstance(value, str) else None
            return None if value is False and field in ONLY_TRUE else value

        return get

    def parse_slice(self, field: str, ftype: str) -> Callable[[bytes], bytes | None] | None:
        return parse_slice(self, field, ftype)  # (render/filter_syntax.py)

    def parse_pdu_key_test(self, field: str, key: str) -> tuple[Test, bool]:
        """`fields.KEY OP value`: a key holding a list (fields.values, fields.sub_requests...) is a repeated
        field, as in Wireshark: the test holds when one element passes it, `!=` when every element differs."""
        all_ne = self.at("op", "!=")
        all_eq = self.at("op", "===")
        ftype = {"uint": "number", "byte": "bytes"}.get(pdu_key_types().get(key, "")[:4], "any")
        if ftype == "bytes":  # (hex text in the item)
            test, _ = self.parse_operation(field, ftype, lambda item, element: as_bytes(element), False)
        else:
            test, _ = self.parse_operation(field, ftype, lambda item, element: element, False)

        def elements(item: Item) -> list[Any]:
            return pdu_values(item.get("fields"), key)

        if all_ne or all_eq or self.every:
            return (lambda item, reg: bool(values := elements(item)) and all(test(item, v) for v in values)), False
        return (lambda item, reg: any(test(item, v) for v in elements(item))), False

    def parse_operation(self, field: str, ftype: str, get: Callable[..., Any], register: bool) -> tuple[Test, bool]:
        """What follows a field's name: an operator and its value, or nothing (presence)."""
        token = self.token
        if ftype == "struct":
            if not (self.at("end") or self.at("punct", ")") or self.at("keyword", "and", "or") or self.at("op", "&&", "||")):
                hint = " (fields.KEY tests one of its keys)" if field == "fields" else ""
                raise self.error(f"{field} is a structure: alone, it tests its presence{hint}", token)
            return (lambda item, reg: is_present(get(item, reg))), register
        if self.at("op", "&"):
            self.advance()
            if ftype not in ("number", "any", "bytes"):
                raise self.error(f"& tests bits of a number; {field} is a {_TYPE_WORDS[ftype]}", token)
            if ftype == "number" and kind_of(field_type(field)) != "int":  # (a time, a decimal: as tshark)
                raise self.error(f"& tests bits of a whole number; {field} is {type_name(field_type(field))}",
                                 token)
            mask_token = self.token
            mask = self.parse_value(field, "any" if ftype == "number" else ftype)  # (1.5: named below)
            if ftype == "bytes":  # (some bit set in both, over the shorter: tshark's frame[0:2] & 0f)
                return (lambda item, reg: any_bit_bytes(get(item, reg), mask)), register
            if not isinstance(mask, int):
                raise self.error("& needs a whole-number mask such as 0x8000", mask_token)
            if self.token.kind == "op" and self.token.value in _COMPARISONS:  # value & 0x8000 == 0x8000
                def masked(item: Item, reg: dict[str, Any] | None) -> Any:
                    value = get(item, reg)
                    return value & mask if is_number(value) and isinstance(value, int) else None

                return self._relation(field, "number", masked, register, self.token)
            return (lambda item, reg: any_bit(get(item, reg), mask)), register
        if self.at("keyword", "matches") or self.at("op", "~"):
            self.advance()
            if ftype not in ("str", "list", "any", "bytes"):
                raise self.error(f"matches needs a text field; {field} is a {_TYPE_WORDS[ftype]}", token)
            pattern_token = self.token
            if pattern_token.kind == "char":
                raise self.error("matches takes a regular expression in double quotes, not a character "
                                 "constant (as tshark)")
            pattern = compile_regex(self.parse_value(field, "str"), self.text, pattern_token.position)
            if ftype == "bytes":  # each byte a character: "\x0c\x03" matches the bytes 0c 03
                return (lambda item, reg: search(pattern, latin1(get(item, reg)))), register
            if ftype == "list":
                every = self.every
                return (lambda item, reg: elements_pass(every, get(item, reg),
                                                        lambda v: isinstance(v, str) and pattern.search(v))), register
            return (lambda item, reg: search(pattern, get(item, reg))), register
        if field == "address":
            get = address_of
        if token.kind == "op" and token.value not in ("!", "&&", "||"):  # (crc_ok && ...: a bare crc_ok)
            return self._relation(field, ftype, get, register, token)
        if self.at("keyword", "contains"):
            self.advance()
            if ftype not in ("str", "list", "any", "bytes"):
                kind = _TYPE_WORDS[ftype]
                raise self.error(f"contains needs a text or bytes field; {field} is a {kind}", token)
            if ftype == "bytes":
                data = self.parse_value(field, ftype)
                if not data and self.protocol:  # (tshark's frame contains no empty bytes; its slice does)
                    return (lambda item, reg: False), register
                return (lambda item, reg: isinstance(got := get(item, reg), bytes) and data in got), register
            value = self.parse_value(field, "str")
            if ftype == "list":
                every = self.every
                return (lambda item, reg: elements_pass(every, get(item, reg),
                                                        lambda v: contains_text(v, value))), register
            return (lambda item, reg: contains_text(get(item, reg), value)), register
        if self.at("keyword", "in"):
            if ftype == "bytes":
                raise self.error(f"in takes numbers or texts; {field} is a byte string (tshark 4.0 refuses "
                                 "it too): compare with == or contains")
            self.advance()
            self.member_of = field
            members = self.parse_set(field, ftype)
            if any(isinstance(bound, Operand) for member in members for bound in member):
                return set_test(get, register, members, self.every,  # (value in {address}, tshark's)
                                unsigned_type(field_type(field))), False
            if field == "address":
                def inside(item: Item, reg: dict[str, Any] | None, members: list[Any] = members) -> bool:
                    return any(in_members(v, members) for v in address_values(reg))
            else:
                def inside(item: Item, reg: dict[str, Any] | None, members: list[Any] = members) -> bool:
                    return in_members(get(item, reg), members)
            if self.every and register:  # all x in {a, b}: all x are a, or all are b (tshark 4.0.17's)
                present = every_present(get)
                tests = [every_of(lambda item, reg, m=[m]: inside(item, reg, m), present) for m in members]
                return (lambda item, reg: any(test(item, reg) for test in tests)), False
            return inside, register
        literal = token.kind in ("number", "string", "name", "bytes", "dashed", "slice")
        if literal or self.at("keyword", "true", "false"):
            raise self.error(f"expected an operator (== != ~= < <= > >= & in contains matches) after {field}")
        return (lambda item, reg: is_present(get(item, reg))), register

    def _relation(self, field: str, ftype: str, get: Callable[..., Any], register: bool, token: Token
                  ) -> tuple[Test, bool]:
        """`field OP value` with OP at `token`, over the frame's registers for a register's field."""
        if token.value == "!=" and register:
            # Wireshark's `a != b` (all_ne, since 3.6): some register has the field and none has it equal to b.
            equal = self.parse_comparison(field, ftype, get, "==", token)
            some_equal = quantify(equal)
            some_present = quantify(lambda item, reg: is_present(get(item, reg)))
            return (lambda item, reg: some_present(item) and not some_equal(item)), False
        if token.value == "===" and register:
            # Wireshark 4.0's all_eq: some register has the field and every one that has it has it equal.
            differs = quantify(self.parse_comparison(field, ftype, get, "~=", token))
            some_present = quantify(lambda item, reg: is_present(get(item, reg)))
            return (lambda item, reg: some_present(item) and not differs(item)), False
        return self.parse_comparison(field, ftype, get, token.value, token), register

    def parse_comparison(self, field: str, ftype: str, get: Callable[..., Any], op: str, token: Token) -> Test:
        """`field OP value` on one register (or the frame): `~=` is "differs", as `!=` was before Wireshark 3.6."""
        self.advance()
        written = token.value
        value_token = self.token
        value = self.parse_value(field, ftype)
        if negative_for_unsigned(field, value):  # (tshark 4.0.17: slave > -1 holds for no frame)
            # none is equal (all_ne), none differs (all_eq), none fails (all >): only these hold
            holds = op in ("!=", "===") or self.every
            return lambda item, reg: holds and is_present(get(item, reg))
        if ftype == "list":
            if op == "!=":  # all_ne: some element, and none equal
                return lambda item, reg: bool(get(item, reg)) and all(v != value for v in get(item, reg))
            if op == "===":  # all_eq: some element, and all equal
                return lambda item, reg: bool(get(item, reg)) and all(v == value for v in get(item, reg))
            if op == "~=":  # any_ne: some element differs
                return lambda item, reg: any(v != value for v in get(item, reg) or ())
            if op != "==":
                raise self.error(f"{field} is a list of texts: use ==, !=, ~=, === or contains", token)
            return lambda item, reg: any(v == value for v in get(item, reg) or ())
        if op == "===":
            op = "=="  # one value (a frame's, one register's, one element's): all of it is equal
        if written in ("==", "!=", "~=", "===") and not isinstance(value, bytes):  # (a misspelt name)
            self._check_choice(field, value, value_token)
        if field == "time" and isinstance(value, (int, float)) and 0 <= value < 1e9 and written not in ("!=", "~="):
            raise self.error(
                f"time is seconds since the epoch (as --json prints it), and {value_token.text} is no date: "
                "time_relative counts from the first item, as the time column", value_token)
        if op == "~=":
            op = "!="  # one value (a frame's, or one register's): it is there and differs
        if field == "address":
            return address_test(op, value)
        if field in NUMBERED and op not in ("==", "!="):  # (ordered by the plugin's numbers, as tshark orders them)
            self._check_choice(field, value, value_token)
            rank = {name: number for number, name in enumerate(NUMBERED[field], 1)}
            return lambda item, reg: match_op(op, rank.get(get(item, reg)), rank[value])
        return lambda item, reg: match_op(op, get(item, reg), value)

    def parse_value(self, field: str, ftype: str) -> Any:
        token = self.token
        if token.kind == "end":
            raise self.error(f"expected a value to compare {field} with")
        if token.kind == "char" and ftype in ("str", "list", "bytes"):  # 'R': a text's character, a byte
            self.advance()
            return bytes([token.value]) if ftype == "bytes" else chr(token.value)
        if ftype == "bool":  # true, false, or a whole number as tshark 4.0.17 takes them (crc_ok == 2: true)
            value = bool_literal(token, self.text, field)
            self.advance()
            return value
        if field == "time" and token.kind == "string":  # a date and time, as tshark's frame.time takes
            from dissector.render.filter_dates import EXAMPLES, absolute_time

            seconds = absolute_time(token.value)
            if seconds is None:
                raise self.error(f"{token.text} is no date and time: write {EXAMPLES}")
            self.advance()
            return seconds
        if ftype == "bytes":  # 0c:03 0c-03 0c.03 0c03, or a string: its characters' bytes (\x0c too)
            data = token.data if token.kind == "string" else parse_bytes(token)
            if data is None:
                raise self.error(f"{field} is a byte string: write its bytes in hex as 0c:03 (or 0c-03, "
                                 f"0c.03, 0c03), not {self._describe(token)}")
            self.advance()
            return data
        if ftype == "number":
            return self.parse_number(field, token)
        if ftype == "any":  # a key of the PDU's fields: a number, a text (bytes as hex), true or false
            if token.kind in ("number", "string", "char"):
                self.advance()
                return token.value
            if self.at("keyword", "true", "false"):
                self.advance()
                return token.value == "true"
            raise self.error(f"{field} takes a number or a text in double quotes, not {self._describe(token)}")
        if field in NUMBERED:
            return self._numbered(field, token)
        if token.kind != "string":
            hint = ' (strings go in double quotes: "...")' if token.kind in ("name", "number") else ""
            raise self.error(f"{field} is a text, not {self._describe(token)}{hint}")
        self.advance()
        return token.value

    def _numbered(self, field: str, token: Token) -> str:
        """A value of a field the plugin numbers (NUMBERED): its name, from the number or the name in any case
        (a misspelt name is left to _check_choice, which suggests one)."""
        names = NUMBERED[field]
        if token.kind == "number" and token.value in range(1, len(names) + 1):
            self.advance()
            return names[token.value - 1]
        if token.kind in ("string", "name"):
            name = str(token.value).lower()
            self.advance()
            return name if name in names else str(token.value)
        raise self.error(f"{field} {token.text} does not exist: {field} is one of {numbered_choices(field)}")

    def parse_number(self, field: str, token: Token) -> int | float:
        """A number for `field`: 1.5 and 13.5e-3 for a decimal one, but as tshark refuses `vw3.item == 1e0`
        a whole-number field (an integer or frame number) takes whole numbers only."""
        if token.kind == "dashed":  # (as tshark refuses it: 1-3 read as 1 and -3 would match frame 1 alone)
            low, high = token.text.split("-")
            raise self.error(f"{token.text!r} is not a number: a range is written {low}..{high}")
        if token.kind == "bytes" and (NUMBER.fullmatch(token.text) or token.text[:2] in ("0b", "0B")):
            # (12.50, 1e0 and 0b1100 are read as bytes first)
            token = Token("number", token.text, number(token.text, self.text, token.position), token.position)
        ftype = field_type(field)
        if ftype in TIME_TYPES:  # seconds in decimals: tshark 4.0.17 refuses 1e-3, 0x1, '\x01' for a time
            seconds = time_literal(token.text) if token.kind in ("number", "bytes") else None
            if seconds is None:
                raise self.error(f"{token.text} is not a valid time: {field} takes seconds written as 1.5 "
                                 "(no exponent, hex or character; 9 decimals at most, as tshark)")
            self.advance()
            return seconds
        if token.kind != "number" and token.kind != "char":
            raise self.error(f"{field} is a number, not {self._describe(token)}")
        if isinstance(token.value, float) and whole_number(field):
            raise self.error(f"{field} is a whole number, and {token.text} is not written as one "
                             "(as tshark refuses it)")
        limit = uint_limit(ftype)
        if limit is not None and abs(token.value) > limit:  # (-300 for a uint8 too: tshark reads - apart)
            raise self.error(f"{token.text} is too big for {field}, {type_name(ftype)}: at most {limit} "
                             "(as tshark refuses it)")
        self.advance()
        return token.value

    def parse_set(self, field: str, ftype: str) -> list[tuple[Any, Any]]:
        return parse_set(self, field, ftype)  # (render/filter_syntax.py)

    def parse_reference(self) -> Any:
        return parse_reference(self)  # ${slave} (render/filter_ops.py; a set's member: filter_syntax.py)

    def parse_member(self) -> Any:
        return parse_member(self, self.member_of)  # a set's member that is a field or a function

    @staticmethod
    def is_field(token: Token) -> bool:
        return is_field(token)

    # -- messages -----------------------------------------------------------------------------
    def _check_choice(self, field: str, value: Any, token: Token) -> None:
        refusal = self.context.refusal(field, value)
        if refusal is not None:
            raise self.error(refusal, token)

    @staticmethod
    def _describe(token: Token) -> str:
        if token.kind == "end":
            return "the end of the filter"
        return f"{token.text!r}"

    @staticmethod
    def _suggest(name: str) -> str:
        import difflib

        names = [*FRAME_FIELDS, *REGISTER_FIELDS, *ALIASES, *TIME_FILTER_FIELDS]
        close = difflib.get_close_matches(name.lower(), names, n=1)
        return f" (did you mean {close[0]}?)" if close else ""


def compile_filter(text: str, context: FilterContext | None = None) -> Callable[[Item], bool]:
    """Compile a display filter to a predicate on item dicts. Raises FilterError."""
    if not isinstance(text, str):
        raise FilterError("a filter is text", "", 0)
    test, uses_registers = _Parser(text, context).parse()
    if uses_registers:
        return quantify(test)
    return lambda item: test(item, None)
