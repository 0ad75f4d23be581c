"""Display-filter functions, arithmetic and character constants as tshark 4.0.17 takes them (render/
filter_expr.py, filter_functions.py, filter_ops.py), and times typed as tshark types frame.time_*: each
filter selects the frames tshark selects with the plugin (vw3.* for the keys, frame for raw, frame.time_* for
the times; tests/integration/test_filter_functions_as_tshark.py runs tshark on a part of them), and each
construct tshark refuses is refused in one line, exit 2. Before, every one of these was refused or, for
`slave + 1`, read as a comparison."""
from __future__ import annotations

import pytest

from conftest import ROOT
from helpers import run_cli

from dissector.render.filter_error import FilterError
from dissector.render.filter_lexer import tokenize
from dissector.render.filters import compile_filter

NOISY = str(ROOT / "captures" / "noisy_bus.pcap")
P38 = str(ROOT / "captures" / "p38_protection.pcap")
ATV71 = str(ROOT / "captures" / "atv71_commissioning.pcap")
ALL_NOISY = list(range(1, 39))
MODBUS = [n for n in ALL_NOISY if n not in (1, 34)]  # (1 and 34: noise)
SLAVE_12 = [2, 3, 6, 7, 10, 11, 14, 15, 20, 21, 24, 25, 30, 31, 35, 36]
ANSWERS = [3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 31, 33, 36, 38]  # noisy_bus's responses


def frames(expression: str, capture: str) -> list[int]:
    status, out, err = run_cli(["-Y", expression, "-T", "fields", "-e", "frame", capture])
    assert (status, err) == (0, ""), err
    return [int(line) for line in out.split()]


