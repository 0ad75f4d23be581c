"""A deterministic Modbus serial bus: a master, simulated slaves, and the bytes a tap would record.

Used to make the sample captures in captures/ (`python3 -m dissector.sim.simulate --out captures/`) and
large sessions for benchmarks (`generate_session`). Frames are built with the dissector's own grammars
(dissector.protocol.grammar.build_pdu) and checks (dissector.protocol.crc), by devices that follow the manuals' semantics
(dissector.sim.devices), so a capture is what those devices would put on the wire.

Timing is simulated at 19200 baud: a frame lasts bytes x bits-per-character / baud (11 bits in RTU:
start, 8 data, parity, stop; 10 in ASCII: start, 7 data, parity, stop), the master leaves a random idle
gap of at least 3.5 characters before each request, and a slave answers after a random turnaround.
Each frame is recorded with the time its first byte went on the wire. Time is kept in integer
microseconds from a fixed epoch and every random draw comes from one seeded generator, so the output
is reproducible byte for byte.
"""
from __future__ import annotations

import argparse
import errno
import functools
import os
import random
import sys
from collections.abc import Callable
from pathlib import Path

from dissector.protocol.crc import lrc, with_crc
from dissector.model import Kind
from dissector.render.pcapwriter import PcapWriter
from dissector.sim.devices import Atv71, Device, Sel749m, pdu_of

BAUD = 19200
EPOCH_US = 1_767_225_600 * 1_000_000  # 2026-01-01 00:00:00 UTC, fixed for reproducible captures
MASTER_GAP_MS = (4.0, 12.0)  # idle time before a request (t3.5 at 19200 baud is 2.0 ms)
TURNAROUND_MS = (3.0, 9.0)  # slave processing time before its answer
TIMEOUT_MS = 200.0  # master response timeout

Record = tuple[bytes, float]


def encode_rtu(slave: int, pdu: bytes) -> bytes:
    return with_crc(bytes([slave]) + pdu)


def encode_ascii(slave: int, pdu: bytes) -> bytes:
    """Modbus ASCII: ':' then address, PDU and LRC as upper-case hex pairs, then CR LF."""
    binary = bytes([slave]) + pdu
    return b":" + (binary + bytes([lrc(binary)])).hex().upper().encode("ascii") + b"\r\n"


class Bus:
    """One master and its slaves on a serial line; `records` is what a passive tap saw."""

    def __init__(self, devices: list[Device], seed: int, mode: str = "rtu", baud: int = BAUD) -> None:
        self.devices = {device.slave: device for device in devices}
        self.mode = mode
        self.baud = baud
        self.char_bits = 11 if mode == "rtu" else 10
        self.encode = encode_rtu if mode == "rtu" else encode_ascii
        self.rng = random.Random(seed)
        self.now_us = EPOCH_US
        self.records: list[Record] = []

    @property
    def now(self) -> float:
        return self.now_us / 1_000_000

    def _draw_us(self, bounds_ms: tuple[float, float]) -> int:
        low, high = bounds_ms
        return int((low + (high - low) * self.rng.random()) * 1000)

    def put(self, data: bytes) -> None:
        """Record bytes on the wire at the current time; the line is busy while they are sent."""
        self.records.append((data, self.now))
        self.now_us += len(data) * self.char_bits * 1_000_000 // self.baud

    def idle_ms(self, milliseconds: float) -> None:
        self.now_us += int(milliseconds * 1000)

    def idle_until(self, time_us: int) -> None:
        self.now_us = max(self.now_us, time_us)

    def garbage(self, data: bytes) -> None:
        """Line noise (a connector plugged in, a drive switching nearby): bytes that are no frame."""
        self.now_us += self._draw_us(MASTER_GAP_MS)
        self.put(data)

    def request(
        self,
        slave: int,
        pdu: bytes,
        damage_request: int | None = None,
        damage_response: int | None = None,
    ) -> bytes | None:
        """One transaction. `damage_*` flips bits of the byte at that index of the ADU on the wire."""
        self.now_us += self._draw_us(MASTER_GAP_MS)
        adu = self.encode(slave, pdu)
        if damage_request is not None:
            adu = _damaged(adu, damage_request)
        self.put(adu)
        if slave == 0:
            for device in self.devices.values():
                device.handle(pdu, self.now)
            return None
        device = self.devices.get(slave)
        # A slave ignores a frame whose check fails (SEL-749M manual: "the message is ignored").
        if device is None or damage_request is not None:
            self.idle_ms(TIMEOUT_MS)
            return None
        self.now_us += self._draw_us(TURNAROUND_MS)
        response = device.handle(pdu, self.now)
        if response is None:
            self.idle_ms(TIMEOUT_MS)
            return None
        answer = self.encode(slave, response)
        if damage_response is not None:
            answer = _damaged(answer, damage_response)
        self.put(answer)
        return response

    # -- master helpers ----------------------------------------------------------------------
    def read(self, slave: int, start: int, quantity: int, function: int = 3, **damage: int) -> bytes | None:
        return self.request(slave, pdu_of(function, Kind.REQUEST, start=start, quantity=quantity), **damage)

    def write(self, slave: int, address: int, value: int) -> bytes | None:
        return self.request(slave, pdu_of(6, Kind.REQUEST, address=address, value=value))

    def write_multiple(
        self, slave: int, start: int, values: list[int], quantity: int | None = None
    ) -> bytes | None:
        """FC16; a `quantity` other than len(values) makes the byte count disagree with it."""
        count = len(values) if quantity is None else quantity
        pdu = pdu_of(16, Kind.REQUEST, start=start, quantity=count, byte_count=2 * len(values), values=values)
        return self.request(slave, pdu)

    def read_write(
        self, slave: int, read: tuple[int, int], write_start: int, values: list[int]
    ) -> bytes | None:
        pdu = pdu_of(
            23,
            Kind.REQUEST,
            read_start=read[0],
            read_quantity=read[1],
            write_start=write_start,
            write_quantity=len(values),
            byte_count=2 * len(values),
            values=values,
        )
        return self.request(slave, pdu)

    def identify(self, slave: int) -> bytes | None:
        body = {"read_code": 1, "object_id": 0}  # basic identification from object 0
        return self.request(slave, pdu_of(43, Kind.REQUEST, mei_type=14, body=body))


