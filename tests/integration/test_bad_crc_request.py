"""A request that failed its check, then a good answer (pairing.py trusted_request). The slave ignores a
request whose check fails (Modbus over serial line 2.5.1.2), so a good answer after one answers the bytes
the slave got, which the tap's damaged copy may not be: the answer is paired (its request number and
response time) and its values shown, but no address is taken from the damaged request: its registers are
those of an answer with no request (`?+0=...`, address null) with the note `addresses unknown: the
request's CRC is bad` (LRC in ASCII), no name, no status, no story, no parameter memory, no --watch,
--stats or --report row, no Parquet event, no profile `auto` evidence; nor is it measured against the
damaged request (byte count, echo), nor does an exception to it name or judge the parameters it refused.
vw3-decode (compiled engine and VW3_PURE_PYTHON=1) and the plugin (tshark one pass and -2).

Before: a bit flipped in the start address (8400 -> 8401) named the answer `8401..8403 (3): CHCF=protected
COP=protected 8403=2` with `8401..8402 became protected (2)` and, at the next good read, `readable again`;
a damaged FC16 value was remembered as written (`written 4 in frame #4`); an exception 02 to a damaged read
said `every parameter of this read is non-existent or protected` and started a story; a damaged read
counted as profile `auto` evidence (`function 3 at 8502..8503 in frame #2`)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import duckdb
import pytest

from helpers import run_cli, rtu, stats_section, use_engine
from lua_compare import compare
from lua_harness import lua_errors, lua_items, python_items, run_tshark, write_pcap
from dissector.protocol.crc import lrc

pytestmark = pytest.mark.integration


def damaged(frame: str, at: int, flip: int) -> bytes:
    """The frame with its good CRC, byte `at` XOR `flip` (a bit the line flipped on the tap's side)."""
    data = bytearray(rtu(frame))
    data[at] ^= flip
    return bytes(data)


def _capture(tmp_path: Path, frames: list[bytes], name: str = "bad_request.pcap") -> Path:
    """One pcap record a frame (a raw stream would frame a bad CRC as noise), 100 ms apart."""
    return write_pcap(tmp_path / name, [(frame, 1.0 + 0.1 * index) for index, frame in enumerate(frames)])


READ = "0C 03 20 D0 00 03"  # 8400..8402 on the ATV71
READ_3 = rtu("0C 03 06 80 00 00 03 00 02")  # 8400 16#8000 (non-existent), CHCF 3, COP 2
# The request read as 8401..8403 (its start's low bit flipped), the answer p.38's scenario 2 (CHCF 16#8000)
# to the 8400..8402 the slave got.
FLIPPED = [rtu(READ), READ_3, damaged(READ, 3, 1), rtu("0C 03 06 80 00 80 00 00 02"), rtu(READ), READ_3]
ASK = "  12 request   Read Holding Registers 8400..8402 (3)  CRC ok"
GOOD = "  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) COP=Cd (command)"
UNKNOWN = "addresses unknown: the request's CRC is bad"
SUMMARY = [
    ASK, GOOD + " [#1, 100.0 ms]  CRC ok",
    "  12 request   Read Holding Registers 8401..8403 (3)  CRC BAD (received 0xEF0E, expected 0x2F5F)",
    f"  12 response  Read Holding Registers (3): ?+0=32768 ?+1=32768 ?+2=2 [#3, 100.0 ms] [{UNKNOWN}]  CRC ok",
    ASK, GOOD + " [#5, 100.0 ms]  CRC ok",
]


def _lines(lines: list[str]) -> list[str]:
    return [f"{number:6d}     0.{number - 1}00000{line}" for number, line in enumerate(lines, start=1)]


@pytest.mark.parametrize("pure", [False, True])
def test_an_answer_to_a_damaged_request_has_no_addresses(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                         pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = str(_capture(tmp_path, FLIPPED))
    status, out, err = run_cli([capture, "--profile", "atv71"])
    assert status == 0, err
    assert out.splitlines() == _lines(SUMMARY)
    status, out, err = run_cli([capture, "--profile", "atv71", "-V"])
    assert status == 0, err
    detail = out.split("Frame 4:")[1].split("Frame 5:")[0]
    # (the quantity its byte count gives, as --json's: no start address)
    assert detail.splitlines()[5] == "        [Quantity: 3]"
    assert detail.splitlines()[7:] == [
        "        Register ?: 32768 (0x8000)", "        Register ?: 32768 (0x8000)", "        Register ?: 2 (0x0002)",
        "        CRC: 0x24CE [CRC ok]", "    Request in frame: 3", "    Response time: 100.000 ms",
        f"    Note: {UNKNOWN}", ""]
    status, out, err = run_cli([capture, "--profile", "atv71", "--json"])
    assert status == 0, err
    frame = json.loads(out.splitlines()[3])
    assert (frame["request_frame"], frame["notes"], frame["registers"], "start" in frame) == (
        3, [UNKNOWN], [{"address": None, "value": 32768}, {"address": None, "value": 32768},
                       {"address": None, "value": 2}], False)
    status, out, err = run_cli([capture, "--profile", "atv71", "-T", "registers"])
    assert status == 0, err
    assert [line.split("\t", 2)[2] for line in out.splitlines()[3:6]] == [
        "12\t3\tread\t\t\t\t\t32768\t\t\t\t\t\t", "12\t3\tread\t\t\t\t\t32768\t\t\t\t\t\t",
        "12\t3\tread\t\t\t\t\t2\t\t\t\t\t\t"]
    status, out, err = run_cli([capture, "--profile", "atv71", "--watch", "CHCF,COP"])
    assert (status, out) == (0, ""), err
    status, out, err = run_cli([capture, "--profile", "atv71", "--stats"])
    assert status == 0, err
    assert stats_section(out) == [
        "slave   address  code  reads  unreadable  writes  refused  last              changes",
        "------------------------------------------------------------------------------------",
        "   12      8400            0           2       0        0  non-existent            0",
        "   12      8401  CHCF      2           0       0        0  IO (I/O profile)        0",
        "   12      8402  COP       2           0       0        0  Cd (command)            0",
        "  all  3 params            4           2       0        0                          0",
    ]
    page = tmp_path / "report.html"
    status, _out, err = run_cli([capture, "--profile", "atv71", "--report", str(page)])
    assert status == 0, err
    data = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(), re.S).group(1))
    assert data["events"] == [[0.1, "protection", 12, "8400 non-existent"], [0.2, "crc", 12, "bad CRC, function 3, 8 bytes"]]


