"""The annotator: applies device profiles and register maps to decoded frames, in stream order.

Called once per frame after decode_frame. Each job has its own module: which profile a slave gets
(selection.py, profile `auto`), register naming and scaling (naming.py), the parameter memory and its
16#8000 story (memory.py, told as notes by story.py), exception explanations (explain.py), device
limits (checks.py) and identification objects (objects.py); the per-slave setup is device.py. What is
left here is the order of those steps for each kind of frame, and the answers renderers and the compiled
summary path (dissector/accel/fastsummary.py) ask for.

Everything is precomputed per slave on first sight (profile, merged map, address labels), so the cost
per frame is a few dictionary lookups per register.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence

from dissector.devices.access import check_writes
from dissector.devices.checks import check_request, check_subfunction, within_limits
from dissector.devices.device import Device, DeviceBuilder, MapLayer
from dissector.devices.explain import all_unreadable_registers, explain_exception, known_meanings, refused_read
from dissector.devices.maps import MEMO_LIMIT, RegisterDef, interpret
from dissector.devices.memory import (
    readable_again, remember_answered, remember_mask, remember_writes, unreadable, unreadable_status,
)
from dissector.devices.naming import (name_from_map, name_register, name_second_alone, name_wide, plc_label,
                                      wide_before, window_label)
from dissector.devices.objects import check_objects
from dissector.devices.profiles import HOLDING_REGISTERS, Profile
from dissector.devices.selection import ProfileChoice, Selector
from dissector.devices.story import Event, tell
from dissector.model import DeviceObject, Frame, Kind, Register, RegisterList
from dissector.protocol import table
from dissector.protocol.rules import CONFIRM, Confirm, text
from dissector.protocol.spec import SPEC

__all__ = ["Annotator", "MapLayer", "ProfileChoice"]

_READS = table.register_reads()  # functions whose response registers are values read from the device
# Register writes by how they are confirmed (data/modbus.toml [confirm]): FC6 by its echo, FC16/23 by an answer.
_BY_ECHO = table.confirmed_registers(Confirm.ECHO)
_BY_ANSWER = table.confirmed_registers(Confirm.ANSWER)
_HAS_LABEL = "label" in Register.__dataclass_fields__
_REQUEST = Kind.REQUEST
_WRITE_WINDOWS = table.write_windows()  # (FC23: a written window of its own, labelled too)
_RESPONSE = Kind.RESPONSE
_EXCEPTION = Kind.EXCEPTION


class Annotator:
    """`default`: the profile of every slave not in `per_slave`; `selector`: profile `auto` instead
    (the default is then the fallback a slave has until evidence arrives)."""

    def __init__(
        self,
        default: Profile,
        per_slave: dict[int, Profile],
        layers: list[MapLayer],
        address_style: str | None = None,
        selector: Selector | None = None,
    ) -> None:
        self.default = default
        self.per_slave = dict(per_slave)
        self.selector = selector
        self._builder = DeviceBuilder(layers, address_style)
        self._devices: dict[int, Device] = {}
        self._chosen: dict[int, Profile] = {}  # profiles `auto` chose
        self.changed: set[int] = set()  # slaves whose profile changed (the compiled path reloads them)
        self._settled: set[int] = set()
        self._rereading: dict[tuple[int, str], Device] = {}  # reread()'s devices of other profiles
        # slave -> copies of its provisional frames, until its choice (_observe annotates them again):
        # bounded, a slave's frames are provisional until selection.FIT_FRAMES of them at most.
        self._held: dict[int, list[Frame]] = {}
        self._broadcasting: dict[str, Device] = {}  # slave 0's device by profile (_broadcast)
        self.masked: dict[int, int | None] | None = None  # remember_mask's values, for render/history.py
        # Parameter histories holding a slave's frames until its choice is final: the compiled path leaves
        # such a slave to the Python stages (render/history.py History.holds, compilable)
        self.holds: list[Callable[[int], bool]] = []
        for profile in [default, *per_slave.values()]:
            self._builder.build(profile, None)  # load every map now: errors before the first frame

    def __getstate__(self) -> dict[str, object]:  # a copy (another bus's, app/cli.py): its own histories hold it
        return {**self.__dict__, "holds": []}

    @property
    def layers(self) -> list[MapLayer]:
        return self._builder.layers

    # -- profile selection --------------------------------------------------------------------------------
    def choices(self) -> list[ProfileChoice]:
        """Which slave got which profile and why, by slave (forced ones too), for stderr and --stats."""
        out = []
        slaves = set(self._devices) | set(self.per_slave)
        for slave in sorted(slaves):
            if slave in self.per_slave:
                out.append(ProfileChoice(slave, self.per_slave[slave].name, "--profile", None, True))
            elif self.selector is None:
                out.append(ProfileChoice(slave, self.default.name, "--profile", None, True))
            elif slave != 0:
                choice = self.selector.choice(slave)
                if choice is None:
                    choice = ProfileChoice(
                        slave, self.default.name, "no evidence of a device: spec semantics only", None, False
                    )
                out.append(choice)
        return out

    def profile_report(self) -> list[str]:
        """With profile `auto`: a line per slave that got a device profile, one for those left without
        (stderr, after a decode). Empty when every profile was forced."""
        if self.selector is None:
            return []
        lines = []
        left: list[int] = []
        for choice in self.choices():
            if choice.frame is None and choice.profile == self.default.name:
                left.append(choice.slave)
            else:
                lines.append(f"profile {choice.text()}")
        if left:
            names = ", ".join(map(str, left))
            lines.append(
                f"profile slave{'s' if len(left) > 1 else ''} {names}: {self.default.name} "
                "(no evidence of a device: spec semantics only)"
            )
        return lines

    def _observe(self, frame: Frame) -> Device | None:
        selector = self.selector
        choice = selector.observe(frame)  # type: ignore[union-attr]
        slave = frame.slave
        if slave not in self._settled and selector.settled(slave):  # type: ignore[union-attr]
            self._settled.add(slave)
            self.changed.add(slave)
        held = self._held.pop(slave, ()) if choice is not None or slave in self._settled else ()
        if choice is None:
            return None
        profile = self.selector.profile(choice.profile) or self.default  # type: ignore[union-attr]
        self._chosen[slave] = profile
        device = self._devices[slave] = self._builder.build(profile, slave)
        self.changed.add(slave)
        # The slave's provisional frames annotated again with the device just chosen, as they would have
        # been had it been known from the first (a file, read twice): it remembers of them what the one
        # annotate path remembers, so a parameter read in one and 16#8000 now `became protected`. On
        # copies (_scratch): those frames were shown, what is told of them again is dropped.
        for copy in held:
            self._annotate_frame(copy, device)
        return device

    def freeze(self) -> None:
        """The selector has seen the whole input (app/preselect.py): every slave's device is the one
        chosen over it, from the slave's first frame on, and no frame changes it until thaw()."""
        selector = self.selector
        if selector is None:
            return
        for slave, choice in selector.chosen().items():
            profile = selector.profile(choice.profile) or self.default
            if self.profile_for(slave) is not profile:
                self._chosen[slave] = profile
                if slave in self._devices:
                    self._devices[slave] = self._builder.build(profile, slave)
                self.changed.add(slave)
        selector.frozen = True

    def thaw(self) -> None:
        """The next input's first pass: its frames may add to (or take back) the choices."""
        if self.selector is not None:
            self.selector.frozen = False

    def choice_frame(self, slave: int) -> int | None:
        """The frame whose evidence gave this slave its profile (None: forced, no choice yet, or chosen
        before the decode by a first pass): frames before it were named with the profile the slave had then."""
        if self.selector is None or slave in self.per_slave or self.selector.frozen:
            return None
        choice = self.selector.choice(slave)
        return None if choice is None else choice.frame

    def settled(self, slave: int) -> bool:
        """The profile of this slave can change only through frames the compiled path hands over."""
        return self.selector is None or slave in self.per_slave or self.selector.settled(slave)

    def final(self, slave: int) -> bool:
        """No frame can change this slave's profile any more (forced, or identified)."""
        if self.selector is None or slave in self.per_slave:
            return True
        choice = self.selector.choice(slave)
        return choice is not None and choice.final

    def _inferred_broadcast(self, slave: int) -> bool:
        """Slave 0 under profile auto, not forced: named with the device the slaves share (_broadcast)."""
        return slave == 0 and self.selector is not None and 0 not in self.per_slave

    def compilable(self, slave: int) -> bool:
        """The compiled path may show this slave's plain transactions: a settled profile, no 32-bit rows."""
        if self._inferred_broadcast(slave):
            return False  # (named with the device of the slaves met so far: _broadcast)
        device = self.device(slave)  # (input rows apart too: the engine knows one map a slave)
        return self.settled(slave) and not (device.wide or device.inputs) and not any(h(slave) for h in self.holds)

    # -- setup ----------------------------------------------------------------------------------------
    def device(self, slave: int) -> Device:
        if self._inferred_broadcast(slave):
            return self._broadcast()[0]  # (as the choices stand now: a broadcast read again at the end)
        device = self._devices.get(slave)
        if device is None:
            device = self._devices[slave] = self._builder.build(self.profile_for(slave), slave)
        return device

    # -- names for renderers ------------------------------------------------------------------------------
    def chosen_profile(self, choice: ProfileChoice | None) -> Profile:
        """The profile a choice names (None: the fallback a slave has until one is made)."""
        found = None if choice is None or self.selector is None else self.selector.profile(choice.profile)
        if found is None and choice is not None:  # (a broadcast's: a profile forced for a slave, _broadcast)
            found = next((profile for profile in self.per_slave.values() if profile.name == choice.profile), None)
        return found or self.default

    def profiles(self) -> list[Profile]:
        """Every profile a slave may have in this run: in use, or that `auto` may choose."""
        profiles = [self.default, *self.per_slave.values()]
        if self.selector is not None:
            profiles += [profile for profile, _rows in self.selector.candidates]
        return list({profile.name: profile for profile in profiles}.values())

    def filter_names(self) -> dict[str, frozenset[str]]:
        """The texts the run's profiles can give the display filter's enumerated keys beside the
        spec's (render/filters.py FilterContext): profile, function_name, exception_meaning and
        subfunction_name."""
        profiles = self.profiles()
        return {
            "profile": frozenset(profile.name for profile in profiles),
            "function_name": frozenset(name for p in profiles for name in p.function_names.values()),
            # (the code's meaning, to a read with p.38's clause, to a read-only write, the causes: explain.py)
            "exception_meaning": frozenset(text for p in profiles for text in known_meanings(p)),
            "subfunction_name": frozenset(text for p in profiles for text in p.diagnostics.values()),
        }

    def codes(self) -> dict[str, frozenset[int]]:
        """Every parameter code (upper case) a slave may have in this run -> its addresses: the rows of
        every profile in use or that `auto` may choose, and of the --map files (what --watch may name)."""
        maps = [self._builder.build(profile, None).rows for profile in self.profiles()]
        maps += [table for layer in self.layers for table in (layer.rows, getattr(layer.rows, "inputs", {}))]
        found: dict[str, set[int]] = {}
        for rows in maps:
            for address, row in rows.items():
                if row.code:
                    found.setdefault(row.code.upper(), set()).add(address)
        return {code: frozenset(addresses) for code, addresses in found.items()}

    def profile_for(self, slave: int) -> Profile:
        if self._inferred_broadcast(slave):
            return self.device(0).profile
        profile = self.per_slave.get(slave)
        if profile is None:
            profile = self._chosen.get(slave, self.default)
        return profile

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
        return plc_label(device.plc.get(function, device.plc_default), address)

    # -- for the compiled summary path (dissector/accel/fastsummary.py) -------------------------------------------
    def plain_register(self, slave: int, function: int, address: int, value: int) -> Register:
        """A register named and read as _annotate does when no note applies (no bits_depend switch, no
        16#8000 status): what a summary shows of it depends on (slave, function, address, value) alone."""
        register = Register(address, value)
        device = self.device(slave)
        if device.plc is not None:
            register.label = plc_label(device.plc.get(function, device.plc_default), address)
        row = device.rows_for(function).get(address)
        if row is not None:
            name_register(register, row, row)
        return register

    def reread(self, frame: Frame, profile: Profile | None = None) -> list[Register] | None:
        """The registers of `frame` as its slave's device names them now: what the decode says of them
        when the device is known from the frame on (a file, read twice). For a frame read before
        profile `auto` chose (Frame.provisional) or named with a choice taken back since: the parameter
        history (render/history.py) reads it again once the choice is made, so 16#8000 in a
        multi-register read is the status the device gives it, never a value beside it. New Register
        objects: the frame, the parameter memory and the notes are left as they were. `profile`: the
        one to read them with (default: the slave's now)."""
        device = self.device(frame.slave)
        if profile is not None and profile is not device.profile:
            key = (frame.slave, profile.name)
            other = self._rereading.get(key)
            if other is None:
                if len(self._rereading) >= 64:
                    self._rereading.clear()
                other = self._rereading[key] = self._builder.build(profile, frame.slave)
            device = other
        profile = device.profile
        function = frame.function
        kind = frame.kind
        if kind is _EXCEPTION:
            request = refused_read(frame, device)
            return None if request is None else all_unreadable_registers(frame, device, request)
        registers = frame.registers
        if not registers:
            return registers
        plc = None if device.plc is None else device.plc.get(function, device.plc_default)
        fresh = [Register(register.address, register.value) for register in registers]
        rows = device.rows_for(function)
        for index, register in enumerate(fresh):
            address = register.address
            if address is None or register.value is None:
                continue
            if plc is not None:
                register.label = plc_label(plc, address)
            name_from_map(fresh, index, rows)
        protected = profile.protected_value if kind is _RESPONSE and function in _READS else None
        if protected is not None and frame.crc_ok:  # (of a frame that failed its check: no status judged)
            multi = len(fresh) > 1
            for register in fresh:
                if register.address is None:
                    continue
                if register.value == protected and multi and register.words == 1:
                    # (a 32-bit value's second word alone: that value's 16#8000, ambiguous as its first's)
                    unreadable_status(register, rows.get(register.address) or wide_before(rows, register.address))
                else:
                    register.status = "ok"
        return fresh

    def namer(self, slave: int) -> Callable[..., tuple[str | None, str | None]]:
        """(address, value, table) -> (text, code) of a register of the table (profiles.register_table's) as
        the slave's device names it now, as plain_register does (--stats asks it for a last value)."""
        device = self.device(slave)

        def name(address: int, value: int, table: int = HOLDING_REGISTERS) -> tuple[str | None, str | None]:
            register = Register(address, value)
            row = device.table_rows(table).get(address)
            if row is not None:
                if row.words != 1:  # one word of a 32-bit value: its text needs the other word
                    return None, row.code
                name_register(register, row, row)
            return register.text, register.code

        return name

    def summary_facts(self, slave: int, functions: tuple[int, ...]) -> tuple[object, ...]:
        """What the compiled path must know of a slave to give the annotator's answers itself:
        (names and request checks per function, mapped addresses, bits_depend rules, their sources,
        the parameter memory, the protected value or -1, the PLC base per function or None). A check
        is () for none, the device's limits, or None when every request must go to the annotator
        (Device.engine_check: _check_request, or a memory of its own).
        """
        device = self.device(slave)
        bases = None
        if device.plc is not None:
            bases = {function: device.plc.get(function, device.plc_default) for function in functions}
        checks: dict[int, tuple[str | None, tuple[int, ...] | None]] = {}
        for function in functions:
            checks[function] = (device.profile.function_names.get(function), device.engine_check(function))
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
        if self._inferred_broadcast(frame.slave):
            device, said, frame.profile_choice, frame.provisional = self._broadcast()
            if said is not None:
                frame.notes.append(said)
        elif self.selector is not None and frame.slave not in self.per_slave:
            chosen = self._observe(frame)
            if chosen is not None:
                device = chosen
            choice = frame.profile_choice = self.selector.choice(frame.slave)  # type: ignore[union-attr]
            if self.selector.open(frame.slave):  # type: ignore[union-attr]
                # read once: no device yet (or the one chosen taken back), and evidence may still come
                frame.provisional = True
                self._held.setdefault(frame.slave, []).append(_scratch(frame))
        if device is None:
            device = self.device(frame.slave)
        frame.profile = device.profile.name
        self._annotate_frame(frame, device)

    def _broadcast(self) -> tuple[Device, str | None, ProfileChoice | None, bool]:
        """Slave 0 under profile `auto`: its device as the choices stand (Selector.broadcast)."""
        profile, said, choice, provisional = self.selector.broadcast(self.per_slave)  # type: ignore[union-attr]
        device = self._broadcasting.get(profile.name)
        if device is None:
            device = self._broadcasting[profile.name] = self._builder.build(profile, 0)
        if self._devices.get(0) is not device:
            self._devices[0], self._chosen[0] = device, profile
            self.changed.add(0)
        return device, said, choice, provisional

    def _annotate_frame(self, frame: Frame, device: Device) -> None:
        """The one annotate path: a frame, or a provisional frame's copy (_observe), with `device`."""
        kind, function = frame.kind, frame.function
        special_name = device.profile.function_names.get(function)
        if special_name is not None:
            frame.function_text = special_name
        if device.plc is not None and frame.start is not None:
            _span_label(frame, device)
        events: list[Event] = []
        trusted = frame.crc_ok  # (a frame that failed its check tells nothing of parameters: memory.py)
        if kind is _REQUEST:
            if frame.broadcast or function not in device.unchecked:
                if frame.broadcast or not within_limits(frame, device):
                    check_request(frame, device)
            elif frame.subfunction is not None:
                check_subfunction(frame, device.profile)
            check_writes(frame, device)
        elif kind is _EXCEPTION:
            explain_exception(frame, device, events)
            if events:
                frame.notes.extend(tell(events))
            return
        elif device.track and trusted and function in _BY_ANSWER:
            remember_answered(frame, device)  # (FC23 writes before it reads)
        elif device.track and trusted and CONFIRM.get(function) is Confirm.MASK:
            remember_mask(frame, device, self.masked)
        registers = frame.registers
        if registers:
            read = kind is _RESPONSE and function in _READS and trusted
            self._annotate(frame, device, registers, read, events)
            if kind is _RESPONSE and function in _BY_ECHO and device.track and trusted:
                remember_writes(frame, device, registers)
            if events:
                frame.notes.extend(tell(events))
        if frame.subfunction is not None:  # FC8: only its lifter sets one
            _diagnostics(frame, device)
        if frame.objects:
            check_objects(frame, device.profile, frame.objects)

    def _annotate(
        self, frame: Frame, device: Device, registers: Sequence[Register], read: bool, events: list[Event]
    ) -> None:
        rows = device.rows_for(frame.function)
        depend = device.depend if rows is device.rows else {}  # (bits_depend rules name holding registers)
        labels: dict[int, str] | None = None
        base = 0
        if device.plc is not None and _HAS_LABEL:
            base = device.base(frame.function)
            labels = device.labels.setdefault(base, {})
        protected = device.profile.protected_value if read else None
        if type(registers) is RegisterList and registers.plain and protected is None:
            if registers.start is None:
                return  # no addresses: nothing to name or label
            addresses = registers.addresses
            alone = device.wide and wide_before(rows, registers.start)
            if not rows or (rows.keys().isdisjoint(addresses) and not alone):
                # No map row in the block (nor a 32-bit row's second word first) and no 16#8000 to check: at
                # most labels, set in bulk.
                if labels is not None:
                    registers.labels = _labels(labels, base, addresses)
                return
        # A single-register read of an unreadable parameter draws an exception, not 16#8000 (p.38).
        multi = len(registers) > 1
        if multi and protected is not None and _all_marked(frame, device, registers, protected):
            protected = None  # (nothing is known unreadable: no story, each value kept as read)
        seen = device.memory(frame.function)
        number = frame.number
        for index, register in enumerate(registers):
            address = register.address
            if address is None:
                continue
            if labels is not None:
                label = labels.get(address)
                if label is None:
                    label = labels[address] = plc_label(base, address)
                register.label = label
            row = rows.get(address)
            value = register.value
            if row is not None:
                if row.words == 2:
                    name_wide(registers, index, row)
                elif depend and address in depend:
                    name_register(register, row, _depend(frame, device, address))
                else:  # name_register(register, row, row), inline: this runs for every mapped register
                    register.code = row.code
                    register.name = row.name
                    register.unit = row.unit
                    register.source = row.source
                    memo = row.memo
                    reading = memo.get(value)
                    if reading is None:
                        reading = interpret(row, value)
                        if len(memo) < MEMO_LIMIT:
                            memo[value] = reading
                    register.scaled, register.text = reading
            elif index == 0:  # (a second word without its first can only come first)
                name_second_alone(rows, register)
            if protected is None:
                continue
            if value == protected and multi and register.words == 1:
                # (a 32-bit value's second word alone: that value's 16#8000, ambiguous as its first's)
                unreadable(frame, device, register, row or wide_before(rows, address), events)
                continue
            register.status = "ok"
            last = seen.get(address)
            if last is not None and last[0] is None:
                readable_again(address, row, register.label, last, value, events)
            seen[address] = (value, number, "read")


