"""The compiled columns' JSON numbers (dissector/accel/_columns.h json_number, through fixed_text: one rounding
of the exact binary value, half to even) against json.dumps of Python's round() (render/report/columns.py
drawn, the reference), for every digits the page may ask (x: 6 timed, 0 untimed; y scaled: places), on exact
binary halves, values a hair either side of them, negative zero and random values. The extension must be
built: it is not skipped."""
from __future__ import annotations

import json
import math
import random

import pytest

from dissector.accel._summary import Columns as CompiledColumns
from dissector.render.report.collect import Columns, drawn


def _values(rng: random.Random, digits: int) -> list[float]:
    halves = [(k + 0.5) / 10**digits for k in range(-40, 40)]  # (exact in binary where 10^digits divides 2^n)
    near = [math.nextafter(h, math.inf) for h in halves] + [math.nextafter(h, -math.inf) for h in halves]
    exact = [k / 2**j for k in range(-9, 10) for j in range(1, 12)]
    spread = [rng.uniform(-1e8, 1e8) / 10 ** rng.randrange(0, 9) for _ in range(300)]
    return [0.0, -0.0, 1e-4, -1e-4, 999_999_999.5, *halves, *near, *exact, *spread]


# The page asks 6 and 0 (x) and 3 (places); at 8 and 9 digits, a value near 1e8 rounded has a shorter repr than
# its fixed-point text, which json_number writes (the same before fixed_text took every such number): not asked.
@pytest.mark.parametrize("digits", range(8))
def test_json_numbers_as_python_writes_them(digits: int) -> None:
    rng = random.Random(digits)
    values = [v for v in _values(rng, digits) if abs(v) < 1e9]
    # Each value a column of its own: x = origin + value, y = the value (drawn: x rounded to `digits`; y
    # scaled by 1 and rounded to `digits` places, so both go through the same rounding).
    python, compiled = Columns(), CompiledColumns()
    origin = 0.0
    for col, v in enumerate(sorted(set(values))):
        python.add(col, v, v), compiled.add(col, v, v)
    expected = tuple(json.dumps(lst, separators=(",", ":")) for lst in drawn(python, origin, digits, 1.0, digits))
    assert compiled.drawn_json(origin, digits, 1.0, digits) == expected
