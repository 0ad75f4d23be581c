"""Parameter memory: each parameter followed across the capture (VW3 A3 303 manual p.38).

A multi-register read returns 16#8000 for a non-existent or protected parameter; a parameter read (or
written) earlier and unreadable now "became protected", one unreadable before and read now is
"readable again". One job: the story of each parameter, told as events (devices/story.py tells them).
The memory is the Device's `seen` dict, which the compiled summary path also keeps up to date; a device
whose input registers are a table of their own (profile input_registers "separate") keeps theirs apart
(Device.memory: FC4's 8401 is not FC3's; the compiled path hands such reads to the annotator). Of several
files read as one bus, the frames of a file read before are cited with it (cite_from).
A frame that failed its check was ignored by the device (Modbus over serial line 2.5.1.2; SEL-749M p. D.3:
"the check fails and the message is ignored"): its values are shown, but the annotator judges no status
of them, tells no story and changes no memory (as --stats and --watch skip it).
"""
from __future__ import annotations

import weakref
from collections.abc import Iterable, Sequence

from dissector.decode.pairing import trusted_request
from dissector.devices.device import Device
from dissector.devices.maps import RegisterDef
from dissector.devices.selection import Cited
from dissector.devices.story import Event
from dissector.model import Frame, Register
from dissector.protocol.rules import text


def unreadable_status(register: Register, row: RegisterDef | None) -> str | None:
    """16#8000 in a multi-register read: non-existent, protected, or (if it can be real) ambiguous; the
    register's status and text set, the status returned when the parameter is unreadable (not ambiguous)."""
    if row is None:
        register.status = "non-existent"
        register.text = text("marker_non_existent")
    elif row.ambiguous_8000:
        # The value may be real: keep its own reading, and what was known of the parameter.
        register.status = "ambiguous"
        return None
    else:
        register.status = "protected"
        register.scaled = None
        register.text = text("marker_protected")
    return register.status


def unreadable(frame: Frame, device: Device, register: Register, row: RegisterDef | None, events: list[Event]) -> None:
    """unreadable_status, and the parameter's story told (it became unreadable)."""
    status = unreadable_status(register, row)
    if status is not None:
        lost(frame, device, register.address, row, status, text("marker_now"), register.label, events)  # type: ignore[arg-type]


def lost(
    frame: Frame, device: Device, address: int, row: RegisterDef | None, status: str, now: str,
    label: str | None, events: list[Event],
) -> None:
    """Record a parameter as unreadable, telling the story if it was readable before."""
    seen = device.memory(frame.function)
    last = seen.get(address)
    if last is not None and last[0] is not None:
        became = text("became_protected" if row is not None else "became_unknown")
        before = text("known_value", how=last[2], value=last[0])
        events.append(Event(became, address, row, label, before, last[2], last[1], now, now, key=True))
    seen[address] = (None, frame.number, status)


def readable_again(
    address: int, row: RegisterDef | None, label: str | None, last: tuple[int | None, int, str], value: int,
    events: list[Event],
) -> None:
    now = text("value_now", value=value)
    events.append(Event(text("readable_again"), address, row, label, last[2], last[2], last[1], now, None))


def remember_writes(frame: Frame, device: Device, registers: Sequence[Register]) -> None:
    seen = device.memory(frame.function)
    number = frame.number
    for register in registers:
        if register.address is not None:
            seen[register.address] = (register.value, number, "written")


def remember_answered(frame: Frame, device: Device) -> None:
    """The writes a normal answer confirms: its request's registers (an FC16 answer carries no values), not
    those of a request that failed its check (pairing.trusted_request)."""
    request = trusted_request(frame)
    if request is not None and request.registers:
        remember_writes(frame, device, request.registers)


def masked_value(current: int | None, and_mask: int, or_mask: int) -> int | None:
    """What a Mask Write leaves in a register that held `current` (None: not known): (current AND and_mask)
    OR (or_mask AND NOT and_mask), Application Protocol 6.16; known without `current` when and_mask is 0."""
    if and_mask == 0:
        current = 0
    return None if current is None else (current & and_mask) | (or_mask & ~and_mask & 0xFFFF)


def remember_mask(frame: Frame, device: Device, masked: dict[int, int | None] | None = None) -> None:
    """A Mask Write its echo confirms (data/modbus.toml [confirm] "mask"): the register holds (current AND
    and_mask) OR (or_mask AND NOT and_mask) (Application Protocol 6.16), written as FC6's value is; where
    the current value is not known (and_mask 0 replaces every bit), the parameter is forgotten. The value
    written (None: not known) also in `masked` by the echo's frame number, for the parameter history
    (render/history.py) to count it with its request's masks: only where it has that request, and no longer
    than the request lives (the echo holds it), so an echo the history never reads (dropped by -Y or -c)
    takes its entry with it: `masked` holds no more entries than echoes alive."""
    fields = frame.fields
    if fields is None:
        return  # (malformed: nothing confirmed)
    seen = device.memory(frame.function)
    address, and_mask = fields.address, fields.and_mask
    last = seen.get(address)
    value = masked_value(last[0] if last is not None else None, and_mask, fields.or_mask)
    if value is None:
        seen.pop(address, None)
    else:
        seen[address] = (value, frame.number, "written")
    request = frame.request
    if masked is not None and request is not None and request.crc_ok:
        if frame.number not in masked:  # (a provisional frame's copy, annotated again, shares its request)
            weakref.finalize(request, masked.pop, frame.number, None)
        masked[frame.number] = value


def cite_from(devices: Iterable[Device], source: str) -> None:
    """Several files read as one bus number their frames each from 1: once `source` is read, the frames its
    memory names are cited with it (selection.Cited: `read 3 in frame #2 of a.bin`), so a story told in
    the next file does not name that file's own frame 2."""
    for device in devices:
        for seen in (device.seen, device.input_seen or {}):
            for address, (value, number, how) in seen.items():
                if type(number) is int:
                    seen[address] = (value, Cited(number, source), how)
