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

from dissector.model import Frame, Kind, Stamp


def exception_event(annotator: Any | None) -> Callable[[int, int, int, bytes], str]:
    """The text of ReportCollector.add's exception event (render/report/meaning.py): the meaning on the
    slave's device now of the code answering the request (`request_raw`, its bytes with the CRC: decoded
    only when the meaning depends on it)."""
    device = getattr(annotator, "device", None)

    def text(slave: int, function: int, code: int, request_raw: bytes) -> str:
        from dissector.render.report.meaning import device_meaning, event_text, needs_request

        if device is None:
            return event_text(function, code, None)
        owner = device(slave)
        request = _request(request_raw) if needs_request(owner, function, code) else None
        return event_text(function, code, device_meaning(owner, function, code, request))

    return text


def _request(raw: bytes) -> Frame:
    """A request frame decoded from its bytes, as the Python stages give it to the annotator."""
    from dissector.decode.fields import decode_frame

    crc = int.from_bytes(raw[-2:], "little")
    request = Frame(0, raw, None, Kind.REQUEST, raw[0], raw[1] & 0x7F, crc, crc)
    decode_frame(request)
    return request


def engine_report(collector: Any, health: Any | None, annotator: Any | None) -> Any:
    """A compiled Report feeding `collector` and `health` (None: no health section)."""
    from dissector.accel import _summary

    return _summary.Report(collector, health, Stamp, exception_event(annotator))
