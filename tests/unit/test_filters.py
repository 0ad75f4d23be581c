"""Display filters: exact matches on the sample captures, the per-register rule, errors, fuzzing."""
from __future__ import annotations

import functools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dissector.framing.ascii import AsciiFramer
from dissector.render.filters import FilterError, compile_filter
from dissector.pipeline import dissect
from dissector.devices.build import build_annotator
from dissector.render.jsonout import item_to_dict
from dissector.sources.reader import open_source

from conftest import ROOT

CAPTURES = ROOT / "captures"


@functools.cache
def items(file_name: str) -> tuple[dict, ...]:
    """A capture decoded with the default profiles (ATV71, SEL-749M at slave 1), as NDJSON dicts."""
    annotate = build_annotator(["atv71", "1=sel749m"], [])
    source = open_source(str(CAPTURES / file_name))
    framer = AsciiFramer() if source.mode == "ascii" else None
    return tuple(item_to_dict(item) for item in dissect(source, annotate=annotate, framer=framer))


def matching(file_name: str, expression: str) -> list[int]:
    test = compile_filter(expression)
    return [item["frame"] for item in items(file_name) if test(item)]


CASES = [
    # The per-register rule: both tests on one register.
    # Exception 02 to p.38's read (frames 10, 12) tells the registers' status too (no value).
    ("p38_protection.bin", 'code == "CHCF" and status == "protected"', [6, 8, 10, 12]),
    ("p38_protection.bin", 'status == "protected"', [6, 8, 10, 12]),
    ("p38_protection.bin", 'code == "COP" and status == "protected"', [10, 12]),
    ("p38_protection.bin", 'code == "CHCF" and status == "non-existent"', []),
    ("p38_protection.bin", 'status == "non-existent"', [2, 4, 6, 8, 10, 12]),
    ("p38_protection.bin", 'value == 0x8000 and code == "CHCF"', [6, 8]),
    ("p38_protection.bin", 'address == 8401 and value == 3', [2, 4]),
    ("p38_protection.bin", 'slave == 12 and code == "CHCF"', [2, 4, 6, 8, 10, 12]),
    # `not` closes the scope: "no register is CHCF"; ~= (any_ne) is "some register is not CHCF".
    ("p38_protection.bin", 'not code == "CHCF"', [1, 3, 5, 7, 9, 11]),
    ("p38_protection.bin", 'code ~= "CHCF"', [2, 4, 6, 8, 10, 12]),
    ("p38_protection.bin", 'code any_ne "CHCF"', [2, 4, 6, 8, 10, 12]),
    # != is Wireshark's all_ne (3.6+): some register has the field, none equal. tshark with the plugin,
    # `-Y 'vw3.reg.value != 3'` on p38_protection.pcap, shows frames 6 and 8; `vw3.reg.value ~= 3` 2 4 6 8.
    ("p38_protection.bin", 'code != "CHCF"', []),
    ("p38_protection.bin", "value != 3", [6, 8]),
    ("p38_protection.bin", "value all_ne 3", [6, 8]),
    ("p38_protection.bin", "value ~= 3", [2, 4, 6, 8]),
    ("p38_protection.bin", "value != 3 and slave == 12", [6, 8]),
    ("p38_protection.bin", "not value != 3", [1, 2, 3, 4, 5, 7, 9, 10, 11, 12]),
    ("p38_protection.bin", "address != 8401", []),
    ("p38_protection.bin", "address != 8403", list(range(1, 13))),
    # A frame field: present and different (a noise item has no slave).
    ("p38_protection.bin", "slave != 12", []),
    ("p38_protection.bin", "slave != 1", list(range(1, 13))),
    ("sel749m_polling.bin", 'warnings != "x" and function == 16', [49, 55]),
    ("sel749m_polling.bin", 'warnings != "byte count 6 disagrees with the quantity 2" and function == 16', [55]),
    # Read requests name their addresses; exception 02 to a read names the registers it is about.
    ("p38_protection.bin", "address == 8401", list(range(1, 13))),
    ("p38_protection.bin", "exception == 2", [10, 12]),
    ("p38_protection.bin", 'kind == "exception" && slave == 12', [10, 12]),
    ("atv71_commissioning.bin", "exception_code == 7", [64]),
    ("atv71_commissioning.bin", 'function == 6 and code == "CHCF"', [7, 8, 63, 103, 104]),
    ("atv71_commissioning.bin", 'code in {"FR1", "CD1"}', [9, 10, 11, 12, 14, 16]),
    ("atv71_commissioning.bin", 'address in {8413..8423} and kind == "response"', [10, 12, 14, 16]),
    (
        "atv71_commissioning.bin",
        'function == 23 and code == "RFR" and value >= 300',
        [58, 60, 62, 68, 70, 72, 74, 76],
    ),
    ("atv71_commissioning.bin", "function == 43", [1, 2]),
    ("atv71_commissioning.bin", "address == 9001", [17, 18]),
    (
        "atv71_commissioning.bin",
        'code == "CMD" and value == 0x0F and (frame < 40 or frame > 70)',
        [31, 33, 35, 37, 39, 71, 73],
    ),
    (
        "atv71_commissioning.bin",
        '!(function == 23) && kind == "request"',
        [1, 3, 5, 7, 9, 11, 13, 15, 17, 63, 65, 103],
    ),
    ("atv71_commissioning.bin", 'function_name contains "Multiple" and not function == 23', [17, 18]),
    ("atv71_commissioning.pcap", "response_time > 0.0175", [26, 56, 80, 82]),
    ("atv71_commissioning.pcap", "time < 1767225600.03", [1, 2]),
    ("sel749m_polling.bin", "exception", [14, 26, 32, 38, 44, 50, 56, 62]),
    ("sel749m_polling.bin", "exception in {1, 3}", [26, 32, 44, 50, 56]),
    ("sel749m_polling.bin", 'function == 16 and warnings contains "byte count"', [49]),
    (
        "sel749m_polling.bin",
        'address in {250, 302} or (address in {400..401} and kind == "request")',
        [31, 37, 55, 61],  # (frame 49's 302 is past its quantity 2: no register written)
    ),
    # A bare field tests presence, as Wireshark's (tshark -Y '!vw3.crc_ok': 1 34): frame 17's bad CRC is
    # a crc_ok, false.
    ("noisy_bus.bin", "not crc_ok", [1, 34]),
    ("noisy_bus.bin", "not crc_ok or crc_ok == 0", [1, 17, 34]),
    ("noisy_bus.bin", "crc_ok == false", [17]),
    ("noisy_bus.bin", "crc_ok == 0", [17]),  # 1 and 0 as Wireshark takes them and -T fields prints them
    ("noisy_bus.bin", "crc_ok != 1", [17]),
    ("noisy_bus.bin", "unanswered == 1", [28, 29]),
    ("noisy_bus.bin", 'kind == "noise"', [1, 34]),
    ("noisy_bus.bin", "unanswered", [28, 29]),
    ("noisy_bus.bin", "slave == 5 or length < 5", [1, 28, 29]),
    ("noisy_bus.bin", 'kind == "noise" and length >= 5', [34]),
    (
        "noisy_bus.bin",
        'not slave == 12 and not kind == "noise" and function == 3 and kind == "request"',
        [4, 8, 12, 16, 18, 22, 26, 28, 29, 32, 37],
    ),
    ("ascii_session.bin", 'mode == "ascii" and address in {9001..9002}', [3, 4, 5, 6]),
]


