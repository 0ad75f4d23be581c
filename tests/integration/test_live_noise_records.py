"""Live -w on a damaged line: the file decodes back to what live showed. Live wrote a record an item, so a
noise run's record ended where the line gave no silence, and a reader takes a record's end for a pause
(framing/rtu.py _followed): 20 bytes of noise live showed right before a damaged exception read back from
their own record as 12 bytes of noise and a damaged request (4 of 12 damaged plant tapes differed with the
engine, 6 of 18 with the Python stages).
A noise run now shares the record of the items after it in the batch that no silence parts it from
(app/live_capture.py CaptureFiles._records). Tapes of reads replayed (VW3_LIVE_REPLAY), both live paths."""
from __future__ import annotations

import json
import random
import shutil
import subprocess
from pathlib import Path

import pytest

from live_tape import run_cli, tape_of, write_tape
from lua_harness import record_lengths

from dissector.sim.mixes import plant_mix

pytestmark = pytest.mark.serial  # (--live replays: run alone, as before run_cli moved to live_tape)
ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
# Seed 6's plant tape: slave 30's read, 20 bytes of noise, right after them a damaged exception, then the answer.
READS = [(bytes.fromhex(text), 100 + at) for text, at in [
    ("1e0400000028f27b", 0.0), ("fe9cefa5bb53c088a3cbf9509403e61d5d0f39bd", 0.004991), ("b9fe1f624f", 0.016449),
    ("1e0450447ab6a744fa76fa453bbcf6457a49f0459c73a345bb924f45dae8b045fa2b61460ca658461c55ff462beec8463b9194"
     "464b3400465acc1e466a6954467a0e744684d910468ca87f46947a0f469c455e9009", 0.019564)]]
LIVE = [
    "     1     0.000000  30 request   Read Input Registers 0..39 (40) [no response]  CRC ok",
    "     2     0.004834   - noise     20 bytes of noise at offset 8: fe 9c ef a5 bb 53 c0 88 a3 cb f9 50 94 03 e6 1d…",
    "     3     0.016871 185 exception Function 126: exception 31 (Unknown exception 31) [no request] [response "
    "without a matching request in the capture] [warning: exception code 31 is not defined by the spec]  CRC BAD "
    "(received 0x4F62, expected 0x8DA1)",
    "     4     0.019782  30 response  Read Input Registers (40): ?+0=17530 ?+1=46759 ?+2=17658 ?+3=30458 "
    "?+4=17723 ?+5=48374 … (+34) [no request] [response without a matching request in the capture]  CRC ok",
]


def run(argv: list[str], pure: bool, tape: Path | None = None) -> list[str]:
    done = run_cli(["-n", *argv], pure, tape)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


def items(lines: list[str]) -> list[tuple[str, str]]:
    return [(item["kind"], item["raw"]) for item in map(json.loads, lines)]


@ENGINES
def test_noise_right_before_a_damaged_frame_shares_its_record(pure: bool, tmp_path: Path) -> None:
    tape = tmp_path / "noise.tape"
    tape.write_bytes(tape_of(READS, random.Random(1)))
    written, commented = tmp_path / "live.pcap", tmp_path / "live.pcapng"
    assert run(["-w", str(written), "-P"], pure, tape) == LIVE
    assert record_lengths(written) == [8, 25, 85, 0]  # (was 8, 20, 5, 85, 0)
    # Read back: the noise and the exception as live showed them (was 12 bytes of noise, then a damaged
    # request of slave 148 of the noise's last 8), the noise at its record's time, the exception's.
    assert run([str(written)], pure) == [LIVE[0], LIVE[1].replace("0.004834", "0.016871"), *LIVE[2:]]
    run(["-w", str(commented)], pure, tape)
    if shutil.which("tshark"):
        comments = subprocess.run(["tshark", "-r", str(commented), "-T", "fields", "-e", "frame.comment"],
                                  capture_output=True, text=True, check=True).stdout.splitlines()
        assert comments[:3] == ["", "noise: 20 bytes, no valid frame; then a damaged frame (5 bytes)", ""]


@ENGINES
@pytest.mark.parametrize("seed", [0, 3, 6, 7, 12, 16])
def test_damaged_tapes_read_back_as_live_showed(pure: bool, seed: int, tmp_path: Path) -> None:
    tape = write_tape(tmp_path / "plant.tape", plant_mix(200, seed=seed), seed=seed, damage=0.05)
    written = tmp_path / "live.pcap"
    live = items(run(["--json", "-w", str(written), "-P"], pure, tape))
    assert items(run(["--json", str(written)], pure)) == live
