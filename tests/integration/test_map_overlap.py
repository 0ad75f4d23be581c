"""A --map row overlapping a row beneath it (a built-in row, or an earlier --map file's) hides it: the
user's file says what those registers are, so one register is named one way in every output. Before, a
user's 32-bit LCR2 at 3204 over the built-in ATV71 map showed 3205 as LCR2's second word in the summary and
--stats, and as OTR (15 %) beside LCR2 = 1.5 A in -V, --json, -T fields and the plugin; the same overlap
inside one file is a map error (maps.parse_map). Exact output for exact bytes, engine and
VW3_PURE_PYTHON=1; the plugin (tshark 4.0.17, -2) field by field as vw3-decode."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_compare import compare
from lua_harness import lua_items, python_items, run_tshark, write_pcap

from dissector.devices.maps import overlay, parse_map

pytestmark = pytest.mark.integration

HEADER = "address,code,name,unit,scale,type\n"
WIDE = HEADER + "3204,LCR2,Motor current 32,A,0.1,uint32\n"
R = "Read Holding Registers 3202..3205 (4)"


def _files(tmp_path: Path) -> tuple[Path, Path]:
    pcap = write_pcap(tmp_path / "ov.pcap", [(rtu("0C 03 0C82 0004"), 1700000000.0),
                                            (rtu("0C 03 08 0005 0006 0000 000F"), 1700000000.01)])
    wide = tmp_path / "ov.csv"
    wide.write_text(WIDE)
    return pcap, wide


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_user_row_hides_the_built_in_row_it_covers(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     pure: bool) -> None:
    use_engine(monkeypatch, pure)
    pcap, wide = _files(tmp_path)
    options = ["--profile", "atv71", "--map", f"atv71={wide}"]
    status, out, err = run_cli([str(pcap), *options])
    assert (status, out.splitlines(), err) == (0, [
        f"     1     0.000000  12 request   {R}  CRC ok",
        f"     2     0.010000  12 response  {R}: RFR=0.5 Hz FRH=0.6 Hz LCR2=1.5 A [#1, 10.0 ms]  CRC ok"], "")
    status, out, err = run_cli([str(pcap), *options, "-V"])
    assert status == 0 and err == ""
    lines = out.splitlines()
    at = lines.index("        Register 3205: 15 (0x000F)  LCR2 [Motor current 32]")
    assert lines[at + 1] == "            Value: second word of LCR2"
    assert "OTR" not in out
    status, out, err = run_cli([str(pcap), *options, "--json"])
    registers = json.loads(out.splitlines()[1])["registers"]
    assert [(r["address"], r.get("code"), r.get("text")) for r in registers] == [
        (3202, "RFR", "0.5 Hz"), (3203, "FRH", "0.6 Hz"), (3204, "LCR2", "1.5 A"), (3205, "LCR2", "second word of LCR2")]
    status, out, err = run_cli([str(pcap), *options, "-T", "fields", "-e", "code"])
    assert (status, out.splitlines(), err) == (0, ["", "RFR,FRH,LCR2,LCR2"], "")  # (a request: no code)


def test_a_later_map_hides_an_earlier_map_s_32_bit_row(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, False)
    pcap, wide = _files(tmp_path)
    single = tmp_path / "otr.csv"
    single.write_text(HEADER + "3205,OTR2,Torque again,%,1,\n")
    status, out, err = run_cli([str(pcap), "--profile", "atv71", "--map", f"atv71={wide}", "--map", f"atv71={single}"])
    # (3204 is then nobody's: the built-in LCR went with the first file, LCR2 with the second)
    assert (status, out.splitlines()[1], err) == (
        0, f"     2     0.010000  12 response  {R}: RFR=0.5 Hz FRH=0.6 Hz 3204=0 OTR2=15 % [#1, 10.0 ms]  CRC ok", "")


def test_overlay_rules() -> None:
    base = parse_map(HEADER + "10,A,a,,,\n11,B,b,,,\n20,W,w,,,uint32\n", "base")
    assert sorted(overlay(base, parse_map(WIDE.replace("3204", "10"), "user"))) == [10, 20]
    assert sorted(overlay(base, parse_map(HEADER + "21,C,c,,,\n", "user"))) == [10, 11, 21]
    assert sorted(overlay(base, parse_map(HEADER + "19,C,c,,,uint32\n", "user"))) == [10, 11, 19]
    assert sorted(base) == [10, 11, 20]  # (a new map: the base is shared by every device)


def test_plugin_names_the_overlap_as_vw3_decode(tmp_path: Path) -> None:
    pcap, wide = _files(tmp_path)
    got = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-o", f"vw3.maps:atv71={wide}", "-T", "fields",
                     "-e", "vw3.reg.code")
    assert got.stdout.splitlines() == ["", "RFR,FRH,LCR2,LCR2"]
    lua, _, _ = lua_items(pcap, "-o", "vw3.profiles:atv71", "-o", f"vw3.maps:atv71={wide}")
    differences = compare(python_items(pcap, ["atv71"], "--map", f"atv71={wide}"), lua)
    assert not differences, "\n".join(differences[:40])
