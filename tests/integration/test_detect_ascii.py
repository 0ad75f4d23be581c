"""--detect on Modbus ASCII buses: framing, baud rate, parity and data bits; --mode and --bytesize.

Modbus ASCII is sent with 7 data bits (7E1 its default, 7O1, 7N2), or 8 on some devices; RTU with 8.
What these prove, with the bit-level UART model (tests/support/uart_sim.py): ASCII is scored at its
7-bit settings and wins over every RTU setting; an 8-bit listen of a 7-bit line hears the parity bit
as bit 7, which the report names when ASCII was not tried there; --bytesize and --mode narrow what is
tried. On ptys (which carry bytes at any setting but tell the feeder the baud rate): the exact report
and command line of `vw3-decode --live --detect`, exit statuses, and the extcap capturing ASCII.
The ASCII frames are built here from the spec (MODBUS over Serial Line V1.02, 2.5.2: ':', hex pairs,
LRC = two's complement of the byte sum, CR LF), not by the framer under test.
"""
from __future__ import annotations

import os
import subprocess
import sys

import pytest

from dissector.app.detect import BAUDS, Score, Setting, command_line, detect, framings, nothing_found
from dissector.app.extcap_capture import detected
from dissector.app.live import StopFlag
from dissector.errors import LiveError
from dissector.sources.serial_port import PortSettings
from extcap_harness import AS_DATA
from live_bus import ROOT, open_pty
from lua_harness import ensure_tool
from uart_sim import SimListener, TtyFeeder, Wire, ascii_traffic, traffic

ASCII_FRAMES = ascii_traffic(20, seed=3)
ASCII_BYTES = sum(len(frame) for frame, _ in ASCII_FRAMES)


def by_setting(scores: list[Score]) -> dict[tuple[str, str], Score]:
    return {(str(s.where), s.mode): s for s in scores}


def test_ascii_frames_follow_the_spec() -> None:
    # The first poll of traffic(20, seed=3), FC3 to slave 1, as the spec's 2.5.2 spells ASCII frames.
    frame, _ = ASCII_FRAMES[0]
    assert frame[:1] == b":" and frame[-2:] == b"\r\n"
    binary = bytes.fromhex(frame[1:-2].decode())
    assert binary[:2] == b"\x01\x03" and sum(binary) % 256 == 0


def test_auto_finds_ascii_7e1() -> None:
    wire = Wire(19200, "E", ASCII_FRAMES, size=7)
    scores = detect(SimListener(wire), 10.0, tried=framings(None, None))
    assert len(scores) == 30
    best = scores[0]
    assert (best.where, best.mode) == (Setting(19200, "E", 7, 1), "ascii")
    assert best.describe() == (
        f"19200 7E1: 40 ASCII frames with a good LRC ({ASCII_BYTES} bytes), {ASCII_BYTES} bytes heard, "
        "0 bytes flagged"
    )
    assert command_line("/dev/ttyUSB0", best) == (
        "vw3-decode --live /dev/ttyUSB0 --mode ascii --baud 19200 --parity E"
    )
    found = by_setting(scores)
    # 7O1 flags every parity bit; 7N2 takes the parity bit for its stop bit (flagged where it is 0).
    assert (found["19200 7O1", "ascii"].frames, found["19200 7O1", "ascii"].flagged_frames) == (0, 40)
    assert (found["19200 7N2", "ascii"].frames, found["19200 7N2", "ascii"].flagged_frames) == (0, 40)
    # RTU's settings hear no CRC-valid frame in ASCII text; other baud rates hear nothing whole.
    assert [s for s in scores[1:] if s.frames] == []
    assert {s.mode for s in scores if s.where.bytesize == 8} == {"rtu"}


