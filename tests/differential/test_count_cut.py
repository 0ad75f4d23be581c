"""-c N on the compiled engine's frames path (accel/framespath.py _Counted): the engine frames the bytes that
cannot hold the Nth item, the Python stages the chunk that may and the ones after, chunk by chunk, as
decode_chunks does with VW3_PURE_PYTHON=1. The outputs are byte-identical to the Python stages' for N
anywhere in random captures (damaged frames, noise runs, a record a frame or the stream cut anywhere,
records without a time), for the summary, -V, --json, -Y, --stats (its bus timing and device profiles
see the chunk that reached N as the Python stages do, nothing after it), --report, -w, and standard
input; and the engine frames the frames before the cut (app/paths.py kept -c on the Python stages
before: a capture of 20,000 records with -c 1000000 was decoded at the Python stages' speed).
The extension must be built: it is not skipped."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from helpers import decode_counting_frames as decode, engine_output_as_python as same
from test_timed_summary import cut_records, frames_of, write_pcap, write_pcapng

OPTIONS = [["--stats"], ["-V"], ["--json"], ["-Y", "slave == 1 or function == 3", "--stats"], ["--profile", "auto", "--stats"],
           ["-t", "d"]]

def capture(tmp_path: Path, seed: int, how: str) -> tuple[Path, int]:
    """A random bus (some frames damaged) as pcap or pcapng records; and how many frames it holds."""
    rng = random.Random(seed)
    frames = frames_of(seed + 900, damaged=0.0 if seed == 0 else 0.06)
    path = tmp_path / (f"bus{seed}{how}.pcapng" if seed % 2 else f"bus{seed}{how}.pcap")
    (write_pcapng if seed % 2 else write_pcap)(path, cut_records(rng, frames, how))
    return path, len(frames)


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("how", ["frame", "bursts", "untimed"])
def test_cut_anywhere_same_as_the_python_stages(seed: int, how: str, tmp_path: Path,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    path, frames = capture(tmp_path, seed, how)
    rng = random.Random(seed * 31 + len(how))
    counts = sorted({1, 2, 3, 7, frames // 2, frames - 1, frames, frames + 3, *rng.sample(range(1, frames), 6)})
    for count in counts:
        options = rng.choice(OPTIONS)
        same([str(path), "-c", str(count), *options], monkeypatch)


def test_every_count_of_a_short_capture(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Every N over the first 120 frames of a capture cut in bursts: the cut at each chunk boundary."""
    path, _frames = capture(tmp_path, 5, "bursts")
    for count in range(1, 121):
        same([str(path), "-c", str(count), "--stats"], monkeypatch)


@pytest.mark.parametrize("seed", [1, 2])
def test_report_write_and_stdin(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    path, frames = capture(tmp_path, seed, "bursts" if seed % 2 else "frame")
    for count in (5, frames // 3, frames - 2):
        pages, written = [], []
        for pure in (False, True):
            page, pcap = tmp_path / f"r{pure}.html", tmp_path / f"w{pure}.pcap"
            out, _ = decode([str(path), "-c", str(count), "--stats", "--report", str(page), "-w", str(pcap)],
                            monkeypatch, pure)
            pages.append(out + page.read_text(encoding="utf-8"))
            written.append(pcap.read_bytes())
        assert pages[0] == pages[1] and written[0] == written[1], count
        same(["-", "-c", str(count), "--stats"], monkeypatch, stdin=path.read_bytes())
        same(["-", "-c", str(count), "-V"], monkeypatch, stdin=path.read_bytes())


def test_the_engine_frames_up_to_the_cut(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Clean traffic, a record a frame: with N past the end the engine frames what it frames without -c;
    with N inside, the same up to the last few frames before the cut (failing before: -c ran the Python
    stages alone, the engine framed nothing)."""
    path, frames = capture(tmp_path, 0, "frame")
    _out, uncut = decode([str(path), "-V"], monkeypatch, pure=False)
    # (broadcasts, exceptions, late answers: the Python stages'; a late FC5/FC6 echo is a master's retry since
    # bd48460, a request whose wait the Python stages follow to the next frame: 436 of this bus's 588)
    assert len(uncut) > frames * 2 // 3
    out, framed = same([str(path), "-c", "1000000", "--stats"], monkeypatch)
    assert out.startswith(f"{frames} frames, 0 noise bytes in 0 runs,")
    assert framed == uncut
    out, framed = same([str(path), "-c", "400", "--stats"], monkeypatch)
    assert out.startswith("400 frames, 0 noise bytes in 0 runs,")
    before = [number for number in uncut if number <= 400]
    # The Python stages take the chunk from which the items left (-c counts noise runs too, and one may
    # be a byte) could fit in the bytes the engine holds (requests awaiting their answer, what it looks
    # ahead at) and the next record: records of up to 256 bytes, so from a few hundred items before N.
    assert framed == before[: len(framed)] and 40 <= len(framed) < len(before)
    out, framed = same([str(path), "-c", "1000", "--stats"], monkeypatch)  # (588 items: N past the end)
    assert out.startswith(f"{frames} frames, 0 noise bytes in 0 runs,")
    assert framed == uncut[: len(framed)] and len(uncut) - 30 <= len(framed) < len(uncut)
