"""The stamp of the compiled extension's sources, one value for every feature the callers use.

setup.py builds `SOURCES = stamp()` into dissector.accel._summary; dissector/accel/__init__.py compares
it once with the stamp of the sources beside it. A build older than its sources (a rebase without a
rebuild) lacks what the callers use (Engine.frames, Stats.bus_line, ...): it is then not imported at
all and every caller takes the Python stages, never a traceback. Without the sources (an installed
wheel) the build is trusted.
"""
from __future__ import annotations

import hashlib
import os

FOLDER = os.path.dirname(os.path.abspath(__file__))


def stamp(folder: str = FOLDER) -> str | None:
    """The first 16 hex digits of the SHA-256 of every .c and .h file of `folder` in name order (each
    name, then its bytes); None when there is none (the sources are not shipped)."""
    digest = hashlib.sha256()
    names = sorted(name for name in os.listdir(folder) if name.endswith((".c", ".h")))
    if "_summary.c" not in names:
        return None
    for name in names:
        with open(os.path.join(folder, name), "rb") as source:
            digest.update(name.encode() + b"\0" + source.read())
    return digest.hexdigest()[:16]
