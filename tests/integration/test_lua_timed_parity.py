"""The plugin (tshark -2 with lua/vw3.lua) against `vw3-decode --json` on timed captures, frame by frame: a
bounded run of bench/lua_timed_fuzz.py (random buses cut into pcap and pcapng records one frame a record, in
bursts, late inside frames, some untimed; random --baud and --timeout), and the times in texts to the digit.

Before: the plugin warned of no silence inside a frame (vw3-decode's `silence of 2.000 ms inside the frame
before byte 57 (longer than t1.5 = 0.859 ms at 19200 baud)`: 150 to 290 fields a seed), and took record times
as pinfo.abs_ts, a double near 1.7e9 s 238 ns coarse: a response 1000.05 ms after its request read
`response 1000.0 ms after request #1` where vw3-decode says 1000.1 ms.
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import ROOT, LuaItem, lua_items, python_items

sys.path.insert(0, str(ROOT / "bench"))
sys.path.insert(0, str(ROOT / "tests" / "differential"))
import lua_timed_fuzz  # noqa: E402
from test_timed_summary import write_pcap  # noqa: E402

pytestmark = pytest.mark.integration


# (seed: how its records are cut, its options) bursts, us pcap, --baud 19200; bursts, ns pcap, --baud 115200;
# bursts, pcapng, a damaged Write File Record answer past the timeout (test_damaged_answer_...)
@pytest.mark.parametrize("seed", [0, 6, 11])
def test_random_timed_capture_parity(seed: int, tmp_path: Path) -> None:
    how, options, differences = lua_timed_fuzz.differences_of(seed, tmp_path)
    assert not differences, f"seed {seed} ({how}, {options}): " + "\n".join(differences[:20])


READ, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0001 0002")
BASE = 1_700_000_000 * 10**9 + 123_456_789
# Each time chosen where abs_ts's doubles give another digit than the nanoseconds (1005.5, 2.0, 500.0 ms).
LATE, BACKWARDS, ENDING = BASE + 1_000_003, BASE + 5 * 10**9, BASE + 10_001_000_003
RECORDS: list[tuple[bytes, int | None]] = [
    (READ, LATE), (ANSWER, LATE + 1_005_450_000),  # 1005.45 ms: past the 1 s timeout after the read's 4.6 ms
    (READ, BACKWARDS), (ANSWER, BACKWARDS - 2_050_000),  # stamped 2.05 ms before its request
    (READ, ENDING), (b"", ENDING + 500_050_000),  # the capture ends 500.05 ms after the last request
]
TEXTS = [
    "response 1005.4 ms after request #1, later than the 1000 ms timeout: not its answer",
    "response stamped 2.1 ms before request #3: time goes backwards, left out of the response times",
    "the capture ends 500.1 ms after the request, within the 1000 ms timeout: not known whether it was answered",
]


def _said(records: list[tuple[bytes, int | None]], texts: list[str], tmp_path: Path, baud: int | None = None
          ) -> list[LuaItem]:
    """The plugin's items (at `baud`: its preference, vw3-decode --baud), checked against vw3-decode's; each of
    `texts` said by both."""
    capture = tmp_path / "times.pcap"
    write_pcap(capture, records)
    python = python_items(capture, None, *(["--baud", str(baud)] if baud else []))
    lua = lua_items(capture, *(["-o", f"vw3.baud:{baud}"] if baud else []))[0]
    differences = compare(python, lua)
    assert not differences, "\n".join(differences)
    said = [text for item in lua for kind in ("warning", "note") for text in item.texts.get(kind, [])]
    python_said = [text for item in python for text in item.data["warnings"] + item.data["notes"]]
    for text in texts:
        assert text in said and text in python_said, text
    return lua


def test_times_in_texts_have_vw3_decode_digits(tmp_path: Path) -> None:
    lua = _said(RECORDS, TEXTS, tmp_path)
    # (the response time, exact to the nanosecond: 2.05 ms before its request)
    times = [item.fields["response_time"] for item in lua if "response_time" in item.fields]
    assert times == ["-0.002050000"]


@pytest.mark.parametrize("baud, text", [
    (None, "silence of 18.281 ms inside the frame before byte 3 (longer than t1.5 = 0.859 ms at 19200 baud)"),
    (9600, "silence of 16.562 ms inside the frame before byte 3 (longer than t1.5 = 1.719 ms at 9600 baud)"),
])
def test_silence_inside_a_frame_is_warned_of(tmp_path: Path, baud: int | None, text: str) -> None:
    # A request whose bytes stop for 20 ms after its third (its 3 characters took 1.7 ms at 19200 baud).
    records: list[tuple[bytes, int | None]] = [
        (READ[:3], BASE), (READ[3:], BASE + 20_000_000), (ANSWER, BASE + 40_000_000)]
    lua = _said(records, [text], tmp_path, baud)
    assert [item.fields["response_time"] for item in lua if "response_time" in item.fields] == ["0.040000000"]


def test_damaged_answer_past_the_timeout_is_no_retry(tmp_path: Path) -> None:
    """A Mask Write Register (same layout both ways) cut across records, then past the 1 s timeout a frame of
    its length and CRC bytes whose data differ (its CRC bad): vw3-decode's retry rule compares the data
    (pairing.py _repeats), a late answer. The plugin, whose request had dropped its byte table, took the
    length and CRC for the data and read the master's retry: a request, unanswered."""
    mask_write = rtu("01 16 0004 00F2 0025")
    damaged = mask_write[:5] + b"\x00" + mask_write[6:]
    records: list[tuple[bytes, int | None]] = [
        (mask_write[:4], BASE), (mask_write[4:], BASE + 1_000_000), (damaged, BASE + 1_500_000_000)]
    lua = _said(records, ["response 1500.0 ms after request #1, later than the 1000 ms timeout: not its answer"],
                tmp_path)
    assert [item.fields.get("kind") for item in lua if item.fields.get("kind")] == ["1", "2"]


