"""The plain-Lua conformance runner (lua/tests/conformance.lua) fails when the Python reference says
something else than the plugin's modules: one expected value changed in a copy of the vectors
(tests/conformance/vectors.json, written as generate.py writes vectors.lua), stage by stage, and the
runner names the case and stage that differ and exits 1, under lua5.2 and lua5.4. (That it passes on
the vectors as generated: test_lua_modules.py.)"""
from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from lua_harness import PLUGIN, ROOT, ensure_tool

CONFORMANCE = ROOT / "tests" / "conformance"
RUNNER = ROOT / "lua" / "tests" / "conformance.lua"
sys.path.insert(0, str(CONFORMANCE))
from generate import render  # noqa: E402  (tests/conformance is no package)


def _case(data: dict[str, Any], name: str) -> dict[str, Any]:
    return next(case for case in data["cases"] if case["name"] == name)


def _first_with(rows: list[dict[str, Any]], key: str) -> dict[str, Any]:
    return next(row for row in rows if row.get(key))


# (the stage's name in the runner's output, how the copy's expectation is changed)
CHANGES: dict[str, tuple[str, Callable[[dict[str, Any]], None]]] = {
    "framing": ("fc5 echo differs framing",
                lambda d: _case(d, "fc5 echo differs")["framing"][0].update(slave=6)),
    "pairing": ("seed pages in order pairing",
                lambda d: _first_with(_case(d, "seed pages in order")["pairing"], "request").update(request=None)),
    "decoding": ("capture p38_protection.bin decoding",
                 lambda d: _first_with(_case(d, "capture p38_protection.bin")["decoding"], "registers")
                 ["registers"][0].__setitem__(1, 0x1234)),
    "lifting": ("fc16 quantity above the limit decoding",
                lambda d: _case(d, "fc16 quantity above the limit")["decoding"][0]["warnings"].clear()),
    "selection": ("capture p38_protection.bin selection",
                  lambda d: _case(d, "capture p38_protection.bin")["selection"][0].update(profile="sel749m")),
    "annotation": ("capture p38_protection.bin annotation",
                   lambda d: _first_with(_case(d, "capture p38_protection.bin")["annotation"], "registers")
                   ["registers"][1].update(text="IO")),
    "maps": ("map atv71 ", lambda d: next(m for m in d["maps"] if m["map"] == "atv71")["rows"][0].update(name="x")),
    # (the message as the plugin said it before it took maps.py's: Lua's %q, not Python's repr)
    "map reading": ("map reading address", lambda d: next(e for e in d["map_reading"] if e["name"] == "address")
                    .update(error='map.csv:2: address "x1" is not a number')),
}


def _run(lua: str, vectors: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([ensure_tool(lua, lua), str(RUNNER), str(PLUGIN), str(vectors)], capture_output=True,
                          text=True, timeout=300)


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
@pytest.mark.parametrize("stage", sorted(CHANGES))
def test_a_changed_vector_fails_the_runner(tmp_path: Path, stage: str, lua: str) -> None:
    data = json.loads((CONFORMANCE / "vectors.json").read_text(encoding="utf-8"))
    where, change = CHANGES[stage]
    change(data)
    vectors = tmp_path / "vectors.lua"
    vectors.write_text(render(data)[1], encoding="utf-8")
    result = _run(lua, vectors)
    assert result.returncode == 1, (result.stdout[-2000:], result.stderr[-2000:])
    lines = result.stdout.splitlines()
    assert lines[-1].endswith(" 1 differences"), lines[-1]
    assert lines[0].startswith(where), lines[0][:300]


def test_the_vectors_as_generated_pass(tmp_path: Path) -> None:
    # the copy unchanged (written from vectors.json as above): the failures above come from the change alone
    vectors = tmp_path / "vectors.lua"
    vectors.write_text(render(json.loads((CONFORMANCE / "vectors.json").read_text(encoding="utf-8")))[1],
                       encoding="utf-8")
    result = _run("lua5.4", vectors)
    assert result.returncode == 0 and result.stdout.splitlines()[-1].endswith(" 0 differences"), result.stdout[-2000:]
