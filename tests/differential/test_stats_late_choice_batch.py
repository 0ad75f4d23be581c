"""--stats of standard input where profile `auto` settles slave 12 without a device (8 answers, frame #16),
then chooses the ATV71 (FC43 ProductCode, frame #19), whose FC4 reads its holding registers. Holding register 3
was read by FC4 (#8: 65535, an input register while the slave had no device), FC3 (#10: 150), FC3 (#14: 65535).
The history counts the frames named before the choice in the tables of the profile they were named with, and
the choice's frame moves them (History._named_tables, _rehome), however the input is cut. Before, when the
choice was decoded in the same read as the frames before it (the annotator ahead of the history), those went
to the ATV71's tables at once: one read of the whole input showed `3 ... 65535 2` (changes), frame by frame
`... 1`. Found by bench/fastsummary_fuzz.py --stats, seed 41435 (its reference decodes all before counting).
Since the history holds a slave's frames until its choice is final (render/history.py held), the stream counts
what the file, named with the choice from its first frame, counts: 2 changes at 3 (65535, 150, 65535 in one
table; it was 1), and address 65535's 16#8000 `non-existent` once (it was read twice: a value before the choice)."""
from __future__ import annotations

import pytest

from helpers import fed_piece_by_piece, rtu

from dissector.accel import fastsummary

HEAD = bytes.fromhex(
    "0c10ffff00030601280096000072d20c10ffff000381310c0420d200019b2e0c04027d91740d0c08000b000090d40c08000b000090d4"
    "0c04fffe000620f10c040c000280000128000f0002ffffc95d0c03fffe000695310c030c0002002000010637bdfe0096ec9c"
    "0c170c2000020c8100020400050001d75b0c17040128000225d20c0300000006c4d50c030c9ce600070096ffffffff0005d4aa"
    "0c080000fa9257f2fd39da1ff4518c287048e366ff9ff90c080000fa9257f2fd39da1ff4518c287048e366ff9ff9"
)
MIDDLE = rtu("0c0300640001") + rtu("0c03020009")  # frames #17, #18: after settling, before the choice
CHOICE = bytes.fromhex("0c2b0e0102ff00020003e974e90106415456373148dc0d")  # #19: ProductCode 'ATV71H'
TAIL = (rtu("0c0300000001") + rtu("0c03020007")) * 6
PARAMETERS = [
    "Parameters",
    "slave    address  code  reads  unreadable  writes  refused  last                                   changes",
    "----------------------------------------------------------------------------------------------------------",
    "   12          0            9           0       1        0  7                                            4",
    "   12          1            3           0       1        0  7                                            3",
    "   12          2            3           0       0        0  150                                          2",
    "   12          3            3           0       0        0  65535                                        2",
    "   12          4            1           0       0        0  65535                                        0",
    "   12          5            1           0       0        0  5                                            0",
    "   12        100            1           0       0        0  9                                            0",
    "   12       3104  HSP       1           0       0        0  29.6 Hz                                      0",
    "   12       3105  LSP       1           0       0        0  0.2 Hz                                       0",
    "   12       3201  ETA       0           0       1        0  Ready to switch on, Operation enabled        0",
    "   12       3202  RFR       0           0       1        0  0.1 Hz                                       0",
    "   12       8402  COP       1           0       0        0  32145 (not a listed value)                   0",
    "   12      65534            2           0       0        0  2                                            0",
    "   12      65535            1           1       1        0  32                                           2",
    "  all  14 params           27           1       5        0                                              13",
]


@pytest.mark.skipif(fastsummary is None, reason="the compiled engine is not built")
@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("cut", ["at-once", "in-pieces"])
def test_frames_before_a_late_choice_count_alike_however_read(pure: bool, cut: str) -> None:
    pieces = [HEAD + MIDDLE + CHOICE + TAIL] if cut == "at-once" else [HEAD, MIDDLE, CHOICE + TAIL]
    lines = fed_piece_by_piece(["--stats", "-"], pieces, pure).splitlines()
    start = lines.index("Parameters")
    assert lines[start : start + len(PARAMETERS)] == PARAMETERS


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_the_file_counts_the_same(pure: bool, tmp_path) -> None:
    path = tmp_path / "late.bin"
    path.write_bytes(HEAD + MIDDLE + CHOICE + TAIL)
    lines = fed_piece_by_piece(["--stats", str(path)], [b""], pure).splitlines()
    start = lines.index("Parameters")
    assert lines[start : start + len(PARAMETERS)] == PARAMETERS
