"""A normal answer whose every value is 16#8000, from a device that answers exception 02 when every parameter
read is non-existent or protected (VW3-A3-303 p.38, seed 000): one value at least is real, so none is told
unreadable. Before, 8400=non-existent CHCF=protected COP=protected, and --stats counted 3 unreadable
(hunter). Vectors: p.38's request 0C 03 20 D0 00 03 0E EF; its answer there 0C 03 06 80 00 00 03 00 02 17 E4."""
from __future__ import annotations

import json

import pytest

from helpers import run_cli, use_engine

ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
REQUEST = "0C 03 20 D0 00 03 0E EF"
ALL_MARKED = "0C 03 06 80 00 80 00 80 00 2E 25"
NOTE = ("every value is 16#8000, but the VW3 A3 303 answers exception 02 when every parameter read is "
        "non-existent or protected: one at least is the value 32768")


@ENGINES
def test_every_value_at_the_marker_is_ambiguous(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--profile", "atv71", "--hex", REQUEST, "--hex", ALL_MARKED])
    assert (status, err) == (0, "")
    assert out.splitlines()[1] == (
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 (16#8000: ambiguous) "
        "CHCF=32768 (not a listed value) (16#8000: ambiguous) COP=32768 (not a listed value) (16#8000: ambiguous) "
        f"[#1] [{NOTE}]  CRC ok")
    record = json.loads(run_cli(["--profile", "atv71", "--json", "--hex", REQUEST, "--hex", ALL_MARKED])[1].splitlines()[1])
    assert [(r["address"], r["value"], r["status"]) for r in record["registers"]] == [
        (8400, 32768, "ambiguous"), (8401, 32768, "ambiguous"), (8402, 32768, "ambiguous")]
    assert record["notes"] == [NOTE]


@ENGINES
def test_no_story_is_told_of_an_all_marked_answer(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    """CHCF read as 3 first: an all-16#8000 answer after it is no "became protected", and --stats counts no
    unreadable read."""
    use_engine(monkeypatch, pure)
    args = ["--profile", "atv71", "--hex", REQUEST, "--hex", "0C 03 06 80 00 00 03 00 02 17 E4",
            "--hex", REQUEST, "--hex", ALL_MARKED]
    out = run_cli(args)[1].splitlines()
    assert "became" not in out[3] and out[3].endswith(f"[#3] [{NOTE}]  CRC ok")
    stats = run_cli([*args, "--stats"])[1]
    rows = {line.split()[1]: line.split() for line in stats.splitlines() if line.startswith("   12      84")}
    assert [rows[address][2:5] for address in ("8401", "8402")] == [["CHCF", "2", "0"], ["COP", "2", "0"]]
    assert rows["8400"][1:4] == ["8400", "1", "1"]  # (its first read, p.38's non-existent 8400; then 32768)


@ENGINES
def test_one_value_not_at_the_marker_keeps_the_p38_reading(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    out = run_cli(["--profile", "atv71", "--hex", REQUEST, "--hex", "0C 03 06 80 00 00 03 00 02 17 E4"])[1]
    assert out.splitlines()[1] == (
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent "
        "CHCF=IO (I/O profile) COP=Cd (command) [#1]  CRC ok")


@ENGINES
def test_a_single_register_read_and_the_generic_profile_are_unchanged(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # One register: 16#8000 is its value (an unreadable one draws exception 02, p.38), as before.
    out = run_cli(["--profile", "atv71", "--hex", "0C 03 20 D1 00 01", "--hex", "0C 03 02 80 00"])[1]
    assert "ambiguous" not in out and "every value" not in out
    out = run_cli(["--profile", "generic", "--hex", REQUEST, "--hex", ALL_MARKED])[1]
    assert out.splitlines()[1] == (
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=32768 8402=32768 "
        "[#1]  CRC ok")
