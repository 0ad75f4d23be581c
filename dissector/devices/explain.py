"""Exceptions in the device's own terms: the spec's name stays in the Info column, the device's
meaning is said once, in one note (with the relay counters an error increments, or the parameters a
refused read was made of). One job: what an exception means on this device."""
from __future__ import annotations

from itertools import combinations

from dissector.decode.pairing import trusted_request
from dissector.devices.access import (READ_ONLY, READ_ONLY_EXCEPTION, READ_ONLY_MEANING, refused_read_only,
                                      written_read_only)
from dissector.devices.device import Device
from dissector.devices.memory import lost
from dissector.devices.naming import address_name, plc_label
from dissector.devices.profiles import ExceptionCause, Profile
from dissector.devices.story import Event, listed
from dissector.model import Frame, Kind, Note, Register
from dissector.protocol import table
from dissector.protocol.rules import text
from dissector.protocol.spec import SPEC
from dissector.protocol.table import lift_of

# Reads whose exception can be explained parameter by parameter (FC23 may fail on its write part).
PLAIN_READS = table.plain_register_reads()
REGISTER_READS = table.register_reads()  # (FC23 too: its read part may be the one refused)
SHORT_PARTS = 6  # runs of parameters a summary line names in an exception explanation
READ_LIMIT = int(SPEC.limits["read_registers"][1])  # type: ignore[index]
_EXPLAINED_LIMIT = 4096  # explanations kept per device: memory stays bounded whatever the capture


def explain_exception(frame: Frame, device: Device, events: list[Event]) -> None:
    profile = device.profile
    code = frame.exception_code
    if code is None:
        return
    function = frame.function
    name = profile.function_names.get(function) or SPEC.function_name(function)
    causes = profile.exception_causes.get((function, code))
    request = trusted_request(frame)  # (one that failed its check refused what the tap did not see)
    refused = refused_read_only(frame, device)
    if refused:  # (a write of read-only parameters: named rather than the code's meaning)
        frame.notes.append(_read_only_note(frame, profile, refused, causes))
    elif causes:
        key = (function, code, None if request is None else request.raw)
        note = device.explained.get(key)
        if note is None:
            causes_text = causes_meaning(request, profile, causes)
            note = text("exception_cause", code=code, device=profile.device, name=name, causes=causes_text)
            _remember(device.explained, key, note)
        frame.notes.append(note)  # type: ignore[arg-type]
    elif (read := refused_read(frame, device)) is not None:
        _all_unreadable(frame, device, read, events)
    elif code in profile.exceptions:
        meaning = device_meaning(profile, function, code)
        frame.notes.append(text("exception_meaning", code=code, device=profile.device, meaning=meaning))
    elif profile.exceptions:
        known = documented(profile)
        frame.notes.append(text("exception_undocumented", code=code, device=profile.device, known=known))
    frame.exception_text = exception_meaning(device, function, code, request)


def refused_read(frame: Frame, device: Device) -> Frame | None:
    """The read an exception says every parameter of is non-existent or protected (the device's
    all_protected_exception to a plain read, with no cause of its own), or None: not such an exception, or
    one that failed its check (it tells nothing of parameters: memory.py), or its request is not known
    (pairing.trusted_request). explain_exception tells the story, Annotator.reread lists the registers."""
    profile, code, function = device.profile, frame.exception_code, frame.function
    request = trusted_request(frame)
    if (code is None or code != profile.all_protected_exception or function not in PLAIN_READS or not frame.crc_ok
            or request is None or request.start is None or not request.quantity
            or profile.exception_causes.get((function, code))):
        return None
    return request


def exception_meaning(device: Device, function: int, code: int, request: Frame | None) -> str | None:
    """Frame.exception_text of an exception answering `request` (None: not known) on the device, what its
    note says: a refused write of read-only parameters means that (access.READ_ONLY_MEANING); the causes
    the device lists for the code to this function, those the request picks (causes_meaning); else the
    code's meaning. The report's events too (report/meaning.py), re-told once profile `auto` chose the device."""
    if code == READ_ONLY_EXCEPTION and request is not None and written_read_only(request, device):
        return READ_ONLY_MEANING
    profile = device.profile
    causes = profile.exception_causes.get((function & 0x7F, code))
    if causes:
        return causes_meaning(request, profile, causes)
    return device_meaning(profile, function, code)


