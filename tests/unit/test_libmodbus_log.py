"""libmodbus debug output as an input (hunt64): what `mbpoll -v` (and any program calling modbus_set_debug)
prints, a frame sent a line in [ ], a frame heard in < >, between the program's own lines. An engineer's
`mbpoll -v -m rtu ... /dev/ttyUSB0 > poll.log` was "the input is text, but neither a hex dump nor Modbus
ASCII: decoded as raw bytes", one noise item of the whole log; `--hex '[0C][03]...'` (pasted from such a
log) said "'0C][03][20]...' is not hex".

TRANSCRIPT is mbpoll 1.0-0's (Debian 12) own output, polling slave 12 at 8402 (3 registers, wire address
8401) through a pseudo-terminal whose far end answered: normally, with a bad CRC, with exception 02."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from dissector.sources.reader import open_source
from helpers import run_cli

BANNER = """debug enabled
Set mode=rtu
iGetIntList(12)
Integer found: 12
iCount=1
Set start reference=8402
Set number of values=3
Set rtu baudrate=19200
Set rtu parity=even
Set function=4
Set poll rate=100
Set timeout=0.3
Set device=/dev/pts/0
mbpoll 1.0-0 - FieldTalk(tm) Modbus(R) Master Simulator
Copyright \u00a9 2015-2019 Pascal JEAN, https://github.com/epsilonrt/mbpoll
This program comes with ABSOLUTELY NO WARRANTY.
This is free software, and you are welcome to redistribute it
under certain conditions; type 'mbpoll -w' for details.

Opening /dev/pts/0 at 19200 bauds (E, 8, 1)
Set response timeout to 0 sec, 300000 us
Protocol configuration: Modbus RTU
Slave configuration...: address = [12]
                        start reference = 8402, count = 3
Communication.........: /dev/pts/0,      19200-8E1 
                        t/o 0.30 s, poll rate 100 ms
Data type.............: 16-bit register, output (holding) register table

