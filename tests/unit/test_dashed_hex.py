"""Dash-separated hex, as C#'s BitConverter.ToString writes a byte array (`01-03-00-00-00-02-C4-0B`): how
.NET Modbus programs (NModbus, EasyModbus users) log the frames they send and receive. Colon-separated hex
(ESPHome's) was read, this was refused: `--hex '01-03-...'` said "'01-03-00-00-00-02-C4-0B' is not hex", and
a log of such lines was "neither a hex dump nor Modbus ASCII: decoded as raw bytes", one noise item (hunt64)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli

LINES = ["     1            -   1 request   Read Holding Registers 0..1 (2)  CRC ok",
         "     2            -   1 response  Read Holding Registers 0..1 (2): 0=0 1=1 [#1]  CRC ok"]


def test_hex_typed_with_dashes() -> None:
    assert run_cli(["-n", "--hex", "01-03-00-00-00-02-C4-0B", "--hex", "01-03-04-00-00-00-01-3b-f3"]) == (
        0, "\n".join(LINES) + "\n", "")


def test_a_log_of_dashed_lines(tmp_path: Path) -> None:
    log = tmp_path / "nmodbus.log"
    log.write_text("2024-05-01 10:00:00.125 TX: 01-03-00-00-00-02-C4-0B\n"
                   "2024-05-01 10:00:00.150 RX: 01-03-04-00-00-00-01-3B-F3\n")
    assert run_cli(["-n", str(log)]) == (0, "\n".join([
        "     1     0.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
        "     2     0.025000   1 response  Read Holding Registers 0..1 (2): 0=0 1=1 [#1, 25.0 ms]  CRC ok"]) + "\n", "")


@pytest.mark.parametrize("typed", ["01-03:00", "1-3-0", "01--03", "01-03-"])
def test_a_dash_alone_proves_nothing(typed: str) -> None:
    """(one separator a token, two digits a byte: anything else stays refused as before)"""
    assert run_cli(["--hex", typed]) == (2, "", f"vw3-decode: --hex: {typed!r} is not hex\n")
