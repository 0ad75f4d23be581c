"""--stats of timed captures counted in the engine (dissector/accel/timedpath.py count_input; the bus
timing, response times, poll intervals and first and last times in dissector/accel/_bus.h) against the
Python stages (VW3_PURE_PYTHON=1): the tables, the bus section and the JSON byte for byte, on pcap,
pcapng and hex dumps cut at random, with times (outages, late answers, times going back, silences of
minutes, untimed records) and damage, alone and after or before other inputs."""
from __future__ import annotations

import json
import os
import random
from pathlib import Path

import pytest

from dissector.accel import timedpath
from dissector.render import stats_store
from dissector.sim.mixes import max_size_mix
from dissector.sim.simulate import generate_session
from helpers import rtu
from test_timed_summary import CHAR_NS, assert_same, cut_records, decode, frames_of, write_pcap, write_pcapng

ROOT = Path(__file__).resolve().parents[2]
OUTPUTS = [["--stats"], ["--stats", "--json"], ["--stats", "--json", "--timeout", "0.03", "--baud", "9600"],
           ["--stats", "--profile", "atv71", "-t", "d"]]


@pytest.fixture
def counted(monkeypatch: pytest.MonkeyPatch) -> list[bool]:
    """What count_input answered for each timed input of the compiled runs (True: the engine counted)."""
    answers: list[bool] = []
    count_input = timedpath.count_input

    def spy(*args: object) -> bool:
        answer = count_input(*args)  # type: ignore[arg-type]
        if not os.environ.get("VW3_PURE_PYTHON"):
            answers.append(answer)
        return answer

    monkeypatch.setattr(timedpath, "count_input", spy)
    return answers


@pytest.mark.parametrize("seed", range(8))
def test_random_captures_same_stats(seed: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                    counted: list[bool]) -> None:
    rng = random.Random(seed)
    how = ["frame", "bursts", "untimed", "frame"][seed % 4]
    records = cut_records(rng, frames_of(seed + 300, damaged=0.0 if seed == 0 else 0.07), how)
    capture = tmp_path / ("bus.pcapng" if seed % 3 == 2 else "bus.pcap")
    if seed % 3 == 2:
        write_pcapng(capture, records)
    else:
        write_pcap(capture, records, nano=seed % 2 == 0)
    for output in OUTPUTS[seed % 2 :: 2]:
        assert_same([str(capture), *output], monkeypatch)
    assert counted and all(counted)


def story() -> list[tuple[bytes, int | None]]:
    """A bus with what the bus section measures: a slave silent for a run of polls (an outage) then back,
    answers after the timeout, a record stamped before the one ahead of it, a silence of three minutes,
    untimed records, exceptions, writes."""
    ns = 1_700_000_000 * 10**9 + 123_456_789
    records: list[tuple[bytes, int | None]] = []

    def add(frame: bytes, after_ms: float) -> None:
        nonlocal ns
        ns += int(after_ms * 1e6)
        records.append((frame, ns))
        ns += len(frame) * CHAR_NS

    for cycle in range(120):
        add(rtu("01 03 0C81 0004"), 10 + cycle % 3)
        if not 40 <= cycle < 46:  # slave 1 silent for six polls: an outage
            add(rtu("01 03 08 0001 0002 0003 0004"), 2 + (cycle * 7) % 11)
        add(rtu("02 04 0000 0002"), 5)
        if cycle % 17 == 5:
            add(rtu("02 84 02"), 3)
        else:
            add(rtu("02 04 04 00%02X 0000" % (cycle % 256)), 1500 if cycle % 29 == 3 else 4)  # late: unanswered
        add(rtu("03 06 2000 %04X" % cycle), 7)
        add(rtu("03 06 2000 %04X" % cycle), 3)
        if cycle == 60:
            ns += 180 * 10**9  # three minutes of silence
        if cycle == 80:
            ns -= 5 * 10**6  # the next record stamped before the end of the last
    records[10] = (records[10][0], None)  # untimed records
    records[11] = (records[11][0], None)
    return records


@pytest.mark.parametrize("output", range(len(OUTPUTS)))
def test_outages_late_answers_and_times_going_back(output: int, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                   counted: list[bool]) -> None:
    capture = tmp_path / "story.pcap"
    write_pcap(capture, story())
    text, _lines = assert_same([str(capture), *OUTPUTS[output]], monkeypatch)
    assert counted == [True]
    if output == 0:
        assert "slave 1 silent" in text and "6 requests unanswered" in text


