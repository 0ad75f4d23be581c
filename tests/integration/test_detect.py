"""--detect: scoring settings on a line modelled bit by bit (tests/support/uart_sim.py), and on real ttys.

What these prove: the scoring and ranking pick 38400 8E1 out of the 15 settings when wrong settings
deliver what the UART model says they would; the error marking path works with the Linux tty layer
(a pseudo-terminal); and the CLI path reconfigures a pyserial port, listens and prints the command
line. They cannot prove that a given USB adapter mis-samples exactly like the model.
"""
from __future__ import annotations

import argparse
import io
import os
import subprocess
import sys
import threading
import time
import types

import pytest
import serial

from dissector.protocol.crc import with_crc
from dissector.app.detect import BAUDS, Heard, SerialListener, Setting, detect, rank, score, unmark
from dissector.app.live import run_live
from dissector.render.summary import summary_line
from live_bus import ROOT, open_pty
from uart_sim import SimListener, SimSerial, TtyFeeder, Wire, receive, traffic

FRAMES = traffic(40, seed=2)
WIRE = Wire(38400, "E", FRAMES)
ALL_BYTES = b"".join(frame for frame, _ in FRAMES)


def test_uart_model_reads_its_own_setting_exactly() -> None:
    data, errors, _ = receive(WIRE, 38400, "E", 0.0, WIRE.duration)
    assert data == ALL_BYTES and errors == set()


def test_uart_model_wrong_parity_same_baud() -> None:
    # 8N1 takes the parity bit for the stop bit: same data, a framing error where it is 0.
    data, errors, _ = receive(WIRE, 38400, "N", 0.0, WIRE.duration)
    assert data == ALL_BYTES
    assert errors == {i for i, byte in enumerate(ALL_BYTES) if bin(byte).count("1") % 2 == 0}
    # 8O1: every parity bit is wrong.
    data, errors, _ = receive(WIRE, 38400, "O", 0.0, WIRE.duration)
    assert data == ALL_BYTES and errors == set(range(len(ALL_BYTES)))


def test_detect_finds_38400_8E1() -> None:
    scores = detect(SimListener(WIRE), seconds=10.0)
    assert len(scores) == 15
    best = scores[0]
    assert (best.baud, best.parity) == (38400, "E")
    assert (best.frames, best.frame_bytes, best.errors) == (80, len(ALL_BYTES), 0)
    by_setting = {(s.baud, s.parity): s for s in scores}
    assert by_setting[38400, "N"].frame_bytes < best.frame_bytes
    assert by_setting[38400, "N"].flagged_frames + by_setting[38400, "N"].frames == 80
    assert by_setting[38400, "O"].frames == 0
    for baud in BAUDS:
        if baud != 38400:
            for parity in "ENO":
                assert by_setting[baud, parity].frames == 0, (baud, parity)
    assert best.describe() == (
        f"38400 8E1: 80 CRC-valid frames ({len(ALL_BYTES)} bytes), {len(ALL_BYTES)} bytes heard, "
        "0 bytes flagged"
    )


def test_ties_without_error_marks_prefer_even_parity() -> None:
    frame = bytes.fromhex("0103006b00037417")
    scores = rank([score(Setting(38400, parity), Heard(frame)) for parity in "NOE"])
    assert [s.parity for s in scores] == ["E", "N", "O"]
    assert scores[0].describe() == (
        "38400 8E1: 1 CRC-valid frames (8 bytes), 8 bytes heard, errors not reported by this port"
    )


def test_unmark() -> None:
    assert unmark(b"\x01\xff\xff\x02\xff\x00\x41\xff\x00\x00\x03") == (
        b"\x01\xff\x02\x41\x00\x03",
        frozenset({3, 4}),
    )
    assert unmark(b"\x05\xff") == (b"\x05", frozenset())


def test_serial_listener_marks_errors_through_the_tty_layer() -> None:
    """On a pty the kernel applies PARMRK to the input: a data byte FF arrives doubled."""
    master, slave, path = open_pty()
    port = serial.serial_for_url(path, baudrate=9600, parity=serial.PARITY_NONE, timeout=0.01)
    # "FF 00 01" would read as an error mark if the kernel did not double the data FF.
    frame = with_crc(bytes.fromhex("0103040 0ff0001".replace(" ", "")))
    try:
        listener = SerialListener(port)

        def later() -> None:
            time.sleep(0.05)
            os.write(master, frame)

        threading.Thread(target=later).start()
        heard = listener.listen(Setting(115200, "N"), 0.2)
    finally:
        port.close()
        os.close(master)
        os.close(slave)
    assert heard == Heard(frame, frozenset(), marked=True)
    assert score(Setting(115200, "N"), heard).frames == 1


