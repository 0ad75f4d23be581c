"""A -w pcapng copy of a pcapng keeps each interface's if_tsresol (10^-3 s, 2^-10 s, 10^-7 s, 1 s), as
editcap and tshark -w keep it: before, the copy was written in microseconds, or nanoseconds for one finer
or not held by microseconds (2^-10 s), and the copy's time column showed 6 or 9 decimals where its input
showed 3. A 2^-n tick is the one its nanoseconds were cut from (167/1024 s: editcap 4.0.17 writes 166).
A pcap copy cannot hold such a resolution: said once on standard error."""
from __future__ import annotations

import struct
import subprocess
from pathlib import Path

import pytest

from helpers import rtu, run_cli
from lua_harness import ensure_tool
from test_time_precision import START, _block

REQUEST, ANSWER = rtu("01 03 0000 0001"), rtu("01 03 02 0007")


def pcapng(path: Path, interfaces: list[int], packets: list[tuple[int, int, bytes]]) -> Path:
    """A pcapng of serial interfaces with these if_tsresol bytes, its packets (interface, ticks, bytes)."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    for number, resolution in enumerate(interfaces):
        name = f"bus{number}".encode()
        out += _block(1, struct.pack("<HHI", 147, 0, 0) + struct.pack("<HH", 2, len(name)) + name + b"\0" * (-len(name) % 4)
                      + struct.pack("<HHB3x", 9, 1, resolution) + b"\0" * 4)
    for interface, ticks, data in packets:
        out += _block(6, struct.pack("<IIIII", interface, ticks >> 32, ticks & 0xFFFFFFFF, len(data), len(data)) + data)
    path.write_bytes(out)
    return path


def blocks(path: Path) -> tuple[list[int | None], list[tuple[int, int]]]:
    """The copy's interfaces' if_tsresol (None: none given) and its packets' (interface, ticks)."""
    data, position = path.read_bytes(), 0
    resolutions: list[int | None] = []
    packets = []
    while position < len(data):
        kind, total = struct.unpack_from("<II", data, position)
        body = data[position + 8 : position + total - 4]
        if kind == 1:
            resolutions.append(None)
            option = 8
            while option + 4 <= len(body):
                code, length = struct.unpack_from("<HH", body, option)
                if code == 9:
                    resolutions[-1] = body[option + 4]
                option += 4 + length + (-length % 4)
        elif kind == 6:
            interface, high, low = struct.unpack_from("<III", body)
            packets.append((interface, high << 32 | low))
        position += total
    return resolutions, packets


def copy(original: Path, written: Path, *options: str) -> tuple[str, str]:
    status, out, err = run_cli(["-n", str(original), "-w", str(written), *options])
    assert status == 0, err
    return out, err


def summary(path: Path) -> list[str]:
    status, out, err = run_cli(["-n", str(path)])
    assert (status, err) == (0, "")
    return out.splitlines()


@pytest.mark.parametrize("resolution", [0x80 | 10, 3, 7, 0, 0x80 | 30])
def test_pcapng_copy_keeps_its_resolution(tmp_path: Path, resolution: int) -> None:
    units = 2 ** (resolution & 0x7F) if resolution & 0x80 else 10**resolution
    ticks = [START * units + units // 7, START * units + units // 7 + units // 60 + 1]
    original = pcapng(tmp_path / "in.pcapng", [resolution], [(0, ticks[0], REQUEST), (0, ticks[1], ANSWER)])
    written = tmp_path / "copy.pcapng"
    assert copy(original, written)[1] == ""
    # its resolution, the input's ticks (was if_tsresol 9 or none, ticks in ns or us)
    assert blocks(written) == ([resolution], [(0, ticks[0]), (0, ticks[1])])
    assert summary(written) == summary(original)


def test_interfaces_keep_their_own(tmp_path: Path) -> None:
    """Two buses, one in ms, one in ns: each copied interface keeps its own (was both 9)."""
    original = pcapng(tmp_path / "two.pcapng", [3, 9], [
        (0, START * 1000 + 5, REQUEST), (1, START * 10**9 + 7_000_001, REQUEST),
        (0, START * 1000 + 17, ANSWER), (1, START * 10**9 + 19_000_123, ANSWER)])
    written = tmp_path / "copy.pcapng"
    assert copy(original, written)[1] == ""
    resolutions, packets = blocks(written)
    assert resolutions == [3, 9]
    assert sorted(packets) == [(0, START * 1000 + 5), (0, START * 1000 + 17),
                               (1, START * 10**9 + 7_000_001), (1, START * 10**9 + 19_000_123)]
    assert [line for line in summary(written) if "==>" not in line] == \
        [line for line in summary(original) if "==>" not in line]


def test_a_ring_file_keeps_it(tmp_path: Path) -> None:
    """Each file of a ring buffer describes the interface anew, its resolution with it."""
    packets = [(0, START * 1024 + 1024 * 2 * n + 3, REQUEST if n % 2 == 0 else ANSWER) for n in range(4)]
    original = pcapng(tmp_path / "b10.pcapng", [0x80 | 10], packets)
    assert copy(original, tmp_path / "ring.pcapng", "-b", "duration:3")[1] == ""
    files = sorted(tmp_path.glob("ring_*.pcapng"))
    assert len(files) == 2 and all(blocks(path)[0] == [0x80 | 10] for path in files)
    assert [ticks for path in files for _interface, ticks in blocks(path)[1]] == [ticks for _i, ticks, _d in packets]


def test_pcap_copy_says_what_it_cannot_keep(tmp_path: Path) -> None:
    original = pcapng(tmp_path / "b10.pcapng", [0x80 | 10], [(0, START * 1024 + 146, REQUEST),
                                                           (0, START * 1024 + 167, ANSWER)])
    written = tmp_path / "copy.pcap"
    assert copy(original, written)[1] == (
        f"vw3-decode: warning: -w {written}: pcap cannot hold the time resolution of {original} (if_tsresol "
        "2^-10 s): its times are written in nanoseconds (write pcapng, -F pcapng, to keep it)\n")
    assert written.read_bytes()[:4] == bytes.fromhex("4d3cb2a1")
    ms = pcapng(tmp_path / "ms.pcapng", [3], [(0, START * 1000 + 146, REQUEST)])
    # once a run; a microsecond pcapng into a microsecond pcap: nothing to say
    assert copy(ms, tmp_path / "ms.pcap")[1].count("cannot hold the time resolution") == 1
    us = pcapng(tmp_path / "us.pcapng", [6], [(0, START * 10**6 + 146, REQUEST)])
    assert copy(us, tmp_path / "us.pcap")[1] == ""


@pytest.mark.parametrize("resolution", [3, 7, 0])
def test_as_editcap(tmp_path: Path, resolution: int) -> None:
    """Where editcap keeps a tick exactly (decimal resolutions), the copy is its copy, block for block."""
    ensure_tool("editcap", "wireshark-common")  # (a missing tool fails, never skips)
    units = 10**resolution
    ticks = [START * units + units // 7, START * units + units // 7 + units // 60 + 1]
    original = pcapng(tmp_path / "in.pcapng", [resolution], [(0, ticks[0], REQUEST), (0, ticks[1], ANSWER)])
    theirs = tmp_path / "editcap.pcapng"
    subprocess.run(["editcap", str(original), str(theirs)], check=True, capture_output=True)
    ours = tmp_path / "copy.pcapng"
    copy(original, ours)
    assert blocks(ours) == blocks(theirs)
