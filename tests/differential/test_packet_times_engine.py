"""The compiled summary path (accel/timedpath.py) on captures whose time column counts their packets (render/timefmt.py
Clock.packets): a pcapng with packets on several interfaces (two serial lines beside an Ethernet tap) and a network
capture of Modbus RTU over TCP with packets of no bus byte between (an ARP, a DNS datagram) and answers split over
segments. -t r counts from the capture's first packet (given the engine as its first reference), -t d from the
packet before each item's first (the engine told it per chunk), -t dd from the item shown before: the engine
writes them, byte-identical to VW3_PURE_PYTHON=1. Before, such a capture's plain summary was the Python stages'
(app/paths.py: the engine wrote none of its lines), 100k polls of two serial lines 3.7 s -> 5.7 s.
"""
from __future__ import annotations

import random
import subprocess
import sys
from pathlib import Path

import pytest
from lua_net import NetWriter
from test_timed_summary import decode, frames_of

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "unit"))  # (collected alone, it is not on the path)
from test_pcapng_other_links import _pcapng  # noqa: E402

ENGINE_FORMATS = ("r", "d", "dd")
FORMATS = (*ENGINE_FORMATS, "a", "ud", "e")
ETHERNET = bytes(60)


def _pieces(rng: random.Random, frame: bytes) -> list[bytes]:
    """A frame whole, or split over two or three packets."""
    if len(frame) < 4 or rng.random() < 0.6:
        return [frame]
    cuts = sorted(rng.sample(range(1, len(frame)), rng.choice([1, 2])))
    return [frame[a:b] for a, b in zip([0, *cuts], [*cuts, len(frame)])]


def several_interfaces(tmp_path: Path, seed: int) -> Path:
    """Two serial buses' frames (some damaged) interleaved by time with each other and with Ethernet packets."""
    rng = random.Random(seed)
    packets: list[tuple[int, int, bytes]] = []
    for interface in (0, 1):
        for frame, ns in frames_of(seed * 2 + interface, 0.05)[:120]:
            micros = (ns - 1_700_000_000 * 10**9) // 1000 + interface * 777
            for k, piece in enumerate(_pieces(rng, frame)):
                packets.append((interface, micros + k * 300, piece))
    packets += [(2, rng.randrange(0, 10**8), ETHERNET) for _ in range(60)]
    packets.sort(key=lambda packet: packet[1])
    path = tmp_path / f"several{seed}.pcapng"
    path.write_bytes(_pcapng([147, 147, 1], packets))
    return path


def network(tmp_path: Path, seed: int, pcapng: bool) -> Path:
    """One connection's frames (some damaged) over TCP, some split over segments, with other packets between."""
    rng = random.Random(seed)
    path = tmp_path / f"net{seed}.pcap"
    writer = NetWriter(path)
    writer._write(bytes(28), 1_699_999_999.5)  # (not IP: tshark's first frame all the same)
    to_server = True
    for frame, ns in frames_of(seed, 0.05)[:150]:
        time = ns / 1e9
        for k, piece in enumerate(_pieces(rng, frame)):
            writer.tcp(to_server, 40001, 4001, piece, time + k * 0.0003)
        if rng.random() < 0.2:
            writer.udp(True, 5353, 53, bytes(12), time + 0.0007)
        to_server = not to_server
    writer.close()
    if not pcapng:
        return path
    subprocess.run(["editcap", "-F", "pcapng", str(path), str(tmp_path / f"net{seed}.pcapng")], check=True)
    return tmp_path / f"net{seed}.pcapng"


def _same(argv: list[str], monkeypatch: pytest.MonkeyPatch, time_format: str) -> None:
    fast, engine_lines = decode(argv, monkeypatch, pure=False)
    reference, none = decode(argv, monkeypatch, pure=True)
    assert none == 0
    assert fast == reference
    if time_format in ENGINE_FORMATS:
        assert engine_lines > 0  # (the engine wrote them: not the Python stages alone)


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("time_format", FORMATS)
def test_several_interfaces(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, seed: int, time_format: str) -> None:
    _same(["-t", time_format, str(several_interfaces(tmp_path, seed))], monkeypatch, time_format)


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("pcapng", [False, True], ids=["pcap", "pcapng"])
@pytest.mark.parametrize("time_format", FORMATS)
def test_rtu_over_tcp(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, seed: int, pcapng: bool,
                      time_format: str) -> None:
    _same(["--tcp-port", "4001", "-t", time_format, str(network(tmp_path, seed, pcapng))], monkeypatch, time_format)


def test_the_engine_writes_the_pinned_columns(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """test_several_interface_times' capture (its columns checked against tshark there), through the engine."""
    request, answer = bytes.fromhex("0C0320D000030EEF"), bytes.fromhex("0C030680000003000217E4")
    path = tmp_path / "three.pcapng"
    path.write_bytes(_pcapng([147, 147, 1], [(2, 0, ETHERNET), (0, 1000, request), (1, 3000, request),
                                             (0, 10_000, answer[:5]), (1, 11_000, answer), (0, 12_000, answer[5:]),
                                             (2, 20_000, ETHERNET), (0, 30_000, request)]))
    columns = {}
    for time_format in ENGINE_FORMATS:
        out, engine_lines = decode(["-t", time_format, str(path)], monkeypatch, pure=False)
        assert engine_lines == 4  # (bus 0's last request, unanswered at the end, is the Python stages')
        columns[time_format] = [line[8:19].strip() for line in out.splitlines() if line[:6].strip().isdigit()]
    assert columns == {"r": ["0.001000", "0.010000", "0.030000", "0.003000", "0.011000"],
                       "d": ["0.001000", "0.007000", "0.010000", "0.002000", "0.001000"],
                       "dd": ["0.000000", "0.009000", "0.020000", "0.000000", "0.008000"]}


def test_marks_forgotten_on_a_long_capture(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """More than the 4096 packet marks PacketTimes.forget keeps before it drops any, with noise and damage the
    Python stages take (a request they pair may come from before the chunks the engine keeps)."""
    rng = random.Random(5)
    packets: list[tuple[int, int, bytes]] = []
    for interface in (0, 1):
        micros = interface * 777
        for frame, _ns in [timed for k in range(12) for timed in frames_of(interface * 1000 + k, 0.03)]:
            micros += rng.choice([2000, 5000, 30000, 200000])
            packets += [(interface, micros + k * 300, piece) for k, piece in enumerate(_pieces(rng, frame))]
    assert sum(1 for interface, _micros, _data in packets if interface == 0) > 4096
    packets += [(2, rng.randrange(0, 10**9), ETHERNET) for _ in range(400)]
    packets.sort(key=lambda packet: packet[1])
    path = tmp_path / "long.pcapng"
    path.write_bytes(_pcapng([147, 147, 1], packets))
    _same(["-t", "d", str(path)], monkeypatch, "d")
