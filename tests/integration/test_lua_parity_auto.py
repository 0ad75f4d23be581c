"""Profile `auto` in the Wireshark plugin: the same device per slave as `vw3-decode` (its default), from
the same evidence in the same order: identification (FC43 ProductCode), SEL function codes, traffic that
fits one map, the choice taken back by an unsupported function, slaves judged long enough (settled).

Real tshark 4.0.17 with lua/vw3.lua against `vw3-decode --json`, item by item (tests/support/lua_compare),
and the plugin's `vw3.profile_choice` against the choices vw3-decode reports (Annotator.choices()).
"""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from lua_compare import compare, lua_shown
from lua_harness import (
    CLI_TIMEOUT, PLUGIN, USER_DLT, ensure_tool, lua_errors, lua_items, parse_pdml, python_items, run_tshark,
    write_pcap,
)
from lua_session import SessionBuilder, exception, frame

from dissector.devices.build import build_annotator
from dissector.framing.rtu import RtuFramer
from dissector.model import Kind
from dissector.pipeline import Dissector
from dissector.sim.simulate import generate_session, write_capture
from dissector.sources.reader import open_source


# What one pass cannot know yet: a request's answer is in a later record (tshark -2 shows it).
LATER = frozenset(["response_frame", "unanswered"])


def _read(slave: int, start: int, values: list[int], function: int = 3) -> list[bytes]:
    request = frame(slave, function, Kind.REQUEST, start=start, quantity=len(values))
    return [request, frame(slave, function, Kind.RESPONSE, byte_count=2 * len(values), values=values)]


def _coils(slave: int) -> list[bytes]:
    return [frame(slave, 1, Kind.REQUEST, start=0, quantity=8), frame(slave, 1, Kind.RESPONSE, byte_count=1,
                                                                       status=b"\x05")]


def _identification(slave: int, product: bytes) -> list[bytes]:
    objects = [(0, b"Schneider Electric"), (1, product), (2, b"0201")]
    request = frame(slave, 43, Kind.REQUEST, mei_type=14, body={"read_code": 1, "object_id": 0})
    response = frame(slave, 43, Kind.RESPONSE, mei_type=14, body={
        "read_code": 1, "conformity": 1, "more_follows": 0, "next_object_id": 0, "object_count": len(objects),
        "objects": [{"id": key, "length": len(value), "value": value} for key, value in objects],
    })
    return [request, response]


def evidence_session() -> list[tuple[bytes, float]]:
    """One frame a record; every kind of evidence profile auto weighs, and what it must not be fooled by."""
    sel = SessionBuilder(seed=4)
    frames: list[bytes] = []
    # slave 3: its first answer fits the ATV71 map (8400 reads 16#8000: non-existent, CHCF and COP known);
    # one answer is no evidence (issue 26): its second read, at other addresses the map knows, decides
    frames += _read(3, 8400, [0x8000, 3, 2])
    frames += _read(3, 3202, [500, 0x8000])
    # slave 4: a read no map knows, then its identification: ATV71 from the ProductCode (final)
    frames += _read(4, 0, [1, 2])
    frames += _identification(4, b"ATV71HU15M3")
    frames += _coils(4)  # (final: an unsupported function takes nothing back)
    # slave 7: a SEL-749M function code (60h, Read Parameter Information): final
    frames += _read(7, 3100, [40, 600])  # fits the ATV71 (one read: no evidence yet)...
    frames += [sel._scanned(7, 0x60, 10), sel._scanned(7, 0x60, 24)]  # ...then says what it is
    frames += [frame(7, 3, Kind.REQUEST, start=0, quantity=200), exception(7, 3, 3)]  # Table D.5, quantity
    # slave 9: fits the ATV71 (two reads), then answers a function the VW3 A3 303 does not support:
    # back to generic
    frames += _read(9, 8401, [3, 2])
    frames += _read(9, 3202, [500, 7])
    frames += _coils(9)
    frames += _read(9, 8400, [0x8000, 0x8000, 2])  # generic now: no 16#8000 status
    # slave 11: no evidence at all (spec semantics only)
    frames += _coils(11) + _read(11, 0, [7])
    # slave 12: chosen from its traffic (one read answered twice with the VW3 card's 16#8000 for the
    # non-existent 8400), then every parameter of a read unreadable: exception 02 (p.38)
    frames += _read(12, 8400, [0x8000, 3, 2])
    frames += _read(12, 8400, [0x8000, 3, 2])
    frames += [frame(12, 3, Kind.REQUEST, start=8400, quantity=3), exception(12, 3, 2)]
    frames += [frame(12, 3, Kind.REQUEST, start=8401, quantity=1), exception(12, 3, 2)]
    # slave 13: judged on its first 8 answers (FIT_ANSWERS), none fits: settled, a later fit changes nothing
    for _ in range(8):
        frames += _coils(13)
    frames += _read(13, 8400, [0x8000, 3, 2])
    # slave 14: 32 frames (FIT_FRAMES) without an answer that fits: settled as well
    for index in range(32):
        frames.append(frame(14, 3, Kind.REQUEST, start=index, quantity=1))
    frames += _read(14, 8400, [0x8000, 3, 2])
    # a broadcast write (slave 0 is never chosen for)
    frames.append(frame(0, 6, Kind.REQUEST, address=8501, value=6))
    frames += _read(3, 8400, [0x8000, 0x8000, 2])  # slave 3 kept the ATV71: CHCF protected now
    return [(data, 1767225600.0 + 0.02 * index) for index, data in enumerate(frames)]


