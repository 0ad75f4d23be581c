"""A pcapng of a serial interface beside an Ethernet one (a tap on the line and a capture of the gateway's network
side): with --tcp-port, the Ethernet interface's connections on the port are buses of their own beside the serial
interface's, as the plugin decodes both (sources/interfaces.py packet_interfaces). Before, the Ethernet packets
were passed over with a warning that the ports were not read."""
from __future__ import annotations

import struct
from pathlib import Path

from helpers import run_cli
from lua_harness import lua_errors, run_tshark
from lua_net import NetWriter
from seed_frames import SCENARIO_1, SCENARIO_REQUEST

SERIAL_REQUEST = bytes.fromhex("0C0320D000030EEF")
SERIAL_ANSWER = bytes.fromhex("0C0306000100020003A5E4")  # 8400=1, CHCF=SEP, COP=ALL
REQUEST = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"


def _block(kind: int, body: bytes) -> bytes:
    return struct.pack("<II", kind, 12 + len(body)) + body + struct.pack("<I", 12 + len(body))


def _ethernet_frames() -> list[bytes]:
    frames: list[bytes] = []
    writer = NetWriter.__new__(NetWriter)
    writer._seq = {}
    writer._write = lambda packet, time: frames.append(bytes.fromhex("001122334455 66778899aabb 0800") + packet)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 0)
    writer.tcp(False, 40001, 4001, SCENARIO_1, 0)
    return frames


def capture(path: Path) -> Path:
    """Interface 0 USER0 (serial), interface 1 Ethernet: a poll on each, the network one 0.5 ms after the serial."""
    request, answer = _ethernet_frames()
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    out += _block(1, struct.pack("<HHI", 147, 0, 0)) + _block(1, struct.pack("<HHI", 1, 0, 0))
    for interface, micros, data in ((0, 0, SERIAL_REQUEST), (1, 500, request), (0, 10_000, SERIAL_ANSWER),
                                    (1, 10_800, answer)):
        stamp = 1_767_225_600_000_000 + micros
        out += _block(6, struct.pack("<IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data))
                      + data + b"\0" * (-len(data) % 4))
    path.write_bytes(out)
    return path


def test_the_serial_and_the_network_interface_are_each_decoded(tmp_path: Path) -> None:
    path = capture(tmp_path / "both.pcapng")
    # (the network bus's times are tshark's: from the capture's first packet, the serial one's; -t d from the
    # packet before, a serial one)
    assert run_cli(["--tcp-port", "4001", "--profile", "atv71", str(path)]) == (0, (
        f"==> {path}: interface 0 <==\n"
        f"     1     0.000000  {REQUEST}\n"
        "     2     0.010000  12 response  Read Holding Registers 8400..8402 (3): 8400=1 CHCF=SEP (separate) "
        "COP=ALL (command and reference) [#1, 10.0 ms]  CRC ok\n"
        f"==> {path}: TCP 10.0.0.1:40001 - 10.0.0.2:4001 <==\n"
        f"     1     0.000500  {REQUEST}\n"
        "     2     0.010800  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O "
        "profile) COP=Cd (command) [#1, 10.3 ms]  CRC ok\n"), "")
    fields = run_cli(["--tcp-port", "4001", "-T", "fields", "-e", "slave", "-e", "time_relative", "-e", "time_delta",
                      "-e", "response_time", str(path)])[1]
    done = run_tshark(path, "-o", "vw3.tcp_port:4001", "-T", "fields", "-e", "vw3.slave", "-e", "frame.time_relative",
                      "-e", "frame.time_delta", "-e", "vw3.response_time")
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr)
    # The plugin reads both interfaces' polls (packets 1, 3 serial; 2, 4 TCP); its network rows are vw3-decode's.
    assert [row.split("\t")[0] for row in done.stdout.splitlines()] == ["12"] * 4
    assert fields.splitlines()[2:] == done.stdout.splitlines()[1::2]
