"""Test layout: unit/ (fast, no external tools), differential/ (the compiled path and the framer held
equal to the Python reference, fuzzing), integration/ (tshark, Lua, pseudo-terminal buses); support/
holds the shared helpers. Each test gets the marker of its folder, so `pytest -m "not integration"` is
the fast loop; the README's test command runs everything.

The README's command runs the suite in two steps on a 2-core machine: the tests that need the machine to
themselves (SERIAL: a pseudo-terminal bus, a serial port or loop://, a live capture's silences measured in
real time, a browser, apt-get) alone, marked `serial`, and the rest in two pytest-xdist workers (`-n 2
-m "not serial"`), where one pytest process waiting on tshark or a subprocess left a core idle."""
from __future__ import annotations

import re
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
# What in a test file's text makes it `serial` (a new test of a live bus is serial without being listed).
# A file that measures CPU time against a peer says so itself: `pytestmark = pytest.mark.serial`.
SERIAL = re.compile(r"openpty|\bpty\.|live_bus|Sniffer|\"--live\"|loop://|uart_sim|extcap_harness|chromium|flock|apt-get"
                    r"|pytest\.mark\.serial")


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    serial: dict[str, bool] = {}
    for item in items:
        path = Path(str(item.fspath)).resolve()
        folder = path.relative_to(TESTS).parts[0]
        if folder in MARKED_FOLDERS:
            item.add_marker(getattr(pytest.mark, folder))
        if str(path) not in serial:
            serial[str(path)] = bool(SERIAL.search(path.read_text(encoding="utf-8")))
        if serial[str(path)]:
            item.add_marker(pytest.mark.serial)