def _damaged(adu: bytes, index: int) -> bytes:
    return adu[:index] + bytes([adu[index] ^ 0x24]) + adu[index + 1 :]


# -- the sample sessions -------------------------------------------------------------------------


def session_p38() -> list[Record]:
    """Seed 000 (manual p.38): the same 3-word read of 8400..8402, as CHCF then COP get protected."""
    drive = Atv71(12)
    bus = Bus([drive], seed=38)
    for protect in ((), ("CHCF",), ("COP",)):
        drive.protect(*protect)  # from the keypad: invisible on the bus
        for _ in range(2):
            bus.read(12, 8400, 3)
            bus.idle_ms(500)
    return bus.records


def _scan(bus: Bus, drive: Atv71, cycles: int, cmd: int, lfr: int, period_us: int = 50_000) -> None:
    """The I/O scanner: FC23 writes CMD, LFR and reads ETA, RFR, once a period."""
    for _ in range(cycles):
        start = bus.now_us
        bus.read_write(drive.slave, (drive.address("ETA"), 2), drive.address("CMD"), [cmd, lfr])
        bus.idle_until(start + period_us)


def session_commissioning() -> list[Record]:
    """ATV71 commissioning: identification, channel setup, DRIVECOM start, a write refused while running."""
    drive = Atv71(2)
    bus = Bus([drive], seed=71)
    bus.identify(2)  # seed 001: Telemecanique / ATV71HU15M3 / 0201 / MACHINE 4
    bus.read(2, drive.address("SFR"), 4)  # the card manual's worked FC3 example
    bus.read(2, drive.address("CHCF"), 2)
    bus.write(2, drive.address("CHCF"), 2)  # separate channels
    bus.write(2, drive.address("FR1"), 164)  # reference from Modbus
    bus.write(2, drive.address("CD1"), 10)  # command from Modbus
    bus.read(2, drive.address("FR1"), 1)
    bus.read(2, drive.address("CD1"), 1)
    bus.write_multiple(2, drive.address("ACC"), [10, 10])  # ACC, DEC = 1.0 s
    _scan(bus, drive, 3, 0x0006, 0)  # shutdown
    _scan(bus, drive, 3, 0x0007, 0)  # switch on
    _scan(bus, drive, 16, 0x000F, 300)  # enable operation at 30.0 Hz
    bus.write(2, drive.address("CHCF"), 3)  # configuration while running: exception 7
    bus.write(2, drive.address("HSP"), 550)  # adjustment while running: accepted
    _scan(bus, drive, 4, 0x000F, 300)
    _scan(bus, drive, 12, 0x0007, 0)  # disable operation: ramp down
    _scan(bus, drive, 2, 0x0006, 0)
    bus.write(2, drive.address("CHCF"), 3)  # stopped now: accepted
    return bus.records


