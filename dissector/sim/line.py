"""What a real RS-485 line adds to the frames a master and its slaves send, as a tap records it.

Random damage to frames (bit flips, dropped bytes: bench/noise_accuracy.py) is one thing a line does;
real recordings show others, which no damage model produced (issue 26):

- turn-around glitches: a bus driver switching between transmit and receive leaves one byte after
  each frame. On the sigrok-dumps `uart/modbus_rtu` wizmodbus recording, 00 after every request and
  FE after every response (`glitch after`); other adapters leave them before frames too, of any shape
  a short low pulse reads as, FF << k (`glitches both sides`);
- idle-line bytes: noise on an idle, badly biased line reads as FF (runs of them between frames);
- breaks: a line held low reads as 00 bytes, with framing errors the tap does not record;
- a truncated last frame: the capture stops inside a frame;
- bursts split at random: a USB adapter delivers what it has every few milliseconds, anywhere inside
  frames (the framers' input as chunks with boundary=True, as a pcap of serial reads is).

`on_the_line` applies one kind to a list of frames and says where each frame went; the frames
themselves stay whole, so every one of them must be found.
"""
from __future__ import annotations

import random
from dataclasses import dataclass

from dissector.framing.stream import GLITCH_BYTES
from dissector.model import Chunk

GLITCHES = tuple(sorted(GLITCH_BYTES, reverse=True))  # FF FE FC F8 F0 E0 C0 80 00
KINDS = ("glitch after", "glitches both sides", "idle-line bytes", "breaks", "truncated last frame")
BURST_BYTES = (1, 64)  # a read of a USB adapter: 1 to 64 bytes (FTDI's packet)


@dataclass
class Line:
    stream: bytes
    frames: list[tuple[int, bytes]]  # (offset, bytes) of every frame sent whole
    cut: bytes = b""  # the frame the capture ends inside, as far as it got


def on_the_line(frames: list[bytes], requests: list[bool], kind: str, rng: random.Random) -> Line:
    """The bytes a tap records when `frames` (requests[i]: frame i is a request) go over a line with
    noise of `kind` (KINDS)."""
    stream = bytearray()
    placed: list[tuple[int, bytes]] = []
    last = len(frames) - 1
    for index, (frame, request) in enumerate(zip(frames, requests)):
        if kind == "glitches both sides" and rng.random() < 0.5:
            stream.append(rng.choice(GLITCHES))
        elif kind == "idle-line bytes" and rng.random() < 0.3:
            stream += b"\xff" * rng.randint(1, 8)
        elif kind == "breaks" and rng.random() < 0.1:
            stream += b"\x00" * rng.randint(1, 3)
        if kind == "truncated last frame" and index == last:
            cut = frame[: rng.randrange(1, len(frame))]
            stream += cut
            return Line(bytes(stream), placed, cut)
        placed.append((len(stream), frame))
        stream += frame
        if kind == "glitch after":
            stream.append(0x00 if request else 0xFE)
        elif kind == "glitches both sides":
            stream.append(rng.choice(GLITCHES))
    return Line(bytes(stream), placed)


def bursts(data: bytes, rng: random.Random, time: float = 1_700_000_000.0) -> list[Chunk]:
    """`data` as a USB adapter's reads: random sizes, each a record (boundary=True), 1 ms apart."""
    chunks: list[Chunk] = []
    position = 0
    while position < len(data):
        size = rng.randint(*BURST_BYTES)
        chunks.append(Chunk(data[position : position + size], time + len(chunks) * 0.001, True))
        position += size
    return chunks
