"""Whether FC4 reads a table of its own is a fact of the device (profile `input_registers`): on the ATV71's
VW3 A3 303 card Read Holding Registers and Read Input Registers are identical (the manual's function table),
so an FC4 read of 8401 is a read of CHCF, the parameter FC3 reads: --stats, --watch and --report show one
parameter (profiles.device_tables; the compiled store asks each slave's, _stats.h slave_table). A device
whose tables are separate (generic: Application Protocol 4.3) keeps input register N apart
(tests/integration/test_register_tables.py). Before, the ATV71's CHCF was two rows, `8401 CHCF` and
`input 8401 CHCF`, and --watch printed the FC4 read of the value written as a change."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from dissector.devices.profiles import ProfileError, load_profile, parse_profile
from helpers import run_cli, stats_section, use_engine, write_rtu

# ATV71 slave 1: FC3 reads CHCF (8401) = 1, FC4 reads it = 1, FC6 writes 2 (echoed), FC4 reads 2, FC3
# reads 2, then FC4 reads 8401..8402: 16#8000 (CHCF protected) and 0 (COP).
FRAMES = [
    "01 03 20D1 0001", "01 03 02 0001",
    "01 04 20D1 0001", "01 04 02 0001",
    "01 06 20D1 0002", "01 06 20D1 0002",
    "01 04 20D1 0001", "01 04 02 0002",
    "01 03 20D1 0001", "01 03 02 0002",
    "01 04 20D1 0002", "01 04 04 8000 0000",
]
ATV71 = ["--profile", "atv71"]


def _capture(tmp_path: Path) -> Path:
    return write_rtu(tmp_path / "atv71.bin", FRAMES)


def test_the_profiles_say_what_fc4_reads() -> None:
    assert [load_profile(name).input_registers for name in ("atv71", "generic", "sel749m")] == [
        "holding", "separate", "separate"]
    with pytest.raises(ProfileError, match="input_registers 'coils' is not one of separate, holding"):
        parse_profile('name = "x"\ninput_registers = "coils"\n', "x.toml")


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("profile", [ATV71, []])  # named, or chosen by profile `auto`
def test_stats_counts_one_parameter_on_the_atv71(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                                 profile: list[str]) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats", *profile])
    assert status == 0, err
    assert stats_section(out) == [
        "slave   address  code  reads  unreadable  writes  refused  last          changes",
        "--------------------------------------------------------------------------------",
        "    1      8401  CHCF      4           1       1        0  protected           2",
        "    1      8402  COP       1           0       0        0  nO (no copy)        0",
        "  all  2 params            5           1       1        0                      2",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_stats_counts_two_parameters_on_a_generic_device(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                        pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats", "--profile", "generic"])
    assert status == 0, err
    assert stats_section(out) == [
        "slave     address  code  reads  unreadable  writes  refused  last   changes",
        "---------------------------------------------------------------------------",
        "    1        8401            2           0       1        0  2            1",
        "    1  input 8401            3           0       0        0  32768        2",
        "    1  input 8402            1           0       0        0  0            0",
        "  all    3 params            6           0       1        0               3",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_stats_json_row_is_the_holding_register(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), "--stats", "--json", *ATV71])
    assert status == 0, err
    assert [(row["address"], row["table"], row["code"], row["reads"], row["unreadable"], row["writes"],
             row["last_text"], row["changes"]) for row in json.loads(out)["parameters"]] == [
        (8401, "holding", "CHCF", 4, 1, 1, "protected", 2), (8402, "holding", "COP", 1, 0, 0, "nO (no copy)", 0)]


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("source", ["file", "stdin"])
def test_watch_sees_no_change_in_the_fc4_read_of_the_value_written(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                   pure: bool, source: str) -> None:
    use_engine(monkeypatch, pure)
    capture = _capture(tmp_path)
    if source == "file":
        status, out, err = run_cli([str(capture), "--watch", "8401", *ATV71])
    else:
        status, out, err = run_cli(["-", "--watch", "8401", *ATV71], stdin=capture.read_bytes())
    assert status == 0, err
    assert out.splitlines() == [
        "     6            -   1 CHCF SIM (combined) -> SEP (separate)",
        "    12            -   1 CHCF SEP (separate) -> protected",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_report_draws_one_series(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    page = tmp_path / "report.html"
    status, _out, err = run_cli([str(_capture(tmp_path)), "--report", str(page), *ATV71])
    assert status == 0, err
    data = json.loads(page.read_text().split('id="report-data">', 1)[1].split("</script>", 1)[0])
    assert [(row["address"], row["table"], row["label"], row["x"], row["y"], row["marks"])
            for row in data["parameters"]] == [
        (8401, "holding", None, [2.0, 4.0, 6.0, 10.0], [1, 1, 2, 2], [[12.0, "protected"]]),
        (8402, "holding", None, [12.0], [0], []),
    ]
    assert data["written"] == ["1:8401"]


@pytest.mark.parametrize("pure", [False, True])
def test_the_summary_tells_chcf_became_protected_after_fc4_read_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                   pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path)), *ATV71])
    assert status == 0, err
    assert out.splitlines()[11].endswith(
        "[CHCF (8401) became protected: read 2 in frame #10, 16#8000 now]  CRC ok")


@pytest.mark.parametrize("pure", [False, True])
def test_the_engine_counts_a_poll_of_both_codes_as_one_table(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                             pure: bool) -> None:
    """A poll the compiled engine counts itself (all but the first transactions): it asks the slave's
    tables of the store's device_tables (given none, it counted 49 reads as `input 8402`)."""
    use_engine(monkeypatch, pure)
    capture = write_rtu(tmp_path / "poll.bin", ["01 03 20D1 0001", "01 03 02 0001", "01 04 20D2 0001",
                                                "01 04 02 0000"] * 50)
    status, out, err = run_cli([str(capture), "--stats", *ATV71])
    assert status == 0, err
    assert stats_section(out)[2:] == [
        "    1      8401  CHCF     50           0       0        0  SIM (combined)        0",
        "    1      8402  COP      50           0       0        0  nO (no copy)          0",
        "  all  2 params          100           0       0        0                        0",
    ]