@pytest.mark.parametrize(("capture", "expression", "expected"), [
    # each as tshark 4.0.17 -2 with the plugin selects (the same filter on vw3.*, frame, frame.time_*)
    (NOISY, 'len(raw) == 8', [2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 29, 30, 32, 35, 37]),
    (NOISY, 'len(raw) != 8', [1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 31, 33, 34, 36, 38]),
    (NOISY, 'len(function_name) > 21', MODBUS),
    (NOISY, 'len(slave) == 1', MODBUS),
    (NOISY, 'len(crc) == 2', MODBUS),
    (NOISY, 'len(crc_ok) == 0', MODBUS),
    (NOISY, 'len(frame) == 4', ALL_NOISY),
    (NOISY, 'len(response_time) == 0', ANSWERS),
    (NOISY, 'len(value) == 2', ANSWERS),
    (NOISY, 'upper(function_name) contains "READ"', MODBUS),
    (NOISY, 'lower(function_name) == "read holding registers"', MODBUS),
    (NOISY, 'upper(function_name) matches "^WRITE"', []),
    (NOISY, 'lower(function_name)[0:4] == "read"', MODBUS),
    (NOISY, 'count(value) == 2', [3, 7, 11, 15, 21, 25, 31, 36]),
    (NOISY, 'count(address) == 2', [2, 3, 6, 7, 10, 11, 14, 15, 20, 21, 24, 25, 28, 29, 30, 31, 35, 36]),
    (NOISY, 'count(slave) == 1', MODBUS),
    (NOISY, 'string(slave) == "12"', SLAVE_12),
    (NOISY, 'string(crc) == "29492"', []),
    (NOISY, 'max(slave, 10) == 12', SLAVE_12),
    (NOISY, 'min(slave, 10) == 10', [1, 2, 3, 6, 7, 10, 11, 14, 15, 20, 21, 24, 25, 30, 31, 34, 35, 36]),
    (NOISY, 'max(value) > 100', ANSWERS),
    (NOISY, 'min(value) == 0', [3, 7, 11, 15, 21, 25, 31, 36]),
    (NOISY, 'max(slave, function) == 12', SLAVE_12),
    (NOISY, 'abs(slave - 20) == 8', SLAVE_12),
    (NOISY, 'abs(response_time - 1) > 0.99', []),
    (NOISY, 'abs(time_relative) > 1.5', [35, 36, 37, 38]),
    (NOISY, 'slave + 1 == 13', SLAVE_12),
    (NOISY, '{slave + 1} == 13', SLAVE_12),
    (NOISY, 'slave == 11 + 1', SLAVE_12),
    (NOISY, 'slave == {12 + 0}', SLAVE_12),
    (NOISY, 'slave == 2 * 6 + 0', SLAVE_12),
    (NOISY, '-slave == -12', SLAVE_12),
    (NOISY, 'slave -1 == 11', SLAVE_12),
    (NOISY, '{slave - 20} < 0', MODBUS),
    (NOISY, '{slave / 5} == 2', SLAVE_12),
    (NOISY, '{slave % 5} == 2', SLAVE_12),
    (NOISY, '{slave & 4} == 4', [2, 3, 6, 7, 10, 11, 14, 15, 20, 21, 24, 25, 28, 29, 30, 31, 35, 36]),
    (NOISY, 'slave & 4 + 1 == 5', [28, 29]),
    (NOISY, '{slave * 30} > 255', SLAVE_12),
    (NOISY, '{slave / 0} == 1', []),
    (NOISY, '{slave - 12}', [4, 5, 8, 9, 12, 13, 16, 17, 18, 19, 22, 23, 26, 27, 28, 29, 32, 33, 37, 38]),
    (NOISY, 'slave + 1', MODBUS),
    (NOISY, '{slave + function} == 15', SLAVE_12),
    (NOISY, '{slave + value} > 0', ANSWERS),
    (NOISY, 'value - address < 0', [3, 7, 11, 15, 21, 25, 31, 36]),
    (NOISY, 'response_time + 1 > 1.01', [5, 7, 9, 13, 17, 27, 31, 36, 38]),
    (NOISY, 'response_time - 1 < 0', ANSWERS),
    (NOISY, 'time_relative + 1 > 2.5', [35, 36, 37, 38]),
    (NOISY, 'time_delta - time_relative < 0', ALL_NOISY[2:]),
    (NOISY, '{time_relative - 2} < 0', ALL_NOISY),
    (NOISY, 'time_relative > 1.5', [35, 36, 37, 38]),
    (NOISY, 'time_relative > 1', [29, 30, 31, 32, 33, 34, 35, 36, 37, 38]),
    (NOISY, 'time_relative > +1', [29, 30, 31, 32, 33, 34, 35, 36, 37, 38]),
    (NOISY, 'time_relative > -1', ALL_NOISY),
    (NOISY, 'time_relative == 0', [1]),
    (NOISY, 'time_relative in {1..2}', [29, 30, 31, 32, 33, 34, 35, 36, 37, 38]),
    (NOISY, 'time_delta > 0.05', [6, 10, 14, 20, 24, 29, 30, 35]),
    (NOISY, 'time > 1767225601.5', [35, 36, 37, 38]),
    (NOISY, 'max(time_relative, 1) > 1', [29, 30, 31, 32, 33, 34, 35, 36, 37, 38]),
    (NOISY, "slave == 'a'", []),
    (NOISY, "slave == '\\x0c'", SLAVE_12),
    (NOISY, "slave == '\\014'", SLAVE_12),
    (NOISY, "slave == '\\f'", SLAVE_12),
    (NOISY, "raw[0] == '\\x0c'", SLAVE_12),
    (NOISY, "raw contains '\\x0c'", SLAVE_12),
    (NOISY, "function_name contains 'R'", MODBUS),
    (NOISY, "crc_ok == '\\x01'", [n for n in MODBUS if n != 17]),  # (17: bad CRC)
    (NOISY, "slave in {'\\x0c', 'a'}", SLAVE_12),
    (NOISY, "slave in {'\\x0c'..'\\x0d'}", SLAVE_12),
    (NOISY, 'slave == slave', MODBUS),
    (NOISY, 'slave != function', MODBUS),
    (NOISY, 'slave == {slave}', MODBUS),
    (NOISY, 'upper(function_name) == lower(function_name)', []),
    (NOISY, 'len(slave) == len(function)', MODBUS),
    (NOISY, 'slave + 1 == 13 and function == 3', SLAVE_12),
    (NOISY, 'not slave + 1 == 13', [n for n in ALL_NOISY if n not in SLAVE_12]),
    (NOISY, 'raw[0] == raw[0]', ALL_NOISY),
    (P38, 'count(value) > 1', [2, 4, 6, 8]),
    (P38, 'count(value) != 1', [2, 4, 6, 8]),
    (P38, 'len(code) == 4', [2, 4, 6, 8, 10, 12]),
    (P38, 'len(code) != 4', []),
    (P38, 'max(value) == 2', []),
    (P38, '{value - address} < 0', [2, 4, 6, 8]),
    (P38, 'value & 0x8000 == 0x8000', [2, 4, 6, 8]),
    (ATV71, 'string(scaled) == "2.1000000000000001"', [34]),
    (ATV71, 'string(scaled) == "4"', [4]),
    (ATV71, 'string(value) == "2"', [6, 7, 8]),
    (ATV71, 'len(function_name) == 22', [3, 4, 5, 6, 13, 14, 15, 16]),
    (ATV71, 'max(value, 3) == 3', [1, 2, 3, 5, 6, 7, 8, 13, 15, 18, 63, 64, 103, 104]),
    (ATV71, 'upper(code) == "CHCF"', [6, 7, 8, 63, 103, 104]),
    (ATV71, 'len(code) === 4', [7, 8, 63, 103, 104]),
    (ATV71, 'value + 1 === 3', [7, 8]),
])
def test_selects_as_tshark(capture: str, expression: str, expected: list[int]) -> None:
    assert frames(expression, capture) == expected


