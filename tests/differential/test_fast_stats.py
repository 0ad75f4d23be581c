"""--stats counted by the compiled engine (dissector/accel/_stats.h) against the Python stages, which are
the reference: the same report (JSON) and the same tables, on every kind of stream, however it is cut
into chunks, while the Python stages count what the engine hands back into the same store.
"""
from __future__ import annotations

import io
import json
import random
import sys
from pathlib import Path

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from dissector.accel import fastsummary
from dissector.app.cli import Environment, run
from dissector.devices.build import build_annotator
from dissector.framing.rtu import RtuFramer
from dissector.model import Chunk
from dissector.pipeline import Dissector
from dissector.render import history
from dissector.render.history import History
from dissector.render.stats import StatsCollector
from dissector.render.stats_store import ParameterTable
from dissector.sim.mixes import PLANT_PROFILES, max_size_mix, plant_mix
from dissector.sim.simulate import generate_session, write_capture
import strategies
from helpers import rtu
from strategies import adu

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench"))
import noise_accuracy  # noqa: E402


def python_stats(data: bytes, annotator: object | None) -> StatsCollector:
    # The pure-Python store: the reference.
    collector = StatsCollector(getattr(annotator, "choices", None), History(annotator, ParameterTable()))
    dissector = Dissector(annotate=annotator)  # type: ignore[arg-type]
    for item in dissector.feed(Chunk(data)) + dissector.finish():
        collector.add(item)
    collector.history.finish()  # the frames held until a slave's profile was chosen (render/history.py)
    return collector


def compiled_stats(data: bytes, annotator: object | None, splits: list[int] | None = None) -> StatsCollector:
    collector = StatsCollector(getattr(annotator, "choices", None), History(annotator))
    store = collector.engine_store()
    assert store is not None, "the compiled store is not built"

    def items(found: list) -> None:
        for item in found:
            collector.add(item)

    path = fastsummary.SummaryPath(
        Dissector(framer=RtuFramer(), annotate=annotator), annotator, items, lambda lines: None, store  # type: ignore[arg-type]
    )
    cuts = [0, *sorted(set(splits or [])), len(data)]
    for start, end in zip(cuts, cuts[1:]):
        path.feed(data[start:end])
    path.finish()
    collector.history.finish()
    return collector


def assert_same(data: bytes, factory, splits: list[int] | None = None) -> StatsCollector:  # noqa: ANN001
    expected = python_stats(data, factory())
    got = compiled_stats(data, factory(), splits)
    assert got.report() == expected.report()
    assert got.render_plain() == expected.render_plain()
    return got


def annotator(profile: str | None):  # noqa: ANN201
    return (lambda: None) if profile is None else (lambda: build_annotator([profile], [], None))


@pytest.mark.parametrize("capture", sorted(p.name for p in (ROOT / "captures").glob("*.bin")))
@pytest.mark.parametrize("profile", [None, "auto", "atv71", "sel749m", "generic"])
def test_shipped_captures_same_stats(capture: str, profile: str | None) -> None:
    assert_same((ROOT / "captures" / capture).read_bytes(), annotator(profile))


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("profile", ["atv71", "auto"])
def test_simulated_sessions_same_stats_mostly_counted_by_the_engine(seed: int, profile: str, monkeypatch) -> None:
    # (profile auto: a slave whose choice is not final is the Python stages' while the history holds its frames,
    # render/history.py held; past MAX_HELD of them the engine takes it, as here from the 300th)
    monkeypatch.setattr(history, "MAX_HELD", 300)
    data = b"".join(raw for raw, _time in generate_session(1500, seed=seed))
    rng = random.Random(seed)
    got = assert_same(data, annotator(profile), [rng.randrange(len(data)) for _ in range(30)])
    assert got.store.frames > 0.8 * got.report()["frames"]


def test_plant_mix_same_stats_nearly_all_from_the_engine() -> None:
    data = b"".join(raw for raw, _time in plant_mix(6000, seed=3))
    factory = lambda: build_annotator(["atv71", *PLANT_PROFILES], [], None)  # noqa: E731
    got = assert_same(data, factory, [777, 30000, 65432])
    assert got.store.frames > 0.97 * got.report()["frames"]


@pytest.mark.parametrize("profile", ["generic", "atv71", None])
def test_max_size_mix_same_stats(profile: str | None) -> None:
    data = b"".join(raw for raw, _time in max_size_mix(2500, seed=4))
    assert_same(data, annotator(profile), [5000, 5001, 90000])


@pytest.mark.parametrize("seed", range(4))
def test_damaged_streams_same_stats(seed: int) -> None:
    """Noise, dropped bytes and bit flips: CRC errors and noise are the Python stages', in the same counts."""
    rng = random.Random(seed)
    stream = bytearray()
    for frame in noise_accuracy.session(rng, 400):
        if rng.random() < 0.1:
            _how, frame = noise_accuracy.damage(rng, frame)
        stream += frame
    data = bytes(stream)
    splits = [rng.randrange(len(data)) for _ in range(rng.choice([0, 5, 100]))]
    assert_same(data, annotator("atv71"), splits)
    assert_same(data, annotator(None), splits)


