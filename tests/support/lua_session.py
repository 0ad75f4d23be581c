"""Random Modbus RTU sessions for the Lua parity and fuzz tests, built with the package's own grammars.

A session is a list of pcap records (bytes, time), one frame a record unless a record deliberately
holds a request and its response. Damage is placed where a record-by-record reader and a byte-stream
reader must agree: a frame with a bad CRC is always followed by an intact frame, a noise record (bytes
above the highest slave address, which start no frame) never follows another one, and the capture
ends with an intact frame.
"""
from __future__ import annotations

import random
from typing import Any

from dissector.protocol.crc import crc16, with_crc
from dissector.protocol.grammar import build_pdu
from dissector.model import Kind

Record = tuple[bytes, float]

# Addresses worth reading: mapped ATV71 parameters, CHCF/COP of the p.38 story, CMD/ETA, and the rest.
_AREAS = [(3100, 3110), (3200, 3212), (8400, 8404), (8500, 8503), (8600, 8606), (3015, 3016), (6001, 6003)]
_SLAVES = [12, 2, 1, 3, 7]
_EXCEPTIONS = [1, 2, 2, 3, 4, 6, 7, 0, 9]
_SUBFUNCTIONS = [0, 1, 4, 10, 11, 12, 13, 14, 15, 16, 17, 18, 20, 99]
_OTHER = [0x60, 0x61, 0x62, 0x7D, 0x7E, 65, 100]
_SCANNED = frozenset(_OTHER)


def _scanned_layout(data: bytes) -> bool:
    """A frame of a layout without a length rule (the framer finds its end by a CRC scan)."""
    function = data[1]
    return function in _SCANNED or (function == 8 and data[2:4] == b"\0\0") or (function == 43 and data[2] != 14)


def first_crc_length(data: bytes, minimum: int = 4) -> int | None:
    """The shortest length from `minimum` at which `data` ends in a valid CRC (a framer's scan)."""
    for length in range(minimum, len(data) + 1):
        if crc16(data[: length - 2]) == int.from_bytes(data[length - 2 : length], "little"):
            return length
    return None


def frame(slave: int, function: int, kind: Kind, **fields: Any) -> bytes:
    fields.setdefault("trailing", b"")
    if function in (3, 4, 16, 23) and "values" in fields:
        fields.setdefault("odd_byte", None)
    return with_crc(bytes([slave, function]) + build_pdu(function, kind, fields))


def exception(slave: int, function: int, code: int) -> bytes:
    return with_crc(bytes([slave, function | 0x80, code]))


