"""FC43 object values as a bytes literal's text (protocol/printable.py bytes_text), alike in vw3-decode
(compiled engine and VW3_PURE_PYTHON=1) and the plugin under tshark 4.0: a byte past ASCII is `\\xc3`
with one backslash (repr doubled it: `\\\\xc3`), a backslash byte is `\\\\`, so the byte C3 and the four
bytes `\\xc3` never read the same; the quote is `\\'`, control bytes `\\x1b`, `\\t`. The summary, -V and
the plugin show the value between single quotes, --json and vw3.object.value hold it as it is, and it
gives the bytes back (ast.literal_eval of b'...'). A profile's notes quote it so too."""
from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare
from lua_harness import lua_items, python_items, write_pcap
from test_lua_info_data import T0, tshark, vw3_decode

pytestmark = pytest.mark.integration

# VendorName `été ` in UTF-8; ProductCode the four bytes `\xc3`; the revision `it's "q"`; object 0x80 ESC [31m TAB
SENT = [b"\xc3\xa9t\xc3\xa9 ", b"\\xc3", b"it's \"q\"", b"\x1b[31m\t"]
VALUES = [r"\xc3\xa9t\xc3\xa9 ", r"\\xc3", "it\\'s \"q\"", r"\x1b[31m\t"]
NAMES = ["VendorName", "ProductCode", "MajorMinorRevision", "Object 128"]
SHOWN = " ".join(f"{name}='{value}'" for name, value in zip(NAMES, VALUES))
INFO = f"Read Device Identification, basic: {SHOWN}"
MEI = "Encapsulated Interface Transport"


def _answer(slave: int) -> bytes:
    objects = "".join(f"{oid:02x}{len(data):02x}{data.hex()}" for oid, data in zip([0, 1, 2, 0x80], SENT))
    return rtu(f"{slave:02x} 2b 0e 01 01 00 00 04" + objects)


@pytest.fixture(scope="module")
def capture(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return write_pcap(tmp_path_factory.mktemp("escapes") / "fc43.pcap",
                      [(rtu("11 2b 0e 01 00"), T0), (_answer(17), T0 + 1)])


def test_a_value_gives_its_bytes_back() -> None:
    assert len(VALUES[1]) == 5 and len(VALUES[3]) == 10  # (the backslash byte two characters, ESC four, TAB two)
    assert [ast.literal_eval(f"b'{value}'") for value in VALUES] == SENT


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure-python"])
def test_vw3_decode(capture: Path, pure: bool) -> None:
    assert vw3_decode(capture, pure).splitlines()[1] == (
        f"     2     1.000000  17 response  {MEI} {INFO} [#1, 1000.0 ms]  CRC ok")
    detail = vw3_decode(capture, pure, "-V").splitlines()
    assert [line.strip() for line in detail if line.startswith("        Object ")] == [
        f"Object 0 VendorName: '{VALUES[0]}'", f"Object 1 ProductCode: '{VALUES[1]}'",
        f"Object 2 MajorMinorRevision: '{VALUES[2]}'", f"Object 128: '{VALUES[3]}'"]
    (response,) = [item for item in map(json.loads, vw3_decode(capture, pure, "--json").splitlines())
                   if item["frame"] == 2]
    assert [obj["value"] for obj in response["objects"]] == VALUES
    assert vw3_decode(capture, pure, "-T", "fields", "-e", "objects").splitlines()[1] == json.dumps(
        response["objects"], separators=(",", ":"))


def test_plugin(capture: Path) -> None:
    assert tshark(capture, "-T", "fields", "-e", "_ws.col.Info").splitlines()[1] == f"17 {MEI} response {INFO}"
    values = tshark(capture, "-Y", "frame.number == 2", "-T", "fields", "-E", "occurrence=a",
                    "-E", "aggregator=|", "-e", "vw3.object.value")
    assert values.splitlines() == ["|".join(VALUES)]
    labels = [line.strip() for line in tshark(capture, "-V", "-Y", "frame.number == 2").splitlines()
              if line.startswith("    ") and line.strip().startswith(tuple(name + ":" for name in NAMES))]
    assert labels == [f"{name}: '{value}'" for name, value in zip(NAMES, VALUES)]
    lua, _, _ = lua_items(capture)
    assert compare(python_items(capture), lua) == []


def test_a_profile_quotes_the_value_so(tmp_path: Path) -> None:
    """ATV71's revision (MMmm) and product code: the notes quote the value as the summary shows it."""
    revision = b"0\xb2\\'"
    answer = rtu("02 2b 0e 01 02 00 00 02" + f"02{len(revision):02x}{revision.hex()}" + "01 06" + b"ATV71'".hex())
    pcap = write_pcap(tmp_path / "atv71.pcap", [(rtu("02 2b 0e 01 00"), T0), (answer, T0 + 1)])
    note = r"MajorMinorRevision '0\xb2\\\'' is not in the MMmm form the VW3 A3 303 uses"
    for pure in (False, True):
        (item,) = [item for item in map(json.loads, vw3_decode(pcap, pure, "--json", "--profile", "auto").splitlines())
                   if item["frame"] == 2]
        assert note in item["notes"]
        assert item["profile_reason"] == r"Read Device Identification in frame #2: ProductCode 'ATV71\''"
    lua, _, _ = lua_items(pcap, "-o", "vw3.profiles:auto")
    assert compare(python_items(pcap, ["auto"]), lua) == []


def test_every_byte_as_python_writes_it(tmp_path: Path) -> None:
    """The 256 bytes in two answers' private objects: each value is repr(bytes)'s text (that repr escapes
    the quote: the bytes hold both), in vw3-decode's --json and the plugin's vw3.object.value alike."""
    halves = [bytes(range(128)), bytes(range(128, 256))]
    answers = [rtu("11 2b 0e 01 01 00 00 01 80 80" + half.hex()) for half in halves]
    records = [data for answer in answers for data in (rtu("11 2b 0e 01 00"), answer)]
    pcap = write_pcap(tmp_path / "bytes.pcap", [(data, T0 + at) for at, data in enumerate(records)])
    expected = [repr(half)[2:-1] for half in halves]
    assert "\\'" in expected[0] and "\\\\" in expected[0]
    items = map(json.loads, vw3_decode(pcap, False, "--json").splitlines())
    assert [obj["value"] for item in items for obj in item.get("objects", [])] == expected
    values = tshark(pcap, "-Y", "vw3.object", "-T", "fields", "-e", "vw3.object.value")
    assert values.splitlines() == expected
