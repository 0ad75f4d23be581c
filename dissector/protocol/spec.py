"""Protocol tables (function, exception and object names, limits) loaded from data/modbus.toml."""
from __future__ import annotations

import tomllib
from dataclasses import dataclass
from importlib import resources


def _int_keys(table: dict[str, object]) -> dict[int, str]:
    return {int(key): str(value) for key, value in table.items()}


@dataclass(frozen=True, slots=True)
class DiagnosticData:
    """What an FC8 request's data word is for one sub-function ([diagnostic_data]): the words allowed and what
    each asks ("": nothing to say), or the character it sets (`character`: what, `names`: of unprintable ones)."""

    data: dict[int, str] | None = None
    character: str | None = None
    names: dict[int, str] | None = None


@dataclass(frozen=True, slots=True)
class Spec:
    functions: dict[int, str]
    exceptions: dict[int, str]
    diagnostics: dict[int, str]
    mei_types: dict[int, str]
    device_id_codes: dict[int, str]
    device_id_objects: dict[int, str]
    limits: dict[str, object]
    not_broadcast: frozenset[int]
    plc_references: dict[int, int]  # function -> PLC reference base (1: 00001, 10001, 30001)
    user_defined: frozenset[int]  # function codes the spec leaves to users
    read_only_exception: int  # the exception that refuses a write of a read-only parameter
    # Codes with no public layout that a shipped device profile speaks (data/profiles/*.toml `functions`)
    vendor_functions: frozenset[int]
    # The rule tables protocol/rules.py reads: how a write is confirmed, how frames are lifted, the texts
    confirm: dict[int, str]
    lift: dict[str, dict[str, object]]
    texts: dict[str, str]
    layouts: dict[str, list[str]]  # each layout's fields (protocol/shapes.py, layouts.py)
    parts: dict[str, list[str]]  # the fields of the parts layouts repeat or switch to
    names: dict[str, dict[int, str]]  # value names of u8{NAMES} fields
    # [pairing], by function code: the data bytes an answer echoes from its request (FC8: 2, the sub-function),
    # the values of a request's first data word no answer follows (FC8: 4, Force Listen Only Mode)
    echo: dict[int, int]
    never_answered: dict[int, frozenset[int]]
    diagnostic_data: dict[int, DiagnosticData]  # FC8 request data by sub-function
    diagnostic_echoes: frozenset[int]  # FC8 sub-functions whose response repeats the request's data

    def function_name(self, code: int) -> str:
        name = self.functions.get(code)
        if name is not None:
            return name
        return self.texts["user_function" if code in self.user_defined else "other_function"].format(code=code)

    def exception_name(self, code: int | None) -> str:
        if code is None:
            return self.texts["missing_exception"]
        return self.exceptions.get(code) or self.texts["undefined_exception"].format(code=code)


def load_spec() -> Spec:
    text = resources.files("dissector").joinpath("data/modbus.toml").read_text(encoding="utf-8")
    data = tomllib.loads(text)
    return Spec(
        functions=_int_keys(data["functions"]),
        exceptions=_int_keys(data["exceptions"]),
        diagnostics=_int_keys(data["diagnostics"]),
        mei_types=_int_keys(data["mei_types"]),
        device_id_codes=_int_keys(data["device_id_codes"]),
        device_id_objects=_int_keys(data["device_id_objects"]),
        limits=data["limits"],
        not_broadcast=frozenset(data["not_broadcast"]),
        plc_references={int(key): int(value) for key, value in data.get("plc_references", {}).items()},
        read_only_exception=int(data["read_only_exception"]),
        user_defined=frozenset(code for low, high in data["user_defined"] for code in range(low, high + 1)),
        vendor_functions=_vendor_functions(frozenset(_int_keys(data["functions"]))),
        confirm=_int_keys(data["confirm"]),
        lift=data["lift"],
        texts={str(key): str(value) for key, value in data["texts"].items()},
        layouts={str(key): [str(field) for field in value] for key, value in data["layouts"].items()},
        parts={str(key): [str(field) for field in value] for key, value in data["parts"].items()},
        names={str(key): _int_keys(value) for key, value in data["names"].items()},
        echo={int(key): int(value) for key, value in data["pairing"]["echo"].items()},
        never_answered={int(key): frozenset(value) for key, value in data["pairing"]["never_answered"].items()},
        diagnostic_data={int(key): _diagnostic_data(value) for key, value in data["diagnostic_data"].items()},
        diagnostic_echoes=frozenset(int(sub) for sub in data["diagnostic_answers"]["echo"]),
    )


def _diagnostic_data(entry: dict[str, object]) -> DiagnosticData:
    words, names = entry.get("data"), entry.get("names")
    return DiagnosticData(
        data=None if words is None else _int_keys(words),  # type: ignore[arg-type]
        character=None if entry.get("character") is None else str(entry["character"]),
        names=None if names is None else _int_keys(names),  # type: ignore[arg-type]
    )


def _vendor_functions(public: frozenset[int]) -> frozenset[int]:
    """The codes shipped profiles list beyond the public ones: the framer must know their frames exist
    before any profile is chosen (a relay's 60h answer on a bus that also carries drives)."""
    codes: set[int] = set()
    for entry in resources.files("dissector").joinpath("data/profiles").iterdir():
        if entry.name.endswith(".toml"):
            codes.update(tomllib.loads(entry.read_text(encoding="utf-8")).get("functions", []))
    return frozenset(codes - public)


SPEC = load_spec()
