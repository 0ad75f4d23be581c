"""The annotator: applies device profiles and register maps to decoded frames, in stream order.

Called once per frame after decode_frame. It names and scales register values, gives read values a
status (`ok`, `non-existent`, `protected`, `ambiguous`), explains exceptions in the device's own terms,
flags requests beyond the device's limits, and follows each parameter across the capture so that a
parameter read earlier and protected now is told as such (VW3 A3 303 manual p.38).

Everything is precomputed per slave on first sight (profile, merged map, address labels), so the cost
per frame is a few dictionary lookups per register.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

from dissector.devices.maps import MEMO_LIMIT, RegisterDef, RegisterMap, interpret
from dissector.model import DeviceObject, Frame, Kind, Register
from dissector.devices.profiles import BitsDepend, ExceptionCause, Profile, load_profile_map
from dissector.protocol import table
from dissector.protocol.spec import SPEC

_READS = table.register_reads()  # functions whose response registers are values read from the device
# Reads whose exception can be explained parameter by parameter (FC23 may fail on its write part).
_PLAIN_READS = table.plain_register_reads()
_MAX_LISTED = 8  # registers named one by one in an exception explanation
_READ_LIMIT = int(SPEC.limits["read_registers"][1])  # type: ignore[index]
# decode_frame already warns when the spec forbids a broadcast; the profile adds device rules only.
_HAS_LABEL = "label" in Register.__dataclass_fields__
_REQUEST = Kind.REQUEST
_RESPONSE = Kind.RESPONSE
_EXCEPTION = Kind.EXCEPTION

# What the annotator last knew of a parameter: (value, frame number, how). value None: unreadable
# (how is then its status); how "read" or "written" otherwise. Plain tuples: this is the hot path.
_Seen = tuple[int | None, int, str]


@dataclass(frozen=True, slots=True)
class MapLayer:
    """Rows from a --map file, for every slave, one slave, or the slaves of one profile."""

    rows: RegisterMap
    slave: int | None = None
    profile: str | None = None


@dataclass(slots=True)
class _Device:
    """Everything one slave needs, computed on its first frame."""

    profile: Profile
    rows: RegisterMap
    plain: dict[int, RegisterDef]  # rows without bit labels, for bits_depend
    depend: dict[int, BitsDepend]
    plc: dict[int, int] | None  # PLC base per function (None: protocol addresses)
    plc_default: int
    # Parameters are followed only where it tells something: protection, or bits that depend on a value.
    track: bool
    # Requests that need no check at all (supported, no device limit): the common case costs one lookup.
    unchecked: frozenset[int]
    # Supported functions with a device limit: checked inline before the full (slower) check.
    limited: dict[int, tuple[int, ...]]
    seen: dict[int, _Seen] = field(default_factory=dict)
    labels: dict[int, dict[int, str]] = field(default_factory=dict)
    # Exception explanations depend on the request's bytes alone: a PLC that polls a protected block
    # draws the same exception again and again.
    explained: dict[object, object] = field(default_factory=dict)


def _name(register: Register, row: RegisterDef, used: RegisterDef) -> None:
    """Name and read a register from its map row (`used`: the row, or its plain form under bits_depend)."""
    register.code = row.code
    register.name = row.name
    register.unit = row.unit
    register.source = row.source
    value = register.value
    memo = used.memo
    reading = memo.get(value)
    if reading is None:
        reading = interpret(used, value)
        if len(memo) < MEMO_LIMIT:
            memo[value] = reading
    register.scaled, register.text = reading


def _plc_label(base: int, address: int) -> str:
    # 5-digit references (40001 + address) up to 49999, then 6-digit ones (400001 + address).
    digits = len(str(base))
    top = (base // 10 ** (digits - 1) + 1) * 10 ** (digits - 1) - 1
    number = base + address
    if number > top:
        number = base * 10 - 9 + address
    return str(number)


def address_name(row: RegisterDef | None, address: int) -> str:
    """`CHCF (8401)` for a mapped register, `8400` otherwise."""
    return f"{row.code} ({address})" if row is not None else str(address)


class Annotator:
    def __init__(
        self,
        default: Profile,
        per_slave: dict[int, Profile],
        layers: list[MapLayer],
        address_style: str | None = None,
    ) -> None:
        self.default = default
        self.per_slave = dict(per_slave)
        self.layers = list(layers)
        self.address_style = address_style
        self._devices: dict[int, _Device] = {}
        self._base_maps: dict[str, RegisterMap] = {}
        for profile in [default, *per_slave.values()]:
            self._device_for(profile, None)  # load every map now: errors before the first frame

    # -- setup ----------------------------------------------------------------------------------------
    def _device_for(self, profile: Profile, slave: int | None) -> _Device:
        base = self._base_maps.get(profile.name)
        if base is None:
            base = self._base_maps[profile.name] = load_profile_map(profile)
        rows = base
        for layer in self.layers:
            if layer.slave is not None and layer.slave != slave:
                continue
            if layer.profile is not None and layer.profile != profile.name:
                continue
            if rows is base:
                rows = dict(base)
            rows.update(layer.rows)
        depend: dict[int, BitsDepend] = {}
        plain: dict[int, RegisterDef] = {}
        for rule in profile.bits_depend:
            for address in rule.registers:
                if address in rows:
                    depend[address] = rule
                    plain[address] = dataclasses.replace(rows[address], bits={}, memo={})
        style = self.address_style or profile.address_style
        supported = profile.functions if profile.functions is not None else frozenset(range(256))
        return _Device(
            profile=profile,
            rows=rows,
            plain=plain,
            depend=depend,
            plc=dict(profile.plc_base) if style == "plc" else None,
            plc_default=profile.plc_base_default,
            track=profile.protected_value is not None or bool(depend),
            unchecked=frozenset(supported - profile.inner_only - set(profile.limits)),
            limited={
                function: limits
                for function, limits in profile.limits.items()
                if function in supported and function not in profile.inner_only
            },
        )

    def device(self, slave: int) -> _Device:
        device = self._devices.get(slave)
        if device is None:
            profile = self.per_slave.get(slave, self.default)
            device = self._devices[slave] = self._device_for(profile, slave)
        return device

    # -- names for renderers ------------------------------------------------------------------------------
    def profile_for(self, slave: int) -> Profile:
        return self.per_slave.get(slave, self.default)

    def function_name(self, slave: int, function: int) -> str:
        return self.profile_for(slave).function_names.get(function) or SPEC.function_name(function)

    def exception_name(self, slave: int, code: int | None) -> str:
        meaning = None if code is None else self.profile_for(slave).exceptions.get(code)
        return meaning or SPEC.exception_name(code)

    def subfunction_name(self, slave: int, subfunction: int) -> str | None:
        meaning = self.profile_for(slave).diagnostics.get(subfunction)
        return meaning or SPEC.diagnostics.get(subfunction)

    def label(self, slave: int, function: int, address: int) -> str | None:
        """The display address of a register (None: the protocol address itself)."""
        device = self.device(slave)
        if device.plc is None:
            return None
        return _plc_label(device.plc.get(function, device.plc_default), address)

    # -- for the compiled summary path (dissector/accel/fastsummary.py) -------------------------------------------
    def plain_register(self, slave: int, function: int, address: int, value: int) -> Register:
        """A register named and read as _annotate does when no note applies (no bits_depend switch, no
        16#8000 status): what a summary shows of it depends on (slave, function, address, value) alone."""
        register = Register(address, value)
        device = self.device(slave)
        if device.plc is not None:
            register.label = _plc_label(device.plc.get(function, device.plc_default), address)
        row = device.rows.get(address)
        if row is not None:
            _name(register, row, row)
        return register

    def summary_facts(self, slave: int, functions: tuple[int, ...]) -> tuple[object, ...]:
        """What the compiled path must know of a slave to give the annotator's answers itself:
        (names and request checks per function, mapped addresses, bits_depend rules, their sources,
        the parameter memory, the protected value or -1, the PLC base per function or None). A check
        is () for none, the device's limits, or None when every request must go to _check_request.
        """
        device = self.device(slave)
        bases = None
        if device.plc is not None:
            bases = {function: device.plc.get(function, device.plc_default) for function in functions}
        checks: dict[int, tuple[str | None, tuple[int, ...] | None]] = {}
        for function in functions:
            if function in device.unchecked:
                check: tuple[int, ...] | None = ()
            else:
                check = device.limited.get(function)
            checks[function] = (device.profile.function_names.get(function), check)
        depend = {address: (rule.on, rule.plain_when) for address, rule in device.depend.items()}
        protected = device.profile.protected_value
        return (
            checks,
            frozenset(device.rows),
            depend,
            frozenset(rule.on for rule in device.depend.values()),
            device.seen if device.track else None,
            -1 if protected is None else protected,
            bases,
        )

    # -- per frame ----------------------------------------------------------------------------------------
    def __call__(self, frame: Frame) -> None:
        device = self._devices.get(frame.slave)
        if device is None:
            device = self.device(frame.slave)
        kind = frame.kind
        function = frame.function
        special_name = device.profile.function_names.get(function)
        if special_name is not None:
            frame.function_text = special_name
        if device.plc is not None and frame.start is not None:
            self._span_label(frame, device)
        if kind is _REQUEST:
            if frame.broadcast or function not in device.unchecked:
                if frame.broadcast or not self._within_limits(frame, device):
                    self._check_request(frame, device)
        elif kind is _EXCEPTION:
            self._explain_exception(frame, device)
            return
        elif device.track and function in (16, 23):
            # Confirmed writes (FC16 answers carry no values; FC23 writes before it reads).
            request = frame.request
            if request is not None and request.registers:
                self._remember_writes(frame, device, request.registers)
        registers = frame.registers
        if registers:
            read = kind is _RESPONSE and function in _READS
            self._annotate(frame, device, registers, read)
            if kind is _RESPONSE and function == 6 and device.track:
                self._remember_writes(frame, device, registers)
        if function == 8 and frame.subfunction is not None:
            self._diagnostics(frame, device)
        if frame.objects:
            self._objects(frame, device.profile, frame.objects)

    @staticmethod
    def _span_label(frame: Frame, device: _Device) -> None:
        """`40501..40504` for a PLC-style device, so requests without registers show 4X numbers too."""
        base = device.plc.get(frame.function, device.plc_default)  # type: ignore[union-attr]
        start = frame.start
        quantity = frame.quantity or 1
        first = _plc_label(base, start)  # type: ignore[arg-type]
        if quantity == 1:
            frame.span_label = first
        else:
            frame.span_label = f"{first}..{_plc_label(base, (start + quantity - 1) & 0xFFFF)}"  # type: ignore[operator]

    def _annotate(self, frame: Frame, device: _Device, registers: list[Register], read: bool) -> None:
        rows = device.rows
        depend = device.depend
        labels: dict[int, str] | None = None
        base = 0
        if device.plc is not None and _HAS_LABEL:
            base = device.plc.get(frame.function, device.plc_default)
            labels = device.labels.setdefault(base, {})
        protected = device.profile.protected_value if read else None
        # A single-register read of an unreadable parameter draws an exception, not 16#8000 (p.38).
        multi = len(registers) > 1
        seen = device.seen
        number = frame.number
        for register in registers:
            address = register.address
            if address is None:
                continue
            if labels is not None:
                label = labels.get(address)
                if label is None:
                    label = labels[address] = _plc_label(base, address)
                register.label = label
            row = rows.get(address)
            value = register.value
            if row is not None:
                used = row
                if depend and address in depend:
                    used = self._depend(frame, device, address)
                _name(register, row, used)
            if protected is None:
                continue
            if value == protected and multi:
                self._unreadable(frame, device, register, row)
                continue
            register.status = "ok"
            last = seen.get(address)
            if last is not None and last[0] is None:
                frame.notes.append(
                    f"{address_name(row, address)} readable again: {last[2]} in frame #{last[1]}, "
                    f"{value} now"
                )
            seen[address] = (value, number, "read")

    @staticmethod
    def _depend(frame: Frame, device: _Device, address: int) -> RegisterDef:
        rule = device.depend[address]
        last = device.seen.get(rule.on)
        if last is not None and last[0] in rule.plain_when:
            if rule.reason not in frame.notes:
                frame.notes.append(rule.reason)
            return device.plain[address]
        return device.rows[address]

    def _unreadable(self, frame: Frame, device: _Device, register: Register, row: RegisterDef | None) -> None:
        """16#8000 in a multi-register read: non-existent, protected, or (if it can be real) ambiguous."""
        if row is None:
            status = "non-existent"
            register.text = "16#8000: non-existent (address not in the map)"
        elif row.ambiguous_8000:
            # The value may be real: keep its own reading, and what was known of the parameter.
            register.status = "ambiguous"
            return
        else:
            status = "protected"
            register.scaled = None
            register.text = "16#8000: protected"
        register.status = status
        self._lost(frame, device, register.address, row, status, "16#8000 now")  # type: ignore[arg-type]

    @staticmethod
    def _lost(
        frame: Frame, device: _Device, address: int, row: RegisterDef | None, status: str, now: str
    ) -> None:
        """Record a parameter as unreadable, telling the story if it was readable before."""
        last = device.seen.get(address)
        if last is not None and last[0] is not None:
            became = "protected" if row is not None else "non-existent or protected"
            frame.notes.append(
                f"{address_name(row, address)} became {became}: {last[2]} {last[0]} in "
                f"frame #{last[1]}, {now}"
            )
        device.seen[address] = (None, frame.number, status)

    @staticmethod
    def _remember_writes(frame: Frame, device: _Device, registers: list[Register]) -> None:
        seen = device.seen
        number = frame.number
        for register in registers:
            if register.address is not None:
                seen[register.address] = (register.value, number, "written")

    # -- requests -----------------------------------------------------------------------------------------
    @staticmethod
    def _within_limits(frame: Frame, device: _Device) -> bool:
        """True when a supported request is within the device's limits (nothing to report)."""
        limits = device.limited.get(frame.function)
        if limits is None:
            return False
        quantity = frame.quantity
        if quantity is None or quantity > limits[0]:
            return False
        if len(limits) > 1:
            fields = frame.fields
            return fields is not None and fields.write_quantity <= limits[1]
        return True

    def _check_request(self, frame: Frame, device: _Device) -> None:
        profile = device.profile
        function = frame.function
        name = profile.function_names.get(function) or SPEC.function_name(function)
        if profile.functions is not None and function not in profile.functions:
            frame.warnings.append(f"{name} ({function}) is not supported by the {profile.device}")
        elif function in profile.inner_only:
            frame.warnings.append(
                f"{name} ({function}) is only valid inside an encapsulated packet on the {profile.device}"
            )
        limits = profile.limits.get(function)
        if limits is not None:
            self._check_limits(frame, profile, name, limits)
        if (
            frame.broadcast
            and profile.broadcast is not None
            and function not in profile.broadcast
            and function not in SPEC.not_broadcast  # decode.py already warned with the spec's rule
        ):
            allowed = ", ".join(str(code) for code in sorted(profile.broadcast)) or "none"
            frame.warnings.append(
                f"{name} cannot be broadcast to the {profile.device} (broadcast functions: {allowed})"
            )

    @staticmethod
    def _check_limits(frame: Frame, profile: Profile, name: str, limits: tuple[int, ...]) -> None:
        if frame.function == 23:
            fields = frame.fields
            if fields is None:
                return
            checks = [("read quantity", fields.read_quantity), ("write quantity", fields.write_quantity)]
        else:
            checks = [("quantity", frame.quantity)]
        for (what, quantity), limit in zip(checks, limits):
            if quantity is not None and quantity > limit:
                frame.warnings.append(
                    f"{what} {quantity} is beyond the {profile.device}'s limit of {limit} words "
                    f"for {name}"
                )

    # -- exceptions ---------------------------------------------------------------------------------------
    def _explain_exception(self, frame: Frame, device: _Device) -> None:
        profile = device.profile
        code = frame.exception_code
        if code is None:
            return
        function = frame.function
        name = profile.function_names.get(function) or SPEC.function_name(function)
        causes = profile.exception_causes.get((function, code))
        if causes:
            request = frame.request
            key = (function, code, None if request is None else request.raw)
            note = device.explained.get(key)
            if note is None:
                chosen = self._pick_causes(request, profile, causes)
                note = f"exception {code:02X} from the {profile.device} to {name}: " + " or ".join(
                    _cause_text(cause) for cause in chosen
                )
                _remember(device.explained, key, note)
            frame.notes.append(note)  # type: ignore[arg-type]
        elif code in profile.exceptions:
            frame.notes.append(f"exception {code:02X} from the {profile.device}: {profile.exceptions[code]}")
        elif profile.exceptions:
            known = ", ".join(f"{known:02X}" for known in sorted(profile.exceptions))
            frame.notes.append(f"exception {code:02X} is not one the {profile.device} documents ({known})")
        frame.exception_text = profile.exceptions.get(code)
        if code == profile.all_protected_exception and function in _PLAIN_READS:
            self._all_unreadable(frame, device)

    @staticmethod
    def _pick_causes(
        request: Frame | None, profile: Profile, causes: tuple[ExceptionCause, ...]
    ) -> tuple[ExceptionCause, ...]:
        if request is None:
            return causes
        hits = tuple(cause for cause in causes if cause.when and _holds(cause.when, request, profile))
        if hits:
            return hits
        return tuple(cause for cause in causes if cause.when is None) or causes

    def _all_unreadable(self, frame: Frame, device: _Device) -> None:
        request = frame.request
        if request is None or request.start is None or not request.quantity:
            frame.notes.append(
                "on a read, this exception means every parameter read is non-existent or protected"
            )
            return
        key = (request.start, request.quantity)
        known = device.explained.get(key)
        if known is None:
            rows = device.rows
            addresses = [(request.start + index) & 0xFFFF for index in range(min(request.quantity, _READ_LIMIT))]
            lost = [(address, rows.get(address)) for address in addresses]
            parts = [
                f"{address_name(row, address)} " + ("non-existent" if row is None else "protected")
                for address, row in lost
            ]
            if len(parts) > _MAX_LISTED:
                parts[_MAX_LISTED:] = [f"… (+{len(parts) - _MAX_LISTED})"]
            known = ("every parameter of this read is non-existent or protected: " + ", ".join(parts), lost)
            _remember(device.explained, key, known)
        note, lost = known  # type: ignore[misc]
        frame.notes.append(note)
        now = f"exception {frame.exception_code:02X} now"
        for address, row in lost:
            self._lost(frame, device, address, row, "non-existent" if row is None else "protected", now)

    # -- other functions ----------------------------------------------------------------------------------
    @staticmethod
    def _diagnostics(frame: Frame, device: _Device) -> None:
        profile = device.profile
        sub = frame.subfunction
        meaning = profile.diagnostics.get(sub)  # type: ignore[arg-type]
        if meaning is None:
            return
        frame.subfunction_text = meaning
        text = f"sub-function {sub:02X} on the {profile.device}: {meaning}"
        fields = frame.fields
        if frame.kind is Kind.RESPONSE and fields is not None and len(fields.data) == 2:
            text += f"; value {int.from_bytes(fields.data, 'big')}"
        frame.notes.append(text)

    @staticmethod
    def _objects(frame: Frame, profile: Profile, objects: list[DeviceObject]) -> None:
        for obj in objects:
            meaning = profile.objects.get(obj.id)
            if meaning is None:
                continue
            if meaning.format == "MMmm":
                value = obj.value
                if len(value) == 4 and value.isascii() and value.isdigit():
                    obj.text = f"V{int(value[:2])}.{int(value[2:])}"
                    continue
                frame.notes.append(
                    f"{obj.name} {value!r} is not in the MMmm form the {profile.device} uses"
                )
            obj.text = meaning.meaning


_EXPLAINED_LIMIT = 4096  # explanations kept per device: memory stays bounded whatever the capture


def _remember(cache: dict[object, object], key: object, value: object) -> None:
    if len(cache) >= _EXPLAINED_LIMIT:
        cache.clear()
    cache[key] = value


def _holds(when: str, request: Frame, profile: Profile) -> bool:
    fields = request.fields
    if when == "quantity":
        quantity = request.quantity
        limits = profile.limits.get(request.function)
        limit = limits[0] if limits else _READ_LIMIT
        return quantity is not None and not 1 <= quantity <= limit
    if when == "byte_count":
        if fields is None or "byte_count" not in fields or "quantity" not in fields:
            return False
        return bool(fields.byte_count != 2 * fields.quantity)
    return False


def _cause_text(cause: ExceptionCause) -> str:
    if not cause.counters:
        return cause.error
    counters = cause.counters
    names = " and ".join(counters)
    plural = "counters" if len(counters) > 1 else "counter"
    return f"{cause.error} (increments the {names} {plural})"
