"""--hex: one frame per argument, so a CRC typo or a frame typed without its CRC is decoded and the
check spelled out, instead of noise (issue 15). Vectors: the p.38 seed (0C 03 20 D0 00 03 0E EF)."""
from __future__ import annotations

import json

from helpers import run_cli


def test_a_crc_typo_is_decoded_and_the_crc_spelled_out() -> None:
    status, out, err = run_cli(["--hex", "0C 03 20 D0 00 03 0E EE"])
    assert (status, err) == (0, "")
    assert out == (
        "     1            -  12 request   Read Holding Registers 8400..8402 (3) "
        "[the capture ends before any response: not known whether it was answered] [warning: CRC bad: received 0xEE0E, expected 0xEF0E "
        "(on the wire 0E EE typed, 0E EF expected)]  CRC BAD (received 0xEE0E, expected 0xEF0E)\n"
    )
    record = json.loads(run_cli(["--json", "--hex", "0C 03 20 D0 00 03 0E EE"])[1])
    # every typed byte shows up, as typed
    assert (record["raw"], record["crc_ok"], record["crc"], record["crc_expected"]) == (
        "0c0320d000030eee", False, 0xEE0E, 0xEF0E
    )


def test_a_frame_typed_without_its_crc_gets_the_crc_to_append() -> None:
    status, out, err = run_cli(["--hex", "0C 03 20 D0 00 03", "--hex", "0C 03 06 80 00 00 03 00 02"])
    assert (status, err) == (0, "")
    assert out.splitlines() == [
        "     1            -  12 request   Read Holding Registers 8400..8402 (3) "
        "[no CRC typed: append 0E EF (CRC 0xEF0E)]  CRC computed (none typed)",
        # (one answer is no evidence of an ATV71 under profile auto: issue 26)
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#1] "
        "[no CRC typed: append 17 E4 (CRC 0xE417)]  CRC computed (none typed)",
    ]


def test_a_crc_nobody_typed_is_called_received_by_no_output() -> None:
    # Review of issue 27 (defect 8): -V said `CRC: 0xEF0E [CRC ok]`, --json `crc_ok: true`, -T fields `1`
    # and -x showed `0e ef`, none of them typed.
    typed = ["--hex", "0C 03 20 D0 00 03"]
    status, out, err = run_cli(["-V", *typed])
    assert (status, err) == (0, "")
    assert "        CRC: none typed [CRC computed (none typed): 0xEF0E, not checked]" in out.splitlines()
    assert "CRC ok" not in out
    record = json.loads(run_cli(["--json", *typed])[1])
    assert (record["crc_ok"], record["crc"], record["crc_expected"], record["crc_typed"]) == (None, None, 0xEF0E, False)
    assert run_cli(["-T", "fields", "-e", "frame", "-e", "crc_ok", "-e", "crc", "-e", "crc_expected", "-e", "crc_typed",
                    *typed])[1] == "1\t\t\t0xef0e\t0\n"  # (crc as tshark writes vw3.crc)
    out = run_cli(["-x", *typed])[1]
    assert out.splitlines()[1:] == ["0000  0c 03 20 d0 00 03                                 .. ...", ""]
    assert run_cli(["-Y", "crc_ok", *typed])[1] == ""
    assert run_cli(["-Y", "!crc_ok", *typed])[1].endswith("CRC computed (none typed)\n")
    # ASCII: the LRC the same way
    ascii_typed = ["--hex", ":02062329000A"]
    assert "        LRC: none typed [LRC computed (none typed): 0xA2, not checked]" in run_cli(["-V", *ascii_typed])[1]
    assert run_cli(["-x", *ascii_typed])[1].splitlines()[1] == (
        "0000  3a 30 32 30 36 32 33 32 39 30 30 30 41 0d 0a      :02062329000A..")
    # A CRC typed is received and checked, everywhere as before.
    good = ["--hex", "0C 03 20 D0 00 03 0E EF"]
    assert "        CRC: 0xEF0E [CRC ok]" in run_cli(["-V", *good])[1].splitlines()
    record = json.loads(run_cli(["--json", *good])[1])
    assert (record["crc_ok"], record["crc"], "crc_typed" in record) == (True, 0xEF0E, False)
    assert run_cli(["-x", *good])[1].splitlines()[1] == "0000  0c 03 20 d0 00 03 0e ef                           .. ....."


