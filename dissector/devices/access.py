"""Writes to parameters the map gives as read-only (its access column R, maps.ACCESS): the request is
warned, and the exception that refuses it (data/modbus.toml read_only_exception) means that refusal on the
device (explain.py names them) instead of the code's plain meaning. One job: what a write asks of a
parameter it cannot change."""
from __future__ import annotations

from dissector.decode.pairing import trusted_request
from dissector.devices.device import Device
from dissector.devices.naming import address_name, plc_label
from dissector.model import Frame
from dissector.protocol import table
from dissector.protocol.rules import CONFIRM, Confirm, text
from dissector.protocol.spec import SPEC

READ_ONLY = "R"  # the access of a parameter no write changes (README Device profiles; sim/devices.py)
READ_ONLY_EXCEPTION = SPEC.read_only_exception
# Such an exception's meaning on the device (Frame.exception_text: `Exception meaning on this device`), whatever
# the code's own meaning; the note names the parameters.
READ_ONLY_MEANING = text("read_only_meaning", access=READ_ONLY)
_REGISTER_WRITES = table.register_writes()  # FC6, FC16, FC23: their request's registers are values written
_MASK_WRITES = frozenset(code for code, how in CONFIRM.items() if how is Confirm.MASK)  # FC22: one register


def written_read_only(frame: Frame, device: Device) -> list[str]:
    """The read-only parameters a write request touches, named (`ETA (3201)`; a PLC-style device's
    reference: `SPD (40101)`), in address order."""
    rows = device.rows_for(frame.function)  # (writes: the holding registers)
    if not rows:
        return []
    function = frame.function
    if function in _REGISTER_WRITES:
        addresses = [register.address for register in frame.registers or ()]
    elif function in _MASK_WRITES and frame.start is not None:
        addresses = [frame.start]
    else:
        return []
    named = []
    base = device.base(function) if device.plc is not None else None  # (as the frame shows it: 40101)
    for address in addresses:
        row = rows.get(address)
        if row is not None and row.access == READ_ONLY:
            named.append(address_name(row, address, None if base is None else plc_label(base, address)))
    return named


def read_only_addresses(device: Device) -> frozenset[int]:
    """The addresses of the device's read-only parameters: the compiled path hands a write of one to these
    checks (accel/fastsummary.py SlaveFacts.read_only)."""
    return frozenset(address for address, row in device.rows.items() if row.access == READ_ONLY)


def check_writes(frame: Frame, device: Device) -> None:
    """A write request's read-only parameters, one warning each (the device refuses the write)."""
    for parameter in written_read_only(frame, device):
        frame.warnings.append(text("read_only", parameter=parameter, access=READ_ONLY))


def refused_read_only(frame: Frame, device: Device) -> list[str]:
    """The read-only parameters an exception read_only_exception refuses the write of (its request's),
    named; empty for any other exception (explain.explain_exception names them in its note)."""
    request = trusted_request(frame)  # (not one that failed its check: what it asked is not known)
    if frame.exception_code != READ_ONLY_EXCEPTION or request is None:
        return []
    return written_read_only(request, device)
