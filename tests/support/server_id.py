"""Report Server ID (FC17) as vw3-decode shows it: the checks the unit and the live tests share."""
from __future__ import annotations

import json

from helpers import hx, run_cli

REQUEST = hx("11 11 CD EC")
RESPONSE = hx("11 11 0A B4 FF 4C 4D 42 33 2E 31 2E 36 76 3E")  # a libmodbus 3.1.6 slave's answer


def _decoded(data: bytes, *options: str) -> str:
    status, out, err = run_cli(["-n", "--hex", data.hex(" "), *options])
    assert (status, err) == (0, "")
    return out


def check_decoded(request: bytes, response: bytes, text: str) -> None:
    count = 2 + len(text)
    detail = _decoded(request + response, "-V")
    assert (
        "        Function: 17 (0x11) Report Server ID\n"
        f"        Byte count: {count} (0x{count:X})\n"
        "        Server id: 180 (0xB4)\n"
        "        Run indicator: ON (0xff)\n"
        f"        Additional data: {text}\n"
    ) in detail
    lines = [json.loads(line) for line in _decoded(request + response, "--json").splitlines()]
    assert lines[1]["fields"] == {"byte_count": count, "server_id": 180, "run_indicator": "ON", "additional_data": text}
    assert (lines[1]["warnings"], lines[1]["request_frame"]) == ([], 1)
    summary = _decoded(request + response).splitlines()[1]
    assert f"17 response  Report Server ID server id 180, run ON, {text!r} [#1]  CRC ok" in summary
