"""The time columns of a network capture are tshark's for the same packets (sources/ethernet.py PacketTimes): -t r
counts from the capture's first packet (frame.time_relative), -t d from the packet captured before the item's
first (frame.time_delta: an ARP, another port's datagram, another connection's segment are packets), -t dd from
the item shown before (time_delta_displayed of tshark -Y vw3), in every bus of the capture. Before, each bus
counted from its own first item: 0.000000 for every connection's first request, 0.100000 in tshark."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from helpers import run_cli
from lua_harness import lua_errors, run_tshark
from lua_net import NetWriter
from seed_frames import SCENARIO_1, SCENARIO_2, SCENARIO_REQUEST


@pytest.fixture(params=["pcap", "pcapng"])
def capture(tmp_path: Path, request: pytest.FixtureRequest) -> Path:
    """An ARP-like packet, two connections polling a gateway's port 4001, a DNS datagram between, the second
    connection's answer split over two segments."""
    pcap = tmp_path / "two.pcap"
    writer = NetWriter(pcap)
    writer._write(bytes(28), 0.9)  # (packet 1: not IP)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.000)  # 2
    writer.tcp(True, 40002, 4001, SCENARIO_REQUEST, 1.003)  # 3
    writer.udp(True, 5353, 53, bytes(12), 1.005)  # 4
    writer.tcp(False, 40001, 4001, SCENARIO_1, 1.010)  # 5
    writer.tcp(False, 40002, 4001, SCENARIO_1[:4], 1.014)  # 6
    writer.tcp(False, 40002, 4001, SCENARIO_1[4:], 1.016)  # 7
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.100)  # 8
    writer.tcp(False, 40001, 4001, SCENARIO_2, 1.110)  # 9
    writer.close()
    if request.param == "pcap":
        return pcap
    subprocess.run(["editcap", "-F", "pcapng", str(pcap), str(tmp_path / "two.pcapng")], check=True)
    return tmp_path / "two.pcapng"


FIRST_PACKETS = ["2", "5", "8", "9", "3", "6"]  # each item's first packet, bus by bus


def column(path: Path, *options: str) -> list[str]:
    out = run_cli(["--tcp-port", "4001", *options, str(path)])[1]
    return [line[8:19].strip() for line in out.splitlines() if not line.startswith("==>")]


def test_the_time_columns_are_tsharks(capture: Path) -> None:
    assert column(capture, "-t", "r") == ["0.100000", "0.110000", "0.200000", "0.210000", "0.103000", "0.114000"]
    assert column(capture, "-t", "d") == ["0.100000", "0.005000", "0.084000", "0.010000", "0.003000", "0.004000"]
    assert column(capture, "-t", "dd") == ["0.000000", "0.010000", "0.090000", "0.010000", "0.000000", "0.011000"]
    done = run_tshark(capture, "-o", "vw3.tcp_port:4001", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                      "-e", "frame.time_relative", "-e", "frame.time_delta")
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr)
    theirs = {row.split("|")[0]: row.split("|")[1:] for row in done.stdout.splitlines()}
    fields = run_cli(["--tcp-port", "4001", "-T", "fields", "-e", "time_relative", "-e", "time_delta", str(capture)])[1]
    assert fields.splitlines() == ["\t".join(theirs[packet]) for packet in FIRST_PACKETS]


def test_a_filter_reads_the_same_times(capture: Path) -> None:
    out = run_cli(["--tcp-port", "4001", "-Y", "time_delta < 0.0045 && time_relative > 0.11", str(capture)])[1]
    assert [line if line.startswith("==>") else line[:19] for line in out.splitlines()] == [
        f"==> {capture}: TCP 10.0.0.1:40002 - 10.0.0.2:4001 <==", "     2     0.114000"]
