"""An annotator from what the user asked for: profiles (`atv71`, `12=atv71`) and maps (`FILE`, `12=FILE`,
`sel749m=FILE`), as plain strings, so that the CLI, the tests and the benchmarks build it one way."""
from __future__ import annotations

from pathlib import Path

from dissector.devices.annotator import Annotator, MapLayer
from dissector.devices.device import layered_rows
from dissector.devices.maps import TableRows, load_map_file
from dissector.devices.maps_refs import CheckedAnnotator
from dissector.devices.profiles import (
    ADDRESS_STYLES, AUTO, BUILTIN_PROFILES, DEFAULT_PROFILE, FALLBACK_PROFILE, Profile, load_profile,
    load_profile_map,
)
from dissector.devices.selection import Selector
from dissector.errors import ProfileError


def _split_target(spec: str, option: str) -> tuple[str | None, str]:
    """`12=atv71` -> ("12", "atv71"); `atv71` -> (None, "atv71"); spaces around '=' are not the name's
    (`12 = atv71`), as the plugin's profiles preference reads them."""
    target, sep, rest = spec.partition("=")
    if not sep:
        return None, spec
    target, rest = target.strip(), rest.strip()
    if not rest:
        raise ProfileError(f"{option} {spec!r}: nothing after '='")
    return target, rest


def _slave(text: str, option: str, spec: str) -> int:
    # ASCII digits only: int() would also take '+1', '1_0' (10) and other scripts' digits
    if not (text.isascii() and text.isdigit()):
        raise ProfileError(f"{option} {spec!r}: {text!r} is not a slave address")
    slave = int(text, 10)
    if not 0 <= slave <= 247:
        raise ProfileError(f"{option} {spec!r}: slave {slave} is outside 0..247")
    return slave


def build_annotator(
    profiles: list[str], maps: list[str], address_style: str | None = None
) -> Annotator:
    """Profiles (`atv71`, `12=atv71`), maps (`FILE`, `12=FILE`, `sel749m=FILE`) -> an Annotator."""
    if address_style is not None and address_style not in ADDRESS_STYLES:
        raise ProfileError(f"--address-style {address_style!r}: use {' or '.join(ADDRESS_STYLES)}")
    default: Profile | None = None
    auto = False
    per_slave: dict[int, Profile] = {}
    loaded: dict[str, Profile] = {}
    for spec in profiles:
        target, name = _split_target(spec, "--profile")
        if name == AUTO:
            if target is not None:
                raise ProfileError(f"--profile {spec!r}: auto is for every slave (--profile auto)")
            if default is not None or auto:
                raise ProfileError(
                    f"--profile {spec!r}: a default profile ({default.name if default else AUTO}) is already set"
                )
            auto = True
            continue
        profile = loaded.get(name)
        if profile is None:
            profile = loaded[name] = load_profile(name)
        if target is None:
            if default is not None or auto:
                raise ProfileError(
                    f"--profile {spec!r}: a default profile ({default.name if default else AUTO}) is already set"
                )
            default = profile
            continue
        slave = _slave(target, "--profile", spec)
        if slave in per_slave:
            raise ProfileError(f"--profile {spec!r}: slave {slave} already has a profile")
        per_slave[slave] = profile
    selector = None
    if default is None and (auto or DEFAULT_PROFILE == AUTO):
        default = loaded.get(FALLBACK_PROFILE) or load_profile(FALLBACK_PROFILE)
        candidates = [loaded.get(name) or load_profile(name) for name in BUILTIN_PROFILES]
        selector = Selector([], default)
        auto_candidates = [profile for profile in candidates if profile.name != default.name]
    elif default is None:
        default = loaded.get(DEFAULT_PROFILE) or load_profile(DEFAULT_PROFILE)
    names = {profile.name for profile in [default, *per_slave.values()]}
    if selector is not None:
        names |= {profile.name for profile in auto_candidates}
    layers: list[MapLayer] = []
    paths: list[str] = []  # each layer's file, as given (maps_refs names it)
    for spec in maps:
        target, path = _split_target(spec, "--map")
        if target is not None and Path(spec).exists():
            target, path = None, spec  # a file whose name holds '=' is a file, not a target
        rows = load_map_file(path)
        paths.append(path)
        if target is None:
            layers.append(MapLayer(rows))
        elif target.isdigit():
            layers.append(MapLayer(rows, slave=_slave(target, "--map", spec)))
        elif target in names:
            layers.append(MapLayer(rows, profile=target))
        else:
            raise ProfileError(
                f"--map {spec!r}: {target!r} is neither a slave address nor a profile in use "
                f"({', '.join(sorted(names))})"
            )
    if selector is not None:
        # A profile's map as traffic is judged against it: its own rows and the --map rows given for it.
        # (a map in PLC references: FC4's reads judged against its 3X rows, as the device will name them)
        for profile in auto_candidates:
            rows, inputs = layered_rows(profile, load_profile_map(profile),
                                        [layer for layer in layers if layer.profile == profile.name])
            selector.candidates.append((profile, rows if inputs is None else TableRows(rows, inputs)))
    if layers:  # (a map written in PLC references is told from the traffic: maps_refs.py)
        return CheckedAnnotator(default, per_slave, layers, address_style, selector, paths=paths)
    return Annotator(default, per_slave, layers, address_style, selector)