def _all_marked(frame: Frame, device: Device, registers: Sequence[Register], protected: int) -> bool:
    """Every value 16#8000 where the device answers an exception when every parameter is unreadable (p.38):
    then one at least is the value itself; each register ambiguous, and the frame says why."""
    code = device.profile.all_protected_exception
    if code is None or any(register.value != protected for register in registers):
        return False
    for register in registers:
        register.status = "ambiguous"
    frame.notes.append(text("all_marked", protected=protected, device=device.profile.device, code=code))
    return True


def _scratch(frame: Frame) -> Frame:
    """A copy of a frame for the annotate path to change freely (names, statuses, notes), taken before it
    is annotated: its registers and device objects fresh, as decoded."""
    registers = frame.registers
    if type(registers) is RegisterList:
        registers = RegisterList(registers.start, registers.values)
    elif registers:
        registers = [Register(register.address, register.value) for register in registers]
    objects = frame.objects and [DeviceObject(obj.id, obj.name, obj.value) for obj in frame.objects]
    return dataclasses.replace(frame, registers=registers, objects=objects, notes=[], warnings=[])


def _labels(labels: dict[int, str], base: int, addresses: Sequence[int]) -> list[str]:
    """The display addresses of a block, from the device's cache (filled on first sight)."""
    try:
        return list(map(labels.__getitem__, addresses))
    except KeyError:
        for address in addresses:
            if address not in labels:
                labels[address] = plc_label(base, address)
        return list(map(labels.__getitem__, addresses))


