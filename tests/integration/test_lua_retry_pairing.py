"""The plugin reads a master's retry as vw3-decode does (tests/differential/test_retry_pairing.py): a frame
identical to a request its answer echoes (FC5, FC6, FC8's Return Query Data), later than the timeout
preference, is the master's retry, a request, and the identical frame after it its answer; the frames after
take the kind the framer would have given them had it known (the next write is a request). Real tshark with
-X lua_script:lua/vw3.lua, -2 and one pass (a request's answer is not known in one pass), RTU and ASCII."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
HSP, HSP_LOW = rtu("0C 06 0C20 01F4"), rtu("0C 06 0C20 01C2")
READ, READ_ANSWER = rtu("0C 03 0C81 0002"), rtu("0C 03 04 0001 0002")
CHCF, CHCF_WRITTEN = rtu("0C 10 20D1 0001 02 0003"), rtu("0C 10 20D1 0001")
HUNTER = [(0.0, HSP), (0.5, HSP), (0.512, HSP), (0.6, READ), (0.612, READ_ANSWER),
          (1.0, CHCF), (1.3, CHCF), (1.312, CHCF_WRITTEN)]
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.request_frame", "-e",
          "vw3.response_frame", "-e", "vw3.unanswered", "-e", "vw3.warning", "-e", "vw3.note"]
TIMEOUT = ["-o", "vw3.timeout_ms:400"]


def tshark(pcap: Path, *args: str, two_pass: bool = True) -> str:
    result = run_tshark(pcap, *TIMEOUT, *args, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


def capture(tmp_path: Path, frames: list[tuple[float, bytes]]) -> Path:
    return write_pcap(tmp_path / "retry.pcap", [(frame, T0 + seconds) for seconds, frame in frames])


def ascii_frame(binary: bytes) -> bytes:
    body = binary[:-2]  # (the RTU CRC off: ASCII's LRC instead)
    return b":" + (body + bytes([-sum(body) & 0xFF])).hex().upper().encode() + b"\r\n"


@pytest.mark.parametrize("two_pass", [True, False])
def test_retry_past_the_timeout(tmp_path: Path, two_pass: bool) -> None:
    pcap = capture(tmp_path, HUNTER)
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        "1;;;1;;" if two_pass else "1;;;;;",
        "1;;3;;;" if two_pass else "1;;;;;",  # (was: 2;;;;response 500.0 ms after request #1, later than ...)
        "2;2;;;;",  # (was: 1;;;1;; the drive's echo read as a request)
        "1;;5;;;" if two_pass else "1;;;;;",
        "2;4;;;;",
        "1;;;1;;" if two_pass else "1;;;;;",
        "1;;8;;;" if two_pass else "1;;;;;",
        "2;7;;;;",
    ]
    if two_pass:
        info = tshark(pcap, "-T", "fields", "-e", "_ws.col.Info").splitlines()
        assert info[:3] == ["12 Write Single Register request 3104 HSP=50.0 Hz",
                            "12 Write Single Register request 3104 HSP=50.0 Hz",
                            "12 Write Single Register response 3104 HSP=50.0 Hz"]


@pytest.mark.parametrize("two_pass", [True, False])
def test_after_the_retry_answer_the_next_write_is_a_request(tmp_path: Path, two_pass: bool) -> None:
    frames = [(0.0, HSP), (0.5, HSP), (0.512, HSP), (0.6, HSP_LOW), (0.612, HSP_LOW),
              (1.0, HSP), (1.5, HSP), (2.0, HSP), (2.01, HSP), (2.1, READ), (2.11, READ_ANSWER)]
    lines = tshark(capture(tmp_path, frames), *FIELDS, two_pass=two_pass).splitlines()
    assert [line.split(";")[0] for line in lines] == ["1", "1", "2", "1", "2", "1", "1", "1", "2", "1", "2"]
    assert [line.split(";")[1] for line in lines] == ["", "", "2", "", "4", "", "", "", "8", "", "10"]
    if two_pass:
        assert [line.split(";")[3] for line in lines] == ["1", "", "", "", "", "1", "1", "", "", "", ""]


def test_fc5_and_fc8_echo_retries(tmp_path: Path) -> None:
    coil, echo = rtu("01 05 0010 FF00"), rtu("01 08 0000 A537")
    frames = [(0.0, coil), (0.5, coil), (0.51, coil), (0.6, echo), (1.1, echo), (1.11, echo), (1.2, echo)]
    assert tshark(capture(tmp_path, frames), *FIELDS).splitlines() == [
        "1;;;1;;", "1;;3;;;", "2;2;;;;", "1;;;1;;", "1;;6;;;", "2;5;;;;",
        "1;;;;;the capture ends before any response: not known whether it was answered",
    ]


@pytest.mark.parametrize("two_pass", [True, False])
def test_ascii(tmp_path: Path, two_pass: bool) -> None:
    pcap = capture(tmp_path, [(seconds, ascii_frame(frame)) for seconds, frame in HUNTER[:5]])
    assert tshark(pcap, *FIELDS, two_pass=two_pass).splitlines() == [
        "1;;;1;;" if two_pass else "1;;;;;",
        "1;;3;;;" if two_pass else "1;;;;;",
        "2;2;;;;",
        "1;;5;;;" if two_pass else "1;;;;;",
        "2;4;;;;",
    ]


@pytest.mark.parametrize("quick", ["TRUE", "FALSE"])
def test_a_request_met_before(tmp_path: Path, quick: str) -> None:
    # (the request at 0.1 s is known by its bytes: the quick lane of requests takes it, byte table and all)
    frames = [(0.0, HSP), (0.012, HSP), (0.1, HSP), (0.6, HSP), (0.612, HSP), (0.7, READ), (0.712, READ_ANSWER)]
    assert tshark(capture(tmp_path, frames), *FIELDS, "-o", f"vw3.quick_lanes:{quick}").splitlines() == [
        "1;;2;;;", "2;1;;;;", "1;;;1;;", "1;;5;;;", "2;4;;;;", "1;;7;;;", "2;6;;;;"]


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_request_sharing_its_record(tmp_path: Path, two_pass: bool) -> None:
    # (the request's byte table is gone when its retry comes: it kept its bytes)
    # then an answer past the timeout that is not the request's bytes: a late answer (as vw3-decode)
    frames = [(0.0, READ), (0.012, READ_ANSWER + HSP), (0.6, HSP), (0.612, HSP), (1.0, HSP_LOW), (1.5, HSP)]
    assert tshark(capture(tmp_path, frames), *FIELDS, two_pass=two_pass).splitlines() == [
        "1;;2;;;" if two_pass else "1;;;;;",
        "2,1;1;;1;;" if two_pass else "2,1;1;;;;",
        "1;;4;;;" if two_pass else "1;;;;;",
        "2;3;;;;",
        "1;;;1;;" if two_pass else "1;;;;;",
        "2;;;;response 500.0 ms after request #6, later than the 400 ms timeout: not its answer;",
    ]
