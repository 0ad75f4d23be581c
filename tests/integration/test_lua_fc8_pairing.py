"""The plugin pairs FC8 as vw3-decode does (tests/unit/test_fc8_pairing.py, data/modbus.toml [pairing]):
Force Listen Only Mode (08/04) awaits no answer and says so (an exception still answers it), an FC8 answer whose sub-function differs from
its request's is the master's next request. Real tshark with -X lua_script:lua/vw3.lua, -2 and one pass, every
frame in a record of its own and the 08/04 sharing its record with the next request."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
LISTEN_ONLY, RESTART = rtu("01 08 0004 0000"), rtu("01 08 0001 0000")
REGISTER_QUERY, REGISTER_ANSWER = rtu("01 08 0002 0000"), rtu("01 08 0002 0007")
REFUSED = rtu("01 88 01")  # exception 1: a server that does not support 04 says so
NOTE = "no response expected: the spec's server returns none"
# (after 08/04 the slave is in listen-only mode: it answers nothing, 08/01 included, which ends the mode)
ENDS = "slave 1 leaves listen-only mode (since #1, 08/04): the spec's server does not answer this"
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.subfunction", "-e", "vw3.request_frame",
          "-e", "vw3.response_frame", "-e", "vw3.unanswered", "-e", "vw3.note"]


def tshark(pcap: Path, *args: str, two_pass: bool = True) -> str:
    result = run_tshark(pcap, *args, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


def records(path: Path, frames: list[bytes]) -> Path:
    return write_pcap(path, [(frame, T0 + 0.010 * index) for index, frame in enumerate(frames)])


@pytest.mark.parametrize("two_pass", [True, False])
def test_listen_only_awaits_nothing(tmp_path: Path, two_pass: bool) -> None:
    # (08/01 ends the mode unanswered: the same again is the master's repeat, which the echo answers)
    pcap = records(tmp_path / "fc8.pcap", [LISTEN_ONLY, RESTART, RESTART, RESTART])
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        f"1;4;;;;{NOTE}",
        f"1;1;;;;{ENDS}",
        "1;1;;4;;" if two_pass else "1;1;;;;",  # (one pass: the answer is not read yet)
        "2;1;3;;;",
    ]
    tree = tshark(pcap, "-V", two_pass=two_pass)
    assert f"        [Expert Info (Note/Comment): {NOTE}]\n" in tree
    assert "No response" not in tree and "unanswered" not in tree.lower()


def test_listen_only_in_one_record_with_the_next_request(tmp_path: Path) -> None:
    # (framed in one go: the framer's expectation, not the pairing alone, must know 08/04 awaits nothing;
    # request_frame and response_frame are record numbers)
    pcap = write_pcap(tmp_path / "one.pcap", [(LISTEN_ONLY + REGISTER_QUERY, T0), (REGISTER_ANSWER, T0 + 0.010)])
    # (the slave answers the 08/02: not in listen-only mode after all; the plugin's pairing module, heard)
    assert tshark(pcap, *FIELDS).splitlines() == [
        f"1,1;4,2;;2;;{NOTE}", "2;2;1;;;slave 1 answers: it is not in listen-only mode (#1, 08/04)"]


@pytest.mark.parametrize("two_pass", [True, False])
def test_an_exception_still_answers_listen_only(tmp_path: Path, two_pass: bool) -> None:
    pcap = records(tmp_path / "refused.pcap", [LISTEN_ONLY, REFUSED, RESTART, RESTART, LISTEN_ONLY])
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        f"1;4;;2;;{NOTE}" if two_pass else f"1;4;;;;{NOTE}",
        "3;;1;;;",
        "1;1;;4;;" if two_pass else "1;1;;;;",
        "2;1;3;;;",
        f"1;4;;;;{NOTE}",  # (the last record: not unanswered either)
    ]


RETURN_COUNT = rtu("01 08 000B 0000")  # Return Bus Message Count


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_frame_that_does_not_echo_the_sub_function_is_the_next_request(tmp_path: Path, two_pass: bool) -> None:
    # 08/0B unanswered, then 08/02: the master's next request (not 08/0B's answer, which would echo 000B),
    # and its answer pairs with it. Before: "response without a matching request", its answer a request.
    pcap = records(tmp_path / "echo.pcap", [RETURN_COUNT, REGISTER_QUERY, REGISTER_ANSWER, RESTART, RESTART])
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        "1;11;;;1;" if two_pass else "1;11;;;;",  # (one pass: its wait ends at the next request, not read yet)
        "1;2;;3;;" if two_pass else "1;2;;;;",
        "2;2;2;;;",
        "1;1;;5;;" if two_pass else "1;1;;;;",
        "2;1;4;;;",
    ]


def test_the_echo_is_weighed_in_one_record(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "one.pcap", [(RETURN_COUNT + REGISTER_QUERY + REGISTER_ANSWER, T0)])
    assert tshark(pcap, *FIELDS).splitlines() == ["1,1,2;11,2,2;1;1;1;"]


def ascii_line(frame: bytes) -> bytes:
    """The RTU frame's ADU as a Modbus ASCII line (':' hex LRC CR LF)."""
    adu = frame[:-2]
    return b":" + (adu + bytes([-sum(adu) & 0xFF])).hex().upper().encode() + b"\r\n"


@pytest.mark.parametrize("two_pass", [True, False])
def test_ascii_weighs_the_echo_as_rtu_does(tmp_path: Path, two_pass: bool) -> None:
    # The same exchange in Modbus ASCII: 08/02 after 08/0B is the next request, its answer pairs with it
    # (before: 'response' with no request, its answer a request, as vw3-decode also read it).
    frames = [RETURN_COUNT, REGISTER_QUERY, REGISTER_ANSWER, RESTART, RESTART]
    pcap = records(tmp_path / "echo-ascii.pcap", [ascii_line(frame) for frame in frames])
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        "1;11;;;1;" if two_pass else "1;11;;;;",
        "1;2;;3;;" if two_pass else "1;2;;;;",
        "2;2;2;;;",
        "1;1;;5;;" if two_pass else "1;1;;;;",
        "2;1;4;;;",
    ]
