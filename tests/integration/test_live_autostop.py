"""tshark's and dumpcap's `-a` stops for --live (README's live stops named `-a` where vw3-decode answered
`unrecognized arguments: -a`): `-a duration:S` is --duration, `-a packets:N` is -c; their other conditions are
refused by name (exit 2), never ignored, and a bad value with argparse's one line, no traceback."""
from __future__ import annotations

import time

import pytest

from helpers import run_cli

from dissector.app.options import build_parser, parse_arguments


def test_a_duration_stops_a_live_capture() -> None:
    began = time.monotonic()
    status, out, err = run_cli(["--live", "loop://", "-a", "duration:0.3"])
    assert (status, out) == (0, ""), err
    assert err.startswith("vw3-decode: listening on loop:// at 19200 8E1\n")
    assert time.monotonic() - began < 20


def test_they_set_what_duration_and_count_set() -> None:
    parser = build_parser()
    args = parse_arguments(parser, ["--live", "loop://", "-a", "duration:2.5", "-a", "packets:7"])
    assert (args.duration, args.count) == (2.5, 7)
    later = parse_arguments(parser, ["--live", "loop://", "--duration", "9", "-a", "duration:1"])
    assert later.duration == 1.0  # (the later of two, as --duration given twice)


@pytest.mark.parametrize(("typed", "said"), [
    ("filesize:100", "argument -a: 'filesize:100': stops are duration:S and packets:N (a -w ring buffer's size "
                     "is -b filesize:KB,files:N)"),
    ("duration:x", "argument -a: 'x' is not a number of seconds"),
    ("packets:0", "argument -a: '0' must be more than 0"),
    ("duration", "argument -a: '' is not a number of seconds"),
])
def test_other_stops_and_bad_values_are_refused(typed: str, said: str) -> None:
    status, out, err = run_cli(["--live", "loop://", "-a", typed])
    assert (status, out) == (2, "")
    assert err == f"vw3-decode: {said} (see vw3-decode --help)\n"


def test_a_file_refuses_a_duration_by_both_names(tmp_path) -> None:
    capture = tmp_path / "bus.bin"
    capture.write_bytes(b"\x11\x03\x00\x05\x00\x01\x96\x9b")
    status, out, err = run_cli([str(capture), "-a", "duration:1"])
    assert (status, out, err) == (2, "", "vw3-decode: --duration (-a duration:S) needs --live PORT\n")
