"""The compiled engine on noisy and damaged streams, which it hands to the Python stages
(fastsummary.PythonSide): the outputs byte for byte those of VW3_PURE_PYTHON=1 (summary, -V, --json,
--stats, -w; raw files and pcaps), and the Python stages taking noise by strides and a run of damaged
frames in one stretch, not one byte or one frame per call and hand-over (a 2 MB random file took 9.0 s
of CPU with the engine against 6.2 s without: 555k one-byte steps)."""
from __future__ import annotations

import io
import random
from pathlib import Path

import pytest

from dissector.accel import fastsummary
from dissector.app.cli import Environment, run
from dissector.framing.rtu import RtuFramer
from dissector.pipeline import Dissector
from dissector.protocol.crc import with_crc
from dissector.sim.line import on_the_line
from dissector.sim.simulate import generate_session
from test_fastsummary import Collected, atv71, auto, python_lines
from test_timed_summary import write_pcap
from helpers import use_engine


def random_bytes(seed: int, size: int) -> bytes:
    return random.Random(seed).randbytes(size)


def bad_crc_frame(slave: int = 1) -> bytes:
    frame = bytearray(with_crc(bytes([slave, 0x10, 0x00, 0x64, 0x00, 20, 40]) + bytes(range(40))))
    frame[-1] ^= 0x5A
    return bytes(frame)


def polling(transactions: int, seed: int) -> list[bytes]:
    return [data for data, _time in generate_session(transactions, seed=seed)]


def bad_crc_runs(seed: int) -> bytes:
    """Valid polling, a run of damaged FC16 requests, polling again, another run, polling."""
    frames = polling(240, seed)
    return b"".join([*frames[:80], bad_crc_frame() * 60, *frames[80:160], bad_crc_frame(7) * 45, *frames[160:]])


def garbage_between(seed: int) -> bytes:
    rng = random.Random(seed)
    stream = bytearray()
    for frame in polling(300, seed):
        stream += frame
        if rng.random() < 0.2:
            stream += rng.randbytes(rng.randint(1, 16))
    return bytes(stream)


def noise_then_traffic(seed: int) -> bytes:
    """Random bytes, then a clean bus: the engine takes the stream back once the noise ends."""
    return random_bytes(seed, 6000) + b"".join(polling(400, seed))


def glitches(seed: int) -> bytes:
    frames = polling(300, seed)
    return on_the_line(frames, [True] * len(frames), "glitches both sides", random.Random(seed)).stream


def ascii_with_garbage(seed: int) -> bytes:
    rng = random.Random(seed)
    stream = bytearray()
    for frame in polling(120, seed):
        binary = frame[:-2]
        stream += b":" + (binary + bytes([(-sum(binary)) & 0xFF])).hex().upper().encode() + b"\r\n"
        if rng.random() < 0.3:
            stream += bytes(rng.choice(b"0123456789ABCDEF:\r\nxyz") for _ in range(rng.randint(1, 12)))
    return bytes(stream)


STREAMS = {
    "random": lambda seed: random_bytes(seed, 12000),
    "bad-crc": bad_crc_runs,
    "garbage": garbage_between,
    "noise-then-traffic": noise_then_traffic,
    "glitches": glitches,
}


def decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> tuple[int, str]:
    use_engine(monkeypatch, pure)
    stdout, stderr = io.StringIO(), io.StringIO()
    code = run(argv, Environment(io.BytesIO(), stdout, stderr, False, False))
    return code, stdout.getvalue() + stderr.getvalue()


def assert_same(argv: list[str], monkeypatch: pytest.MonkeyPatch) -> str:
    fast = decode(argv, monkeypatch, pure=False)
    assert fast == decode(argv, monkeypatch, pure=True)
    return fast[1]


# The outputs the engine writes from a raw file (app/paths.py): -V and --json of a raw file run the Python
# stages either way, so they are compared on pcaps below, which the engine's timed path takes.
OUTPUTS = [[], ["--stats"], ["-n"], ["--profile", "atv71"]]


@pytest.mark.parametrize("kind", sorted(STREAMS))
@pytest.mark.parametrize("output", range(len(OUTPUTS)))
def test_noisy_raw_streams_same_outputs(kind: str, output: int, tmp_path: Path,
                                        monkeypatch: pytest.MonkeyPatch) -> None:
    capture = tmp_path / "bus.bin"
    capture.write_bytes(STREAMS[kind](output))
    text = assert_same([str(capture), *OUTPUTS[output]], monkeypatch)
    assert text


