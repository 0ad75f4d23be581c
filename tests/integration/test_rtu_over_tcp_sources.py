"""vw3-decode reads the Ethernet side of a serial gateway as the plugin does (sources/ethernet.py): the TCP/UDP
payloads on the RTU ports (--tcp-port/--udp-port, the plugin's vw3.tcp_port/vw3.udp_port) are the bus's
records, with the packets' times; a frame split over two segments is one frame; each connection is a bus;
packets without bus bytes are counted in one warning; a capture with none on the ports is refused in one
line naming the ports and the options."""
from __future__ import annotations

import json
import random
import struct
import subprocess
from pathlib import Path

import pytest
from helpers import run_cli
from lua_harness import lua_errors, run_tshark
from lua_net import NetWriter
from seed_frames import SCENARIO_1, SCENARIO_2, SCENARIO_REQUEST

ATV71 = ["--profile", "atv71"]
REQUEST = ("12 request   Read Holding Registers 8400..8402 (3)  CRC ok")
ANSWER_1 = ("12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) "
            "COP=Cd (command) [#1, 10.0 ms]  CRC ok")
ANSWER_2 = ("12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=protected COP=Cd (command) "
            "[#3, 10.0 ms] [CHCF (8401) became protected: read 3 in frame #2, 16#8000 now]  CRC ok")
SKIPPED = ("vw3-decode: warning: {name}: 3 packets carried no Modbus RTU bytes on TCP port 4001: skipped "
           "(1 not IP, 1 TCP without payload, 1 other ports)\n")


def gateway(path: Path) -> Path:
    """A gateway's TCP port 4001: an ARP, an empty segment, two polls, the first answer split over two segments
    (4 + 7 bytes), a DNS datagram between."""
    writer = NetWriter(path)
    writer._write(bytes(28), 0.9)  # (its ethertype, 0800, with no IPv4 header: not IP)
    writer.tcp(True, 40001, 4001, b"", 0.95)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.000)
    writer.tcp(False, 40001, 4001, SCENARIO_1[:4], 1.010)
    writer.tcp(False, 40001, 4001, SCENARIO_1[4:], 1.012)
    writer.udp(True, 5353, 53, bytes(12), 1.02)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.100)
    writer.tcp(False, 40001, 4001, SCENARIO_2, 1.110)
    writer.close()
    return path


def lines(*rows: tuple[int, str, str]) -> str:
    return "".join(f"{number:6d}  {time:>11}  {text}\n" for number, time, text in rows)


def test_a_frame_split_over_two_segments_is_one_frame(tmp_path: Path) -> None:
    pcap = gateway(tmp_path / "gateway.pcap")
    status, out, err = run_cli(["--tcp-port", "4001", *ATV71, str(pcap)])
    assert status == 0
    # (times from the capture's first packet, the ARP at 0.9 s, as tshark's frame.time_relative)
    assert out == lines((1, "0.100000", REQUEST), (2, "0.110000", ANSWER_1), (3, "0.200000", REQUEST),
                        (4, "0.210000", ANSWER_2))
    assert err == SKIPPED.format(name=pcap)


def test_json_and_stats_have_the_packets_times(tmp_path: Path) -> None:
    pcap = gateway(tmp_path / "gateway.pcap")
    out = run_cli(["--tcp-port", "4001", *ATV71, "--json", str(pcap)])[1]
    frames = [json.loads(line) for line in out.splitlines()]
    assert [(frame["kind"], frame["time"], frame["raw"], frame.get("request_frame")) for frame in frames] == [
        ("request", 1.0, SCENARIO_REQUEST.hex(), None), ("response", 1.01, SCENARIO_1.hex(), 1),
        ("request", 1.1, SCENARIO_REQUEST.hex(), None), ("response", 1.11, SCENARIO_2.hex(), 3)]
    status, out, err = run_cli(["--tcp-port", "4001", *ATV71, "--stats", str(pcap)])
    assert status == 0 and err == SKIPPED.format(name=pcap)
    assert "   12  3 Read Holding Registers    2     2                     0        0\n" in out


