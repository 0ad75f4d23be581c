"""Benchmark traffic mixes beyond the polling loop of `simulate.generate_session`.

- `plant_mix`: a plant floor. Four ATV71 drives I/O-scanned with FC23 and read for monitoring words,
  two SEL-749M relays polled for 40-register blocks (FC3 and FC4), a coil/input module (FC1, FC2, FC5,
  FC15) and an energy meter (FC4); values change from cycle to cycle and about 1 % of the transactions
  end in an exception, each the one its device would answer.
- `max_size_mix`: every public function code at random quantities up to the spec's limits (2000
  coils, 125 registers, 1968/123 written, FC23 125/121, 31 FIFO words), random slaves.

Drives and relays are the simulator's own devices (dissector.sim.devices); the module, the meter and
the max-size slaves are built here after the Modbus spec. Both mixes are reproducible from their seed
and return (bytes, time) records, timed like `simulate.generate_session`.
"""
from __future__ import annotations

import random
import struct
from collections.abc import Callable, Iterator

from dissector.model import Kind
from dissector.protocol.crc import with_crc
from dissector.protocol.spec import SPEC
from dissector.sim.devices import Atv71, Device, Response, Sel749m, exception_pdu, pdu_of, registers_pdu
from dissector.sim.simulate import BAUD, EPOCH_US, MASTER_GAP_MS, TIMEOUT_MS, TURNAROUND_MS, Bus, Record

Transaction = tuple[bytes, bytes | None]  # request PDU and response PDU (None: no answer)