def _sel_currents(relay: Sel749m, cycle: int, rng: random.Random) -> None:
    for offset in range(16):
        relay.values[offset] = 400 + 37 * offset + (cycle * 7 + int(rng.random() * 5)) % 13
    for offset in range(100, 108):
        relay.values[offset] = 250 + 3 * (offset - 100) + cycle % 3


def session_sel749m() -> list[Record]:
    """SEL-749M polling loop with every error of Appendix D's tables."""
    relay = Sel749m(1)
    bus = Bus([relay], seed=749)
    mistakes: dict[int, Callable[[], object]] = {
        2: lambda: bus.read(1, 500, 4),  # illegal register: 2
        4: lambda: bus.read(1, 0, 126),  # illegal number of registers: 3
        5: lambda: bus.write(1, 302, 5),  # illegal value: 3
        6: lambda: bus.write(1, 250, 1),  # illegal write address: 2
        7: lambda: bus.read_write(1, (0, 2), 300, [1]),  # FC23 not supported: 1
        8: lambda: bus.write_multiple(1, 300, [1, 0, 1], quantity=2),  # wrong byte count: 3
        9: lambda: bus.write_multiple(1, 300, [1] * 101),  # illegal number of registers: 3
        10: lambda: bus.write_multiple(1, 400, [1, 1]),  # illegal register to set: 2
    }
    for cycle in range(12):
        _sel_currents(relay, cycle, bus.rng)
        bus.read(1, 0, 16)
        bus.read(1, 100, 8, function=4)
        if cycle in mistakes:
            mistakes[cycle]()
        if cycle == 3:
            bus.write(1, 300, 1)
        if cycle == 11:
            bus.write_multiple(1, 300, [0, 1])
        bus.idle_ms(250)
    return bus.records


def session_noisy() -> list[Record]:
    """Two drives and a relay, garbage on the line, a damaged response, a slave that never answers."""
    drive = Atv71(12)
    relay = Sel749m(1)
    bus = Bus([drive, relay], seed=13)
    bus.garbage(bytes([0x00, 0xFF, 0xFF, 0xF0]))  # power-up glitch before the first poll
    for cycle in range(8):
        _sel_currents(relay, cycle, bus.rng)
        bus.read(12, drive.address("ETA"), 2)
        bus.read(1, 0, 4, **({"damage_response": 5} if cycle == 3 else {}))
        if cycle == 3:
            bus.read(1, 0, 4)  # the master retries after the bad CRC
        if cycle == 5:
            bus.read(5, 0, 2)  # slave 5 is switched off: timeout, then one retry
            bus.read(5, 0, 2)
        if cycle == 6:
            bus.garbage(bytes([0xFE, 0xE0, 0x3C, 0xFF, 0x1F]))
        bus.idle_ms(100)
    return bus.records


def session_ascii() -> list[Record]:
    """Modbus ASCII with the card's own examples (FC3 3102..3105, FC6 9001 = 10) and an exception."""
    drive = Atv71(2)
    bus = Bus([drive], seed=7, mode="ascii")
    bus.read(2, drive.address("SFR"), 4)
    bus.write(2, drive.address("ACC"), 10)  # the reference frame :02062329000AA2
    bus.read(2, drive.address("ACC"), 2)
    bus.read(2, 8400, 1)  # non-existent only: exception 2
    bus.identify(2)
    return bus.records


SESSIONS: dict[str, Callable[[], list[Record]]] = {
    "p38_protection": session_p38,
    "atv71_commissioning": session_commissioning,
    "sel749m_polling": session_sel749m,
    "noisy_bus": session_noisy,
    "ascii_session": session_ascii,
}


# -- large sessions for benchmarks --------------------------------------------------------------