def test_bytes_that_are_no_frame_either_way_stay_noise() -> None:
    status, out, _err = run_cli(["--hex", "0C 03 20"])
    assert status == 0
    assert out == "     1            -   - noise     3 bytes of noise at offset 0: 0c 03 20\n"


def test_a_good_frame_is_untouched() -> None:
    out = run_cli(["--hex", "0C 03 20 D0 00 03 0E EF"])[1]
    assert out.endswith("(3) [the capture ends before any response: not known whether it was answered]  CRC ok\n")


def test_an_ascii_frame_typed_without_its_lrc_gets_the_lrc_to_append() -> None:
    # the VW3 A3 303 manual's Write Single Register 9001 = 10 (:02062329000AA2)
    # (a request alone is no evidence of a device: profile `auto` names nothing; `--profile atv71` does)
    out = run_cli(["--hex", ":02062329000A", "--profile", "atv71"])[1]
    assert out == (
        "     1            -   2 request   Write Single Register 9001 ACC=10 (unscaled, in s) "
        "[the capture ends before any response: not known whether it was answered] [no LRC typed: append A2]  LRC computed (none typed)\n"
    )
    assert run_cli(["--hex", ":02062329000AA3"])[1].endswith("LRC BAD (received 0xA3, expected 0xA2)\n")


def test_two_good_frames_in_one_argument_are_left_alone() -> None:
    out = run_cli(["--hex", "0C 03 20 D0 00 03 0E EF 0C 03 06 80 00 00 03 00 02 17 E4"])[1]
    lines = out.splitlines()
    assert len(lines) == 2 and all(line.endswith("CRC ok") and "typed" not in line for line in lines)


def test_an_argument_holding_several_good_frames_is_not_mended_into_one() -> None:
    # Hunt 55 (4): a variable-length frame (FC8, a user-defined code) then another frame in one argument was
    # read as one frame whose last two bytes were a bad CRC (`data 1234ed4f020800001234`, CRC BAD); the same
    # bytes in a file, or as two arguments, are two frames with good CRCs.
    echo = "02 08 00 00 12 34 ed 4f 02 08 00 00 12 34 ed 4f"
    status, out, err = run_cli(["--hex", echo])
    assert (status, err) == (0, "")
    assert out.splitlines() == [
        "     1            -   2 request   Diagnostics 00h Return Query Data = 4660  CRC ok",
        "     2            -   2 response  Diagnostics 00h Return Query Data = 4660 [#1]  CRC ok",
    ]
    assert run_cli(["--hex", "02 41 01 02 d1 d9 02 41 01 02 d1 d9"])[1].splitlines() == [
        "     1            -   2 request   User-defined function 65 2 bytes of data  CRC ok",
        "     2            -   2 response  User-defined function 65 2 bytes of data [#1]  CRC ok",
    ]
    assert run_cli(["--hex", "02 08 00 00 12 34 ed 4f 02 03 00 00 00 01 84 39"])[1].splitlines() == [
        "     1            -   2 request   Diagnostics 00h Return Query Data = 4660 [no response]  CRC ok",
        "     2            -   2 request   Read Holding Registers 0 "
        "[the capture ends before any response: not known whether it was answered]  CRC ok",
    ]
    # A typo in one of them is still a typo: the bytes do not split into good frames, and stay as typed.
    assert "CRC ok" not in run_cli(["--hex", "02 08 00 00 12 34 ed 4f 02 08 00 00 12 34 ed 4e"])[1]
