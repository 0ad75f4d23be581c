"""The values confirmed Mask Writes (FC22) gave their registers wait for the parameter history in
Annotator.masked (memory.remember_mask, render/history.py History._mask) by the echo's frame number. An
echo a -Y display filter drops never reaches the history: before, its entry stayed to the end of the
run (5000 echoes filtered out: 5000 entries, growing with the input). Now an entry lasts no longer than
the echo's request, which the echo holds: the structure holds no more entries than echoes alive (a batch
of the input's) and none once the run is done. vw3-decode --stats, compiled engine (it hands a tracked
slave's FC22 transactions to the Python stages) and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import gc
import weakref
from pathlib import Path

import pytest

import dissector.devices.annotator as annotator
from helpers import rtu, run_cli, use_engine

pytestmark = pytest.mark.integration

ECHOES = 5000
# COP (8402) read 18, then masked AND 00F2 OR 0025 (the ATV71's memory gives it 23), again and again.
CYCLE = b"".join(rtu(frame) for frame in ("0C 03 20D2 0001", "0C 03 02 0012", "0C 16 20D2 00F2 0025",
                                          "0C 16 20D2 00F2 0025"))


@pytest.mark.parametrize("pure", [False, True])
def test_filtered_mask_write_echoes_leave_nothing_behind(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                         pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = tmp_path / "masks.bin"
    capture.write_bytes(CYCLE * ECHOES)
    echoes: weakref.WeakSet = weakref.WeakSet()  # the echoes annotated and still alive
    stores: list[dict] = []
    sizes: list[tuple[int, int]] = []  # (entries, echoes alive) after each echo
    remember_mask = annotator.remember_mask

    def watched(frame, device, masked=None) -> None:  # type: ignore[no-untyped-def]
        remember_mask(frame, device, masked)
        assert masked is not None  # (--stats: the history gave the annotator its store)
        echoes.add(frame)
        if not stores:
            stores.append(masked)
        sizes.append((len(masked), len(echoes)))

    monkeypatch.setattr(annotator, "remember_mask", watched)
    status, out, err = run_cli([str(capture), "--profile", "atv71", "--stats", "-Y", "function == 3"])
    assert status == 0, err
    assert len(sizes) == ECHOES
    assert all(entries <= alive for entries, alive in sizes), max(sizes)
    gc.collect()
    assert stores[0] == {}
