"""FC22, FC21 and FC20 are checked as FC5/6/16 are (data/modbus.toml [lift.mask_write], [lift.write_file],
[lift.read_file_*]): an FC22 answer repeats address and masks, an FC21 answer the request whole (Application
Protocol 6.15), an FC20 sub-response holds the record length its sub-request asked, and a sub-request or record
has reference type 6 and a record number 0..0x270F (6.14, 6.15). The same lines under the compiled engine and
VW3_PURE_PYTHON=1; the plugin's in tests/integration/test_lua_file_mask_checks.py."""
from __future__ import annotations

import pytest

from helpers import run_cli, use_engine

MASK = ["01 16 00 04 00 F2 00 25 67 EE", "01 16 00 04 00 F2 00 26 27 EF"]  # OR mask 0x25 answered with 0x26
WRITE_FILE = [  # file 4, record 7, 3 words; the answer's last word 0x100E, not 0x100D
    "01 15 0D 06 00 04 00 07 00 03 06 AF 04 BE 10 0D D6 0B", "01 15 0D 06 00 04 00 07 00 03 06 AF 04 BE 10 0E 96 0A",
]
READ_FILE = ["01 14 07 06 00 04 00 01 00 02 D8 E5", "01 14 08 07 06 00 01 00 02 00 03 DE 7F"]  # 2 words asked, 3 sent
TYPE_5 = ["01 14 07 05 00 04 27 10 00 02 B1 54"]  # reference type 5, record 0x2710


def lines(frames: list[str]) -> list[str]:
    status, out, err = run_cli([arg for frame in frames for arg in ("--hex", frame)])
    assert (status, err) == (0, "")
    return out.splitlines()


@pytest.mark.parametrize("pure", [False, True])
def test_answers_that_do_not_repeat_their_request_are_warned(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    assert lines(MASK + WRITE_FILE + READ_FILE) == [
        "     1            -   1 request   Mask Write Register 4 AND 0x00F2 OR 0x0025  CRC ok",
        "     2            -   1 response  Mask Write Register 4 AND 0x00F2 OR 0x0026 [#1] "
        "[warning: the response's or_mask differs from the request's]  CRC ok",
        "     3            -   1 request   Write File Record 1 record group(s)  CRC ok",
        "     4            -   1 response  Write File Record 1 record group(s) [#3] "
        "[warning: the response's data differs from the request's]  CRC ok",
        "     5            -   1 request   Read File Record 1 record group(s)  CRC ok",
        "     6            -   1 response  Read File Record 1 record group(s) [#5] "
        "[warning: sub-response 1's length 7 holds registers (3), not the record length asked (2)]  CRC ok",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_echoes_and_answers_that_fit_are_quiet(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    assert lines([MASK[0], MASK[0], WRITE_FILE[0], WRITE_FILE[0], READ_FILE[0], "01 14 06 05 06 00 01 00 02 39 CB"]) == [
        "     1            -   1 request   Mask Write Register 4 AND 0x00F2 OR 0x0025  CRC ok",
        "     2            -   1 response  Mask Write Register 4 AND 0x00F2 OR 0x0025 [#1]  CRC ok",
        "     3            -   1 request   Write File Record 1 record group(s)  CRC ok",
        "     4            -   1 response  Write File Record 1 record group(s) [#3]  CRC ok",
        "     5            -   1 request   Read File Record 1 record group(s)  CRC ok",
        "     6            -   1 response  Read File Record 1 record group(s) [#5]  CRC ok",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_reference_type_and_record_number_are_the_specs(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    # two sub-requests asked, one sub-response sent; an FC21 record of type 7 at record 0x270F (the last one)
    write = "01 15 09 07 00 01 27 0F 00 01 12 34"
    answer = "01 14 06 05 06 00 01 00 02 39 CB"  # one sub-response of 2 words
    assert lines(TYPE_5 + [answer, "01 14 0E 06 00 04 00 01 00 02 06 00 03 00 09 00 01 B4 FC", answer,
                           write + " 34 73"]) == [
        "     1            -   1 request   Read File Record 1 record group(s) "
        "[warning: sub-request 1's reference type 5 is not the spec's 6] "
        "[warning: sub-request 1's record number 10000 outside the spec's 0..9999]  CRC ok",
        "     2            -   1 response  Read File Record 1 record group(s) [#1]  CRC ok",
        "     3            -   1 request   Read File Record 2 record group(s)  CRC ok",
        "     4            -   1 response  Read File Record 1 record group(s) [#3] "
        "[warning: number of sub-responses 1 disagrees with the request's (2)]  CRC ok",
        "     5            -   1 request   Write File Record 1 record group(s) "
        "[the capture ends before any response: not known whether it was answered] "
        "[warning: record 1's reference type 7 is not the spec's 6]  CRC ok",
    ]