@pytest.mark.parametrize(("expression", "message"), [
    # each refused by tshark 4.0.17 too (its words in the comment where ours differ)
    ("len(slave)", "len(slave) alone tests nothing: compare it, as len(slave) > 0 (tshark cannot test "
     "whether a function is present) (column 1)"),
    ("count(value)", "count(value) alone tests nothing: compare it, as count(value) > 0 (tshark cannot test "
     "whether a function is present) (column 1)"),
    ("nosuch(slave) == 1", "function 'nosuch' does not exist (len, count, upper, lower, string, max, min, "
     "abs) (column 1)"),
    ("LEN(slave) == 1", "function 'LEN' does not exist (len, count, upper, lower, string, max, min, abs) "
     "(column 1)"),
    ("max() == 12", "max() needs at least 1 argument (column 1)"),
    ("len(slave, function) == 1", "len() takes 1 argument (column 1)"),
    ('len("abc") == 3', 'only a field can be given to len() (as tshark), not "abc" (column 1)'),
    ("len(raw[0:2]) == 2", "only a field can be given to len() (as tshark), not raw (column 1)"),
    ('upper(slave) == "12"', "upper() takes a text field; slave is an unsigned 8-bit number (FT_UINT8) "
     "(column 1)"),
    ('string(function_name) == "x"', "string() takes a number field; function_name is a text (FT_STRING) "
     "(as tshark) (column 1)"),
    ('string(time_relative) == "1"', "string() takes a number field; time_relative is a time "
     "(FT_RELATIVE_TIME) (as tshark) (column 1)"),
    ("min(value, slave) == 0", "the arguments of min() have one type: value is FT_UINT16, slave FT_UINT8 "
     "(as tshark) (column 1)"),
    ("max(slave, 1.5) == 12", "1.5 is not a whole number, and this is an unsigned 8-bit number (FT_UINT8) "
     "(as tshark refuses it) (column 12)"),
    ("abs(-3) == 3", "abs(-3) is a constant: give it a field (column 5)"),
    ("len(slave) in {1, 2}", "only a field can be tested for membership in a set (as tshark), not len(slave) "
     "(column 12)"),
    ('len(function_name) matches "1"', "len(function_name) is an unsigned 32-bit number (FT_UINT32): it "
     "cannot take matches (as tshark) (column 20)"),
    ('len(function_name) == "22"', '"22" is a string, and this is an unsigned 32-bit number (FT_UINT32) '
     "(column 23)"),
    ("{slave * 1.5} == 18", "1.5 is not a whole number, and this is an unsigned 8-bit number (FT_UINT8) "
     "(as tshark refuses it) (column 10)"),
    ("{response_time * 2} > 0.01", "response_time is a time (FT_RELATIVE_TIME): it cannot * (as tshark) "
     "(column 16)"),
    ('function_name + "x" == "a"',
     "function_name is a text (FT_STRING): it cannot + (as tshark) (column 15)"),
    ("crc_ok + 1 == 2", "crc_ok is a true/false (FT_BOOLEAN): it cannot + (as tshark) (column 8)"),
    ("slave + response_time > 1", "slave and response_time are not type compatible (FT_UINT8, "
     "FT_RELATIVE_TIME) (column 7)"),
    ("slave + 300 > 0", "300 is too big for an unsigned 8-bit number (FT_UINT8): at most 255 (as tshark) "
     "(column 9)"),
    ("{slave * 200} == 2400", "2400 is too big for an unsigned 8-bit number (FT_UINT8): at most 255 (as "
     "tshark) (column 18)"),
    ("slave == 256", "256 is too big for slave, an unsigned 8-bit number (FT_UINT8): at most 255 (as tshark "
     "refuses it) (column 10)"),
    ("slave == 12 + 'a'", "'a' is not a valid arithmetic operand (a character constant) (column 15)"),
    ("slave == -'a'", "'a' is not a valid arithmetic operand (a character constant) (column 11)"),
    ("slave-1 == 11", "slave-1 is no field: put spaces around - to subtract (column 1)"),
    ("12 == slave", "expected a field name, found '12' (column 1)"),
    ("time_relative & 1", "& tests bits of a whole number; time_relative is a time (FT_RELATIVE_TIME) "
     "(column 15)"),
    # a time takes seconds in decimals (tshark: '"1e-3" is not a valid time', 'Character constant 0x1 cannot
    # be converted to Time offset', 'Time offset cannot be converted from a string ("1.5")')
    ("response_time > 1e-3", "1e-3 is not a valid time: response_time takes seconds written as 1.5 (no "
     "exponent, hex or character; 9 decimals at most, as tshark) (column 17)"),
    ("time_relative > 0x1", "0x1 is not a valid time: time_relative takes seconds written as 1.5 (no "
     "exponent, hex or character; 9 decimals at most, as tshark) (column 17)"),
    ("time_relative > '\\x01'", "'\\x01' is not a valid time: time_relative takes seconds written as 1.5 "
     "(no exponent, hex or character; 9 decimals at most, as tshark) (column 17)"),
    ('time_relative > "1.5"', '"1.5" is not a valid time: time_relative takes seconds written as 1.5 (no '
     "exponent, hex or character; 9 decimals at most, as tshark) (column 17)"),
    ("time_relative > 1.50000000001", "1.50000000001 is not a valid time: time_relative takes seconds "
     "written as 1.5 (no exponent, hex or character; 9 decimals at most, as tshark) (column 17)"),
    # character constants as tshark 4.0.17 reads them
    ("raw[0] == 'ab'", "'ab' is too long to be a valid character constant (column 11)"),
    ("slave == ''", "empty character constant (column 10)"),
    ("slave == '\\e'", "'\\e' isn't a valid character constant (column 10)"),
    ("slave == '\\n'", "'\\n' isn't a valid character constant (column 10)"),  # (tshark: "too long")
    ("slave == '\\x0c1'", "'\\x0c1' is too long to be a valid character constant (column 10)"),
    ("slave == '\\400'", "'\\400' is too large to be a valid character constant (column 10)"),
    ("slave == 'a", "the final quote was missing from a character constant (column 10)"),
    ("function_name matches 'R'", "matches takes a regular expression in double quotes, not a character "
     "constant (as tshark) (column 23)"),
])
def test_refused_as_tshark_refuses(expression: str, message: str) -> None:
    status, out, err = run_cli(["-Y", expression, NOISY])
    assert (status, out) == (2, "")
    assert err.splitlines()[0] == f"vw3-decode: {message}"


