"""A master's response timeout starts once its request is sent (Serial Line Guide 2.4.1): at 1200 baud
libmodbus's 209-byte FC16 request takes 1.92 s on the wire, and the slave's answer 5 ms after its last byte
answers it. vw3-decode measured the timeout from the request's first byte: the request was `[no response]`,
its answer `[no request] [warning: response 1920.8 ms after request #1, later than the 1000 ms timeout: not
its answer]` and --stats counted a reply missing; live, the request was given up while its own bytes were
still coming; the plugin alike (`vw3.unanswered` on the request, the same warning on its answer).

The frames are libmodbus 3.1.6's (Debian's libmodbus-dev): its modbus_write_registers(ctx, 0, 100, 0x100+i)
and modbus_write_and_read_registers(ctx, 0, 90, ..., 0, 2) as a libmodbus RTU slave answered them on a
pseudo-terminal pair (peer68, 2026-12-07), then modbus_read_input_registers(ctx, 7, 3). Here they are laid
out as a USB adapter delivers a 1200-baud line: 16-byte reads timed by their first byte (11 bits a
character), answers 5 ms after their request's last byte, requests 60 ms after the answer before.
Needs /work/patches/peer68-timeout-after-request-sent.diff (then python3 -m dissector.codegen)."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from live_bus import ROOT, open_pty
from lua_harness import lua_errors, run_tshark, write_pcap

BAUD = 1200
CHAR = 11 / BAUD
READ = 16  # bytes a record (a USB adapter's read)
T0 = 1_765_000_000.0
FRAMES = [  # (bytes, the master's: a request)
    (rtu("01 10 0000 0064 C8" + "".join(f"{0x100 + i:04X}" for i in range(100))), True),
    (rtu("01 10 0000 0064"), False),
    (rtu("01 17 0000 0002 0000 005A B4" + "".join(f"{0x100 + i:04X}" for i in range(90))), True),
    (rtu("01 17 04 0100 0101"), False),
    (rtu("01 04 0007 0003"), True),
    (rtu("01 04 06 1007 1008 1009"), False),
]
SUMMARY = [
    "     1     0.000000   1 request   Write Multiple Registers 0..99 (100): 0=256 1=257 2=258 3=259 4=260 "
    "5=261 … (+94)  CRC ok",
    "     2     1.920833   1 response  Write Multiple Registers 0..99 (100) written [#1, 1920.8 ms]  CRC ok",
    "     3     2.054167   1 request   Read/Write Multiple Registers read 0..1 (2), write 0=256 1=257 2=258 3=259 "
    "4=260 5=261 … (+84)  CRC ok",
    "     4     3.828333   1 response  Read/Write Multiple Registers 0..1 (2): 0=256 1=257 [#3, 1774.2 ms]  CRC ok",
    "     5     3.970833   1 request   Read Input Registers 7..9 (3)  CRC ok",
    "     6     4.049167   1 response  Read Input Registers 7..9 (3): 7=4103 8=4104 9=4105 [#5, 78.3 ms]  CRC ok",
]


def layout() -> list[tuple[bytes, float]]:
    """The frames as records of READ bytes, each at its first byte's time on a BAUD line."""
    records, at = [], T0
    for index, (frame, request) in enumerate(FRAMES):
        at += (0.060 if index else 0.0) if request else 0.005
        for offset in range(0, len(frame), READ):
            records.append((frame[offset : offset + READ], at + offset * CHAR))
        at += len(frame) * CHAR
    return records


@pytest.mark.parametrize("pure", [False, True])
def test_a_long_request_on_a_slow_line_is_answered(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                   pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = write_pcap(tmp_path / "slow.pcap", layout())
    status, out, err = run_cli(["--baud", str(BAUD), str(capture)])
    assert (status, err) == (0, "")
    assert out.splitlines() == SUMMARY
    status, out, err = run_cli(["--baud", str(BAUD), "--stats", str(capture)])
    assert status == 0, err
    traffic = out.splitlines()[out.splitlines().index("Traffic per slave and function") + 3:][:3]
    assert [line.split()[-4:] for line in traffic] == [["1", "1", "0", "0"]] * 3  # req, resp, no reply, bad CRC


def test_the_plugin_pairs_them_alike(tmp_path: Path) -> None:
    # (each frame is shown in the record completing it: records 14, 15, 28, 29, 30, 31)
    capture = write_pcap(tmp_path / "slow.pcap", layout())
    result = run_tshark(capture, "-o", f"vw3.baud:{BAUD}", "-T", "fields", "-E", "separator=;",
                        "-e", "frame.number", "-e", "vw3.kind", "-e", "vw3.request_frame", "-e", "vw3.unanswered",
                        "-Y", "vw3.kind")
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    assert result.stdout.splitlines() == ["14;1;;", "15;2;14;", "28;1;;", "29;2;28;", "30;1;;", "31;2;30;"]


def test_live_waits_for_the_request_to_be_sent() -> None:
    """The first transaction on a pseudo-terminal at the line's pace: the capture does not give the request
    up while its bytes are still coming, nor its answer after them."""
    line, device, path = open_pty()
    process = subprocess.Popen([sys.executable, "-m", "dissector", "--live", path, "--baud", str(BAUD), "-n"],
                               cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert process.stderr is not None and "listening on" in process.stderr.readline()
        for frame, _request in FRAMES[:2]:
            for offset in range(0, len(frame), READ):
                os.write(line, frame[offset : offset + READ])
                time.sleep(min(READ, len(frame) - offset) * CHAR)
            time.sleep(0.005)
        time.sleep(0.5)
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
        os.close(line)
        os.close(device)
    assert process.returncode == 0, err
    lines = out.splitlines()
    assert [text.split(None, 2)[2] for text in lines] == [
        "1 request   Write Multiple Registers 0..99 (100): 0=256 1=257 2=258 3=259 4=260 5=261 … (+94)  CRC ok",
        f"1 response  Write Multiple Registers 0..99 (100) written [#1, {lines[1].split('[#1, ')[1]}",
    ]
    assert err.startswith("vw3-decode: 2 frames (1 request, 1 response, 0 exceptions) from 1 slave, 0 CRC errors, "
                          "0 unanswered")
