"""The plugin, as vw3-decode (tests/unit/test_rtac_event_record_end.py): an RTAC record of the header alone
(an event, no serial byte) reaches no VW3 dissection (Wireshark's RTAC dissector hands no data on), yet its
own time says the tap was recording then. Before, the plugin's capture ended at the request: frame 3 got
"the capture ends before any response: not known whether it was answered" instead of Unanswered, and a
capture going on 500 ms after it said 1.0 ms (the last data record's time)."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from lua_harness import run_tshark

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER = bytes.fromhex("0C0306000100020003A5E4")
T0 = 1_700_000_000

NOT_KNOWN = ("the capture ends 500.0 ms after the request, within the 1000 ms timeout: not known whether "
             "it was answered")


def _pcap(path: Path, last: float) -> Path:
    """Linktype 250: a read answered, a read at 1 s, then at `last` an event record of the header alone
    (event 0x01, no data); each record's time its RTAC header's."""
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 250)
    for at, data, event in [(0, REQUEST, 0), (0.012, ANSWER, 0), (1, REQUEST, 0), (last, b"", 1)]:
        seconds, micros = divmod(T0 * 1_000_000 + round(at * 1_000_000), 1_000_000)
        payload = struct.pack(">IIBBH", seconds, micros, event, 0, 0) + data
        out += struct.pack("<IIII", seconds, micros, len(payload), len(payload)) + payload
    path.write_bytes(out)
    return path


@pytest.mark.parametrize("last, expected", [(4.0, ["3", "1", ""]), (1.5, ["3", "", NOT_KNOWN])],
                         ids=["past", "within"])
def test_an_event_record_ends_the_capture(tmp_path: Path, last: float, expected: list[str]) -> None:
    path = _pcap(tmp_path / "rtac.pcap", last)
    result = run_tshark(path, "-d", "rtacser.data,vw3", "-Y", "frame.number == 3", "-T", "fields",
                        "-E", "separator=|", "-e", "frame.number", "-e", "vw3.unanswered", "-e", "vw3.note")
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["|".join(expected)]
