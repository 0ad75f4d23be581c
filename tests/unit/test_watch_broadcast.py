"""--watch shows a broadcast write of a watched parameter (slave 0, named with the bus's common profile):
it writes every slave, whatever their states were, so it is shown each time, its old state `?` (JSON
null), marked `[broadcast: every slave]` (JSON "broadcast": true). Before, it was slave 0's first state,
never a change, and the watch showed nothing of it. Exact output for exact bytes (the hunter's bc.pcap),
the engine and VW3_PURE_PYTHON=1 alike."""
from __future__ import annotations

import io
import json
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run
from dissector.render.pcapwriter import PcapWriter
from helpers import rtu, use_engine

T0 = 1700000000.0
FRAMES = [
    (rtu("0C 03 20D0 0003"), 0.0), (rtu("0C 03 06 8000 0003 0002"), 0.02),
    (rtu("0C 03 20D0 0003"), 1.0), (rtu("0C 03 06 8000 8000 0002"), 1.02),
    (rtu("00 06 20D1 0003"), 2.0),  # CHCF = 3 to every slave
    (rtu("00 10 20D1 0002 04 0003 0002"), 3.0),  # CHCF = 3, COP = 2 to every slave
]


def watch(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, *options: str) -> str:
    path = tmp_path / "bc.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for frame, at in FRAMES:
            writer.write(frame, T0 + at)
    outputs = []
    for pure in (False, True):
        use_engine(monkeypatch, pure)
        out, err = io.StringIO(), io.StringIO()
        assert run([str(path), "--profile", "atv71", *options], Environment(io.BytesIO(b""), out, err, False, False)) == 0
        assert err.getvalue() == ""
        outputs.append(out.getvalue())
    assert outputs[0] == outputs[1]
    return outputs[0]


def test_a_broadcast_write_shows_on_the_watch(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    assert watch(tmp_path, monkeypatch, "--watch", "CHCF").splitlines() == [
        "     4     1.020000  12 CHCF IO (I/O profile) -> protected",
        "     5     2.000000   0 CHCF ? -> IO (I/O profile) [broadcast: every slave]",
        "     6     3.000000   0 CHCF ? -> IO (I/O profile) [broadcast: every slave]",
    ]


def test_json(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    records = [json.loads(line) for line in watch(tmp_path, monkeypatch, "--watch", "COP", "--json").splitlines()]
    assert records == [{"time": T0 + 3.0, "time_relative": 3.0, "frame": 6, "slave": 0, "address": 8402,
                        "code": "COP", "old": None, "new": "Cd (command)", "unit": None, "broadcast": True}]