def cli_choices(pcap: Path, profiles: list[str]) -> list[str]:
    """What vw3-decode says of its choices (the stderr lines on a terminal, the --stats table): one per
    slave that evidence decided, `slave 12: atv71 (traffic fits its map: ...)`."""
    with open_source(str(pcap)) as source:
        annotate = build_annotator(profiles, [])
        dissector = Dissector(framer=RtuFramer(), annotate=annotate, timeout=CLI_TIMEOUT)
        for chunk in source:
            dissector.feed(chunk)
        dissector.finish()
    return [choice.text() for choice in annotate.choices() if choice.frame is not None]


def lua_choices(lua: list) -> list[str]:
    """The plugin's last `vw3.profile_choice` per slave (each decision is said on the frame that made it)."""
    last: dict[str, str] = {}
    for item in lua_shown(lua):
        text = item.fields.get("profile_choice")
        if text is not None:
            last[text.split(":", 1)[0]] = text
    return sorted(last.values(), key=lambda text: int(text.split(":")[0].split()[1]))


def _profiles_by_item(lua: list) -> dict[int, tuple[str | None, str | None]]:
    return {int(item.fields["item"]): (item.fields.get("slave"), item.fields.get("profile"))
            for item in lua_shown(lua) if item.fields.get("kind") != "4"}