@pytest.mark.parametrize(("file_name", "expression", "frames"), CASES)
def test_filter_on_sample_captures(file_name: str, expression: str, frames: list[int]) -> None:
    assert matching(file_name, expression) == frames


def test_word_operators_and_case_insensitive_keywords() -> None:
    assert matching("p38_protection.bin", "slave eq 12 AND exception_code ge 2") == [10, 12]
    assert matching("p38_protection.bin", "NOT slave ne 12") == list(range(1, 13))


def test_escapes_and_contains_on_strings() -> None:
    item = {"kind": "noise", "reason": 'say "hi"\\'}
    assert compile_filter(r'reason == "say \"hi\"\\"')(item)
    assert compile_filter('reason contains "hi"')(item)
    assert not compile_filter('reason contains "ho"')(item)


ERRORS = [
    ("slave == ", "expected a value to compare slave with (column 10)\n  slave == \n           ^"),
    ("slave = 3", "a single = is not an operator: use == to compare (column 7)\n  slave = 3\n        ^"),
    ("slav == 3", "unknown field 'slav' (did you mean slave?) (column 1)\n  slav == 3\n  ^"),
    ('slave == "x"', "slave is a number, not '\"x\"' (column 10)\n  slave == \"x\"\n           ^"),
    (
        "code == CHCF",
        "code is a text, not 'CHCF' (strings go in double quotes: \"...\") (column 9)\n"
        "  code == CHCF\n          ^",
    ),
    ("(slave == 3", "expected ) to close the ( at column 1 (column 12)\n  (slave == 3\n             ^"),
    # (as tshark 4.0.17 refuses them: crc_ok == 2 is true, crc_ok > false the good ones)
    ("crc_ok == -1", "crc_ok is true or false: it takes no negative number (tshark: FT_BOOLEAN cannot -) "
     "(column 11)\n  crc_ok == -1\n            ^"),
    ("crc_ok == \"1\"", "\"1\" cannot be found among the possible values for crc_ok: true, false or a whole "
     "number (0 is false, any other true) (column 11)\n  crc_ok == \"1\"\n            ^"),
    ('kind == "req"', "kind 'req' does not exist (did you mean 'request'?): kind is one of request (1), response (2), exception (3), noise (4) (column 9)\n  kind == \"req\"\n          ^"),
    ("", "empty filter: give an expression such as slave == 12 (column 1)\n  \n  ^"),
    ("slave 3", "expected an operator (== != ~= < <= > >= & in contains matches) after slave (column 7)\n  slave 3\n        ^"),
    ("address in 8400", "'8400' was unexpected in this context: expected { after in, a set such as {3, 4, 8400..8402} "
     "(column 12)\n  address in 8400\n             ^"),
    # (a set as tshark 4.0.17 reads it: members separated by commas, a range inside braces)
    ("address in 8400..8402", "'8400' was unexpected in this context: expected { after in, a set such as "
     "{3, 4, 8400..8402} (a range goes in a set: {8400..8402}) (column 12)\n  address in 8400..8402\n             ^"),
    ("slave in {12 13}", "'13' was unexpected in this context: set members are separated by commas, as tshark 4.0 "
     "takes them ({3, 4}) (column 14)\n  slave in {12 13}\n               ^"),
    ("slave in {12,}", "'}' was unexpected in this context: a set holds values separated by commas, none after the "
     "last (as tshark 4.0) (column 14)\n  slave in {12,}\n               ^"),
    ("slave in {12", "expected } to close the { at column 10 (column 13)\n  slave in {12\n              ^"),
    (
        "slave == 1 slave",
        "unexpected 'slave': expected and, or or the end (column 12)\n  slave == 1 slave\n             ^",
    ),
    ('"abc', "string not closed (a \" is missing) (column 1)\n  \"abc\n  ^"),
    ("slave contains 1", "contains needs a text or bytes field; slave is a number (column 7)\n  slave contains 1\n        ^"),
    # (tshark refuses it too; read as {1 -3} it matched frame 1 alone)
    ("frame in {1-3}", "'1-3' is not a number: a range is written 1..3 (column 11)\n  frame in {1-3}\n            ^"),
    ("function in {}", "'}' was unexpected in this context: a set holds at least one value (column 14)\n"
     "  function in {}\n               ^"),
    ("slave == 1 $", "unexpected character '$' (column 12)\n  slave == 1 $\n             ^"),
]


