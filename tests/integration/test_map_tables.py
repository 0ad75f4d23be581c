"""A map copied from a meter's manual names 3X references (30001: input register 0, read by FC4) and 4X
references (40001: holding register 0, FC3/6/16/22/23) in one `reference` column. Both were refused
("reference '40001' is address 0, as '30001' on line 2"), the map's rows being keyed by address alone;
now its 3X rows name the input registers and its 4X rows the holding registers, each table its own, in
every output, the compiled engine and VW3_PURE_PYTHON=1 alike. Where a profile's FC4 reads the holding
registers (the ATV71), a 3X row names the register FC3 reads too, and a 4X row of the same address wins."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import run_cli, use_engine, write_rtu

pytestmark = pytest.mark.integration

MAP = "reference,code,name,unit\n30001,IN0,Input zero,V\n30002,IN1,Input one,V\n40001,HR0,Holding zero,Hz\n" \
      "40002,HR1,Holding one,Hz\n"
# slave 1: FC4 reads input registers 0..1 (10, 11), FC3 holding registers 0..1 (20, 21)
ROUND = ["01 04 0000 0002", "01 04 04 000A 000B", "01 03 0000 0002", "01 03 04 0014 0015"]
SUMMARY = [
    "     1            -   1 request   Read Input Registers 0..1 (2)  CRC ok",
    "     2            -   1 response  Read Input Registers 0..1 (2): IN0=10 V IN1=11 V [#1]  CRC ok",
    "     3            -   1 request   Read Holding Registers 0..1 (2)  CRC ok",
    "     4            -   1 response  Read Holding Registers 0..1 (2): HR0=20 Hz HR1=21 Hz [#3]  CRC ok",
]


def _files(tmp_path: Path, frames: list[str] = ROUND, text: str = MAP) -> tuple[str, str]:
    (tmp_path / "m.csv").write_text(text)
    return str(write_rtu(tmp_path / "r.bin", frames)), str(tmp_path / "m.csv")


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_3x_rows_name_input_registers_and_4x_rows_holding_registers(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture, path = _files(tmp_path)
    status, out, err = run_cli([capture, "--profile", "generic", "--map", path])
    assert (status, out.splitlines(), err) == (0, SUMMARY, "")
    status, out, err = run_cli([capture, "--profile", "generic", "--map", path,
                                "-T", "fields", "-e", "frame", "-e", "code", "-e", "value"])
    assert (status, out, err) == (0, "1\t\t\n2\tIN0,IN1\t10,11\n3\t\t\n4\tHR0,HR1\t20,21\n", "")
    status, out, _err = run_cli([capture, "--profile", "generic", "--map", path, "--json"])
    answers = [json.loads(line) for line in out.splitlines()][1::2]
    assert [[(r["address"], r["code"], r["name"], r["text"]) for r in item["registers"]] for item in answers] == [
        [(0, "IN0", "Input zero", "10 V"), (1, "IN1", "Input one", "11 V")],
        [(0, "HR0", "Holding zero", "20 Hz"), (1, "HR1", "Holding one", "21 Hz")],
    ]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_stats_and_watch_keep_the_tables_apart(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture, path = _files(tmp_path)
    status, out, _err = run_cli([capture, "--profile", "generic", "--map", path, "--stats"])
    table = out.split("Parameters\n")[1].split("\n\n")[0].splitlines()
    assert (status, table[2:]) == (0, [
        "    1         0  HR0       1           0       0        0  20 Hz        0",
        "    1   input 0  IN0       1           0       0        0  10 V         0",
        "    1         1  HR1       1           0       0        0  21 Hz        0",
        "    1   input 1  IN1       1           0       0        0  11 V         0",
        "  all  4 params            4           0       0        0               0",
    ])
    capture = write_rtu(tmp_path / "w.bin", ROUND + [
        "01 04 0000 0002", "01 04 04 001A 001B", "01 03 0000 0002", "01 03 04 0024 0025"])
    status, out, _err = run_cli([str(capture), "--profile", "generic", "--map", path, "--watch", "IN0,HR1"])
    assert (status, out) == (0, "     6            -   1 IN0 10 -> 26 (V)\n     8            -   1 HR1 21 -> 37 (Hz)\n")


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_map_of_3x_rows_alone_names_no_holding_register(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                          pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture, path = _files(tmp_path, text="reference,code\n30001,IN0\n30002,IN1\n")
    status, out, _err = run_cli([capture, "--profile", "generic", "--map", path])
    assert (status, out.splitlines()[1::2]) == (0, [
        "     2            -   1 response  Read Input Registers 0..1 (2): IN0=10 IN1=11 [#1]  CRC ok",
        "     4            -   1 response  Read Holding Registers 0..1 (2): 0=20 1=21 [#3]  CRC ok",
    ])


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_where_fc4_reads_the_holding_registers_a_4x_row_wins(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                            pure: bool) -> None:
    """The ATV71 (input_registers = "holding"): one table, so 30001 and 40001 are one register, HR0; 30003,
    register 2, names it for FC3 and FC4 alike."""
    use_engine(monkeypatch, pure)
    capture, path = _files(tmp_path, ["01 04 0000 0003", "01 04 06 000A 000B 000C",
                                      "01 03 0000 0003", "01 03 06 0014 0015 0016"],
                           "reference,code\n30001,IN0\n30003,IN2\n40001,HR0\n")
    status, out, _err = run_cli([capture, "--profile", "atv71", "--map", path])
    assert (status, out.splitlines()[1::2]) == (0, [
        "     2            -   1 response  Read Input Registers 0..2 (3): HR0=10 1=11 IN2=12 [#1]  CRC ok",
        "     4            -   1 response  Read Holding Registers 0..2 (3): HR0=20 1=21 IN2=22 [#3]  CRC ok",
    ])


# Profile auto judges a slave's FC4 reads against the 3X rows of a map given for a candidate profile, as
# that device will name them (it judged them against the holding rows: no evidence, the slave stayed generic).
FC4_READS = ["01 04 0000 0002", "01 04 04 000A 000B", "01 04 000A 0001", "01 04 02 0007"] * 2
FIT = "traffic fits its map: function 4 at 0..1 in frame #2, function 4 at 10 in frame #4"


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_auto_judges_fc4_reads_by_the_3x_rows(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture, path = _files(tmp_path, FC4_READS, "reference,code\n30001,IN0\n30002,IN1\n30011,IN10\n40001,HR0\n")
    status, out, err = run_cli([capture, "--map", f"sel749m={path}", "--stats"])
    assert (status, err) == (0, "")
    assert out.split("Device profiles\n")[1].splitlines()[2] == f"    1  sel749m  {FIT}"
    status, out, err = run_cli([capture, "--map", f"sel749m={path}", "-T", "fields", "-e", "code", "-c", "4"])
    assert (status, out, err) == (0, "\nIN0,IN1\n\nIN10\n", "")
