"""A gateway capture of many TCP connections (a master that connects once per poll): each connection is a bus
(sources/ethernet.py), and reading one bus parses its own span of the file's records alone, not the whole file
again: 1,600 connections of one poll each took 417 s (every bus parsed every record, each looking its
connection up in a list), 1.4 s now."""
from __future__ import annotations

from pathlib import Path

import dissector.sources.ethernet as ethernet
from helpers import run_cli
from lua_net import NetWriter
from seed_frames import SCENARIO_1, SCENARIO_REQUEST

REQUEST = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
ANSWER = ("12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) "
          "COP=Cd (command) [#1, 10.0 ms]  CRC ok")


def polled(index: int, request: str, answer: str) -> str:
    """The `index`-th connection's poll, 100 ms after the one before: its times from the capture's first packet,
    as tshark's frame.time_relative (each bus counted from its own first item before)."""
    return f"     1  {index / 10:11.6f}  {request}\n     2  {index / 10 + 0.01:11.6f}  {answer}\n"


def polls_capture(path: Path, count: int, first_port: int = 40000) -> Path:
    """`count` connections of one poll each (a request and SCENARIO_1's answer 10 ms later), 100 ms apart, each
    from its own port from `first_port` up; a .pcapng `path` converted by editcap from the pcap beside it."""
    pcap = path.with_suffix(".pcap")
    writer = NetWriter(pcap)
    for index in range(count):
        writer.tcp(True, first_port + index, 4001, SCENARIO_REQUEST, 1.0 + index / 10)
        writer.tcp(False, first_port + index, 4001, SCENARIO_1, 1.01 + index / 10)
    writer.close()
    if path.suffix == ".pcapng":
        import subprocess

        subprocess.run(["editcap", "-F", "pcapng", str(pcap), str(path)], check=True)
    return path


def test_each_connection_bus_parses_its_own_records_alone(tmp_path: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    pcap = polls_capture(tmp_path / "polls.pcap", 40)
    parsed = []
    segment = ethernet.segment
    monkeypatch.setattr(ethernet, "segment", lambda *args: parsed.append(1) or segment(*args))
    assert run_cli(["--tcp-port", "4001", "--profile", "atv71", str(pcap)]) == (0, "".join(
        f"==> {pcap}: TCP 10.0.0.1:{40000 + index} - 10.0.0.2:4001 <==\n"
        + polled(index, REQUEST, ANSWER) for index in range(40)), "")
    # The scan for the connections and the first bus read the 80 records; each later bus its own 2 (before:
    # 80 records a bus, 3,280 in all).
    assert len(parsed) == 80 + 80 + 39 * 2


def test_each_connection_has_devices_of_its_own(tmp_path: Path) -> None:
    # Two connections, one poll each: the second's bus started with the first's devices (profile auto had seen
    # the first's poll and named the second's registers: CHCF=IO), as a pcapng's interfaces did not.
    pcap = polls_capture(tmp_path / "two.pcap", 2, 40001)
    answer = "12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#1, 10.0 ms]  CRC ok"
    assert run_cli(["--tcp-port", "4001", str(pcap)]) == (0, "".join(
        f"==> {pcap}: TCP 10.0.0.1:{40001 + index} - 10.0.0.2:4001 <==\n"
        + polled(index, REQUEST, answer) for index in range(2)), "")


def test_a_connection_warning_names_its_bus(tmp_path: Path) -> None:
    # The second connection's answer captured in part (its IPv4 length 4 bytes more than its packet holds): the
    # warning numbered the record without saying whose bus it was in, as a pcapng interface's warning says.
    import struct
    import subprocess

    pcap = tmp_path / "part.pcap"
    writer = NetWriter(pcap)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.0)
    writer.tcp(True, 40002, 4001, SCENARIO_REQUEST, 1.001)
    writer.tcp(False, 40001, 4001, SCENARIO_1, 1.01)
    whole = writer._ip
    writer._ip = lambda *parts: (lambda ip: ip[:2] + struct.pack("!H", len(ip) + 4) + ip[4:])(whole(*parts))
    writer.tcp(False, 40002, 4001, SCENARIO_1, 1.011)
    writer.close()
    subprocess.run(["editcap", "-F", "pcapng", str(pcap), str(tmp_path / "part.pcapng")], check=True)
    for path in (pcap, tmp_path / "part.pcapng"):
        assert run_cli(["--tcp-port", "4001", str(path)])[2] == (
            f"vw3-decode: warning: {path}: TCP 10.0.0.1:40002 - 10.0.0.2:4001: record 4: only 11 of its 15 payload "
            "bytes were captured\n")


