"""A record of which no byte was captured (a snapshot length of 0 on it: `0 of its 9 bytes`) tells neither slave
nor function, but its length on the line: within the timeout of a request, only the slave asked speaks, so a
length the answer can have (its exception's, 5; its normal answer's where the request fixes it: 9 for a read of
2 registers, 8 for an FC6 echo; any from 5 up where it does not) is that answer, captured in part. Before, such a
record was never paired: the request said `[no response]` and --stats counted a no reply, while the 3 bytes of
the same answer (`3 of its 9`) answered it. A length no answer has (7), or a record after the timeout, is not the
answer, as before. Python stages, the compiled engine and the plugin (-2 and one pass) alike."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import engine_output_as_python, rtu
from lua_harness import assert_as_vw3_decode_in_one_and_two_passes
from part_records import raw_pcap

READ, WRITE = rtu("02 03 20d1 0002"), rtu("02 06 20d1 0003")
LATER = frozenset(["response_frame", "unanswered", "notes"])  # (as test_lua_captured_in_part: one pass's notes)
ANSWERED = ("0 bytes of noise at offset 8 [captured in part (0 of its {size} bytes; the answer to #1): its CRC cannot be"
            " checked]")
NOT = "0 bytes of noise at offset 8 [captured in part (0 of its {size} bytes): its CRC cannot be checked]"


@pytest.mark.parametrize("request_bytes, size, after, answered", [
    (READ, 9, 10_000, True), (READ, 5, 10_000, True), (WRITE, 8, 10_000, True),
    (READ, 7, 10_000, False), (READ, 9, 1_500_000, False)])
def test_a_record_of_no_byte_is_the_answer_its_length_fits(request_bytes: bytes, size: int, after: int,
                                                           answered: bool, tmp_path: Path,
                                                           monkeypatch: pytest.MonkeyPatch) -> None:
    capture = raw_pcap(tmp_path / "zero.pcap", [(0, len(request_bytes), request_bytes), (after, size, b""),
                                                 (after + 100_000, len(READ), READ)])
    out, _framed = engine_output_as_python([str(capture), "-T", "fields", "-e", "frame", "-e", "notes", "-e",
                                            "unanswered"], monkeypatch)
    first = "1\tanswer captured in part in #2\t" if answered else "1\t\t1"
    assert out.splitlines()[0] == first
    out, _framed = engine_output_as_python([str(capture)], monkeypatch)
    assert out.splitlines()[1][34:] == (ANSWERED if answered else NOT).format(size=size)
    out, _framed = engine_output_as_python([str(capture), "--stats"], monkeypatch)
    assert ("no reply" in out) and any(line.split()[-2:] == (["0", "0"] if answered else ["1", "0"])
                                       for line in out.splitlines() if line.startswith("    2  ")), out
    assert_as_vw3_decode_in_one_and_two_passes(capture, LATER)


def test_an_ascii_line_of_no_byte(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """An ASCII line's length is 2 characters a byte (its LRC's too), `:` and CR LF: 19 for a read of 2 registers."""
    request = b":020320010002D8\r\n"
    capture = raw_pcap(tmp_path / "ascii.pcap", [(0, len(request), request), (10_000, 19, b""),
                                                  (100_000, len(request), request)])
    out, _framed = engine_output_as_python([str(capture)], monkeypatch)
    assert out.splitlines()[1][34:] == ("0 bytes of noise at offset 17 [captured in part (0 of its 19 bytes; the answer"
                                        " to #1): its LRC cannot be checked]")
    assert_as_vw3_decode_in_one_and_two_passes(capture, LATER)
