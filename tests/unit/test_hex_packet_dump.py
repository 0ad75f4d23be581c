"""--hex takes a packet's bytes pasted as tshark -x and Wireshark's Copy > Bytes as Hex + ASCII Dump write
them (offset, bytes, the character column), as standard input reads them (sources/packetdump.py): the
bytes of each packet, one frame each. Before (hunt67b), the character column was refused
(`--hex: '........' is not hex`), so a Wireshark user could not paste what Wireshark copies.
The dump text is tshark 4.0.17's own -x output for a pcap of these frames (libmodbus 3.1.6 answering
FC23, FC22 on a pseudo-terminal), checked against it where tshark is installed."""
from __future__ import annotations

import subprocess
from pathlib import Path

from dissector.render.pcapwriter import PcapWriter
from helpers import run_cli
from lua_harness import ensure_tool

FC23 = "01 17 00 03 00 04 00 04 00 02 04 11 11 22 22 ef 28"
FC23_ANSWER = "01 17 08 00 09 11 11 22 22 00 12 99 aa"
# tshark -x of the two records (a frame of 17 bytes takes two lines), and one of Wireshark's copy (3 spaces).
DUMP = (
    '0000  01 17 00 03 00 04 00 04 00 02 04 11 11 22 22 ef   ............."".\n'
    "0010  28                                                (\n"
    "\n"
    '0000  01 17 08 00 09 11 11 22 22 00 12 99 aa            .......""....\n'
    "\n"
)
COPIED = "0000   01 16 00 05 00 f2 00 25 5a 2e                     .......%Z.\n"
LINES = [
    "     1            -   1 request   Read/Write Multiple Registers read 3..6 (4), write 4=4369 5=8738  CRC ok",
    "     2            -   1 response  Read/Write Multiple Registers 3..6 (4): 3=9 4=4369 5=8738 6=18 [#1]  CRC ok",
]


def test_the_dump_is_tsharks(tmp_path: Path) -> None:
    tshark = ensure_tool("tshark", "tshark")
    path = tmp_path / "fc23.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for number, frame in enumerate((FC23, FC23_ANSWER)):
            writer.write(bytes.fromhex(frame), 1767225600.0 + number / 100)
    done = subprocess.run([tshark, "-n", "-x", "-r", str(path)], capture_output=True, text=True, timeout=120)
    assert done.stdout == DUMP


def test_a_pasted_dump_is_its_packets() -> None:
    assert run_cli(["--hex", DUMP]) == (0, "\n".join(LINES) + "\n", "")
    assert run_cli(["--hex", DUMP]) == run_cli(["--hex", FC23, "--hex", FC23_ANSWER])
    # one packet an argument, as copied one at a time
    first, second = DUMP.split("\n\n")[:2]
    assert run_cli(["--hex", first, "--hex", second]) == (0, "\n".join(LINES) + "\n", "")


def test_wiresharks_copy_and_a_mended_crc() -> None:
    assert run_cli(["--hex", COPIED]) == (0, (
        "     1            -   1 request   Mask Write Register 5 AND 0x00F2 OR 0x0025 "
        "[the capture ends before any response: not known whether it was answered]  CRC ok\n"), "")
    # a byte mistyped in the pasted dump: the CRC spelled out as for any typed frame
    typo = COPIED.replace("00 25", "00 26").replace("%Z", "&Z")
    status, out, err = run_cli(["--hex", typo])
    assert (status, err) == (0, "")
    assert out == run_cli(["--hex", "01 16 00 05 00 f2 00 26 5a 2e"])[1] == (
        "     1            -   1 request   Mask Write Register 5 AND 0x00F2 OR 0x0026 [the capture ends before any "
        "response: not known whether it was answered] [warning: CRC bad: received 0x2E5A, expected 0x2F1A (on the "
        "wire 5A 2E typed, 1A 2F expected)]  CRC BAD (received 0x2E5A, expected 0x2F1A)\n")


def test_a_dump_with_a_line_missing_is_refused() -> None:
    gap = DUMP.replace("0010  28", "0020  28")
    assert run_cli(["--hex", gap]) == (2, "", (
        "vw3-decode: --hex line 2: offset 0x0020 where 0x0010 was expected (bytes missing or repeated)\n"))


def test_lines_of_a_modbus_poll_traffic_log() -> None:
    """Modbus Poll's Communication Traffic lines (sources/traffic.py's formats), pasted: the counter and the
    time are no bytes. Before: `--hex: 'Tx:000001-01' is not hex`."""
    request, answer = "01 03 00 00 00 01 84 0A", "01 03 02 00 07 F9 86"
    typed = run_cli(["--hex", request, "--hex", answer])
    assert typed == (0, (
        "     1            -   1 request   Read Holding Registers 0  CRC ok\n"
        "     2            -   1 response  Read Holding Registers 0: 0=7 [#1]  CRC ok\n"), "")
    assert run_cli(["--hex", f"Tx:000001-{request}", "--hex", f"Rx:000002-{answer}"]) == typed
    assert run_cli(["--hex", f"000001-Tx:{request}\n000002-Rx:{answer}\n"]) == typed
    assert run_cli(["--hex", f"Tx:000003-10:15:30.125-{request}\nRx:000004-10:15:30.140-{answer}"]) == typed