def test_first_record_at_the_epoch_is_timed_when_the_second_is_within_day_0(tmp_path: Path) -> None:
    """sources/pcap.py EpochRecord: a capture's first record at the epoch is timed (a time-of-day log of day 0)
    when the second is not at the epoch but within day 0, untimed otherwise (vw3-decode -w's untimed records,
    an untimed record before a real date's). Before, the plugin took every record at the epoch as untimed; then
    both took one before a real date's as timed: a silence of 1700000000121.738 ms inside the request, its
    answer 1700000000133.5 ms after it, past the timeout. (The request is sent when its last byte is, an hour
    after its first: its answer 10 ms later answers it, 3600133.5 ms after its first byte: model.sent_in.)"""
    day_zero = 3_600 * 10**9 + 123_456_789  # 01:00 on 1 January 1970
    timed = [(READ[:3], 0), (READ[3:], day_zero), (ANSWER, day_zero + 10_000_000)]
    lua = _said(timed, [
        "silence of 3600121.738 ms inside the frame before byte 3 (longer than t1.5 = 0.859 ms at 19200 baud)",
    ], tmp_path)
    assert [item.fields.get("response_time") for item in lua if item.fields.get("kind") == "2"] == ["3600.133456789"]
    real_date = [(READ[:3], 0), (READ[3:], BASE), (ANSWER, BASE + 10_000_000)]
    lua = _said(real_date, [], tmp_path)
    said = [text for item in lua for kind in ("warning", "note") for text in item.texts.get(kind, [])]
    assert not [text for text in said if "silence" in text or "timeout" in text], said
    assert [item.fields["kind"] for item in lua if "kind" in item.fields] == ["1", "2"]  # (the answer paired)
    untimed = [(READ[:3], 0), (READ[3:], 0), (ANSWER, BASE + 10_000_000)]
    lua = _said(untimed, [], tmp_path)
    assert [item.fields.get("response_time") for item in lua if item.fields.get("kind") == "2"] == [None]
