"""RTU over TCP/UDP segments as Wireshark's TCP and IP give them to the plugin (sources/ethernet.py): a TCP
segment starting before the highest sequence number seen is given to no subdissector even when it brings new
bytes (tcp.no_subdissector_on_error); IPv4 fragments are reassembled (ip.defragment; IPv6: test_rtu_over_tcp_ipv6.py) and the datagram read in
its last fragment's packet."""
from __future__ import annotations

import struct
from pathlib import Path

from helpers import run_cli
from lua_harness import lua_errors, run_tshark
from lua_net import CLIENT, SERVER, NetWriter
from seed_frames import SCENARIO_1, SCENARIO_2, SCENARIO_REQUEST

ATV71 = ["--profile", "atv71"]
REQUEST = "12 request   Read Holding Registers 8400..8402 (3)"
ANSWER_1 = ("12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) "
            "COP=Cd (command) [#1, 10.0 ms]  CRC ok")
ANSWER_2 = ("12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=protected COP=Cd (command) "
            "[#3, 10.0 ms]  CRC ok")


def plugin_rows(pcap: Path, *preferences: str) -> list[str]:
    done = run_tshark(pcap, *preferences, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|",
                      "-e", "frame.number", "-e", "vw3.kind", "-e", "vw3.request_frame")
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr)
    return done.stdout.splitlines()


def test_an_overlapping_segment_is_not_read_again(tmp_path: Path) -> None:
    # The answer's first 5 bytes, then (its end lost) a segment sent again from byte 3 to the end: Wireshark
    # flags it a retransmission and the plugin never sees it; its first 2 bytes were read twice, as noise.
    pcap = tmp_path / "overlap.pcap"
    writer = NetWriter(pcap)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.0)
    start = writer._seq.get((4001, 40001), 1000)
    writer.tcp(False, 40001, 4001, SCENARIO_1[:5], 1.010)
    writer._seq[(4001, 40001)] = start + 3
    writer.tcp(False, 40001, 4001, SCENARIO_1[3:], 1.3)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.4)
    writer.tcp(False, 40001, 4001, SCENARIO_2, 1.41)
    writer.close()
    assert run_cli(["--tcp-port", "4001", *ATV71, str(pcap)]) == (0, (
        f"     1     0.000000  {REQUEST} [no response]  CRC ok\n"
        "     2     0.010000   - noise     5 bytes of noise at offset 8: 0c 03 06 80 00\n"
        f"     3     0.400000  {REQUEST}  CRC ok\n"
        f"     4     0.410000  {ANSWER_2}\n"), f"vw3-decode: warning: {pcap}: 1 packet carried no Modbus RTU bytes on "
        "TCP port 4001: skipped (1 TCP retransmissions)\n")
    # (the plugin, two passes: the 5 bytes noise in packet 2, packet 3 given no subdissector)
    assert plugin_rows(pcap, "-o", "vw3.tcp_port:4001") == ["1|1|", "2|4|", "3||", "4|1|", "5|2|4"]


def _fragments(writer: NetWriter, to_server: bool, payload: bytes, time: float, ident: int) -> None:
    """A UDP datagram in two IPv4 fragments (its header and nothing more, then the rest), 0.1 ms apart."""
    source, destination = (CLIENT, SERVER) if to_server else (SERVER, CLIENT)
    ports = (40001, 5021) if to_server else (5021, 40001)
    datagram = struct.pack("!HHHH", *ports, 8 + len(payload), 0) + payload
    for offset, piece, more, at in ((0, datagram[:8], 1, time), (1, datagram[8:], 0, time + 0.0001)):
        writer._write(struct.pack("!BBHHHBBH4s4s", 0x45, 0, 20 + len(piece), ident, more << 13 | offset, 64, 17, 0,
                                  source, destination) + piece, at)


def test_ip_fragments_are_reassembled(tmp_path: Path) -> None:
    # Before: refused, "its 4 packets: 4 fragmented IP"; tshark reassembles them and the plugin reads both frames.
    pcap = tmp_path / "fragments.pcap"
    writer = NetWriter(pcap)
    _fragments(writer, True, SCENARIO_REQUEST, 1.0, 77)
    _fragments(writer, False, SCENARIO_1, 1.01, 78)
    for ident, flags_offset, time in ((79, 1 << 13, 1.1), (80, 1, 1.2)):  # (a first and a last, never completed)
        writer._write(struct.pack("!BBHHHBBH4s4s", 0x45, 0, 28, ident, flags_offset, 64, 17, 0, CLIENT, SERVER)
                      + bytes(8), time)
    writer.close()
    assert run_cli(["--udp-port", "5021", *ATV71, str(pcap)]) == (0, (
        f"     1     0.000100  {REQUEST}  CRC ok\n     2     0.010100  {ANSWER_1}\n"),  # (its last fragment's)
        f"vw3-decode: warning: {pcap}: 2 packets carried no Modbus RTU bytes on UDP port 5021: skipped (2 fragmented IP "
        "never reassembled)\n")
    assert plugin_rows(pcap, "-o", "vw3.udp_port:5021") == ["1||", "2|1|", "3||", "4|2|2", "5||", "6||"]