def test_auto_is_the_default_and_chooses_as_vw3_decode(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "evidence.pcap", evidence_session())
    # vw3-decode's default, profile auto, reading the file twice as tshark -2 shows it (issue 27)
    python = python_items(pcap)
    lua, record_experts, _ = lua_items(pcap)  # the plugin's default
    differences = compare(python, lua)
    assert not differences, "\n".join(differences[:40])
    assert not any("Preferences" in text for _, text in record_experts)
    choices = cli_choices(pcap, [])
    assert lua_choices(lua) == choices
    assert choices == [
        "slave 3: atv71 (traffic fits its map: function 3 at 8400..8402 in frame #2, function 3 at 3202..3203 in "
        "frame #4)",
        "slave 4: atv71 (Read Device Identification in frame #8: ProductCode 'ATV71HU15M3')",
        "slave 7: sel749m (function 60h (Read Parameter Information) in frame #13)",
        "slave 9: generic (function 1 answered in frame #22, which the VW3 A3 303 does not support)",
        "slave 12: atv71 (traffic fits its map: function 3 at 8400..8402 in frames #30 and #32; 16#8000 at 8400, "
        "its answer for a non-existent parameter)",
    ]
    # Slave 9's choice was made, then taken back: both said where they happened.
    said = [item.fields["profile_choice"] for item in lua_shown(lua) if "profile_choice" in item.fields]
    assert ("slave 9: atv71 (traffic fits its map: function 3 at 8401..8402 in frame #18, function 3 at "
            "3202..3203 in frame #20)") in said
    # The evidence shows in what is decoded: names and 16#8000 statuses only where a device was chosen.
    frames = {item.data["frame"]: item.data for item in python}
    profiles = _profiles_by_item(lua)
    # (-2, as vw3-decode reading a file: the second read decides, for the first as well)
    assert profiles[2] == ("3", "atv71") and profiles[4] == ("3", "atv71")
    assert [reg.get("status") for reg in frames[2]["registers"]] == ["non-existent", "ok", "ok"]
    # (FRH's 16#8000 is also a signed value, -3276.8 Hz: ambiguous, data/maps/atv71.csv)
    assert [reg.get("status") for reg in frames[4]["registers"]] == ["ok", "ambiguous"]
    assert profiles[7] == ("4", "atv71") and profiles[8] == ("4", "atv71") and profiles[10] == ("4", "atv71")
    # slave 9's choice taken back: generic from its first frame, with the reason it was taken back
    assert {profiles[number] for number in (17, 18, 19, 20, 24)} == {("9", "generic")}
    assert frames[18]["profile_reason"] == "function 1 answered in frame #22, which the VW3 A3 303 does not support"
    assert frames[13]["function_name"] == "Read Parameter Information"
    assert "illegal number of registers to read" in frames[16]["notes"][0]
    assert [reg.get("status") for reg in frames[24]["registers"]] == [None, None, None]
    assert profiles[24] == ("9", "generic")
    # p.38 on a chosen slave: the statuses an exception 02 tells, listed as vw3-decode lists them.
    inferred = frames[34]["registers"]
    assert [(reg["address"], reg["value"], reg.get("code"), reg["status"], reg["text"]) for reg in inferred] == [
        (8400, None, None, "non-existent", "no value: exception 02"),
        (8401, None, "CHCF", "protected", "no value: exception 02"),
        (8402, None, "COP", "protected", "no value: exception 02"),
    ]
    # Settled slaves 13 and 14 stay generic although their last read fits.
    last_13 = max(number for number, (slave, _) in profiles.items() if slave == "13")
    last_14 = max(number for number, (slave, _) in profiles.items() if slave == "14")
    assert profiles[last_13][1] == "generic" and profiles[last_14][1] == "generic"
    assert "status" not in frames[last_14]["registers"][0]


def test_one_pass_is_vw3_decode_reading_a_stream(tmp_path: Path) -> None:
    # tshark without -2 (one pass) decides in capture order, as vw3-decode does reading standard input:
    # a slave's frames before its choice stay generic there; -2 (lane.again) names them as vw3-decode
    # reading the file does (test_auto_is_the_default_and_chooses_as_vw3_decode).
    records = evidence_session()
    pcap = write_pcap(tmp_path / "evidence.pcap", records)
    one, _, _ = lua_items(pcap, two_pass=False)
    stream = python_items(pcap, one_pass=True)
    differences = compare(stream, one, ignore=LATER)
    # (One pass shows the two SEL frames too: a code without a length rule is framed by a CRC scan, which a
    # record's end right after the frame settles, test_lua_one_pass_records.py; it waited for the next record.)
    sel = sorted(item.data["offset"] for item in stream if item.data.get("function") == 0x60)
    assert len(sel) == 2
    assert differences == []
    # (compare() holds vw3.provisional to vw3-decode's "provisional": frames read before their slave's choice)
    provisional = sorted(int(item.fields["item"]) for item in lua_shown(one) if item.fields.get("provisional") == "1")
    assert provisional == sorted(item.data["frame"] for item in stream if item.data.get("provisional"))
    assert provisional[:3] == [1, 2, 3] and len(provisional) > 10
    two_shown, _, _ = lua_items(pcap)
    assert not any(item.fields.get("provisional") for item in lua_shown(two_shown))  # -2: the file's view
    profiles = _profiles_by_item(one)
    assert profiles[2] == ("3", "generic") and profiles[4] == ("3", "atv71")  # the second read decides, for itself
    assert profiles[7] == ("4", "generic") and profiles[8] == ("4", "atv71")
    # -2 differs exactly where vw3-decode reading the file differs from reading the stream
    two, _, _ = lua_items(pcap)
    shown = [{item.fields["item"]: (item.fields.get("profile"), item.fields.get("profile_reason"), item.registers,
                                    item.texts.get("note")) for item in lua_shown(items)} for items in (one, two)]
    changed = {key for key in shown[0] if shown[0][key] != shown[1][key]}
    # ("provisional", said by vw3-decode reading a stream only, is compared by compare() itself)
    files = {item.data["frame"]: item.data for item in python_items(pcap)}
    streams = {item.data["frame"]: {key: value for key, value in item.data.items() if key != "provisional"}
               for item in stream}
    assert changed == {str(number) for number in streams if streams[number] != files[number]}
    assert {"2", "7", "17", "18", "19", "20"} <= changed


