"""--stats of standard input where profile `auto` takes slave 12 for an ATV71 (whose FC4 reads its holding
registers), counts an FC4 read and an FC6 write of 8502 as one parameter, and takes that back at an FC5 answer
(frame #6): the slave is `generic` at the end, and the file (named with the last choice throughout) counts
input register 8502 (read 7) apart from holding register 8502 (written 32). The stores keep the story each
protocol table's codes tell of a parameter two count (stats_store.ParameterTable._part, dissector/accel/_parts.h)
and part it when the choice is taken back. Before, the engine showed one row `12  8502  1 ... 1  32  1` from
standard input (and the Python stages fed frame by frame too). Found by bench/fastsummary_fuzz.py --stats, seed 256."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import fed_piece_by_piece

from dissector.accel import fastsummary
from dissector.devices.profiles import ONE_TABLE, TABLES
from dissector.render.stats_store import (
    CONFIRM, HOLDING_REGISTERS, INPUT_REGISTERS, MAX_KEYS, READ, WRITE, ParameterTable, parameter_rows, table_homes,
)

# FC4 8502 (7), FC6 8502 := 32 (echoed), FC5 (which the VW3 A3 303 does not support): slave 12
FRAMES = [bytes.fromhex(f) for f in (
    "0c0421360001dae5", "0c04020007d533", "0c0621360020633d", "0c0621360020633d", "0c0520d0ff00871e",
    "0c0520d0ff00871e",
)]
PARAMETERS = [
    "Parameters",
    "slave     address  code  reads  unreadable  writes  refused  last  changes",
    "--------------------------------------------------------------------------",
    "   12        8502            0           0       1        0  32          0",
    "   12  input 8502            1           0       0        0  7           0",
    "  all    2 params            1           0       1        0              0",
]


def stats(pure: bool, pieces: list[bytes] | None, path: Path | None = None) -> list[str]:
    lines = fed_piece_by_piece(["--stats", str(path or "-")], pieces or [], pure).splitlines()
    start = lines.index("Parameters")
    return lines[start : start + len(PARAMETERS)]


@pytest.mark.skipif(fastsummary is None, reason="the compiled engine is not built")
@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("pieces", [None, [b"".join(FRAMES)], FRAMES], ids=["file", "at-once", "frame-by-frame"])
def test_taken_back_parts_what_the_atv71_counted_as_one(tmp_path: Path, pure: bool, pieces: list[bytes] | None) -> None:
    path = None
    if pieces is None:
        path = tmp_path / "bus.bin"
        path.write_bytes(b"".join(FRAMES))
    assert stats(pure, pieces, path) == PARAMETERS


@pytest.mark.skipif(fastsummary is None, reason="the compiled engine is not built")
def test_both_stores_part_and_join_alike() -> None:
    """generic -> ATV71 -> generic -> ATV71 on one slave: input 8401 and holding 8401 joined (their parts kept),
    a further read of each, parted again (each its own story), joined again; 8402 (FC4 only) moves each time."""
    from dissector.accel import _summary

    one, apart = table_homes(ONE_TABLE), table_homes(TABLES)
    H, I = HOLDING_REGISTERS, INPUT_REGISTERS
    steps = [
        ("param", (5, 8401, READ, 3, None, None, I, I)),
        ("param", (5, 8401, READ, 4, None, None, H, H)),
        ("param", (5, 8402, READ, 9, None, None, I, I)),
        ("rehome", (5, one)),
        ("param", (5, 8401, READ, 3, None, None, H, I)),  # changed (4 -> 3) as one story, no change as input's
        ("param", (5, 8401, WRITE, 6, None, None, H, H)),
        ("param", (5, 8401, CONFIRM, 6, None, None, H, H)),
        ("rehome", (5, apart)),
        ("param", (5, 8401, READ, 3, None, None, I, I)),
        ("rehome", (5, one)),
    ]
    stores = [_summary.Stats(MAX_KEYS), ParameterTable()]
    seen = []
    for store in stores:
        told = []
        for name, args in steps:
            told.append(getattr(store, name)(*args))
            if name == "rehome":
                told.append(list(parameter_rows(store)))
        seen.append(told)
    assert seen[0] == seen[1]
    assert seen[1][5] is True and seen[1][10] is False  # (3 after 4; 3 after input's 3)
    assert seen[1][9] == [  # parted: input 2 reads of 3 (no change), holding 1 read of 4, written 6 (1 change)
        (5, 8401, None, 1, 0, 1, 0, 6, None, 1, H),
        (5, 8401, None, 2, 0, 0, 0, 3, None, 0, I),
        (5, 8402, None, 1, 0, 0, 0, 9, None, 0, I),
    ]
    assert seen[1][12] == [  # joined again: 4 reads, a write, 6 -> 3 one change more
        (5, 8401, None, 4, 0, 1, 0, 3, None, 2, H),
        (5, 8402, None, 1, 0, 0, 0, 9, None, 0, H),
    ]