@functools.lru_cache(maxsize=8)
def _transaction_pool(seed: int) -> tuple[tuple[bytes, bytes | None, int], ...]:
    """A few hundred real transactions (request ADU, response ADU or None, turnaround in us)."""
    drives = [Atv71(2), Atv71(12)]
    relay = Sel749m(1)
    bus = Bus([*drives, relay], seed=seed)
    pool: list[tuple[bytes, bytes | None, int]] = []

    def transact(action: Callable[[], object]) -> None:
        before = len(bus.records)
        action()
        frames = bus.records[before:]
        request = frames[0][0]
        if len(frames) > 1:
            turnaround = int(round((frames[1][1] - frames[0][1]) * 1_000_000))
            pool.append((request, frames[1][0], turnaround))
        else:
            pool.append((request, None, int(TIMEOUT_MS * 1000)))

    for cycle in range(64):
        for drive in drives:
            lfr = (cycle * 37) % 500
            transact(
                lambda d=drive, f=lfr: bus.read_write(
                    d.slave, (d.address("ETA"), 2), d.address("CMD"), [0x000F, f]
                )
            )
        _sel_currents(relay, cycle, bus.rng)
        transact(lambda: bus.read(1, 0, 16))
        if cycle % 8 == 3:
            transact(lambda: bus.read(12, 8400, 1))  # exception 2
        if cycle % 16 == 5:
            transact(lambda: bus.read(9, 0, 2))  # absent slave: unanswered
        if cycle % 16 == 9:
            transact(lambda c=cycle: bus.write(2, drives[0].address("HSP"), 500 + c))
    return tuple(pool)


def generate_session(n_transactions: int, seed: int = 0) -> list[Record]:
    """`n_transactions` request/response exchanges (about two frames each) as (bytes, time) records.

    Transactions are drawn from a cached pool of frames built once per seed, so 100,000 transactions
    (200,000 frames) take well under a second; timing follows the same rules as the sample sessions.
    """
    pool = _transaction_pool(seed)
    rng = random.Random(seed)
    draw = rng.random
    size = len(pool)
    char_us = 11 * 1_000_000 / BAUD
    gap_low, gap_span = MASTER_GAP_MS[0] * 1000, (MASTER_GAP_MS[1] - MASTER_GAP_MS[0]) * 1000
    timeout_us = TIMEOUT_MS * 1000
    now = float(EPOCH_US)
    out: list[Record] = []
    append = out.append
    for _ in range(n_transactions):
        request, response, turnaround = pool[int(draw() * size)]
        now += gap_low + gap_span * draw()
        append((request, int(now) / 1_000_000))
        if response is None:
            now += len(request) * char_us + timeout_us
            continue
        now += turnaround
        append((response, int(now) / 1_000_000))
        now += len(response) * char_us
    return out


# -- output -------------------------------------------------------------------------------------


def write_capture(records: list[Record], base: Path) -> tuple[Path, Path]:
    """`base`.bin (the raw byte stream) and `base`.pcap (linktype 147, one frame a record)."""
    bin_path, pcap_path = base.with_suffix(".bin"), base.with_suffix(".pcap")
    bin_path.write_bytes(b"".join(data for data, _time in records))
    with pcap_path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for data, time in records:
            writer.write(data, time)
    return bin_path, pcap_path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python3 -m dissector.sim.simulate", description="Write simulated Modbus serial captures."
    )
    parser.add_argument("--out", type=Path, default=Path("captures"), help="output directory")
    parser.add_argument("--session", action="append", choices=sorted(SESSIONS), help="only these sessions")
    parser.add_argument(
        "--transactions", type=int, help="write a benchmark session of N transactions instead"
    )
    parser.add_argument("--seed", type=int, default=0, help="seed of the benchmark session")
    args = parser.parse_args(argv)
    if args.transactions is not None and args.transactions < 0:
        parser.error("--transactions must be 0 or more")
    try:
        return _write(args)
    except OSError as error:  # (an output that cannot be written: one line and status 1, as vw3-decode's)
        where = error.filename if error.filename is not None else args.out
        print(f"{parser.prog}: cannot write {where}: {error.strerror or error}", file=sys.stderr)
        return 1


def _write(args: argparse.Namespace) -> int:
    """Write the sessions (or the benchmark session) `args` asks for."""
    if args.out.exists() and not args.out.is_dir():
        raise NotADirectoryError(errno.ENOTDIR, os.strerror(errno.ENOTDIR), str(args.out))
    args.out.mkdir(parents=True, exist_ok=True)
    if args.transactions is not None:
        records = generate_session(args.transactions, args.seed)
        paths = write_capture(records, args.out / f"bench-{args.transactions}-{args.seed}")
        print(f"{paths[0]}: {len(records)} frames", file=sys.stderr)
        return 0
    for name in args.session or list(SESSIONS):
        records = SESSIONS[name]()
        paths = write_capture(records, args.out / name)
        print(f"{paths[0]} and {paths[1].name}: {len(records)} records", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