def test_auto_with_forced_slaves_and_plc_addresses(tmp_path: Path) -> None:
    # `--profile auto --profile 9=atv71 --profile 3=generic --address-style plc` = the same preferences.
    records = evidence_session() + SessionBuilder(seed=11).session(600, start_time=1767226000.0)
    pcap = write_pcap(tmp_path / "forced.pcap", records)
    python = python_items(pcap, ["auto", "9=atv71", "3=generic"], "--address-style", "plc")
    lua, record_experts, _ = lua_items(pcap, "-o", "vw3.profiles:auto,9=atv71,3=generic",
                                       "-o", "vw3.address_style:plc")
    differences = compare(python, lua)
    assert not differences, "\n".join(differences[:40])
    assert not any("Preferences" in text for _, text in record_experts)
    profiles = _profiles_by_item(lua)
    assert {profile for slave, profile in profiles.values() if slave == "9"} == {"atv71"}
    assert {profile for slave, profile in profiles.values() if slave == "3"} == {"generic"}
    labels = [reg.get("label") for item in python for reg in item.data.get("registers", [])]
    assert "48402" in labels  # CHCF of an ATV71 slave as a 4X reference
    assert lua_choices(lua) == [text for text in cli_choices(pcap, ["auto", "9=atv71", "3=generic"])
                                if not text.startswith(("slave 9:", "slave 3:"))]


def test_auto_preference_errors(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "one.pcap", evidence_session()[:2])
    _, record_experts, _ = lua_items(pcap, "-o", "vw3.profiles:12=auto,atv71,auto,12=sel749m,12=generic")
    texts = [text for _, text in record_experts]
    for phrase in ('"12=auto": auto is for every slave', '"auto": a default profile (atv71) is already set',
                   '"12=generic": slave 12 already has a profile'):
        assert any(phrase in text for text in texts), (phrase, texts)


def test_one_read_is_no_evidence_and_the_reason_is_on_every_frame(tmp_path: Path) -> None:
    """Issue 26: an iEM3255 energy meter (slave 1) polling its INT64 energy at 3203..3206, addresses the
    ATV71 map names FRH, LCR, OTR, ETI, stays generic however often it is polled; an Altivar read at
    two places is chosen at the second, and from then on each frame says which profile and why."""
    meter = _read(1, 3203, [0, 0, 1, 0xE240]) * 5
    drive = _read(2, 3202, [500, 7]) + _read(2, 8401, [3, 2]) + _read(2, 3202, [500, 7])
    records = [(data, 1767225600.0 + 0.02 * index) for index, data in enumerate(meter + drive)]
    pcap = write_pcap(tmp_path / "meter.pcap", records)
    python = python_items(pcap)
    lua, _, _ = lua_items(pcap)
    differences = compare(python, lua)
    assert not differences, "\n".join(differences[:40])
    reason = "traffic fits its map: function 3 at 3202..3203 in frame #12, function 3 at 8401..8402 in frame #14"
    # (-2, as vw3-decode reading the file: the drive's frames from its first; tshark's one pass names
    # them from the frame that decides, as vw3-decode reading a stream)
    assert [(item.fields.get("profile"), item.fields.get("profile_reason")) for item in lua_shown(lua)] == (
        [("generic", None)] * 10 + [("atv71", reason)] * 6)
    assert [(item.data.get("profile"), item.data.get("profile_reason")) for item in python] == (
        [("generic", None)] * 10 + [("atv71", reason)] * 6)
    one, _, _ = lua_items(pcap, two_pass=False)
    assert not compare(python_items(pcap, one_pass=True), one, ignore=LATER)
    assert [(item.fields.get("profile"), item.fields.get("profile_reason")) for item in lua_shown(one)] == (
        [("generic", None)] * 13 + [("atv71", reason)] * 3)
    assert [reg.get("code") for reg in python[9].data["registers"]] == [None, None, None, None]
    assert cli_choices(pcap, []) == [f"slave 2: atv71 ({reason})"]