def test_auto_finds_ascii_7n2() -> None:
    wire = Wire(19200, "N", ASCII_FRAMES, size=7, stops=2)
    best = detect(SimListener(wire), 10.0, tried=framings(None, None))[0]
    assert (best.where, best.mode, best.frames) == (Setting(19200, "N", 7, 2), "ascii", 40)
    assert command_line("COM3", best) == (
        "vw3-decode --live COM3 --mode ascii --baud 19200 --parity N --stopbits 2"
    )


def test_ascii_with_8_data_bits_needs_bytesize_8() -> None:
    wire = Wire(19200, "N", ASCII_FRAMES)  # 8N1: ASCII text with bit 7 clear
    scores = detect(SimListener(wire), 10.0, tried=framings(None, None))
    assert scores[0].frame_bytes == 0
    assert nothing_found(scores) == (
        "no CRC-valid RTU frame or Modbus ASCII frame with a good LRC heard at any setting, but the bytes "
        "heard at 19200 8N1 hold Modbus ASCII frames with a good LRC (detect with --mode ascii --bytesize 8)"
    )
    best = detect(SimListener(wire), 10.0, tried=framings("ascii", 8))[0]
    assert (best.where, best.mode, best.frames) == (Setting(19200, "N", 8, 1), "ascii", 40)
    assert command_line("COM3", best) == "vw3-decode --live COM3 --mode ascii --baud 19200 --parity N --bytesize 8"
    # --bytesize 8 without --mode: RTU and ASCII scored on the bytes of the same 15 listens.
    scores = detect(SimListener(wire), 10.0, tried=framings(None, 8))
    assert len(scores) == 30 and {s.where.bytesize for s in scores} == {8}
    assert (scores[0].where, scores[0].mode, scores[0].frames) == (Setting(19200, "N", 8, 1), "ascii", 40)
    assert by_setting(scores)["19200 8N1", "rtu"].describe() == (
        f"19200 8N1: 0 CRC-valid frames (0 bytes), {ASCII_BYTES} bytes heard, 0 bytes flagged"
    )


@pytest.mark.parametrize("mode, bytesize, looked_for", [
    ("rtu", None, "CRC-valid frame"),
    ("ascii", 8, "Modbus ASCII frame with a good LRC"),
])
def test_a_7_bit_line_heard_at_8_bits_is_named(mode: str, bytesize: int | None, looked_for: str) -> None:
    """An 8N1 UART hears a 7E1 line's characters whole, the parity bit as bit 7: not the wiring."""
    wire = Wire(19200, "E", ASCII_FRAMES, size=7)
    scores = detect(SimListener(wire), 10.0, tried=framings(mode, bytesize))
    assert len(scores) == 15 and {s.where.bytesize for s in scores} == {8}
    assert scores[0].frame_bytes == 0
    assert nothing_found(scores) == (
        f"no {looked_for} heard at any setting, but the bytes heard at 19200 8N1 hold Modbus ASCII "
        "frames sent with 7 data bits (detect with --mode ascii)"
    )


def test_mode_ascii_on_an_rtu_line_blames_nothing_it_cannot_see() -> None:
    # 7-bit UARTs lose bit 7 of every RTU byte: no frame, and no RTU frame to name either.
    scores = detect(SimListener(Wire(19200, "E", traffic(20, seed=3))), 10.0, tried=framings("ascii", None))
    assert {(str(s.where)[-3:], s.mode) for s in scores} == {("7E1", "ascii"), ("7N2", "ascii"), ("7O1", "ascii")}
    assert nothing_found(scores) == (
        "no Modbus ASCII frame with a good LRC heard at any setting (is there traffic? are A and B swapped?)"
    )


def test_framings() -> None:
    assert framings(None, None) == (("rtu", 8), ("ascii", 7))
    assert framings(None, 8) == (("rtu", 8), ("ascii", 8))
    assert framings(None, 7) == (("ascii", 7),)
    assert framings("rtu", None) == framings("rtu", 8) == (("rtu", 8),)
    assert framings("ascii", None) == framings("ascii", 7) == (("ascii", 7),)
    assert framings("ascii", 8) == (("ascii", 8),)


