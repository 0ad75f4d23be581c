"""A Modbus ASCII line ended LF then CR (the line end reversed: a device or a tty that writes them in the wrong
order): the frame decodes and keeps the CR, with the warning 'line ends with LF then CR, reversed (the spec ends a
frame with CR LF)' (framing/ascii.py). Before: the frame said 'line ends with LF without CR', false, and its CR
was a byte of noise of its own. A CR after a whole CR LF line, or an LF after LF CR, stays noise: shown, its own
item. Exact summary lines and --json, under the engine and VW3_PURE_PYTHON=1 (ASCII is framed in Python either
way), whatever the chunks; the plugin: tests/integration/test_lua_ascii_reversed_line_end.py."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import ascii_items, run_cli, use_engine
from test_ascii_line_end_faults import ANSWER, HOLDING, READ, UNKNOWN, VALUES, line

REVERSED = "line ends with LF then CR, reversed (the spec ends a frame with CR LF)"
NO_CR = "line ends with LF without CR (the spec ends a frame with CR LF)"

# (bytes, summary lines)
CASES = {
    "LF CR": (
        line(READ, b"\n\r") + line(ANSWER, b"\n\r"),
        [f"     1            -   2 request   {HOLDING} [warning: {REVERSED}]  LRC ok",
         f"     2            -   2 response  {VALUES} [#1] [warning: {REVERSED}]  LRC ok"],
    ),
    "LF CR, then CR LF": (
        line(READ, b"\n\r") + line(ANSWER) + line(READ, b"\n\r"),
        [f"     1            -   2 request   {HOLDING} [warning: {REVERSED}]  LRC ok",
         f"     2            -   2 response  {VALUES} [#1]  LRC ok",
         f"     3            -   2 request   {HOLDING} [{UNKNOWN}] [warning: {REVERSED}]  LRC ok"],
    ),
    "LF alone": (
        line(READ, b"\n") + line(ANSWER, b"\n"),
        [f"     1            -   2 request   {HOLDING} [warning: {NO_CR}]  LRC ok",
         f"     2            -   2 response  {VALUES} [#1] [warning: {NO_CR}]  LRC ok"],
    ),
}
# (bytes, summary lines): a byte no line end takes stays a noise item
STRAYS = {
    "CR after CR LF": (
        line(READ) + b"\r" + line(ANSWER),
        [f"     1            -   2 request   {HOLDING}  LRC ok",
         "     2            -   - noise     1 byte of noise at offset 17: 0d",
         f"     3            -   2 response  {VALUES} [#1]  LRC ok"],
    ),
    "LF after LF CR": (
        line(READ, b"\n\r\n") + line(ANSWER),
        [f"     1            -   2 request   {HOLDING} [warning: {REVERSED}]  LRC ok",
         "     2            -   - noise     1 byte of noise at offset 17: 0a",
         f"     3            -   2 response  {VALUES} [#1]  LRC ok"],
    ),
}


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("case", [*CASES, *STRAYS])
def test_summary(case: str, pure: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    data, lines = {**CASES, **STRAYS}[case]
    path = tmp_path / "capture.txt"
    path.write_bytes(data)
    assert run_cli([str(path)]) == (0, "\n".join(lines) + "\n", "")


def test_the_frame_keeps_its_cr(tmp_path: Path) -> None:
    path = tmp_path / "capture.txt"
    path.write_bytes(CASES["LF CR"][0])
    status, out, _ = run_cli(["--json", str(path)])
    first = json.loads(out.splitlines()[0])
    assert (status, first["offset"], first["length"], bytes.fromhex(first["raw"])[-2:]) == (0, 0, 17, b"\n\r")
    assert first["warnings"] == [REVERSED]


@pytest.mark.parametrize("case", [*CASES, *STRAYS])
def test_the_same_whatever_the_chunks(case: str) -> None:
    data = {**CASES, **STRAYS}[case][0]
    whole = ascii_items(data)
    assert b"".join(raw for _, _, raw, _ in whole) == data
    for size in (1, 2, 3, 16):
        assert ascii_items(data, size) == whole