def four_inputs(tmp_path: Path, transactions: int, seed: int, cut_seed: int, dump_frames: int
                ) -> tuple[Path, Path, Path, Path]:
    """The story as a pcap, a polling session as a raw file and as a pcapng, and a stamped hex dump:
    inputs of every kind, for one run over several of them."""
    pcap = tmp_path / "story.pcap"
    write_pcap(pcap, story())
    records = generate_session(transactions, seed=seed)
    polling = tmp_path / "polling.pcapng"
    write_pcapng(polling, [(data, round(time * 1e9)) for data, time in records])
    raw = tmp_path / "polling.bin"
    raw.write_bytes(b"".join(data for data, _time in records))
    dump = tmp_path / "bus.txt"
    dump.write_text("".join(f"{ns // 10**9}.{ns % 10**9 // 1000:06d} {data.hex(' ')}\n"
                            for data, ns in cut_records(random.Random(cut_seed), frames_of(dump_frames, 0.05), "frame")))
    return pcap, raw, polling, dump


def test_several_inputs_in_one_run(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, counted: list[bool]) -> None:
    """A pcap, a raw file and a pcap again, a hex dump after a pcapng, a raw file first, two captures:
    one bus, one poll cycle, one set of first and last times over them all, whichever side counted."""
    pcap, raw, polling, dump = four_inputs(tmp_path, 300, 4, 1, 7)
    for files in ([pcap, raw, polling], [raw, pcap], [polling, dump, pcap], [dump, pcap],
                  [ROOT / "captures" / "noisy_bus.pcap", ROOT / "captures" / "p38_protection.pcap"]):
        for output in (["--stats"], ["--stats", "--json"]):
            counted.clear()
            assert_same([*map(str, files), *output], monkeypatch)
            assert counted and all(counted)


@pytest.mark.parametrize("name", ["atv71_commissioning", "noisy_bus", "p38_protection", "sel749m_polling"])
def test_shipped_captures_same_stats(name: str, monkeypatch: pytest.MonkeyPatch, counted: list[bool]) -> None:
    for output in (["--stats"], ["--stats", "--json", "--profile", "auto"]):
        assert_same([str(ROOT / "captures" / f"{name}.pcap"), *output], monkeypatch)
    assert counted and all(counted)


def test_times_too_far_apart_for_the_engine(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                             counted: list[bool]) -> None:
    """A record 120 days after the one before (past 2^53 ns, where a difference's double rounds): the
    engine's stamp subtraction rounds once, as the Python stages', into the same store."""
    records = story()
    jump = 120 * 86_400 * 10**9
    records = records[:300] + [(data, None if ns is None else ns + jump) for data, ns in records[300:]]
    capture = tmp_path / "jump.pcap"
    write_pcap(capture, records)
    for output in OUTPUTS:
        assert_same([str(capture), *output], monkeypatch)
    assert counted and all(counted)


def test_histograms_past_their_limit(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, counted: list[bool]) -> None:
    """Response times, bus timing and poll intervals of every public code at random slaves, past the
    entries a kind of histogram may keep (stats_store.MAX_TALLY, here 64): both stores round their keys
    down alike (stats_store.Coarse, _bus.h Tallies), so the tables and the JSON stay byte-identical."""
    records = [(data, round(time * 1e6) * 1000) for data, time in max_size_mix(3000, seed=5)]
    records[700] = (records[700][0][:-1] + bytes([records[700][0][-1] ^ 0xFF]), records[700][1])  # damage
    capture = tmp_path / "max-size.pcap"
    write_pcap(capture, records)
    exact, _lines = decode([str(capture), "--stats", "--json"], monkeypatch, pure=False)
    monkeypatch.setattr(stats_store, "MAX_TALLY", 64)
    for output in (["--stats", "--json"], ["--stats"], ["--stats", "--json", "--profile", "generic"]):
        text, _lines = assert_same([str(capture), *output], monkeypatch)
        if output == ["--stats", "--json"]:
            assert text != exact  # rounded: medians, percentiles and periods moved
            report, _end = json.JSONDecoder().raw_decode(text)  # (its warnings on stderr after it)
            times = [row["response_time"]["min"] for row in report["functions"] if row["response_time"]]
            assert times and all(round(seconds * 1e9) % 1024 == 0 for seconds in times)
    assert counted and all(counted)
