"""FC12 (Get Comm Event Log): each event byte is named in -V and --json (the NDJSON key fields -> event_list), as Wireshark's
modbus dissector names them (Application Protocol 6.13; names from data/modbus.toml [names.comm_event*]): a
receive event (bit 7) or a send event (bit 6) with the bits it sets, 0x04 entered listen only mode, 0x00
communication restart, any other byte unknown. Before, the events were their bytes' hex only
(`Events: 200004c27f80`). Compared with tshark's own Modbus/TCP decoding of the same PDU (an MBAP header in a
pcap made by text2pcap)."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from helpers import rtu, run_cli

PDU = "0C 0C FFFF 0108 0121 20 00 04 C2 7F 80"  # 6 events, newest first

EVENT_LINES = """\
        Events: 200004c27f80
        Event list (6)
            [0]
                Byte: 32 (0x20)
                Event: Unknown Event
            [1]
                Byte: 0 (0x0)
                Event: Initiated Communication Restart
            [2]
                Byte: 4 (0x4)
                Event: Entered Listen Only Mode
            [3]
                Byte: 194 (0xC2)
                Event: Receive Event
                Flags
                    .... ..1. = Communication Error: 1
                    ...0 .... = Character Overrun: 0
                    ..0. .... = Currently in Listen Only Mode: 0
                    .1.. .... = Broadcast Received: 1
            [4]
                Byte: 127 (0x7F)
                Event: Send Event
                Flags
                    .... ...1 = Read Exception Sent: 1
                    .... ..1. = Slave Abort Exception Sent: 1
                    .... .1.. = Slave Busy Exception Sent: 1
                    .... 1... = Slave Program NAK Exception Sent: 1
                    ...1 .... = Write Timeout Error Occurred: 1
                    ..1. .... = Currently in Listen Only Mode: 1
            [5]
                Byte: 128 (0x80)
                Event: Receive Event
                Flags
                    .... ..0. = Communication Error: 0
                    ...0 .... = Character Overrun: 0
                    ..0. .... = Currently in Listen Only Mode: 0
                    .0.. .... = Broadcast Received: 0
        CRC: """

EVENTS = [
    {"byte": 0x20, "event": "Unknown Event"},
    {"byte": 0x00, "event": "Initiated Communication Restart"},
    {"byte": 0x04, "event": "Entered Listen Only Mode"},
    {"byte": 0xC2, "event": "Receive Event", "flags": ["Communication Error", "Broadcast Received"]},
    {"byte": 0x7F, "event": "Send Event", "flags": [
        "Read Exception Sent", "Slave Abort Exception Sent", "Slave Busy Exception Sent",
        "Slave Program NAK Exception Sent", "Write Timeout Error Occurred", "Currently in Listen Only Mode"]},
    {"byte": 0x80, "event": "Receive Event", "flags": []},
]


def _capture(tmp_path: Path) -> Path:
    capture = tmp_path / "fc12.bin"
    capture.write_bytes(rtu("01 0C") + rtu("01 " + PDU))
    return capture


def test_detail_names_each_event(tmp_path: Path) -> None:
    code, out, err = run_cli(["-n", "-V", str(_capture(tmp_path))])
    assert code == 0, err
    assert EVENT_LINES in out


def test_json_lists_each_event(tmp_path: Path) -> None:
    code, out, err = run_cli(["-n", "--json", str(_capture(tmp_path))])
    assert code == 0, err
    fields = json.loads(out.splitlines()[1])["fields"]
    assert fields["events"] == "200004c27f80"
    assert fields["event_list"] == EVENTS


def test_no_events_no_list(tmp_path: Path) -> None:
    capture = tmp_path / "empty.bin"
    capture.write_bytes(rtu("01 0C") + rtu("01 0C 06 0000 0000 0000"))
    assert "event_list" not in json.loads(run_cli(["-n", "--json", str(capture)])[1].splitlines()[1])["fields"]


def _tshark_events(tmp_path: Path) -> list[dict[str, object]]:
    """tshark's decoding of the PDU behind an MBAP header (Modbus/TCP, port 502): each event's name and the
    bits it says are 1."""
    pdu = bytes.fromhex(PDU.replace(" ", ""))
    packets = [(bytes.fromhex("0001 0000 0002 01 0C".replace(" ", "")), "50000,502"),
               (bytes.fromhex("0001 0000".replace(" ", "")) + (len(pdu) + 1).to_bytes(2, "big") + b"\x01" + pdu,
                "502,50000")]
    pcaps = []
    for index, (data, ports) in enumerate(packets):
        text = tmp_path / f"p{index}.txt"
        text.write_text("000000 " + " ".join(f"{byte:02x}" for byte in data) + "\n")
        pcaps.append(tmp_path / f"p{index}.pcap")
        subprocess.run(["text2pcap", "-q", "-T", ports, str(text), str(pcaps[-1])], check=True, timeout=60)
    merged = tmp_path / "fc12.pcap"
    subprocess.run(["mergecap", "-a", "-w", str(merged), *map(str, pcaps)], check=True, timeout=60)
    tree = subprocess.run(["tshark", "-r", str(merged), "-Y", "frame.number == 2", "-O", "modbus", "-V"],
                          capture_output=True, text=True, check=True, timeout=60).stdout
    events: list[dict[str, object]] = []
    for line in tree[tree.index("    Events\n"):].splitlines()[1:]:
        if line.startswith("        ") and not line.startswith("         "):
            name = re.sub(r": 0x[0-9A-F]{2}$", "", line.strip())
            events.append({"event": name, "flags": [], "bits": []})
        elif line.startswith("            ") and events:
            events[-1]["bits"].append(line.strip())  # type: ignore[union-attr]
            flag, value = re.match(r".* = (.*): (\d)$", line).groups()
            if value == "1":
                events[-1]["flags"].append(flag)  # type: ignore[union-attr]
        else:
            break
    return events


@pytest.mark.skipif(not all(map(shutil.which, ("tshark", "text2pcap", "mergecap"))), reason="no tshark")
def test_names_as_tsharks(tmp_path: Path) -> None:
    said = json.loads(run_cli(["-n", "--json", str(_capture(tmp_path))])[1].splitlines()[1])["fields"]
    ours = [{"event": event["event"], "flags": event.get("flags", [])} for event in said.get("event_list", [])]
    assert [{"event": event["event"], "flags": event["flags"]} for event in _tshark_events(tmp_path)] == ours


@pytest.mark.skipif(not all(map(shutil.which, ("tshark", "text2pcap", "mergecap"))), reason="no tshark")
def test_flag_bits_as_tsharks(tmp_path: Path) -> None:
    """-V lists each bit of a receive or send event, set or not, in tshark -V's words: a receive event of no
    flag (0x80) its four bits each 0, where it said `Flags (0)` alone before."""
    out = run_cli(["-n", "-V", str(_capture(tmp_path))])[1].splitlines()
    ours: list[list[str]] = []
    for index, line in enumerate(out):
        if line.strip().startswith("Event: "):
            ours.append([])
        elif line.strip() == "Flags":
            depth = len(line) - len(line.lstrip())
            for inner in out[index + 1:]:
                if len(inner) - len(inner.lstrip()) <= depth:
                    break
                ours[-1].append(inner.strip())
    theirs = [event["bits"] for event in _tshark_events(tmp_path)]
    assert theirs[5] == [".... ..0. = Communication Error: 0", "...0 .... = Character Overrun: 0",
                         "..0. .... = Currently in Listen Only Mode: 0", ".0.. .... = Broadcast Received: 0"]
    assert ours == theirs
