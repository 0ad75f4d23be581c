"""Noise framed by the engine (dissector/accel/_noise.h, fastsummary.skip_noise): where the Python framer has a
noise run open, the engine takes the bytes its _run would take as noise, and the framer decides only where the
engine stops. The outputs stay byte for byte those of VW3_PURE_PYTHON=1 (random bytes, noise that looks like
frame starts, the answer awaited or an FC8 echo awaited through the noise, a glitchy line, noise runs cut at
4096 bytes, any split into chunks, pcap records bounding the noise, silences), and the framer weighs a few
positions a kilobyte where it weighed every one (100 KB of random bytes: 164 _match calls, 33,522 before)."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from dissector.accel import fastsummary
from dissector.framing.rtu import RtuFramer
from dissector.pipeline import Dissector
from dissector.protocol.crc import with_crc
from dissector.sim.simulate import generate_session
from test_fastsummary import Collected, assert_same, atv71, auto
from test_noise_handover import assert_same as assert_same_cli, decode
from test_timed_summary import write_pcap

READ = with_crc(bytes.fromhex("0c0320d00003"))  # read of 8400..8402 on slave 12 (an ATV71)
ANSWER = with_crc(bytes.fromhex("0c0306000000010003"))
CODES = (1, 2, 3, 4, 5, 6, 15, 16, 23)


def random_bytes(seed: int, size: int) -> bytes:
    return random.Random(seed).randbytes(size)


def near_modbus(seed: int, size: int) -> bytes:
    """A slave address and a common function code, then 0..30 random bytes, again and again."""
    rng = random.Random(seed)
    out = bytearray()
    while len(out) < size:
        out += bytes([rng.randint(1, 247), rng.choice(CODES)]) + rng.randbytes(rng.randint(0, 30))
    return bytes(out[:size])


def salted(seed: int, size: int, starts: tuple[bytes, ...]) -> bytes:
    """Random bytes with one of `starts` every few bytes: the answer awaited's slave and function (or its
    echo) where the framer weighs them, glitch bytes, codes found by a CRC scan (FC8 00 00, FC43 0E)."""
    rng = random.Random(seed)
    out = bytearray()
    while len(out) < size:
        out += rng.choice(starts) + rng.randbytes(rng.randint(0, 12))
    return bytes(out)


def polling(transactions: int, seed: int) -> bytes:
    return b"".join(data for data, _time in generate_session(transactions, seed=seed))


def glitchy_then_noise(seed: int) -> bytes:
    """A line that leaves a 00 after its frames (learnt: StreamFramer.glitchy), then noise, then traffic."""
    frames = [data for data, _time in generate_session(40, seed=seed)]
    return b"".join(frame + b"\x00" for frame in frames) + random_bytes(seed, 3000) + polling(30, seed)


STREAMS = {
    "random": lambda seed: random_bytes(seed, 30000),
    "near-modbus": lambda seed: near_modbus(seed, 30000),
    # the answer awaited after the noise: its CRC counts wherever it starts; its slave and function in the noise
    "answer-after-noise": lambda seed: READ + salted(seed, 3000, (b"\x0c\x03", b"\x0c\x83", b"\x0c\x03\x06"))
    + ANSWER + polling(20, seed),
    # an FC8 echo awaited (Return Query Data, its data repeated): the answer's reading first where the echo is
    "echo-awaited": lambda seed: with_crc(bytes.fromhex("0c0800001234"))
    + salted(seed, 3000, (b"\x0c\x08\x00\x00", b"\x0c\x08\x00\x01", b"\x0c\x88", b"\x0c\x08")) + READ + ANSWER,
    # glitch bytes, scanned codes (FC8 00 00, FC43 0E objects, vendor codes), broadcasts, reserved addresses
    "scans-and-glitches": lambda seed: salted(seed, 8000, (b"\x00", b"\xff", b"\xfe\x01", b"\x01\x08\x00\x00",
                                                          b"\x01\x2b\x0e", b"\x01\x2b\x0e\x01\x01\x00\x00\x02",
                                                          b"\x00\x03", b"\x00\x10", b"\xf8\x03", b"\x07\x41")),
    "glitchy": glitchy_then_noise,
    "noise-then-traffic": lambda seed: random_bytes(seed, 9000) + polling(200, seed),
    "traffic-noise-traffic": lambda seed: polling(60, seed) + near_modbus(seed, 5000) + polling(60, seed + 1),
    "babble": lambda seed: b"\x01\x03" * 3000 + random_bytes(seed, 500) + b"\x0c" * 2000,
}


@pytest.mark.parametrize("kind", sorted(STREAMS))
@pytest.mark.parametrize("annotator", [auto, atv71], ids=["auto", "atv71"])
def test_noise_framed_by_the_engine_same_lines(kind: str, annotator) -> None:  # noqa: ANN001
    data = STREAMS[kind](len(kind))
    rng = random.Random(len(kind))
    assert_same(data, annotator)  # (in 64 KiB windows as a file is read)
    assert_same(data, annotator, [rng.randrange(len(data)) for _ in range(40)])  # and cut anywhere
    assert_same(data, annotator, list(range(0, len(data), 7)))  # and read 7 bytes at a time


def test_noise_between_two_transactions_exact_lines(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "bus.bin"
    capture.write_bytes(READ + ANSWER + random_bytes(5, 300) + READ + ANSWER)
    text = assert_same_cli([str(capture)], monkeypatch)
    assert text.splitlines()[:6] == [
        "     1            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=0 8401=1 8402=3 [#1]  CRC ok",
        "     3            -   - noise     295 bytes of noise at offset 19: 45 7c 76 9f 39 d8 64 41 99 c0 e5 bd bc fb c8 5b…",
        "     4            -  46 exception Read/Write Multiple Registers: exception 205 (Unknown exception 205) [no request]"
        " [response without a matching request in the capture] [warning: exception code 205 is not defined by the"
        " spec]  CRC BAD (received 0xF0E3, expected 0x6CBE)",
        "     5            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
        "     6            -  12 response  Read Holding Registers 8400..8402 (3): 8400=0 8401=1 8402=3 [#5]  CRC ok",
    ]


def test_long_noise_cut_in_items_of_4096_bytes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # 9,000 random bytes: the run is cut where the framer cuts it (NOISE_ITEM_MAX), the engine's noise kept under it
    capture = tmp_path / "bus.bin"
    capture.write_bytes(READ + ANSWER + random_bytes(7, 9000) + READ + ANSWER)
    text = assert_same_cli([str(capture)], monkeypatch)
    assert text.splitlines()[2:8] == [
        "     3            -   - noise     4096 bytes of noise at offset 19: 38 b4 e6 52 e4 4d a7 f2 37 0d 9e 26 0e 27 13 65…",
        "     4            -   - noise     4096 bytes of noise at offset 4115: b5 00 62 77 de 3c 65 c4 08 34 56 1e 63 ef 48 fe…",
        "     5            -   - noise     803 bytes of noise at offset 8211: a8 ad 54 35 f8 f4 85 97 94 4b 4b 43 f2 68 a9 9d…",
        "     6            -  12 exception Function 98: exception 205 (Unknown exception 205) [no request] [response without"
        " a matching request in the capture] [warning: exception code 205 is not defined by the spec]  CRC BAD (received"
        " 0xFE7A, expected 0xF638)",
        "     7            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
        "     8            -  12 response  Read Holding Registers 8400..8402 (3): 8400=0 8401=1 8402=3 [#7]  CRC ok",
    ]


def records_of(data: bytes, rng: random.Random, low: int, high: int, gap_ns: int) -> list[tuple[bytes, int]]:
    """pcap records of low..high bytes at 19200 baud's pace (a char 573 us), `gap_ns` more between some
    (0: a line that never goes quiet, no silence)."""
    records, start, ns = [], 0, 1_700_000_000 * 10**9
    while start < len(data):
        end = min(len(data), start + rng.randint(low, high))
        records.append((data[start:end], ns))
        ns += (end - start) * 573_000 + (gap_ns if rng.random() < 0.3 else 0)
        start = end
    return records


PCAPS = {
    "random": lambda: random_bytes(8, 20000),
    "near-modbus": lambda: near_modbus(9, 20000),
    "noise-then-traffic": lambda: random_bytes(10, 5000) + polling(150, 10),
}


@pytest.mark.parametrize("kind", sorted(PCAPS))
@pytest.mark.parametrize("records", [(1, 8, 0), (20, 60, 0), (200, 200, 0), (20, 60, 3_000_000)],
                         ids=["reads", "dozens", "stretches", "silences"])
def test_noise_in_pcap_records_same_outputs(kind: str, records: tuple[int, int, int], tmp_path: Path,
                                            monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, records_of(PCAPS[kind](), random.Random(len(kind)), *records))
    for options in ([], ["--stats"], ["-t", "d"]):
        assert_same_cli([str(capture), *options], monkeypatch)


def counted_matches(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    count = [0]
    match = RtuFramer._match

    def counting(self, *args):  # noqa: ANN001, ANN202
        count[0] += 1
        return match(self, *args)

    monkeypatch.setattr(RtuFramer, "_match", counting)
    return count


def test_random_bytes_weighed_by_the_engine(monkeypatch: pytest.MonkeyPatch) -> None:
    data = random_bytes(12, 100_000)
    count = counted_matches(monkeypatch)
    out = Collected()
    annotator = auto()
    path = fastsummary.SummaryPath(Dissector(framer=RtuFramer(), annotate=annotator), annotator, out.items, out.text)
    for start in range(0, len(data), 65536):
        path.feed(data[start : start + 65536])
    path.finish()
    assert len(out.lines) > 20
    assert count[0] < 1500  # (164; 33,522 before: the framer weighed every position that may start a frame)


@pytest.mark.parametrize("kind", ["random", "near-modbus"])
def test_noise_in_pcap_records_weighed_by_the_engine(kind: str, tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, records_of(PCAPS[kind](), random.Random(1), 20, 60, 0))
    count = counted_matches(monkeypatch)
    code, text = decode([str(capture)], monkeypatch, pure=False)
    assert code in (0, 1) and text.count("\n") > 100
    assert count[0] < 3000  # (616 and 848; 12,690 and 13,758 before, every position weighed in Python)