def test_a_connection_on_ports_used_again_is_read(tmp_path: Path) -> None:
    # A poll, FIN both ways, then the same ports connect again (a master binding a fixed port) with lower initial
    # sequence numbers: Wireshark says "TCP Port numbers reused" and the plugin reads the second poll; vw3-decode
    # took its two segments for retransmissions of the first connection's and dropped them.
    pcap = tmp_path / "reused.pcap"
    writer = NetWriter(pcap)

    def segment(to_server: bool, seq: int, ack: int, flags: int, payload: bytes, time: float) -> None:
        ends, ports = ((CLIENT, SERVER), (40001, 4001)) if to_server else ((SERVER, CLIENT), (4001, 40001))
        tcp = struct.pack("!HHIIBBHHH", *ports, seq, ack, 5 << 4, flags, 8192, 0, 0)
        writer._write(writer._ip(6, *ends, tcp + payload), time)

    for base, time in ((1000, 1.0), (500, 2.0)):  # (SYN, SYN-ACK, the poll; FIN both ways after the first)
        segment(True, base - 1, 0, 0x02, b"", time - 0.01)
        segment(False, 5 * base - 1, base, 0x12, b"", time - 0.009)
        segment(True, base, 5 * base, 0x18, SCENARIO_REQUEST, time)
        segment(False, 5 * base, base + 8, 0x18, SCENARIO_1, time + 0.01)
        if base == 1000:
            segment(True, base + 8, 5 * base + 11, 0x11, b"", time + 0.02)
            segment(False, 5 * base + 11, base + 9, 0x11, b"", time + 0.021)
    writer.close()
    assert run_cli(["--tcp-port", "4001", *ATV71, str(pcap)]) == (0, (
        f"     1     0.010000  {REQUEST}  CRC ok\n     2     0.020000  {ANSWER_1}\n"  # (from the first SYN)
        f"     3     1.010000  {REQUEST}  CRC ok\n     4     1.020000  {ANSWER_1.replace('#1', '#3')}\n"),
        f"vw3-decode: warning: {pcap}: 6 packets carried no Modbus RTU bytes on TCP port 4001: skipped (6 TCP "
        "without payload)\n")
    assert [row for row in plugin_rows(pcap, "-o", "vw3.tcp_port:4001") if row.split("|")[1]] == [
        "3|1|", "4|2|3", "9|1|", "10|2|9"]


def test_a_fast_retransmission_is_read_as_the_plugin_reads_it(tmp_path: Path) -> None:
    # Two polls, three ACKs of the first's byte (two duplicates), the first poll sent again 1 ms later: Wireshark's
    # TCP flags it a fast retransmission and gives it to the plugin, which pairs the answer with it (7 ms);
    # vw3-decode dropped it as a retransmission and paired the answer with the second poll (9 ms).
    pcap = tmp_path / "fast.pcap"
    writer = NetWriter(pcap)

    def segment(to_server: bool, seq: int, ack: int, flags: int, payload: bytes, time: float) -> None:
        ends, ports = ((CLIENT, SERVER), (40001, 4001)) if to_server else ((SERVER, CLIENT), (4001, 40001))
        tcp = struct.pack("!HHIIBBHHH", *ports, seq, ack, 5 << 4, flags, 8192, 0, 0)
        writer._write(writer._ip(6, *ends, tcp + payload), time)

    segment(True, 1000, 5000, 0x18, SCENARIO_REQUEST, 1.0)
    segment(True, 1008, 5000, 0x18, SCENARIO_REQUEST, 1.001)
    for index in range(3):
        segment(False, 5000, 1000, 0x10, b"", 1.002 + index / 10000)
    segment(True, 1000, 5000, 0x18, SCENARIO_REQUEST, 1.003)
    segment(False, 5000, 1016, 0x18, SCENARIO_1, 1.01)
    writer.close()
    assert run_cli(["--tcp-port", "4001", *ATV71, str(pcap)]) == (0, (
        f"     1     0.000000  {REQUEST} [no response]  CRC ok\n     2     0.001000  {REQUEST} [no response]  CRC ok\n"
        f"     3     0.003000  {REQUEST}  CRC ok\n     4     0.010000  {ANSWER_1.replace('#1, 10.0', '#3, 7.0')}\n"),
        f"vw3-decode: warning: {pcap}: 3 packets carried no Modbus RTU bytes on TCP port 4001: skipped (3 TCP "
        "without payload)\n")
    assert [row for row in plugin_rows(pcap, "-o", "vw3.tcp_port:4001") if row.split("|")[1]] == [
        "1|1|", "2|1|", "6|1|", "7|2|6"]
