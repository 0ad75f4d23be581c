"""vw3-decode -V names an exception's function as -Y's `function` and --json hold it, 3 (tshark's modbus
alike: `Read Holding Registers (3)`), the byte's high bit said as the exception it marks (0x83), so the
number -V shows can be typed into -Y. Under the compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import pytest

from helpers import run_cli, use_engine

ARGV = ["--hex", "0C 03 20 D0 00 03 0E EF", "--hex", "0C 83 02 51 32"]


@pytest.mark.parametrize("pure", [False, True])
def test_exception_function_line(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([*ARGV, "-V"])
    assert status == 0, err
    assert [line.strip() for line in out.splitlines() if "Function:" in line or "Exception code:" in line] == [
        "Function: 3 (0x03) Read Holding Registers",
        "Function: 3 (0x03) Read Holding Registers, exception (0x83)",
        "Exception code: Illegal Data Address (2)",
    ]
    status, out, err = run_cli([*ARGV, "-T", "fields", "-e", "frame", "-Y", 'function == 3 && kind == "exception"'])
    assert (status, out) == (0, "2\n"), err