class SessionBuilder:
    def __init__(self, seed: int) -> None:
        self.rng = random.Random(seed)

    # -- fields -------------------------------------------------------------------------------
    def _start(self) -> int:
        rng = self.rng
        if rng.random() < 0.7:
            low, high = rng.choice(_AREAS)
            return rng.randrange(low, high)
        return rng.randrange(0, 0x10000 - 130) if rng.random() < 0.95 else rng.randrange(0xFFF0, 0x10000)

    def _quantity(self, usual: int, limit: int) -> int:
        rng = self.rng
        roll = rng.random()
        if roll < 0.9:
            return rng.randint(1, usual)
        if roll < 0.97:
            return rng.randint(usual, limit)
        return 0

    def _value(self) -> int:
        rng = self.rng
        roll = rng.random()
        if roll < 0.15:
            return 0x8000
        if roll < 0.25:
            return 3
        return rng.randrange(0, 0x10000) if roll < 0.6 else rng.randrange(0, 1000)

    def _values(self, count: int) -> list[int]:
        return [self._value() for _ in range(count)]

    def _scanned(self, slave: int, function: int, most: int) -> bytes:
        """A frame of a code without a length rule, whose first valid CRC is its own (so that the
        framer's scan finds this frame and not a shorter prefix that happens to check)."""
        while True:
            data = with_crc(bytes([slave, function]) + self.rng.randbytes(self.rng.randint(0, most)))
            if first_crc_length(data) == len(data):
                return data

    # -- transactions: (request, response or None) ---------------------------------------------------------
    def transaction(self, slave: int) -> tuple[bytes, bytes | None]:
        rng = self.rng
        function = rng.choice([3, 3, 3, 4, 6, 6, 16, 16, 23, 1, 2, 5, 7, 8, 11, 12, 15, 17, 22, 24, 43, 0])
        if function == 0:
            function = rng.choice(_OTHER)
            return self._scanned(slave, function, 12), self._scanned(slave, function, 30)
        if function in (3, 4):
            start, quantity = self._start(), self._quantity(12, 125)
            request = frame(slave, function, Kind.REQUEST, start=start, quantity=quantity)
            count = quantity if rng.random() < 0.95 else max(0, quantity - 1)
            response = frame(slave, function, Kind.RESPONSE, byte_count=2 * count, values=self._values(count))
            return request, response
        if function in (1, 2):
            start, quantity = self._start(), self._quantity(40, 2000)
            count = min((quantity + 7) // 8, 250)
            request = frame(slave, function, Kind.REQUEST, start=start, quantity=quantity)
            return request, frame(slave, function, Kind.RESPONSE, byte_count=count, status=rng.randbytes(count))
        if function in (5, 6):
            address = self._start()
            value = rng.choice([0xFF00, 0, 0x1234]) if function == 5 else self._value()
            request = frame(slave, function, Kind.REQUEST, address=address, value=value)
            return request, request
        if function == 16:
            start, quantity = self._start(), self._quantity(10, 123)
            count = quantity if rng.random() < 0.95 else quantity + 1
            request = frame(slave, 16, Kind.REQUEST, start=start, quantity=quantity, byte_count=2 * count,
                            values=self._values(count))
            return request, frame(slave, 16, Kind.RESPONSE, start=start, quantity=quantity)
        if function == 15:
            start, quantity = self._start(), self._quantity(40, 1968)
            count = min((quantity + 7) // 8, 240)
            request = frame(slave, 15, Kind.REQUEST, start=start, quantity=quantity, byte_count=count,
                            status=rng.randbytes(count))
            return request, frame(slave, 15, Kind.RESPONSE, start=start, quantity=quantity)
        if function == 23:
            read_quantity, write_quantity = self._quantity(10, 125), self._quantity(10, 121)
            write_quantity = min(write_quantity, 100)
            request = frame(slave, 23, Kind.REQUEST, read_start=self._start(), read_quantity=read_quantity,
                            write_start=self._start(), write_quantity=write_quantity,
                            byte_count=2 * write_quantity, values=self._values(write_quantity))
            count = min(read_quantity, 120)
            return request, frame(slave, 23, Kind.RESPONSE, byte_count=2 * count, values=self._values(count))
        if function == 8:
            sub = rng.choice(_SUBFUNCTIONS)
            while True:
                data = rng.randbytes(rng.randint(1, 8)) if sub == 0 else rng.randbytes(2)
                request = frame(slave, 8, Kind.REQUEST, subfunction=sub, data=data)
                if sub != 0 or first_crc_length(request, 6) == len(request):
                    return request, request
        if function == 7:
            return frame(slave, 7, Kind.REQUEST), frame(slave, 7, Kind.RESPONSE, status=rng.randrange(256))
        if function == 11:
            return frame(slave, 11, Kind.REQUEST), frame(
                slave, 11, Kind.RESPONSE, status=rng.choice([0, 0xFFFF]), event_count=rng.randrange(0x10000)
            )
        if function == 12:
            events = rng.randbytes(rng.randint(0, 20))
            return frame(slave, 12, Kind.REQUEST), frame(
                slave, 12, Kind.RESPONSE, byte_count=6 + len(events), status=0, event_count=1,
                message_count=2, events=events,
            )
        if function == 17:
            data = rng.choice([rng.randbytes(rng.randint(0, 18)), b"LMB3.1.6"])
            return frame(slave, 17, Kind.REQUEST), frame(
                slave, 17, Kind.RESPONSE, byte_count=2 + len(data), server_id=rng.randrange(256),
                run_indicator=rng.choice([0, 0xFF, 0xFF, rng.randrange(256)]), additional_data=data,
            )
        if function == 22:
            request = frame(slave, 22, Kind.REQUEST, address=self._start(), and_mask=rng.randrange(0x10000),
                            or_mask=rng.randrange(0x10000))
            return request, request
        if function == 24:
            count = rng.randint(0, 33)
            extra = 2 if rng.random() < 0.1 else 0
            return frame(slave, 24, Kind.REQUEST, address=self._start()), frame(
                slave, 24, Kind.RESPONSE, byte_count=2 + 2 * count + extra, fifo_count=count,
                values=self._values(count), trailing=rng.randbytes(extra),
            )
        # 43 / MEI 14: device identification, with a revision that may or may not be "MMmm".
        revision = rng.choice([b"0201", b"0310", b"V2.1", b"12"])
        objects = [(0, b"Telemecanique"), (1, b"ATV71HU15M3"), (2, revision), (6, b"MACHINE 4")]
        request = frame(slave, 43, Kind.REQUEST, mei_type=14, body={"read_code": 1, "object_id": 0})
        response = frame(
            slave, 43, Kind.RESPONSE, mei_type=14,
            body={
                "read_code": 1, "conformity": 1, "more_follows": 0, "next_object_id": 0,
                "object_count": len(objects),
                "objects": [{"id": key, "length": len(value), "value": value} for key, value in objects],
            },
        )
        return request, response

    # -- the session ------------------------------------------------------------------------------------
    def session(self, transactions: int, start_time: float = 1767225600.0) -> list[Record]:
        rng = self.rng
        records: list[Record] = []
        time = start_time
        last_noise = True  # no noise record first
        # Frame records to come that must be intact: after a damaged frame (1: it is shown as damaged
        # only where an intact frame follows), after noise (2: a frame that resynchronises counts only
        # where an intact frame follows it), after a response nobody asked for (1: the same rule).
        protect = 0

        def add(data: bytes, gap: float) -> None:
            nonlocal time, protect
            time += gap
            records.append((data, round(time, 6)))
            protect = max(0, protect - 1)
            if _scanned_layout(data):
                protect = max(protect, 1)  # found by a CRC scan: counts only where an intact frame follows

        def damage(data: bytes, chance: float) -> bytes:
            # Only frames whose length a rule gives can be shown with a bad CRC; the others (found by
            # scanning for a CRC) turn into noise, which a byte stream may join to the next record.
            nonlocal protect
            if protect or rng.random() >= chance or _scanned_layout(data):
                return data
            protect = 2  # this frame, then the one after it
            return data[:-2] + bytes([data[-2] ^ 0x5A, data[-1]])

        for _ in range(transactions):
            if rng.random() < 0.03 and not last_noise and not protect:
                time += 0.003
                records.append((bytes([rng.randrange(248, 256)]) * rng.randint(1, 20), round(time, 6)))
                last_noise = True
                protect = 2
            else:
                last_noise = False
            slave = rng.choice(_SLAVES) if rng.random() < 0.9 else rng.randint(1, 247)
            request, response = self.transaction(slave)
            if rng.random() < 0.03:
                # Broadcast: slave 0, no answer.
                add(with_crc(bytes([0]) + request[1:-2]), rng.uniform(0.004, 0.012))
                continue
            sent = damage(request, 0.04)
            add(sent, rng.uniform(0.004, 0.012))
            roll = rng.random()
            if roll < 0.06 and not protect:
                continue  # unanswered
            if roll < 0.12:
                response = exception(slave, request[1], rng.choice(_EXCEPTIONS))
            if response is None:
                continue
            if roll > 0.96 and not protect:
                # Request and response in one record (a tap that cut records by time).
                data, when = records.pop()
                records.append((data + response, when))
                continue
            late = 1.2 if rng.random() < 0.02 else rng.uniform(0.003, 0.03)
            add(damage(response, 0.03), late)
            if rng.random() < 0.02 and not protect:
                # A response nobody asked for (the tap missed the request).
                _, stray = self.transaction(rng.choice(_SLAVES))
                if stray is not None:
                    add(stray, 0.01)
                    protect = 1
        if protect or not records:
            request, _ = self.transaction(12)
            add(request, 0.01)
        return records


def random_records(seed: int, count: int) -> list[Record]:
    """Fuzz records: random bytes, truncated and oversized frames, cut and glued sessions."""
    rng = random.Random(seed)
    builder = SessionBuilder(seed + 1)
    session = builder.session(count // 2)
    records: list[Record] = []
    time = 1767225600.0
    while len(records) < count:
        time += 0.001
        roll = rng.random()
        data, _ = rng.choice(session)
        if roll < 0.2:
            record = rng.randbytes(rng.randint(0, 40))
        elif roll < 0.3:
            record = rng.randbytes(rng.randint(257, 3000))
        elif roll < 0.5:
            record = data[: rng.randint(0, max(0, len(data) - 1))]
        elif roll < 0.6:
            record = data + rng.randbytes(rng.randint(1, 300))
        elif roll < 0.7:
            glued = b"".join(rng.choice(session)[0] for _ in range(rng.randint(2, 30)))
            cut = rng.randint(0, len(glued))
            record = glued[cut:] if rng.random() < 0.5 else glued[:cut]
        elif roll < 0.8:
            mutable = bytearray(data)
            for _ in range(rng.randint(1, 4)):
                mutable[rng.randrange(len(mutable))] = rng.randrange(256)
            record = bytes(mutable)
        elif roll < 0.85:
            # A frame whose length byte promises more than there is, or a MEI object list past the end.
            record = with_crc(bytes([rng.randint(0, 247), rng.choice([3, 12, 15, 16, 23, 24, 43, 8])])
                              + bytes([14, 1, 1, 0, 0, 255]) + rng.randbytes(rng.randint(0, 20)))
        elif roll < 0.9:
            record = b":" + rng.randbytes(rng.randint(0, 60)).hex().upper().encode() + b"\r\n"
        else:
            record = data
        records.append((record, time))
    return records


def ascii_frame(binary: bytes, lower: bool = False, bad: bool = False) -> bytes:
    """The Modbus ASCII form of an RTU frame's bytes (CRC dropped, LRC added)."""
    check = (-sum(binary)) & 0xFF
    if bad:
        check ^= 0x01
    text = (binary + bytes([check])).hex()
    return b":" + (text if lower else text.upper()).encode() + b"\r\n"


def ascii_session(seed: int, transactions: int, start_time: float = 1767225600.0) -> list[Record]:
    """A Modbus ASCII session: the RTU transactions re-encoded, with bad LRCs, lower-case digits, junk
    between frames (never two junk records in a row), cut frames and unanswered requests."""
    builder = SessionBuilder(seed)
    rng = builder.rng
    records: list[Record] = []
    time = start_time
    junk_last = True
    for _ in range(transactions):
        time += rng.uniform(0.005, 0.02)
        if rng.random() < 0.04 and not junk_last:
            records.append((bytes(rng.choice(b"xyz \t0123GHIJ") for _ in range(rng.randint(1, 10))), round(time, 6)))
            junk_last = True
            continue
        junk_last = False
        slave = rng.choice(_SLAVES)
        request, response = builder.transaction(slave)
        roll = rng.random()
        records.append((ascii_frame(request[:-2], lower=roll < 0.03, bad=0.03 <= roll < 0.06), round(time, 6)))
        if rng.random() < 0.06 or response is None:
            continue
        if rng.random() < 0.1:
            response = exception(slave, request[1], rng.choice(_EXCEPTIONS))
        time += rng.uniform(0.003, 0.03)
        encoded = ascii_frame(response[:-2], bad=rng.random() < 0.03)
        if rng.random() < 0.02:
            encoded = encoded[:-1]  # LF lost: the frame runs into the next one's ':'
            junk_last = True  # (junk next would join it in a byte stream)
        records.append((encoded, round(time, 6)))
    return records
