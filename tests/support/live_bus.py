"""A Modbus RTU bus made of pseudo-terminals, for live-capture tests without hardware.

    master ── pty A ──┐                ┌── pty B ── slave (answers FC3/FC6/FC16 from a register dict)
                      └──── relay ─────┘
                              └──────────── pty C ── the sniffer (a subprocess reading C's device)

The relay copies each direction to the other side and to C, paced at the simulated baud rate
(11 bits a byte) and cut into 1 to 3 writes at random, so the sniffer sees bytes arrive as a USB
adapter delivers them: in pieces. It logs when each byte reached C, for latency figures. The slave
records every frame it received and sent, in bus order: that is what the sniffer must report.
"""
from __future__ import annotations

import errno
import fcntl
import os
import random
import select
import signal
import struct
import subprocess
import sys
import threading
import time
import tty
from dataclasses import dataclass, field
from pathlib import Path

from dissector.protocol.crc import with_crc

ROOT = Path(__file__).resolve().parents[2]


def open_pty() -> tuple[int, int, str]:
    master, slave = os.openpty()
    # Raw before anyone opens it: bytes written early must not be echoed or translated.
    tty.setraw(slave)
    return master, slave, os.ttyname(slave)


class Relay(threading.Thread):
    def __init__(self, a: int, b: int, c: int, baud: int, seed: int) -> None:
        super().__init__(daemon=True)
        self.a, self.b, self.c = a, b, c
        self.byte_time = 11 / baud
        self.random = random.Random(seed)
        self.stop = threading.Event()
        self.c_open = True
        self.lock = threading.Lock()
        self.c_bytes = 0
        self.c_log: list[tuple[int, float]] = []  # (bytes written to C so far, time.time() before)
        self.c_data = bytearray()
        self.dropped = 0
        fcntl.fcntl(c, fcntl.F_SETFL, fcntl.fcntl(c, fcntl.F_GETFL) | os.O_NONBLOCK)

    def close_c(self) -> None:
        """Close the sniffer's far end, as an unplugged adapter would vanish."""
        with self.lock:
            self.c_open = False
            os.close(self.c)

    def run(self) -> None:
        while not self.stop.is_set():
            ready, _, _ = select.select([self.a, self.b], [], [], 0.02)
            for source in ready:
                try:
                    data = os.read(source, 4096)
                except OSError:
                    continue
                self._forward(data, self.b if source == self.a else self.a)

    def _forward(self, data: bytes, destination: int) -> None:
        cuts = sorted(self.random.sample(range(1, len(data)), min(self.random.randint(0, 2), len(data) - 1)))
        for start, end in zip([0, *cuts], [*cuts, len(data)]):
            piece = data[start:end]
            deadline = time.perf_counter() + len(piece) * self.byte_time
            while time.perf_counter() < deadline:
                pass  # the bytes are on the wire; sleep() is too coarse at 95 us a byte
            with self.lock:
                if self.c_open:
                    try:
                        # Stamped before write(2): the sniffer may print before it returns.
                        stamp = time.time()
                        os.write(self.c, piece)
                        self.c_bytes += len(piece)
                        self.c_data += piece
                        self.c_log.append((self.c_bytes, stamp))
                    except OSError as error:
                        if error.errno != errno.EAGAIN:
                            raise
                        self.dropped += len(piece)
            os.write(destination, piece)

    def time_of_byte(self, offset: int) -> float:
        """When the byte at `offset` (0-based) of C's stream had been written."""
        for count, stamp in self.c_log:
            if count > offset:
                return stamp
        raise KeyError(offset)