@pytest.mark.parametrize(("expression", "message"), ERRORS)
def test_errors_point_at_the_token(expression: str, message: str) -> None:
    with pytest.raises(FilterError) as caught:
        compile_filter(expression)
    assert str(caught.value) == message


def test_registers_bits_and_named_addresses() -> None:
    coils = {"kind": "response", "function": 1, "start": 4, "quantity": 2,
             "bits": [{"address": 4, "value": 0}, {"address": 5, "value": 1}]}
    assert compile_filter("address == 5 and value == 1")(coils)
    assert not compile_filter("address == 4 and value == 1")(coils)
    read_write = {"kind": "request", "function": 23, "start": 3201, "quantity": 2,
                  "registers": [{"address": 8501, "value": 15}, {"address": 8502, "value": 300}]}
    assert compile_filter("address == 3202")(read_write)  # read part: named, no value
    assert not compile_filter("address == 3202 and value")(read_write)
    assert compile_filter("address == 8502 and value == 300")(read_write)
    assert not compile_filter("address == 8502 and value == 15")(read_write)
    exception = {"kind": "exception", "function": 3, "exception_code": 2}
    assert compile_filter("not address == 8401")(exception)
    assert not compile_filter("address")(exception)


def test_huge_number_is_an_error() -> None:
    with pytest.raises(FilterError, match="number too long"):
        compile_filter("slave == " + "9" * 5000)


