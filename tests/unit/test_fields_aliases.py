"""-T fields -e takes the other names -Y takes and -G fields lists (`exception_code ... (alias: exception)`):
`-e exception` is the exception code's column, headed as asked. Under the engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import pytest

from helpers import run_cli, use_engine

ARGV = ["--hex", "0C 03 20 D0 00 03 0E EF", "--hex", "0C 83 02 51 32", "-T", "fields", "-E", "header=y"]


@pytest.mark.parametrize("pure", [False, True])
def test_exception_alias_column(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([*ARGV, "-e", "frame", "-e", "exception", "-e", "exception_code"])
    assert (status, out) == (0, "frame\texception\texception_code\n1\t\t\n2\t2\t2\n"), err
    status, out, err = run_cli([*ARGV, "-e", "frame", "-e", "exception", "-Y", "exception == 2"])
    assert (status, out) == (0, "frame\texception\n2\t2\n"), err
