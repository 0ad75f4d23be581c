"""Hypothesis strategies: random valid transactions (request, response) of every public function code."""
from __future__ import annotations

from hypothesis import strategies as st

from dissector.protocol.crc import crc16_reference

u16 = st.integers(0, 0xFFFF)
slaves = st.integers(1, 247)


def adu(slave: int, pdu: bytes) -> bytes:
    body = bytes([slave]) + pdu
    return body + crc16_reference(body).to_bytes(2, "little")


def w(*values: int) -> bytes:
    return b"".join(value.to_bytes(2, "big") for value in values)


@st.composite
def read_bits(draw: st.DrawFn, function: int) -> tuple[bytes, bytes, dict]:
    quantity = draw(st.integers(1, 2000))
    start = draw(st.integers(0, 0x10000 - quantity))
    packed = draw(st.binary(min_size=(quantity + 7) // 8, max_size=(quantity + 7) // 8))
    request = bytes([function]) + w(start, quantity)
    response = bytes([function, len(packed)]) + packed
    return request, response, {"start": start, "quantity": quantity}


@st.composite
def read_registers(draw: st.DrawFn, function: int) -> tuple[bytes, bytes, dict]:
    quantity = draw(st.integers(1, 125))
    start = draw(st.integers(0, 0x10000 - quantity))
    values = draw(st.lists(u16, min_size=quantity, max_size=quantity))
    request = bytes([function]) + w(start, quantity)
    response = bytes([function, 2 * quantity]) + w(*values)
    registers = [{"address": start + i, "value": v} for i, v in enumerate(values)]
    return request, response, {"start": start, "quantity": quantity, "registers": registers}


@st.composite
def write_single(draw: st.DrawFn, function: int) -> tuple[bytes, bytes, dict]:
    address = draw(u16)
    value = draw(st.sampled_from([0xFF00, 0x0000])) if function == 5 else draw(u16)
    pdu = bytes([function]) + w(address, value)
    return pdu, pdu, {"start": address, "quantity": 1}


@st.composite
def write_registers(draw: st.DrawFn) -> tuple[bytes, bytes, dict]:
    quantity = draw(st.integers(1, 123))
    start = draw(st.integers(0, 0x10000 - quantity))
    values = draw(st.lists(u16, min_size=quantity, max_size=quantity))
    request = bytes([16]) + w(start, quantity) + bytes([2 * quantity]) + w(*values)
    response = bytes([16]) + w(start, quantity)
    registers = [{"address": start + i, "value": v} for i, v in enumerate(values)]
    return request, response, {"start": start, "quantity": quantity, "request_registers": registers}


@st.composite
def write_coils(draw: st.DrawFn) -> tuple[bytes, bytes, dict]:
    quantity = draw(st.integers(1, 1968))
    start = draw(st.integers(0, 0x10000 - quantity))
    packed = draw(st.binary(min_size=(quantity + 7) // 8, max_size=(quantity + 7) // 8))
    request = bytes([15]) + w(start, quantity) + bytes([len(packed)]) + packed
    response = bytes([15]) + w(start, quantity)
    return request, response, {"start": start, "quantity": quantity}


@st.composite
def diagnostics(draw: st.DrawFn) -> tuple[bytes, bytes, dict]:
    # (not 04, Force Listen Only Mode: the spec has no server answer it, data/modbus.toml [pairing])
    sub = draw(st.sampled_from([1, 2, 10, 11, 12, 13, 14, 15, 16, 17, 18, 20]))
    request = bytes([8]) + w(sub, 0)
    response = bytes([8]) + w(sub, draw(u16))
    return request, response, {"subfunction": sub}


@st.composite
def read_write(draw: st.DrawFn) -> tuple[bytes, bytes, dict]:
    read_quantity = draw(st.integers(1, 125))
    write_quantity = draw(st.integers(1, 121))
    read_start = draw(st.integers(0, 0x10000 - read_quantity))
    write_start = draw(st.integers(0, 0x10000 - write_quantity))
    write_values = draw(st.lists(u16, min_size=write_quantity, max_size=write_quantity))
    read_values = draw(st.lists(u16, min_size=read_quantity, max_size=read_quantity))
    request = (
        bytes([23]) + w(read_start, read_quantity, write_start, write_quantity)
        + bytes([2 * write_quantity]) + w(*write_values)
    )
    response = bytes([23, 2 * read_quantity]) + w(*read_values)
    registers = [{"address": read_start + i, "value": v} for i, v in enumerate(read_values)]
    return request, response, {"start": read_start, "quantity": read_quantity, "registers": registers}


@st.composite
def device_identification(draw: st.DrawFn) -> tuple[bytes, bytes, dict]:
    texts = draw(st.lists(st.binary(min_size=0, max_size=16), min_size=1, max_size=7))
    objects = b"".join(bytes([index, len(text)]) + text for index, text in enumerate(texts))
    request = bytes([43, 14, 1, 0])
    response = bytes([43, 14, 1, 1, 0, 0, len(texts)]) + objects
    return request, response, {}


@st.composite
def simple(draw: st.DrawFn) -> tuple[bytes, bytes, dict]:
    choice = draw(st.sampled_from(["fc7", "fc11", "fc22", "fc24"]))
    if choice == "fc7":
        return bytes([7]), bytes([7, draw(st.integers(0, 255))]), {}
    if choice == "fc11":
        return bytes([11]), bytes([11]) + w(draw(u16), draw(u16)), {}
    if choice == "fc22":
        pdu = bytes([22]) + w(draw(u16), draw(u16), draw(u16))
        return pdu, pdu, {}
    count = draw(st.integers(0, 31))
    values = draw(st.lists(u16, min_size=count, max_size=count))
    return bytes([24]) + w(draw(u16)), bytes([24]) + w(2 + 2 * count, count, *values), {}


@st.composite
def exception(draw: st.DrawFn) -> tuple[bytes, bytes, dict]:
    request, _, expected = draw(read_registers(3))
    code = draw(st.sampled_from([1, 2, 3, 4, 6]))
    return request, bytes([0x83, code]), {"exception_code": code}


pdu_pairs = st.one_of(
    read_bits(1),
    read_bits(2),
    read_registers(3),
    read_registers(4),
    write_single(5),
    write_single(6),
    write_registers(),
    write_coils(),
    diagnostics(),
    read_write(),
    device_identification(),
    simple(),
    exception(),
)


@st.composite
def transactions(draw: st.DrawFn, slave_numbers: st.SearchStrategy[int] = slaves) -> tuple[bytes, bytes, dict]:
    """(request ADU, response ADU, expected fields) for one slave."""
    slave = draw(slave_numbers)
    request, response, expected = draw(pdu_pairs)
    return adu(slave, request), adu(slave, response), expected


# A few slaves, the highest address among them: sessions where the same slaves come back.
named_slaves = st.sampled_from([1, 12, 20, 247])


def session_bytes(exchanges: list[tuple[bytes, bytes, dict]]) -> bytes:
    """The bytes of transactions() one after another: each request, then its response."""
    return b"".join(request + response for request, response, _expected in exchanges)
