"""Several files are one bus's pieces: profile `auto` chooses over all of them before the first is decoded,
so the same bytes are named alike whatever the files' order. Before, `vw3-decode polls.bin atv71.bin`
named polls.bin's FC4 reads with the generic profile (`8401=3`: atv71.bin's identification came later),
and `vw3-decode atv71.bin polls.bin` named the same frames `CHCF=IO`. Standard input is read once: its
frames stay provisional. Compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

POLL = rtu("02 04 20D1 0001") + rtu("02 04 02 0003")
IDENT = rtu("02 2B 0E 01 00") + rtu(
    "02 2B 0E 01 02 00 00 02 00 0D" + b"Telemecanique".hex() + "01 0B" + b"ATV71HU15M3".hex())
POLLS = [
    "==> polls.bin <==",
    "     1            -   2 request   Read Input Registers 8401  CRC ok",
    "     2            -   2 response  Read Input Registers 8401: CHCF=IO (I/O profile) [#1]  CRC ok",
    "     3            -   2 request   Read Input Registers 8401  CRC ok",
    "     4            -   2 response  Read Input Registers 8401: CHCF=IO (I/O profile) [#3]  CRC ok",
]


@pytest.fixture
def files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "polls.bin").write_bytes(POLL * 2)
    (tmp_path / "atv71.bin").write_bytes(IDENT)


def _section(out: str, name: str) -> list[str]:
    lines = out.splitlines()
    start = lines.index(f"==> {name} <==")
    stop = next((at for at in range(start + 1, len(lines)) if lines[at].startswith("==> ")), len(lines))
    return lines[start:stop]


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("order", [["polls.bin", "atv71.bin"], ["atv71.bin", "polls.bin"]])
def test_same_bytes_same_names_in_either_order(files: None, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                               order: list[str]) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(order)
    assert status == 0, err
    assert _section(out, "polls.bin") == POLLS


@pytest.mark.parametrize("pure", [False, True])
def test_stats_the_same_in_either_order(files: None, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    first = run_cli(["--stats", "polls.bin", "atv71.bin"])
    second = run_cli(["--stats", "atv71.bin", "polls.bin"])
    assert first[0] == second[0] == 0
    registers = [line for line in first[1].splitlines() if "8401" in line]
    assert registers and registers == [line for line in second[1].splitlines() if "8401" in line]


def test_standard_input_is_read_once(files: None, monkeypatch: pytest.MonkeyPatch) -> None:
    status, out, err = run_cli(["-", "atv71.bin"], stdin=Path("polls.bin").read_bytes())
    assert status == 0, err
    assert _section(out, "-")[2] == (
        "     2            -   2 response  Read Input Registers 8401: 8401=3 [#1] [provisional]  CRC ok")
