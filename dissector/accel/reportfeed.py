"""--report fed by the engine (issue 28): the compiled Report (dissector/accel/_report.h) that the engine's
count path (timedpath.count_input) gives what the report takes of the transactions it counts itself,
into the very objects the Python stages fill (render/report/collect.py ReportCollector, health.py
Health): the x axis, the events, the trends' points and the response times (the setpoints are the parameter table's). The Python
stages' items go to those objects as before, in stream order; the engine takes their state at the
start of each of its runs (Report.pull) and gives it back at the end (Report.push).
tests/differential/test_timed_report.py holds the page byte-identical to VW3_PURE_PYTHON=1.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

from dissector.model import Stamp


def exception_event(annotator: Any | None) -> Callable[[int, int, int], str]:
    """The text of ReportCollector.add's exception event: the device's meaning of the code
    (devices/explain.py: Frame.exception_text) for the slave's profile now."""
    device = getattr(annotator, "device", None)

    def text(slave: int, function: int, code: int) -> str:
        if device is None:
            meaning = None
        else:
            from dissector.devices.explain import device_meaning  # (to a read, p.38's clause: as explain.py)

            meaning = device_meaning(device(slave).profile, function, code)
        return f"exception {code:02X} to function {function & 0x7F}" + (f": {meaning}" if meaning else "")

    return text


def engine_report(collector: Any, health: Any | None, annotator: Any | None) -> Any:
    """A compiled Report feeding `collector` and `health` (None: no health section)."""
    from dissector.accel import _summary

    return _summary.Report(collector, health, Stamp, exception_event(annotator))