def _read_only_note(frame: Frame, profile: Profile, refused: list[str],
                    causes: tuple[ExceptionCause, ...] | None) -> str:
    """`exception 02 from the VW3 A3 303: ETA (3201) read-only (access R), not written`, with the relay
    counters the device's causes of this code to this function increment (SEL-749M: any 02 to 06h)."""
    refusal = text("read_only_refusal", parameters=", ".join(refused), access=READ_ONLY)
    picked = _pick_causes(trusted_request(frame), profile, causes or ())
    counters = [counter for cause in picked for counter in cause.counters]
    meaning = counted(refusal, tuple(dict.fromkeys(counters)))
    return text("exception_meaning", code=frame.exception_code, device=profile.device, meaning=meaning)


def device_meaning(profile: Profile, function: int, code: int) -> str | None:
    """The profile's meaning of an exception code to this function: to a read of registers, its
    all_protected_exception also says p.38's clause (every parameter read is non-existent or protected);
    to a write, the code's meaning alone (it reads nothing). Frame.exception_text; the report's events."""
    meaning = profile.exceptions.get(code)
    if meaning is not None and code == profile.all_protected_exception and function & 0x7F in REGISTER_READS:
        return text("all_protected_read", meaning=meaning)
    return meaning


def causes_meaning(request: Frame | None, profile: Profile, causes: tuple[ExceptionCause, ...]) -> str:
    """The causes the request picks, as the note tells them (`a or b`); the report's events say the same."""
    return " or ".join(cause_text(cause) for cause in _pick_causes(request, profile, causes))


def known_meanings(profile: Profile) -> frozenset[str]:
    """Every text exception_meaning can give on the profile, the display filter's exception_meaning values
    (Annotator.filter_names): each code's meaning (to a read of registers, with p.38's clause), a refused
    read-only write's, and the causes of each choice _pick_causes can make (all of them without a request)."""
    found = {READ_ONLY_MEANING}
    for code, meaning in profile.exceptions.items():
        found |= {meaning, device_meaning(profile, min(REGISTER_READS), code) or meaning}
    for causes in profile.exception_causes.values():
        whens = sorted({cause.when for cause in causes if cause.when})
        picks = [causes, tuple(cause for cause in causes if cause.when is None) or causes]
        picks += [tuple(cause for cause in causes if cause.when in chosen)
                  for size in range(1, len(whens) + 1) for chosen in combinations(whens, size)]
        found |= {" or ".join(cause_text(cause) for cause in pick) for pick in picks}
    return frozenset(found)


def _pick_causes(
    request: Frame | None, profile: Profile, causes: tuple[ExceptionCause, ...]
) -> tuple[ExceptionCause, ...]:
    if request is None:
        return causes
    hits = tuple(cause for cause in causes if cause.when and _holds(cause.when, request, profile))
    if hits:
        return hits
    return tuple(cause for cause in causes if cause.when is None) or causes


def _all_unreadable(frame: Frame, device: Device, request: Frame, events: list[Event]) -> None:
    """Exception 02 to a read on a device whose reads fail only when every parameter is unreadable."""
    key = (request.function, request.start, request.quantity)
    known = device.explained.get(key)
    if known is None:
        rows = device.rows_for(request.function)
        base = device.base(request.function) if device.plc is not None else None
        addresses = [
            (request.start + index) & 0xFFFF  # type: ignore[operator]
            for index in range(min(request.quantity, READ_LIMIT))  # type: ignore[type-var]
        ]
        lost_ = [
            (address, rows.get(address), None if base is None else plc_label(base, address))
            for address in addresses
        ]
        parts: list[tuple[str, int]] = []
        run: list[tuple[int, object, str | None]] = []
        for entry in lost_:
            if run and (entry[1] is None) == (run[-1][1] is None) and entry[1] is None and entry[0] == run[-1][0] + 1:
                run.append(entry)
                continue
            if run:
                parts.append(_part(run))
            run = [entry]
        parts.append(_part(run))
        full, short = (
            text("all_unreadable", code=frame.exception_code, device=device.profile.device, parameters=parameters)
            for parameters in listed(parts, SHORT_PARTS)
        )
        known = (Note(full, short, key=True), lost_)
        _remember(device.explained, key, known)
    note, lost_ = known  # type: ignore[misc]
    frame.notes.append(note)
    now = text("unreadable_now", code=frame.exception_code)
    for address, row, label in lost_:
        lost(frame, device, address, row, "non-existent" if row is None else "protected", now, label, events)
    frame.registers = _registers(frame, lost_)


