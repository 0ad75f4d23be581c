"""Profile `auto`: which device each slave is, from evidence in the capture.

Evidence, strongest first (what identifies a device is data: the `[identify]` table of each profile in
data/profiles/*.toml):
- a Read Device Identification answer whose ProductCode starts with one of a profile's product codes
  (`ATV71HU15M3` -> atv71);
- a function code only that device speaks (SEL-749M 60h-62h, 7Dh), asked or answered;
- traffic that fits one profile alone, over more than one answer: answers to function codes it
  supports, at addresses its map knows (or reading the value it returns for a non-existent parameter,
  16#8000 on the VW3 A3 303). One answer is never enough: an energy meter's read of 3203..3206 fits
  the Altivar map by chance. The map must explain FIT_READS different reads (a master polling one
  block again and again is one read, however often), or one read answered again with the device's own
  non-existent marker at an address its map lacks (what the VW3 card does, p.38). An answer the map
  cannot explain (a register it does not know, a function the device does not support) rules the
  profile out for that slave. Traffic is judged on a slave's first answers (FIT_ANSWERS); a later
  answer to a function the chosen profile does not support takes the choice back (that device is then
  ruled out, and the slave's traffic judged on for the others while it is not settled).
Until evidence arrives a slave gets spec semantics only (`generic`): no device claims. The choice's
reason names the frames, and every frame a chosen profile annotates carries it (Frame.profile: -V's
`Profile:` line, --json's `profile`).

A file is read twice (app/preselect.py, issue 27): a first pass hands every frame to observe(), then
`frozen` holds the choices while the decode names every frame of a slave, from its first, with the
profile chosen over the whole input. Frozen, no frame changes a choice and every slave is settled.
"""
from __future__ import annotations

from dataclasses import dataclass

from dissector.devices.maps import RegisterMap, TableRows
from dissector.devices.profiles import INPUT_REGISTERS, Profile, register_table
from dissector.model import Frame, Kind
from dissector.protocol import table
from dissector.protocol.rules import text

_READS = table.register_reads()  # answers whose registers are values read (16#8000 can mean non-existent)
FIT_ANSWERS = 8  # answers of a slave its traffic is judged on
FIT_READS = 2  # different reads a map must explain (or answers with the non-existent marker)
FIT_FRAMES = 4 * FIT_ANSWERS  # frames of a slave that seldom answers, the same
PRODUCT_CODE = 1  # FC43 object 01h ProductCode


@dataclass(frozen=True, slots=True)
class ProfileChoice:
    """Which profile a slave got and why (the stderr line and the --stats row show it)."""

    slave: int
    profile: str
    reason: str
    frame: int | None  # the frame that decided it (None: forced with --profile, or no evidence)
    final: bool  # identification or forced: later traffic does not change it
    # The input that frame is in, when several are read as one bus (their frame numbers restart with each).
    source: str | None = None

    def text(self) -> str:
        return f"slave {self.slave}: {self.profile} ({self.reason})"


class Cited(int):
    """A frame number of one of several inputs read as one bus, whose numbers restart with each (as the
    summary numbers them under each `==> FILE <==`): a reason cites it with its input, `#2 of b.bin`, the
    way the texts' `{frame:d}` formats it. An int otherwise (choice_frame compares it)."""

    source: str | None

    def __new__(cls, number: int, source: str | None = None) -> Cited:
        cited = super().__new__(cls, number)
        cited.source = source
        return cited

    def __format__(self, spec: str) -> str:
        number = int(self).__format__(spec)
        return number if self.source is None else f"{number} of {self.source}"


@dataclass(slots=True)
class _Evidence:
    """The answers one candidate's map explains, for one slave: by read (function, start, count)."""

    reads: dict[tuple[int, int, int], list[int]]  # read -> the frames that answered it
    spans: dict[tuple[int, int, int], str]  # read -> its addresses, `8400..8402`
    marker: int | None = None  # an unmapped address read as the non-existent marker

    def enough(self) -> bool:
        if len(self.reads) >= FIT_READS:
            return True
        return self.marker is not None and sum(map(len, self.reads.values())) >= FIT_READS

    def reason(self, protected: int | None) -> str:
        parts = []
        for read, frames in list(self.reads.items())[:FIT_READS]:
            again = frames[1] if len(frames) > 1 else None  # (the first two frames are named)
            parts.append(text("fit_read" if again is None else "fit_read_again", function=read[0],
                              span=self.spans[read], frame=frames[0], again=again))
        reads = ", ".join(parts)
        if len(self.reads) < FIT_READS and self.marker is not None and protected is not None:
            return text("chosen_fit_marker", reads=reads, protected=protected, marker=self.marker)
        return text("chosen_fit", reads=reads)