def test_the_plugin_shows_the_same_frames(tmp_path: Path) -> None:
    pcap = gateway(tmp_path / "gateway.pcap")
    done = run_tshark(pcap, "-o", "vw3.tcp_port:4001", "-o", "vw3.profiles:atv71", "-T", "fields",
                      "-E", "separator=|", "-e", "frame.number", "-e", "_ws.col.Info", "-e", "vw3.kind",
                      "-e", "vw3.slave", "-e", "vw3.request_frame", "-e", "vw3.response_time", "-e", "vw3.note")
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr)
    ours = [json.loads(line) for line in run_cli(["--tcp-port", "4001", *ATV71, "--json", str(pcap)])[1].splitlines()]
    rows = [line.split("|") for line in done.stdout.splitlines() if line.split("|")[2]]
    # The plugin shows a frame in the packet that completes it (packet 5 for the split answer); the texts,
    # kinds, slaves, pairing (in packets: 3, 7) and response times are vw3-decode's.
    assert [row[1] for row in rows] == ["12 Read Holding Registers request 8400..8402 (3)",
                                        "12 Read Holding Registers response 8400..8402 (3)"] * 2
    assert [(row[0], row[4]) for row in rows] == [("3", ""), ("5", "3"), ("7", ""), ("8", "7")]
    assert [(row[2], int(row[3]), row[5], row[6]) for row in rows] == [
        ({"request": "1", "response": "2"}[frame["kind"]], frame["slave"],
         f"{frame['response_time']:.9f}" if "response_time" in frame else "", ",".join(frame["notes"]))
        for frame in ours]
    assert ",".join(ours[3]["notes"]) == "CHCF (8401) became protected: read 3 in frame #2, 16#8000 now"


def test_an_ethernet_capture_without_the_port_is_refused_in_one_line(tmp_path: Path) -> None:
    pcap = gateway(tmp_path / "gateway.pcap")
    assert run_cli([str(pcap)]) == (2, "", (
        f"vw3-decode: {pcap}: Ethernet (linktype 1): no TCP or UDP payload on the Modbus RTU ports (none given: "
        "--tcp-port and --udp-port, as the plugin's vw3.tcp_port and vw3.udp_port preferences, set them); "
        "payloads on TCP port 4001 (5 packets), UDP port 53 (1 packet)\n"))


def test_modbus_tcp_is_named_in_the_refusal(tmp_path: Path) -> None:
    writer = NetWriter(tmp_path / "mbtcp.pcap")
    writer.tcp(True, 40000, 502, struct.pack("!HHHB", 1, 0, 6, 12) + SCENARIO_REQUEST[1:6], 1.0)
    writer.close()
    assert run_cli(["--tcp-port", "4001", str(tmp_path / "mbtcp.pcap")]) == (2, "", (
        f"vw3-decode: {tmp_path / 'mbtcp.pcap'}: Ethernet (linktype 1): no TCP or UDP payload on the Modbus RTU "
        "ports (TCP port 4001: --tcp-port and --udp-port, as the plugin's vw3.tcp_port and vw3.udp_port "
        "preferences, set them); payloads on TCP port 502 (1 packet); port 502 is Modbus/TCP (MBAP header, "
        "no CRC), which vw3-decode does not read: tshark with lua/vw3.lua and lua/vw3_modbus.lua names its "
        "registers\n"))


def test_two_connections_are_two_buses(tmp_path: Path) -> None:
    # Two masters poll one gateway; their answers come split and interleaved: each pairs with its own request.
    writer = NetWriter(tmp_path / "two.pcap")
    writer.tcp(True, 40001, 5020, SCENARIO_REQUEST, 1.000)
    writer.tcp(True, 40002, 5020, SCENARIO_REQUEST, 1.001)
    writer.tcp(False, 40002, 5020, SCENARIO_1[:5], 1.010)
    writer.tcp(False, 40001, 5020, SCENARIO_1[:3], 1.011)
    writer.tcp(False, 40002, 5020, SCENARIO_1[5:], 1.012)
    writer.tcp(False, 40001, 5020, SCENARIO_1[3:], 1.013)
    writer.close()
    answer = ANSWER_1.replace("10.0 ms", "{} ms")
    subprocess.run(["editcap", "-F", "pcapng", str(tmp_path / "two.pcap"), str(tmp_path / "two.pcapng")], check=True)
    for pcap in (tmp_path / "two.pcap", tmp_path / "two.pcapng"):
        assert run_cli(["--tcp-port", "5020", *ATV71, str(pcap)]) == (0, (
            f"==> {pcap}: TCP 10.0.0.1:40001 - 10.0.0.2:5020 <==\n"
            + lines((1, "0.000000", REQUEST), (2, "0.011000", answer.format("11.0")))
            + f"==> {pcap}: TCP 10.0.0.1:40002 - 10.0.0.2:5020 <==\n"  # (times from the capture's first packet)
            + lines((1, "0.001000", REQUEST), (2, "0.010000", answer.format("9.0")))), "")


