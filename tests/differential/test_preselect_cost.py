"""Profile auto's compiled first pass (dissector/accel/preselect.py) on frames the engine hands to the Python
stages one by one (FC24 Read FIFO Queue, FC43 identification): the bits of what the selector must see are
made again for the slaves of the frames handed over, not for all 255 at every hand-back. They were: 255
selector look-ups a frame, 7x a normal capture's time for 1 MB of FC24 transactions (2.3 s against 0.33 s;
1.2 s now, cost63)."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.accel import fastsummary
from dissector.app.preselect import choose_profiles
from dissector.devices.build import build_annotator
from dissector.devices.selection import Selector
from dissector.sources.reader import open_source
from helpers import rtu
from test_timed_summary import write_pcap

TRANSACTIONS = 400
FIFO = "0118" + "0020" + "001e" + "".join(f"{value:04x}" for value in range(14))  # 14 registers queued
OBJECTS = "2b0e0183000078" + "".join(f"{id:02x}00" for id in range(0x80, 0xf8))  # 120 empty objects
PAIRS = {
    "fc24": (rtu("01180400"), rtu(FIFO)),
    "fc43": (rtu("012b0e0300"), rtu("01" + OBJECTS)),
    "fc3": (rtu("010300000002"), rtu("0103040001ffff")),  # (a normal poll, for the count it costs)
}


def _looked_up(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, kind: str) -> tuple[int, dict[int, str]]:
    """Selector.settled calls in profile auto's first pass over TRANSACTIONS pairs, the choices made."""
    monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)
    request, answer = PAIRS[kind]
    records, ns = [], 1767225600 * 10**9
    for _ in range(TRANSACTIONS):
        records += [(request, ns), (answer, ns + 10**7)]
        ns += 5 * 10**7
    pcap = tmp_path / f"{kind}.pcap"
    write_pcap(pcap, records)
    calls = 0
    settled = Selector.settled

    def counted(self: Selector, slave: int) -> bool:
        nonlocal calls
        calls += 1
        return settled(self, slave)

    monkeypatch.setattr(Selector, "settled", counted)
    annotate = build_annotator([], [], None)
    with open_source(str(pcap)) as source:
        choose_profiles(annotate, source, source.mode, None, 1.0)  # type: ignore[arg-type]
    return calls, {slave: choice.text() for slave, choice in annotate.selector.chosen().items()}


@pytest.mark.skipif(not fastsummary.available(), reason="the compiled engine is not built")
@pytest.mark.parametrize("kind", ["fc24", "fc43"])
def test_handed_over_frames_cost_a_few_lookups_each(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                    kind: str) -> None:
    calls, chosen = _looked_up(tmp_path, monkeypatch, kind)
    normal, _ = _looked_up(tmp_path, monkeypatch, "fc3")
    # (slave 1's frames only: a few look-ups a transaction and one table of 255 slaves at the start; the
    # normal poll's pass costs about as much. Before: 255 a hand-back, 100 000+ here.)
    assert calls < 10 * TRANSACTIONS + 2 * 255, (calls, normal)
    assert calls < 10 * normal, (calls, normal)
    assert list(chosen) in ([], [1])
