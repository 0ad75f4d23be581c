"""Live lines read before profile `auto` chose a slave's device say they are provisional (issue 27).

A file is read twice (app/preselect.py): its frames are named from the first with the device chosen
over the whole input. A live line cannot wait for the future: the p.38 capture's frames 1 to 3 come
before the evidence of frame 4 (the second answer with 16#8000 at 8400), so live they are named with
spec semantics only and marked: `[provisional]` in the summary, `"provisional": true` in --json,
`Profile: provisional (...)` in -V, the `provisional` key of -T fields and -Y (with one stderr note when
-T fields does not show it), `[provisional]` on --watch lines. The p.38 bytes go through a
pseudo-terminal one frame at a time; live --json equals `vw3-decode - --json` of the capture it wrote
(one pass), key for key, and differs from the two-pass decode of that file in frames 1 to 3 only.
"""
from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

from conftest import ROOT
from live_bus import live_on_pty

from dissector.protocol.crc import with_crc
from dissector.render.detail import PROVISIONAL_LINE
from dissector.sources.reader import open_source

P38_FRAMES = [chunk.data for chunk in open_source(str(ROOT / "captures" / "p38_protection.pcap"))]
NOTE = ("vw3-decode: warning: rows from frame 1 on of slaves whose device profile auto has not chosen yet are "
        "provisional (read once, named with spec semantics only); -e provisional marks them")


def run_live(*options: str, frames: list[bytes] = P38_FRAMES) -> tuple[list[str], str]:
    """`frames` written to a pseudo-terminal one by one; vw3-decode --live (profile auto) on its other end."""
    lines, err, status = live_on_pty(frames, *options)
    assert status == 0, err
    return lines, err


def _untimed(line: str) -> str:
    """A summary line without its time column and the response time it measured."""
    line = re.sub(r"^( *\d+) +\d+\.\d{6} ", r"\1 ", line)
    return re.sub(r"\[#(\d+), \d+\.\d ms\]", r"[#\1]", line)


REQUEST = " 12 request   Read Holding Registers 8400..8402 (3)"
RESPONSE = " 12 response  Read Holding Registers 8400..8402 (3): "
EXCEPTION = (" 12 exception Read Holding Registers: exception 2 (Illegal Data Address) [#{n}] [exception 02 from the "
             "VW3 A3 303: every parameter of this read is non-existent or protected: 8400 non-existent, CHCF (8401) "
             "protected, COP (8402) protected]")
LIVE_SUMMARY = [
    f"     1 {REQUEST} [provisional]  CRC ok",
    f"     2 {RESPONSE}8400=32768 8401=3 8402=2 [#1] [provisional]  CRC ok",
    f"     3 {REQUEST} [provisional]  CRC ok",
    f"     4 {RESPONSE}8400=non-existent CHCF=IO (I/O profile) COP=Cd (command) [#3]  CRC ok",
    f"     5 {REQUEST}  CRC ok",
    f"     6 {RESPONSE}8400=non-existent CHCF=protected COP=Cd (command) [#5] "
    "[CHCF (8401) became protected: read 3 in frame #4, 16#8000 now]  CRC ok",
    f"     7 {REQUEST}  CRC ok",
    f"     8 {RESPONSE}8400=non-existent CHCF=protected COP=Cd (command) [#7]  CRC ok",
    f"     9 {REQUEST}  CRC ok",
    f"    10 {EXCEPTION.format(n=9)} [COP (8402) became protected: read 2 in frame #8, exception 02 now]  CRC ok",
    f"    11 {REQUEST}  CRC ok",
    f"    12 {EXCEPTION.format(n=11)}  CRC ok",
]


def test_live_summary_marks_the_lines_read_before_the_choice() -> None:
    lines, err = run_live()
    assert [_untimed(line) for line in lines] == LIVE_SUMMARY
    # When the choice is made, stderr says from where the lines are final.
    assert err.splitlines()[0] == (
        "vw3-decode: profile slave 12: atv71 (traffic fits its map: function 3 at 8400..8402 in frames #2 and #4; "
        "16#8000 at 8400, its answer for a non-existent parameter); its earlier lines were provisional")


