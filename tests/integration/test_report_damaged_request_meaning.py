"""An exception answering a request whose copy failed its check: the slave answered bytes the tap did not see
(pairing.trusted_request), so the note, -V's `Meaning on this device` and --json pick nothing from the
damaged request (SEL-749M: every cause of 03 to FC3; ATV71: 02 to a write is the code's meaning, not a
read-only refusal). --report's event read the damaged request (`illegal number of registers to read ...`
alone; `write refused: read-only parameter (access R)`): now it says what the note says. The compiled
engine and VW3_PURE_PYTHON=1 (the damaged request is the Python stages' in both)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import write_pcap

pytestmark = pytest.mark.integration

SEL_BOTH = ("illegal number of registers to read (increments the Illegal Register counter) or format error "
            "(increments the Bad Packet Format counter)")
CASES = [  # profile, request (its CRC made bad), answer, meaning, function
    ("sel749m", "03 03 00 00 00 82", "03 83 03", SEL_BOTH, 3),
    ("atv71", "0C 06 0C 81 00 07", "0C 86 02", "address does not exist", 6),
]


def damaged(frame: str) -> bytes:
    raw = bytearray(rtu(frame))
    raw[-1] ^= 0xFF
    return bytes(raw)


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("profile, asked, answer, meaning, function", CASES)
def test_report_reads_no_damaged_request(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, profile: str,
                                         asked: str, answer: str, meaning: str, function: int) -> None:
    use_engine(monkeypatch, pure)
    path = str(write_pcap(tmp_path / "damaged.pcap", [(damaged(asked), 1700000000.0),
                                                       (rtu(answer), 1700000000.01)]))
    frames = [json.loads(line) for line in run_cli(["--profile", profile, "--json", path])[1].splitlines()]
    assert frames[1]["exception_meaning"] == meaning
    assert frames[1]["notes"][-1].split(": ", 1)[1] == meaning
    page = tmp_path / "damaged.html"
    assert run_cli(["--profile", profile, "--report", str(page), path])[0] == 0
    data = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(encoding="utf-8")).group(1))
    code = answer.split()[2]
    assert [event[3] for event in data["events"] if event[1] == "exception"] == [
        f"exception {code} to function {function}: {meaning}"]
