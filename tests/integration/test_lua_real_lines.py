"""Issue 26 in the plugin: what a real RS-485 tap records, framed as vw3-decode frames it. Real tshark
with lua/vw3.lua against `vw3-decode --json` on the same pcap, item by item (lua_compare), and the
frames each case must give."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from lua_compare import compare, lua_kind, lua_shown
from lua_harness import lua_items, python_items, write_pcap

from dissector.protocol.crc import with_crc

GLITCHED = bytes.fromhex(
    "01 03 03 E8 00 02 44 7B 00 01 03 04 52 66 57 07 75 66 FE "
    "01 03 03 EA 00 02 E5 BB 00 01 03 04 A4 71 46 2C BA A5 FE"
)


def rtu(hex_text: str) -> bytes:
    return with_crc(bytes.fromhex(hex_text))


def both(path: Path, records: list[bytes]) -> list[tuple[str, str]]:
    """Decode the records (1 ms apart) with vw3-decode and the plugin; both must agree item by item.
    Returns the items as (kind, raw hex) from vw3-decode."""
    pcap = write_pcap(path, [(data, 1_700_000_000 + index * 0.001) for index, data in enumerate(records)])
    python = python_items(pcap, [])
    lua, _, _ = lua_items(pcap)
    # (FC43 object strings of random bytes: tshark's PDML escapes control bytes its own way; framing is
    # what is compared here)
    differences = compare(python, lua, ignore=frozenset({"objects"}))
    assert not differences, "\n".join(differences[:40])
    assert len([item for item in lua_shown(lua) if lua_kind(item) != "noise"]) == len(
        [item for item in python if item.data["kind"] != "noise"])
    return [(item.data["kind"], item.data["raw"]) for item in python]


def test_turn_around_glitches_one_record_and_random_bursts(tmp_path: Path) -> None:
    items = both(tmp_path / "one.pcap", [GLITCHED])
    assert [kind for kind, _ in items] == ["request", "noise", "response", "noise"] * 2
    stream = GLITCHED * 10
    rng = random.Random(26)
    cuts = sorted(rng.sample(range(1, len(stream)), 40))
    items = both(tmp_path / "bursts.pcap", [stream[a:b] for a, b in zip([0, *cuts], [*cuts, len(stream)])])
    assert [kind for kind, _ in items].count("request") == 20
    assert [kind for kind, _ in items].count("response") == 20


def test_glitches_of_every_shape_on_both_sides_with_damage(tmp_path: Path) -> None:
    rng = random.Random(7)
    glitches = [(0xFF << k) & 0xFF for k in range(9)]
    stream = bytearray()
    for index in range(60):
        request = rtu(f"{1 + index % 3:02X} 03 {index:04X} 0002")
        response = rtu(f"{1 + index % 3:02X} 03 04 {index:04X} {2 * index:04X}")
        if index % 9 == 4:
            response = response[:5] + bytes([response[5] ^ 0x10]) + response[6:]  # damaged
        for frame in (request, response):
            if rng.random() < 0.3:
                stream.append(rng.choice(glitches))
            stream += frame + bytes(rng.choice(glitches) for _ in range(rng.choice([1, 1, 2])))
    cuts = sorted(rng.sample(range(1, len(stream)), 80))
    items = both(tmp_path / "glitches.pcap", [bytes(stream[a:b]) for a, b in zip([0, *cuts], [*cuts, len(stream)])])
    assert [kind for kind, _ in items].count("request") == 60


def test_the_reproductions_of_the_issue(tmp_path: Path) -> None:
    # A CRC-valid FC16 request whose byte count disagrees with its quantity, answered by exception 03.
    items = both(tmp_path / "fc16.pcap", [bytes.fromhex("01 10 18 70 00 02 03 C4 00 17 70 D8 6F"),
                                          bytes.fromhex("01 90 03 0C 01")])
    assert [kind for kind, _ in items] == ["request", "exception"]
    # A response cut by the end of the capture: noise, no invented request.
    items = both(tmp_path / "cut.pcap", [bytes.fromhex("14 04 00 34 00 02 32 C0"),
                                         bytes.fromhex("14 04 04 14 00 00 FA 7D")])
    assert items == [("request", "14040034000232c0"), ("noise", "1404041400 00fa7d".replace(" ", ""))]
    # A good frame, then garbage in the same record, after a noise record.
    items = both(tmp_path / "garbage.pcap", [bytes.fromhex("55 12"), bytes.fromhex("11 03 00 6B 00 03 76 87 20 54 54 FF")])
    assert items[1:] == [("request", "1103006b00037687"), ("noise", "205454ff")]
    # A good request after noise, its answer damaged.
    answer = bytearray(rtu("05 06 0100 1234"))
    answer[4] ^= 0x40
    items = both(tmp_path / "damaged.pcap", [bytes.fromhex("47 A1 33") + rtu("05 06 0100 1234") + bytes(answer)])
    assert [kind for kind, _ in items] == ["noise", "request", "response"]
    # Reserved addresses.
    items = both(tmp_path / "reserved.pcap", [rtu("FE 03 0000 0001"), rtu("FE 03 02 0007"), rtu("FF 03 0000 0001")])
    assert [kind for kind, _ in items] == ["request", "response", "request"]


@pytest.mark.parametrize("kind", ["glitch after", "glitches both sides", "breaks", "truncated last frame"])
def test_real_line_noise_of_every_kind_in_random_reads(tmp_path: Path, kind: str) -> None:
    """Every function code, vendor codes and FC8 echoes (CRC scans) over a line with real-line noise
    (dissector/sim/line.py), delivered as a USB adapter's random reads: the plugin as vw3-decode."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
    import noise_accuracy

    from dissector.sim.line import on_the_line

    rng = random.Random(len(kind))
    requests: list[bool] = []
    frames = noise_accuracy.session(rng, 300, noise_accuracy.BUS, requests)
    line = on_the_line(frames, requests, kind, rng)
    stream = line.stream
    cuts = sorted(rng.sample(range(1, len(stream)), len(stream) // 40))
    items = both(tmp_path / "line.pcap", [stream[a:b] for a, b in zip([0, *cuts], [*cuts, len(stream)])])
    found = {raw for item_kind, raw in items if item_kind != "noise"}
    assert sum(frame.hex() in found for _offset, frame in line.frames) >= 0.99 * len(line.frames)


def test_the_wizmodbus_line_as_a_pcap_of_reads(tmp_path: Path) -> None:
    """The real RS-485 line of tests/corpus (a glitch byte after every frame): the plugin finds the 88
    frames of the node's RX and TX channels, as vw3-decode does, in the line's own bursts and in reads
    cut anywhere."""
    corpus = Path(__file__).resolve().parents[1] / "corpus"

    def recs(name: str) -> list[bytes]:
        return [bytes.fromhex(line.partition(" ")[2]) for line in (corpus / name).read_text().splitlines()]

    sides = [data.hex() for data in recs("wizmodbus_rxtx.records")]
    bus = recs("wizmodbus_bus.records")
    items = both(tmp_path / "bus.pcap", bus)
    assert [raw for kind, raw in items if kind != "noise"] == sides
    stream = b"".join(bus)
    rng = random.Random(88)
    cuts = sorted(rng.sample(range(1, len(stream)), 150))
    items = both(tmp_path / "reads.pcap", [stream[a:b] for a, b in zip([0, *cuts], [*cuts, len(stream)])])
    assert [raw for kind, raw in items if kind != "noise"] == sides


def test_ascii_lines_that_lost_their_cr_and_reserved_addresses(tmp_path: Path) -> None:
    def ascii_frame(hex_text: str) -> bytes:
        from dissector.protocol.crc import lrc

        binary = bytes.fromhex(hex_text)
        return b":" + (binary + bytes([lrc(binary)])).hex().upper().encode() + b"\r\n"

    lines = [ascii_frame("01 03 00 00 00 02"), ascii_frame("01 03 04 00 0A 00 14"),
             ascii_frame("F8 03 20 D0 00 03"), ascii_frame("F8 03 06 00 01 00 02 00 03")]
    records = [line.replace(b"\r", b"") for line in lines[:2]] + lines[2:]
    items = both(tmp_path / "ascii.pcap", records)
    assert [kind for kind, _ in items] == ["request", "response", "request", "response"]
