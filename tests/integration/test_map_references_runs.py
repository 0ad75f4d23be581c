"""A --map written in PLC references is told on stderr by a --live run (at its end, before the capture's
summary line) and by a --parquet run (once after the captures), as by a file decode
(test_map_references_stderr.py): neither said it before. A map at protocol addresses says nothing."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from helpers import rtu, write_rtu
from live_tape import run_cli, tape_of

pytestmark = [pytest.mark.integration, pytest.mark.serial]  # (--live replays: serial, as before)

READ = ["01 03 0000 0004", "01 03 08 0193 01B8 01DC 0202"]
WARNING = ("vw3-decode: warning: map {path} names 2 of the 4 unnamed registers slave 1 reads or writes at "
           "address + 40001: PLC references? A map takes protocol addresses (reference - 40001) or a reference "
           "column")
ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def _run(argv: list[str], pure: bool, tape: Path | None = None) -> tuple[int, str, str]:
    done = run_cli(argv, pure, tape)
    return done.returncode, done.stdout, done.stderr


def _maps(tmp_path: Path) -> tuple[Path, Path]:
    wrong, right = tmp_path / "m.csv", tmp_path / "ok.csv"
    wrong.write_text("address,code\n40001,IA\n40002,IB\n")
    right.write_text("address,code\n0,IA\n1,IB\n")
    return wrong, right


@ENGINES
@pytest.mark.parametrize("output", [[], ["--json"], ["-V"]], ids=["summary", "json", "V"])
def test_a_live_run_warns_of_a_4x_map_at_its_end(tmp_path: Path, pure: bool, output: list[str]) -> None:
    records = [(rtu(frame), 100 + 0.05 * at) for at, frame in enumerate(READ * 3)]
    tape = tmp_path / "bus.tape"
    tape.write_bytes(tape_of(records, random.Random(1)))
    wrong, right = _maps(tmp_path)
    status, _out, err = _run(["--profile", "generic", "--map", str(wrong), *output], pure, tape)
    lines = err.splitlines()
    assert status == 0, err
    assert lines[0].startswith("vw3-decode: listening on /dev/ttyTAPE")
    assert lines[1:-1] == [WARNING.format(path=wrong)]  # (was: nothing between the two)
    assert lines[-1].startswith("vw3-decode: 6 frames")
    status, _out, err = _run(["--profile", "generic", "--map", str(right), *output], pure, tape)
    assert (status, len(err.splitlines())) == (0, 2), err


def test_a_parquet_run_warns_of_a_4x_map_once(tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    first = write_rtu(tmp_path / "a.bin", READ * 3)
    second = write_rtu(tmp_path / "b.bin", READ * 2)
    wrong, right = _maps(tmp_path)
    argv = ["--profile", "generic", "--parquet", str(tmp_path / "set"), str(first), str(second)]
    status, out, err = _run([*argv, "--map", str(wrong)], False)
    assert (status, err) == (0, WARNING.format(path=wrong) + "\n")  # (was: no warning)
    assert sorted(out.splitlines()) == [f"{first}: 6 frames, 12 registers, 0 events",
                                        f"{second}: 4 frames, 8 registers, 0 events"]
    assert _run([*argv, "--jobs", "2", "--map", str(wrong)], False)[::2] == (0, WARNING.format(path=wrong) + "\n")
    assert _run([*argv, "--map", str(right)], False)[::2] == (0, "")
