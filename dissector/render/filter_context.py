"""What a display filter needs beyond the item (render/filters.py): the time column's references and
the values the run's enumerated keys can have (the spec's names, the run's profiles' and map codes)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from dissector.model import REGISTER_STATUSES
from dissector.protocol.spec import SPEC

Item = dict[str, Any]

CHOICES = {
    "kind": ("request", "response", "exception", "noise"),
    "mode": ("rtu", "ascii"),
    "status": REGISTER_STATUSES,
}
# Texts the plugin's field numbers with value strings, in their order from 1 (vw3.kind: lua/src/pack.lua
# NUMBER_KIND): a filter takes the number, the name quoted or bare, in any case, as tshark takes a value
# string (`kind == 2`, `kind == Response`), and orders them by number (`kind > 2`: exception, noise).
NUMBERED = {"kind": CHOICES["kind"]}


def numbered_choices(field: str) -> str:
    """`request (1), response (2), ...`: a numbered field's values, as an error names them."""
    return ", ".join(f"{name} ({number})" for number, name in enumerate(NUMBERED[field], 1))


# Enumerated texts: the spec's names (every code 0..255 has one) and, from FilterContext.names, the
# run's profiles' (a profile's own function names, exception meanings, diagnostics).
SPEC_NAMES = {
    "function_name": frozenset(SPEC.function_name(code) for code in range(256)),
    "exception_name": frozenset([SPEC.exception_name(None), *(SPEC.exception_name(code) for code in range(256))]),
    "subfunction_name": frozenset(SPEC.diagnostics.values()),
    "exception_meaning": frozenset(),
    "profile": frozenset(),
}
SHOWN_CHOICES = 12  # an error lists the values when there are at most this many


@dataclass(slots=True)
class FilterContext:
    """What a filter needs beyond the item: the capture's first time and each item's previous captured
    time (the time column's references, set by the caller as items are captured, before filtering),
    and the parameter codes the run's maps know (None: not checked)."""

    first: float | None = None
    previous: dict[int, float | None] | None = None  # frame -> time of the item captured before
    codes: frozenset[str] | None = None
    names: dict[str, frozenset[str]] | None = None  # Annotator.filter_names(): the profiles' texts

    @classmethod
    def of(cls, annotate: object) -> FilterContext:
        """The context of a run whose annotator is `annotate` (None: -n, spec names only)."""
        codes = getattr(annotate, "codes", None)
        names = getattr(annotate, "filter_names", None)
        if names is None:
            from dissector.devices.profiles import BUILTIN_PROFILES

            found = {"profile": frozenset(BUILTIN_PROFILES)}
        else:
            found = names()
        return cls(codes=frozenset(codes()) if codes is not None else None, names=found)

    def choices(self, field: str) -> frozenset[str] | tuple[str, ...] | None:
        """The values an enumerated field can have in this run (None: not enumerated)."""
        spec = SPEC_NAMES.get(field)
        if spec is None:
            return CHOICES.get(field)
        if self.names is None:
            return None  # no run to ask (a library caller): not checked
        return spec | self.names.get(field, frozenset())

    def refusal(self, field: str, value: Any) -> str | None:
        """Why `value` is no value of the enumerated `field` in this run, with a suggestion (None: it is one,
        or `field` is not enumerated)."""
        import difflib

        from dissector.render.filter_fields import REGISTER_TEXTS

        if value == "" and field in REGISTER_TEXTS:
            return None  # (a register's empty text: the value of one without it, as tshark reads the plugin's)
        if field == "code" and self.codes is not None:
            choices = tuple(sorted(self.codes))
            if not choices or (isinstance(value, str) and value.upper() in self.codes) or value in choices:
                return None  # compared as the maps spell it
            close = difflib.get_close_matches(str(value).upper(), choices, n=3)
            hint = f" (did you mean {', '.join(map(repr, close))}?)" if close else ""
            return f"code {value!r} is no parameter code of this run's maps{hint}"
        choices = self.choices(field)
        if not choices or value in choices:
            return None
        ordered = sorted(choices) if isinstance(choices, frozenset) else list(choices)
        lowered = {choice.lower(): choice for choice in ordered}
        close = difflib.get_close_matches(str(value).lower(), list(lowered), n=1)
        hint = f" (did you mean {lowered[close[0]]!r}?)" if close else ""
        listed = f": {field} is one of {', '.join(ordered)}" if len(ordered) <= SHOWN_CHOICES else ""
        if field in NUMBERED:
            listed = f": {field} is one of {numbered_choices(field)}"
        return f"{field} {value!r} does not exist{hint}{listed}"

    def captured(self, items: list[Any], last: float | None, packets: Any) -> float | None:
        """The time references of `items` as captured, before filtering, after an item at `last` (returned:
        theirs); a network capture's from its packets, as the time column (render/timefmt.py Clock.packets)."""
        from dissector.model import Stamp
        from dissector.render.timefmt import network, packet_before

        previous: dict[int, float | None] = {}
        packets = network(packets)
        for item in items:
            if item.time is None:
                continue
            if self.first is None:
                self.first = item.time if packets is None or packets.start is None else Stamp(packets.start)
            previous[item.number] = last if packets is None else packet_before(packets, item)
            last = item.time
        self.previous = previous
        return last

    def seconds(self, item: Item, key: str) -> float | None:
        time = item.get("time")
        if not isinstance(time, (int, float)):
            return None
        if key == "time_relative":
            return None if self.first is None else time - self.first
        before = (self.previous or {}).get(item.get("frame"))  # type: ignore[arg-type]
        return 0.0 if before is None else time - before