def test_standard_input_is_one_stream_and_says_so(tmp_path: Path) -> None:
    # Standard input cannot be read once per connection: its connections' bytes are one stream, warned; the
    # server's end being both connections', neither's segment is taken for the other's retransmission.
    writer = NetWriter(tmp_path / "two.pcap")
    writer.tcp(True, 40001, 5020, SCENARIO_REQUEST, 1.000)
    writer.tcp(True, 40002, 5020, SCENARIO_REQUEST, 1.001)
    writer.tcp(False, 40001, 5020, SCENARIO_1, 1.010)
    writer.tcp(False, 40002, 5020, SCENARIO_1, 1.011)
    writer.close()
    status, out, err = run_cli(["--tcp-port", "5020", *ATV71, "-"], stdin=(tmp_path / "two.pcap").read_bytes())
    assert (status, err) == (0, "vw3-decode: warning: packets come from several connections on the RTU ports; their "
                             "bytes are decoded as one stream (vw3-decode FILE decodes each connection as its own "
                             "bus: save standard input to a file)\n")
    assert out == lines(
        (1, "0.000000", REQUEST.replace("(3)", "(3) [no response]")), (2, "0.001000", REQUEST),
        (3, "0.010000", ANSWER_1.replace("#1, 10.0 ms", "#2, 9.0 ms")),
        (4, "0.011000", "12 response  Read Holding Registers (3): ?+0=32768 ?+1=3 ?+2=2 [no request] [response "
                        "without a matching request in the capture]  CRC ok"))


def _relinked(pcap: Path, path: Path, linktype: int, strip: int, header: bytes) -> Path:
    """The same packets with their Ethernet header (`strip` bytes) replaced by another link's `header`."""
    data = pcap.read_bytes()
    out, at = bytearray(data[:20] + struct.pack("<I", linktype)), 24
    while at < len(data):
        seconds, fraction, captured, _original = struct.unpack_from("<IIII", data, at)
        body = header + data[at + 16 + strip : at + 16 + captured]
        out += struct.pack("<IIII", seconds, fraction, len(body), len(body)) + body
        at += 16 + captured
    path.write_bytes(bytes(out))
    return path


def test_linux_cooked_raw_ip_udp_and_pcapng_read_alike(tmp_path: Path) -> None:
    pcap = gateway(tmp_path / "gateway.pcap")
    expected = lines((1, "0.100000", REQUEST), (2, "0.110000", ANSWER_1), (3, "0.200000", REQUEST),
                     (4, "0.210000", ANSWER_2))
    sll = _relinked(pcap, tmp_path / "sll.pcap", 113, 14, bytes(14) + b"\x08\x00")
    sll2 = _relinked(pcap, tmp_path / "sll2.pcap", 276, 14, b"\x08\x00" + bytes(18))
    raw = _relinked(pcap, tmp_path / "raw.pcap", 101, 14, b"")
    pcapng = tmp_path / "gateway.pcapng"
    subprocess.run(["editcap", "-F", "pcapng", str(pcap), str(pcapng)], check=True)
    for path in (sll, sll2, raw, pcapng):
        assert run_cli(["--tcp-port", "4001", *ATV71, str(path)])[1] == expected, path
    writer = NetWriter(tmp_path / "udp.pcap")
    writer.udp(True, 40001, 5021, SCENARIO_REQUEST, 1.0)
    writer.udp(False, 40001, 5021, SCENARIO_1, 1.01)
    writer.close()
    assert run_cli(["--udp-port", "5021", *ATV71, str(tmp_path / "udp.pcap")]) == (
        0, lines((1, "0.000000", REQUEST), (2, "0.010000", ANSWER_1)), "")


