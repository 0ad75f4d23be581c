"""A compiled extension built from older sources (a rebase without a rebuild) is not used: vw3-decode
decodes with the Python stages and says exactly what they say, never a traceback (REVIEW 6: `--stats`
with an old build was `AttributeError: ... 'Stats' object has no attribute 'bus_line'`)."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

# The extension as an older build was: its stamp of other sources, an Engine that takes one argument
# fewer, a Stats without bus_line (the last feature the --stats path added). Loaded from the built
# file before dissector.accel is imported.
STALE = """
import glob, importlib.util, sys, types
path, = glob.glob(sys.argv.pop(1) + "/dissector/accel/_summary*.so")
spec = importlib.util.spec_from_file_location("dissector.accel._summary", path)
real = importlib.util.module_from_spec(spec)
spec.loader.exec_module(real)
stale = types.ModuleType("dissector.accel._summary")
stale.__dict__.update({key: value for key, value in vars(real).items() if not key.startswith("__")})
stale.SOURCES = "0123456789abcdef"

class Stats:
    def __init__(self, *args):
        self._store = real.Stats(*args)

    def __getattr__(self, name):
        if name == "bus_line":
            raise AttributeError("'dissector.accel._summary.Stats' object has no attribute 'bus_line'")
        return getattr(self._store, name)

class Engine:
    def __init__(self, *args):
        raise TypeError(f"Engine() takes at most {len(args) - 1} arguments ({len(args)} given)")

stale.Stats, stale.Engine = Stats, Engine
sys.modules["dissector.accel._summary"] = stale
from dissector.app.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _decode(argv: list[str], stale: bool) -> tuple[int, str, str]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("VW3_PURE_PYTHON", None)
    command = [sys.executable, "-c", STALE, str(ROOT)] if stale else [sys.executable, "-m", "dissector"]
    if not stale:
        env["VW3_PURE_PYTHON"] = "1"  # the reference: the Python stages
    done = subprocess.run([*command, *argv], capture_output=True, text=True, env=env, cwd=ROOT, timeout=120)
    return done.returncode, done.stdout, done.stderr


def test_the_stale_module_would_fail_if_it_were_used() -> None:
    # What the check keeps away: the reviewer's old build (its Engine as today's) run as if its stamp
    # were the sources': --stats is a traceback.
    script = STALE.replace("stale.Stats, stale.Engine = Stats, Engine", "stale.Stats = Stats").replace('sys.modules["dissector.accel._summary"] = stale',
                           'spec = importlib.util.spec_from_file_location("stamp", path[:path.rindex("/")] + "/stamp.py"); '
                           'stamp = importlib.util.module_from_spec(spec); spec.loader.exec_module(stamp); '
                           'stale.SOURCES = stamp.stamp(); sys.modules["dissector.accel._summary"] = stale')
    done = subprocess.run([sys.executable, "-c", script, str(ROOT), "--stats", "captures/p38_protection.bin"],
                          capture_output=True, text=True, cwd=ROOT, timeout=120,
                          env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert done.returncode == 1
    assert done.stderr.splitlines()[-1] == (
        "AttributeError: 'dissector.accel._summary.Stats' object has no attribute 'bus_line'")


@pytest.mark.parametrize("argv", [
    ["captures/p38_protection.bin"],  # the summary's compiled path
    ["captures/atv71_commissioning.pcap"],  # the timed path
    ["--stats", "captures/p38_protection.bin"],  # the engine's --stats store
    ["--stats", "captures/atv71_commissioning.pcap"],
    ["-V", "captures/p38_protection.pcap"],  # framed in C, shown by Python
    ["-Y", "slave == 12", "captures/noisy_bus.pcap"],
])
def test_a_build_from_older_sources_falls_back_to_the_python_stages(argv: list[str]) -> None:
    status, out, err = _decode(argv, stale=True)
    assert (status, err) == (0, "")
    assert (status, out, err) == _decode(argv, stale=False)
    assert out
