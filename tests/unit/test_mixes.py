"""The benchmark mixes (dissector.sim.mixes): reproducible, what they claim to hold, clean to the decoder."""
from __future__ import annotations

from collections import Counter

from dissector.model import Frame, Kind
from dissector.pipeline import dissect_bytes
from dissector.protocol.spec import SPEC
from dissector.sim.mixes import DRIVES, METER, MODULE, RELAYS, max_size_mix, plant_mix


def _frames(records: list[tuple[bytes, float]]) -> list[Frame]:
    items = dissect_bytes(b"".join(data for data, _time in records))
    assert all(isinstance(item, Frame) and item.crc_ok for item in items), "no noise, no bad check"
    return items  # type: ignore[return-value]


def test_mixes_are_reproducible() -> None:
    assert plant_mix(500, seed=3) == plant_mix(500, seed=3)
    assert plant_mix(500, seed=3) != plant_mix(500, seed=4)
    assert max_size_mix(500, seed=3) == max_size_mix(500, seed=3)


def test_plant_mix_holds_the_devices_codes_changing_values_and_few_exceptions() -> None:
    frames = _frames(plant_mix(6000))
    codes = Counter((frame.slave, frame.function) for frame in frames if frame.kind is Kind.REQUEST)
    assert {function for (slave, function) in codes if slave in DRIVES} >= {3, 23}
    assert {function for (slave, function) in codes if slave in RELAYS} >= {3, 4}
    assert {function for (slave, function) in codes if slave == MODULE} == {1, 2, 5, 15}
    assert {function for (slave, function) in codes if slave == METER} >= {4}
    relay_reads = [f for f in frames if f.slave == RELAYS[0] and f.function == 3 and f.kind is Kind.RESPONSE
                   and f.quantity == 40]
    assert len({tuple(r.value for r in f.registers) for f in relay_reads}) > len(relay_reads) // 2
    exceptions = sum(frame.kind is Kind.EXCEPTION for frame in frames)
    transactions = sum(frame.kind is Kind.REQUEST for frame in frames)
    assert 0.003 < exceptions / transactions < 0.02
    assert not [frame.warnings for frame in frames if frame.warnings]


def test_max_size_mix_holds_every_public_code_up_to_the_spec_limits() -> None:
    frames = _frames(max_size_mix(8000))
    assert {frame.function for frame in frames} == set(SPEC.functions)
    assert not [frame.warnings for frame in frames if frame.warnings]
    assert all(not frame.unanswered for frame in frames)
    largest = Counter()
    for frame in frames:
        if frame.kind is Kind.REQUEST and frame.quantity is not None:
            largest[frame.function] = max(largest[frame.function], frame.quantity)
    assert largest[1] > 1900 and largest[2] > 1900 and largest[15] > 1850
    assert largest[3] > 115 and largest[4] > 115 and largest[16] > 115 and largest[23] > 115
    assert len(max(frames, key=lambda frame: frame.length).raw) <= 256
