"""What a request's own fields say: evidence that a frame with a good CRC found inside noise is real.

A random byte string passes the CRC once in 65,536 tries; a read request's quantity is within the
spec's limits (1..125 registers: once in 524 for random bytes) and a coil written by FC5 is ON or OFF
(twice in 65,536). Together they are evidence enough for the framer (rtu.RtuFramer._confirmed) to keep a
request that nothing else confirms: one followed by garbage, its answer lost. The limits come from the
protocol table and data/modbus.toml, as the decoder's checks do.
"""
from __future__ import annotations

from dissector.protocol import table
from dissector.protocol.spec import SPEC
from dissector.framing.rules import MAX_SLAVE

COIL_VALUES = (0xFF00, 0x0000)


def _request_checks() -> dict[int, tuple[int, int]]:
    """Function codes whose requests the spec constrains enough to be told from random bytes: the
    quantity's limits of the reads (FC1-FC4: 1..2000 bits, 1..125 registers)."""
    checks = {}
    for entry in table.FUNCTIONS:
        layout = entry.request
        if entry.access is table.Access.READ and layout.limit and layout.length == table.Fixed(8):
            checks[entry.code] = SPEC.limits[layout.limit]  # type: ignore[assignment]
    return checks


READ_LIMITS = _request_checks()
COIL_REQUESTS = table.coil_requests()  # the lifting rules' coil values (FC5)


def plausible_request(buf: bytes | bytearray, i: int, length: int) -> bool:
    """A request whose fields only a real one has: a read of 1..limit items within the address
    space (1 chance in 500 for random bytes, FC3/FC4), or a coil written ON or OFF (1 in 32,768). On
    top of its CRC, it counts where nothing else confirms a frame (RtuFramer._confirmed)."""
    function = buf[i + 1]
    if length != 8 or not 1 <= buf[i] <= MAX_SLAVE:
        return False
    word = buf[i + 4] << 8 | buf[i + 5]
    if function in COIL_REQUESTS:
        return word in COIL_VALUES
    limits = READ_LIMITS.get(function)
    return limits is not None and limits[0] <= word <= limits[1] and (buf[i + 2] << 8 | buf[i + 3]) + word <= 0x10000
