"""The Info of an answer whose request is not in the capture (a tap started between the two): a register
read's answer counts its registers and shows its values by index; a bit read's answer has no window to
name, so its bits follow the function's name directly, never after a stray space (`Read Coils : ...`)."""
from __future__ import annotations

import pytest

from helpers import run_cli, use_engine

TAIL = " [no request] [response without a matching request in the capture]  CRC ok\n"


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize(("frame", "info"), [
    ("01 01 01 05 91 8B", "Read Coils: 10100000"),
    ("01 02 01 05 61 8B", "Read Discrete Inputs: 10100000"),
    ("01 03 02 00 07 F9 86", "Read Holding Registers (1): ?+0=7"),
])
def test_an_answer_without_its_request(frame: str, info: str, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--hex", frame])
    assert (status, err) == (0, "")
    assert out == f"     1            -   1 response  {info}{TAIL}"
