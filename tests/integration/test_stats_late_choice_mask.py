"""A Mask Write (FC22) among the frames the history holds until profile `auto` chooses late: standard input
counts it as the file does. The echo was decoded while the slave had no device, so the annotator kept no
parameter memory and gave no value (memory.remember_mask); read again with the ATV71 chosen by the FC43
ProductCode at the end, its value is the replay's memory of the register ((7 AND 0xFFF0) OR 0x0003 = 3), as
the file, named with the ATV71 from frame #1, counts it: 8501 changes 7 -> 3 -> 7 -> 11, three changes (stdin
counted one: the mask's write confirmed nothing)."""
from __future__ import annotations

import json

import pytest

from helpers import rtu, stats_section, use_engine

from test_stats_late_choice_stream import MIN, _min_cut_after, _stats

CUT = _min_cut_after(10)  # (after #10, before the FC43 answer that chooses)
READ_8501 = rtu("0c0321350001")
MASK = rtu("0c16" + "2135" + "fff0" + "0003")  # echo confirms it: the register holds (v AND FFF0) OR 0003


def _read(value: int) -> bytes:
    return READ_8501 + rtu(f"0c0302{value:04x}")


KNOWN = MIN[:CUT] + _read(7) + MASK + MASK + _read(7) + _read(11) + MIN[CUT:]
# No read before the mask: the value it gives is not known (its write counted, the state unchanged).
UNKNOWN = MIN[:CUT] + MASK + MASK + _read(7) + _read(11) + MIN[CUT:]
ROWS = {
    "value-known": "   12      8501  CMD       3           0       1        0  Switch on, Enable voltage, Enable operation        3",
    "value-unknown": "   12      8501  CMD       2           0       1        0  Switch on, Enable voltage, Enable operation        1",
}
VECTORS = {"value-known": KNOWN, "value-unknown": UNKNOWN}


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("read", ["stdin", "file"])
@pytest.mark.parametrize("name", list(VECTORS))
def test_a_held_mask_write_counts_as_the_file(name: str, read: str, pure: bool, tmp_path, monkeypatch) -> None:
    use_engine(monkeypatch, pure)
    rows = [row for row in stats_section(_stats(VECTORS[name], read, tmp_path)) if "8501" in row]
    assert rows == [ROWS[name]]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_json_of_the_stream_is_the_files(pure: bool, tmp_path, monkeypatch) -> None:
    use_engine(monkeypatch, pure)
    stream = json.loads(_stats(KNOWN, "stdin", tmp_path, "--json"))
    assert stream == json.loads(_stats(KNOWN, "file", tmp_path, "--json"))
    row = [p for p in stream["parameters"] if p["address"] == 8501][0]
    assert (row["writes"], row["changes"], row["last"]) == (1, 3, 11)