def test_parquet_takes_no_address_from_a_damaged_request(tmp_path: Path) -> None:
    capture = _capture(tmp_path, FLIPPED)
    status, _out, err = run_cli([str(capture), "--profile", "atv71", "--parquet", str(tmp_path / "data")])
    assert status == 0, err
    query = duckdb.connect().execute
    events = query(f"SELECT kind, frame FROM read_parquet('{tmp_path}/data/events/*.parquet') ORDER BY frame")
    assert events.fetchall() == [("non-existent", 2), ("crc", 3)]
    rows = query(f"SELECT frame, address, code, value, status FROM read_parquet('{tmp_path}/data/registers/*.parquet') "
                 "WHERE frame = 4")
    assert rows.fetchall() == [(4, None, None, 32768, None), (4, None, None, 32768, None), (4, None, None, 2, None)]


WRITE = "0C 10 20 D1 00 01 02 00 05"  # CHCF := 5


@pytest.mark.parametrize("pure", [False, True])
def test_the_story_remembers_nothing_of_a_damaged_request(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                          pure: bool) -> None:
    """An FC16 whose value the tap read as 4 (CRC bad), confirmed by a good answer: its value is not known
    written (before: `written 4 in frame #4`); an exception 02 to a damaged read tells only its code's
    meaning (before: the read's parameters named unreadable, a story, `readable again` after)."""
    use_engine(monkeypatch, pure)
    frames = [rtu(READ), READ_3, damaged(WRITE, 8, 1), rtu("0C 10 20 D1 00 01"), rtu(READ),
              rtu("0C 03 06 80 00 80 00 00 02"), damaged("0C 03 20 D1 00 02", 3, 1), rtu("0C 83 02"), rtu(READ), READ_3]
    status, out, err = run_cli([str(_capture(tmp_path, frames)), "--profile", "atv71"])
    assert status == 0, err
    assert out.splitlines()[2:] == _lines([""] * 2 + [
        "  12 request   Write Multiple Registers 8401: CHCF=4 (not a listed value)  CRC BAD (received 0x400D, "
        "expected 0x80CC)",
        "  12 response  Write Multiple Registers 8401 written [#3, 100.0 ms]  CRC ok", ASK,
        "  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=protected COP=Cd (command) "
        "[#5, 100.0 ms] [CHCF (8401) became protected: read 3 in frame #2, 16#8000 now]  CRC ok",
        "  12 request   Read Holding Registers 8400..8401 (2)  CRC BAD (received 0xEF9E, expected 0x2FCF)",
        "  12 exception Read Holding Registers: exception 2 (Illegal Data Address) [#7, 100.0 ms] [exception 02 "
        "from the VW3 A3 303: address does not exist (also: every parameter read is non-existent or protected)]  "
        "CRC ok", ASK,
        "  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) COP=Cd "
        "(command) [#9, 100.0 ms] [CHCF (8401) readable again: protected in frame #6, 3 now]  CRC ok"])[2:]


