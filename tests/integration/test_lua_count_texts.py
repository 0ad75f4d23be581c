"""The plugin shows the review's texts as vw3-decode does (tests/unit/test_count_texts.py): a count reads
singular for one (`noise (1 byte)`, `1 byte outside any frame`, `(1 byte continues in #2)`), a window
past 65535 ends at its last address as asked (`65535..65539`, PLC style `465536..465540`), as its warning
says it, the byte-count warnings read right for 1 (`the registers asked (1)`), and an FC43 object the spec
does not name is `Object 128: 'ABC'`. Real tshark with -X lua_script:lua/vw3.lua, -2 and one pass."""
from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_count_texts import RECORDS, T0  # noqa: E402

pytestmark = pytest.mark.integration

INFO = [
    "1 Read Holding Registers request 65535..65539 (5)",
    "1 Read Holding Registers response 65535..65539 (5)",
    "noise (1 byte)",
    "1 Write Multiple Coils request 65535..65544 (10)",
    "1 Write Multiple Coils response 65535..65544 (10) written",
    "1 Encapsulated Interface Transport request Read Device Identification, individual, from object 128",
    "1 Encapsulated Interface Transport response Read Device Identification, individual: Object 128='ABC' "
    "ModelName='XY'",
    # (the sub-function and its data, as vw3-decode says them: 16 bytes, then `(+1 byte)`, singular)
    "1 Diagnostics request 00h Return Query Data data 0102030405060708090a0b0c0d0e0f10… (+1 byte)",
    "1 Diagnostics response 00h Return Query Data data 0102030405060708090a0b0c0d0e0f10… (+1 byte)",
    "1 Read Holding Registers request 16",
    "1 Read Holding Registers response 16",
    "1 Read Coils request 32",
    "1 Read Coils response 32",
    "noise (2 bytes)",
]


def tshark(pcap: Path, *args: str, two_pass: bool = True) -> str:
    result = run_tshark(pcap, *args, two_pass=two_pass)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_pcap(tmp_path_factory.mktemp("lua_texts") / "texts.pcap", [(data, T0 + at) for data, at in RECORDS])


def test_info_column(capture: Path) -> None:
    assert tshark(capture, "-T", "fields", "-e", "_ws.col.Info").splitlines() == INFO


def test_info_column_plc_style(capture: Path) -> None:
    lines = tshark(capture, "-o", "vw3.address_style:plc", "-T", "fields", "-e", "_ws.col.Info").splitlines()
    assert lines[:5] == [
        "1 Read Holding Registers request 465536..465540 (5)",
        "1 Read Holding Registers response 465536..465540 (5)",
        "noise (1 byte)",
        "1 Write Multiple Coils request 065536..065545 (10)",
        "1 Write Multiple Coils response 065536..065545 (10) written",
    ]


def test_tree(capture: Path) -> None:
    tree = tshark(capture, "-V")
    for line in [
        "VW3 Modbus RTU, 1 Read Holding Registers request 65535..65539 (5)\n",
        "        [Expert Info (Warning/Protocol): addresses 65535..65539 run past 65535]\n",
        "VW3 noise, 1 byte: too short for a frame\n",
        "    [Expert Info (Warning/Malformed): 1 byte outside any frame: too short for a frame]\n",
        "VW3 noise, 2 bytes: too short for a frame\n",
        "    Object 128: 'ABC'\n        Object id: 128\n",
        "        [Expert Info (Warning/Protocol): byte count 4 disagrees with the registers asked (1)]\n",
        "        [Expert Info (Warning/Protocol): byte count 2 disagrees with the bits asked (1)]\n",
    ]:
        assert line in tree, line
    assert not re.search(r"\b1 bytes", tree)


def test_one_byte_continued_in_the_next_record(tmp_path: Path) -> None:
    request, response = rtu("01 03 0010 0001"), rtu("01 03 02 0007")
    pcap = write_pcap(tmp_path / "split.pcap", [(request + response[:1], T0), (response[1:], T0 + 0.01)])
    assert tshark(pcap, "-T", "fields", "-e", "_ws.col.Info").splitlines() == [
        "(1 byte continues in #2); 1 Read Holding Registers request 16", "1 Read Holding Registers response 16"]
    assert "VW3 bytes of a frame shown in a later record: 1 byte continues in item 2 (record 2)\n" in tshark(pcap, "-V")
    one_pass = tshark(pcap, "-V", two_pass=False)
    assert "[The record ends inside a frame: its last byte is framed with the next records']\n" in one_pass
    assert tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=False).splitlines() == [
        "1 Read Holding Registers request 16 [provisional]; (1 byte continues)",
        "1 Read Holding Registers response 16 [provisional]"]


def test_fc23_windows_past_65535_draw_the_warning(tmp_path: Path) -> None:
    from test_count_texts import FC23_PAST_65535

    pcap = write_pcap(tmp_path / "fc23.pcap", [(data, T0 + at) for data, at in FC23_PAST_65535])
    warnings = re.findall(r"\[Expert Info \(Warning/Protocol\): ([^\]]*)\]", tshark(pcap, "-V"))
    assert [w for w in warnings if "past" in w] == [
        "addresses 65535..65539 run past 65535", "addresses 65534..65536 run past 65535"]