def _pack_bits(bits: list[int]) -> bytes:
    packed = bytearray((len(bits) + 7) // 8)
    for index, bit in enumerate(bits):
        if bit:
            packed[index >> 3] |= 1 << (index & 7)
    return bytes(packed)


class IoModule(Device):
    """A coil/input module: 256 coils (FC1, FC5, FC15) and 256 discrete inputs (FC2)."""

    SIZE = 256

    def __init__(self, slave: int) -> None:
        self.slave = slave
        self.coils = [0] * self.SIZE
        self.inputs = [0] * self.SIZE

    def handle(self, pdu: bytes, now: float) -> Response:
        function = pdu[0]
        if function in (1, 2):
            start, quantity = struct.unpack_from(">HH", pdu, 1)
            if not 1 <= quantity <= 2000:
                return exception_pdu(function, 3)
            if start + quantity > self.SIZE:
                return exception_pdu(function, 2)
            table = self.coils if function == 1 else self.inputs
            packed = _pack_bits(table[start : start + quantity])
            return bytes([function, len(packed)]) + packed
        if function == 5:
            address, value = struct.unpack_from(">HH", pdu, 1)
            if address >= self.SIZE:
                return exception_pdu(function, 2)
            self.coils[address] = 1 if value == 0xFF00 else 0
            return pdu
        if function == 15:
            start, quantity, count = struct.unpack_from(">HHB", pdu, 1)
            if start + quantity > self.SIZE:
                return exception_pdu(function, 2)
            for index in range(quantity):
                self.coils[start + index] = pdu[6 + (index >> 3)] >> (index & 7) & 1
            return pdu[:5]
        return exception_pdu(function, 1)


class EnergyMeter(Device):
    """An energy meter: 64 input registers (FC4) of 32-bit floats, high word first; FC4 only."""

    def __init__(self, slave: int) -> None:
        self.slave = slave
        self.registers = [0] * 64

    def set_readings(self, readings: list[float]) -> None:
        for index, reading in enumerate(readings[:32]):
            high, low = struct.unpack(">HH", struct.pack(">f", reading))
            self.registers[2 * index : 2 * index + 2] = [high, low]

    def handle(self, pdu: bytes, now: float) -> Response:
        function = pdu[0]
        if function != 4:
            return exception_pdu(function, 1)
        start, quantity = struct.unpack_from(">HH", pdu, 1)
        if not 1 <= quantity <= 125:
            return exception_pdu(function, 3)
        if start + quantity > len(self.registers):
            return exception_pdu(function, 2)
        return registers_pdu(function, self.registers[start : start + quantity])


DRIVES = (2, 3, 4, 5)
RELAYS = (1, 7)
MODULE = 20
METER = 30

# The profiles a user of this bus would give vw3-decode (drives keep the default, atv71).
PLANT_PROFILES = [f"{slave}=sel749m" for slave in RELAYS] + [f"{MODULE}=generic", f"{METER}=generic"]


def plant_mix(frames: int, seed: int = 1) -> list[Record]:
    """About `frames` frames of the plant floor described in the module docstring."""
    rng = random.Random(seed)
    drives = [Atv71(slave) for slave in DRIVES]
    relays = [Sel749m(slave) for slave in RELAYS]
    module, meter = IoModule(MODULE), EnergyMeter(METER)
    bus = Bus([*drives, *relays, module, meter], seed=seed)
    for drive in drives:
        drive.values[drive.address("ACC")] = 1  # short ramps: RFR follows LFR within a cycle
        drive.values[drive.address("DEC")] = 1
    energy = [1000.0 * (index + 1) for index in range(32)]
    cycle = 0
    while len(bus.records) < frames:
        # Values that change: relay currents, meter readings, module inputs, drive references.
        for number, relay in enumerate(relays):
            for offset in range(40):
                relay.values[offset] = 300 + 11 * offset + number + int(rng.random() * 40)
            for offset in range(100, 140):
                relay.values[offset] = 200 + (offset + cycle * 3 + int(rng.random() * 9)) % 97
        energy = [value + rng.random() * 2.5 for value in energy]
        meter.set_readings(energy)
        for _ in range(4):
            module.inputs[int(rng.random() * IoModule.SIZE)] ^= 1
        for number, drive in enumerate(drives):
            lfr = (cycle * 13 + number * 97) % 500
            bus.read_write(drive.slave, (drive.address("ETA"), 2), drive.address("CMD"), [0x000F, lfr])
            if cycle % 4 == number:
                bus.read(drive.slave, 3201, 9)  # monitoring words
        for relay in relays:
            bus.read(relay.slave, 0, 40)
            bus.read(relay.slave, 100, 40, function=4)
        bus.read(MODULE, 0, 64, function=2)
        bus.read(MODULE, 0, 32, function=1)
        if cycle % 3 == 0:
            bus.request(MODULE, pdu_of(5, Kind.REQUEST, address=cycle % 32, value=0xFF00 * (cycle % 2)))
        if cycle % 5 == 0:
            states = [int(rng.random() * 2) for _ in range(16)]
            pdu = pdu_of(15, Kind.REQUEST, start=32, quantity=16, byte_count=2, status=_pack_bits(states))
            bus.request(MODULE, pdu)
        bus.read(METER, 0, 40, function=4)
        # About 1 % of the transactions (16 a cycle) are mistakes their device refuses.
        if rng.random() < 0.16:
            _plant_mistake(bus, drives, rng)
        cycle += 1
    return bus.records[:frames]


def _plant_mistake(bus: Bus, drives: list[Atv71], rng: random.Random) -> None:
    drive = drives[int(rng.random() * len(drives))]
    mistakes: list[Callable[[], object]] = [
        lambda: bus.write(drive.slave, drive.address("CHCF"), 2),  # configuration while running: 7
        lambda: bus.read(RELAYS[0], 500, 4),  # illegal register: 2
        lambda: bus.read(MODULE, 250, 16, function=1),  # past the module's coils: 2
        lambda: bus.read(METER, 0, 8, function=3),  # the meter has no holding registers: 1
    ]
    mistakes[int(rng.random() * len(mistakes))]()


# -- every public function code at random sizes -----------------------------------------------


def _words(rng: random.Random, count: int) -> list[int]:
    return [int(rng.random() * 0x10000) for _ in range(count)]


def _random_bytes(rng: random.Random, count: int) -> bytes:
    return bytes(int(rng.random() * 256) for _ in range(count))


def _read_bits(rng: random.Random, function: int) -> Transaction:
    quantity = 1 + int(rng.random() * 2000)
    start = int(rng.random() * (0x10000 - quantity))
    packed = bytearray(_random_bytes(rng, (quantity + 7) // 8))
    if quantity % 8:
        packed[-1] &= (1 << (quantity % 8)) - 1  # unused high bits are zero (spec)
    return struct.pack(">BHH", function, start, quantity), bytes([function, len(packed)]) + packed


def _read_registers(rng: random.Random, function: int) -> Transaction:
    quantity = 1 + int(rng.random() * 125)
    start = int(rng.random() * (0x10000 - quantity))
    return struct.pack(">BHH", function, start, quantity), registers_pdu(function, _words(rng, quantity))


def _write_single(rng: random.Random, function: int) -> Transaction:
    value = 0xFF00 * int(rng.random() * 2) if function == 5 else int(rng.random() * 0x10000)
    pdu = struct.pack(">BHH", function, int(rng.random() * 0x10000), value)
    return pdu, pdu


def _write_coils(rng: random.Random, function: int) -> Transaction:
    quantity = 1 + int(rng.random() * 1968)
    start = int(rng.random() * (0x10000 - quantity))
    packed = bytearray(_random_bytes(rng, (quantity + 7) // 8))
    if quantity % 8:
        packed[-1] &= (1 << (quantity % 8)) - 1
    head = struct.pack(">BHHB", function, start, quantity, len(packed))
    return head + packed, head[:5]


def _write_registers(rng: random.Random, function: int) -> Transaction:
    quantity = 1 + int(rng.random() * 123)
    start = int(rng.random() * (0x10000 - quantity))
    head = struct.pack(">BHHB", function, start, quantity, 2 * quantity)
    return head + struct.pack(f">{quantity}H", *_words(rng, quantity)), head[:5]


def _read_write(rng: random.Random, function: int) -> Transaction:
    reads, writes = 1 + int(rng.random() * 125), 1 + int(rng.random() * 121)
    read_start = int(rng.random() * (0x10000 - reads))
    write_start = int(rng.random() * (0x10000 - writes))
    request = struct.pack(">BHHHHB", function, read_start, reads, write_start, writes, 2 * writes)
    request += struct.pack(f">{writes}H", *_words(rng, writes))
    return request, registers_pdu(function, _words(rng, reads))


def _no_data(rng: random.Random, function: int) -> Transaction:
    request = bytes([function])
    if function == 7:
        return request, bytes([function, int(rng.random() * 256)])
    if function == 11:
        return request, struct.pack(">BHH", function, 0xFFFF * int(rng.random() * 2), int(rng.random() * 0x10000))
    if function == 12:
        events = _random_bytes(rng, int(rng.random() * 65))
        counters = struct.pack(">HHH", 0, int(rng.random() * 0x10000), int(rng.random() * 0x10000))
        return request, bytes([function, 6 + len(events)]) + counters + events
    # 17, Report Server ID: server id, run indicator, then device-specific text.
    text = b"VW3 bench slave " + str(int(rng.random() * 1000)).encode()
    data = bytes([int(rng.random() * 256), 0xFF * int(rng.random() * 2)]) + text
    return request, bytes([function, len(data)]) + data


def _diagnostics(rng: random.Random, function: int) -> Transaction:
    pdu = struct.pack(">BH", function, 0) + _random_bytes(rng, 2 * int(rng.random() * 60))
    return pdu, pdu  # Return Query Data echoes the request


def _file_records(rng: random.Random, function: int) -> Transaction:
    count = 1 + int(rng.random() * 5)
    if function == 20:
        lengths = [1 + int(rng.random() * 24) for _ in range(count)]
        subrequests = b"".join(
            struct.pack(">BHHH", 6, 1 + int(rng.random() * 9), int(rng.random() * 10000), length)
            for length in lengths
        )
        subresponses = b"".join(
            struct.pack(f">BB{length}H", 1 + 2 * length, 6, *_words(rng, length)) for length in lengths
        )
        return (
            bytes([function, len(subrequests)]) + subrequests,
            bytes([function, len(subresponses)]) + subresponses,
        )
    records = b""
    for _ in range(count):
        length = 1 + int(rng.random() * 20)
        records += struct.pack(f">BHHH{length}H", 6, 1 + int(rng.random() * 9), int(rng.random() * 10000),
                               length, *_words(rng, length))
    pdu = bytes([function, len(records)]) + records
    return pdu, pdu  # the response echoes the request


def _mask_write(rng: random.Random, function: int) -> Transaction:
    pdu = struct.pack(">BHHH", function, *_words(rng, 3))
    return pdu, pdu


def _fifo(rng: random.Random, function: int) -> Transaction:
    count = int(rng.random() * 32)
    response = struct.pack(f">BHH{count}H", function, 2 + 2 * count, count, *_words(rng, count))
    return struct.pack(">BH", function, int(rng.random() * 0x10000)), response


def _identification(rng: random.Random, function: int) -> Transaction:
    texts = [b"Bench Vendor", b"BV-" + str(int(rng.random() * 10000)).encode(), b"1.0"]
    objects = b"".join(bytes([index, len(text)]) + text for index, text in enumerate(texts))
    response = bytes([function, 14, 1, 0x81, 0, 0, len(texts)]) + objects
    return bytes([function, 14, 1, 0]), response


_MAKERS: dict[int, Callable[[random.Random, int], Transaction]] = {
    1: _read_bits, 2: _read_bits, 3: _read_registers, 4: _read_registers, 5: _write_single,
    6: _write_single, 7: _no_data, 8: _diagnostics, 11: _no_data, 12: _no_data, 15: _write_coils,
    16: _write_registers, 17: _no_data, 20: _file_records, 21: _file_records, 22: _mask_write,
    23: _read_write, 24: _fifo, 43: _identification,
}
assert sorted(_MAKERS) == sorted(SPEC.functions), "every public function code has a maker"


def _max_size_transactions(rng: random.Random) -> Iterator[Transaction]:
    functions = sorted(_MAKERS)
    while True:
        function = functions[int(rng.random() * len(functions))]
        request, response = _MAKERS[function](rng, function)
        if rng.random() < 0.01:
            response = exception_pdu(function, 1 + int(rng.random() * 4))
        yield request, response


def max_size_mix(frames: int, seed: int = 1, pool_size: int = 4000) -> list[Record]:
    """About `frames` frames: transactions of every public code drawn from a pool of `pool_size`."""
    rng = random.Random(seed)
    maker = _max_size_transactions(rng)
    pool = [(1 + int(rng.random() * 247), *next(maker)) for _ in range(pool_size)]
    return _timed(pool, frames, rng)


def _timed(pool: list[tuple[int, bytes, bytes | None]], frames: int, rng: random.Random) -> list[Record]:
    """Records of transactions drawn from `pool`, timed like simulate.generate_session."""
    char_us = 11 * 1_000_000 / BAUD
    draw = rng.random
    now = float(EPOCH_US)
    out: list[Record] = []
    adus = [(with_crc(bytes([slave]) + request), response and with_crc(bytes([slave]) + response))
            for slave, request, response in pool]
    while len(out) < frames:
        request, response = adus[int(draw() * len(adus))]
        now += MASTER_GAP_MS[0] * 1000 + (MASTER_GAP_MS[1] - MASTER_GAP_MS[0]) * 1000 * draw()
        out.append((request, int(now) / 1_000_000))
        now += len(request) * char_us
        if response is None:
            now += TIMEOUT_MS * 1000
            continue
        now += TURNAROUND_MS[0] * 1000 + (TURNAROUND_MS[1] - TURNAROUND_MS[0]) * 1000 * draw()
        out.append((response, int(now) / 1_000_000))
        now += len(response) * char_us
    return out[:frames]