def test_modbus_tcp_on_the_rtu_port_is_refused_not_shown_as_noise(tmp_path: Path) -> None:
    # Port 502 given as the RTU port: its first payload is an MBAP header (protocol 0, length 6: the rest),
    # not an RTU frame (no CRC), after an empty segment.
    writer = NetWriter(tmp_path / "mbtcp.pcap")
    writer.tcp(True, 40000, 502, b"", 0.5)
    writer.tcp(True, 40000, 502, struct.pack("!HHHB", 7, 0, 6, 12) + SCENARIO_REQUEST[1:6], 1.0)
    writer.close()
    assert run_cli(["--tcp-port", "502", str(tmp_path / "mbtcp.pcap")]) == (2, "", (
        f"vw3-decode: {tmp_path / 'mbtcp.pcap'}: record 2: TCP port 502 carries Modbus/TCP (MBAP header: "
        "transaction 7, unit 12, no CRC), not Modbus RTU frames, which vw3-decode does not read: tshark with "
        "lua/vw3.lua and lua/vw3_modbus.lua names its registers\n"))
    # RTU over TCP on port 502 (a gateway's choice) is read: its frame checks out.
    writer = NetWriter(tmp_path / "rtu502.pcap")
    writer.tcp(True, 40000, 502, SCENARIO_REQUEST, 1.0)
    writer.close()
    assert run_cli(["--tcp-port", "502", *ATV71, str(tmp_path / "rtu502.pcap")]) == (
        0, lines((1, "0.000000", REQUEST.replace(
            "(3)", "(3) [the capture ends before any response: not known whether it was answered]"))), "")


def test_a_retransmitted_segment_is_read_once_as_the_plugin_reads_it(tmp_path: Path) -> None:
    # The request sent again 200 ms later with the same sequence number: Wireshark's TCP gives the retransmission
    # to no dissector, so the answer pairs with the first (210 ms), not with a second request.
    writer = NetWriter(tmp_path / "again.pcap")
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.000)
    writer._seq[(40001, 4001)] -= len(SCENARIO_REQUEST)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.200)
    writer.tcp(False, 40001, 4001, SCENARIO_1, 1.210)
    writer.close()
    pcap = tmp_path / "again.pcap"
    assert run_cli(["--tcp-port", "4001", *ATV71, str(pcap)]) == (
        0, lines((1, "0.000000", REQUEST), (2, "0.210000", ANSWER_1.replace("10.0 ms", "210.0 ms"))),
        f"vw3-decode: warning: {pcap}: 1 packet carried no Modbus RTU bytes on TCP port 4001: skipped "
        "(1 TCP retransmissions)\n")
    done = run_tshark(pcap, "-o", "vw3.tcp_port:4001", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                      "-e", "vw3.kind", "-e", "vw3.request_frame", "-e", "vw3.response_time")
    assert done.stdout.splitlines() == ["1|1||", "2|||", "3|2|1|0.210000000"]


def test_a_random_session_cut_into_segments_reads_as_the_plugin_reads_it(tmp_path: Path) -> None:
    # Every function code, exceptions, noise and bad CRCs (lua_session), each frame cut into segments of 1 to 40
    # bytes, with empty segments and DNS datagrams between: every item, its fields, registers, pairing (by the
    # packet it is shown in), warnings and notes as the plugin shows them (lua_compare.compare).
    from lua_compare import compare
    from lua_harness import lua_items, place_items
    from lua_session import SessionBuilder

    rng = random.Random(13)
    writer = NetWriter(tmp_path / "cut.pcap")
    lengths = []  # each packet's payload on the RTU port (0: none), to place vw3-decode's items in packets
    for index, (data, time) in enumerate(SessionBuilder(seed=13).session(120)):
        position = 0
        while position < len(data):
            piece = data[position : position + rng.randint(1, 40)]
            writer.tcp(index % 2 == 0, 40001, 5020, piece, time + position * 0.0001)
            lengths.append(len(piece))
            position += len(piece)
            if rng.random() < 0.1:
                writer.tcp(index % 2 == 1, 40001, 5020, b"", time + position * 0.0001)
                writer.udp(True, 5353, 53, bytes(12), time + position * 0.0001)
                lengths += [0, 0]
    writer.close()
    status, out, err = run_cli(["--tcp-port", "5020", "--json", str(tmp_path / "cut.pcap")])
    pairs = lengths.count(0) // 2
    assert (status, err) == (0, f"vw3-decode: warning: {tmp_path / 'cut.pcap'}: {2 * pairs} packets carried no Modbus "
                             f"RTU bytes on TCP port 5020: skipped ({pairs} TCP without payload, {pairs} other ports)\n")
    ours = place_items([json.loads(line) for line in out.splitlines()], lengths)
    theirs, _, _ = lua_items(tmp_path / "cut.pcap", "-o", "vw3.tcp_port:5020", header=54)
    assert len(ours) > 200
    differences = compare(ours, theirs)
    assert not differences, "\n".join(differences[:40])


