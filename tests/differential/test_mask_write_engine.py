"""A Mask Write (FC22) of a slave that follows no parameter memory (no profile: generic) is counted by the
compiled engine itself under --stats and --report, as history.History._mask counts it (a write of its
register; its echo confirms or_mask where and_mask is 0; an exception refuses it), byte-identical to the
Python stages (VW3_PURE_PYTHON=1). Before, the engine handed every such transaction to the Python stages
when it counted: on the max-size mix (5 % FC22) --stats took 2.4-3.5 times the summary's time, over
issue 28's 2x."""
from __future__ import annotations

import io
import json
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run
from dissector.render.history import History
from helpers import rtu
from test_timed_summary import assert_same, write_pcap

# 8402 read 18, masked AND 00F2 OR 0025 (23, from the last value read), read 23; 8403 masked AND 0000 OR 0005
# (5 whatever it held); 8405's mask refused (exception 01); slave 7 masked AND 0000 OR 1234, unanswered.
FRAMES = [
    "0C 03 20D2 0001", "0C 03 02 0012",
    "0C 16 20D2 00F2 0025", "0C 16 20D2 00F2 0025",
    "0C 03 20D2 0001", "0C 03 02 0017",
    "0C 16 20D3 0000 0005", "0C 16 20D3 0000 0005",
    "0C 16 20D5 00F2 0025", "0C 96 01",
    "07 16 0010 0000 1234",
    "0C 03 20D3 0001", "0C 03 02 0005",
]


def _capture(tmp_path: Path) -> Path:
    capture = tmp_path / "mask.pcap"
    start = 1_700_000_000 * 10**9
    # 10 ms between frames; the unanswered one is followed by 1 s of silence
    times = [start + k * 10_000_000 + (1_000_000_000 if k > 10 else 0) for k in range(len(FRAMES))]
    write_pcap(capture, [(rtu(frame), ns) for frame, ns in zip(FRAMES, times)])
    return capture


@pytest.mark.parametrize("option", [["--stats"], ["--stats", "--json"]])
def test_the_engine_counts_an_untracked_mask_write(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                    option: list[str]) -> None:
    out, _ = assert_same([str(_capture(tmp_path)), *option], monkeypatch)
    assert _python_masks(tmp_path, option, monkeypatch) == []  # none handed to the Python stages
    if option == ["--stats"]:
        assert "   12      8403            1           0       1        0  5           0" in out.splitlines()
    else:
        rows = json.loads(out)["parameters"]
        assert [(row["slave"], row["address"], row["writes"], row["refused"], row["last"]) for row in rows] == [
            (7, 16, 1, 0, None), (12, 8402, 1, 0, 23), (12, 8403, 1, 0, 5), (12, 8405, 1, 1, None)]


def _python_masks(tmp_path: Path, option: list[str], monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """The frames whose Mask Write the Python stages' history counted, in an engine run."""
    monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)
    counted: list[int] = []
    mask = History._mask

    def counting(self: History, frame, provisional: bool) -> None:  # type: ignore[no-untyped-def]
        counted.append(frame.number)
        mask(self, frame, provisional)

    monkeypatch.setattr(History, "_mask", counting)
    env = Environment(io.BytesIO(), io.StringIO(), io.StringIO(), False, False)
    assert run([str(_capture(tmp_path)), *option], env) == 0
    monkeypatch.setattr(History, "_mask", mask)
    return counted


def test_the_engine_draws_an_untracked_mask_write(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pages = []
    for pure in (False, True):
        page = tmp_path / f"report-{pure}.html"
        if pure:
            monkeypatch.setenv("VW3_PURE_PYTHON", "1")
        else:
            monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)
        env = Environment(io.BytesIO(), io.StringIO(), io.StringIO(), False, False)
        assert run([str(_capture(tmp_path)), "--report", str(page)], env) == 0
        pages.append(page.read_text())
    assert pages[0] == pages[1]
    assert _python_masks(tmp_path, ["--report", str(tmp_path / "page.html")], monkeypatch) == []
    data = json.loads(pages[0].split('id="report-data">', 1)[1].split("</script>", 1)[0])
    points = {row["address"]: row["y"] for row in data["parameters"]}
    assert points == {8402: [18, 23, 23], 8403: [5, 5]}  # (the echo gives 8402 23: test_mask_write_last)