def test_nesting_is_bounded() -> None:
    with pytest.raises(FilterError, match="nested more than 64 levels"):
        compile_filter("(" * 200 + "slave == 1" + ")" * 200)
    with pytest.raises(FilterError, match="nested more than 64 levels"):
        compile_filter("not " * 500 + "slave == 1")
    # flat: no recursion limit (frame, as slave takes 255 at most, as tshark's FT_UINT8)
    long_chain = " or ".join(f"frame == {n}" for n in range(5000))
    assert compile_filter(long_chain)({"frame": 4999})


TOKENS = [
    "slave", "function", "kind", "code", "status", "address", "value", "crc_ok", "exception",
    "warnings", "time", "==", "!=", "<", ">=", "in", "contains", "and", "or", "not", "&&", "||", "!",
    "(", ")", "{", "}", "..", ",", "12", "0x20D1", "1.5", '"CHCF"', '"protected"', "true", "false",
    '"', "=", "$", "\\", "\x00", "é",
    # functions, arithmetic and characters (render/filter_expr.py)
    "+", "-", "*", "/", "%", "&", "len(", "count(", "upper(", "string(", "max(", "abs(", "raw", "raw[0:2]",
    "'a'", "'\\x0c'", "'", "response_time", "time_relative", "scaled", "fields.values", "0", "-1",
]
SAMPLES = [dict(item) for item in items("p38_protection.bin")] + [dict(item) for item in items("noisy_bus.bin")[:2]]


def _compile_and_run(text: str) -> None:
    try:
        test = compile_filter(text)
    except FilterError as error:
        assert str(error)
        return
    for item in SAMPLES:
        assert test(item) in (True, False)


@settings(max_examples=400, deadline=None)
@given(st.text(max_size=80))
def test_fuzz_any_text_raises_only_filter_error(text: str) -> None:
    _compile_and_run(text)


@settings(max_examples=400, deadline=None)
@given(st.binary(max_size=80))
def test_fuzz_random_bytes_raise_only_filter_error(data: bytes) -> None:
    _compile_and_run(data.decode("latin-1"))


@settings(max_examples=600, deadline=None)
@given(st.lists(st.sampled_from(TOKENS), max_size=14))
def test_fuzz_token_soup_raises_only_filter_error(tokens: list[str]) -> None:
    _compile_and_run(" ".join(tokens))


def test_negative_numbers_compare_with_signed_scaled_values() -> None:
    from dissector.render.filters import compile_filter

    negative = {"kind": "response", "registers": [{"address": 3205, "value": 65436, "scaled": -100}]}
    positive = {"kind": "response", "registers": [{"address": 3205, "value": 100, "scaled": 100}]}
    test = compile_filter("scaled < -1")
    assert (test(negative), test(positive)) == (True, False)
    assert compile_filter("scaled in {-200..-50}")(negative) is True


# -- misspelt values of enumerated keys, and keys of the PDU's fields (issue 27) ---------------------------------------

from helpers import run_cli  # noqa: E402


@pytest.mark.parametrize("expression, message", [
    ('profile == "atv7"',
     "profile 'atv7' does not exist (did you mean 'atv71'?): profile is one of atv71, generic, sel749m (column 12)"),
    ('exception_name == "Illegal Data Adress"',
     "exception_name 'Illegal Data Adress' does not exist (did you mean 'Illegal Data Address'?) (column 19)"),
    ('function_name == "Read Holding Register"',
     "function_name 'Read Holding Register' does not exist (did you mean 'Read Holding Registers'?) (column 18)"),
    ('function_name in {"Read Holding Registers", "Write Single Registre"}',
     "function_name 'Write Single Registre' does not exist (did you mean 'Write Single Register'?) (column 45)"),
    ('subfunction_name == "Return Query Dat"',
     "subfunction_name 'Return Query Dat' does not exist (did you mean 'Return Query Data'?) (column 21)"),
    ("fields.strat == 8400",
     "unknown field 'fields.strat': no PDU layout has the key 'strat' (did you mean fields.start, fields.status?); "
     "-G fields lists them (column 1)"),
])
def test_misspelt_enumerated_values_are_refused_with_a_suggestion(expression: str, message: str) -> None:
    status, out, err = run_cli([str(CAPTURES / "p38_protection.pcap"), "-Y", expression])
    assert (status, out) == (2, "") and err.splitlines()[0] == f"vw3-decode: {message}", err


