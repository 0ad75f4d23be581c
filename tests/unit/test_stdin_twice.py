"""Standard input named twice (`vw3-decode - -`, `-r - -`) is refused in one line, exit 2, before reading: it can be
read once. Before, the first `-` decoded it and the second warned `-: standard input: the input is empty` under a
second `==> - <==` title, exit 0. A file named twice is two inputs, decoded twice, as before."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli

REQUEST = rtu("01 03 0000 0002")


@pytest.mark.parametrize("argv", [["-", "-"], ["-r", "-", "-"], ["-n", "-", "-", "-w", "out.pcap"]])
def test_standard_input_twice_is_refused(argv: list[str]) -> None:
    assert run_cli(argv, stdin=REQUEST) == (2, "", "vw3-decode: standard input (-) is given twice: it can be read once\n")


def test_a_file_twice_is_two_inputs(tmp_path: Path) -> None:
    path = tmp_path / "poll.bin"
    path.write_bytes(REQUEST)
    status, out, err = run_cli(["-n", str(path), "-", str(path)], stdin=REQUEST)
    assert (status, err) == (0, "")
    assert [line for line in out.splitlines() if line.startswith("==>")] == [
        f"==> {path} <==", "==> - <==", f"==> {path} <=="]
