"""--parity, --stopbits and --bytesize set the serial port of --live (sources/serial_port.py); a file's line
is --baud's (framing/linespeed.py), its characters as many bits as the mode's (11 RTU, 10 ASCII). With a
file they are refused with one line (exit 2), not left silently out of the bus timing: before,
`--stats --baud 9600 --parity N FILE` said `line: 9600 baud (--baud), 11 bits a character` (8N1 is 10) and
`-w x.pcapng` kept `9600 baud (--baud)` alone. Live, they set the port as before (app/live.py)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli


def _capture(tmp_path: Path) -> Path:
    capture = tmp_path / "bus.bin"
    capture.write_bytes(rtu("11 03 0005 0001") + rtu("11 03 02 0001"))
    return capture


@pytest.mark.parametrize(("typed", "named"), [
    (["--parity", "N"], "--parity"),
    (["--stopbits", "2"], "--stopbits"),
    (["--bytesize", "7"], "--bytesize"),
    (["--parity", "E", "--stopbits", "1", "--bytesize", "8"], "--parity, --stopbits, --bytesize"),
])
def test_a_file_refuses_the_port_format(tmp_path: Path, typed: list[str], named: str) -> None:
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats", "--baud", "9600", *typed])
    assert (status, out) == (2, "")
    assert err == (f"vw3-decode: {named}: the serial port's frame format needs --live PORT (a file's line is "
                   "--baud's, its characters the mode's: 11 bits RTU, 10 ASCII)\n")


def test_a_file_without_them_is_read_as_before(tmp_path: Path) -> None:
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats", "--baud", "9600"])
    assert status == 0, err
    assert "line: 9600 baud (--baud), 11 bits a character" in out


def test_live_keeps_their_defaults_and_takes_them_typed() -> None:
    from dissector.app.options import build_parser, parse_arguments

    parser = build_parser()
    plain = parse_arguments(parser, ["--live", "loop://"])
    assert (plain.parity, plain.stopbits, plain.bytesize, plain.port_format) == ("E", 1, 8, [])
    typed = parse_arguments(parser, ["--live", "loop://", "--parity", "n", "--stopbits", "2"])
    assert (typed.parity, typed.stopbits, typed.port_format) == ("N", 2, ["--parity", "--stopbits"])


def test_live_opens_the_port_with_them() -> None:
    """`--live PORT --parity N` opens the port at 8N2 with --stopbits 2 (before this test, ebf0977 refused
    them live too: the display check _live makes took them for a file's)."""
    status, out, err = run_cli(["--live", "loop://", "--parity", "N", "--stopbits", "2", "--duration", "0.3"])
    assert (status, out) == (0, ""), err
    assert err.startswith("vw3-decode: listening on loop:// at 19200 8N2\n")