def records_of(data: bytes, rng: random.Random, how: str) -> list[tuple[bytes, int | None]]:
    """A pcap's records of a raw stream: reads of 1..64 bytes (USB bursts) at 19200 baud's pace, or
    stretches of 200 bytes (a sniffer of a noisy line)."""
    records: list[tuple[bytes, int | None]] = []
    start, ns = 0, 1_700_000_000 * 10**9
    while start < len(data):
        end = min(len(data), start + (rng.randint(1, 64) if how == "bursts" else 200))
        records.append((data[start:end], ns))
        ns += (end - start) * 573_000 + rng.choice([0, 0, 2_000_000])
        start = end
    return records


@pytest.mark.parametrize("kind", sorted(STREAMS))
@pytest.mark.parametrize("how", ["bursts", "stretches"])
def test_noisy_pcaps_same_outputs(kind: str, how: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    rng = random.Random(len(kind) * 3 + len(how))
    capture = tmp_path / "bus.pcap"
    write_pcap(capture, records_of(STREAMS[kind](7), rng, how))
    for options in ([], ["-t", "d"], ["--stats"], ["--json"], ["-V"]):
        assert_same([str(capture), *options], monkeypatch)


@pytest.mark.parametrize("kind", ["random", "bad-crc", "garbage"])
def test_noisy_streams_written_alike(kind: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (-w of a raw file runs the Python stages under either switch today: this holds it so if that changes)
    capture = tmp_path / "bus.bin"
    capture.write_bytes(STREAMS[kind](3))
    written = {}
    for pure in (False, True):
        out = tmp_path / f"out{pure}.pcapng"
        decode([str(capture), "-w", str(out)], monkeypatch, pure)
        written[pure] = out.read_bytes()
    assert written[False] == written[True]
    assert len(written[False]) > len(STREAMS[kind](3))


def test_ascii_with_garbage_same_outputs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (ASCII runs the Python stages under either switch today: this holds it so if that changes)
    capture = tmp_path / "bus.txt"
    capture.write_bytes(ascii_with_garbage(5))
    for options in ([], ["--stats"], ["--json"]):
        text = assert_same([str(capture), *options], monkeypatch)
    assert "noise" in text


class Counting:
    """SummaryPath over `data` in chunks of 4 KiB, counting the Python framer's runs and the
    hand-overs; the lines equal the Python stages'."""

    def __init__(self, data: bytes, annotator_factory) -> None:  # noqa: ANN001
        self.runs = 0
        self.hand_overs = 0
        framer = RtuFramer()
        run_framer = framer._run

        def counted_run(final: bool) -> list:
            self.runs += 1
            return run_framer(final)

        framer._run = counted_run  # type: ignore[method-assign]
        out = Collected()
        annotator = annotator_factory()
        path = fastsummary.SummaryPath(Dissector(framer=framer, annotate=annotator), annotator, out.items, out.text)
        hand_over = path._hand_over

        def counted_hand_over() -> None:
            self.hand_overs += 1
            hand_over()

        path._hand_over = counted_hand_over  # type: ignore[method-assign]
        for start in range(0, len(data), 4096):
            path.feed(data[start : start + 4096])
        path.finish()
        assert out.lines == python_lines(data, annotator_factory())
        self.engine_lines = out.engine_lines
        self.lines = len(out.lines)


def test_random_bytes_taken_by_strides() -> None:
    # 20,000 random bytes: the Python framer ran once a byte (20,000+ runs) before the strides
    counted = Counting(random_bytes(11, 20000), auto)
    assert counted.runs < 600
    assert counted.hand_overs < 20


def test_a_run_of_damaged_frames_is_one_stretch() -> None:
    # 400 damaged FC16 requests: each was handed back to the engine, which handed it over again
    data = b"".join(polling(50, 2)) + bad_crc_frame() * 400 + b"".join(polling(300, 3))
    counted = Counting(data, atv71)
    assert counted.runs < 200  # (12,458 before: a run a byte or frame)
    assert counted.hand_overs < 30
    # the clean polling after the run, from the engine but for the Python stages' last stride (4 KiB)
    assert counted.engine_lines > 0.6 * counted.lines


def test_the_engine_takes_a_clean_bus_back_after_noise() -> None:
    counted = Counting(noise_then_traffic(4), atv71)
    assert counted.engine_lines > 0.7 * counted.lines


def test_noise_every_few_frames_stays_with_the_python_stages() -> None:
    # garbage after a fifth of the frames: a hand-over costs more than the few frames the engine shows
    # between two (calm doubles: PythonSide)
    counted = Counting(garbage_between(6), atv71)
    assert counted.hand_overs < 40