# Wireshark's packet details opened while it captures: a record older than the newest dissected again.
# The capture so far is then decoded again with its choices (as tshark -2 shows a file), and the records
# that come after are read once, as vw3-decode --live reads them. Under the stub (lua/tests), Lua 5.2 and
# 5.4: records 1..HALF first, then record CLICKED again, then the others; each record shown at the end.
_LIVE_DRIVER = r'''
package.path = arg[1] .. "/?.lua;" .. package.path
local stub = require("wireshark_stub")
dofile(arg[2])
local proto = stub.protos.vw3
proto.set_pref("user0", true)
proto.prefs_changed()
proto.init()
local half, clicked, records = tonumber(arg[3]), tonumber(arg[4]), {}
for index = 5, #arg do
  records[#records + 1] = (arg[index]:gsub("%x%x", function(pair) return string.char(tonumber(pair, 16)) end))
end
local function dissect(number, visited)
  local tree = stub.tree()
  proto.dissector(stub.tvb(records[number]), stub.pinfo(number, visited, 1767225600 + number * 0.05), tree)
  return tree
end
for number = 1, #records do
  dissect(number, false)
  if number == half then dissect(clicked, true) end
end
for number = 1, #records do
  local shown = {}
  for _, line in ipairs(stub.dump(dissect(number, true))) do
    local key, value = line:match("^%s*vw3%.([a-z_]+)=(.*)$")
    if key == "item" or key == "provisional" then shown[#shown + 1] = key .. "=" .. value end
  end
  print(number .. " " .. table.concat(shown, " "))
end
'''


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_a_live_capture_goes_on_after_its_details_are_opened(tmp_path: Path, lua: str) -> None:
    # Slave 1 reads what no profile explains: its frames are provisional until its 8th answer (settled).
    records = [data for index in range(12) for data in _read(1, 100 + index, [index, 7])]
    driver = tmp_path / "live.lua"
    driver.write_text(_LIVE_DRIVER, encoding="utf-8")
    half, clicked = 8, 3
    result = subprocess.run([ensure_tool(lua, lua), str(driver), str(PLUGIN.parent / "tests"), str(PLUGIN), str(half),
                             str(clicked), *(data.hex() for data in records)], capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 0, result.stderr
    shown = {}
    for line in result.stdout.splitlines():
        number, *fields = line.split()
        shown[int(number)] = dict(field.split("=", 1) for field in fields)
    pcap = write_pcap(tmp_path / "live.pcap", [(data, 1767225600 + (index + 1) * 0.05) for index, data in
                                               enumerate(records)])
    stream = {item.data["frame"]: bool(item.data.get("provisional")) for item in python_items(pcap, one_pass=True)}
    assert [number for number, said in stream.items() if said] == list(range(1, 16))  # 8 requests, 7 answers
    # records 1..8, decoded again: the file's view (none provisional); 9.. read once, as vw3-decode --live
    assert [int(shown[number]["item"]) for number in shown] == list(range(1, 25))
    assert {number: shown[number].get("provisional") == "true" for number in shown} == {
        number: number > half and stream[number] for number in stream}


def test_one_pass_summary_says_provisional_where_vw3_decode_does(tmp_path: Path) -> None:
    # tshark's one pass without a tree (its plain summary) takes a request met before from the quick lanes'
    # entry, Info text included: an entry made while its slave was provisional said "[provisional]" on
    # every later request with those bytes (1,468 of 3,000 records here, where vw3-decode says 77).
    _raw, pcap = write_capture(generate_session(1650, seed=1)[:3000], tmp_path / "polling")
    summary = run_tshark(pcap, two_pass=False)
    assert summary.returncode == 0, summary.stderr[-3000:]
    shown = {int(line.split()[0]) for line in summary.stdout.splitlines() if "[provisional]" in line}
    stream = {item.record for item in python_items(pcap, one_pass=True) if item.data.get("provisional")}
    assert shown == stream and 50 < len(shown) < 200
