"""A record boundary where the framer stops to wait for more bytes is still a boundary when the bytes come
(stream.py _consume keeps the boundaries at and after the new base): a frame that starts at a record's
start after noise is anchored there, in the plugin as in vw3-decode, and counts on its CRC alone."""
from __future__ import annotations

from pathlib import Path

from lua_compare import compare, lua_kind, lua_shown
from lua_harness import lua_items, python_items, write_pcap

from dissector.protocol.crc import with_crc

# A read of 256 registers (above FC3's limit of 125: not plausible on its own fields) from slave 0x20, whose
# answer never comes: only the record boundary it starts at makes it a frame.
REQUEST = with_crc(bytes.fromhex("20 03 0000 0100"))
GARBAGE = bytes.fromhex("77 88 99 AA BB CC DD EE FF 11 12 13 14 15 16 17 18 19 1A 1B 1C 1D")


def test_a_frame_cut_across_records_after_noise_is_anchored_at_its_record(tmp_path: Path) -> None:
    records = [b"\x99" * 6, REQUEST[:4], REQUEST[4:] + GARBAGE]
    pcap = write_pcap(tmp_path / "cut.pcap", [(data, 1_700_000_000 + index * 0.001) for index, data in enumerate(records)])
    python = python_items(pcap, [])
    assert [(item.data["kind"], item.data["raw"]) for item in python] == [
        ("noise", "99" * 6), ("request", REQUEST.hex()), ("noise", GARBAGE.hex())]
    lua, _, _ = lua_items(pcap)
    differences = compare(python, lua)
    assert not differences, "\n".join(differences[:40])
    assert [lua_kind(item) for item in lua_shown(lua)] == ["noise", "request", "noise"]
