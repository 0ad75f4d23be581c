"""A real master's debug log decoded (hunt64): mbpoll -v (libmodbus's debug output) polls a server on a
pseudo-terminal, for coils, discrete inputs, input and holding registers and a write of registers; its
log, read by vw3-decode, holds exactly the frames that went over the line, the server's answers paired with
the requests (before, the log was one noise item: 'the input is text, but neither a hex dump nor Modbus
ASCII')."""
from __future__ import annotations

import json
import os
import select
import struct
import subprocess
import time
import tty
from pathlib import Path

import pytest

from dissector.protocol.crc import with_crc
from helpers import run_cli
from lua_harness import ensure_tool

pytestmark = pytest.mark.integration


def _answer(request: bytes) -> bytes:
    unit, function = request[0], request[1]
    start, count = struct.unpack(">HH", request[2:6])
    if function in (1, 2):
        return bytes([unit, function, (count + 7) // 8]) + bytes([0xA5] * ((count + 7) // 8))
    if function in (3, 4):
        return bytes([unit, function, 2 * count]) + b"".join(struct.pack(">H", start + i) for i in range(count))
    return request[:6]  # FC6, FC16: the echo of address and value/quantity


def _poll(args: list[str], values: list[str]) -> tuple[str, list[bytes]]:
    """mbpoll's standard output (its debug log) and the frames on the line (its request and our answer)."""
    mbpoll = ensure_tool("mbpoll", "mbpoll")
    master, slave = os.openpty()
    tty.setraw(slave)
    command = [mbpoll, "-v", "-m", "rtu", "-b", "19200", "-P", "even", "-o", "0.5", "-1", *args, os.ttyname(slave),
               *values]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    line: list[bytes] = []
    heard = b""
    deadline = time.monotonic() + 10
    try:
        while process.poll() is None and time.monotonic() < deadline:
            ready, _, _ = select.select([master], [], [], 0.03)
            if ready:
                heard += os.read(master, 512)
            elif heard:  # a silence after the request: answer it
                line.append(heard)
                answer = with_crc(_answer(heard[:-2]))
                os.write(master, answer)
                line.append(answer)
                heard = b""
        out = process.communicate(timeout=10)[0].decode("utf-8", "replace")
    finally:
        os.close(master)
        os.close(slave)
    return out, line


@pytest.mark.parametrize("args, values", [
    (["-a", "3", "-t", "0", "-r", "5", "-c", "12"], []), (["-a", "4", "-t", "1", "-r", "1", "-c", "3"], []),
    (["-a", "5", "-t", "3", "-r", "100", "-c", "4"], []), (["-a", "6", "-t", "4", "-r", "8402", "-c", "3"], []),
    (["-a", "7", "-t", "4", "-r", "10"], ["7", "8"]), (["-a", "8", "-t", "4", "-r", "10"], ["9"]),
])
def test_mbpoll_log_holds_the_lines_frames(args: list[str], values: list[str], tmp_path: Path) -> None:
    out, line = _poll(args, values)
    assert len(line) == 2, out
    log = tmp_path / "poll.log"
    log.write_text(out, encoding="utf-8")
    status, decoded, err = run_cli(["-n", "--json", str(log)])
    items = [json.loads(text) for text in decoded.splitlines()]
    assert (status, err) == (0, "")
    assert [bytes.fromhex(item["raw"]) for item in items] == line
    assert [(item["kind"], item["crc_ok"], item.get("request_frame")) for item in items] == [
        ("request", True, None), ("response", True, 1)]
