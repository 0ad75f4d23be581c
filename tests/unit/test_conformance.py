"""The shared conformance vectors (tests/conformance/): current with the Python reference, and the
compiled engine gives their summary lines byte for byte (issue 30). The extension must be built: a
missing one fails here, it is not skipped."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
VECTORS = ROOT / "tests" / "conformance"
sys.path.insert(0, str(VECTORS))

import generate  # noqa: E402

CASES = json.loads((VECTORS / "vectors.json").read_text(encoding="utf-8"))["cases"]


def test_vectors_are_current() -> None:
    """A change to the Python semantics must come with refreshed vectors (what the ports check)."""
    result = subprocess.run([sys.executable, str(VECTORS / "generate.py"), "--check"], capture_output=True, text=True)
    assert (result.returncode, result.stderr) == (0, "")


def test_vectors_cover_every_stage_and_rule() -> None:
    stages = {"framing", "pairing", "decoding", "selection", "annotation", "summary"}
    assert all(stages <= set(case) for case in CASES)
    warnings = {w for case in CASES for row in case["decoding"] for w in row["warnings"]}
    # Each lifting rule's text is broken once somewhere (data/modbus.toml [lift]).
    for start in ("quantity 126 outside", "addresses 65520..65551",
                  "byte count 2 disagrees with the registers asked (2)", "odd byte count", "bits asked", "coil value 0x1234", "the response's address and value differ",
                  "the response's start and quantity differ", "with the quantity 124", "write quantity 122",
                  "FIFO count 32 above", "disagrees with the FIFO count"):
        assert any(start in w for w in warnings), start
    assert {"atv71", "sel749m"} == {m["map"] for m in json.loads((VECTORS / "vectors.json").read_text())["maps"]}


def test_lua_twin_holds_the_same_cases() -> None:
    text = (VECTORS / "vectors.lua").read_text(encoding="utf-8")
    assert text.startswith("-- GENERATED") and "\nreturn {" in text
    assert all(generate.lua_literal(case["name"]) in text for case in CASES)


@pytest.mark.parametrize("case", [c for c in CASES if c["mode"] == "rtu"], ids=lambda c: c["name"])
def test_compiled_engine_gives_the_vectors_summary(case: dict[str, object]) -> None:
    from dissector.accel import fastsummary

    assert fastsummary._summary is not None, "the C extension is not built (python3 setup.py build_ext --inplace)"
    lines = generate.summary_lines(str(case["mode"]), bytes.fromhex(str(case["input"])), pure=False)
    assert lines == case["summary"]
