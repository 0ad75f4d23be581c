"""A --map written in PLC references (40001 for register 0, as the SEL-749M manual and PLC manuals tell
users to add) named nothing the bus read, and nothing said why: every register stayed a bare number. Now
the traffic tells it (devices/maps_refs.py): where a slave reads or writes registers no map names and the
map names more of them at address + the PLC base of their function (40001, FC4 30001; or one less) than
at their address, the deciding frame gets a note, once per map and slave. A map whose addresses really
are 40000 and up (SunSpec) read there, a correct map, and a map that matches the traffic at no offset get
none. A map may say it is written in references: a `reference` column in place of `address` (40001 is
address 0; 3X 30001; six digits 400001), its bad cells refused in one line. Exact bytes, exact texts, the
compiled engine and VW3_PURE_PYTHON=1 alike."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import run_cli, use_engine, write_rtu

from dissector.devices.build import build_annotator
from dissector.pipeline import dissect_bytes
from helpers import rtu

pytestmark = pytest.mark.integration

READ = ["01 03 0000 0004", "01 03 08 0193 01B8 01DC 0202"]  # slave 1 reads 0..3: 403 440 476 514
REQUEST = "     1            -   1 request   Read Holding Registers 0..3 (4)  CRC ok"
ANSWER = "     2            -   1 response  Read Holding Registers 0..3 (4): "


COLUMN = " or a reference column"  # (where the rows are the references themselves, in a map without that column)


def note(path: Path, unnamed: int, shifted: int, offset: str, slave: int = 1, column: str = COLUMN) -> str:
    return (f"map {path} names {shifted} of the {unnamed} unnamed registers slave {slave} reads or writes at "
            f"address + {offset}: PLC references? A map takes protocol addresses (reference - {offset}){column}")


def _map(tmp_path: Path, rows: str, name: str = "m.csv") -> Path:
    path = tmp_path / name
    path.write_text("address,code,name,unit\n" + rows)
    return path


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_4x_map_is_told_on_the_frame_that_shows_it(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = write_rtu(tmp_path / "r.bin", READ)
    path = _map(tmp_path, "40001,IA,Phase A current,A\n40002,IB,Phase B current,A\n")
    status, out, _err = run_cli([str(capture), "--profile", "generic", "--map", str(path)])
    assert status == 0
    assert out.splitlines() == [REQUEST, ANSWER + f"0=403 1=440 2=476 3=514 [#1] [{note(path, 4, 2, '40001')}]  CRC ok"]
    status, out, _err = run_cli([str(capture), "--profile", "generic", "--map", str(path), "--json"])
    assert json.loads(out.splitlines()[1])["notes"] == [note(path, 4, 2, "40001")]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_map_of_protocol_addresses_gets_no_hint(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                  pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = write_rtu(tmp_path / "r.bin", READ)
    path = _map(tmp_path, "0,IA,Phase A current,A\n1,IB,Phase B current,A\n")
    status, out, err = run_cli([str(capture), "--profile", "generic", "--map", str(path)])
    assert (status, out.splitlines(), err) == (0, [REQUEST, ANSWER + "IA=403 A IB=440 A 2=476 3=514 [#1]  CRC ok"], "")


def test_a_sunspec_map_read_at_its_addresses_gets_no_hint(tmp_path: Path) -> None:
    # SunSpec: "SunS" at 40000..40001, the common model's ID and length at 40002, 40003; read 40000..40005
    # (40004, 40005 are in no map: + 40001 is past 65535).
    capture = write_rtu(tmp_path / "s.bin", ["02 03 9C40 0006", "02 03 0C 5375 6E53 0001 0042 0000 0000"])
    path = _map(tmp_path, "40000,SID,SunSpec ID,\n40001,SID2,SunSpec ID low,\n40002,ID,Model ID,\n40003,L,Length,\n")
    status, out, err = run_cli([str(capture), "--profile", "generic", "--map", str(path)])
    assert (status, err) == (0, "")
    assert out.splitlines()[1] == ("     2            -   2 response  Read Holding Registers 40000..40005 (6): "
                                   "SID=21365 SID2=28243 ID=1 L=66 40004=0 40005=0 [#1]  CRC ok")


def test_a_map_the_traffic_matches_at_no_offset_gets_no_hint(tmp_path: Path) -> None:
    capture = write_rtu(tmp_path / "r.bin", READ)
    path = _map(tmp_path, "40101,VAB,Voltage AB,V\n40102,VBC,Voltage BC,V\n")  # (0..3 + 40001: not these)
    status, out, err = run_cli([str(capture), "--profile", "generic", "--map", str(path)])
    assert (status, out.splitlines(), err) == (0, [REQUEST, ANSWER + "0=403 1=440 2=476 3=514 [#1]  CRC ok"], "")


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_the_off_by_one_variant_and_fc4_s_3x_references(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                        pure: bool) -> None:
    use_engine(monkeypatch, pure)  # (the engine leaves a judged slave's frames to the annotator: frame 4 here)
    capture = write_rtu(tmp_path / "r.bin", READ + ["01 04 0064 0002", "01 04 04 00FA 00FD"])
    path = _map(tmp_path, "40000,IA,Phase A current,A\n40001,IB,Phase B current,A\n")  # (40000 for register 0)
    status, out, err = run_cli([str(capture), "--profile", "generic", "--map", str(path)])
    assert out.splitlines()[1] == ANSWER + f"0=403 1=440 2=476 3=514 [#1] [{note(path, 4, 2, '40000', column='')}]  CRC ok"
    inputs = _map(tmp_path, "30101,T1,Temperature 1,degC\n30102,T2,Temperature 2,degC\n", "i.csv")
    status, out, err = run_cli([str(capture), "--profile", "generic", "--map", str(inputs)])
    assert out.splitlines()[1:] == [
        ANSWER + "0=403 1=440 2=476 3=514 [#1]  CRC ok",
        "     3            -   1 request   Read Input Registers 100..101 (2)  CRC ok",
        "     4            -   1 response  Read Input Registers 100..101 (2): 100=250 101=253 [#3] "
        f"[{note(inputs, 6, 2, '30001')}]  CRC ok"]


def test_said_once_per_map_and_slave_and_given_for_the_run(tmp_path: Path) -> None:
    """The SEL-749M capture (slave 1 polls 0..15 and input 100..107 in a loop) with a map of 4X references,
    as its manual writes them: one note, on frame 2; the annotator gives it for the run's stderr."""
    path = _map(tmp_path, "40001,IA,Phase A current,A\n40002,IB,Phase B current,A\n40003,IC,Phase C current,A\n")
    annotate = build_annotator(["1=sel749m"], [str(path)])
    data = (Path(__file__).resolve().parents[2] / "captures" / "sel749m_polling.bin").read_bytes()
    items = dissect_bytes(data, annotate=annotate)
    noted = [(item.number, item.notes) for item in items if any(n.startswith("map ") for n in item.notes)]
    assert noted == [(2, [note(path, 16, 3, "40001")])]
    assert annotate.map_warnings() == [note(path, 16, 3, "40001")]
    assert build_annotator(["1=sel749m"], []).__class__.__name__ == "Annotator"  # (no map: no check)