def run_detect_cli(path: str, *options: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "dissector", "--live", path, *options, "--detect", "0.3"],
        cwd=ROOT, capture_output=True, text=True, timeout=120,
    )


@pytest.mark.parametrize("options, message", [
    (("--mode", "rtu", "--bytesize", "7"), "--bytesize 7: Modbus RTU is sent with 8 data bits"),
    (("--bytesize", "6"), "--bytesize 6: Modbus is sent with 8 data bits (RTU, or ASCII) or 7 (ASCII)"),
])
def test_cli_sizes_no_modbus_is_sent_with(options: tuple[str, ...], message: str) -> None:
    done = run_detect_cli("/dev/null", *options)
    assert (done.returncode, done.stdout, done.stderr) == (2, "", f"vw3-decode: --detect: {message}\n")


class PtyBus:
    """A pty whose feeder delivers `wire` as `receiver` hears it, at the sniffer's baud rate."""

    def __init__(self, wire: Wire, receiver: tuple[str, int]) -> None:
        self.master, self.slave, self.path = open_pty()
        self.feeder = TtyFeeder(self.master, wire, receiver)
        self.feeder.start()

    def close(self) -> None:
        self.feeder.stop.set()
        self.feeder.join(2)
        os.close(self.master)
        os.close(self.slave)


def ascii_bus(receiver: tuple[str, int] = ("E", 7)) -> PtyBus:
    return PtyBus(Wire(38400, "E", ascii_traffic(40, seed=8), size=7), receiver)


SEVEN_BIT = [f"{baud} 7{format}" for baud in BAUDS for format in ("E1", "N2", "O1")]
EIGHT_BIT = [f"{baud} 8{parity}1" for baud in BAUDS for parity in "ENO"]


@pytest.mark.parametrize("options, tried", [((), EIGHT_BIT + SEVEN_BIT), (("--mode", "ascii"), SEVEN_BIT)])
def test_cli_detects_ascii_on_a_pty(options: tuple[str, ...], tried: list[str]) -> None:
    bus = ascii_bus()
    try:
        done = run_detect_cli(bus.path, *options)
    finally:
        bus.close()
    assert done.returncode == 0, done.stderr
    assert done.stdout == f"vw3-decode --live {bus.path} --mode ascii --baud 38400 --parity E\n"
    lines = done.stderr.splitlines()
    assert lines[0] == f"vw3-decode: listening on {bus.path} for 0.3 s at each of {len(tried)} settings"
    assert lines[1].startswith("  38400 7E1: ") and " ASCII frames with a good LRC (" in lines[1]
    assert lines[1].endswith(" bytes heard, 0 bytes flagged") and not lines[1].startswith("  38400 7E1: 0 ")
    assert sorted(line.split(":")[0].strip() for line in lines[1:-1]) == sorted(tried)
    # A pty ignores parity and data bits: the ASCII settings of the right baud rate hear alike.
    assert lines[-1] == (
        "vw3-decode: 38400 7N2, 38400 7O1 heard frames as well as 38400 7E1 (no more parity or framing "
        "errors were flagged there): E was chosen as the Modbus default"
    )


@pytest.mark.parametrize("receiver, heard", [
    # What an 8N1 UART hears of a 7E1 line: each character whole, its parity bit as bit 7.
    (("N", 8), "Modbus ASCII frames sent with 7 data bits (detect with --mode ascii)"),
    # What a pty or a gateway delivers at any data size: the characters themselves.
    (("E", 7), "Modbus ASCII frames with a good LRC (detect with --mode ascii --bytesize 8)"),
])
def test_cli_mode_rtu_on_an_ascii_pty(receiver: tuple[str, int], heard: str) -> None:
    bus = ascii_bus(receiver)
    try:
        done = run_detect_cli(bus.path, "--mode", "rtu")
    finally:
        bus.close()
    assert (done.returncode, done.stdout) == (1, ""), done.stderr
    lines = done.stderr.splitlines()
    assert lines[0] == f"vw3-decode: listening on {bus.path} for 0.3 s at each of 15 settings"
    assert sorted(line.split(":")[0].strip() for line in lines[1:-1]) == sorted(EIGHT_BIT)
    assert all(": 0 CRC-valid frames (0 bytes), " in line for line in lines[1:-1])
    assert lines[-1] == (
        f"vw3-decode: no CRC-valid frame heard at any setting, but the bytes heard at 38400 8E1 hold {heard}"
    )


