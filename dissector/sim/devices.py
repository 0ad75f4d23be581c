"""Simulated slaves for the bus simulator: an Altivar 71 with its VW3 A3 303 card, and a SEL-749M relay.

A device gets a request PDU (function code and data) and answers a response PDU, or None when it
stays silent. Requests are parsed with the dissector's own grammars and responses built with them, so
the simulator exercises the same layouts the decoder reads. What each device does is read from
data/simulator.toml and the register map (data/maps/atv71.csv): codes, access and enum values are
never written here.
"""
from __future__ import annotations

from abc import ABC, abstractmethod

import tomllib
from importlib import resources
from typing import Any

from dissector.protocol.grammar import GrammarError, build_pdu, parse_pdu
from dissector.devices.maps import RegisterMap, load_builtin_map
from dissector.model import Kind



def _data_text(name: str) -> str | None:
    resource = resources.files("dissector").joinpath("data", *name.split("/"))
    if resource.is_file():
        return resource.read_text(encoding="utf-8")
    return None


def load_behaviour() -> dict[str, Any]:
    text = _data_text("simulator.toml")
    if text is None:
        raise FileNotFoundError("dissector/data/simulator.toml is missing")
    return tomllib.loads(text)


def load_atv71_map() -> RegisterMap:
    """The ATV71 register map by address (data/maps/atv71.csv, read by column name)."""
    return load_builtin_map("atv71.csv")


Response = bytes | None


def exception_pdu(function: int, code: int) -> bytes:
    fields = {"exception_code": code, "trailing": b""}
    return bytes([function | 0x80]) + build_pdu(function, Kind.EXCEPTION, fields)


def registers_pdu(function: int, values: list[int]) -> bytes:
    fields = {"byte_count": 2 * len(values), "values": values, "odd_byte": None, "trailing": b""}
    return bytes([function]) + build_pdu(function, Kind.RESPONSE, fields)


class Device(ABC):
    """A slave: `handle(pdu, now)` answers a response PDU, or None for no answer."""

    slave: int

    @abstractmethod
    def handle(self, pdu: bytes, now: float) -> Response:
        """The response PDU to a request PDU addressed to this slave (None: no answer)."""


