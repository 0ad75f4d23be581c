"""--address-style plc labels FC23's written window as its read window: where the request writes none (write
quantity 0, or a byte count of 0) the summary says `write 40006 (0)`, not the protocol number `5 (0)`; -V
says `PLC references (write): 40006` under the read line, --json and -T fields give `write_span_label`
(annotator._span_label, describe._write_span). Under the compiled engine and VW3_PURE_PYTHON=1 (the
plugin's side: tests/integration/test_lua_write_window_label.py)."""
from __future__ import annotations

import json

import pytest

from helpers import rtu, run_cli, use_engine

PLC = ["--profile", "generic", "--address-style", "plc"]
FRAMES = [  # (request, its Info, its write_span_label)
    ("01 17 0000 0001 0005 0000 00", "read 40001, write 40006 (0)", "40006"),
    ("01 17 0000 0002 0005 0003 00", "read 40001..40002 (2), write 40006..40008 (3)", "40006..40008"),
    ("01 17 0000 0001 0005 0001 02 0007", "read 40001, write 40006=7", "40006"),
]


def _args(*options: str) -> list[str]:
    return [*PLC, *options, *(arg for frame, _, _ in FRAMES for arg in ("--hex", rtu(frame).hex()))]


@pytest.mark.parametrize("pure", [False, True])
def test_summary(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(_args())
    assert (status, err) == (0, "")
    assert [line[34:].split(" [")[0] for line in out.splitlines()] == [
        f"Read/Write Multiple Registers {info}" for _, info, _ in FRAMES]


@pytest.mark.parametrize("pure", [False, True])
def test_detail_json_fields(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, _ = run_cli(_args("-V"))
    assert status == 0
    assert [line for line in out.splitlines() if "PLC references" in line] == [
        "        PLC references (read): 40001", "        PLC references (write): 40006",
        "        PLC references (read): 40001..40002", "        PLC references (write): 40006..40008",
        "        PLC references (read): 40001", "        PLC references (write): 40006"]
    status, out, _ = run_cli(_args("--json"))
    assert [json.loads(line)["write_span_label"] for line in out.splitlines()] == [label for _, _, label in FRAMES]
    status, out, _ = run_cli(_args("-T", "fields", "-e", "frame", "-e", "write_span_label",
                                   "-Y", 'write_span_label == "40006"'))
    assert out == "1\t40006\n3\t40006\n"


def test_protocol_style_keeps_numbers() -> None:
    status, out, _ = run_cli(["--profile", "generic", "--hex", rtu(FRAMES[0][0]).hex(), "--json"])
    record = json.loads(out)
    assert "write_span_label" not in record and "span_label" not in record
    status, out, _ = run_cli(["--profile", "generic", "--hex", rtu(FRAMES[0][0]).hex()])
    assert out[34:].startswith("Read/Write Multiple Registers read 0, write 5 (0) [")
