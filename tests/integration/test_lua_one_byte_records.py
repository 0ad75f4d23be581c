"""Random bytes read one byte a record (a USB tap's reads of a line at the wrong speed), with frames and silences
among them: the plugin frames them as vw3-decode does, in one pass and in two. Every record end is a boundary the
framer weighs (lua/src/rtu.lua framed_reach asks, for each start, whether the records ahead are frames of their
own); they are kept as ascending lists asked by bisection and a record end's answer is kept while the stream's end
and the answer awaited stay, as framing/offsets.py and stream.py _ends_memo do: a look-up through every record end
cost 2 ms a byte (bench/lua_noise_records.py: 20,000 records 41.6 s -> 21.7 s of tshark -2, same output)."""
from __future__ import annotations

import random
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import assert_as_vw3_decode_in_one_and_two_passes, lua_items, write_pcap
from lua_compare import lua_kind, lua_shown

pytestmark = pytest.mark.integration
# (what one pass cannot know when it shows a request: the answer after it, test_lua_parity_auto.py)
LATER = frozenset(["response_frame", "unanswered"])
REQUEST, ANSWER = rtu("01 03 0000 0002"), rtu("01 03 04 0102 0304")


def _one_byte_records(tmp_path: Path) -> Path:
    noise = random.Random(57).randbytes
    data = noise(300) + REQUEST + ANSWER + noise(200) + REQUEST + noise(150)
    records, time = [], 1_700_000_000.0
    for index, byte in enumerate(data):
        # 1 ms apart (no silence of t3.5 at 19200 baud), but for a silence of 50 ms before a few of them
        time += 0.05 if index in (120, 330, 560) else 0.001
        records.append((bytes([byte]), time))
    # (then a request and its answer a record each: frames of their own, which settle the noise before them in
    # one pass too; without them the end of the capture would, which one pass shows in no record)
    records += [(REQUEST, time + 0.05), (ANSWER, time + 0.06)]
    return write_pcap(tmp_path / "one_byte_records.pcap", records)


def test_one_byte_records_are_framed_as_vw3_decode_frames_them(tmp_path: Path) -> None:
    pcap = _one_byte_records(tmp_path)
    assert_as_vw3_decode_in_one_and_two_passes(pcap, LATER)
    shown = lua_shown(lua_items(pcap)[0])
    kinds = [lua_kind(item) for item in shown]
    assert kinds.count("request") >= 2 and "response" in kinds and "noise" in kinds, kinds
