"""A pcapng whose serial interface has an Ethernet (or any non-serial) interface beside it: the serial
interfaces are decoded, the others' packets skipped with one warning per interface saying how many records
and bytes it held (every byte of the input accounted for). Before, the whole file was refused (exit 2) at
the first Ethernet packet, though tshark decodes the serial interface. A file with no serial interface is
still refused in one line."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER = bytes.fromhex("0C0306000100020003A5E4")  # 8400=1, CHCF=SEP, COP=ALL
ETHERNET = b"\xff" * 6 + b"\x02" * 6 + b"\x08\x00" + b"E" * 40  # 54 bytes
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
READ = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
ANSWERED = ("12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3 [#1, 10.0 ms]  CRC ok")
NOT_READ = "interface 0: linktype 1 (Ethernet) carries no serial bytes"


def _block(kind: int, body: bytes) -> bytes:
    total = 12 + len(body)
    return struct.pack("<II", kind, total) + body + struct.pack("<I", total)


def _pcapng(linktypes: list[int], packets: list[tuple[int, int, bytes]]) -> bytes:
    """Interfaces (their link types) and packets (interface, microseconds, bytes)."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    for linktype in linktypes:
        out += _block(1, struct.pack("<HHI", linktype, 0, 0))
    for interface, micros, data in packets:
        stamp = 1_767_225_600_000_000 + micros
        out += _block(6, struct.pack("<IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data))
                      + data + b"\0" * (-len(data) % 4))
    return out


@BOTH
def test_serial_interface_beside_ethernet_is_decoded(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "serial_and_ethernet.pcapng"
    path.write_bytes(_pcapng([1, 147], [(0, 0, ETHERNET), (1, 1000, REQUEST), (0, 5000, ETHERNET),
                                        (1, 11_000, ANSWER)]))
    status, out, err = run_cli([str(path)])
    assert status == 0
    # (from the capture's first packet, the Ethernet one, as tshark's frame.time_relative)
    assert out.splitlines() == [f"     1     0.001000  {READ}", f"     2     0.011000  {ANSWERED}"]
    assert err.splitlines() == [f"vw3-decode: warning: {NOT_READ}: 2 records (108 bytes) skipped"]


@BOTH
def test_two_serial_buses_beside_ethernet_warn_once(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "two_serial_and_ethernet.pcapng"
    path.write_bytes(_pcapng([1, 147, 147], [(0, 0, ETHERNET), (1, 1000, REQUEST), (2, 2000, REQUEST),
                                            (1, 11_000, ANSWER), (2, 12_000, ANSWER)]))
    status, out, err = run_cli([str(path)])
    assert status == 0
    assert out.splitlines() == [
        f"==> {path}: interface 1 <==", f"     1     0.001000  {READ}", f"     2     0.011000  {ANSWERED}",
        f"==> {path}: interface 2 <==", f"     1     0.002000  {READ}", f"     2     0.012000  {ANSWERED}",
    ]
    assert err.splitlines() == [f"vw3-decode: warning: {NOT_READ}: 1 record (54 bytes) skipped"]


@BOTH
def test_no_serial_interface_is_refused(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "ethernet.pcapng"
    path.write_bytes(_pcapng([1], [(0, 0, ETHERNET)]))
    status, out, err = run_cli([str(path)])
    assert (status, out) == (2, "")
    # (an Ethernet capture is read for Modbus RTU over TCP/UDP on the ports given: test_rtu_over_tcp_sources.py)
    assert err.splitlines() == [
        f"vw3-decode: {path}: Ethernet (linktype 1): no TCP or UDP payload on the Modbus RTU ports (none given: "
        "--tcp-port and --udp-port, as the plugin's vw3.tcp_port and vw3.udp_port preferences, set them); "
        "its 1 packet: 1 fragmented IP never reassembled"]


def test_serial_interface_names_the_copy(tmp_path: Path) -> None:
    # The serial interface's if_name and speed (framing/linespeed.py reads the description) are the file's,
    # not the Ethernet interface's described before it.
    from dissector.sources.pcapng import first_interface

    path = tmp_path / "named.pcapng"
    named = b"".join(struct.pack("<HH", code, len(text)) + text + b"\0" * (-len(text) % 4)
                     for code, text in ((2, b"/dev/ttyUSB0"), (3, b"/dev/ttyUSB0 19200 8E1"))) + b"\0" * 4
    content = _pcapng([1], [])
    content += _block(1, struct.pack("<HHI", 147, 0, 0) + named)
    path.write_bytes(content + _pcapng([], [(1, 0, REQUEST)])[28:])  # (after its section header)
    interface = first_interface(str(path))
    assert interface is not None and (interface.linktype, interface.name, interface.description) == (
        147, "/dev/ttyUSB0", "/dev/ttyUSB0 19200 8E1")
    status, _out, err = run_cli([str(path), "-w", str(tmp_path / "copy.pcapng")])
    assert (status, err) == (0, "")
    copied = first_interface(str(tmp_path / "copy.pcapng"))
    assert copied is not None and (copied.linktype, copied.name) == (147, "/dev/ttyUSB0")


def test_the_ports_given_say_they_were_not_read_beside_a_serial_interface(tmp_path: Path) -> None:
    # --tcp-port given for a pcapng of a serial interface and an Ethernet one whose packet carries no TCP or UDP
    # payload on it: the Ethernet interface's packets are passed over, said (its connections on the port would be
    # buses beside the serial one: tests/integration/test_rtu_over_tcp_beside_serial.py); from standard input,
    # read once, they are not read.
    path = tmp_path / "serial_and_ethernet.pcapng"
    path.write_bytes(_pcapng([147, 1], [(0, 0, REQUEST), (1, 500, ETHERNET), (0, 10_000, ANSWER)]))
    said = "vw3-decode: warning: interface 1: linktype 1 (Ethernet) carries no serial bytes: 1 record (54 bytes) skipped; "
    assert run_cli(["--tcp-port", "4001", str(path)]) == (0, f"     1     0.000000  {READ}\n     2     0.010000  {ANSWERED}\n",
        f"{said}no TCP or UDP payload on its TCP port 4001\n")
    assert run_cli(["--tcp-port", "4001", "-"], stdin=path.read_bytes())[2] == (
        f"{said}its TCP port 4001 not read in one stream beside a serial interface (vw3-decode FILE reads its "
        "connections as buses of their own)\n")
