"""Device limits: requests a device does not support, beyond its word limits, or broadcast against
its rules, as warnings. One job: what a request asks that this device will refuse."""
from __future__ import annotations

from dissector.devices.device import Device
from dissector.devices.profiles import Profile
from dissector.model import Frame, Kind
from dissector.protocol.rules import text
from dissector.protocol.spec import SPEC
from dissector.protocol.table import lift_of, write_windows

_WRITE_WINDOWS = write_windows()  # requests with a write quantity of their own (FC23)


def within_limits(frame: Frame, device: Device) -> bool:
    """True when a supported request is within the device's limits (nothing to report)."""
    limits = device.limited.get(frame.function)
    if limits is None:
        return False
    quantity = frame.quantity
    if quantity is None or quantity > limits[0]:
        return False
    if len(limits) > 1:
        window = _WRITE_WINDOWS.get(frame.function)
        fields = frame.fields
        # a key, not Container.__getattr__
        return window is not None and fields is not None and fields[window[1]] <= limits[1]
    return True


def check_request(frame: Frame, device: Device) -> None:
    profile = device.profile
    function = frame.function
    name = profile.function_names.get(function) or SPEC.function_name(function)
    if profile.functions is not None and function not in profile.functions:
        frame.warnings.append(text("not_supported", name=name, function=function, device=profile.device))
    elif function in profile.inner_only:
        frame.warnings.append(text("inner_only", name=name, function=function, device=profile.device))
    else:
        check_subfunction(frame, profile)
    limits = profile.limits.get(function)
    if limits is not None:
        _check_limits(frame, profile, name, limits)
    if (
        frame.broadcast
        and profile.broadcast is not None
        and function not in profile.broadcast
        and function not in SPEC.not_broadcast  # decode.py already warned with the spec's rule
    ):
        frame.warnings.append(
            text("device_broadcast", name=name, device=profile.device, allowed=broadcast_allowed(profile))
        )


def unsupported_subfunctions(profile: Profile) -> frozenset[int]:
    """The FC8 sub-functions the spec defines (fields.py warned of the others) that this device does not
    answer: the engine hands their requests to the Python stages (accel/fastsummary.py)."""
    if profile.subfunctions is None:
        return frozenset()
    return frozenset(SPEC.diagnostics) - profile.subfunctions


def check_subfunction(frame: Frame, profile: Profile) -> None:
    """A request's FC8 sub-function that this device does not answer, as a warning (its FC8 requests are
    otherwise unchecked: the annotator calls this alone for them)."""
    sub, answered = frame.subfunction, profile.subfunctions
    if answered is not None and sub is not None and sub not in answered and sub in SPEC.diagnostics:
        frame.warnings.append(text("subfunction_not_supported", subfunction=sub, name=SPEC.diagnostics[sub],
                                   device=profile.device))


def broadcast_allowed(profile: Profile) -> str:
    """The functions a device takes broadcast, as its warning lists them (`5, 6, 15, 16`, or `none`); the
    plugin's profile data carries it (codegen/lua.py)."""
    return ", ".join(str(code) for code in sorted(profile.broadcast or ())) or "none"


def _check_limits(frame: Frame, profile: Profile, name: str, limits: tuple[int, ...]) -> None:
    rule = lift_of(frame.function, Kind.REQUEST)
    if rule is not None and rule.write_window is not None:
        # Read and write quantities (FC23): as the spec's checks of the lifting rule name them.
        fields = frame.fields
        if fields is None:
            return
        checks = [(check.what, fields[check.field]) for check in rule.checks]
    else:
        checks = [("quantity", frame.quantity)]
    for (what, quantity), limit in zip(checks, limits):
        if quantity is not None and quantity > limit:
            frame.warnings.append(
                text("device_limit", what=what, quantity=quantity, device=profile.device, limit=limit, name=name)
            )
