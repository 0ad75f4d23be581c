"""`vw3-decode FILE -w COPY` of a tap's reads decodes as FILE (sources/trail.py, render/capturefile.py
write_items): random streams of frames, damaged frames and line noise, cut into reads of 1..12 bytes with
silences of 0..20 ms between them (some inside frames, some reads stamped before the last one ended).
Before the copy wrote its reads, 45 of these 50 streams read back otherwise (silences inside frames lost);
then 14 of 2,000 such streams (seeds 56, 244, ...: an item from inside a read a record of its own), none of
these: test_copy_read_bounds.py holds them."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from helpers import rtu, run_cli
from dissector.model import Stamp
from dissector.render.pcapwriter import PcapWriter

T0 = 1_767_225_600_000_000  # us
FRAMES = [rtu("0C 03 20 D0 00 03"), rtu("0C 03 06 0001 0002 0003"), rtu("01 06 0001 0003"),
          rtu("01 10 0001 0002 04 0001 0002"), rtu("01 83 02"), rtu("01 10 0001 0002")]
CHARACTER_US = 573  # 11 bits at 19200 baud
SILENCES_US = [0, 0, 200, 900, 3000, 20000, -300]


def stream(rng: random.Random) -> bytes:
    data = b""
    for _ in range(rng.randint(3, 12)):
        draw, frame = rng.random(), rng.choice(FRAMES)
        if draw < 0.15:
            data += bytes(rng.randrange(256) for _ in range(rng.randint(1, 6)))
        elif draw < 0.25:
            damaged = bytearray(frame)
            damaged[rng.randrange(len(damaged))] ^= 1 << rng.randrange(8)
            data += bytes(damaged)
        else:
            data += frame
    return data


def reads(rng: random.Random, data: bytes) -> list[tuple[bytes, int]]:
    position, micros, found = 0, 0, []
    while position < len(data):
        piece = data[position : position + rng.randint(1, 12)]
        found.append((piece, micros))
        position += len(piece)
        micros = max(micros + len(piece) * CHARACTER_US + rng.choice(SILENCES_US), micros)
    return found


@pytest.mark.parametrize("seed", range(50))
def test_a_copy_of_reads_decodes_as_they_do(tmp_path: Path, seed: int) -> None:
    rng = random.Random(seed)
    original, copy = tmp_path / "reads.pcap", tmp_path / "copy.pcap"
    with original.open("wb") as stream_:
        writer = PcapWriter(stream_, flush=False)
        for data, micros in reads(rng, stream(rng)):
            writer.write(data, Stamp((T0 + micros) * 1000))
    decoded = run_cli([str(original)])
    assert run_cli([str(original), "-w", str(copy)])[:2] == (0, "")
    assert run_cli([str(copy)])[1] == decoded[1]