def test_the_values_that_exist_still_match() -> None:
    p38 = str(CAPTURES / "p38_protection.pcap")
    for expression, frames in [
        ('profile == "atv71"', list(range(1, 13))),
        ('exception_name == "Illegal Data Address"', [10, 12]),
        ('function_name == "Read Holding Registers"', list(range(1, 13))),
        ("fields.start == 8400", [1, 3, 5, 7, 9, 11]),
        ('exception_name == "Unknown exception 99"', []),  # a name the spec gives an unknown code
        ('function_name == "Function 9"', []),
    ]:
        status, out, err = run_cli([p38, "-Y", expression, "-T", "fields", "-e", "frame"])
        assert (status, err) == (0, "") and out.split() == [str(frame) for frame in frames], expression
    # A profile's own names are values of the run that has it: the SEL-749M's function 60h.
    sel = str(CAPTURES / "sel749m_polling.pcap")
    named = 'function_name == "Read Parameter Information"'
    assert run_cli([sel, "-Y", named, "--profile", "sel749m"]) == (0, "", "")
    assert run_cli([sel, "-Y", named, "--profile", "atv71"])[2].splitlines()[0] == (
        "vw3-decode: function_name 'Read Parameter Information' does not exist (column 18)")


def test_a_pdu_key_holding_a_list_is_a_repeated_field() -> None:
    # fields.values of a write (frame 4: 40 600 500 0, frame 6: 3 2), as Wireshark tests a repeated field:
    # one element passes, != when every element differs; -e lists each element as an occurrence.
    # Before, the list was compared whole: == 40 and > 550 matched nothing, and -e printed [40,600,500,0].
    capture = str(CAPTURES / "atv71_commissioning.pcap")

    def frames(expression: str) -> list[int]:
        status, out, err = run_cli([capture, "-Y", f"({expression}) and frame <= 6", "-T", "fields", "-e", "frame"])
        assert (status, err) == (0, ""), expression
        return [int(frame) for frame in out.split()]

    assert frames("fields.values == 40") == [4]
    assert frames("fields.values > 550") == [4]
    assert frames("fields.values in {2..3}") == [6]
    assert frames("fields.values != 40") == [6]
    assert frames("fields.values ~= 40") == [4, 6]
    assert frames("fields.values") == [4, 6]
    argv = [capture, "-T", "fields", "-e", "frame", "-e", "fields.values", "-Y", "frame in {4, 6}"]
    assert run_cli(argv) == (0, "4\t40,600,500,0\n6\t3,2\n", "")
    assert run_cli([*argv, "-E", "occurrence=l", "-E", "aggregator=/s"]) == (0, "4\t0\n6\t2\n", "")


def test_fields_key_of_t_fields_is_checked_and_listed() -> None:
    p38 = str(CAPTURES / "p38_protection.pcap")
    assert run_cli([p38, "-T", "fields", "-e", "fields.strat"]) == (2, "", (
        "vw3-decode: -e fields.strat: no PDU layout has the key 'strat' (did you mean fields.start, fields.status?); "
        "-G fields lists them\n"))
    assert run_cli([p38, "-T", "fields", "-e", "fields.start", "-c", "1"]) == (0, "8400\n", "")
    listing = run_cli(["-Y", "help"])[1].splitlines()
    from dissector.protocol import table

    # Every key of the protocol table's layouts, with the functions whose PDU has it.
    assert "fields.start           frame     value          PDU key of functions 1 2 3 4 15 16" in listing
    assert "fields.exception_code  frame     value          PDU key of exceptions" in listing
    assert "fields.read_start      frame     value          PDU key of function 23" in listing
    listed = {line.split()[0][7:] for line in listing if line.startswith("fields.")}
    assert listed == {sub.name for entry in table.FUNCTIONS for layout in (entry.request, entry.response)
                      for sub in layout.grammar.subcons if sub.name} | {"exception_code", "data", "trailing",
                                                                        "event_list"}  # (FC12's, the decode's)
    assert "fields.event_list      frame     value          PDU key of function 12" in listing
    assert "KEY" not in listed  # the real names, not a placeholder
