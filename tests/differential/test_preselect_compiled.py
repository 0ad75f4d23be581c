"""Profile auto's first pass framed in C (dissector/accel/preselect.py) against the Python pass: the same
choice for every slave, with the same reason (frame numbers included), on the shipped captures and on
random timed pcaps with damage; and the engine passes most frames of a settled bus itself."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from dissector.accel import preselect as compiled
from dissector.app.preselect import choose_profiles
from dissector.devices.build import build_annotator
from dissector.sources.reader import open_source
from test_timed_summary import cut_records, frames_of, write_pcap

ROOT = Path(__file__).resolve().parents[2]
CAPTURES = sorted(str(path) for path in (ROOT / "captures").glob("*.pcap"))


def choices(path: str, pure: bool, monkeypatch: pytest.MonkeyPatch, forced: list[str] | None = None) -> dict:
    if pure:
        monkeypatch.setenv("VW3_PURE_PYTHON", "1")
    else:
        monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)
    annotate = build_annotator(forced or [], [], None)
    with open_source(path) as source:
        choose_profiles(annotate, source, source.mode, None, 1.0)  # type: ignore[arg-type]
    return {slave: choice.text() for slave, choice in annotate.selector.chosen().items()}


@pytest.mark.parametrize("path", CAPTURES + [str(ROOT / "captures" / "sel749m_polling.bin")])
def test_shipped_captures_same_choices(path: str, monkeypatch: pytest.MonkeyPatch) -> None:
    fast = choices(path, False, monkeypatch)
    assert fast == choices(path, True, monkeypatch)
    if "atv71" in path:
        assert fast  # (these identify or fit a device)


@pytest.mark.parametrize("seed", range(4))
def test_random_captures_same_choices(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(seed)
    records = cut_records(rng, frames_of(seed + 40, damaged=0.05), ["frame", "bursts"][seed % 2])
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, records)
    assert choices(str(capture), False, monkeypatch) == choices(str(capture), True, monkeypatch)
    forced = ["1=sel749m", "2=atv71"]
    assert choices(str(capture), False, monkeypatch, forced) == choices(str(capture), True, monkeypatch, forced)


def test_settled_slaves_frames_stay_in_the_engine() -> None:
    """A polling bus: once its slaves are settled, the engine hands the selector nothing."""
    from dissector.decode.fields import decode_frame
    from dissector.decode.pairing import Pairer
    from dissector.framing.rtu import RtuFramer
    from dissector.model import Chunk, Frame, Stamp
    from dissector.sim.simulate import generate_session

    annotate = build_annotator([], [], None)
    annotate.thaw()
    handed: list[Frame] = []

    def judge(items: list) -> None:
        for item in items:
            if isinstance(item, Frame):
                handed.append(item)
                decode_frame(item)
                annotate.selector.observe(item)

    records = generate_session(3000, seed=2)
    chunks = [Chunk(data, Stamp(round(time * 1e9)), True) for data, time in records]
    assert compiled.choose(annotate, chunks, RtuFramer(), Pairer(timeout=1.0), judge, 1.0)
    assert len(handed) < 0.05 * len(chunks)
    assert all(annotate.selector.settled(frame.slave) for frame in handed if frame.slave)