class Slave(threading.Thread):
    """Answers every request for slaves 1..247 from one register dict; records the bus in order."""

    def __init__(self, fd: int) -> None:
        super().__init__(daemon=True)
        self.fd = fd
        self.registers: dict[int, int] = {}
        self.frames: list[bytes] = []
        self.read_values: list[list[int]] = []
        self.stop = threading.Event()
        self.transactions = 0

    def run(self) -> None:
        buf = bytearray()
        while not self.stop.is_set():
            # Generous: a loaded test machine may stall the relay mid-frame for tens of ms.
            ready, _, _ = select.select([self.fd], [], [], 0.5)
            if not ready:
                buf.clear()  # a silence ends any partial frame
                continue
            buf += os.read(self.fd, 4096)
            while len(buf) >= 8:
                function = buf[1]
                length = 9 + buf[6] if function == 16 else 8
                if len(buf) < length:
                    break
                request, buf = bytes(buf[:length]), buf[length:]
                self.frames.append(request)
                response = self.answer(request)
                self.frames.append(response)
                os.write(self.fd, response)
                self.transactions += 1

    def answer(self, request: bytes) -> bytes:
        slave, function = request[0], request[1]
        start, value = struct.unpack(">HH", request[2:6])
        if function == 3:
            values = [self.registers.get((start + i) & 0xFFFF, 0) for i in range(value)]
            self.read_values.append(values)
            return with_crc(bytes([slave, 3, 2 * value]) + struct.pack(f">{value}H", *values))
        if function == 6:
            self.registers[start] = value
            return request
        values = struct.unpack(f">{value}H", request[7 : 7 + 2 * value])
        for index, register in enumerate(values):
            self.registers[(start + index) & 0xFFFF] = register
        return with_crc(request[:6])


def our_master(fd: int, count: int, seed: int, stop: threading.Event | None = None) -> None:
    """FC3/FC6/FC16 requests from our own encoding, each waiting for its response."""
    rng = random.Random(seed)
    for _ in range(count):
        if stop is not None and stop.is_set():
            return
        slave, function = rng.randint(1, 3), rng.choice([3, 6, 16])
        start, quantity = rng.randrange(0, 200), rng.randint(1, 20)
        if function == 3:
            request, expect = struct.pack(">BBHH", slave, 3, start, quantity), 5 + 2 * quantity
        elif function == 6:
            request, expect = struct.pack(">BBHH", slave, 6, start, rng.randrange(0x10000)), 8
        else:
            values = [rng.randrange(0x10000) for _ in range(quantity)]
            request = struct.pack(f">BBHHB{quantity}H", slave, 16, start, quantity, 2 * quantity, *values)
            expect = 8
        os.write(fd, with_crc(request))
        got = b""
        deadline = time.monotonic() + 2
        while len(got) < expect and time.monotonic() < deadline:
            ready, _, _ = select.select([fd], [], [], 0.05)
            if ready:
                got += os.read(fd, 4096)
        assert len(got) == expect, f"no response to {request.hex()}: {got.hex()}"