class Atv71(Device):
    """An Altivar 71 behind a VW3 A3 303 card: parameter protection, DRIVECOM start, ramps."""

    def __init__(
        self,
        slave: int,
        product: str = "ATV71HU15M3",
        device_name: str = "MACHINE 4",
        values: dict[str, int] | None = None,
        params: RegisterMap | None = None,
        behaviour: dict[str, Any] | None = None,
    ) -> None:
        self.slave = slave
        self.params = params if params is not None else load_atv71_map()
        self.rules = (behaviour if behaviour is not None else load_behaviour())["atv71"]
        self.product = product
        self.device_name = device_name
        self.by_code = {param.code: param.address for param in self.params.values()}
        self.values: dict[int, int] = {address: 0 for address in self.params}
        for code, value in {**self.rules["initial"], **(values or {})}.items():
            self.values[self.by_code[code]] = value
        if "ADD" in self.by_code:
            self.values[self.by_code["ADD"]] = slave
        self.protected: set[int] = set()
        self._config = {self.by_code[code] for code in self.rules["config_codes"] if code in self.by_code}
        self._drivecom = {int(key, 0): value for key, value in self.rules["drivecom"].items()}
        self._last = 0.0

    # -- state --------------------------------------------------------------------------------
    def address(self, code: str) -> int:
        return self.by_code[code]

    def get(self, code: str) -> int:
        return self.values[self.by_code[code]]

    def protect(self, *codes: str) -> None:
        """Protection is set from the keypad or another channel: nothing of it appears on the bus."""
        self.protected |= {self.by_code[code] for code in codes}

    @property
    def enabled(self) -> bool:
        return self.get("ETA") == self._drivecom.get(0x000F)

    @property
    def running(self) -> bool:
        return self.enabled and (self.get("LFR") != 0 or self.get("RFR") != 0)

    def _advance(self, now: float) -> None:
        """Ramp the output frequency RFR toward the reference LFR (ACC/DEC: 0.1 s for the motor's 50 Hz)."""
        elapsed, self._last = max(0.0, now - self._last), now
        target = self.get("LFR") if self.enabled else 0
        rfr = self.get("RFR")
        if rfr == target:
            return
        ramp = self.get("ACC") if abs(target) > abs(rfr) else self.get("DEC")
        step = int(elapsed * 500 * 10 / max(ramp, 1))  # 0.1 Hz per elapsed time
        if rfr < target:
            rfr = min(target, rfr + step)
        else:
            rfr = max(target, rfr - step)
        self.values[self.by_code["RFR"]] = rfr

    def _write(self, address: int, value: int) -> None:
        self.values[address] = value
        if address == self.by_code["CMD"] and value in self._drivecom:
            self.values[self.by_code["ETA"]] = self._drivecom[value]

    def _write_refusal(self, addresses: list[int]) -> int | None:
        for address in addresses:
            param = self.params.get(address)
            if param is None or param.access not in ("W", "RW"):
                return int(self.rules["bad_address_exception"])
            if self.running and address in self._config:
                return int(self.rules["running_write_exception"])
        return None

    def _read(self, start: int, quantity: int) -> tuple[list[int], bool]:
        unreadable = int(self.rules["unreadable_value"])
        values, any_readable = [], False
        for address in range(start, start + quantity):
            if address in self.values and address not in self.protected:
                values.append(self.values[address])
                any_readable = True
            else:
                values.append(unreadable)
        return values, any_readable

    # -- requests -----------------------------------------------------------------------------
    def handle(self, pdu: bytes, now: float) -> Response:
        self._advance(now)
        function = pdu[0]
        handler = _ATV71_HANDLERS.get(function)
        if handler is None:
            return exception_pdu(function, 1)
        try:
            fields = parse_pdu(function, Kind.REQUEST, pdu[1:])
        except GrammarError:
            return exception_pdu(function, 3)
        return handler(self, function, fields)

    def _fc_read(self, function: int, fields: Any) -> Response:
        if not 1 <= fields.quantity <= self.rules["max_read"]:
            return exception_pdu(function, 3)
        values, readable = self._read(fields.start, fields.quantity)
        if not readable:
            return exception_pdu(function, int(self.rules["all_unreadable_exception"]))
        return registers_pdu(function, values)

    def _fc_write_single(self, function: int, fields: Any) -> Response:
        refusal = self._write_refusal([fields.address])
        if refusal is not None:
            return exception_pdu(function, refusal)
        self._write(fields.address, fields.value)
        return pdu_of(function, Kind.RESPONSE, address=fields.address, value=fields.value)

    def _fc_write_multiple(self, function: int, fields: Any) -> Response:
        if not 1 <= fields.quantity <= self.rules["max_write"] or len(fields["values"]) != fields.quantity:
            return exception_pdu(function, 3)
        addresses = list(range(fields.start, fields.start + fields.quantity))
        refusal = self._write_refusal(addresses)
        if refusal is not None:
            return exception_pdu(function, refusal)
        for address, value in zip(addresses, fields["values"]):
            self._write(address, value)
        return pdu_of(function, Kind.RESPONSE, start=fields.start, quantity=fields.quantity)

    def _fc_read_write(self, function: int, fields: Any) -> Response:
        if not (
            1 <= fields.read_quantity <= self.rules["max_rw_read"]
            and 1 <= fields.write_quantity <= self.rules["max_rw_write"]
            and len(fields["values"]) == fields.write_quantity
        ):
            return exception_pdu(function, 3)
        addresses = list(range(fields.write_start, fields.write_start + fields.write_quantity))
        refusal = self._write_refusal(addresses)
        if refusal is not None:
            return exception_pdu(function, refusal)
        # Modbus: the write is performed before the read.
        for address, value in zip(addresses, fields["values"]):
            self._write(address, value)
        values, readable = self._read(fields.read_start, fields.read_quantity)
        if not readable:
            return exception_pdu(function, int(self.rules["all_unreadable_exception"]))
        return registers_pdu(function, values)

    def _fc_identification(self, function: int, fields: Any) -> Response:
        if fields.mei_type != 14 or fields.body.read_code != 1:
            return exception_pdu(function, 3)
        texts = [
            (0, self.rules["vendor"]),
            (1, self.product),
            (2, self.rules["revision"]),
            (6, self.device_name),
        ]
        objects = [{"id": oid, "length": len(text), "value": text.encode("latin-1")} for oid, text in texts]
        body = {
            "read_code": 1,
            "conformity": self.rules["conformity"],
            "more_follows": 0,
            "next_object_id": 0,
            "object_count": len(objects),
            "objects": objects,
        }
        return pdu_of(function, Kind.RESPONSE, mei_type=14, body=body)

    def _fc_diagnostics(self, function: int, fields: Any) -> Response:
        if fields.subfunction != 0:
            return exception_pdu(function, 1)
        return pdu_of(function, Kind.RESPONSE, subfunction=0, data=fields.data)


