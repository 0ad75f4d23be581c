"""Profile `auto`: which device each slave is, from evidence in the capture.

Evidence, strongest first (what identifies a device is data: the `[identify]` table of each profile in
data/profiles/*.toml):
- a Read Device Identification answer whose ProductCode starts with one of a profile's product codes
  (`ATV71HU15M3` -> atv71);
- a function code only that device speaks (SEL-749M 60h-62h, 7Dh), asked or answered;
- traffic that fits one profile alone: answers to function codes it supports, at addresses its map
  knows (or reading the value it returns for a non-existent parameter, 16#8000 on the VW3 A3 303).
  Traffic is judged on a slave's first answers (FIT_ANSWERS); a later answer to a function the chosen
  profile does not support takes the choice back.
Until evidence arrives a slave gets spec semantics only (`generic`): no device claims.
"""
from __future__ import annotations

from dataclasses import dataclass

from dissector.devices.maps import RegisterMap
from dissector.devices.profiles import Profile
from dissector.model import Frame, Kind
from dissector.protocol import table

_READS = table.register_reads()  # answers whose registers are values read (16#8000 can mean non-existent)
FIT_ANSWERS = 8  # answers of a slave its traffic is judged on
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

    def text(self) -> str:
        return f"slave {self.slave}: {self.profile} ({self.reason})"


@dataclass(slots=True)
class _Judged:
    answers: int = 0
    frames: int = 0
    choice: ProfileChoice | None = None


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

    def settled(self, slave: int) -> bool:
        """No later frame can change this slave's profile unless it is handed to observe()."""
        judged = self._slaves.get(slave)
        return judged is not None and (
            judged.answers >= FIT_ANSWERS
            or judged.frames >= FIT_FRAMES
            or (judged.choice is not None and judged.choice.final)
        )

    def choice(self, slave: int) -> ProfileChoice | None:
        judged = self._slaves.get(slave)
        return None if judged is None else judged.choice

    def observe(self, frame: Frame) -> ProfileChoice | None:
        """A new choice for frame.slave when this frame decides (or undoes) one, else None."""
        slave = frame.slave
        if slave == 0:
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
        if current is not None:
            profile = self.profile(current.profile)
            if profile is not None and profile.functions is not None and frame.function not in profile.functions:
                judged.choice = ProfileChoice(
                    slave, self.fallback.name,
                    f"function {frame.function} answered in frame #{frame.number}, which the {profile.device} does not support",
                    frame.number, False,
                )
                return judged.choice
            return None
        if not judging:
            return None
        fits = [profile for profile, rows in self.candidates if _fits(frame, profile, rows)]
        if len(fits) == 1:
            profile = fits[0]
            judged.choice = ProfileChoice(
                slave, profile.name,
                f"traffic fits its map: {_what(frame)} in frame #{frame.number}", frame.number, False,
            )
            return judged.choice
        return None

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
                            f"Read Device Identification in frame #{frame.number}: ProductCode {obj.value!r}",
                            frame.number, True,
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
                f"function {frame.function:02X}h ({name}) in frame #{frame.number}", frame.number, True,
            )
        return None


def _fits(frame: Frame, profile: Profile, rows: RegisterMap) -> bool:
    """This answer is one the device of `profile` gives: a function it supports, addresses it knows."""
    if not profile.traffic_fit or not rows:
        return False
    if profile.functions is not None and frame.function not in profile.functions:
        return False
    registers = frame.registers
    if not registers:
        return False
    known = 0
    for register in registers:
        address = register.address
        if address is None:
            return False
        if address in rows:
            known += 1
        elif register.value != profile.protected_value or frame.function not in _READS:
            return False
    return known > 0


def _what(frame: Frame) -> str:
    addresses = [register.address for register in frame.registers or [] if register.address is not None]
    span = str(addresses[0]) if len(addresses) == 1 else f"{addresses[0]}..{addresses[-1]}"
    return f"function {frame.function} at {span}"