@dataclass
class Sniffer:
    """`python3 -m dissector.app.live` on C, its stdout lines stamped as they arrive."""

    process: subprocess.Popen[str]
    lines: list[tuple[float, str]] = field(default_factory=list)
    ready: str = ""

    @classmethod
    def start(cls, path: str, *options: str, env: dict[str, str] | None = None) -> Sniffer:
        """`env`: the sniffer's environment (None: this one's), e.g. with VW3_PURE_PYTHON or VW3_LIVE_TAPE."""
        process = subprocess.Popen(
            [sys.executable, "-m", "dissector", "--live", path, "-n", *options],
            cwd=ROOT,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        sniffer = cls(process)
        assert process.stderr is not None
        sniffer.ready = process.stderr.readline()  # "listening on ...": the port is open
        threading.Thread(target=sniffer._collect, daemon=True).start()
        return sniffer

    def _collect(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            self.lines.append((time.time(), line.rstrip("\n")))

    def interrupt(self) -> tuple[int, str]:
        self.process.send_signal(signal.SIGINT)
        return self.wait()

    def wait(self) -> tuple[int, str]:
        status = self.process.wait(timeout=10)
        assert self.process.stderr is not None
        rest = self.process.stderr.read()
        time.sleep(0.05)  # let the collector drain stdout
        return status, rest

    def wait_lines(self, count: int, timeout: float = 5.0) -> None:
        deadline = time.monotonic() + timeout
        while len(self.lines) < count and time.monotonic() < deadline:
            time.sleep(0.01)


class Bus:
    """With `slave=False`, side B (b_path) is free for another slave (pymodbus_slave)."""

    def __init__(self, baud: int = 115200, seed: int = 1, slave: bool = True) -> None:
        self.a, self.a_slave, self.a_path = open_pty()
        self.b, self.b_slave, self.b_path = open_pty()
        self.c, self.c_slave, self.c_path = open_pty()
        self.relay = Relay(self.a, self.b, self.c, baud, seed)
        self.slave = Slave(self.b_slave)
        self.relay.start()
        if slave:
            self.slave.start()

    def close(self) -> None:
        self.relay.stop.set()
        self.slave.stop.set()
        self.relay.join(2)
        if self.slave.ident is not None:
            self.slave.join(2)
        fds = [self.a, self.a_slave, self.b, self.b_slave, self.c_slave]
        if self.relay.c_open:
            fds.append(self.c)
        for fd in fds:
            try:
                os.close(fd)
            except OSError:
                pass


def read_pcap(path: Path) -> list[tuple[float, bytes]]:
    """Records of a classic pcap; fails on any trailing partial record."""
    data = path.read_bytes()
    magic, major, minor, _zone, _sig, _snap, linktype = struct.unpack_from("<IHHiIII", data)
    assert (magic, major, minor, linktype) == (0xA1B2C3D4, 2, 4, 147)
    records = []
    offset = 24
    while offset < len(data):
        assert len(data) - offset >= 16, "partial record header"
        seconds, micros, length, original = struct.unpack_from("<IIII", data, offset)
        assert length == original and len(data) - offset - 16 >= length, "partial record"
        records.append((seconds + micros / 1e6, data[offset + 16 : offset + 16 + length]))
        offset += 16 + length
    return records


def byte_records(path: Path) -> list[tuple[float, bytes]]:
    """The records of bytes of a live capture stopped cleanly (SIGINT, SIGHUP, --duration, a port gone):
    read_pcap's, after which the file holds its closing record, of no byte, at the stop
    (live_capture.CaptureFiles.close; tests/integration/test_live_capture_end.py checks its time)."""
    records = read_pcap(path)
    assert records and records[-1][1] == b"", "no closing record"
    return records[:-1]


class PymodbusSlave(threading.Thread):
    """pymodbus's RTU server on `path` for `devices` (holding registers 0..299); requests to other
    slaves go unanswered, as on a bus where that slave is absent."""

    def __init__(self, path: str, devices: tuple[int, ...] = (1, 2, 3), baud: int = 115200) -> None:
        super().__init__(daemon=True)
        self.path, self.devices, self.baud = path, devices, baud
        self.ready = threading.Event()
        self._loop: object = None
        self._server: object = None

    def run(self) -> None:
        import asyncio

        from pymodbus.datastore import ModbusDeviceContext, ModbusSequentialDataBlock, ModbusServerContext
        from pymodbus.server import ModbusSerialServer

        context = ModbusServerContext(
            devices={d: ModbusDeviceContext(hr=ModbusSequentialDataBlock(1, [0] * 300)) for d in self.devices},
            single=False,
        )

        async def serve() -> None:
            # pymodbus builds its transport on the running loop.
            self._loop = asyncio.get_running_loop()
            server = ModbusSerialServer(
                context, port=self.path, baudrate=self.baud, parity="N", ignore_missing_devices=True,
                trace_packet=self._absent,
            )
            self._server = server
            self._loop.call_soon(self.ready.set)
            await server.serve_forever()

        try:
            asyncio.run(serve())
        except Exception:  # noqa: BLE001  (stopped by close())
            pass

    def _absent(self, sending: bool, data: bytes) -> bytes:
        # pymodbus 3.16 answers a missing device with an exception despite ignore_missing_devices:
        # what it would send for a slave that is not on the bus is not sent.
        return b"" if sending and data and data[0] not in self.devices else data

    def close(self) -> None:
        import asyncio

        loop, server = self._loop, self._server
        if loop is not None and server is not None:
            future = asyncio.run_coroutine_threadsafe(server.shutdown(), loop)  # type: ignore[arg-type]
            try:
                future.result(5)
            except Exception:  # noqa: BLE001
                pass
        self.join(5)


def paced_writer(fd: int, data: bytes, baud: int, piece: int = 32) -> int:
    """Write `data` to a pty at line rate (11 bits a byte), never blocking: bytes the terminal does
    not take (its reader stopped reading) are counted, as a UART overrun would lose them."""
    flags = fcntl.fcntl(fd, fcntl.F_GETFL)
    fcntl.fcntl(fd, fcntl.F_SETFL, flags | os.O_NONBLOCK)
    lost = 0
    byte_time = 11 / baud
    start = time.perf_counter()
    for offset in range(0, len(data), piece):
        chunk = data[offset : offset + piece]
        due = start + (offset + len(chunk)) * byte_time
        while time.perf_counter() < due:
            time.sleep(min(0.0005, max(0.0, due - time.perf_counter())))
        try:
            written = os.write(fd, chunk)
        except BlockingIOError:
            written = 0
        lost += len(chunk) - written
    fcntl.fcntl(fd, fcntl.F_SETFL, flags)
    return lost


def transactions(count: int, seed: int) -> bytes:
    """A plant-floor-like stream: FC3/FC6/FC16 requests to slaves 1..3, each with its response."""
    rng = random.Random(seed)
    out = bytearray()
    slave = Slave(-1)
    for _ in range(count):
        unit, function = rng.randint(1, 3), rng.choice([3, 3, 6, 16])
        start, quantity = rng.randrange(0, 200), rng.randint(1, 30)
        if function == 3:
            request = struct.pack(">BBHH", unit, 3, start, quantity)
        elif function == 6:
            request = struct.pack(">BBHH", unit, 6, start, rng.randrange(0x10000))
        else:
            values = [rng.randrange(0x10000) for _ in range(quantity)]
            request = struct.pack(f">BBHHB{quantity}H", unit, 16, start, quantity, 2 * quantity, *values)
        request = with_crc(request)
        out += request + slave.answer(request)
    return bytes(out)


def run_live_on_pty(chunks: list[tuple[bytes, float]], options: list[str], env: dict[str, str] | None = None,
                    settle: float = 0.3, timeout: float = 20) -> tuple[bytes, bytes, int]:
    """`chunks` (bytes, pause after) written to a pseudo-terminal; vw3-decode --live at 115200 baud on its
    other end, stopped by SIGINT `settle` seconds after the last: (its stdout, its stderr after
    "listening on", its status)."""
    line, device_fd, path = open_pty()
    process = subprocess.Popen(
        [sys.executable, "-m", "dissector", "--live", path, "--baud", "115200", *options],
        cwd=ROOT, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )
    try:
        assert process.stderr is not None and process.stdout is not None
        assert b"listening on" in process.stderr.readline()
        for data, pause in chunks:
            os.write(line, data)
            time.sleep(pause)
        time.sleep(settle)
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=timeout)
    finally:
        if process.poll() is None:
            process.kill()
        os.close(line)
        os.close(device_fd)
    return out, err, process.returncode


def _text(data: bytes) -> str:
    """As a text-mode pipe reads it (universal newlines)."""
    return data.decode().replace("\r\n", "\n").replace("\r", "\n")


def live_on_pty(frames: list[bytes], *options: str, pause: float = 0.1) -> tuple[list[str], str, int]:
    """`frames` written to a pseudo-terminal one by one, `pause` apart; vw3-decode --live at 115200 baud
    on its other end, stopped by SIGINT: (its stdout lines, its stderr after "listening on", its status)."""
    out, err, status = run_live_on_pty([(frame, pause) for frame in frames], list(options))
    return _text(out).splitlines(), _text(err), status
