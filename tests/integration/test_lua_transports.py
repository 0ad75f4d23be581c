"""The plugin's other ways in: RTU over a TCP port, RTAC serial records (Decode As), and the post-dissector
that names the registers of Wireshark's own Modbus/TCP dissection."""
from __future__ import annotations

import struct
from pathlib import Path

from dissector.render.pcapwriter import LINKTYPE_RTAC_SERIAL, PcapWriter
from lua_harness import PLUGIN, lua_items, run_tshark
from lua_net import NetWriter
from seed_frames import SCENARIO_1, SCENARIO_2, SCENARIO_REQUEST

# The ATV71 named: one answer is no evidence for profile auto (issue 26), and these captures have one.
ATV71 = ("-o", "vw3.profiles:atv71")


def _fields(pcap: Path, *args: str) -> list[list[str]]:
    result = run_tshark(pcap, *args, "-T", "fields", "-E", "separator=|", "-e", "vw3.kind",
                        "-e", "vw3.request_frame", "-e", "vw3.reg.code", "-e", "vw3.reg.status")
    assert result.returncode == 0, result.stderr
    return [line.split("|") for line in result.stdout.splitlines()]


def test_rtu_over_tcp_port_preference_and_decode_as(tmp_path: Path) -> None:
    writer = NetWriter(tmp_path / "rtu-tcp.pcap")
    writer.tcp(True, 40000, 5020, SCENARIO_REQUEST, 1.0)
    writer.tcp(False, 40000, 5020, SCENARIO_1, 1.01)
    writer.close()
    # (the kind is an integer with value strings: 1 request, 2 response; the status text, as vw3-decode's)
    expected = [["1", "", "", ""], ["2", "1", ",CHCF,COP", "non-existent,ok,ok"]]
    assert _fields(tmp_path / "rtu-tcp.pcap", "-o", "vw3.tcp_port:5020", *ATV71) == expected
    assert _fields(tmp_path / "rtu-tcp.pcap", "-d", "tcp.port==5020,vw3", *ATV71) == expected
    # Without either, the port is not ours.
    assert _fields(tmp_path / "rtu-tcp.pcap") == [["", "", "", ""], ["", "", "", ""]]


def test_rtac_serial_decode_as(tmp_path: Path) -> None:
    pcap = tmp_path / "rtac.pcap"
    with pcap.open("wb") as stream:
        writer = PcapWriter(stream, linktype=LINKTYPE_RTAC_SERIAL)
        for index, frame in enumerate([SCENARIO_REQUEST, SCENARIO_2]):
            header = struct.pack(">IIBBH", 100, index * 10_000, 0, 0, 0)
            writer.write(header + frame, 100 + index * 0.01)
    rows = _fields(pcap, "-d", "rtacser.data,vw3", *ATV71)
    assert rows == [["1", "", "", ""], ["2", "1", ",CHCF,COP", "non-existent,protected,ok"]]
    items, _, _ = lua_items(pcap, "-d", "rtacser.data,vw3")
    assert [(item.record, item.offset) for item in items] == [(1, 12), (2, 12)]


def test_modbus_tcp_registers_are_named(tmp_path: Path) -> None:
    writer = NetWriter(tmp_path / "mbtcp.pcap")
    pairs = [
        (bytes.fromhex("0320D00003"), bytes.fromhex("0306 8000 0003 0002")),
        (bytes.fromhex("0320D00003"), bytes.fromhex("0306 8000 8000 0002")),
        (bytes.fromhex("030C1E0004"), bytes.fromhex("0308 0028 0258 01F4 0000")),
    ]
    time = 1.0
    for transaction, (request, response) in enumerate(pairs, start=1):
        for to_server, pdu in ((True, request), (False, response)):
            writer.tcp(to_server, 40000, 502, struct.pack("!HHHB", transaction, 0, len(pdu) + 1, 0) + pdu, time)
            time += 0.01
    writer.close()
    names = ("-X", f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}")
    result = run_tshark(tmp_path / "mbtcp.pcap", *names, *ATV71, "-T", "fields", "-E", "separator=|", "-e", "modbus.regnum16",
                        "-e", "vw3.reg.code", "-e", "vw3.reg.status", "-e", "vw3.reg.text", "-e", "vw3.note")
    assert result.returncode == 0, result.stderr
    rows = [line.split("|") for line in result.stdout.splitlines()]
    assert rows[1] == ["8400,8401,8402", ",CHCF,COP", "non-existent,ok,ok",
                       "16#8000: non-existent (address not in the map),IO (I/O profile),Cd (command)", ""]
    assert rows[3][:3] == ["8400,8401,8402", ",CHCF,COP", "non-existent,protected,ok"]
    assert rows[3][4] == "CHCF (8401) became protected: read 3 in frame #2, 16#8000 now"
    assert rows[5][:4] == ["3102,3103,3104,3105", "SFR,TFR,HSP,LSP", "ok,ok,ok,ok",
                           "4.0 kHz,60.0 Hz,50.0 Hz,0.0 Hz"]
    off = run_tshark(tmp_path / "mbtcp.pcap", *names, "-o", "vw3names.enabled:FALSE", "-T", "fields",
                     "-e", "vw3.reg.code")
    assert off.stdout.split() == []
    # Without the optional file, nothing is named (and serial captures build no tree for it).
    alone = run_tshark(tmp_path / "mbtcp.pcap", "-T", "fields", "-e", "vw3.reg.code")
    assert alone.returncode == 0 and alone.stdout.split() == []


def test_installed_by_copying_into_the_personal_plugins_folder(tmp_path: Path) -> None:
    # Wireshark loads every .lua file of ~/.local/lib/wireshark/plugins (Linux, macOS) at start.
    import shutil
    import subprocess

    from lua_harness import PLUGIN, ROOT, ensure_tool

    folder = tmp_path / ".local" / "lib" / "wireshark" / "plugins"
    folder.mkdir(parents=True)
    shutil.copy(PLUGIN, folder / "vw3.lua")
    shutil.copy(PLUGIN.parent / "vw3_modbus.lua", folder / "vw3_modbus.lua")
    # What Preferences > Protocols > DLT_USER writes when USER0 (linktype 147) is mapped to vw3.
    config = tmp_path / ".config" / "wireshark"
    config.mkdir(parents=True)
    (config / "user_dlts").write_text('"User 0 (DLT=147)","vw3","0","","0",""\n')
    tshark = ensure_tool("tshark", "tshark")
    env = {"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"}
    plugins = subprocess.run([tshark, "-G", "plugins"], capture_output=True, text=True, env=env)
    listed = [line.split("\t") for line in plugins.stdout.splitlines() if line.startswith("vw3")]
    assert [[part.strip() for part in line] for line in listed] == [
        ["vw3.lua", "1.0.0", "lua script", str(folder / "vw3.lua")],
        ["vw3_modbus.lua", "1.0.0", "lua script", str(folder / "vw3_modbus.lua")],
    ]
    capture = ROOT / "captures" / "p38_protection.pcap"
    result = subprocess.run([tshark, "-n", "-r", str(capture)], capture_output=True, text=True, env=env)
    # (one pass: slave 12's device is chosen at frame 4, so frame 2 is provisional, as vw3-decode on stdin)
    assert result.stdout.splitlines()[1].split("→")[1].split() == [
        "VW3", "11", "12", "Read", "Holding", "Registers", "response", "8400..8402", "(3)", "[provisional]"
    ]
