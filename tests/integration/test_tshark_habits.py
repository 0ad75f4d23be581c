"""tshark as the oracle of its own habits: the -t time column and -T fields / -E output, on the same
pcap with the same display filter (issue 15)."""
from __future__ import annotations

import os
import re
import subprocess
from pathlib import Path

import pytest

from helpers import run_cli
from lua_harness import ensure_tool

ROOT = Path(__file__).resolve().parents[2]
COLUMNS = re.compile(r" *\d+ +(.+?) +(?:\d{1,3}|-) (?:request|response|exception|noise)")
CAPTURES = [ROOT / "captures" / "p38_protection.pcap", ROOT / "captures" / "sel749m_polling.pcap"]


def _tshark(*argv: str) -> list[str]:
    done = subprocess.run(
        [ensure_tool("tshark", "tshark"), *argv], capture_output=True, text=True, timeout=120,
        env=dict(os.environ, TZ="UTC"),
    )
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


@pytest.mark.parametrize("capture", CAPTURES, ids=lambda path: path.stem)
@pytest.mark.parametrize("fmt", ["r", "d", "dd", "e", "u", "ud"])
def test_time_column_equals_tsharks_under_a_filter(capture: Path, fmt: str) -> None:
    # One frame per record in these captures, so frame numbers agree; frame 1 is filtered out, so r,
    # d and dd differ from one another only if the references are the capture's (r, d) or the shown (dd).
    expected = _tshark("-r", str(capture), "-t", fmt, "-Y", "frame.number >= 3 && frame.number <= 12",
                       "-T", "fields", "-e", "_ws.col.Time")
    status, out, err = run_cli(["-t", fmt, "-Y", "frame >= 3 and frame <= 12", str(capture)])
    assert (status, err) == (0, "")
    ours = [COLUMNS.match(line).group(1) for line in out.splitlines()]  # type: ignore[union-attr]
    assert ours == expected


@pytest.mark.parametrize(
    "options",
    [
        ["-E", "header=y", "-E", "separator=,", "-E", "quote=d"],
        ["-E", "separator=/s", "-E", "quote=s"],
        ["-E", "separator=;", "-E", "bom=y"],
        [],
    ],
)
def test_fields_layout_equals_tsharks(options: list[str]) -> None:
    capture = str(CAPTURES[0])
    expected = _tshark("-r", capture, "-T", "fields", "-e", "frame.number", "-e", "frame.len", *options)
    status, out, err = run_cli(["-T", "fields", "-e", "frame", "-e", "length", *options, capture])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    if "header=y" in options:  # the names differ (frame vs frame.number): compare the layout only
        assert lines[0] == "frame,length" and expected[0] == "frame.number,frame.len"
        lines, expected = lines[1:], expected[1:]
    assert lines == expected


@pytest.mark.parametrize("capture", CAPTURES, ids=lambda path: path.stem)
def test_time_fields_equal_tsharks_frame_time_fields(capture: Path) -> None:
    expected = _tshark("-r", str(capture), "-Y", "frame.number >= 3 && frame.number <= 12", "-T", "fields",
                       "-e", "frame.number", "-e", "frame.time_relative", "-e", "frame.time_delta",
                       "-e", "frame.time_delta_displayed", "-e", "frame.time_epoch")
    status, out, err = run_cli(["-Y", "frame >= 3 and frame <= 12", "-T", "fields", "-e", "frame",
                                "-e", "time_relative", "-e", "time_delta", "-e", "time_delta_displayed",
                                "-e", "time", str(capture)])
    assert (status, err) == (0, "")
    # tshark prints the epoch with 9 decimals; ours is the NDJSON number
    assert [line.rsplit("\t", 1)[0] for line in out.splitlines()] == [
        line.rsplit("\t", 1)[0] for line in expected
    ]
    assert [float(line.rsplit("\t", 1)[1]) for line in out.splitlines()] == [
        float(line.rsplit("\t", 1)[1]) for line in expected
    ]
