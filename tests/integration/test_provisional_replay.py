"""Reading once (standard input, live, tshark without -2), profile `auto`'s device annotates the slave's
provisional frames again when it is chosen (annotator.py _observe, the plugin's device_now): it remembers
of them what it would have remembered known from the first, so the choosing frame tells what a file decode
(two passes) tells. Each path of that memory: several slaves, confirmed writes (FC6 echo, FC16 answer,
FC23's write), an exception 02 to a read (then `readable again`), a bits_depend layout, a damaged frame;
vw3-decode (engine and VW3_PURE_PYTHON=1) and the plugin (one pass and -2, one frame a record or a
stream cut across records, Modbus/TCP through vw3_modbus.lua)."""
from __future__ import annotations

import struct
import subprocess
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import PLUGIN, ensure_tool, lua_items, run_tshark, write_pcap
from lua_net import NetWriter

READ = rtu("0C 03 20D0 0003")  # 8400..8402: 8400 is in no map of the ATV71 (its 16#8000 is evidence)
PREFIX = "            -  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent "
# 8400..8413, FR1 (8413) read as 1: not every value 16#8000 (that answer keeps each one ambiguous, p.38)
READ14 = rtu("0C 03 20D0 000E")
ANSWER14 = rtu("0C 03 1C" + " 8000" * 13 + " 0001")
PREFIX14 = "            -  12 response  Read Holding Registers 8400..8413 (14): 8400=non-existent "
REST14 = "8403=non-existent 8404=non-existent 8405=non-existent … (+8)"
# name -> (frames, the frame that makes profile auto choose, its summary line)
CASES = {
    "two_slaves": (
        [READ, rtu("0C 03 06 8000 0003 0002"), rtu("0D 03 20D0 0003"), rtu("0D 03 06 8000 0005 0001"),
         READ, rtu("0C 03 06 8000 8000 0002"), rtu("0D 03 20D0 0003"), rtu("0D 03 06 8000 0005 8000")],
        8,
        "     8            -  13 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=5 (not a "
        "listed value) COP=protected [#7] [COP (8402) became protected: read 1 in frame #4, 16#8000 now]  CRC ok",
    ),
    "writes": (
        [rtu("0C 06 20D1 0003"), rtu("0C 06 20D1 0003"), rtu("0C 10 20D2 0001 02 0002"), rtu("0C 10 20D2 0001"),
         READ14, ANSWER14],
        6,
        f"     6{PREFIX14}CHCF=protected COP=protected {REST14} [#5] [CHCF (8401) became protected: written 3 in frame #2, "
        "16#8000 now] [COP (8402) became protected: written 2 in frame #4, 16#8000 now]  CRC ok",
    ),
    "fc23": (  # FC23 writes COP (8402) and reads 8400..8401
        [rtu("0C 17 20D0 0002 20D2 0001 02 0002"), rtu("0C 17 04 8000 0003"), READ14, ANSWER14],
        4,
        f"     4{PREFIX14}CHCF=protected COP=protected {REST14} [#3] [CHCF (8401) became protected: read 3 in frame #2, "
        "16#8000 now] [COP (8402) became protected: written 2 in frame #2, 16#8000 now]  CRC ok",
    ),
    "exception": (  # exception 02: every parameter of the read of 8401..8402 unreadable (p.38)
        [READ, rtu("0C 03 06 8000 0003 0002"), rtu("0C 03 20D1 0002"), rtu("0C 83 02"),
         READ, rtu("0C 03 06 8000 0003 0002")],
        6,
        f"     6{PREFIX}CHCF=IO (I/O profile) COP=Cd (command) [#5] [8401..8402 readable again (2): protected in "
        "frame #4]  CRC ok",
    ),
    "depend": (  # CHCF = 3 read before the choice: CMD (8501) has its plain layout
        [READ, rtu("0C 03 06 8000 0003 0002"), rtu("0C 03 2134 0002"), rtu("0C 03 04 8000 0003")],
        4,
        "     4            -  12 response  Read Holding Registers 8500..8501 (2): 8500=non-existent CMD=3 [#3] "
        "[CHCF = 3 (I/O profile): CMD bits are assigned by configuration]  CRC ok",
    ),
    "damaged": (  # a frame with a bad CRC is decoded, not remembered: the device ignored it (de21138)
        [READ, rtu("0C 03 06 8000 0005 0002"), READ, rtu("0C 03 06 8000 0003 0002")[:-2] + b"\xff\xff",
         READ, rtu("0C 03 06 8000 8000 0002")],
        6,
        f"     6{PREFIX}CHCF=protected COP=Cd (command) [#5] [CHCF (8401) became protected: read 5 in frame #2, "
        "16#8000 now]  CRC ok",
    ),
}

PROVISIONAL = {"two_slaves": 6, "writes": 5, "fc23": 3, "exception": 5, "depend": 3, "damaged": 5}


def _notes(line: str) -> list[str]:
    """The notes of a summary line, as the plugin's vw3.note gives them."""
    parts = [part.split("]")[0] for part in line.split(" [")[1:]]
    return [part for part in parts if not part.startswith("#") and part != "provisional"]


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("name", sorted(CASES))
def test_vw3_decode_reading_once_tells_what_the_file_decode_tells(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, name: str, pure: bool
) -> None:
    use_engine(monkeypatch, pure)
    frames, choosing, line = CASES[name]
    data = b"".join(frames)
    status, one, err = run_cli(["-"], stdin=data)
    assert status == 0, err
    lines = one.splitlines()
    assert lines[choosing - 1] == line
    # (the frames before the choice were named provisionally: the device chosen annotated them again)
    assert sum("[provisional]" in text for text in lines) == PROVISIONAL[name]
    path = tmp_path / "capture.bin"
    path.write_bytes(data)
    status, two, err = run_cli([str(path)])
    assert status == 0, err
    assert two.splitlines()[choosing - 1] == line


