"""Ethernet/IPv4 pcaps for the plugin's network transports: TCP segments (sequence numbers per direction,
any client port) and UDP datagrams, one payload per packet."""
from __future__ import annotations

import struct
from pathlib import Path

from dissector.render.pcapwriter import PcapWriter

LINKTYPE_ETHERNET = 1
CLIENT, SERVER = bytes([10, 0, 0, 1]), bytes([10, 0, 0, 2])


def _checksum(header: bytes) -> int:
    total = sum(struct.unpack(f"!{len(header) // 2}H", header))
    total = (total >> 16) + (total & 0xFFFF)
    return ~(total + (total >> 16)) & 0xFFFF


class NetWriter:
    def __init__(self, path: Path) -> None:
        self._stream = path.open("wb")
        self._writer = PcapWriter(self._stream, linktype=LINKTYPE_ETHERNET, flush=False)
        self._seq: dict[tuple[int, int], int] = {}

    def _ip(self, protocol: int, source: bytes, destination: bytes, body: bytes) -> bytes:
        ip = struct.pack("!BBHHHBBH4s4s", 0x45, 0, 20 + len(body), 1, 0, 64, protocol, 0, source, destination)
        return ip[:10] + struct.pack("!H", _checksum(ip)) + ip[12:] + body

    def _write(self, packet: bytes, time: float) -> None:
        self._writer.write(bytes.fromhex("001122334455 66778899aabb 0800") + packet, time)

    def tcp(self, to_server: bool, client_port: int, port: int, payload: bytes, time: float) -> None:
        source, destination = (CLIENT, SERVER) if to_server else (SERVER, CLIENT)
        sport, dport = (client_port, port) if to_server else (port, client_port)
        seq = self._seq.get((sport, dport), 1000)
        self._seq[(sport, dport)] = seq + len(payload)
        ack = self._seq.get((dport, sport), 1000)
        tcp = struct.pack("!HHIIBBHHH", sport, dport, seq, ack, 5 << 4, 0x18, 8192, 0, 0)
        self._write(self._ip(6, source, destination, tcp + payload), time)

    def udp(self, to_server: bool, client_port: int, port: int, payload: bytes, time: float) -> None:
        source, destination = (CLIENT, SERVER) if to_server else (SERVER, CLIENT)
        sport, dport = (client_port, port) if to_server else (port, client_port)
        udp = struct.pack("!HHHH", sport, dport, 8 + len(payload), 0)
        self._write(self._ip(17, source, destination, udp + payload), time)

    def close(self) -> None:
        self._stream.close()