def test_a_parameter_seen_by_both_sides_keeps_the_streams_order() -> None:
    """HSP read, then 16#8000 in a multi-word read and its "readable again" (the Python stages' notes),
    then read, written and refused with the engine counting: one story, in the stream's order."""
    exchanges = [
        (rtu("0c03 0c20 0001"), rtu("0c03 02 0003")),
        (rtu("0c03 0c1f 0003"), rtu("0c03 06 8000 8000 0001")),
        (rtu("0c03 0c20 0001"), rtu("0c03 02 0004")),
        (rtu("0c03 0c20 0001"), rtu("0c03 02 0005")),
        (rtu("0c06 0c20 0003"), rtu("0c06 0c20 0003")),
        (rtu("0c10 0c20 0001 02 0006"), rtu("0c10 0c20 0001")),
        (rtu("0c06 0c20 0009"), rtu("0c86 04")),
    ]
    data = b"".join(request + answer for request, answer in exchanges)
    got = assert_same(data, annotator("atv71"))
    (hsp,) = [row for row in got.report()["parameters"] if row["address"] == 3104]
    assert (hsp["code"], hsp["reads"], hsp["unreadable"], hsp["writes"], hsp["refused"]) == ("HSP", 3, 1, 3, 1)
    # 3 -> protected -> 4 -> 5 -> 3 (FC6) -> 6 (FC16): five changes of state, as --watch prints them.
    assert (hsp["last"], hsp["last_text"], hsp["changes"]) == (6, "0.6 Hz", 5)
    assert got.store.frames >= 8  # the engine counted the writes and the exception


def test_a_profile_chosen_later_names_the_last_values_with_it() -> None:
    """Profile auto: slave 2 is read before and after its identification names an ATV71."""
    commissioning = (ROOT / "captures" / "atv71_commissioning.bin").read_bytes()
    early = rtu("0203 0c1e 0002") + rtu("0203 04 0237 0000")
    assert_same(early * 4 + commissioning + early, annotator("auto"))


def test_more_request_keys_than_the_poll_table_keeps() -> None:
    """Past MAX_KEYS distinct requests the poll cycle counts, not follows: the same keys either way,
    with exceptions (the Python stages') among the engine's unanswered requests."""
    rng = random.Random(9)
    parts = []
    for index in range(50_300):
        parts.append(rtu(f"01 03 {index % 65536:04x} {1 + index // 65536:04x}"))
        if rng.random() < 0.02:
            parts.append(rtu("0183 02"))
    parts.append(rtu("01 03 0000 0001") * 3)
    assert_same(b"".join(parts), annotator("generic"))


values = st.sampled_from([0, 1, 3, 5, 0x8000, 0xFFFF, 296, 0x0637])
addresses = st.sampled_from([0, 3201, 3104, 8400, 8401, 8410, 8501, 65535])


@st.composite
def transaction(draw: st.DrawFn) -> bytes:
    slave = draw(st.sampled_from([0, 1, 12, 12, 247]))
    start = draw(addresses)
    words = [draw(values) for _ in range(draw(st.integers(1, 5)))]
    body = b"".join(word.to_bytes(2, "big") for word in words)
    count = len(words)
    kind = draw(st.integers(0, 6))
    if kind == 0:
        return rtu(f"{slave:02x}03{start:04x}{count:04x}") + adu(slave, bytes([3, 2 * count]) + body)
    if kind == 1:
        request = rtu(f"{slave:02x}06{start:04x}{words[0]:04x}")
        return request + (request if draw(st.booleans()) else rtu(f"{slave:02x}8604"))
    if kind == 2:
        request = adu(slave, bytes.fromhex(f"10{start:04x}{count:04x}{2 * count:02x}") + body)
        return request + rtu(f"{slave:02x}10{start:04x}{count:04x}")
    if kind == 3:
        write = draw(addresses)
        request = adu(slave, bytes.fromhex(f"17{start:04x}{count:04x}{write:04x}{count:04x}{2 * count:02x}") + body)
        return request + adu(slave, bytes([23, 2 * count]) + body[::-1])
    if kind == 4:
        return rtu(f"{slave:02x}03{start:04x}{count:04x}")  # unanswered
    if kind == 5:
        return rtu(f"{slave:02x}03{start:04x}{count:04x}") + rtu(f"{slave:02x}83{draw(st.integers(1, 11)):02x}")
    return draw(st.binary(min_size=1, max_size=6))


@settings(max_examples=150, deadline=None)
@given(st.lists(transaction(), max_size=16), st.lists(st.integers(0, 400), max_size=4),
       st.sampled_from(["atv71", "auto", None]))
def test_random_register_sessions_same_stats(parts: list[bytes], splits: list[int], profile: str | None) -> None:
    data = b"".join(parts)
    assert_same(data, annotator(profile), [cut for cut in splits if cut < len(data)])