@dataclass(slots=True)
class _Judged:
    answers: int = 0
    frames: int = 0
    choice: ProfileChoice | None = None
    evidence: dict[str, _Evidence] | None = None  # candidate -> what its map explains
    ruled_out: set[str] | None = None  # candidates an answer contradicted


class Selector:
    """Chooses a profile per slave from `candidates` (name -> (profile, its map)); `fallback` until then."""

    def __init__(self, candidates: list[tuple[Profile, RegisterMap]], fallback: Profile) -> None:
        self.candidates = candidates
        self.fallback = fallback
        self._slaves: dict[int, _Judged] = {}
        # The first candidate that a function code identifies, by code: one lookup a frame (made again
        # when candidates are added).
        self._identifying: dict[int, Profile] = {}
        self._identifying_from = -1
        self.frozen = False  # the choices were made over the whole input (a first pass): observe() is idle
        # The input being read when several are one bus (render/buses.py Buses.switch), None for one:
        # its name goes with the frames a reason cites (Cited).
        self.source: str | None = None

    def _cited(self, number: int) -> int:
        return number if self.source is None else Cited(number, self.source)

    def settled(self, slave: int) -> bool:
        """No later frame can change this slave's profile unless it is handed to observe()."""
        if self.frozen:
            return True
        judged = self._slaves.get(slave)
        return judged is not None and (
            judged.answers >= FIT_ANSWERS
            or judged.frames >= FIT_FRAMES
            or (judged.choice is not None and judged.choice.final)
        )

    def open(self, slave: int) -> bool:
        """Profile `auto` has no device for this slave (none chosen yet, or the one chosen taken back) and
        may still choose one from its traffic: its frames are provisional."""
        if self.frozen or slave == 0:
            return False
        judged = self._slaves.get(slave)
        if judged is None:
            return True
        choice = judged.choice
        return (choice is None or choice.profile == self.fallback.name) and not self.settled(slave)

    def chosen(self) -> dict[int, ProfileChoice]:
        """The choice of every slave that has one, by slave."""
        return {slave: judged.choice for slave, judged in self._slaves.items() if judged.choice is not None}

    def choice(self, slave: int) -> ProfileChoice | None:
        judged = self._slaves.get(slave)
        return None if judged is None else judged.choice

    def observe(self, frame: Frame) -> ProfileChoice | None:
        """A new choice for frame.slave when this frame decides (or undoes) one, else None."""
        slave = frame.slave
        if slave == 0 or self.frozen:
            return None
        judged = self._slaves.get(slave)
        if judged is None:
            judged = self._slaves[slave] = _Judged()
        current = judged.choice
        if current is not None and current.final:
            return None
        # Once settled, traffic decides nothing more: the compiled path shows the slave's plain
        # transactions itself from then on, and must agree with what this would have said.
        judging = not (judged.answers >= FIT_ANSWERS or judged.frames >= FIT_FRAMES)  # settled(), inline
        judged.frames += 1
        found = self._identified(frame)
        if found is not None:
            judged.choice = found
            return found if current is None or current.profile != found.profile else None
        if frame.kind is not Kind.RESPONSE or not frame.crc_ok:
            return None
        judged.answers += 1
        if current is not None and current.profile != self.fallback.name:
            profile = self.profile(current.profile)
            if profile is not None and profile.functions is not None and frame.function not in profile.functions:
                judged.choice = ProfileChoice(
                    slave, self.fallback.name,
                    text("chosen_unsupported", function=frame.function, frame=self._cited(frame.number),
                         device=profile.device),
                    frame.number, False, self.source,
                )
                # (the device taken back is ruled out; the other candidates are judged on, while the slave is)
                if judged.ruled_out is not None and judged.evidence is not None:
                    judged.ruled_out.add(profile.name)
                    judged.evidence.pop(profile.name, None)
                return judged.choice
            return None
        if not judging:
            return None
        return self._weigh(judged, frame)

    def _weigh(self, judged: _Judged, frame: Frame) -> ProfileChoice | None:
        """Add what this answer says of each candidate; a choice when one alone has enough."""
        if judged.evidence is None:
            judged.evidence, judged.ruled_out = {}, set()
        evidence, ruled_out = judged.evidence, judged.ruled_out
        assert ruled_out is not None
        for profile, rows in self.candidates:
            name = profile.name
            if name in ruled_out:
                continue
            verdict = _fits(frame, profile, rows)
            if verdict is None:
                continue
            if verdict is False:
                ruled_out.add(name)
                evidence.pop(name, None)
                continue
            found = evidence.get(name)
            if found is None:
                found = evidence[name] = _Evidence({}, {})
            registers = frame.registers or []
            read = (frame.function, registers[0].address or 0, len(registers))
            found.reads.setdefault(read, []).append(self._cited(frame.number))
            found.spans.setdefault(read, _span(frame))
            if found.marker is None and verdict is not True:
                found.marker = verdict
        ready = [name for name, found in evidence.items() if found.enough()]
        if len(ready) != 1:
            return None
        profile = self.profile(ready[0])
        assert profile is not None
        judged.choice = ProfileChoice(
            frame.slave, profile.name, evidence[profile.name].reason(profile.protected_value), frame.number, False,
            self.source,
        )
        return judged.choice

    def broadcast(self, forced: dict[int, Profile]) -> tuple[Profile, str | None, ProfileChoice | None, bool]:
        """Slave 0's profile: a broadcast reaches every slave, so it is named with the profile of every slave
        met (forced in `forced`, or chosen so far; over the whole input when frozen), the choice saying so
        (inferred); slaves of different devices, or one met without a device, leave it the fallback, and a
        note says why (the one said; None else).
        Last: a slave met may still get a device, or none is met yet, which may name it otherwise (read once:
        provisional)."""
        fallback = self.fallback.name
        named = {slave: profile for slave, profile in forced.items() if slave and profile.name != fallback}
        unknown = []
        for slave, judged in self._slaves.items():
            choice = judged.choice
            if choice is not None and choice.profile != fallback:
                named[slave] = self.profile(choice.profile) or self.fallback
            elif slave not in named:
                unknown.append(slave)
        provisional = not self.frozen and (not self._slaves or any(map(self.open, self._slaves)))
        if len({profile.name for profile in named.values()}) == 1 and not unknown:
            profile = next(iter(named.values()))
            slaves = f"slave{'s' if len(named) > 1 else ''} {', '.join(map(str, sorted(named)))}"
            said = text("broadcast_profile", profile=profile.name, slaves=slaves)
            return profile, None, ProfileChoice(0, profile.name, said, None, False), provisional
        if named:
            kinds = {slave: profile.name for slave, profile in named.items()} | dict.fromkeys(unknown, "unknown")
            slaves = ", ".join(f"slave {slave} {kinds[slave]}" for slave in sorted(kinds))
            return self.fallback, text("broadcast_mixed", slaves=slaves), None, provisional
        return self.fallback, None, None, provisional

    def profile(self, name: str) -> Profile | None:
        for profile, _ in self.candidates:
            if profile.name == name:
                return profile
        return None

    def _identified(self, frame: Frame) -> ProfileChoice | None:
        if frame.objects and frame.kind is Kind.RESPONSE:
            for obj in frame.objects:
                if obj.id != PRODUCT_CODE:
                    continue
                for profile, _ in self.candidates:
                    if any(obj.value.startswith(code) for code in profile.product_codes):
                        return ProfileChoice(
                            frame.slave, profile.name,
                            text("chosen_product_code", frame=self._cited(frame.number), value=obj.value),
                            frame.number, True, self.source,
                        )
        if self._identifying_from != len(self.candidates):
            self._identifying = {}
            for candidate, _ in reversed(self.candidates):
                self._identifying.update(dict.fromkeys(candidate.identifying_functions, candidate))
            self._identifying_from = len(self.candidates)
        profile = self._identifying.get(frame.function)
        if profile is not None and frame.kind is not Kind.NOISE and frame.crc_ok:
            name = profile.function_names.get(frame.function, str(frame.function))
            return ProfileChoice(
                frame.slave, profile.name,
                text("chosen_function", function=frame.function, name=name, frame=self._cited(frame.number)),
                frame.number, True, self.source,
            )
        return None


def _fits(frame: Frame, profile: Profile, rows: RegisterMap) -> bool | int | None:
    """What this answer says of the device of `profile`: True, it is one the device gives (a function
    it supports, addresses its map knows); an address (int) when it is also read as the device's
    non-existent marker there; False, the device would not give it; None, nothing either way."""
    if not profile.traffic_fit or not rows:
        return None
    if profile.functions is not None and frame.function not in profile.functions:
        return False
    registers = frame.registers
    if not registers:
        return None
    if isinstance(rows, TableRows) and register_table(frame.function) == INPUT_REGISTERS:
        rows = rows.inputs  # (FC4's registers, named by a map's 3X rows apart: Device.rows_for)
    known = 0
    marker: int | None = None
    for register in registers:
        address = register.address
        if address is None:
            return None
        if address in rows:
            known += 1
        elif register.value == profile.protected_value and frame.function in _READS:
            marker = address if marker is None else marker
        else:
            return False
    if not known:
        return None
    return True if marker is None else marker


def _span(frame: Frame) -> str:
    addresses = [register.address for register in frame.registers or [] if register.address is not None]
    return str(addresses[0]) if len(addresses) == 1 else f"{addresses[0]}..{addresses[-1]}"