@pytest.mark.parametrize("pure", [False, True])
def test_nothing_is_measured_against_a_damaged_request(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                       pure: bool) -> None:
    """An FC6 echo of 8401 after a request read as 8400: no `address differs` warning (the slave wrote what
    it got); a refusal of a damaged write of read-only ETA: the code's meaning, no parameter named; bits
    and FC23's read: no addresses either."""
    use_engine(monkeypatch, pure)
    frames = [damaged("0C 06 20 D1 00 05", 3, 1), rtu("0C 06 20 D1 00 05"),
              damaged("0C 06 0C 81 00 05", 5, 1), rtu("0C 86 02"),
              damaged("0C 01 00 00 00 10", 3, 1), rtu("0C 01 02 FF 00"),
              damaged("0C 17 20 D0 00 03 20 D1 00 01 02 00 07", 3, 1), rtu("0C 17 06 80 00 00 03 00 02")]
    status, out, err = run_cli([str(_capture(tmp_path, frames)), "--profile", "atv71"])
    assert status == 0, err
    assert out.splitlines()[1::2] == _lines([
        "", "  12 response  Write Single Register 8401 CHCF=5 (not a listed value) [#1, 100.0 ms]  CRC ok",
        "", "  12 exception Write Single Register: exception 2 (Illegal Data Address) [#3, 100.0 ms] [exception 02 "
        "from the VW3 A3 303: address does not exist]  CRC ok",
        "", f"  12 response  Read Coils: 1111111100000000 [#5, 100.0 ms] [{UNKNOWN}]  CRC ok",
        "", f"  12 response  Read/Write Multiple Registers (3): ?+0=32768 ?+1=3 ?+2=2 [#7, 100.0 ms] [{UNKNOWN}]  "
        "CRC ok"])[1::2]


def test_a_damaged_request_is_no_profile_evidence(tmp_path: Path) -> None:
    """Profile `auto`: the answer to a read of 8501..8502 the tap saw as 8502..8503 fits the ATV71's map by
    the damaged addresses; it is no evidence (before: `function 3 at 8502..8503 in frame #2`)."""
    frames = [damaged("0C 03 21 35 00 02", 3, 3), rtu("0C 03 04 00 05 00 64"), rtu("0C 03 21 9B 00 02"),
              rtu("0C 03 04 00 01 00 02"), rtu("0C 03 21 35 00 02"), rtu("0C 03 04 00 05 00 64")]
    status, out, err = run_cli([str(_capture(tmp_path, frames)), "-V"])
    assert status == 0, err
    assert set(re.findall(r"Profile: .*", out)) == {
        "Profile: atv71 (traffic fits its map: function 3 at 8603..8604 in frame #4, function 3 at 8501..8502 "
        "in frame #6)"}


def _ascii(frame: str, bad: bool = False) -> bytes:
    data = bytes.fromhex(frame.replace(" ", ""))
    return f":{data.hex().upper()}{lrc(data) ^ bad:02X}\r\n".encode()


