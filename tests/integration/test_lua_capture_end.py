"""The plugin on a request the capture ends after (lua/src/pairing.lua ended, as pairing.py capture_ended):
in the second pass (tshark -2, Wireshark once the file is read) the capture's end is its last record. Later
than --timeout after the request: vw3.unanswered, 'Request not answered'; sooner: not known, no
vw3.unanswered, a note saying so. One pass cannot know where the capture ends: nothing is said of the last
request (as before). The captures of tests/unit/test_capture_end_unknown.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import lua_errors, run_tshark, write_pcap

REQUEST = bytes.fromhex("010300000002C40B")  # slave 1 reads 0..1
ANSWER = bytes.fromhex("010304000100022A32")
UNKNOWN = "the capture ends before any response: not known whether it was answered"
WITHIN = "the capture ends 200.0 ms after the request, within the 1000 ms timeout: not known whether it was answered"
# A poll answered, then a request the capture ends with: its own record last, noise 200 ms later (within the
# 1 s timeout), noise 1.5 s later (past it), the first 3 bytes of its answer.
ENDS = {"last": [], "within": [(b"\x55\x55", 1001.2)], "past": [(b"\x55\x55", 1002.5)], "cut": [(ANSWER[:3], 1001.02)]}


def capture(tmp_path: Path, end: str) -> Path:
    return write_pcap(tmp_path / f"{end}.pcap", [(REQUEST, 1000.0), (ANSWER, 1000.01), (REQUEST, 1001.0)] + ENDS[end])

FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.response_frame", "-e", "vw3.unanswered",
          "-e", "vw3.note"]


def fields(pcap: Path, two_pass: bool = True) -> list[str]:
    result = run_tshark(pcap, *FIELDS, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize(("end", "third", "fourth"), [
    ("last", f"1;;;{UNKNOWN}", None),
    ("within", f"1;;;{WITHIN}", "4;;;"),
    ("past", "1;;1;", "4;;;"),
    ("cut", "1;;;the capture ends inside the response (3 of 9 bytes)", "4;;;"),
])
def test_second_pass(tmp_path: Path, end: str, third: str, fourth: str | None) -> None:
    assert fields(capture(tmp_path, end)) == ["1;2;;", "2;;;", third] + ([fourth] if fourth else [])


def test_one_pass_says_nothing_of_the_last_request(tmp_path: Path) -> None:
    assert fields(capture(tmp_path, "past"), two_pass=False)[2] == "1;;;"
    assert fields(capture(tmp_path, "last"), two_pass=False)[2] == "1;;;"
