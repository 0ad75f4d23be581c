"""The two stores of --stats' per-parameter counts (render/stats_store.py): the compiled one
(`_summary.Stats`, accel/_stats.h) and the pure-Python `ParameterTable` take the same events and give
the same rows; the compiled one refuses bad arguments with an exception, never a crash.
"""
from __future__ import annotations

import random

import pytest

from dissector.accel import _summary
from dissector.render.stats_store import (
    HOLDING_REGISTERS, INPUT_REGISTERS, MAX_KEYS, MAX_TALLY, TALLY_TIMES, Coarse,
    CONFIRM, READ, REFUSED, UNREADABLE, WRITE, WRITE_OBSERVED, ParameterTable, new_store, parameter_rows,
)


def test_the_compiled_store_is_the_default(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)
    assert isinstance(new_store(), _summary.Stats)
    monkeypatch.setenv("VW3_PURE_PYTHON", "1")
    assert isinstance(new_store(), ParameterTable)


def test_one_story_in_both_stores() -> None:
    events = [
        (12, 3104, READ, 500, "HSP", "50.0 Hz"),
        (12, 3104, UNREADABLE, 0, "HSP", "protected"),  # the state becomes the status: a change
        (12, 3104, READ, 500, None, "50.0 Hz"),
        (12, 3104, WRITE, 510, "HSP", "51.0 Hz"),
        (12, 3104, CONFIRM, 510, "HSP", "51.0 Hz"),
        (12, 3104, WRITE, 520, "HSP", "52.0 Hz"),
        (12, 3104, REFUSED, 520, "HSP", "52.0 Hz"),
        (0, 9001, WRITE_OBSERVED, 10, None, None),
        (1, 7, CONFIRM, 3, "NEW", None),  # a code on first sight
        (1, 7, CONFIRM, 4, "LATER", "4 things"),  # CONFIRM keeps the first code
        (1, 7, READ, 4, "READ", None),  # a read sets it
        (5, 1, READ, 3, "X", "3 x"),
        (5, 1, UNREADABLE, 0, "X", "protected"),  # last seen protected
        (5, 1, UNREADABLE, 0, "X", "protected"),  # the same state: no change
        (5, 2, UNREADABLE, 0, None, "non-existent"),  # a first state is no change
    ]
    compiled, python = _summary.Stats(MAX_KEYS), ParameterTable()
    changed = [(compiled.param(*event), python.param(*event)) for event in events]
    assert [a for a, b in changed] == [b for a, b in changed] == [
        False, True, True, False, True, False, False, False, False, True, False, False, True, False, False,
    ]
    assert list(parameter_rows(compiled)) == python.parameters() == [
        (0, 9001, None, 0, 0, 1, 0, 10, None, 0, HOLDING_REGISTERS),  # no text: the tables and JSON show the number
        (1, 7, "READ", 1, 0, 0, 0, 4, None, 1, HOLDING_REGISTERS),
        (5, 1, "X", 1, 2, 0, 0, None, "protected", 1, HOLDING_REGISTERS),  # last: the status, no value
        (5, 2, None, 0, 1, 0, 0, None, "non-existent", 0, HOLDING_REGISTERS),
        (12, 3104, "HSP", 2, 1, 2, 1, 510, "51.0 Hz", 3, HOLDING_REGISTERS),  # 500 -> protected -> 500 -> 510
    ]
    # A profile chosen later names the values kept of its slave (and leaves statuses as they are).
    namers = {1: lambda address, value, table: (f"{value} named", "NAMED"),
              5: lambda address, value, table: ("never", "Y")}
    compiled.rename(namers)
    python.rename(namers)
    assert list(parameter_rows(compiled)) == python.parameters()
    assert [row[2] for row in python.parameters()] == [None, "NAMED", "Y", "Y", "HSP"]
    assert [row[8] for row in python.parameters()] == [None, "4 named", "protected", "non-existent", "51.0 Hz"]


def test_rename_names_each_table_by_its_rows() -> None:
    """A profile chosen later names a kept input register by the rows of the input table: a map in PLC
    references names 30001 (input register 0) and 40001 (holding register 0) apart (Device.table_rows), and
    both stores ask the namer with the parameter's table (they asked (address, value): IN0 was named HR0)."""
    rows = {HOLDING_REGISTERS: {0: "HR0"}, INPUT_REGISTERS: {0: "IN0"}}
    namers = {1: lambda address, value, table: (f"{value} of {rows[table][address]}", rows[table][address])}
    compiled, python = _summary.Stats(MAX_KEYS), ParameterTable()
    for store in (compiled, python):
        store.param(1, 0, READ, 7, None, None, INPUT_REGISTERS)
        store.param(1, 0, READ, 9, None, None, HOLDING_REGISTERS)
        store.rename(namers)
    assert list(parameter_rows(compiled)) == python.parameters()
    assert [(row[1], row[2], row[8], row[10]) for row in python.parameters()] == [
        (0, "HR0", "9 of HR0", HOLDING_REGISTERS), (0, "IN0", "7 of IN0", INPUT_REGISTERS)]


