"""Named styles, overridable as a rich Theme; renderers use the names, never colours."""
from __future__ import annotations

from rich.theme import Theme

STYLES = {
    "vw3.number": "dim",
    "vw3.time": "dim",
    "vw3.slave": "bold",
    "vw3.request": "cyan",
    "vw3.response": "green",
    "vw3.exception": "bold red",
    "vw3.noise": "magenta",
    "vw3.crc.ok": "dim green",
    "vw3.crc.bad": "bold red",
    "vw3.warning": "yellow",
    "vw3.pairing": "dim",
    "vw3.note": "",  # explanations: plain, not dim (they are what the line is for)
    "vw3.key": "bold yellow",  # key events: a parameter became protected or non-existent
    "vw3.protected": "bold yellow",
    "vw3.field": "bold",
    "vw3.hex": "",
}

THEME = Theme(STYLES)