def test_live_json_is_the_one_pass_decode_of_its_own_capture(tmp_path: Path) -> None:
    pcap = tmp_path / "live.pcap"
    lines, _err = run_live("--json", "-w", str(pcap))
    live = [json.loads(line) for line in lines]
    assert [(r["frame"], r.get("provisional", False)) for r in live] == [
        (number, number <= 3) for number in range(1, 13)]
    assert [[reg.get("code") for reg in r.get("registers") or []] for r in live[:4]] == [
        [], [None, None, None], [], [None, "CHCF", "COP"]]
    once = subprocess.run([sys.executable, "-m", "dissector", "-", "--json"], input=pcap.read_bytes(), cwd=ROOT,
                          capture_output=True, timeout=60)
    assert [json.loads(line) for line in once.stdout.splitlines()] == live  # key for key, times too
    twice = subprocess.run([sys.executable, "-m", "dissector", str(pcap), "--json"], cwd=ROOT, capture_output=True,
                           text=True, timeout=60)
    files = [json.loads(line) for line in twice.stdout.splitlines()]
    assert files[3:] == live[3:]
    assert [frame["frame"] for frame, seen in zip(files, live) if frame != seen] == [1, 2, 3]
    assert not any("provisional" in frame for frame in files)
    assert files[1]["registers"] == live[3]["registers"] == [  # the file names frame 2 as live names frame 4
        {"address": 8400, "value": 32768, "text": "16#8000: non-existent (address not in the map)",
         "status": "non-existent"},
        {"address": 8401, "value": 3, "code": "CHCF", "name": "Profile", "text": "IO (I/O profile)", "status": "ok",
         "source": "S"},
        {"address": 8402, "value": 2, "code": "COP", "name": "Copy channel 1 <> 2", "text": "Cd (command)",
         "status": "ok", "source": "S"}]
    assert live[1]["registers"] == [{"address": 8400, "value": 32768}, {"address": 8401, "value": 3},
                                    {"address": 8402, "value": 2}]


def test_live_detail_fields_and_filter_say_provisional() -> None:
    lines, _err = run_live("-V", "-Y", "frame <= 4")
    blocks = "\n".join(lines).split("\n\n")
    assert [PROVISIONAL_LINE in block.splitlines() for block in blocks] == [True, True, True, False]
    assert [re.sub(r"\d+\.\d+ ms$", "- ms", line) for line in blocks[1].splitlines()[3:]] == [
        "        Slave: 12", "        Function: 3 (0x03) Read Holding Registers", "        [Start address: 8400]",
        "        [Quantity: 3]", "        Byte count: 6 (0x6)",
        "        Register 8400: 32768 (0x8000)", "        Register 8401: 3 (0x0003)", "        Register 8402: 2 (0x0002)",
        "        CRC: 0xE417 [CRC ok]", "    Request in frame: 1", "    Response time: - ms", PROVISIONAL_LINE]
    assert PROVISIONAL_LINE == ("    Profile: provisional (profile auto has not chosen this slave's device yet: values "
                                "named with spec semantics only, which its device may name otherwise)")
    assert blocks[3].splitlines()[-1] == (
        "    Profile: atv71 (traffic fits its map: function 3 at 8400..8402 in frames #2 and #4; 16#8000 at 8400, "
        "its answer for a non-existent parameter)")
    lines, err = run_live("-T", "fields", "-e", "frame", "-e", "provisional", "-e", "value", "-Y", "frame <= 4")
    assert lines == ["1\t1\t", "2\t1\t32768,3,2", "3\t1\t", "4\t\t32768,3,2"]  # (a request: no value, as tshark)
    assert "warning:" not in err
    lines, err = run_live("-T", "fields", "-e", "frame", "-e", "value", "-Y", "frame <= 4")
    assert lines == ["1\t", "2\t32768,3,2", "3\t", "4\t32768,3,2"]
    assert err.count(NOTE) == 1, err
    lines, _err = run_live("-Y", "provisional", "--json")
    assert [json.loads(line)["frame"] for line in lines] == [1, 2, 3]


def test_live_watch_by_code_and_by_address_agree_before_the_choice() -> None:
    # CHCF read alone, 3 then 4: one read, no 16#8000, so no device yet: the change is provisional.
    request = with_crc(bytes.fromhex("0c0320d10001"))
    frames = [request, with_crc(bytes.fromhex("0c03020003")), request, with_crc(bytes.fromhex("0c03020004"))]
    for watched in ("8401", "CHCF"):
        lines, _err = run_live("--watch", watched, frames=frames)
        assert [re.sub(r"^( *\d+) +\d+\.\d{6} ", r"\1 ", line) for line in lines] == [
            "     4  12 8401 3 -> 4 [provisional]"], watched
        lines, _err = run_live("--watch", watched, "--json", frames=frames)
        record = json.loads(lines[0])
        assert (record["frame"], record["address"], record["code"], record["old"], record["new"],
                record["provisional"]) == (4, 8401, None, "3", "4", True)