@pytest.fixture
def uartsim() -> types.ModuleType:
    """Registers uartsim:// with pyserial's URL handlers, the way a plug-in protocol is added."""
    package = types.ModuleType("vw3sim")
    module = types.ModuleType("vw3sim.protocol_uartsim")
    module.Serial = SimSerial  # type: ignore[attr-defined]
    sys.modules["vw3sim"], sys.modules["vw3sim.protocol_uartsim"] = package, module
    serial.protocol_handler_packages.append("vw3sim")
    yield module
    serial.protocol_handler_packages.remove("vw3sim")
    del sys.modules["vw3sim"], sys.modules["vw3sim.protocol_uartsim"]


def detect_args(port: str, seconds: float, mode: str | None = None) -> argparse.Namespace:
    return argparse.Namespace(
        live=port, baud=19200, parity="E", stopbits=1, bytesize=8, raw=None, duration=None,
        count=None, detect=seconds, write=None, json=False, timeout=1.0, mode=mode,
    )


# Without --mode, RTU's 8-bit settings and ASCII's 7-bit ones are tried; the RTU report is the same.
@pytest.mark.parametrize("mode, count", [(None, 30), ("rtu", 15)])
def test_cli_detect_on_a_simulated_port(uartsim: types.ModuleType, mode: str | None, count: int) -> None:
    SimSerial.WIRE = Wire(38400, "E", traffic(40, seed=6))
    out, err = io.StringIO(), io.StringIO()
    status = run_live(detect_args("uartsim://bus", 0.25, mode), out, err, False, summary_line, None)
    assert status == 0, err.getvalue()
    assert out.getvalue() == "vw3-decode --live uartsim://bus --baud 38400 --parity E\n"
    lines = err.getvalue().splitlines()
    assert lines[0] == f"vw3-decode: listening on uartsim://bus for 0.25 s at each of {count} settings"
    assert lines[1].startswith("  38400 8E1: ")
    assert len(lines) == count + 2
    # Without error marks the three parities of the right baud rate hear alike; the report says so.
    assert lines[-1] == (
        "vw3-decode: 38400 8N1, 38400 8O1 heard frames as well as 38400 8E1 (this port does not "
        "report parity errors): E was chosen as the Modbus default"
    )


@pytest.mark.parametrize("mode, looked_for", [
    (None, "CRC-valid RTU frame or Modbus ASCII frame with a good LRC"),
    ("rtu", "CRC-valid frame"),
    ("ascii", "Modbus ASCII frame with a good LRC"),
])
def test_cli_detect_hears_nothing(mode: str | None, looked_for: str) -> None:
    out, err = io.StringIO(), io.StringIO()
    status = run_live(detect_args("loop://", 0.02, mode), out, err, False, summary_line, None)
    assert status == 1
    assert out.getvalue() == ""
    assert err.getvalue().splitlines()[-1] == (
        f"vw3-decode: no {looked_for} heard at any setting (is there traffic? are A and B swapped?)"
    )


@pytest.mark.parametrize("mode", [None, "rtu"])
def test_cli_detect_on_a_pty(mode: str | None) -> None:
    master, slave, path = open_pty()
    feeder = TtyFeeder(master, Wire(38400, "E", traffic(40, seed=8)))
    feeder.start()
    try:
        process = subprocess.run(
            [sys.executable, "-m", "dissector", "--live", path, "--detect", "0.3",
             *(["--mode", mode] if mode else [])],
            cwd=ROOT, capture_output=True, text=True, timeout=60,
        )
    finally:
        feeder.stop.set()
        feeder.join(2)
        os.close(master)
        os.close(slave)
    assert process.returncode == 0, process.stderr
    assert process.stdout == f"vw3-decode --live {path} --baud 38400 --parity E\n"
    lines = process.stderr.splitlines()
    assert lines[1].startswith("  38400 8E1: ") and "0 bytes flagged" in lines[1]
    # A pty marks no errors at any parity: 8N1 and 8O1 are as likely, and the report says so.
    assert lines[-1] == (
        "vw3-decode: 38400 8N1, 38400 8O1 heard frames as well as 38400 8E1 (no more parity or framing "
        "errors were flagged there): E was chosen as the Modbus default"
    )
    # Every setting is reported: the baud rate changes at each, which a pty accepts with any parity.
    tried = [f"{baud} 8{parity}1" for baud in BAUDS for parity in "ENO"]
    if mode is None:
        tried += [f"{baud} 7{format}" for baud in BAUDS for format in ("E1", "N2", "O1")]
    assert lines[0] == f"vw3-decode: listening on {path} for 0.3 s at each of {len(tried)} settings"
    assert sorted(line.split(":")[0].strip() for line in lines[1:-1]) == sorted(tried)
    assert all("CRC-valid frames" in line for line in lines[1:-1] if " 8" in line.split(":")[0])
    assert all(": 0 ASCII frames with a good LRC (0 bytes), " in line
               for line in lines[1:-1] if " 7" in line.split(":")[0])