def test_random_events_same_rows() -> None:
    rng = random.Random(3)
    compiled, python = _summary.Stats(MAX_KEYS), ParameterTable()
    for _ in range(20_000):
        kind = rng.randrange(6)
        event = (
            rng.choice([1, 2, 247]), rng.randrange(40), kind, rng.choice([0, 1, 2, 0x8000, 65535]),
            rng.choice([None, "A", "B"]),
            rng.choice(["protected", "non-existent"]) if kind == UNREADABLE else rng.choice([None, "x", "y"]),
        )
        assert compiled.param(*event) == python.param(*event)
    assert list(parameter_rows(compiled)) == python.parameters()
    assert compiled.parameter_count == python.parameter_count == len(python.parameters())
    # The report's setpoints (html.py): a parameter's writes, 0 for one never seen (address 40).
    keys = [(slave, address) for slave in (1, 2, 3, 247) for address in range(41)]
    assert [compiled.writes(*key) for key in keys] == [python.writes(*key) for key in keys]
    assert any(python.writes(*key) for key in keys)


def test_poll_keys_in_the_order_first_seen() -> None:
    store = _summary.Stats(MAX_KEYS)
    store.poll((12, 3, 8400, 3), 5, False)
    store.poll((1, 23, 3201, 2, 8501, 2), 2, False)
    store.poll((12, 3, 8400, 3), 9, True)
    store.poll((12, 8, 0), 11, False)
    store.poll_fail((1, 23, 3201, 2, 8501, 2))
    store.poll_fail((7, 7))  # never seen: nothing to miss
    assert store.polls() == [
        ((12, 3, 8400, 3), 5, 2, 1),
        ((1, 23, 3201, 2, 8501, 2), 2, 1, 1),
        ((12, 8, 0), 11, 1, 0),
    ]


@pytest.mark.parametrize(
    "arguments",
    [
        (256, 1, READ, 1, None, None),
        (1, 65536, READ, 1, None, None),
        (1, 1, 6, 1, None, None),
        (1, 1, READ, 70000, None, None),
        (1, 1, READ, -1, None, None),
        ("1", 1, READ, 1, None, None),
    ],
)
def test_bad_events_are_refused(arguments: tuple) -> None:
    with pytest.raises((ValueError, TypeError, OverflowError)):
        _summary.Stats(MAX_KEYS).param(*arguments)


@pytest.mark.parametrize("key", [(), (1,), (1, 2, 3, 4, 5, 6, 7), [1, 3], (1, "3"), (1, -3), (1, 2**40)])
def test_bad_poll_keys_are_refused(key: object) -> None:
    store = _summary.Stats(MAX_KEYS)
    with pytest.raises((ValueError, TypeError, OverflowError)):
        store.poll(key, 1, False)
    with pytest.raises((ValueError, TypeError, OverflowError)):
        store.poll_fail(key)


def test_an_engine_takes_only_a_store() -> None:
    from dissector.accel import fastsummary

    engine = fastsummary.make_engine(None)
    with pytest.raises(TypeError):
        engine.stats = object()
    engine.stats = store = _summary.Stats(MAX_KEYS)
    assert engine.stats is store
    engine.stats = None
    assert engine.stats is None


def test_histograms_of_a_kind_stay_within_their_limit() -> None:
    """Coarse (and the compiled store's Tallies): past `limit` entries together, every key of the kind is
    rounded down to a multiple of 2**shift, the smallest shift at which they fit, whatever the order."""
    values = [(owner, key) for owner in range(3) for key in (-5, 0, 1, 2, 3, 9, 10, 11, 1000)]
    results = set()
    for seed in range(5):
        random.Random(seed).shuffle(values)
        coarse = Coarse(limit=12)
        histograms = [coarse.histogram() for _owner in range(3)]
        for owner, key in values:
            coarse.add(histograms[owner], key)
        results.add((coarse.shift, tuple(tuple(sorted(histogram.items())) for histogram in histograms)))
    # shift 1: 6 keys an owner (18 > 12); shift 2: -8 0 8 1000, 4 an owner (12)
    assert results == {(2, (((-8, 1), (0, 4), (8, 3), (1000, 1)),) * 3)}
    store = _summary.Stats(MAX_KEYS, 1 << 18, 12)
    for owner, key in values:
        store.response(0, owner, key)
    assert store.tallies(TALLY_TIMES) == {owner: {-8: 1, 0: 4, 8: 3, 1000: 1} for owner in range(3)}
    assert Coarse(limit=0).limit == 0 and Coarse().limit == MAX_TALLY
