"""A real Modbus ASCII master and slave (pymodbus, FramerType.ASCII) on a pseudo-terminal bus, sniffed live by
vw3-decode --mode ascii (peer69): every function pymodbus's client sends, at the spec's extreme quantities
(a read of 2000 coils, a write of 1968 coils and of 123 registers, a one-coil FC15), FC23, FC22, FC8, FC7,
FC17, FC43, FC24 and an exception 02, each decoded as what the client asked and what it was answered: the
addresses and values the client sent and got back, frame for frame, LRC ok, each answer paired with its
request; and the live lines are the decode of the capture file written beside them (-w)."""
from __future__ import annotations

import asyncio
import json
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from live_bus import ROOT, Bus, Sniffer

pytestmark = pytest.mark.integration

BAUD = 115200
DEVICE = 5
COILS = [int(i % 3 == 0) for i in range(2000)]
INPUTS = [i % 2 for i in range(2000)]
HOLDING = [i * 3 for i in range(200)]
INPUT_REGISTERS = [1000 + i for i in range(200)]


class AsciiSlave(threading.Thread):
    """pymodbus's serial server in ASCII framing on `path`, device DEVICE only."""

    def __init__(self, path: str) -> None:
        super().__init__(daemon=True)
        self.path = path
        self.ready = threading.Event()
        self.loop: asyncio.AbstractEventLoop | None = None
        self.server: Any = None

    def run(self) -> None:
        from pymodbus import FramerType
        from pymodbus.datastore import ModbusDeviceContext, ModbusSequentialDataBlock, ModbusServerContext
        from pymodbus.server import ModbusSerialServer

        # pymodbus's sequential blocks hold protocol address 0 at their address 1.
        device = ModbusDeviceContext(co=ModbusSequentialDataBlock(1, COILS), di=ModbusSequentialDataBlock(1, INPUTS),
                                     hr=ModbusSequentialDataBlock(1, HOLDING),
                                     ir=ModbusSequentialDataBlock(1, INPUT_REGISTERS))
        context = ModbusServerContext(devices={DEVICE: device}, single=False)

        async def serve() -> None:
            self.loop = asyncio.get_running_loop()
            self.server = ModbusSerialServer(context, framer=FramerType.ASCII, port=self.path, baudrate=BAUD,
                                             parity="N")
            self.loop.call_soon(self.ready.set)
            await self.server.serve_forever()

        try:
            asyncio.run(serve())
        except Exception:  # noqa: BLE001  (stopped by close())
            pass

    def close(self) -> None:
        if self.loop is not None and self.server is not None:
            try:
                asyncio.run_coroutine_threadsafe(self.server.shutdown(), self.loop).result(5)
            except Exception:  # noqa: BLE001
                pass
        self.join(5)


def _registers(item: dict[str, Any]) -> list[tuple[int, int]]:
    return [(register["address"], register["value"]) for register in item.get("registers", [])]


def _bits(item: dict[str, Any]) -> list[int]:
    return [bit["value"] for bit in item.get("bits", [])]


