"""While a slave is in Listen Only Mode (pairing.py), the compiled engine, which keeps no mode, hands that slave's
transactions to the Python stages (slave_info: not usable; in judge and frames mode, its row of the judge
bitmap) and still takes the other slaves' ones: the outputs byte-identical to VW3_PURE_PYTHON=1. Before, the
Python stages kept the whole stream from the first 08/04 on (the pairer was not idle while a slave was in the
mode): a random bus's share of the engine fell from 436 to 133 of 588 frames (test_count_cut). The extension
must be built: it is not skipped."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.accel import fastsummary
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk
from dissector.pipeline import Dissector
from dissector.render.summary import summary_line
from helpers import engine_output_as_python as frames_path, rtu, use_engine
from test_timed_summary import write_pcap

LISTEN_ONLY, RESTART = rtu("0C 08 0004 0000"), rtu("0C 08 0001 0000")
BROADCAST_LISTEN_ONLY = rtu("00 08 0004 0000")
READ_12, ANSWER_12 = rtu("0C 03 20D1 0001"), rtu("0C 03 02 0003")
READ_5, ANSWER_5 = rtu("05 03 0000 0002"), rtu("05 03 04 0001 0002")
RESTART_5 = rtu("05 08 0001 0000")


def summary(data: bytes, pure: bool) -> tuple[list[str], int]:
    """The summary lines of raw RTU bytes, and how many of them the engine wrote."""
    if pure:
        dissector = Dissector(framer=RtuFramer())
        return [summary_line(item) for item in dissector.feed(Chunk(data)) + dissector.finish()], 0
    lines: list[str] = []
    written = [0]

    def text(encoded: bytes) -> None:
        new = encoded.decode()[:-1].split("\n")
        lines.extend(new)
        written[0] += len(new)

    path = fastsummary.SummaryPath(Dissector(framer=RtuFramer()), None,
                                   lambda items: lines.extend(summary_line(item) for item in items), text)
    path.feed(data)
    path.finish()
    return lines, written[0]


def test_the_engine_takes_the_other_slaves_while_one_listens() -> None:
    polls = (READ_5 + ANSWER_5) * 15
    data = LISTEN_ONLY + polls + READ_12 + polls + RESTART + (READ_12 + ANSWER_12) * 10
    expected, _ = summary(data, pure=True)
    got, engine = summary(data, pure=False)
    assert got == expected
    assert " ".join(expected[31].split()) == (
        "32 - 12 request Read Holding Registers 8401 "
        "[slave 12 is in listen-only mode since #1 (08/04): it does not answer] CRC ok")
    # (of the 83 lines, slave 5's 60 and slave 12's 20 after its 08/01, but where a hand-over costs one)
    assert len(expected) == 83 and engine >= 70


def test_frames_mode_after_a_broadcast_08_04(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # Every slave is in the mode until its own 08/01: slave 5's reads are the Python stages' before it, the
    # engine's after it (slave 12, still in the mode, the Python stages' to the end).
    frames = [BROADCAST_LISTEN_ONLY, *[READ_5, READ_12] * 5, RESTART_5, *[READ_5, ANSWER_5] * 20, READ_12]
    pcap = tmp_path / "lo.pcap"
    write_pcap(pcap, [(frame, 1_700_000_000_000_000_000 + k * 50_000_000) for k, frame in enumerate(frames)])
    out, framed = frames_path([str(pcap), "--json"], monkeypatch)
    assert out.count("is in listen-only mode since #1 (08/04, broadcast)") == 11
    assert out.count("leaves listen-only mode") == 1
    assert not [number for number in framed if number <= 12]
    assert len([number for number in framed if 12 < number <= 52]) >= 36
    assert 53 not in framed  # (slave 12's last read)