def test_extcap_detect_captures_ascii() -> None:
    """The extcap's --detect tries both framings (its dialog's framing is then ignored) and hands the
    capture the ASCII framing and 7 data bits."""
    bus = ascii_bus()
    try:
        with StopFlag() as stop:
            settings, mode = detected(PortSettings(bus.path, 19200, "E", 1, 8), 0.2, stop)
    finally:
        bus.close()
    assert (settings, mode) == (PortSettings(bus.path, 38400, "E", 1, 7), "ascii")


def test_extcap_detect_names_what_it_heard() -> None:
    bus = ascii_bus(("N", 8))
    try:
        with StopFlag() as stop, pytest.raises(LiveError) as raised:
            detected(PortSettings(bus.path, 19200, "E", 1, 8), 0.1, stop)
    finally:
        bus.close()
    # The feeder gives 8N1's view of the 7E1 line at every setting (a pty cannot tell data sizes
    # apart), so here the 7-bit listens find nothing either; the report names what the 8-bit ones
    # heard, and vw3-decode's options (the dialog's framing is ignored under --detect).
    assert str(raised.value) == (
        f"--detect on {bus.path}: no CRC-valid RTU frame or Modbus ASCII frame with a good LRC heard at any "
        f"setting, but the bytes heard at 38400 8E1 hold Modbus ASCII frames sent with 7 data bits "
        f"(vw3-decode --live {bus.path} --detect --mode ascii)"
    )


def test_extcap_detect_then_ascii_capture_through_tshark(tmp_path) -> None:
    """Through Wireshark's own path (tshark -i, the dialog's detect boolflag): the capture that follows
    --detect frames Modbus ASCII at the 7E1 setting found, one record per ':' .. CR LF frame."""
    ensure_tool("tshark", "tshark")
    env = dict(os.environ, WIRESHARK_CONFIG_DIR=str(tmp_path / "config"))
    env.pop("PYTHONPATH", None)
    done = subprocess.run([sys.executable, "-m", "dissector.app.extcap", "--install"], cwd=ROOT,
                          env=dict(env, PYTHONPATH=str(ROOT)), capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    bus = ascii_bus()
    prefix = "extcap.vw3_socket."
    try:
        done = subprocess.run(
            ["tshark", "-i", "vw3-socket", "-o", f"{prefix}port:{bus.path}", "-o", f"{prefix}detect:true",
             "-o", f"{prefix}detectseconds:0.1", "-c", "6", "-n", "-T", "fields",
             "-e", "frame.interface_description", "-e", "data", "-o", AS_DATA],
            env=env, capture_output=True, text=True, timeout=120,
        )
    finally:
        bus.close()
    assert done.returncode == 0, done.stderr
    fields = [line.split("\t") for line in done.stdout.splitlines()]
    assert len(fields) == 6
    assert {description for description, _ in fields} == {
        f"serial port {bus.path}, 38400 baud, 7 data bits, even parity, 1 stop bit (38400 7E1), found by --detect"
    }
    # The capture starts mid-traffic: the first record may be the end of a frame cut by the start.
    sent = {frame for frame, _ in ascii_traffic(40, seed=8)}
    records = [bytes.fromhex(data) for _, data in fields]
    assert all(record in sent for record in records[1:]), records