"""
POLLS = """-- Polling slave 12... Ctrl-C to stop)
[0C][03][20][D1][00][03][5F][2F]
Waiting for a confirmation...
<0C><03><06><20><D1><20><D2><20><D3><71><33>
[8402]: \t8401
[8403]: \t8402
[8404]: \t8403
-- Polling slave 12... Ctrl-C to stop)
[0C][03][20][D1][00][03][5F][2F]
Waiting for a confirmation...
<0C><03><06><20><D1><20><D2><20><D3><71><00>
ERROR CRC received 0x7100 != CRC calculated 0x7133
Read output (holding) register failed: Invalid CRC
-- Polling slave 12... Ctrl-C to stop)
[0C][03][20][D1][00][03][5F][2F]
Waiting for a confirmation...
<0C><83><02><51><32>
ERROR Illegal data address
Read output (holding) register failed: Illegal data address
"""
TRANSCRIPT = BANNER + POLLS
DECODED = [
    "     1            -  12 request   Read Holding Registers 8401..8403 (3)  CRC ok",
    "     2            -  12 response  Read Holding Registers 8401..8403 (3): 8401=8401 8402=8402 8403=8403 [#1]  CRC ok",
    "     3            -  12 request   Read Holding Registers 8401..8403 (3)  CRC ok",
    "     4            -  12 response  Read Holding Registers 8401..8403 (3): 8401=8401 8402=8402 8403=8403 [#3]"
    "  CRC BAD (received 0x0071, expected 0x3371)",
    "     5            -  12 request   Read Holding Registers 8401..8403 (3)  CRC ok",
    "     6            -  12 exception Read Holding Registers: exception 2 (Illegal Data Address) [#5]  CRC ok",
]


def test_mbpoll_transcript_is_decoded(tmp_path: Path) -> None:
    log = tmp_path / "poll.log"
    log.write_text(TRANSCRIPT, encoding="utf-8")
    assert run_cli(["-n", str(log)]) == (0, "\n".join(DECODED) + "\n", "")
    # each line of bytes is a record of the -w copy, as Wireshark's mbrtu reads frames: one a record
    copy = tmp_path / "poll.pcap"
    assert run_cli(["-n", "-w", str(copy), str(log)])[0] == 0
    assert [len(chunk.data) for chunk in open_source(str(copy))] == [8, 11, 8, 11, 8, 5]


@pytest.mark.parametrize("skipped", [0, 19])
def test_a_pipe_told_by_its_first_lines(skipped: int) -> None:
    """A pipe is judged on its first 512 bytes (`mbpoll -v ... | vw3-decode -`), mbpoll's own lines: its first,
    `debug enabled`, tells; so does libmodbus's `Opening /dev/pts/0 at 19200 bauds (E, 8, 1)` (mbpoll's echo of
    its arguments and banner left out)."""
    root = Path(__file__).resolve().parents[2]
    env = {**os.environ, "PYTHONPATH": str(root)}
    text = "".join(TRANSCRIPT.splitlines(keepends=True)[skipped:])
    run = subprocess.run([sys.executable, "-m", "dissector", "-n", "-"], input=text.encode(), cwd=root, env=env,
                         capture_output=True, timeout=120)
    assert (run.returncode, run.stderr) == (0, b"")
    assert run.stdout.decode() == "\n".join(DECODED) + "\n"


def test_opening_line_tells_before_any_frame() -> None:
    from dissector.sources.reader import detect_format

    opening = "".join(TRANSCRIPT.splitlines(keepends=True)[19:])
    assert detect_format(opening[:400].encode(), False) == ("libmodbus", None)  # (its first frame at 435)
    assert detect_format(TRANSCRIPT[:512].encode(), False) == ("libmodbus", None)  # (mbpoll's `debug enabled`)


def test_format_given_for_standard_input() -> None:
    """(A pipe is judged on its first lines, mbpoll's own: `mbpoll -v ... | vw3-decode --format libmodbus -`.)"""
    assert run_cli(["-n", "--format", "libmodbus", "-"], stdin=TRANSCRIPT.encode()) == (
        0, "\n".join(DECODED) + "\n", "")


def test_value_lines_of_mbpoll_are_not_bytes(tmp_path: Path) -> None:
    """mbpoll shows the value of reference 10 as `[10]: 5`: two hex digits in brackets, but no frame."""
    log = tmp_path / "poll.log"
    log.write_text("[01][03][00][08][00][02][45][C9]\nWaiting for a confirmation...\n"
                   "<01><03><04><00><05><00><06><6A><30>\n[9]: \t5\n[10]: \t6\n", encoding="utf-8")
    assert run_cli(["-n", str(log)])[1].splitlines() == [
        "     1            -   1 request   Read Holding Registers 8..9 (2)  CRC ok",
        "     2            -   1 response  Read Holding Registers 8..9 (2): 8=5 9=6 [#1]  CRC ok",
    ]


def test_last_line_cut_short(tmp_path: Path) -> None:
    log = tmp_path / "poll.log"
    log.write_text("[01][03][00][08][00][02][45][C9]\nWaiting for a confirmation...\n<01><03><0", encoding="utf-8")
    status, out, err = run_cli(["-n", str(log)])
    assert (status, out.splitlines()[1]) == (0, "     2            -   - noise     2 bytes of noise at offset 8: 01 03")
    assert err == (f"vw3-decode: warning: {log} line 3 is cut short (the input ends inside it, without a line end): "
                   "its 2 whole bytes are decoded, the rest ('<0') is not\n")


def test_format_given_to_another_text_says_so(tmp_path: Path) -> None:
    other = tmp_path / "notes.txt"
    other.write_text("no frame here\n", encoding="utf-8")
    assert run_cli(["--format", "libmodbus", str(other)]) == (
        0, "", f"vw3-decode: warning: {other}: no line of libmodbus debug output ([01][03]... sent, <01><03>... "
               "received)\n")


@pytest.mark.parametrize("typed", [
    ["--hex", "[0C][03][20][D1][00][03][5F][2F]", "--hex", "<0C><03><06><20><D1><20><D2><20><D3><71><33>"],
    ["--hex", "[0C][03][20][D1][00][03][5F][2F] <0C><03><06><20><D1><20><D2><20><D3><71><33>"],
])
def test_hex_typed_from_such_a_log(typed: list[str]) -> None:
    assert run_cli(["-n", *typed])[1].splitlines() == [line.replace("  CRC BAD (received 0x0071, expected 0x3371)",
                                                                    "  CRC ok") for line in DECODED[:2]]
