"""Ethernet/IPv4 pcaps for the plugin's network transports: TCP segments (sequence numbers per direction,
any client port) and UDP datagrams, one payload per packet; Modbus/TCP transactions of hex PDUs and the checks
vw3_modbus.lua and vw3-decode must agree on (warnings on requests, notes on answers)."""
from __future__ import annotations

import json
import struct
from pathlib import Path

from dissector.render.pcapwriter import PcapWriter
from helpers import run_cli, write_rtu
from lua_harness import lua_errors, run_tshark

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


def write_modbus_tcp_pairs(path: Path, pairs: list[tuple[str, str]], unit: int = 12) -> Path:
    """(request, response) PDUs in hex (spaces allowed) as Modbus/TCP transactions of one connection, 10 ms apart."""
    writer = NetWriter(path)
    time = 1.0
    for transaction, (request, response) in enumerate(pairs, start=1):
        for to_server, text in ((True, request), (False, response)):
            pdu = bytes.fromhex(text.replace(" ", ""))
            writer.tcp(to_server, 40000, 502, struct.pack("!HHHB", transaction, 0, len(pdu) + 1, unit) + pdu, time)
            time += 0.01
    writer.close()
    return path


def assert_device_checks(pcap: Path, plugin: Path, warnings: list[str], notes: list[str], two_pass: bool) -> None:
    """vw3_modbus.lua under profile atv71: each request's vw3.warning and each answer's vw3.note, exactly."""
    done = run_tshark(pcap, "-X", f"lua_script:{plugin}", "-o", "vw3.profiles:atv71", "-T", "fields",
                      "-E", "separator=|", "-e", "frame.number", "-e", "vw3.warning", "-e", "vw3.note",
                      two_pass=two_pass)
    assert done.returncode == 0, done.stderr
    assert not lua_errors(done.stdout + done.stderr)
    lines = done.stdout.splitlines()
    assert lines[0::2] == [f"{2 * index + 1}|{warning}|" for index, warning in enumerate(warnings)]
    assert lines[1::2] == [f"{2 * index + 2}||{note}" for index, note in enumerate(notes)]


def assert_same_over_rtu(path: Path, pairs: list[tuple[str, str]], warnings: list[str], notes: list[str]) -> None:
    """vw3-decode (serial captures only) on the same PDUs over RTU at unit 12: the same warnings and notes."""
    write_rtu(path, [f"0C{pdu}".replace(" ", "") for pair in pairs for pdu in pair])
    frames = [json.loads(line) for line in run_cli(["--profile", "atv71", "--json", str(path)])[1].splitlines()]
    assert [",".join(frame["warnings"]) for frame in frames[0::2]] == warnings
    assert [",".join(frame["notes"]) for frame in frames[1::2]] == notes