@settings(max_examples=150, deadline=None)
@given(
    st.lists(strategies.transactions(strategies.named_slaves), min_size=1, max_size=10),
    st.lists(st.integers(0, 600), max_size=3),
    st.sampled_from(["generic", "atv71", "sel749m", "auto", None]),
)
def test_every_public_code_same_stats(exchanges: list, splits: list[int], profile: str | None) -> None:
    data = strategies.session_bytes(exchanges)
    assert_same(data + b"\x01", annotator(profile), [cut for cut in splits if cut < len(data)])


def cli(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    if pure:
        monkeypatch.setenv("VW3_PURE_PYTHON", "1")
    else:
        monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)
    stdout = io.StringIO()
    assert run(argv, Environment(io.BytesIO(), stdout, io.StringIO(), False, False)) == 0
    return stdout.getvalue()


@pytest.mark.parametrize("extra", [[], ["--json"], ["-n"], ["--profile", "sel749m"], ["--address-style", "plc"]])
def test_cli_stats_same_bytes(extra: list[str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    records = plant_mix(3000, seed=5)
    raw, pcap = write_capture(records, tmp_path / "plant")
    # Several inputs: raw captures (the engine) and a pcap (timed: the Python stages), in either order.
    argv = ["--stats", str(raw), str(ROOT / "captures" / "p38_protection.bin"), *extra]
    assert cli(argv, monkeypatch, pure=False) == cli(argv, monkeypatch, pure=True)
    for argv in (["--stats", str(pcap), str(raw), *extra], ["--stats", str(raw), str(pcap), str(raw), *extra]):
        assert cli(argv, monkeypatch, pure=False) == cli(argv, monkeypatch, pure=True)
    if "--json" in extra:
        report = json.loads(cli(["--stats", str(raw), *extra], monkeypatch, pure=False))
        assert report["frames"] == len(records)


@given(st.lists(st.tuples(st.sampled_from([1, 2, 3]), st.sampled_from([0, 1, 2, 3, 4, 5, 0xFFFE, 0xFFFF]),
                          st.integers(0, 5), st.integers(0, 3), st.sampled_from([None, "ACC", "DEC"])),
                max_size=80),
       st.integers(1, 12), st.integers(1, 4))
@example([(1, 0xFFFE, 0, 1, None), (1, 0xFFFF, 0, 1, None), (2, 0, 0, 1, None), (2, 1, 0, 1, None)], 10, 2)
@settings(max_examples=300, deadline=None)
def test_parameter_table_same_rows(events: list, max_rows: int, group_min: int) -> None:
    """The compiled store's parameter table (Stats.table) gives the rows, pieces, count and sums of the
    Python store's: runs of the next address of a slave (never across slaves: 0xFFFF then 0 of the next),
    the same counts, named or not, cut at max_rows."""
    from dissector.render.stats_store import CompiledStore

    stores = [CompiledStore(50_000), ParameterTable()]
    for slave, address, event, value, code in events:
        for store in stores:
            store.param(slave, address, event, value, code, "protected" if event == 1 else None)
    compiled, python = (store.table(max_rows, group_min) for store in stores)
    assert compiled == python


@pytest.mark.parametrize("extra", [[], ["--json"]])
def test_a_profile_chosen_twice_in_one_pass(extra: list[str], monkeypatch: pytest.MonkeyPatch) -> None:
    """Standard input (one pass): profile auto chooses the ATV71 at frame 5, then the generic profile at
    frame 7 (function 1 answered). The engine's side sees both choices, the Python stages' one batch the
    last only: the codes kept are the last device's (none for 8501), both ways, not the ATV71's CMD
    (bench/fastsummary_fuzz.py seed 16)."""
    data = bytes.fromhex("f70621350006076cf70621350006076c00f70320d10001cb65f703020001b191"
                         "f70120d0001aa36ef7010461e86b065d24")

    def decode(pure: bool) -> str:
        if pure:
            monkeypatch.setenv("VW3_PURE_PYTHON", "1")
        else:
            monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)
        stdout = io.StringIO()
        assert run(["-", "--stats", *extra], Environment(io.BytesIO(data), stdout, io.StringIO(), False, False)) == 0
        return stdout.getvalue()

    fast = decode(False)
    assert fast == decode(True)
    assert "CMD" not in fast and "8501" in fast


@given(st.lists(st.tuples(st.sampled_from([(1, 3), (1, 4), (7, 3)]),
                          st.one_of(st.integers(-10**6, 10**10), st.sampled_from([0, 1, 2, 2_000_000, 2_000_001]))),
                min_size=1, max_size=60))
@settings(max_examples=300, deadline=None)
def test_response_times_kept_exactly(times: list) -> None:
    """The compiled store keeps each pair's response times exactly (TALLY_TIMES): render/stats.py time_summary
    then gives the count, min, median, p95 and max of either side's from the same histogram."""
    from dissector.render.stats_store import TALLY_TIMES, CompiledStore

    store = CompiledStore(50_000)
    expected: dict[int, dict[int, int]] = {}
    for (slave, function), ns in times:
        store.response(slave, function, ns)
        pair = expected.setdefault(slave << 8 | function, {})
        pair[ns] = pair.get(ns, 0) + 1
    assert store.tallies(TALLY_TIMES) == expected
