"""HTML pieces of the report page: escaped text, numbers in ms, tables (readable without script)."""
from __future__ import annotations

import html
import re
from typing import Any


_SPECIAL = re.compile("[&<>\"']")


class Markup(str):
    """A cell's HTML, made of escaped text (_details): _table writes it as it is."""


def _esc(value: object) -> str:
    if type(value) is int:  # (most cells of the poll table: nothing to escape)
        return str(value)
    if type(value) is Markup:
        return value
    text = "" if value is None else str(value)
    return html.escape(text) if _SPECIAL.search(text) else text


def _details(summary: str, detail: str | None) -> str:
    """A text, with its detail folded under it when it has one (a protection event's registers)."""
    if detail is None:
        return summary
    return Markup(f"<details><summary>{_esc(summary)}</summary>{_esc(detail)}</details>")


def _ms(seconds: float | None) -> str:
    return "" if seconds is None else f"{seconds * 1000:.1f}"


def _table(headers: list[str], rows: list[list[object]], cls: str = "") -> str:
    head = "".join(f"<th>{_esc(header)}</th>" for header in headers)
    body = "".join("<tr><td>" + "</td><td>".join(map(_esc, row)) + "</td></tr>" if row else "<tr></tr>" for row in rows)
    return f'<table class="{cls}"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>'


def cited(data: dict[str, Any], number: int) -> str:
    """A frame as the report cites it: `#12`; of several files read as one bus, whose frames the report
    numbers on from file to file (collect.py new_input, data's `inputs`), by its number in its file as the
    summary shows it under `==> FILE <==`: `#4 of b.bin`."""
    inputs = data.get("inputs")
    if not inputs:
        return f"#{number}"
    numbered, name = next((entry for entry in reversed(inputs) if entry[0] < number), inputs[0])
    return f"#{number - numbered} of {name}"
