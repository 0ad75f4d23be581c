"""A serial bus of a pcapng whose packets come from several interfaces (two serial lines, a serial line beside an
Ethernet tap) has tshark's time columns for the same packets: -t r and time_relative count from the capture's
first packet, any interface's (frame.time_relative), -t d and time_delta from the packet captured before the
item's first, any interface's (frame.time_delta). Before, each bus counted from its own items: every bus's first
request showed 0.000000 where tshark shows 0.001000 or 0.003000. -V's Arrival time says what its seconds count
from: `since the first packet` where it is the capture's first packet (a network capture's, a several-interface
pcapng's: tshark -V's `Time since reference or first frame`), `since the first item` where it is the first item."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from helpers import run_cli, use_engine
from lua_harness import ensure_tool
from lua_net import NetWriter
from seed_frames import SCENARIO_1, SCENARIO_REQUEST

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "unit"))  # (collected alone, it is not on the path)
from test_pcapng_other_links import _pcapng  # noqa: E402

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER_A = bytes.fromhex("0C030680000003000217E4")
ANSWER_B = bytes.fromhex("0C0306000100020003A5E4")
ETHERNET = bytes(60)
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


# Two serial interfaces and an Ethernet one (its packets first and between): bus 0's answer split over packets 4
# and 6, bus 1's answer between them.
THREE = ([147, 147, 1], [(2, 0, ETHERNET), (0, 1000, REQUEST), (1, 3000, REQUEST), (0, 10_000, ANSWER_A[:5]),
                         (1, 11_000, ANSWER_B), (0, 12_000, ANSWER_A[5:]), (2, 20_000, ETHERNET),
                         (0, 30_000, REQUEST)])
THREE_PACKETS = ["2", "4", "8", "3", "5"]  # each item's first packet, bus by bus
# One serial interface beside an Ethernet one: one input (no title).
BESIDE = ([147, 1], [(1, 0, ETHERNET), (0, 1000, REQUEST), (1, 5000, ETHERNET), (0, 10_000, ANSWER_B)])


def _write(tmp_path: Path, name: str, capture: tuple[list[int], list[tuple[int, int, bytes]]]) -> Path:
    path = tmp_path / name
    path.write_bytes(_pcapng(*capture))
    return path


def _column(path: Path, *options: str) -> list[str]:
    out = run_cli([*options, str(path)])[1]
    return [line if line.startswith("==>") else line[8:19].strip() for line in out.splitlines()]


def _tsharks(path: Path) -> dict[str, str]:
    """tshark's frame.time_relative and frame.time_delta by frame number, tab-separated (no plugin needed)."""
    done = subprocess.run([ensure_tool("tshark", "tshark"), "-n", "-r", str(path), "-T", "fields", "-e",
                           "frame.number", "-e", "frame.time_relative", "-e", "frame.time_delta"],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return {row.split("\t")[0]: "\t".join(row.split("\t")[1:]) for row in done.stdout.splitlines()}


@BOTH
def test_two_serial_interfaces_count_every_packet(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                  pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = _write(tmp_path, "three.pcapng", THREE)
    one, two = f"==> {path}: interface 0 <==", f"==> {path}: interface 1 <=="
    assert _column(path, "-t", "r") == [one, "0.001000", "0.010000", "0.030000", two, "0.003000", "0.011000"]
    assert _column(path, "-t", "d") == [one, "0.001000", "0.007000", "0.010000", two, "0.002000", "0.001000"]
    assert _column(path, "-t", "dd") == [one, "0.000000", "0.009000", "0.020000", two, "0.000000", "0.008000"]
    fields = run_cli(["-T", "fields", "-e", "time_relative", "-e", "time_delta", str(path)])[1]
    theirs = _tsharks(path)
    assert fields.splitlines() == [theirs[packet] for packet in THREE_PACKETS]
    assert fields.splitlines()[:2] == ["0.001000000\t0.001000000", "0.010000000\t0.007000000"]
    out = run_cli(["-Y", "time_delta > 0.0015 && time_relative < 0.02", str(path)])[1]
    assert [line[:19] for line in out.splitlines()] == [one[:19], "     2     0.010000", two[:19],
                                                        "     1     0.003000"]


@BOTH
def test_a_serial_interface_beside_ethernet_counts_its_packets(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = _write(tmp_path, "beside.pcapng", BESIDE)
    assert _column(path, "-t", "r") == ["0.001000", "0.010000"]
    assert _column(path, "-t", "d") == ["0.001000", "0.005000"]
    fields = run_cli(["-T", "fields", "-e", "time_relative", "-e", "time_delta", str(path)])[1]
    theirs = _tsharks(path)
    assert fields.splitlines() == [theirs["2"], theirs["4"]] == ["0.001000000\t0.001000000",
                                                                 "0.010000000\t0.005000000"]


@BOTH
def test_detail_says_what_its_seconds_count_from(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                 pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = _write(tmp_path, "three.pcapng", THREE)
    out = run_cli(["-V", str(path)])[1]
    assert [line for line in out.splitlines() if "Arrival" in line][:2] == [
        "    Arrival time: 2026-01-01 00:00:00.001000 UTC (0.001000 s since the first packet)",
        "    Arrival time: 2026-01-01 00:00:00.010000 UTC (0.010000 s since the first packet)"]
    pcap = tmp_path / "net.pcap"
    writer = NetWriter(pcap)
    writer._write(bytes(28), 0.9)  # (not IP: a packet all the same, tshark's first frame)
    writer.tcp(True, 40001, 4001, SCENARIO_REQUEST, 1.000)
    writer.tcp(False, 40001, 4001, SCENARIO_1, 1.010)
    writer.close()
    out = run_cli(["--tcp-port", "4001", "-V", str(pcap)])[1]
    assert [line for line in out.splitlines() if "Arrival" in line] == [
        "    Arrival time: 1970-01-01 00:00:01.000000 UTC (0.100000 s since the first packet)",
        "    Arrival time: 1970-01-01 00:00:01.010000 UTC (0.110000 s since the first packet)"]
    # (one serial interface: the first item is the base, as the time column's)
    alone = _write(tmp_path, "alone.pcapng", ([147], [(0, 1000, REQUEST), (0, 10_000, ANSWER_B)]))
    out = run_cli(["-V", str(alone)])[1]
    assert [line for line in out.splitlines() if "Arrival" in line] == [
        "    Arrival time: 2026-01-01 00:00:00.001000 UTC (0.000000 s since the first item)",
        "    Arrival time: 2026-01-01 00:00:00.010000 UTC (0.009000 s since the first item)"]
