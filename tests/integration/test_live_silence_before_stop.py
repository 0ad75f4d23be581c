"""Live on a pseudo-terminal: a request, 3 bytes of its answer, a silence, SIGINT (hunt66b's capture). Live --json,
the -w file decoded by the engine and by the Python stages, and the plugin on it (tshark -2) say the same
(test_live_capture_end.check_one_truth): the line silent t3.5 (1.75 ms at 115200 baud) before the stop cuts the
bytes, 'a silence cuts the response (3 of 7 bytes)', whether live closed them at its 250 ms flush (the file said
'the capture ends inside the response (3 of 7 bytes)') or at the stop (both said so). Exact bytes and tapes:
tests/differential/test_silence_before_stop.py."""
from __future__ import annotations

from pathlib import Path

import pytest

from test_live_capture_end import ANSWER, PURE, READ, check_one_truth, sniff

pytestmark = pytest.mark.integration


@pytest.mark.parametrize("silence", [0.15, 0.4], ids=["before-the-flush", "after-the-flush"])
@pytest.mark.parametrize("env", [{}, PURE], ids=["engine", "python"])
def test_a_silence_then_the_stop(tmp_path: Path, silence: float, env: dict[str, str]) -> None:
    path = tmp_path / "cut.pcap"
    live, err = sniff(path, [(READ, 0.1), (ANSWER[:3], silence)], [], env)
    items = check_one_truth(path, live)
    assert [(item["kind"], item["raw"], item.get("reason")) for item in items] == [
        ("request", READ.hex(), None), ("noise", ANSWER[:3].hex(), "a silence cuts the response (3 of 7 bytes)")]
