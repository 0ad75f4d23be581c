"""A bit-level model of a UART receiving a line driven at another setting, for --detect tests.

A pseudo-terminal ignores baud rate and parity, so the wrong settings are emulated: the bus is a
line level over time (bit cells at the wire's baud rate, idle high between frames), and the
receiver does what a 16550-style UART does: wait for a falling edge, check the start bit at half a
bit, sample 7 or 8 data bits (LSB first), the parity bit if any and the stop bit at the middle of each of
*its own* bit times, flag a parity or framing error, and hunt for the next falling edge after the
stop sample. It is a model: real UARTs sample 16 times a bit and vote, and resynchronise after a
framing error in their own ways; what it shows is that the scoring rejects mis-sampled bytes.
"""
from __future__ import annotations

import math
import os
import random
import termios
import threading
import struct
import time
from bisect import bisect_left
from dataclasses import dataclass

import serial

from dissector.protocol.crc import with_crc
from dissector.app.detect import BAUDS, Heard, Setting


def parity_bit(byte: int, parity: str) -> int:
    ones = bin(byte).count("1") & 1
    return ones if parity == "E" else 1 - ones


def encode_byte(byte: int, parity: str, size: int = 8, stops: int = 1) -> bytes:
    bits = [0, *((byte >> i) & 1 for i in range(size))]
    if parity != "N":
        bits.append(parity_bit(byte, parity))
    bits += [1] * stops
    return bytes(bits)


class Wire:
    """A line carrying `frames` at (baud, parity, data bits, stop bits), each followed by its gap; it
    repeats forever."""

    def __init__(self, baud: int, parity: str, frames: list[tuple[bytes, float]], lead: float = 0.005,
                 size: int = 8, stops: int = 1):
        bits = bytearray(b"\x01" * round(lead * baud))
        for frame, gap in frames:
            for byte in frame:
                bits += encode_byte(byte, parity, size, stops)
            bits += b"\x01" * round(gap * baud)
        self.bits = bytes(bits)
        self.bit_time = 1 / baud
        self.duration = len(bits) * self.bit_time
        n = len(bits)
        self.falls = [k for k in range(n) if bits[k] == 0 and bits[k - 1] == 1]

    def level(self, t: float) -> int:
        return self.bits[int(t / self.bit_time) % len(self.bits)]

    def next_fall(self, t: float) -> float:
        n = len(self.bits)
        k0 = math.ceil(t / self.bit_time - 1e-9)
        cycle, rest = divmod(k0, n)
        index = bisect_left(self.falls, rest)
        if index == len(self.falls):
            cycle, index = cycle + 1, 0
        return (cycle * n + self.falls[index]) * self.bit_time


def receive(
    wire: Wire, baud: int, parity: str, start: float, end: float, size: int = 8
) -> tuple[bytes, set[int], float]:
    """Bytes a receiver at (baud, parity, data bits) completes between start and end; where to resume.
    It checks one stop bit, as UARTs do."""
    bit = 1 / baud
    out = bytearray()
    errors: set[int] = set()
    t = start
    while True:
        edge = wire.next_fall(t)
        stop_at = edge + (size + 2.5 if parity != "N" else size + 1.5) * bit
        if stop_at > end:
            return bytes(out), errors, edge
        if wire.level(edge + bit / 2) != 0:  # a glitch, not a start bit
            t = edge + bit / 2
            continue
        byte = sum(wire.level(edge + (1.5 + i) * bit) << i for i in range(size))
        bad = False
        if parity != "N":
            bad = wire.level(edge + (size + 1.5) * bit) != parity_bit(byte, parity)
        bad = bad or wire.level(stop_at) == 0
        if bad:
            errors.add(len(out))
        out.append(byte)
        t = stop_at


def traffic(transactions: int, seed: int) -> list[tuple[bytes, float]]:
    """FC3 polls of slaves 1 and 2 with their responses: 3 ms turnaround, 10 ms between polls."""
    rng = random.Random(seed)
    frames = []
    for index in range(transactions):
        slave, start, quantity = 1 + index % 2, rng.randrange(0x2000), rng.randint(1, 10)
        values = [rng.choice([0xFFFF, 0x00FF, rng.randrange(0x10000)]) for _ in range(quantity)]
        frames.append((with_crc(struct.pack(">BBHH", slave, 3, start, quantity)), 0.003))
        frames.append(
            (with_crc(bytes([slave, 3, 2 * quantity]) + struct.pack(f">{quantity}H", *values)), 0.010)
        )
    return frames