def test_a_register_named_by_the_built_in_map_is_not_counted(tmp_path: Path) -> None:
    # ATV71: 3201 is ETA, 3202 RFR (built in); a map naming 43202 would be a 4X reference of 3201, but 3201
    # is named already: nothing unnamed, no note.
    capture = write_rtu(tmp_path / "a.bin", ["0C 03 0C81 0002", "0C 03 04 0233 012C"])
    path = _map(tmp_path, "43202,X,X,\n")
    status, out, err = run_cli([str(capture), "--profile", "atv71", "--map", str(path)])
    assert (status, err) == (0, "")
    assert "[map " not in out


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
def test_a_reference_column_reads_the_manual_s_numbers(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                      pure: bool) -> None:
    """A map headed `reference` instead of `address` is written as manuals number registers: 4X 40001 is
    address 0 (six digits: 400001), 3X 30101 input register 100; the traffic names its rows, no note."""
    use_engine(monkeypatch, pure)
    capture = write_rtu(tmp_path / "r.bin", READ + ["01 04 0064 0002", "01 04 04 00FA 00FD"])
    path = tmp_path / "m.csv"
    path.write_text("reference,code,name,unit\n40001,IA,Phase A current,A\n400002,IB,Phase B current,A\n"
                    "30101,T1,Temperature 1,degC\n")
    status, out, err = run_cli([str(capture), "--profile", "generic", "--map", str(path)])
    assert (status, out.splitlines()[1::2], err) == (0, [
        ANSWER + "IA=403 A IB=440 A 2=476 3=514 [#1]  CRC ok",
        "     4            -   1 response  Read Input Registers 100..101 (2): T1=250 degC 101=253 [#3]  CRC ok"], "")


def test_a_reference_map_still_off_is_told_without_the_column_hint(tmp_path: Path) -> None:
    # (440002 is address 40001: references of references; the note does not offer the column it has)
    capture = write_rtu(tmp_path / "r.bin", READ)
    path = tmp_path / "m.csv"
    path.write_text("reference,code\n440002,IA\n")
    status, out, _err = run_cli([str(capture), "--profile", "generic", "--map", str(path)])
    assert out.splitlines()[1] == ANSWER + f"0=403 1=440 2=476 3=514 [#1] [{note(path, 4, 1, '40001', column='')}]  CRC ok"


BAD_REFERENCES = {
    "reference,address,code\n": "map.csv:1: a map gives each row an address or a reference, not both",
    "reference,code\n40000,A\n": "map.csv:2: reference '40000' is not a 4X or 3X register reference "
                                  "(40001..49999, 400001..465536; 30001..39999, 300001..365536)",
    "reference,code\n0x9C41,A\n": "map.csv:2: reference '0x9C41' is not a 4X or 3X register reference "
                                   "(40001..49999, 400001..465536; 30001..39999, 300001..365536)",
    "reference,code\n465537,A\n": "map.csv:2: reference '465537' is not a 4X or 3X register reference "
                                   "(40001..49999, 400001..465536; 30001..39999, 300001..365536)",
    # (two references of one address: said as references, not `address 0 already defined on line 2`)
    "reference,code\n40001,A\n400001,B\n": "map.csv:3: reference '400001' is holding register 0, as '40001' on "
                                           "line 2: a map names each register once",
    # (a manual's 30001 and 40001 are input and holding register 0: two registers, test_map_tables.py)
    "reference,code\n30001,IN\n 300001 ,X\n": "map.csv:3: reference '300001' is input register 0, as '30001' on "
                                              "line 2: a map names each register once",
    "name,code\n": "map.csv:1: the header lacks the 'address' column",
}


@pytest.mark.parametrize("text", list(BAD_REFERENCES), ids=range(len(BAD_REFERENCES)))
def test_a_bad_reference_is_one_line(tmp_path: Path, text: str) -> None:
    (tmp_path / "map.csv").write_text(text)
    capture = write_rtu(tmp_path / "r.bin", READ)
    status, out, err = run_cli([str(capture), "--map", str(tmp_path / "map.csv")])
    assert (status, out, err) == (2, "", f"vw3-decode: {tmp_path}/{BAD_REFERENCES[text]}\n")
