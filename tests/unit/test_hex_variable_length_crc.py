"""--hex of a frame whose length its data sets (FC8 00 Return Query Data, a user-defined code) typed as a manual
prints it, without its CRC: the Modbus spec's FC8 example (`08 0000 A537`, echoed) at slave 17 is decoded with
its data and the CRC to append, as the same frame typed in Modbus ASCII without its LRC is (`no LRC typed:
append 0B`). Before (hunt67b), its last two bytes were taken for a mistyped CRC: `Diagnostics 00h Return Query
Data [warning: CRC bad: received 0x37A5, expected 0xDA84 ...]`, the data lost. A CRC typed nearly right (one
digit off, or high byte first) is still a typo of it."""
from __future__ import annotations

from helpers import run_cli

SPEC_EXAMPLE = "11 08 0000 A537"


def test_the_specs_fc8_example_typed_without_its_crc() -> None:
    assert run_cli(["--hex", SPEC_EXAMPLE, "--hex", SPEC_EXAMPLE]) == (0, (
        "     1            -  17 request   Diagnostics 00h Return Query Data = 42295 "
        "[no CRC typed: append D8 1D (CRC 0x1DD8)]  CRC computed (none typed)\n"
        "     2            -  17 response  Diagnostics 00h Return Query Data = 42295 [#1] "
        "[no CRC typed: append D8 1D (CRC 0x1DD8)]  CRC computed (none typed)\n"), "")
    ascii = run_cli(["--hex", ":11080000A537", "--hex", ":11080000A537"])[1]
    assert ascii.splitlines()[0].startswith(
        "     1            -  17 request   Diagnostics 00h Return Query Data = 42295 ")


def test_a_user_defined_code_typed_without_its_crc() -> None:
    assert run_cli(["--hex", "11 41 01 02 03"]) == (0, (
        "     1            -  17 request   User-defined function 65 3 bytes of data [the capture ends before any "
        "response: not known whether it was answered] [no CRC typed: append DC 9E (CRC 0x9EDC)]  CRC computed "
        "(none typed)\n"), "")


def test_a_crc_typed_nearly_right_is_its_typo() -> None:
    # high byte first, as a manual may print the CRC's value
    assert run_cli(["--hex", "11 08 0000 A537 1D D8"])[1] == (
        "     1            -  17 request   Diagnostics 00h Return Query Data = 42295 [the capture ends before any "
        "response: not known whether it was answered] [warning: CRC bad: received 0xD81D, expected 0x1DD8 (on the "
        "wire 1D D8 typed, D8 1D expected)]  CRC BAD (received 0xD81D, expected 0x1DD8)\n")
    # one digit off
    assert run_cli(["--hex", "11 08 0000 A537 D8 1E"])[1] == (
        "     1            -  17 request   Diagnostics 00h Return Query Data = 42295 [the capture ends before any "
        "response: not known whether it was answered] [warning: CRC bad: received 0x1ED8, expected 0x1DD8 (on the "
        "wire D8 1E typed, D8 1D expected)]  CRC BAD (received 0x1ED8, expected 0x1DD8)\n")
