"""The fast -V and --json writers held equal to their reference forms.

`item_to_json` splices cached register texts into json.dumps' output; it must give json.dumps(item_to_dict)
byte for byte. `detail_text` joins the flat detail lines without a tree; it must give the tree's plain
rendering. `BitList` decodes packed bits in bulk; it must hold the bits one `Bit` per coil would.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dissector.devices.build import build_annotator
from dissector.model import Bit, BitList, Chunk, Frame, Register, RegisterList, Stamp
from dissector.pipeline import dissect, dissect_bytes
from dissector.render.detail import detail_tree, render_plain
from dissector.render.detail_plain import detail_text
from dissector.render.jsonout import item_to_dict, item_to_json
from dissector.sim.mixes import PLANT_PROFILES, max_size_mix, plant_mix
from dissector.sim.simulate import generate_session
from strategies import session_bytes, transactions

from conftest import ROOT

PROFILES = [["atv71"], ["sel749m"], ["generic"], PLANT_PROFILES, ["atv71", "1=sel749m"]]


def _check(items: list, extra: dict | None = None, base: float | None = 0.5) -> None:
    # The fast writers first, while register blocks are still columns (RegisterList.plain); the
    # references then make every Register object.
    fast = [(item_to_json(item, extra), detail_text(item, base)) for item in items]
    for item, (json_text, text) in zip(items, fast):
        record = item_to_dict(item)
        if extra:
            record.update(extra)
        assert json_text == json.dumps(record)
        assert text == render_plain(detail_tree(item, base))


@pytest.mark.parametrize("path", sorted((ROOT / "captures").glob("*.bin")), ids=lambda path: path.name)
@pytest.mark.parametrize("profiles", PROFILES, ids=lambda profiles: ",".join(profiles))
def test_captures(path: Path, profiles: list[str]) -> None:
    items = dissect_bytes(path.read_bytes(), annotate=build_annotator(profiles, []))
    _check(items)
    _check(items, {"file": "x.bin"})  # repeated: every register text now comes from the cache


@pytest.mark.parametrize("profiles", PROFILES, ids=lambda profiles: ",".join(profiles))
def test_mixes(profiles: list[str]) -> None:
    data = b"".join(raw for raw, _time in plant_mix(3000, seed=5) + max_size_mix(1500, seed=5))
    _check(dissect_bytes(data, annotate=build_annotator(profiles, [])))


@pytest.mark.parametrize("profiles", PROFILES, ids=lambda profiles: ",".join(profiles))
def test_stamped_records(profiles: list[str]) -> None:
    """Records stamped with integer nanoseconds, as pcap and pcapng give them: -V's arrival, relative and
    response times from the integers, and the middles of polled frames kept by their bytes (a second
    pass: every one from the caches, the blocks then Register objects), as the tree writes them."""
    records = generate_session(600, seed=4) + plant_mix(1500, seed=4) + max_size_mix(600, seed=4)
    chunks = [Chunk(data, Stamp(round(time * 1e9) + index * 7), boundary=True)
              for index, (data, time) in enumerate(records)]
    items = list(dissect(chunks, annotate=build_annotator(profiles, [])))
    assert all(type(item.time) is Stamp for item in items)
    for base in (items[0].time, Stamp(items[0].time.ns - 5), None):
        _check(items, base=base)


def test_kept_middles_follow_labels_and_names() -> None:
    """Frames of the same bytes and start whose registers are labelled or named otherwise are not
    written from the text kept for the first."""
    frames = [item for item in dissect_bytes(bytes.fromhex("0C0320D00003 0EEF 0C0306000100020003 2A74"))]
    answer = frames[1]
    plain = detail_text(answer, None)
    assert "Register 8400: 1 (0x0001)" in plain
    same = dissect_bytes(bytes.fromhex("0C0320D00003 0EEF 0C0306000100020003 2A74"))[1]
    same.registers.labels = ["48401", "48402", "48403"]  # type: ignore[union-attr]
    assert "Register 48401: 1 (0x0001)" in detail_text(same, None)
    assert detail_text(same, None) == render_plain(detail_tree(same, None))
    texts = []
    for status in ("ok", "protected", "ok"):
        named = dissect_bytes(bytes.fromhex("0C0320D00003 0EEF 0C0306000100020003 2A74"))[1]
        registers = list(named.registers)  # type: ignore[arg-type]
        named.registers = registers
        registers[1].code, registers[1].status = "CHCF", status
        texts.append(detail_text(named, None))
        assert texts[-1] == render_plain(detail_tree(named, None))
    assert "Register 8401: 2 (0x0002)  CHCF" in texts[1] and "Status: protected" in texts[1]
    assert "Status: protected" not in texts[0] and texts[2] == texts[0] and detail_text(answer, None) == plain


@settings(deadline=None, max_examples=150, suppress_health_check=list(HealthCheck))
@given(st.lists(transactions(st.integers(0, 247)), min_size=1, max_size=6), st.sampled_from(PROFILES))
def test_random_transactions(exchanges: list, profiles: list[str]) -> None:
    data = session_bytes(exchanges)
    _check(dissect_bytes(data, annotate=build_annotator(profiles, [])))


def _reference_bits(start: int | None, packed: bytes, count: int) -> list[Bit]:
    """What decoding made before BitList: one Bit per coil."""
    return [
        Bit(None if start is None else (start + index) & 0xFFFF, packed[index >> 3] >> (index & 7) & 1)
        for index in range(count)
    ]


@given(st.one_of(st.none(), st.integers(0, 0xFFFF)), st.binary(max_size=260), st.data())
def test_bitlist_holds_the_bits_one_per_coil(start: int | None, packed: bytes, data: st.DataObject) -> None:
    count = data.draw(st.integers(0, len(packed) * 8))
    bits, reference = BitList(start, packed, count), _reference_bits(start, packed, count)
    assert len(bits) == count and list(bits) == reference and bits == reference
    assert bits.values == [bit.value for bit in reference]
    assert list(bits.addresses) == [bit.address for bit in reference]
    assert bits[:32] == reference[:32] and bits[3:-2] == reference[3:-2]
    if count:
        index = data.draw(st.integers(-count, count - 1))
        assert bits[index] == reference[index]
    with pytest.raises(IndexError):
        bits[count]


def test_frames_of_the_max_size_mix_carry_bitlists_after_decoding() -> None:
    frames = [item for item in dissect_bytes(b"".join(raw for raw, _t in max_size_mix(400))) if isinstance(item, Frame)]
    assert any(isinstance(frame.bits, BitList) and len(frame.bits) > 100 for frame in frames)


@given(st.one_of(st.none(), st.integers(0, 0xFFFF)), st.lists(st.integers(0, 0xFFFF), max_size=130), st.booleans())
def test_registerlist_holds_one_register_per_value(start: int | None, values: list[int], labelled: bool) -> None:
    registers = RegisterList(start, values)
    labels = [f"4{index:04d}" for index in range(len(values))] if labelled else None
    registers.labels = labels
    reference = [
        Register(None if start is None else (start + index) & 0xFFFF, value, label=None if labels is None else labels[index])
        for index, value in enumerate(values)
    ]
    assert list(registers.addresses) == [register.address for register in reference]
    assert registers.plain and len(registers) == len(values)
    assert list(registers) == reference and registers == reference and not registers.plain
    if values:
        registers[0].status = "ok"  # made once and kept: a change stays
        assert registers[0].status == "ok" and registers[:1] == [registers[0]]


@pytest.mark.parametrize("profiles", PROFILES, ids=lambda profiles: ",".join(profiles))
def test_bulk_annotation_is_the_per_register_one(profiles: list[str]) -> None:
    """The annotator labels a block without map rows in bulk; as Register objects it gives the same."""
    data = b"".join(raw for raw, _time in plant_mix(3000, seed=7) + max_size_mix(800, seed=7))
    captures = [path.read_bytes() for path in sorted((ROOT / "captures").glob("*.bin"))]
    for capture in [data, *captures]:
        bulk = build_annotator(profiles, [])
        per_register = build_annotator(profiles, [])

        def as_objects(frame: Frame) -> None:
            if isinstance(frame.registers, RegisterList):
                frame.registers = list(frame.registers)
            per_register(frame)

        fast = [item_to_dict(item) for item in dissect_bytes(capture, annotate=bulk)]
        assert fast == [item_to_dict(item) for item in dissect_bytes(capture, annotate=as_objects)]


def _utc_reference(seconds: float) -> str:
    from datetime import datetime, timezone

    try:
        moment = datetime.fromtimestamp(seconds, tz=timezone.utc)
    except (OverflowError, OSError, ValueError):
        return f"{seconds:.6f}"
    return f"{moment.year:04d}-{moment:%m-%d %H:%M:%S.%f} UTC"


@given(st.one_of(
    st.integers(0, 4 * 10**18).map(lambda ns: ns / 1e9),
    st.floats(allow_nan=True, allow_infinity=True),
    st.tuples(st.integers(-10**11, 10**11), st.sampled_from([0.0, 0.5, 5e-7, -5e-7, 0.9999995, 0.9999994999, 1e-7]))
    .map(lambda pair: pair[0] + pair[1]),
))
@settings(max_examples=3000, deadline=None)
def test_arrival_time_text_is_datetimes(seconds: float) -> None:
    """-V's `Arrival time` keeps each second's text and appends the microseconds: it must be what
    datetime.fromtimestamp gives (its rounding half to even carries into the next second), out of range
    and non-finite times included."""
    from dissector.render.timefmt import utc_text

    assert utc_text(seconds) == _utc_reference(seconds)