@pytest.mark.parametrize(("text", "value"), [
    ("'a'", 97), ("'\\x0c'", 12), ("'\\x4'", 4), ("'\\014'", 12), ("'\\377'", 255), ("'\\''", 39),
    ("'\\\\'", 92), ("'\\\"'", 34), ("'\\f'", 12), ("'\\t'", 9), ("' '", 32), ("'\"'", 34),
])
def test_a_character_constant_is_its_number(text: str, value: int) -> None:
    tokens = tokenize(f"slave == {text}")
    assert (tokens[2].kind, tokens[2].value) == ("char", value)


def test_minus_after_an_operand_subtracts() -> None:
    assert [(t.kind, t.value) for t in tokenize("slave -1 == 11")][:3] == [("name", "slave"), ("op", "-"),
                                                                         ("number", 1)]
    assert [(t.kind, t.value) for t in tokenize("slave == -1")][2] == ("number", -1)


def test_a_register_field_is_one_register_at_a_time() -> None:
    # lower(code) == "chcf" && value == 2: on one register (the filter's rule), where tshark takes CHCF
    # anywhere and a 2 anywhere in the frame (frame 6 there: CHCF and a 2 in two registers)
    assert frames('lower(code) == "chcf" && value == 2', ATV71) == [7, 8]
    # count, max and min take the frame's every register, as tshark's
    assert frames("count(value) == 2 && max(value) > 100", NOISY) == [3, 7, 11, 15, 21, 25, 31, 36]