def test_pymodbus_ascii_master_and_slave_sniffed_live(tmp_path: Path) -> None:
    from pymodbus import FramerType
    from pymodbus.client import ModbusSerialClient

    bus = Bus(baud=BAUD, slave=False, seed=69)
    slave = AsciiSlave(bus.b_path)
    slave.start()
    assert slave.ready.wait(10)
    time.sleep(0.2)
    pcap = tmp_path / "ascii.pcap"
    sniffer = Sniffer.start(bus.c_path, "--mode", "ascii", "--baud", str(BAUD), "--json", "-w", str(pcap))
    client = ModbusSerialClient(bus.a_path, framer=FramerType.ASCII, baudrate=BAUD, parity="N", timeout=2, retries=0)
    assert client.connect()
    written_coils = [bool(i % 2) for i in range(1968)]
    try:
        got = {
            "coils": client.read_coils(0, count=2000, device_id=DEVICE).bits[:2000],
            "inputs": client.read_discrete_inputs(1990, count=10, device_id=DEVICE).bits[:10],
            "holding": client.read_holding_registers(0, count=125, device_id=DEVICE).registers,
            "input_registers": client.read_input_registers(3, count=2, device_id=DEVICE).registers,
        }
        assert not client.write_coil(7, True, device_id=DEVICE).isError()
        assert not client.write_coils(9, [True], device_id=DEVICE).isError()
        assert not client.write_coils(0, written_coils, device_id=DEVICE).isError()
        assert not client.write_register(4, 0xBEEF, device_id=DEVICE).isError()
        assert not client.write_registers(0, list(range(123)), device_id=DEVICE).isError()
        got["read_write"] = client.readwrite_registers(read_address=3, read_count=2, write_address=16, values=[0x1234],
                                                       device_id=DEVICE).registers
        assert not client.mask_write_register(address=4, and_mask=0x00F2, or_mask=0x0025,
                                              device_id=DEVICE).isError()
        exception = client.read_holding_registers(190, count=20, device_id=DEVICE)
        assert exception.isError() and exception.exception_code == 2
        assert not client.diag_query_data(msg=b"\xa5\x37", device_id=DEVICE).isError()
        got["status"] = client.read_exception_status(device_id=DEVICE).status
        assert not client.report_device_id(device_id=DEVICE).isError()
        assert not client.read_device_information(device_id=DEVICE).isError()
        got["fifo"] = client.read_fifo_queue(address=0, device_id=DEVICE).values
        # The last answer must be on the line before the sniffer stops: 34 frames, one line each.
        sniffer.wait_lines(34, timeout=10)
        status, stderr = sniffer.interrupt()
    finally:
        client.close()
        slave.close()
        bus.close()
    assert status == 0, stderr
    live = [json.loads(line) for _, line in sniffer.lines]
    assert [(item["frame"], item["kind"], item["slave"], item["function"], item["crc_ok"], item["mode"],
             item.get("request_frame")) for item in live] == [
        (number, "request" if number % 2 else kind, DEVICE, function, True, "ascii",
         None if number % 2 else number - 1)
        for number, (kind, function) in enumerate(
            [step for pair in ([("request", f), ("exception" if f == 3 and n == 11 else "response", f)]
                               for n, f in enumerate([1, 2, 3, 4, 5, 15, 15, 6, 16, 23, 22, 3, 8, 7, 17, 43, 24]))
             for step in pair], start=1)]
    assert [item.get("warnings") for item in live if item.get("warnings")] == [
        ["server id of 8 bytes, up to the first 00 (OFF) or FF (ON) after its first byte: after a one-byte id, "
         "0x79 is no run indicator"],
        ["no objects: VendorName, ProductCode, MajorMinorRevision are mandatory"]]
    frames = {item["frame"]: item for item in live}
    # What the client read is what the sniffer read.
    assert _bits(frames[2]) == [int(bit) for bit in got["coils"]] == COILS
    assert _bits(frames[4]) == [int(bit) for bit in got["inputs"]] == INPUTS[1990:]
    assert _registers(frames[6]) == list(enumerate(got["holding"])) == list(enumerate(HOLDING[:125]))
    assert _registers(frames[8]) == [(3, got["input_registers"][0]), (4, got["input_registers"][1])]
    # What it wrote is what the sniffer saw written and confirmed.
    assert [(bit["address"], bit["value"]) for bit in frames[9]["bits"]] == [(7, 1)]
    assert [(bit["address"], bit["value"]) for bit in frames[11]["bits"]] == [(9, 1)]
    assert (frames[11]["start"], frames[11]["quantity"]) == (9, 1)
    assert _bits(frames[13]) == [int(bit) for bit in written_coils]
    assert (frames[14]["start"], frames[14]["quantity"]) == (0, 1968)
    assert _registers(frames[15]) == [(4, 0xBEEF)] == _registers(frames[16])
    assert _registers(frames[17]) == list(enumerate(range(123)))
    assert (frames[18]["start"], frames[18]["quantity"]) == (0, 123)
    assert _registers(frames[19]) == [(16, 0x1234)]
    assert _registers(frames[20]) == [(3, got["read_write"][0]), (4, got["read_write"][1])] == [(3, 3), (4, 4)]
    assert frames[22]["fields"]["and_mask"] == 0x00F2 and frames[22]["fields"]["or_mask"] == 0x0025
    assert (frames[24]["exception_code"], frames[24]["exception_name"]) == (2, "Illegal Data Address")
    assert frames[28]["fields"]["status"] == got["status"]
    assert frames[34]["fields"]["values"] == got["fifo"]
    # The live lines are the decode of the file written beside them.
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", "--json", str(pcap)],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert [json.loads(line) for line in done.stdout.splitlines()] == live