def all_unreadable_registers(frame: Frame, device: Device, request: Frame) -> list[Register]:
    """The registers of an exception 02 to a read on such a device, as _all_unreadable gives them,
    without a note or the parameter memory (Annotator.reread)."""
    rows = device.rows_for(request.function)
    base = device.base(request.function) if device.plc is not None else None
    lost_ = []
    for index in range(min(request.quantity, READ_LIMIT)):  # type: ignore[type-var]
        address = (request.start + index) & 0xFFFF  # type: ignore[operator]
        lost_.append((address, rows.get(address), None if base is None else plc_label(base, address)))
    return _registers(frame, lost_)


def _registers(frame: Frame, lost_: list[tuple[int, object, str | None]]) -> list[Register]:
    # The registers the story is about, with the status it infers and no value (none was sent), so
    # that `status == "protected"` finds this frame as it finds a 16#8000 read.
    inferred = text("no_value", code=frame.exception_code)
    registers = []
    for address, row, label in lost_:
        status = "non-existent" if row is None else "protected"
        register = Register(address, None, status=status, text=inferred, label=label)  # type: ignore[arg-type]
        if row is not None:
            register.code, register.name, register.unit, register.source = row.code, row.name, row.unit, row.source  # type: ignore[attr-defined]
        registers.append(register)
    return registers


def _part(run: list[tuple[int, object, str | None]]) -> tuple[str, int]:
    """`CHCF (8401) protected`, or neighbouring unmapped addresses as one range."""
    address, row, label = run[0]
    if len(run) == 1:
        status = "non-existent" if row is None else "protected"
        return f"{address_name(row, address, label)} {status}", 1  # type: ignore[arg-type]
    last_address, _, last_label = run[-1]
    return text("unmapped_run", span=f"{label or address}..{last_label or last_address}", count=len(run)), len(run)


def _remember(cache: dict[object, object], key: object, value: object) -> None:
    if len(cache) >= _EXPLAINED_LIMIT:
        cache.clear()
    cache[key] = value


def _holds(when: str, request: Frame, profile: Profile) -> bool:
    fields = request.fields
    if when == "quantity":
        # Every quantity the request's lifting rule checks (FC23: read and write, as checks.py warns of
        # them), each against the device's limit for it (without one, a read's READ_LIMIT)
        limits = profile.limits.get(request.function) or (READ_LIMIT,)
        rule = lift_of(request.function, Kind.REQUEST)
        quantities = ([request.quantity] if rule is None or rule.write_window is None or fields is None
                      else [fields[check.field] for check in rule.checks])
        return any(quantity is not None and not 1 <= quantity <= limit
                   for quantity, limit in zip(quantities, limits))
    if when == "byte_count":
        if fields is None or "byte_count" not in fields or "quantity" not in fields:
            return False
        return bool(fields.byte_count != 2 * fields.quantity)
    return False


def documented(profile: Profile) -> str:
    """The exception codes a device documents, as a note lists them (`01, 02, 03`); the plugin's profile
    data carries it (codegen/lua.py)."""
    return ", ".join(f"{known:02X}" for known in sorted(profile.exceptions))


def cause_text(cause: ExceptionCause) -> str:
    """A cause as an exception's note says it (with the counters it increments); the plugin's profile
    data carries each cause's text (codegen/lua.py)."""
    return counted(cause.error, cause.counters)


def counted(error: str, counters: tuple[str, ...]) -> str:
    """An error with the relay counters it increments (`... (increments the Illegal Write counter)`)."""
    if not counters:
        return error
    return text("cause_counters" if len(counters) > 1 else "cause_counter", error=error,
                counters=" and ".join(counters))