def pdu_of(function: int, kind: Kind, **fields: Any) -> bytes:
    """Function code + PDU data built by the dissector's grammar (empty trailing added)."""
    if "subfunction" not in fields:
        fields.setdefault("trailing", b"")
    if "values" in fields:
        fields.setdefault("odd_byte", None)
    return bytes([function]) + build_pdu(function, kind, fields)


_ATV71_HANDLERS = {
    3: Atv71._fc_read,
    4: Atv71._fc_read,
    6: Atv71._fc_write_single,
    8: Atv71._fc_diagnostics,
    16: Atv71._fc_write_multiple,
    23: Atv71._fc_read_write,
    43: Atv71._fc_identification,
}


class Sel749m(Device):
    """A SEL-749M relay: Appendix D error semantics over a simulated register block."""

    def __init__(self, slave: int, behaviour: dict[str, Any] | None = None) -> None:
        self.slave = slave
        self.rules = (behaviour if behaviour is not None else load_behaviour())["sel749m"]
        block = self.rules["simulated_map"]
        self.readable = range(block["read_first"], block["read_last"] + 1)
        self.writable = range(block["write_first"], block["write_last"] + 1)
        self.max_value = int(block["write_max_value"])
        self.values: dict[int, int] = {}

    def value(self, address: int) -> int:
        return self.values.get(address, 0)

    def handle(self, pdu: bytes, now: float) -> Response:
        function = pdu[0]
        illegal_value = int(self.rules["illegal_value_exception"])
        illegal_address = int(self.rules["illegal_address_exception"])
        if function not in self.rules["supported_functions"]:
            return exception_pdu(function, int(self.rules["illegal_function_exception"]))
        try:
            fields = parse_pdu(function, Kind.REQUEST, pdu[1:])
        except GrammarError:
            return exception_pdu(function, illegal_value)  # format error: Bad Packet Format
        if function in (3, 4):
            if not 1 <= fields.quantity <= self.rules["max_read"]:
                return exception_pdu(function, illegal_value)
            addresses = range(fields.start, fields.start + fields.quantity)
            if any(address not in self.readable and address not in self.writable for address in addresses):
                return exception_pdu(function, illegal_address)
            return registers_pdu(function, [self.value(address) for address in addresses])
        if function == 6:
            if fields.address not in self.writable:
                return exception_pdu(function, illegal_address)
            if fields.value > self.max_value:
                return exception_pdu(function, illegal_value)
            self.values[fields.address] = fields.value
            return pdu_of(function, Kind.RESPONSE, address=fields.address, value=fields.value)
        if function == 16:
            if not 1 <= fields.quantity <= self.rules["max_write"]:
                return exception_pdu(function, illegal_value)
            if fields.byte_count != 2 * fields.quantity or len(fields["values"]) != fields.quantity:
                return exception_pdu(function, illegal_value)  # wrong byte count: Bad Packet Format
            addresses = list(range(fields.start, fields.start + fields.quantity))
            if any(address not in self.writable for address in addresses):
                return exception_pdu(function, illegal_address)
            if any(value > self.max_value for value in fields["values"]):
                return exception_pdu(function, illegal_value)
            self.values.update(zip(addresses, fields["values"]))
            return pdu_of(function, Kind.RESPONSE, start=fields.start, quantity=fields.quantity)
        # 60h-62h and 7Dh: layouts not public here; the simulated relay refuses their arguments.
        return exception_pdu(function, illegal_value)