@pytest.mark.parametrize("name", sorted(CASES))
def test_plugin_one_pass_and_two_passes(tmp_path: Path, name: str) -> None:
    frames, choosing, line = CASES[name]
    pcap = write_pcap(tmp_path / f"{name}.pcap", [(frame, 1.0 + 0.05 * index) for index, frame in enumerate(frames)])
    for two_pass in (False, True):
        done = run_tshark(pcap, "-T", "fields", "-E", "aggregator=^", "-e", "vw3.note", two_pass=two_pass)
        assert done.returncode == 0, done.stderr
        rows = done.stdout.splitlines()
        assert rows[choosing - 1].split("^") == _notes(line), two_pass
        if not two_pass:  # every frame's notes as vw3-decode's, reading once
            _status, one, _err = run_cli(["-"], stdin=b"".join(frames))
            assert rows == ["^".join(_notes(text)) for text in one.splitlines()]


@pytest.mark.parametrize("name", ["writes", "fc23", "two_slaves"])
def test_plugin_one_pass_stream_across_records(tmp_path: Path, name: str) -> None:
    """Frames cut across records: the copies keep the bytes of their runs (a request's too) once the
    frames' own are released."""
    frames, _choosing, line = CASES[name]
    data = b"".join(frames)
    records = [(data[at:at + 7], 1.0 + 0.001 * at) for at in range(0, len(data), 7)]
    pcap = write_pcap(tmp_path / f"{name}-cut.pcap", records)
    items, _, _ = lua_items(pcap, two_pass=False)
    told = [item.texts["note"] for item in items if item.texts.get("note")]
    if name == "two_slaves":  # (slave 12 chose on frame 6)
        assert told == [["CHCF (8401) became protected: read 3 in frame #2, 16#8000 now"], _notes(line)]
    else:
        assert told == [_notes(line)]


# The plugin's pure part under plain Lua (no Wireshark): records fed one frame each, read once.
LUA_RUNNER = """
local vw3 = dofile(arg[1])
vw3.configure("", nil, "")
local st, records, frames = vw3.new_state(nil, "rtu"), {}, {}
for line in io.lines(arg[2]) do
  local bytes = line:gsub("%x%x", function(h) return string.char(tonumber(h, 16)) end)
  records[#records + 1] = vw3.dissect_record(st, bytes, nil, #records + 1)
end
vw3.finish(st) -- (the end of the input: what waits is framed, in the last record)
for _, record in ipairs(records) do
  for _, f in ipairs(record) do frames[#frames + 1] = f end
end
table.sort(frames, function(a, b) return a.number < b.number end)
for _, f in ipairs(frames) do print(table.concat(f.notes or {}, "^")) end
"""


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
@pytest.mark.parametrize("name", sorted(CASES))
def test_plain_lua_reading_once(tmp_path: Path, lua: str, name: str) -> None:
    frames, choosing, line = CASES[name]
    (tmp_path / "runner.lua").write_text(LUA_RUNNER, encoding="utf-8")
    (tmp_path / "frames.txt").write_text("".join(frame.hex() + "\n" for frame in frames), encoding="ascii")
    done = subprocess.run([ensure_tool(lua, lua), str(tmp_path / "runner.lua"), str(PLUGIN), str(tmp_path / "frames.txt")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    rows = done.stdout.splitlines()
    assert len(rows) == len(frames)
    assert rows[choosing - 1].split("^") == _notes(line)


TCP_CASES = {
    # the second answer chooses the ATV71 and says CHCF became protected
    "read": ([("0320D00003", "0306 8000 0003 0002"), ("0320D00003", "0306 8000 8000 0002")],
             ["||", ",,|,,|", "||",
              ",CHCF,COP|non-existent,protected,ok|CHCF (8401) became protected: read 3 in frame #2, 16#8000 now"]),
    # an exception 02 before the choice (vw3_modbus.lua explains it with explain_exception): readable again
    "exception": ([("0320D00003", "0306 8000 0003 0002"), ("0320D10002", "8302"), ("0320D00003", "0306 8000 0003 0002")],
                  ["||", ",,|,,|", "||", "||", "||",
                   ",CHCF,COP|non-existent,ok,ok|8401..8402 readable again (2): protected in frame #4"]),
}


@pytest.mark.parametrize("name", sorted(TCP_CASES))
def test_modbus_tcp_names_reading_once(tmp_path: Path, name: str) -> None:
    """vw3_modbus.lua's frames are annotated again by the RTU plugin's path (annotate_with: their registers a
    run over bytes of their own), an exception by explain_exception."""
    pairs, expected = TCP_CASES[name]
    writer = NetWriter(tmp_path / "mbtcp.pcap")
    time = 1.0
    for transaction, (request, response) in enumerate(pairs, start=1):
        for to_server, pdu in ((True, bytes.fromhex(request)), (False, bytes.fromhex(response))):
            writer.tcp(to_server, 40000, 502, struct.pack("!HHHB", transaction, 0, len(pdu) + 1, 12) + pdu, time)
            time += 0.01
    writer.close()
    names = ("-X", f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}")
    for two_pass in (False, True):
        done = run_tshark(tmp_path / "mbtcp.pcap", *names, "-T", "fields", "-E", "separator=|", "-e", "vw3.reg.code",
                          "-e", "vw3.reg.status", "-e", "vw3.note", two_pass=two_pass)
        assert done.returncode == 0, done.stderr
        assert done.stdout.splitlines() == expected, two_pass
