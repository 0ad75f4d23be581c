"""Notes a field engineer can read: what happened to parameters in one frame, told once per event.

The parameter memory (devices/memory.py) reports events one register at a time; a read of 96
registers that were non-existent before would otherwise draw 96 notes. Here events of one kind and one
past (same status, same frame) are told as one note, neighbouring addresses as ranges:

    39193..39288 readable again (96): non-existent in frame #1576

A note keeps every range (JSON and -V show it whole); its short form, for the summary line, lists the
first few and `… (+N more)`. A parameter that became protected or non-existent is a key event: the
summary highlights it.
"""
from __future__ import annotations

from dataclasses import dataclass

from dissector.devices.maps import RegisterDef
from dissector.devices.naming import address_name
from dissector.model import Note
from dissector.protocol.rules import text

SHORT_RUNS = 4  # address runs a summary line names before `… (+N more)`


@dataclass(slots=True)
class Event:
    """One parameter's change: it became unreadable (a key event) or readable again (data/modbus.toml
    [texts]: became_protected, became_unknown, readable_again)."""

    what: str
    address: int
    row: RegisterDef | None
    label: str | None  # the address as the screen shows it (PLC style), None: the address itself
    before: str  # `read 3` / `non-existent`: what was known, for one address
    how: str  # `read` / `non-existent`: the same without the value, for a range
    frame: int  # where it was known
    now: str  # `16#8000 now`, `exception 02 now`, `28092 now`
    now_shared: str | None  # the same for a range (None: values differ, the registers show them)
    key: bool = False  # the parameter became unreadable


def _run_text(run: list[Event]) -> str:
    first = run[0]
    if len(run) == 1:
        return address_name(first.row, first.address, first.label)
    last = run[-1]
    return f"{first.label or first.address}..{last.label or last.address}"


def _runs(events: list[Event]) -> list[list[Event]]:
    ordered = sorted(events, key=lambda event: event.address)
    runs: list[list[Event]] = []
    for event in ordered:
        if runs and event.address == runs[-1][-1].address + 1:
            runs[-1].append(event)
        else:
            runs.append([event])
    return runs


def listed(parts: list[tuple[str, int]], limit: int) -> tuple[str, str]:
    """(every part, the first `limit` parts and `… (+N more)`), parts given as (text, addresses)."""
    full = ", ".join(text for text, _ in parts)
    if len(parts) <= limit:
        return full, full
    rest = sum(count for _, count in parts[limit:])
    return full, ", ".join(text for text, _ in parts[:limit]) + f", … (+{rest} more)"


def tell(events: list[Event]) -> list[Note]:
    """One note per event kind and past, in the order the events first came."""
    groups: dict[tuple[str, str, int, str | None], list[Event]] = {}
    for event in events:
        groups.setdefault((event.what, event.how, event.frame, event.now_shared), []).append(event)
    notes = []
    for (what, how, frame, now), group in groups.items():
        key = group[0].key
        if len(group) == 1:
            event = group[0]
            name = address_name(event.row, event.address, event.label)
            notes.append(Note(text("event_one", name=name, what=what, before=event.before, frame=frame, now=event.now),
                              key=key))
            continue
        parts = [(_run_text(run), len(run)) for run in _runs(group)]
        full, short = listed(parts, SHORT_RUNS)
        form = "event_runs_now" if now else "event_runs"
        said = {"what": what, "count": len(group), "how": how, "frame": frame, "now": now}
        notes.append(Note(text(form, runs=full, **said), text(form, runs=short, **said), key=key))
    return notes