def test_costs_stay_bounded() -> None:
    # the pairs of an operation are the occurrences squared at most, each once
    test = compile_filter("{fields.values + fields.values} == 80")
    item = {"fields": {"values": list(range(0, 125))}}
    assert test(item)
    test = compile_filter("len(function_name) > 1000")
    assert not test({"function_name": "x" * 1000})
    assert compile_filter("len(function_name) == 1000")({"function_name": "x" * 1000})


def test_glossary_types_times_as_tshark() -> None:
    lines = run_cli(["-G", "fields"])[1].splitlines()
    for key in ("time", "time_relative", "time_delta", "time_delta_displayed", "response_time"):
        row = next(line for line in lines if line.split("\t")[2] == key)
        assert row.split("\t")[3] == "FT_RELATIVE_TIME"  # (was FT_DOUBLE but response_time)


def test_a_function_error_is_a_filter_error() -> None:
    with pytest.raises(FilterError, match="does not exist"):
        compile_filter("nosuch(slave) == 1")


@pytest.mark.parametrize(("expression", "expected"), [
    # `comment`: the record's packet comments (its JSON `comments`), one occurrence each, as tshark's
    # frame.comment (FT_STRING); app/cli.py hands them to the filter with the record (d072bdf)
    ("comment", [1, 2]),
    ("!comment", [3]),
    ('comment == "again"', [2]),
    ('comment contains "pump"', [1]),
    ('comment matches "^PUMP"', [1]),
    ("count(comment) == 2", [2]),
    ("len(comment) > 6", [1]),
    ('upper(comment) == "ANSWER"', [2]),
    ('comment != "answer"', [1]),
])
def test_comment_is_tsharks_frame_comment(expression: str, expected: list[int]) -> None:
    records = [{"frame": 1, "comments": ["pump 2 check"]}, {"frame": 2, "comments": ["answer", "again"]},
               {"frame": 3}]
    test = compile_filter(expression)
    assert [record["frame"] for record in records if test(record)] == expected


def test_fields_writes_each_comment() -> None:
    from dissector.render.fields import FieldsOptions, FieldsWriter

    writer = FieldsWriter(FieldsOptions(("frame", "comment")))
    assert writer.line({"frame": 2, "comments": ["answer", "again"]}) == "2\tanswer,again"
    assert writer.line({"frame": 3}) == "3\t"
    lines = run_cli(["-G", "fields"])[1].splitlines()
    assert ("F\tComment\tcomment\tFT_STRING\tvw3\t\t0x0\ta pcapng packet comment (tshark's frame.comment), "
            "one occurrence each") in lines


def test_a_long_arithmetic_chain_is_refused_not_a_crash() -> None:
    # each operation nests a call when computed: past 128 the filter is refused (before: RecursionError)
    assert compile_filter("slave" + " + 1" * 128 + " == 140")({"slave": 12})
    for text in ("slave" + " + 1" * 5000 + " == 3", "slave == 1" + " + 1" * 5000, "-" * 200 + "slave == 1"):
        with pytest.raises(FilterError):
            compile_filter(text)


@pytest.mark.parametrize("expression", [
    'warnings == - "a"',  # (before: TypeError, bad operand type for unary -)
    'fields.data === - "protected"',
    "+ fields.data",
    "- raw == 1",
])
def test_a_sign_on_a_text_or_bytes_is_refused(expression: str) -> None:
    with pytest.raises(FilterError):
        compile_filter(expression)


def test_bytes_of_a_key_that_are_no_hex_are_no_value() -> None:
    # (before: ValueError from bytes.fromhex)
    assert not compile_filter("fields.data == fields.data")({"fields": {"data": "zz"}})
    assert compile_filter("fields.data == fields.data")({"fields": {"data": "0c03"}})


def test_a_frame_wide_function_is_computed_once_per_frame() -> None:
    # count(address) == address compares each register with the frame's count: the count is computed once
    # per item (not once per register: a read of 2000 addresses was 2000 counts of 2000), anew for the next
    import dissector.render.filter_expr as expr

    calls = []
    original = expr.item_elements
    expr.item_elements = lambda item: calls.append(1) or original(item)  # type: ignore[assignment]
    try:
        test = compile_filter("count(address) == address")
        assert test({"kind": "request", "function": 3, "start": 0, "quantity": 2000}) is False
        assert len(calls) == 1  # (the count, once: before, once per register, 2000)
        assert test({"kind": "request", "function": 3, "start": 1, "quantity": 2}) is True  # (address 2)
    finally:
        expr.item_elements = original  # type: ignore[assignment]