def ascii_traffic(transactions: int, seed: int) -> list[tuple[bytes, float]]:
    """traffic() in Modbus ASCII: ':', the hex pairs of slave, PDU and LRC, CR LF (MODBUS over Serial
    Line V1.02, 2.5.2); the gaps are the same."""
    frames = []
    for frame, gap in traffic(transactions, seed):
        adu = frame[:-2]
        frames.append((b":" + (adu + bytes([(-sum(adu)) & 0xFF])).hex().upper().encode() + b"\r\n", gap))
    return frames


@dataclass
class SimListener:
    """detect.Listener over one pass of the wire, with the receiver's error flags (marked)."""

    wire: Wire

    def listen(self, setting: Setting, seconds: float) -> Heard:
        data, errors, _ = receive(self.wire, setting.baud, setting.parity, 0.0,
                                  min(seconds, self.wire.duration), setting.bytesize)
        return Heard(data, frozenset(errors), marked=True)


class SimSerial(serial.SerialBase):
    """A pyserial port (URL uartsim://) hearing `WIRE` in real time at whatever it is set to.

    Like a socket:// port, it cannot report parity errors. Writing to it fails the test.
    """

    WIRE: Wire | None = None

    def open(self) -> None:
        self._t0 = time.monotonic()
        self._buffer = bytearray()
        self._resume = 0.0
        self.is_open = True

    def _now(self) -> float:
        return time.monotonic() - self._t0

    def _reconfigure_port(self, *args: object) -> None:
        if self.is_open:
            self.reset_input_buffer()  # the receiver starts over at the new setting

    def _pull(self) -> None:
        assert self.WIRE is not None
        parity = {serial.PARITY_NONE: "N", serial.PARITY_EVEN: "E", serial.PARITY_ODD: "O"}[self.parity]
        data, _, self._resume = receive(self.WIRE, self.baudrate, parity, self._resume, self._now(),
                                        self.bytesize)
        self._buffer += data

    @property
    def in_waiting(self) -> int:
        self._pull()
        return len(self._buffer)

    def read(self, size: int = 1) -> bytes:
        if not self._buffer:
            time.sleep(self.timeout or 0.01)
            self._pull()
        data = bytes(self._buffer[:size])
        del self._buffer[:size]
        return data

    def reset_input_buffer(self) -> None:
        self._buffer.clear()
        self._resume = self._now()

    def write(self, data: bytes) -> int:
        raise AssertionError("the sniffer wrote to the bus")

    def close(self) -> None:
        self.is_open = False


SPEEDS = {getattr(termios, f"B{baud}"): baud for baud in BAUDS + (19200,)}


class TtyFeeder(threading.Thread):
    """Writes into a pty what a UART at the sniffer's current baud rate would hear of `wire`.

    The speed is read from the terminal itself (termios on the master side reports the slave's), so
    the sniffer's own reconfiguration drives what it hears. A pty drops PARENB and CSIZE, so the feeder
    cannot see the parity nor the data bits: it hears as `receiver` (parity, data bits) says, 8N1 by
    default; nor can it mark errors (the kernel would escape them).
    """

    def __init__(self, master: int, wire: Wire, receiver: tuple[str, int] = ("N", 8)) -> None:
        super().__init__(daemon=True)
        self.master, self.wire, self.receiver = master, wire, receiver
        self.stop = threading.Event()

    def run(self) -> None:
        start = time.monotonic()
        resume, speed = 0.0, None
        parity, size = self.receiver
        while not self.stop.wait(0.005):
            now = time.monotonic() - start
            current = SPEEDS.get(termios.tcgetattr(self.master)[4])
            if current != speed:
                speed, resume = current, now  # the receiver starts over at a new setting
            if speed is None:
                continue
            data, _, resume = receive(self.wire, speed, parity, resume, now, size)
            if data:
                os.write(self.master, data)