def test_a_pcapng_of_many_connections_reads_each_bus_over_its_span(tmp_path: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    # As a pcap: each later bus passes over the packet blocks before its first unread (a pcapng cannot be entered
    # in the middle: its interfaces come first) and stops after its last; the interfaces sought for the line's
    # speed (first_interface) read no packet. Before, 6,716 packet blocks were read for 80 packets, 396 now.
    import dissector.sources.pcapng as pcapng

    polls_capture(tmp_path / "polls.pcapng", 40)
    packets = []
    packet = pcapng._Reader._packet
    monkeypatch.setattr(pcapng._Reader, "_packet", lambda *args: packets.append(1) or packet(*args))
    answer = ANSWER.replace("8400=non-existent CHCF=IO (I/O profile) COP=Cd (command)", "8400=32768 8401=3 8402=2")
    assert run_cli(["--tcp-port", "4001", str(tmp_path / "polls.pcapng")]) == (0, "".join(
        f"==> {tmp_path / 'polls.pcapng'}: TCP 10.0.0.1:{40000 + index} - 10.0.0.2:4001 <==\n"
        + polled(index, REQUEST, answer) for index in range(40)), "")
    assert len(packets) < 3 * 80 + 40 * 6  # (the scan, the first bus, a later bus's 2 packets read 3 times)


def test_a_compressed_capture_of_two_connections_is_two_buses(tmp_path: Path) -> None:
    # capture.pcap.gz (tshark reads it as the pcap): its connections were one stream, with the warning meant for
    # standard input ('save standard input to a file'), though it is a file.
    import gzip

    pcap = polls_capture(tmp_path / "two.pcap", 2, 40001)
    packed = tmp_path / "two.pcap.gz"
    packed.write_bytes(gzip.compress(pcap.read_bytes()))
    assert run_cli(["--tcp-port", "4001", *["--profile", "atv71"], str(packed)]) == (0, "".join(
        f"==> {packed}: TCP 10.0.0.1:{40001 + index} - 10.0.0.2:4001 <==\n"
        + polled(index, REQUEST, ANSWER) for index in range(2)), "")


def test_a_pcapng_bus_goes_straight_to_its_span(tmp_path: Path, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    # 1,600 one-poll connections took 21.8 s as a pcapng, 1.4 s as the same pcap: each bus walked the file's blocks
    # again (sources/interfaces.py _walk), read its head for the line's speed (pcapng.first_interface: no serial
    # interface to stop at) and passed over every packet block before its span one by one, where a pcap's seeks.
    import dissector.sources.interfaces as interfaces
    import dissector.sources.pcapng as pcapng

    path = polls_capture(tmp_path / "polls.pcapng", 40)
    blocks, walks, heads = [], [], []
    trailer, walk, head = pcapng._Reader._trailer, interfaces._walk, pcapng.first_interface_of
    monkeypatch.setattr(pcapng._Reader, "_trailer", lambda *args: blocks.append(1) or trailer(*args))
    monkeypatch.setattr(interfaces, "_walk", lambda *args: walks.append(1) or walk(*args))
    monkeypatch.setattr(pcapng, "first_interface_of", lambda *args: heads.append(1) or head(*args))
    status, out, _err = run_cli(["--tcp-port", "4001", str(path)])
    assert status == 0 and out.count(" response ") == 40
    # The scan and the first bus (twice: profile auto's first look) read the file's 82 blocks; each later bus, opened
    # twice, at most 5 blocks each time: its SHB, IDB, 2 packets and the one after. Before: 6,880 blocks, 81 walks,
    # 40 heads read (562 blocks now).
    assert (len(walks), len(heads)) == (1, 1)
    assert len(blocks) <= 3 * 82 + 39 * 2 * 5
