"""The plugin tells a map written in PLC references as vw3-decode does (test_map_references.py): the
same note, on the same frame, an expert info (Comment) in Wireshark's expert view; in tshark's two passes
and its one pass, through the quick lanes (a polling slave's frames after its judged ones) and not; a
correct map, a SunSpec map read at 40000+ and a map matching no offset get none. Exact bytes; every item
field by field as vw3-decode's --json (lua_compare)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli
from lua_compare import compare
from lua_harness import PLUGIN, lua_errors, lua_items, python_items, run_tshark, write_pcap
from lua_net import write_modbus_tcp_pairs

pytestmark = pytest.mark.integration

READ = ["01 03 0000 0004", "01 03 08 0193 01B8 01DC 0202"]  # slave 1 reads 0..3: 403 440 476 514


def _pcap(tmp_path: Path, frames: list[str]) -> Path:
    return write_pcap(tmp_path / "r.pcap", [(rtu(frame), 1767225600.0 + index * 0.02)
                                            for index, frame in enumerate(frames)])


def _notes(items: list) -> list[tuple[int, list[str]]]:
    return [(index + 1, item.texts["note"]) for index, item in enumerate(items) if item.texts.get("note")]


@pytest.mark.parametrize("two_pass", [True, False], ids=["two", "one"])
def test_plugin_notes_a_4x_map_as_vw3_decode(tmp_path: Path, two_pass: bool) -> None:
    pcap = _pcap(tmp_path, READ * 20 + ["01 04 0064 0002", "01 04 04 00FA 00FD"])  # (40 frames: the lanes after 32)
    path = tmp_path / "m.csv"
    path.write_text("address,code\n40001,IA\n40002,IB\n")
    options = ("-o", "vw3.profiles:generic", "-o", f"vw3.maps:{path}")
    lua, _, _ = lua_items(pcap, *options, two_pass=two_pass)
    said = (f"map {path} names 2 of the 4 unnamed registers slave 1 reads or writes at address + 40001: PLC "
            "references? A map takes protocol addresses (reference - 40001) or a reference column")
    assert _notes(lua) == [(2, [said])]
    # (its expert info: Wireshark cuts an item's label at 240 bytes, its end included; a long path is cut)
    assert ("vw3.expert.note", said.encode()[:239].decode()) in lua[1].experts
    # (one pass: a request's answer is not known yet when it is shown, as in test_lua_modules)
    ignore = frozenset() if two_pass else frozenset(["response_frame", "unanswered"])
    differences = compare(python_items(pcap, ["generic"], "--map", str(path), one_pass=not two_pass), lua, ignore)
    assert not differences, "\n".join(differences[:40])


@pytest.mark.parametrize("rows, frames", [
    ("reference\n40001,IA\n400002,IB\n30101,T1\n",  # a reference column: names them, no note
     READ + ["01 04 0064 0002", "01 04 04 00FA 00FD"]),
    ("0,IA\n1,IB\n", READ),  # protocol addresses
    ("40101,VAB\n40102,VBC\n", READ),  # no offset matches
    ("40000,SID\n40001,SID2\n40002,ID\n40003,L\n",  # SunSpec, read at its addresses
     ["02 03 9C40 0006", "02 03 0C 5375 6E53 0001 0042 0000 0000"]),
], ids=["reference-column", "protocol", "no-offset", "sunspec"])
def test_plugin_says_nothing_of_a_map_the_traffic_does_not_show_in_references(
        tmp_path: Path, rows: str, frames: list[str]) -> None:
    pcap = _pcap(tmp_path, frames)
    path = tmp_path / "m.csv"
    path.write_text(rows.replace("reference\n", "reference,code\n") if rows.startswith("reference") else
                    "address,code\n" + rows)
    lua, _, _ = lua_items(pcap, "-o", "vw3.profiles:generic", "-o", f"vw3.maps:{path}")
    assert _notes(lua) == []
    differences = compare(python_items(pcap, ["generic"], "--map", str(path)), lua)
    assert not differences, "\n".join(differences[:40])


def test_plugin_refuses_a_bad_reference_as_vw3_decode(tmp_path: Path) -> None:
    from test_map_references import BAD_REFERENCES

    paths = []
    for number, text in enumerate(BAD_REFERENCES):
        folder = tmp_path / str(number)
        folder.mkdir()
        (folder / "map.csv").write_text(text)
        paths.append(folder)
    _, record_experts, _ = lua_items(_pcap(tmp_path, READ), "-o", "vw3.maps:" + ";".join(
        str(folder / "map.csv") for folder in paths))
    experts = {text for _, text in record_experts}
    for folder, message in zip(paths, BAD_REFERENCES.values()):
        assert any(expert.endswith(f"{folder}/{message}") for expert in experts), (message, experts)


@pytest.mark.parametrize("two_pass", [True, False], ids=["two", "one"])
def test_modbus_tcp_plugin_notes_a_4x_map_too(tmp_path: Path, two_pass: bool) -> None:
    """lua/vw3_modbus.lua (names in Wireshark's Modbus/TCP dissector) annotates by the serial plugin's path:
    the same note on the first answer, as vw3-decode gives it for the same PDUs over RTU."""
    pcap = write_modbus_tcp_pairs(tmp_path / "t.pcap", [("0300000004", "0308019301B801DC0202")] * 3, unit=1)
    path = tmp_path / "m.csv"
    path.write_text("address,code\n40001,IA\n40002,IB\n")
    done = run_tshark(pcap, "-X", f"lua_script:{PLUGIN.parent / 'vw3_modbus.lua'}", "-o", "vw3.profiles:generic",
                      "-o", f"vw3.maps:{path}", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                      "-e", "vw3.note", two_pass=two_pass)
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr), done.stderr
    said = (f"map {path} names 2 of the 4 unnamed registers slave 1 reads or writes at address + 40001: PLC "
            "references? A map takes protocol addresses (reference - 40001) or a reference column")
    assert done.stdout.splitlines() == ["1|", f"2|{said}", "3|", "4|", "5|", "6|"]
    capture = tmp_path / "t.bin"
    capture.write_bytes(b"".join(rtu("01" + pdu) for pdu in ["0300000004", "0308019301B801DC0202"] * 3))
    status, out, _err = run_cli([str(capture), "--profile", "generic", "--map", str(path), "--json"])
    assert [json.loads(line)["notes"] for line in out.splitlines()][1] == [said]