def _span_label(frame: Frame, device: Device) -> None:
    """`40501..40504` for a PLC-style device, so requests without registers show 4X numbers too; FC23's
    request its written window as well (`40006` where it writes none: describe's `write 40006 (0)`)."""
    base = device.base(frame.function)
    labels = device.labels.setdefault(base, {})  # the cache _annotate fills too
    frame.span_label = window_label(labels, base, frame.start, frame.quantity)  # type: ignore[arg-type]
    window = _WRITE_WINDOWS.get(frame.function)
    if window is not None and frame.kind is _REQUEST and frame.fields is not None:
        fields = frame.fields
        frame.write_span_label = window_label(labels, base, fields[window[0]], fields[window[1]])


def _depend(frame: Frame, device: Device, address: int) -> RegisterDef:
    rule = device.depend[address]
    last = device.seen.get(rule.on)
    if last is not None and last[0] in rule.plain_when:
        if rule.reason not in frame.notes:
            frame.notes.append(rule.reason)
        return device.plain[address]
    return device.rows[address]


def _diagnostics(frame: Frame, device: Device) -> None:
    profile = device.profile
    sub = frame.subfunction
    meaning = profile.diagnostics.get(sub)  # type: ignore[arg-type]
    if meaning is None:
        return
    frame.subfunction_text = meaning
    note = text("subfunction_meaning", subfunction=sub, device=profile.device, meaning=meaning)
    fields = frame.fields
    if frame.kind is Kind.RESPONSE and fields is not None and len(fields.data) == 2:
        value = int.from_bytes(fields.data, "big")
        note += text("subfunction_value", value=value)
        constant = profile.diagnostic_constants.get(sub)  # type: ignore[arg-type]
        if constant is not None and value != constant:
            frame.warnings.append(text("diagnostic_constant", subfunction=sub, device=profile.device,
                                       constant=constant, value=value))
    frame.notes.append(note)

