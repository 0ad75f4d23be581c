"""A packet dump with each packet's details before its bytes, as `tshark -V -x` and Wireshark's File › Export
Packet Dissections › As Plain Text (details and bytes) write it, is told a packet dump (sources/packetdump.py)
as `--format tshark-x` reads it: its first dump line comes after a packet's whole tree (here 24 lines, 1 KB).
Before, the format was judged on the first 512 bytes or 4 lines, the tree's alone: "the input is text, but
neither a hex dump nor Modbus ASCII: decoded as raw bytes", one 2247-byte noise item."""
from __future__ import annotations

from pathlib import Path

from helpers import run_cli

# tshark -V -x -o 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""' of a read of 8400..8402 and its answer
DETAILS_AND_BYTES = "".join([
    'Frame 1: 8 bytes on wire (64 bits), 8 bytes captured (64 bits)\n'
    '    Encapsulation type: USER 0 (45)\n'
    '    Arrival Time: Nov 14, 2023 22:13:20.020000000 UTC\n'
    '    [Time shift for this packet: 0.000000000 seconds]\n'
    '    Epoch Time: 1700000000.020000000 seconds\n'
    '    [Time delta from previous captured frame: 0.000000000 seconds]\n'
    '    [Time delta from previous displayed frame: 0.000000000 seconds]\n'
    '    [Time since reference or first frame: 0.000000000 seconds]\n'
    '    Frame Number: 1\n'
    '    Frame Length: 8 bytes (64 bits)\n'
    '    Capture Length: 8 bytes (64 bits)\n'
    '    [Frame is marked: False]\n'
    '    [Frame is ignored: False]\n'
    '    [Protocols in frame: user_dlt:mbrtu:modbus]\n'
    'DLT: 147, Payload: mbrtu (Modbus RTU)\n'
    'Modbus RTU\n'
    '    Unit ID: 12\n'
    '    CRC-16: 0x0eef [unverified]\n'
    '    [CRC-16 Status: Unverified]\n'
    'Modbus\n'
    '    .000 0011 = Function Code: Read Holding Registers (3)\n'
    '    Reference Number: 8400\n'
    '    Word Count: 3\n'
    '\n'
    '0000  0c 03 20 d0 00 03 0e ef                           .. .....\n'
    '\n'
    'Frame 2: 11 bytes on wire (88 bits), 11 bytes captured (88 bits)\n'
    '    Encapsulation type: USER 0 (45)\n'
    '    Arrival Time: Nov 14, 2023 22:13:20.040000000 UTC\n'
    '    [Time shift for this packet: 0.000000000 seconds]\n'
    '    Epoch Time: 1700000000.040000000 seconds\n'
    '    [Time delta from previous captured frame: 0.020000000 seconds]\n'
    '    [Time delta from previous displayed frame: 0.020000000 seconds]\n'
    '    [Time since reference or first frame: 0.020000000 seconds]\n'
    '    Frame Number: 2\n'
    '    Frame Length: 11 bytes (88 bits)\n'
    '    Capture Length: 11 bytes (88 bits)\n'
    '    [Frame is marked: False]\n'
    '    [Frame is ignored: False]\n'
    '    [Protocols in frame: user_dlt:mbrtu:modbus]\n'
    'DLT: 147, Payload: mbrtu (Modbus RTU)\n'
    'Modbus RTU\n'
    '    Unit ID: 12\n'
    '    CRC-16: 0xa5e4 [unverified]\n'
    '    [CRC-16 Status: Unverified]\n'
    'Modbus\n'
    '    .000 0011 = Function Code: Read Holding Registers (3)\n'
    '    [Request Frame: 1]\n'
    '    [Time from request: 0.020000000 seconds]\n'
    '    Byte Count: 6\n'
    '    Register 8400 (UINT16): 1\n'
    '        Register Number: 8400\n'
    '        Register Value (UINT16): 1\n'
    '    Register 8401 (UINT16): 2\n'
    '        Register Number: 8401\n'
    '        Register Value (UINT16): 2\n'
    '    Register 8402 (UINT16): 3\n'
    '        Register Number: 8402\n'
    '        Register Value (UINT16): 3\n'
    '\n'
    '0000  0c 03 06 00 01 00 02 00 03 a5 e4                  ...........\n'
    '\n'
])
# (timed by each packet's Epoch Time line, as the pcap it was dissected from: test_packet_dump_times)
LINES = ["     1     0.000000  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
         "     2     0.020000  12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3 [#1, 20.0 ms]"
         "  CRC ok"]


def test_details_then_bytes_is_a_packet_dump(tmp_path: Path) -> None:
    path = tmp_path / "export.txt"
    path.write_text(DETAILS_AND_BYTES)
    assert run_cli([str(path)]) == (0, "\n".join(LINES) + "\n", "")
    assert run_cli(["--format", "tshark-x", str(path)]) == (0, "\n".join(LINES) + "\n", "")


def test_from_standard_input_too(tmp_path: Path) -> None:
    # (a file given as standard input, `< export.txt`, its bytes all there; read as it comes: frames before
    # profile auto knows the slave's device are provisional, README)
    provisional = [line.replace("  CRC ok", " [provisional]  CRC ok") for line in LINES]
    assert run_cli(["-"], stdin=DETAILS_AND_BYTES.encode()) == (0, "\n".join(provisional) + "\n", "")


def test_a_pipe_is_judged_on_what_came(tmp_path: Path) -> None:
    # (a live feed is not held back for 64 KiB: from a pipe, the first lines judge, as before)
    import os
    import subprocess
    import sys

    root = Path(__file__).resolve().parents[2]
    env = {**os.environ, "PYTHONPATH": str(root)}
    run = subprocess.run([sys.executable, "-m", "dissector", "-"], input=DETAILS_AND_BYTES.encode(), cwd=root,
                         env=env, capture_output=True, timeout=120)
    assert run.returncode == 0
    assert run.stderr.decode().splitlines()[0] == ("vw3-decode: warning: standard input: the input is text, but "
                                                   "neither a hex dump nor Modbus ASCII: decoded as raw bytes")


def test_text_in_no_format_is_still_its_bytes(tmp_path: Path) -> None:
    # (read on up to 64 KiB for a dump line: none comes, and the text is its bytes, as before)
    path = tmp_path / "tree.txt"
    path.write_text("".join(line for line in DETAILS_AND_BYTES.splitlines(keepends=True) if not line.startswith("00")))
    status, out, err = run_cli([str(path)])
    assert status == 0 and out.startswith("     1            -   - noise     ")
    assert err.splitlines()[0] == (f"vw3-decode: warning: {path}: the input is text, but neither a hex dump nor "
                                   "Modbus ASCII: decoded as raw bytes")
