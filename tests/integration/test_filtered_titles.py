"""Several files with -Y: a file's `==> FILE <==` title comes with its first item shown, as grep -H names
only the files that match; a title over nothing read as a match (a file with no match, an empty file).
Without -Y every file keeps its title, as head(1) prints one over an empty file. Compiled engine and
VW3_PURE_PYTHON=1."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

SLAVE_1 = rtu("01 03 0000 0001") + rtu("01 03 02 0007")
SLAVE_2 = rtu("02 03 0000 0001") + rtu("02 03 02 0009")


@pytest.fixture
def files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    monkeypatch.chdir(tmp_path)
    Path("one.bin").write_bytes(SLAVE_1 * 2)
    Path("empty.bin").write_bytes(b"")
    Path("two.bin").write_bytes(SLAVE_2)
    return ["one.bin", "empty.bin", "two.bin"]


@pytest.mark.parametrize("pure", [False, True])
def test_filter_titles_only_files_with_a_match(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["-Y", "slave == 2", *files])
    assert status == 0, err
    assert out.splitlines() == [
        "==> two.bin <==",
        "     1            -   2 request   Read Holding Registers 0  CRC ok",
        "     2            -   2 response  Read Holding Registers 0: 0=9 [#1]  CRC ok",
    ]
    assert err == "vw3-decode: warning: empty.bin: the input is empty\n"


@pytest.mark.parametrize("pure", [False, True])
def test_filter_with_no_match_anywhere_prints_nothing(files: list[str], monkeypatch: pytest.MonkeyPatch,
                                                      pure: bool) -> None:
    use_engine(monkeypatch, pure)
    for options in ([], ["-V"], ["-x"]):
        status, out, err = run_cli(["-Y", "slave == 9", *options, *files])
        assert (status, out) == (0, ""), (options, err)


@pytest.mark.parametrize("pure", [False, True])
def test_filter_title_over_detail(files: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["-Y", "slave == 1 and frame == 3", "-V", *files])
    assert status == 0, err
    assert out.startswith("==> one.bin <==\nFrame 3:"), out[:80]
    assert out.count("==>") == 1


@pytest.mark.parametrize("pure", [False, True])
def test_without_filter_every_file_has_its_title(files: list[str], monkeypatch: pytest.MonkeyPatch,
                                                 pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(files)
    assert status == 0, err
    assert [line for line in out.splitlines() if line.startswith("==>")] == [
        "==> one.bin <==", "==> empty.bin <==", "==> two.bin <=="]
