"""--live and Modbus ASCII without --mode (hunt 55: a pymodbus ASCII master and slave at 7E1 tapped through
a pty showed 15 noise runs, "0 frames ... 556 noise bytes" and no hint, where a file of the same bytes is
detected as ASCII):
- a port set to 7 data bits (--bytesize 7) frames Modbus ASCII: RTU's binary needs 8 (live_options.live_mode),
  and the listening line says so;
- at 8 data bits the capture frames RTU, and when the first bytes heard hold Modbus ASCII frames (as heard, or
  a 7-bit line heard by an 8-bit UART) one stderr line names the options that decode them (detect.py
  AsciiHeard); --mode rtu, or an RTU bus, gives none.
On a pseudo-terminal (tests/support/live_bus.py), which takes any data bits and delivers the bytes written."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from dissector.protocol.crc import lrc, with_crc
from live_bus import ROOT, open_pty, run_live_on_pty

pytestmark = pytest.mark.integration


def line(hex_text: str) -> bytes:
    body = bytes.fromhex(hex_text)
    return b":" + (body + bytes([lrc(body)])).hex().upper().encode() + b"\r\n"


READ, ANSWER = line("020300000001"), line("0203020007")
WRITES = [(READ, 0.05), (ANSWER, 0.05)] * 3
RTU_READ, RTU_ANSWER = with_crc(bytes.fromhex("020300000001")), with_crc(bytes.fromhex("0203020007"))
RTU_WRITES = [(RTU_READ, 0.05), (RTU_ANSWER, 0.05)] * 3
HINT = "vw3-decode: the bytes heard hold {}, framed here as RTU: capture with {}\n"
AS_HEARD = HINT.format("Modbus ASCII frames with a good LRC", "--mode ascii --bytesize 8")
SEVEN_BITS = HINT.format("Modbus ASCII frames sent with 7 data bits", "--mode ascii")


def seven_e_one(data: bytes) -> bytes:
    """`data` sent at 7E1 as an 8-bit UART delivers it: the even parity bit as bit 7."""
    return bytes(byte | 0x80 if bin(byte).count("1") % 2 else byte for byte in data)


def test_seven_data_bits_frame_ascii() -> None:
    pty, device, path = open_pty()
    process = subprocess.Popen(
        [sys.executable, "-m", "dissector", "--live", path, "--baud", "115200", "--bytesize", "7", "-n",
         "--json"],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )
    try:
        assert process.stderr is not None
        assert process.stderr.readline().decode() == (
            f"vw3-decode: listening on {path} at 115200 7E1 (Modbus ASCII: 7 data bits carry no RTU)\n")
        for data, pause in WRITES:
            os.write(pty, data)
            time.sleep(pause)
        time.sleep(0.3)
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=20)
    finally:
        if process.poll() is None:
            process.kill()
        os.close(pty)
        os.close(device)
    assert process.returncode == 0, err
    items = [json.loads(text) for text in out.decode().splitlines()]
    assert [(item["kind"], bytes.fromhex(item["raw"]), item["warnings"]) for item in items] == [
        (kind, raw, []) for kind, raw in [("request", READ), ("response", ANSWER)] * 3]
    assert err.decode().startswith(
        "vw3-decode: 6 frames (3 requests, 3 responses, 0 exceptions) from 1 slave, ")


@pytest.mark.parametrize(("writes", "options", "hint"), [
    (WRITES, [], AS_HEARD),
    ([(seven_e_one(data), pause) for data, pause in WRITES], [], SEVEN_BITS),
    (WRITES, ["--mode", "rtu"], ""),
    (RTU_WRITES, [], ""),
], ids=["ascii at 8 bits", "7E1 heard at 8 bits", "--mode rtu", "an RTU bus"])
def test_a_hint_at_eight_data_bits(writes: list[tuple[bytes, float]], options: list[str], hint: str) -> None:
    out, err, status = run_live_on_pty(writes, ["-n", *options])
    assert status == 0, err
    text = err.decode()
    assert text.startswith(hint) and text.count("the bytes heard hold") == (1 if hint else 0), text
