"""`FILE -w COPY` of a pcap reads FILE's records in bulk (accel/records.py BlockBuilder.pcap telling the
trail of each block's reads, observe_block) and writes the very file the reads taken one by one write:
the engine's path reading chunk by chunk (records.py's bulk reader turned off) and the Python stages
(VW3_PURE_PYTHON=1), byte for byte, on captures of one frame a record, of reads cut anywhere with
damage, silences inside frames and untimed records, of tap reads with noise and early stamps, and on a
ring buffer's two files; pcap and pcapng copies."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from dissector.accel import records
from dissector.sim.simulate import generate_session
from test_copy_reads import T0, reads, stream
from test_timed_summary import cut_records, decode, frames_of, write_pcap

WAYS = ("bulk", "chunks", "pure")


def captures(tmp_path: Path) -> dict[str, list[Path]]:
    polling = [(data, round(time * 1e9)) for data, time in generate_session(400, seed=9)]
    bursts = cut_records(random.Random(5), frames_of(101, damaged=0.06), "bursts")
    untimed = cut_records(random.Random(6), frames_of(102, damaged=0.06), "untimed")
    rng = random.Random(56)  # (tap reads of 1..12 bytes: noise, damaged frames, reads stamped early)
    taps = [(data, (T0 + micros) * 1000) for seed in range(8)
            for data, micros in reads(random.Random(seed), stream(rng))]
    taps = [(data, ns + index * 10**9) for index, (data, ns) in enumerate(taps)]  # (streams apart, in order)
    found = {}
    for name, kept in (("polling", polling), ("bursts", bursts), ("untimed", untimed), ("taps", taps)):
        path = tmp_path / f"{name}.pcap"
        write_pcap(path, kept, nano=name != "polling")
        found[name] = [path]
    half = len(bursts) // 2
    ring = [tmp_path / "ring_00001_20231114221320.pcap", tmp_path / "ring_00002_20231114221520.pcap"]
    write_pcap(ring[0], bursts[:half])
    write_pcap(ring[1], bursts[half:])
    found["ring"] = ring
    return found


def copy(files: list[Path], out: Path, way: str, monkeypatch: pytest.MonkeyPatch) -> tuple[bytes, str, int]:
    """The copy's bytes, the decode's output, how many blocks were read in bulk with a trail."""
    bulk = 0
    read_in_bulk = records.BlockBuilder.pcap

    def counted(self: records.BlockBuilder, reader: object, scan: object, trail: object = None) -> object:
        nonlocal bulk
        for block in read_in_bulk(self, reader, scan, trail):  # type: ignore[arg-type]
            bulk += trail is not None
            yield block

    with monkeypatch.context() as patch:
        patch.setattr(records.BlockBuilder, "pcap", counted)
        if way == "chunks":  # (no record reads as user 0 to the bulk reader: every chunk one by one)
            patch.setattr(records, "LINKTYPE_USER0", -1)
        said, _lines = decode([*map(str, files), "-w", str(out)], patch, pure=way == "pure")
    return out.read_bytes(), said, bulk


@pytest.mark.parametrize("suffix", [".pcap", ".pcapng"])
def test_a_bulk_copy_is_the_copy_read_one_by_one(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                 suffix: str) -> None:
    for name, files in captures(tmp_path).items():
        written = {way: copy(files, tmp_path / f"{name}-{way}{suffix}", way, monkeypatch) for way in WAYS}
        assert written["bulk"][2] > 0, name  # (read in bulk: fails before observe_block)
        assert written["chunks"][2] == written["pure"][2] == 0, name
        for way in WAYS[1:]:
            assert written["bulk"][:2] == written[way][:2], (name, way)
