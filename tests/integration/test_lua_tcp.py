"""RTU carried over TCP and UDP by serial gateways (real tshark): state per connection, TCP reassembly of
frames split over segments, the UDP port preference and Decode As, and no Lua error on TCP streams cut
at random."""
from __future__ import annotations

import random
from pathlib import Path

from lua_harness import lua_errors, run_tshark
from lua_net import NetWriter
from lua_session import SessionBuilder
from seed_frames import SCENARIO_1, SCENARIO_REQUEST


# The ATV71 named: one answer is no evidence for profile auto (issue 26), and these captures have one.
ATV71 = ("-o", "vw3.profiles:atv71")


def _rows(pcap: Path, *args: str) -> list[list[str]]:
    result = run_tshark(pcap, *args, "-T", "fields", "-E", "separator=|", "-e", "frame.number", "-e", "vw3.kind",
                        "-e", "vw3.request_frame", "-e", "vw3.reg.code", "-e", "vw3.note")
    assert result.returncode == 0, result.stderr
    assert not lua_errors(result.stdout + result.stderr)
    return [line.split("|") for line in result.stdout.splitlines()]


def test_two_connections_keep_their_own_pairing_and_split_frames_are_reassembled(tmp_path: Path) -> None:
    # Two masters poll the same gateway port; their requests and responses interleave, and the
    # responses arrive in two segments each (a USB-serial gateway forwarding each read).
    writer = NetWriter(tmp_path / "two.pcap")
    writer.tcp(True, 40001, 5020, SCENARIO_REQUEST, 1.000)
    writer.tcp(True, 40002, 5020, SCENARIO_REQUEST, 1.001)
    writer.tcp(False, 40002, 5020, SCENARIO_1[:5], 1.010)
    writer.tcp(False, 40001, 5020, SCENARIO_1[:3], 1.011)
    writer.tcp(False, 40002, 5020, SCENARIO_1[5:], 1.012)
    writer.tcp(False, 40001, 5020, SCENARIO_1[3:], 1.013)
    writer.close()
    rows = _rows(tmp_path / "two.pcap", "-o", "vw3.tcp_port:5020", *ATV71)
    # Each response is shown once, reassembled, in the segment that completes it, and answers the
    # request of its own connection (frame 2 for port 40002, frame 1 for port 40001).
    shown = [(row[0], row[1], row[2], row[3]) for row in rows if row[1]]
    assert shown == [("1", "1", "", ""), ("2", "1", "", ""), ("5", "2", "2", ",CHCF,COP"), ("6", "2", "1", ",CHCF,COP")]
    assert not any("without a matching request" in row[4] for row in rows)
    # The same by Decode As.
    assert _rows(tmp_path / "two.pcap", "-d", "tcp.port==5020,vw3", *ATV71) == rows


def test_udp_port_preference_and_decode_as(tmp_path: Path) -> None:
    writer = NetWriter(tmp_path / "udp.pcap")
    writer.udp(True, 40001, 5021, SCENARIO_REQUEST, 1.0)
    writer.udp(False, 40001, 5021, SCENARIO_1, 1.01)
    writer.close()
    expected = [["1", "1", "", "", ""], ["2", "2", "1", ",CHCF,COP", ""]]
    assert _rows(tmp_path / "udp.pcap", "-o", "vw3.udp_port:5021", *ATV71) == expected
    assert _rows(tmp_path / "udp.pcap", "-d", "udp.port==5021,vw3", *ATV71) == expected
    assert [row[1] for row in _rows(tmp_path / "udp.pcap")] == ["", ""]


def test_tcp_streams_with_random_segmentation_raise_no_lua_error(tmp_path: Path) -> None:
    # A random session (every function code, exceptions, noise, bad CRCs) over three connections, each
    # direction cut into segments of 1 to 40 bytes; and the same frames found as in the whole stream.
    rng = random.Random(13)
    records = SessionBuilder(seed=13).session(600)
    writer = NetWriter(tmp_path / "cut.pcap")
    time = 1.0
    for index, (data, _time) in enumerate(records):
        port = 40001 + index % 3
        to_server = index % 2 == 0
        position = 0
        while position < len(data):
            size = rng.randint(1, 40)
            writer.tcp(to_server, port, 5020, data[position : position + size], time)
            position += size
            time += 0.001
    writer.close()
    result = run_tshark(tmp_path / "cut.pcap", "-o", "vw3.tcp_port:5020", "-V")
    assert result.returncode == 0, result.stderr
    assert not lua_errors(result.stdout + result.stderr), lua_errors(result.stdout + result.stderr)[:5]
    assert "Plugin error" not in result.stdout
    assert result.stdout.count("VW3 Modbus RTU") > 300
