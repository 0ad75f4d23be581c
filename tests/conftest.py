"""Test layout: unit/ (fast, no external tools), differential/ (the compiled path and the framer held
equal to the Python reference, fuzzing), integration/ (tshark, Lua, pseudo-terminal buses); support/
holds the shared helpers. Each test gets the marker of its folder, so `pytest -m "not integration"` is
the fast loop; the README's test command runs everything."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
TESTS = Path(__file__).resolve().parent
for path in (ROOT, TESTS / "support"):
    if str(path) not in sys.path:
        sys.path.insert(0, str(path))

SHARED = ROOT.parent / "shared"
MARKED_FOLDERS = ("unit", "differential", "integration")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    for item in items:
        folder = Path(str(item.fspath)).resolve().relative_to(TESTS).parts[0]
        if folder in MARKED_FOLDERS:
            item.add_marker(getattr(pytest.mark, folder))