def test_ascii_says_lrc(tmp_path: Path) -> None:
    frames = [_ascii(READ), _ascii("0C 03 06 80 00 00 03 00 02"), _ascii("0C 03 20 D1 00 03", bad=True),
              _ascii("0C 03 06 80 00 80 00 00 02")]
    status, out, err = run_cli([str(_capture(tmp_path, frames)), "--profile", "atv71"])
    assert status == 0, err
    assert out.splitlines()[3] == ("     4     0.300000  12 response  Read Holding Registers (3): ?+0=32768 ?+1=32768 "
                                   "?+2=2 [#3, 100.0 ms] [addresses unknown: the request's LRC is bad]  LRC ok")


# The plugin's frame | vw3.note | vw3.reg.address | vw3.reg.status (-2: the request's addresses shown with it).
PLUGIN_LINES = ["1||8400,8401,8402|", "2||8400,8401,8402|non-existent,ok,ok", "3||8401,8402,8403|",
                f"4|{UNKNOWN}||,,", "5||8400,8401,8402|", "6||8400,8401,8402|non-existent,ok,ok"]


@pytest.mark.parametrize("two_pass", [False, True])
def test_the_plugin_takes_no_address_from_a_damaged_request(tmp_path: Path, two_pass: bool) -> None:
    done = run_tshark(_capture(tmp_path, FLIPPED), "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|",
                      "-e", "frame.number", "-e", "vw3.note", "-e", "vw3.reg.address", "-e", "vw3.reg.status",
                      two_pass=two_pass)
    assert done.returncode == 0, done.stderr
    assert not lua_errors(done.stdout + done.stderr)
    lines = done.stdout.splitlines()
    if not two_pass:
        # (one pass: the damaged request is shown by the record that settles it, the answer's, beside the
        # answer, which takes no address from it: its statuses are empty)
        assert lines[2:4] == ["3|||", f"4|{UNKNOWN}|8401,8402,8403|,,"]
        lines[2:4] = PLUGIN_LINES[2:4]
    assert lines == PLUGIN_LINES


@pytest.mark.parametrize("profile", ["atv71", None])
def test_the_plugin_agrees_on_every_case(tmp_path: Path, profile: str | None) -> None:
    """Frame for frame as vw3-decode --json (tshark -2): the damaged write, echo, refusal, bits, FC23, a plain
    slave's answer (the plugin's quick lane of answers takes none after a damaged request) and ASCII."""
    plain = [rtu("01 03 00 00 00 02"), rtu("01 03 04 00 07 00 08"), damaged("01 03 00 00 00 02", 3, 1),
             rtu("01 03 04 00 07 00 08"), rtu("01 03 00 00 00 02"), rtu("01 03 04 00 07 00 08")]
    cases = {
        "flipped": FLIPPED, "plain": plain,
        "writes": [rtu(READ), READ_3, damaged(WRITE, 8, 1), rtu("0C 10 20 D1 00 01"), rtu(READ),
                   rtu("0C 03 06 80 00 80 00 00 02"), damaged("0C 06 20 D1 00 05", 3, 1), rtu("0C 06 20 D1 00 05")],
        "refusals": [rtu(READ), READ_3, damaged("0C 03 20 D1 00 02", 3, 1), rtu("0C 83 02"),
                     damaged("0C 06 0C 81 00 05", 5, 1), rtu("0C 86 02"), rtu(READ), READ_3],
        "reads": [damaged("0C 01 00 00 00 10", 3, 1), rtu("0C 01 02 FF 00"),
                  damaged("0C 17 20 D0 00 03 20 D1 00 01 02 00 07", 3, 1), rtu("0C 17 06 80 00 00 03 00 02")],
        "ascii": [_ascii(READ), _ascii("0C 03 06 80 00 00 03 00 02"), _ascii("0C 03 20 D1 00 03", bad=True),
                  _ascii("0C 03 06 80 00 80 00 00 02")],
    }
    options = () if profile is None else ("-o", f"vw3.profiles:{profile}")
    for name, frames in cases.items():
        capture = _capture(tmp_path, frames, f"{name}.pcap")
        python = python_items(capture, None if profile is None else [profile])
        assert sum(UNKNOWN[:20] in note for item in python for note in item.data["notes"]) == (
            name in ("flipped", "plain", "reads", "ascii")) * (2 if name == "reads" else 1)
        differences = compare(python, lua_items(capture, *options)[0])
        assert not differences, f"{name}: " + "\n".join(differences[:20])