def test_a_port_out_of_range_is_refused(tmp_path: Path) -> None:
    pcap = gateway(tmp_path / "gateway.pcap")
    assert run_cli(["--tcp-port", "70000", str(pcap)]) == (
        2, "", "vw3-decode: argument --tcp-port: '70000' is not a port (0..65535) (see vw3-decode --help)\n")
    assert run_cli(["--udp-port", "x", str(pcap)]) == (
        2, "", "vw3-decode: argument --udp-port: 'x' is not a port (0..65535) (see vw3-decode --help)\n")


def test_packets_off_the_ports_do_not_extend_the_capture(tmp_path: Path) -> None:
    # A request, then a DNS datagram 2 s later: the plugin never sees the datagram, so the capture of the bus ends
    # with the request (not known whether it was answered), not 2 s after it (no response); pcap and pcapng alike.
    writer = NetWriter(tmp_path / "end.pcap")
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.0)
    writer.udp(True, 5353, 53, bytes(12), 3.0)
    writer.close()
    subprocess.run(["editcap", "-F", "pcapng", str(tmp_path / "end.pcap"), str(tmp_path / "end.pcapng")], check=True)
    ends = "the capture ends before any response: not known whether it was answered"
    for path in (tmp_path / "end.pcap", tmp_path / "end.pcapng"):
        assert run_cli(["--tcp-port", "4001", *ATV71, str(path)])[1] == lines(
            (1, "0.000000", REQUEST.replace("(3)", f"(3) [{ends}]"))), path
    done = run_tshark(tmp_path / "end.pcap", "-o", "vw3.tcp_port:4001", "-T", "fields", "-e", "vw3.note")
    assert done.stdout.splitlines() == [ends, ""]


def test_parquet_takes_the_ports_and_a_bus_per_connection(tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    writer = NetWriter(tmp_path / "two.pcap")
    for port, time in ((40001, 1.0), (40002, 1.001)):
        writer.tcp(True, port, 5020, SCENARIO_REQUEST, time)
        writer.tcp(False, port, 5020, SCENARIO_1, time + 0.01)
    writer.close()
    pcap = tmp_path / "two.pcap"
    assert run_cli(["--tcp-port", "5020", "--parquet", str(tmp_path / "data"), str(pcap)]) == (0, (
        f"{pcap}: TCP 10.0.0.1:40001 - 10.0.0.2:5020: 2 frames, 3 registers, 0 events\n"
        f"{pcap}: TCP 10.0.0.1:40002 - 10.0.0.2:5020: 2 frames, 3 registers, 0 events\n"), "")


def test_ipv6_over_bsd_loopback(tmp_path: Path) -> None:
    # Linktype 0 (BSD loopback: the address family in the writer's byte order, 30 for IPv6 on macOS), IPv6, TCP.
    from dissector.render.pcapwriter import PcapWriter

    def packet(to_server: bool, payload: bytes, seq: int) -> bytes:
        ports = (40001, 4001) if to_server else (4001, 40001)
        tcp = struct.pack("!HHIIBBHHH", *ports, seq, 0, 5 << 4, 0x18, 8192, 0, 0) + payload
        ends = (bytes(15) + b"\x01", bytes(15) + b"\x02")
        ip = struct.pack("!IHBB", 6 << 28, len(tcp), 6, 64) + b"".join(ends if to_server else ends[::-1])
        return struct.pack("<I", 30) + ip + tcp

    with (tmp_path / "lo.pcap").open("wb") as stream:
        writer = PcapWriter(stream, linktype=0)
        writer.write(packet(True, SCENARIO_REQUEST, 1), 1.0)
        writer.write(packet(False, SCENARIO_1, 1), 1.01)
    assert run_cli(["--tcp-port", "4001", *ATV71, str(tmp_path / "lo.pcap")]) == (
        0, lines((1, "0.000000", REQUEST), (2, "0.010000", ANSWER_1)), "")


def test_live_refuses_the_network_ports() -> None:
    """A serial line has no TCP or UDP port: --tcp-port/--udp-port with --live is refused, not ignored."""
    message = "vw3-decode: --tcp-port and --udp-port read network captures; --live reads the serial line itself\n"
    assert run_cli(["--live", "loop://", "--tcp-port", "4001"]) == (2, "", message)
    assert run_cli(["--live", "loop://", "--udp-port", "4001"]) == (2, "", message)
