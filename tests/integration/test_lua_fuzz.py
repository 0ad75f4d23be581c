"""Malformed records never raise a Lua error in tshark: random, truncated, oversized, glued and mutated
records (12,000 of them), in RTU and in ASCII mode, dissected twice (tshark -2) with the full tree."""
from __future__ import annotations

import random
from pathlib import Path

from lua_harness import lua_errors, run_tshark, write_pcap
from lua_session import random_records


def _check_no_lua_error(pcap: Path, records: int) -> None:
    result = run_tshark(pcap, "-V")
    assert result.returncode == 0, result.stderr[-3000:]
    errors = lua_errors(result.stdout + result.stderr)
    assert not errors, f"{len(errors)} Lua errors, first: {errors[:5]}"
    # Every record reached the plugin: one `VW3` tree or more per non-empty record.
    assert result.stdout.count("\nFrame ") + result.stdout.startswith("Frame ") == records
    assert result.stdout.count("VW3 ") >= records // 2


def test_fuzzed_rtu_records(tmp_path: Path) -> None:
    records = random_records(seed=99, count=12_000)
    lengths = [len(data) for data, _ in records]
    assert sum(length == 0 for length in lengths) > 50 and max(lengths) > 2000
    _check_no_lua_error(write_pcap(tmp_path / "fuzz.pcap", records), len(records))


def test_fuzzed_stream_cut_into_small_records(tmp_path: Path) -> None:
    # The fuzzed records' bytes as one stream cut anew into records of 1 to 16 bytes (a sniffer writing
    # each serial read): frames and noise runs span records, the framer carries them over.
    rng = random.Random(16)
    stream = b"".join(data for data, _ in random_records(seed=16, count=3000))
    records, position = [], 0
    while position < len(stream) and len(records) < 10_000:
        size = rng.randint(1, 16)
        records.append((stream[position : position + size], len(records) * 0.001))
        position += size
    assert len(records) == 10_000
    result = run_tshark(write_pcap(tmp_path / "cut.pcap", records), "-V")
    assert result.returncode == 0, result.stderr[-3000:]
    errors = lua_errors(result.stdout + result.stderr)
    assert not errors, f"{len(errors)} Lua errors, first: {errors[:5]}"
    assert "Plugin error" not in result.stdout
    assert result.stdout.count("VW3 bytes of a frame shown in a later record") > 1000
    assert result.stdout.count("VW3 Modbus RTU") > 100


def test_fuzzed_ascii_records(tmp_path: Path) -> None:
    rng = random.Random(7)
    records = [(b":02062329000AA2\r\n", 0.0)]  # the first record puts the capture in ASCII mode
    alphabet = b"0123456789ABCDEFabcdef:\r\n"
    for index in range(3000):
        if rng.random() < 0.5:
            body = bytes(rng.choice(alphabet) for _ in range(rng.randint(0, 600)))
        else:
            body = b":" + rng.randbytes(rng.randint(0, 260)).hex().upper().encode() + rng.choice([b"\r\n", b"\n", b""])
        records.append((body, index * 0.001))
    _check_no_lua_error(write_pcap(tmp_path / "ascii.pcap", records), len(records))


def test_fuzzed_rtac_records(tmp_path: Path) -> None:
    # RTAC serial records (the pass-through reading their header, then Decode As to the plugin),
    # including records shorter than the 12-byte header.
    import struct

    from dissector.render.pcapwriter import LINKTYPE_RTAC_SERIAL, PcapWriter

    rng = random.Random(250)
    pcap = tmp_path / "rtac.pcap"
    payloads = random_records(seed=250, count=3000)
    with pcap.open("wb") as stream:
        writer = PcapWriter(stream, linktype=LINKTYPE_RTAC_SERIAL, flush=False)
        for data, time in payloads:
            header = struct.pack(">IIBBH", int(time), rng.randrange(1_000_000), rng.randrange(16), 0, 0)
            record = header + data if rng.random() < 0.95 else header[: rng.randrange(12)]
            writer.write(record, time)
    result = run_tshark(pcap, "-V", "-d", "rtacser.data,vw3")
    assert result.returncode == 0, result.stderr[-3000:]
    errors = lua_errors(result.stdout + result.stderr)
    assert not errors, f"{len(errors)} Lua errors, first: {errors[:5]}"
    assert result.stdout.count("VW3 ") > 2000
