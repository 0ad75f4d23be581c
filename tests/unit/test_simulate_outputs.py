"""The simulator's output directory that cannot be written is one line on stderr and status 1, as vw3-decode
says an output it cannot write (README: never a traceback). Before, `python3 -m dissector.sim --out FILE`
(a file where the directory belongs) and `--out FILE/sub` ended in a FileExistsError or NotADirectoryError
traceback."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.sim.simulate import main

PROG = "python3 -m dissector.sim.simulate"


@pytest.mark.parametrize(("below", "args"), [("", ["--session", "p38_protection"]),
                                             ("/sub", ["--transactions", "3"])])
def test_an_output_that_is_a_file(tmp_path: Path, capsys: pytest.CaptureFixture[str], below: str,
                                  args: list[str]) -> None:
    (tmp_path / "taken").write_bytes(b"x")
    out = f"{tmp_path}/taken{below}"
    assert main(["--out", out, *args]) == 1
    assert capsys.readouterr() == ("", f"{PROG}: cannot write {out}: Not a directory\n")
    assert (tmp_path / "taken").read_bytes() == b"x"


def test_a_directory_is_written(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["--out", str(tmp_path / "new" / "dir"), "--session", "p38_protection"]) == 0
    assert capsys.readouterr().err == f"{tmp_path}/new/dir/p38_protection.bin and p38_protection.pcap: 12 records\n"
    assert sorted(path.name for path in (tmp_path / "new" / "dir").iterdir()) == [
        "p38_protection.bin", "p38_protection.pcap"]
