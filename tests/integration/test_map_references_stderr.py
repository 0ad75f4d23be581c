"""A --map written in PLC references is told on stderr once per run, terminal or not, whatever the
output (the summary, --json, --stats): `vw3-decode: warning: ` and the note of the frame that showed it
(test_map_references.py). A map the traffic does not show to be in references says nothing."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli, write_rtu

pytestmark = pytest.mark.integration

READ = ["01 03 0000 0004", "01 03 08 0193 01B8 01DC 0202"]


@pytest.mark.parametrize("output", [[], ["--json"], ["--stats"], ["-V"]], ids=["summary", "json", "stats", "V"])
def test_a_4x_map_is_warned_once_on_stderr(tmp_path: Path, output: list[str]) -> None:
    capture = write_rtu(tmp_path / "r.bin", READ * 3)
    path = tmp_path / "m.csv"
    path.write_text("address,code\n40001,IA\n40002,IB\n")
    status, _out, err = run_cli([str(capture), "--profile", "generic", "--map", str(path), *output])
    assert (status, err) == (0, (
        f"vw3-decode: warning: map {path} names 2 of the 4 unnamed registers slave 1 reads or writes at address "
        "+ 40001: PLC references? A map takes protocol addresses (reference - 40001) or a reference column\n"))
    path.write_text("address,code\n0,IA\n1,IB\n")
    assert run_cli([str(capture), "--profile", "generic", "--map", str(path), *output])[::2] == (0, "")
