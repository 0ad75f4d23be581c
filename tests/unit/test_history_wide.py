"""32-bit map rows in the parameter history (render/history.py): one parameter at the row's address,
compared on its two words together and shown with the summary's text, in --watch, --stats, --stats --json
and --report, under the compiled engine and VW3_PURE_PYTHON=1 alike; a word of one without the other in
its frame is no value (counted in `half_values`), and no parameter of its own.

The frames are the reviewer's (hunter2 m.txt, m2.txt, m3.txt), slave 7 over this map:
PWR int32 CDAB x0.01 kW at 100, FLT float32 at 102, TMP signed x0.1 at 104, MODE enumerated at 105,
ENE uint32 x0.1 kWh at 106."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from dissector.devices.build import build_annotator
from dissector.render.history import History
from dissector.render.stats_store import CompiledStore, ParameterTable
from tests.support.helpers import hx, rtu, run_cli, use_engine

MAP = """address,code,name,unit,scale,access,enum,bits,signed,source,type,order
100,PWR,Power,kW,0.01,R,,,,,int32,CDAB
102,FLT,Flow,m3/h,,R,,,,,float32,ABCD
104,TMP,Temperature,degC,0.1,R,,,1,,,
105,MODE,Mode,,,RW,0=Stop;1=Run;65535=Fault,,,,,
106,ENE,Energy,kWh,0.1,R,,,,,uint32,
"""
MAP16 = """address,code,name,unit,scale,access,enum,bits,signed,source,type,order
104,TMP,Temperature,degC,0.1,R,,,1,,,
"""

# m.txt: two reads of 100..107, MODE written 0 (FC6 and its echo), then a read of 101..102 only: PWR's
# second word and FLT's first, each without the other.
M = """07 03 00 64 00 08 05 b5
07 03 10 1d c0 ff fe 41 48 00 00 ff c9 ff ff ee 6b 28 00 03 e2
07 03 00 64 00 08 05 b5
07 03 10 03 e8 00 00 80 00 00 00 01 2c 00 01 00 00 00 05 17 dd
07 06 00 69 00 00 59 b0
07 06 00 69 00 00 59 b0
07 03 00 65 00 02 d4 72
07 03 04 00 00 00 01 5d f3
"""
# m2.txt: PWR (CDAB) 00000001 -> 00000002 in its high word: 655.36 -> 1310.72 kW, its first word unchanged.
M2 = """07 03 00 64 00 08 05 b5
07 03 10 00 00 00 01 3f 80 00 00 00 01 00 00 00 01 11 70 df 72
07 03 00 64 00 08 05 b5
07 03 10 00 00 00 02 3f 80 00 00 00 01 00 00 00 02 11 70 2a b1
"""
# m3.txt: ENE 70000 -> 70001 (7000.0 -> 7000.1 kWh), its first word unchanged.
M3 = """07 03 00 6a 00 02 e4 71
07 03 04 00 01 11 70 c0 47
07 03 00 6a 00 02 e4 71
07 03 04 00 01 11 71 01 87
"""


@pytest.fixture(params=[False, True], ids=["engine", "pure"])
def engine(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> bool:
    use_engine(monkeypatch, request.param)
    return request.param


def _files(tmp_path: Path, frames: str) -> tuple[str, str]:
    (tmp_path / "m.csv").write_text(MAP)
    (tmp_path / "in.txt").write_text(frames)
    return str(tmp_path / "m.csv"), str(tmp_path / "in.txt")


def _ok(argv: list[str]) -> str:
    status, out, err = run_cli(argv)
    assert status == 0, err
    return out


def _parameter_rows(out: str) -> list[str]:
    """The rows of the Parameters table (after its title, header and rule, up to the blank line)."""
    lines = out.splitlines()
    rows = lines[lines.index("Parameters") + 3:]
    return rows[: rows.index("")] if "" in rows else rows


def _report(path: Path) -> dict:
    return json.loads(re.search(r'id="report-data">(.*?)</script>', path.read_text(encoding="utf-8"), re.S).group(1))


def test_a_change_of_the_second_word_is_a_change(tmp_path: Path, engine: bool) -> None:
    mapped, data = _files(tmp_path, M3)
    assert _ok(["--map", mapped, "--watch", "ENE", data]) == "     4            -   7 ENE 7000.0 -> 7000.1 (kWh)\n"
    out = _ok(["--map", mapped, "--stats", data])
    assert out.splitlines()[0] == "4 frames, 0 noise bytes in 0 runs"
    assert _parameter_rows(out) == [
        "    7      106  ENE       2           0       0        0  7000.1 kWh        1",
    ]
    report = json.loads(_ok(["--map", mapped, "--stats", "--json", data]))
    assert [(p["address"], p["code"], p["reads"], p["last"], p["last_text"], p["changes"])
            for p in report["parameters"]] == [(106, "ENE", 2, 70001, "7000.1 kWh", 1)]
    assert report["half_values"] == 0


def test_a_swapped_value_changes_on_its_high_word(tmp_path: Path, engine: bool) -> None:
    mapped, data = _files(tmp_path, M2)
    assert _ok(["--map", mapped, "--watch", "PWR,ENE", data]) == (
        "     4            -   7 PWR 655.36 -> 1310.72 (kW)\n"
        "     4            -   7 ENE 7000.0 -> 13553.6 (kWh)\n"
    )
    assert _parameter_rows(_ok(["--map", mapped, "--stats", data])) == [
        "    7       100  PWR       2           0       0        0  1310.72 kW         1",
        "    7       102  FLT       2           0       0        0  1 m3/h             0",
        "    7       104  TMP       2           0       0        0  0.1 degC           0",
        "    7       105  MODE      2           0       0        0  Stop               0",
        "    7       106  ENE       2           0       0        0  13553.6 kWh        1",
        "  all  5 params           10           0       0        0                     2",
    ]


def test_half_a_value_is_no_change_and_no_parameter(tmp_path: Path, engine: bool) -> None:
    mapped, data = _files(tmp_path, M)
    assert _ok(["--map", mapped, "--watch", "PWR,FLT,ENE", data]) == (
        "     4            -   7 PWR -1234.56 -> 10.00 (kW)\n"
        "     4            -   7 FLT 12.5 -> -0 (m3/h)\n"
        "     4            -   7 ENE 400000000.0 -> 0.5 (kWh)\n"
    )
    out = _ok(["--map", mapped, "--stats", data])
    assert out.splitlines()[0] == (
        "8 frames, 0 noise bytes in 0 runs, 2 register values one word of a 32-bit value without the other")
    assert _parameter_rows(out) == [
        "    7       100  PWR       2           0       0        0  10.00 kW         1",
        "    7       102  FLT       2           0       0        0  -0 m3/h          1",
        "    7       104  TMP       2           0       0        0  30.0 degC        1",
        "    7       105  MODE      2           0       1        0  Stop             2",
        "    7       106  ENE       2           0       0        0  0.5 kWh          1",
        "  all  5 params           10           0       1        0                   6",
    ]
    report = json.loads(_ok(["--map", mapped, "--stats", "--json", data]))
    assert report["half_values"] == 2
    assert [(p["address"], p["last"], p["last_text"], p["changes"]) for p in report["parameters"]] == [
        (100, 1000, "10.00 kW", 1),  # CDAB: 03E8 0000 is 0x000003E8
        (102, 0x80000000, "-0 m3/h", 1),
        (104, 300, "30.0 degC", 1),
        (105, 0, "Stop", 2),
        (106, 5, "0.5 kWh", 1),
    ]


def test_last_is_the_word_pair_and_its_text(tmp_path: Path, engine: bool) -> None:
    mapped, data = _files(tmp_path, "".join(M.splitlines(keepends=True)[:2]))
    report = json.loads(_ok(["--map", mapped, "--stats", "--json", data]))
    assert [(p["address"], p["code"], p["last"], p["last_text"]) for p in report["parameters"]] == [
        (100, "PWR", 0xFFFE1DC0, "-1234.56 kW"),  # -123456, its words 1DC0 FFFE (CDAB)
        (102, "FLT", 0x41480000, "12.5 m3/h"),
        (104, "TMP", 0xFFC9, "-5.5 degC"),
        (105, "MODE", 0xFFFF, "Fault"),
        (106, "ENE", 4_000_000_000, "400000000.0 kWh"),
    ]


def test_the_report_draws_one_series_a_value(tmp_path: Path, engine: bool) -> None:
    mapped, data = _files(tmp_path, M)
    page = tmp_path / "r.html"
    _ok(["--map", mapped, "--report", str(page), data])
    parameters = _report(page)["parameters"]
    assert [(p["address"], p["code"], p["unit"], p["values"], p["x"], p["y"]) for p in parameters] == [
        (100, "PWR", "kW", 2, [2, 4], [-1234.56, 10]),
        (102, "FLT", "m3/h", 2, [2, 4], [12.5, 0]),
        (104, "TMP", "degC", 2, [2, 4], [-5.5, 30]),
        (105, "MODE", None, 3, [2, 4, 6], [65535, 1, 0]),
        (106, "ENE", "kWh", 2, [2, 4], [400000000, 0.5]),
    ]


def test_writes_of_a_pair_and_of_half_a_pair(tmp_path: Path, engine: bool) -> None:
    """FC16 over both words: a value written and confirmed; FC6 to one word: half a value each way."""
    mapped, data = _files(tmp_path, "".join(rtu(pdu).hex(" ") + "\n" for pdu in [
        "07 10 00 64 00 02 04 00 01 00 02",  # PWR words 0001 0002 (CDAB: 0x00020001, 1310.73 kW)
        "07 10 00 64 00 02",
        "07 06 00 64 00 05",  # PWR's first word alone, and its echo
        "07 06 00 64 00 05",
        "07 10 00 64 00 02 04 00 01 00 03",  # 0x00030001: 1966.09 kW
        "07 10 00 64 00 02",
    ]))
    assert _ok(["--map", mapped, "--watch", "PWR", data]) == "     6            -   7 PWR 1310.73 -> 1966.09 (kW)\n"
    out = _ok(["--map", mapped, "--stats", data])
    assert out.splitlines()[0] == (
        "6 frames, 0 noise bytes in 0 runs, 2 register values one word of a 32-bit value without the other")
    assert _parameter_rows(out) == [
        "    7      100  PWR       0           0       2        0  1966.09 kW        1",
    ]


def test_read_once_the_pair_is_compared_too(tmp_path: Path, engine: bool) -> None:
    """Standard input: the lines of frames read before profile `auto` chose come as decoded."""
    mapped, _ = _files(tmp_path, M3)
    status, out, err = run_cli(["--map", mapped, "--watch", "ENE", "-"], stdin=M3.encode())
    assert status == 0, err
    assert out == "     4            -   7 ENE 7000.0 -> 7000.1 (kWh) [provisional]\n"
    status, out, err = run_cli(["--map", mapped, "--stats", "--json", "-"], stdin=M.encode())
    assert status == 0, err
    report = json.loads(out)
    assert report["half_values"] == 2
    assert [(p["address"], p["changes"]) for p in report["parameters"]] == [
        (100, 1), (102, 1), (104, 1), (105, 2), (106, 1)]


# -- the routing: a map with 32-bit rows is counted by the Python stages, engine built or not --------------
@pytest.mark.parametrize("maps, wide", [
    (["{wide}"], True), (["7={wide}"], True), (["atv71={wide}"], True), (["{narrow}"], False), ([], False),
])
def test_the_store_is_python_with_32_bit_rows(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, maps: list[str],
                                              wide: bool) -> None:
    use_engine(monkeypatch, False)
    (tmp_path / "w.csv").write_text(MAP)
    (tmp_path / "n.csv").write_text(MAP16)
    given = [spec.format(wide=tmp_path / "w.csv", narrow=tmp_path / "n.csv") for spec in maps]
    store = History(build_annotator(["auto"], given)).store
    assert isinstance(store, ParameterTable if wide else CompiledStore)


def _outputs(tmp_path: Path, argv: list[str], data: str) -> list[str]:
    page = tmp_path / "r.html"
    outputs = [_ok([*argv, "--stats", data]), _ok([*argv, "--stats", "--json", data]),
               _ok([*argv, "--watch", "PWR,FLT,ENE,MODE", data])]
    _ok([*argv, "--report", str(page), "--stats", data])
    return outputs + [json.dumps(_report(page))]


@pytest.mark.parametrize("form", ["bin", "pcap"])
def test_engine_and_pure_python_say_the_same(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, form: str) -> None:
    """A capture of an ATV71 (slave 12) and of slave 7 over the 32-bit map, as a raw RTU file (the engine's
    untimed path) and a pcap (its timed path): the same outputs with and without VW3_PURE_PYTHON=1."""
    root = Path(__file__).resolve().parents[2]
    mapped, _ = _files(tmp_path, "")
    data = (root / "captures" / "atv71_commissioning.bin").read_bytes() + b"".join(
        hx(line) for line in (M + M2 + M3).splitlines())
    (tmp_path / "in.bin").write_bytes(data)
    path = str(tmp_path / "in.bin")
    if form == "pcap":
        _ok(["-w", str(tmp_path / "in.pcap"), path])
        path = str(tmp_path / "in.pcap")
    argv = ["--map", f"7={mapped}"]
    use_engine(monkeypatch, False)
    compiled = _outputs(tmp_path, argv, path)
    use_engine(monkeypatch, True)
    assert _outputs(tmp_path, argv, path) == compiled
    seven = [(p["address"], p["code"], p["changes"]) for p in json.loads(compiled[1])["parameters"] if p["slave"] == 7]
    assert seven == [(100, "PWR", 3), (102, "FLT", 2), (104, "TMP", 2), (105, "MODE", 2), (106, "ENE", 5)]
    assert compiled[2].splitlines()[-1] == "   120            -   7 ENE 7000.0 -> 7000.1 (kWh)"


def test_values_named_again_when_auto_chooses(tmp_path: Path, engine: bool) -> None:
    """Slave 7 read over the map, then identified as an ATV71 (the commissioning capture's frames sent to
    slave 7): read once, the values kept are named again by the device chosen, each 32-bit one from its
    word pair (before: `1000` and `2147483648`, the pair as a number), as the file names them."""
    from dissector.pipeline import dissect_bytes

    root = Path(__file__).resolve().parents[2]
    mapped, _ = _files(tmp_path, "")
    atv71 = b"".join(rtu("07" + bytes(item.raw_binary or item.raw)[1:-2].hex())
                     for item in dissect_bytes((root / "captures" / "atv71_commissioning.bin").read_bytes()))
    data = b"".join(hx(line) for line in M.splitlines()) + atv71 + b"".join(hx(line) for line in M3.splitlines())
    (tmp_path / "in.bin").write_bytes(data)
    status, read_once, err = run_cli(["--map", mapped, "--stats", "--json", "-"], stdin=data)
    assert status == 0, err
    from_file = _ok(["--map", mapped, "--stats", "--json", str(tmp_path / "in.bin")])
    assert read_once == from_file
    report = json.loads(from_file)
    assert report["profiles"][0]["profile"] == "atv71"
    assert [(p["address"], p["last"], p["last_text"], p["changes"]) for p in report["parameters"]
            if p["address"] < 200] == [
        (100, 1000, "10.00 kW", 1), (102, 0x80000000, "-0 m3/h", 1), (104, 300, "30.0 degC", 1),
        (105, 0, "Stop", 2), (106, 70001, "7000.1 kWh", 3)]
    status, out, err = run_cli(["--map", mapped, "--watch", "PWR,ENE", "-"], stdin=data)
    assert status == 0, err
    assert out.splitlines()[-2:] == ["   114            -   7 ENE 0.5 -> 7000.0 (kWh)",
                                     "   116            -   7 ENE 7000.0 -> 7000.1 (kWh)"]
