"""The plugin's CRC answers where the bytes repeat a short pattern (lua/src/crc.lua keeps them by the pattern,
its period and the lengths asked, for floods that weigh a frame at every byte): crc_ok_at, crc_scan and
crc_lengths give, at every start and length asked, in the orders the framer asks them, what the Python
reference's CRC gives for the same bytes (protocol/crc.py), under lua5.2 and lua5.4. Patterns of 1 to 5 bytes
(5: past the ones kept, computed), runs broken by another byte, runs that end before a window does, and
patterns whose windows do end in their CRC (found by search: a scan's lengths are then not empty)."""
from __future__ import annotations

import random
import subprocess
from pathlib import Path

import pytest

from dissector.protocol.crc import crc16, crc_lengths
from lua_harness import PLUGIN, ensure_tool

MAX_ADU = 256

RUNNER = """
local plugin, queries = arg[1], arg[2]
dofile(plugin)
local M = package.loaded["vw3.env"]
local b, n, out = nil, 0, {}
for line in io.lines(queries) do
  local what, x, y = line:match("^(%a+) (%x*) ?(%d*)$")
  if what == "buffer" then
    b, n = {}, #x / 2
    for k = 0, n - 1 do b[k] = tonumber(x:sub(2 * k + 1, 2 * k + 2), 16) end
  else
    local i, l = tonumber(x, 16), tonumber(y)
    if what == "ok" then out[#out + 1] = tostring(M.crc_ok_at(b, i, l))
    elseif what == "scan" then out[#out + 1] = tostring(M.crc_scan(b, i, 4, l))
    else out[#out + 1] = table.concat(M.crc_lengths(b, i, n, 4, l), ",") end
  end
end
print(table.concat(out, "\\n"))
"""


def _matching(period: int, rng: random.Random) -> bytes:
    """A pattern of `period` bytes whose repetition ends in its CRC at some length from some phase."""
    for _ in range(20000):
        pattern = bytes(rng.getrandbits(8) for _ in range(period))
        run = pattern * (2 * MAX_ADU // period)
        if any(crc_lengths(run, phase, 4, MAX_ADU) for phase in range(period)):
            return pattern
    raise AssertionError(f"no pattern of {period} bytes found")


def _buffers() -> list[bytes]:
    rng = random.Random(64)
    buffers = []
    for period in (1, 2, 3, 4, 5):
        for pattern in (_matching(period, rng), bytes(rng.getrandbits(8) for _ in range(period))):
            other = bytes([pattern[0] ^ 0x55])
            noise = bytes(rng.getrandbits(8) for _ in range(7))
            # a run, a byte that breaks it, the run again (another phase), a run too short for a window
            buffers.append(noise + pattern * (400 // period) + other + pattern * (150 // period) + noise
                           + pattern * 5 + noise)
    return buffers


def _queries(data: bytes, rng: random.Random) -> list[tuple[str, int, int]]:
    n, asked = len(data), []
    starts = list(range(0, n - 4))
    # the lengths the framer's layouts ask, and every length at which a window here ends in its CRC: an answer
    # kept for the wrong phase or past a run's end is then a wrong answer, not one more `false`
    lengths = sorted({8, 16, 28, 36, 255} | {length for i in starts for length in crc_lengths(data, i, 8, MAX_ADU)})
    # the framer's orders: ascending, each start then the windows after its readings (i + 28, i + 36); and at random
    orders = [starts, [j for i in starts for j in (i, i + 28, i + 36, i + 8) if j < n - 4], rng.sample(starts, len(starts))]
    for order in orders:
        for i in order:
            for length in lengths:
                if i + length <= n:
                    asked.append(("ok", i, length))
            last = min(MAX_ADU, n - i)
            asked.append(("lengths" if rng.random() < 0.5 else "scan", i, last))
    return asked


def _expected(data: bytes, what: str, i: int, length: int) -> str:
    if what == "ok":
        crc = crc16(data[i:i + length - 2])
        return str(data[i + length - 2] | data[i + length - 1] << 8 == crc).lower()
    found = crc_lengths(data, i, 4, length)
    if what == "scan":
        return str(found[0] if found else 0)
    return ",".join(map(str, found))


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_crc_answers_in_repeated_patterns_are_the_reference_answers(tmp_path: Path, lua: str) -> None:
    runner = tmp_path / "periodic.lua"
    runner.write_text(RUNNER, encoding="utf-8")
    rng = random.Random(7)
    lines, expected = [], []
    for data in _buffers():
        lines.append(f"buffer {data.hex()}")
        for what, i, length in _queries(data, rng):
            lines.append(f"{what} {i:x} {length}")
            expected.append(_expected(data, what, i, length))
    queries = tmp_path / "queries.txt"
    queries.write_text("\n".join(lines) + "\n", encoding="utf-8")
    done = subprocess.run([ensure_tool(lua, lua), str(runner), str(PLUGIN), str(queries)], capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    got = done.stdout.split("\n")[:len(expected)]
    assert len(got) == len(expected)
    wrong = [(line, g, e) for line, g, e in zip([q for q in lines if not q.startswith("buffer")], got, expected) if g != e]
    assert not wrong, wrong[:10]
    # (the matching patterns' windows do end in their CRC: the kept answers are not all `false` and none)
    assert sum(1 for e in expected if e not in ("false", "0", "")) > 100
