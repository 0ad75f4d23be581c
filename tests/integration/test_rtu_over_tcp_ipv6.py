"""IPv6 packets are followed to their TCP/UDP payload past their extension headers (hop-by-hop, routing, destination
options, AH), and IPv6 fragments reassembled (ipv6.defragment) and read in the last fragment's packet, as IPv4's:
before, a packet with an extension header was 'not TCP or UDP' and a fragment's pieces never read, where tshark and
the plugin read the frames (sources/ethernet.py)."""
from __future__ import annotations

import struct
from pathlib import Path

from helpers import run_cli
from lua_harness import lua_errors, run_tshark
from lua_net import NetWriter
from seed_frames import SCENARIO_1, SCENARIO_REQUEST

CLIENT6, SERVER6 = bytes.fromhex("fd00" + "00" * 13 + "01"), bytes.fromhex("fd00" + "00" * 13 + "02")
REQUEST = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
ANSWER = ("12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) "
          "COP=Cd (command) [#1, 10.0 ms]  CRC ok")
HOP_BY_HOP, ROUTING, DESTINATION, FRAGMENT = 0, 43, 60, 44


def _ipv6(writer: NetWriter, to_server: bool, next_header: int, body: bytes, time: float) -> None:
    source, destination = (CLIENT6, SERVER6) if to_server else (SERVER6, CLIENT6)
    header = struct.pack("!IHBB", 6 << 28, len(body), next_header, 64) + source + destination
    writer._writer.write(bytes.fromhex("001122334455 66778899aabb 86dd") + header + body, time)


def _options(next_header: int, size: int) -> bytes:
    """An extension header of `size` bytes (a multiple of 8): its next header, its length, padding (PadN)."""
    return bytes([next_header, size // 8 - 1, 1, size - 4]) + bytes(size - 4)


def _tcp(to_server: bool, seq: int, payload: bytes) -> bytes:
    ports = (40001, 4001) if to_server else (4001, 40001)
    return struct.pack("!HHIIBBHHH", *ports, seq, 1000, 5 << 4, 0x18, 8192, 0, 0) + payload


def _rows(pcap: Path, preference: str) -> list[str]:
    done = run_tshark(pcap, "-o", preference, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|",
                      "-e", "frame.number", "-e", "vw3.kind", "-e", "vw3.request_frame")
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr)
    return done.stdout.splitlines()


def test_extension_headers_are_followed_to_the_payload(tmp_path: Path) -> None:
    pcap = tmp_path / "ipv6.pcap"
    writer = NetWriter(pcap)
    # The request after hop-by-hop, routing (type 0, no address left) and destination options; the answer after AH.
    chain = _options(ROUTING, 8) + bytes([DESTINATION, 0, 0, 0]) + bytes(4) + _options(6, 16)
    _ipv6(writer, True, HOP_BY_HOP, chain + _tcp(True, 1, SCENARIO_REQUEST), 1.0)
    ah = bytes([6, 4, 0, 0]) + bytes(20)  # (AH: 4-byte units after the first 8, 24 bytes)
    _ipv6(writer, False, 51, ah + _tcp(False, 1000, SCENARIO_1), 1.01)
    writer.close()
    assert run_cli(["--tcp-port", "4001", "--profile", "atv71", str(pcap)]) == (
        0, f"     1     0.000000  {REQUEST}\n     2     0.010000  {ANSWER}\n", "")
    assert _rows(pcap, "vw3.tcp_port:4001") == ["1|1|", "2|2|1"]


def test_ipv6_fragments_are_reassembled(tmp_path: Path) -> None:
    pcap = tmp_path / "fragments6.pcap"
    writer = NetWriter(pcap)
    for index, (to_server, payload, time) in enumerate(((True, SCENARIO_REQUEST, 1.0), (False, SCENARIO_1, 1.01))):
        ports = (40001, 5021) if to_server else (5021, 40001)
        datagram = struct.pack("!HHHH", *ports, 8 + len(payload), 0) + payload
        # (its UDP header alone, then the rest after a destination options header, 0.1 ms later)
        for offset, piece, more, at in ((0, datagram[:8], 1, time), (8, datagram[8:], 0, time + 0.0001)):
            fragment = struct.pack("!BBHI", 17, 0, offset | more, 77 + index)
            first = _options(FRAGMENT, 8) if offset else b""
            _ipv6(writer, to_server, DESTINATION if offset else FRAGMENT, first + fragment + piece, at)
    _ipv6(writer, True, FRAGMENT, struct.pack("!BBHI", 17, 0, 1, 99) + bytes(8), 1.2)  # (never completed)
    writer.close()
    assert run_cli(["--udp-port", "5021", "--profile", "atv71", str(pcap)]) == (
        0, f"     1     0.000100  {REQUEST}\n     2     0.010100  {ANSWER}\n",
        f"vw3-decode: warning: {pcap}: 1 packet carried no Modbus RTU bytes on UDP port 5021: skipped (1 fragmented "
        "IP never reassembled)\n")
    assert _rows(pcap, "vw3.udp_port:5021") == ["1||", "2|1|", "3||", "4|2|2", "5||"]
