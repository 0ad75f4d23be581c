"""--stats of standard input (no look-ahead preselection) where profile `auto` takes slave 247 for an ATV71
(whose FC4 reads its holding registers) and takes that back at an FC2 answer (frame #6): the slave is
`generic` at the end, so what FC4 read is input registers, as the Python stages count it when they see
the whole stream at once. The compiled engine (and the Python stages fed frame by frame) counted the FC4
read while the slave was an ATV71, into holding registers, and nothing moved it back (SlaveTables moved
only towards a one-table device): `247  3201..3203 (3)`. Found by bench/fastsummary_fuzz.py --stats, seed 120."""
from __future__ import annotations

import pytest

from helpers import fed_piece_by_piece

from dissector.accel import fastsummary

# FC4 3201..3203, FC6 8501 := 15 (echoed), FC2 (which the VW3 A3 303 does not support), slave 247
FRAMES = [bytes.fromhex(f) for f in (
    "f7040c810003f7e5", "f70406063700000000ba95", "f7062135000fc76a", "f7062135000fc76a",
    "f70220d10022b77c", "f7020585f1c72fb5be64",
)]
LINE = "  247  input 3201..3203 (3)            1           0       0        0  (various)        0"
WHY = "  247  generic  function 2 answered in frame #6, which the VW3 A3 303 does not support"


def stats(pure: bool, pieces: list[bytes]) -> list[str]:
    return fed_piece_by_piece(["--stats", "-"], pieces, pure).splitlines()


@pytest.mark.skipif(fastsummary is None, reason="the compiled engine is not built")
@pytest.mark.parametrize("pieces", [[b"".join(FRAMES)], FRAMES], ids=["at-once", "frame-by-frame"])
def test_auto_taken_back_counts_input_registers(pieces: list[bytes]) -> None:
    engine = stats(False, pieces)
    python = stats(True, pieces)
    assert engine == python
    assert WHY in python
    assert LINE in python
    assert not any(line.startswith("  247  3201") for line in python)  # no holding register beside them
