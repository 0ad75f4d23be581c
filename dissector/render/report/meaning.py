"""An exception event's text, with the meaning on its slave's device that the frame's note, -V's `Meaning on
this device` and --json's exception_meaning give it (devices/explain.py exception_meaning), whatever the
profile, of the request its slave got (pairing.trusted_request): a refused write of read-only
parameters says so; causes the profile lists for the code to this function (the SEL-749M's Appendix D,
with the relay counters they increment) are the ones the request picks; else the code's meaning (to a
read, p.38's clause too). The Python stages (collect.py add, _retell) and the engine's events
(accel/reportfeed.py exception_event) tell it alike."""
from __future__ import annotations

from typing import Any

from dissector.devices.access import READ_ONLY_EXCEPTION
from dissector.devices.explain import exception_meaning
from dissector.model import Frame


def event_text(function: int, code: int, meaning: str | None) -> str:
    return f"exception {code:02X} to function {function & 0x7F}" + (f": {meaning}" if meaning else "")


def needs_request(device: Any, function: int, code: int) -> bool:
    """The meaning depends on the request (its registers written, its quantity or byte count): the
    engine decodes it only then."""
    return code == READ_ONLY_EXCEPTION or (function & 0x7F, code) in device.profile.exception_causes


def device_meaning(device: Any, function: int, code: int, request: Frame | None) -> str | None:
    """The exception's meaning on `device` answering `request` (None: not known), as its note says it."""
    return exception_meaning(device, function & 0x7F, code, request)
