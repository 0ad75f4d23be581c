"""--stats bus timing's outages (render/bustiming.py) and FC8 04 Force Listen Only Mode, which the spec's
server never answers (data/modbus.toml [pairing] never_answered): like a broadcast, it is neither one of
a run of unanswered polls nor the end of one; an exception to it (a server that does not support it) is
an answer and ends the run. Before, an 08/04 between unanswered polls cut the run in two: 'slave 1
silent 0.000000 - 0.100000, 2 requests unanswered (frames 1..2)' and the poll after it was lost. Exact
--stats lines and --json under the compiled engine and VW3_PURE_PYTHON=1, alike."""
from __future__ import annotations

import io
import json
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run
from dissector.render.pcapwriter import PcapWriter
from helpers import rtu, use_engine

T0 = 1767225600.0
READ, ANSWER = rtu("01 03 0000 0001"), rtu("01 03 02 0007")
LISTEN_ONLY, RESTART = rtu("01 08 0004 0000"), rtu("01 08 0001 0000")
REFUSED = rtu("01 88 01")  # exception 1: a server that does not support 04 says so
HEADER = "outages (two or more consecutive requests unanswered)"


def stats(frames: list[bytes], tmp_path: Path, monkeypatch: pytest.MonkeyPatch, *options: str) -> str:
    """--stats of the frames 100 ms apart, the same under the engine and the Python stages."""
    path = tmp_path / "bus.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, frame in enumerate(frames):
            writer.write(frame, T0 + 0.100 * index)
    outputs = []
    for pure in (False, True):
        use_engine(monkeypatch, pure)
        out, err = io.StringIO(), io.StringIO()
        assert run([str(path), "--stats", *options], Environment(io.BytesIO(b""), out, err, False, False)) == 0
        assert err.getvalue() == ""
        outputs.append(out.getvalue())
    assert outputs[0] == outputs[1]
    return outputs[0]


def outages(text: str) -> list[str]:
    lines = text.splitlines()
    return lines[lines.index(HEADER):] if HEADER in lines else [line for line in lines if line.startswith("outages")]


def test_listen_only_between_unanswered_polls_neither_counts_nor_ends_the_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # (the polls after 08/04 find the slave in listen-only mode: not answering them is no outage)
    frames = [READ, READ, LISTEN_ONLY, READ, READ, ANSWER]
    assert outages(stats(frames, tmp_path, monkeypatch)) == [
        HEADER,
        "  slave 1 silent 0.000000 - 0.100000, 2 requests unanswered (frames 1..2)",
    ]
    # (and until 08/01 Restart Communications Option, which it does not answer either)
    frames = [LISTEN_ONLY, READ, READ, RESTART, READ, READ, READ, ANSWER]
    assert outages(stats(frames, tmp_path, monkeypatch)) == [
        HEADER,
        "  slave 1 silent 0.400000 - 0.500000, 2 requests unanswered (frames 5..6)",
    ]
    (outage,) = json.loads(stats(frames, tmp_path, monkeypatch, "--json"))["bus"]["outages"]
    assert (outage["requests"], outage["first_frame"], outage["last_frame"]) == (2, 5, 6)
    assert outage["end"] - outage["start"] == pytest.approx(0.1)


def test_listen_only_alone_is_no_outage_and_makes_none(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # One unanswered poll, then 08/04: one request unanswered is no outage (two are), the 08/04 none.
    assert outages(stats([READ, LISTEN_ONLY, LISTEN_ONLY, READ, ANSWER], tmp_path, monkeypatch)) == ["outages: none"]


def test_an_exception_to_listen_only_ends_the_run(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The slave answered (it does not support 04): the polls before and after are two runs of one.
    frames = [READ, READ, LISTEN_ONLY, REFUSED, READ, READ, ANSWER]
    assert outages(stats(frames, tmp_path, monkeypatch)) == [
        HEADER,
        "  slave 1 silent 0.000000 - 0.100000, 2 requests unanswered (frames 1..2)",
    ]
