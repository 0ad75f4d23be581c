"""A frame that fails its check was ignored by the device (Modbus over serial line 2.5.1.2; SEL-749M
p. D.3: "If there is no match, the check fails and the message is ignored"): it tells nothing of the
parameters (devices/memory.py, lua/src/decode.lua verified). Its values are decoded and shown, as Wireshark
shows a bad-checksum packet, but no register gets a status (not even ok), no 16#8000 story starts and
the parameter memory is left as it was, so the next good read is no `readable again`: as --stats and
--watch have always counted (they skip bad-CRC frames). The VW3 A3 303 manual p.38 scenario-2 answer
(CHCF 16#8000) with its CRC replaced by 00 00; noisy_bus frame 17 (a corrupted 9664). vw3-decode
(compiled engine and VW3_PURE_PYTHON=1: summary, -V, --json, -T registers, --parquet, --watch) and the
plugin (tshark one pass and -2). Before: frame 4 `CHCF (8401) became protected: read 3 in frame #2,
16#8000 now`, frame 6 `CHCF (8401) readable again`, Parquet protected/readable-again events, `Status:
ok` on noisy_bus frame 17 and the plugin the same."""
from __future__ import annotations

import json
from pathlib import Path

import duckdb
import pytest

from helpers import run_cli, use_engine
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

REQUEST = "0C 03 20 D0 00 03 0E EF"  # 8400..8402
READ_3 = "0C 03 06 80 00 00 03 00 02 17 E4"  # 8400 16#8000 (non-existent), CHCF 3, COP 2
# p.38's scenario-2 answer, CHCF 16#8000, its CRC 00 00.
BAD_ANSWER = [REQUEST, READ_3, REQUEST, "0C 03 06 80 00 80 00 00 02 00 00", REQUEST, READ_3]
ASK = "  12 request   Read Holding Registers 8400..8402 (3)  "
ANSWER = "  12 response  Read Holding Registers 8400..8402 (3): "
GOOD = "8400=non-existent CHCF=IO (I/O profile) COP=Cd (command)"
SHOWN = "8400=32768 CHCF=32768 (not a listed value) COP=Cd (command)"  # (the values, no 16#8000 judged)


def _summary() -> list[str]:
    lines = [ASK + "CRC ok", ANSWER + GOOD + " [#1, 100.0 ms]  CRC ok", ASK + "CRC ok",
             ANSWER + SHOWN + " [#3, 100.0 ms]  CRC BAD (received 0x0000, expected 0x24CE)", ASK + "CRC ok",
             ANSWER + GOOD + " [#5, 100.0 ms]  CRC ok"]
    return [f"{number:6d}     0.{number - 1}00000{line}" for number, line in enumerate(lines, start=1)]


def _capture(tmp_path: Path, frames: list[str]) -> Path:
    """One pcap record a frame (a raw stream would frame a bad CRC as noise)."""
    return write_pcap(tmp_path / "bad_crc.pcap", [(bytes.fromhex(frame), 1.0 + 0.1 * index)
                                                  for index, frame in enumerate(frames)])


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_tells_no_story_from_a_bad_crc(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                  pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = _capture(tmp_path, BAD_ANSWER)
    status, out, err = run_cli([str(capture), "--profile", "atv71"])
    assert status == 0, err
    assert out.splitlines() == _summary()
    status, out, err = run_cli([str(capture), "--profile", "atv71", "--json"])
    assert status == 0, err
    frame = json.loads(out.splitlines()[3])
    assert frame["notes"] == []
    assert [register.get("status") for register in frame["registers"]] == [None, None, None]
    assert [register.get("text") for register in frame["registers"]] == [None, "32768 (not a listed value)",
                                                                         "Cd (command)"]
    status, out, err = run_cli([str(capture), "--profile", "atv71", "-V"])
    assert status == 0, err
    detail = out.split("Frame 4:")[1].split("Frame 5:")[0]
    assert "Status:" not in detail and "Note:" not in detail
    shown = ("        Register 8401: 32768 (0x8000)  CHCF [Profile]\n"
             "            Value: 32768 (not a listed value)\n")
    assert shown in detail
    status, out, err = run_cli([str(capture), "--profile", "atv71", "-T", "registers"])
    assert status == 0, err
    assert [line.split("\t", 2)[2] for line in out.splitlines()[3:6]] == [
        "12\t3\tread\t8400\t\t\t\t32768\t\t\t\t\t\t",
        "12\t3\tread\t8401\t\tCHCF\tProfile\t32768\t\t\t\t32768 (not a listed value)\t\t",
        "12\t3\tread\t8402\t\tCOP\tCopy channel 1 <> 2\t2\t\t\t\tCd (command)\t\t",
    ]
    status, out, err = run_cli([str(capture), "--profile", "atv71", "--watch", "CHCF"])
    assert (status, out) == (0, ""), err


def test_parquet_has_no_event_from_a_bad_crc(tmp_path: Path) -> None:
    capture = _capture(tmp_path, BAD_ANSWER)
    status, _out, err = run_cli([str(capture), "--profile", "atv71", "--parquet", str(tmp_path / "data")])
    assert status == 0, err
    tables = f"{tmp_path}/data"
    events = duckdb.connect().execute(
        f"SELECT kind, frame FROM read_parquet('{tables}/events/*.parquet') ORDER BY frame").fetchall()
    assert events == [("non-existent", 2), ("crc", 4)]  # (8400, unmapped: non-existent from the first read)
    statuses = duckdb.connect().execute(
        f"SELECT frame, address, status FROM read_parquet('{tables}/registers/*.parquet') "
        "ORDER BY frame, address"
    ).fetchall()
    assert statuses == [(2, 8400, "non-existent"), (2, 8401, "ok"), (2, 8402, "ok"),
                        (4, 8400, None), (4, 8401, None), (4, 8402, None),
                        (6, 8400, "non-existent"), (6, 8401, "ok"), (6, 8402, "ok")]


@pytest.mark.parametrize("pure", [False, True])
def test_noisy_bus_frame_17_is_not_judged_ok(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(ROOT / "captures" / "noisy_bus.pcap"), "--profile", "atv71", "--json"])
    assert status == 0, err
    frame = next(record for record in map(json.loads, out.splitlines()) if record["frame"] == 17)
    assert frame["crc_ok"] is False
    assert frame["registers"] == [{"address": 0, "value": 409}, {"address": 1, "value": 9664},
                                  {"address": 2, "value": 486}, {"address": 3, "value": 519}]


# The plugin's frame | vw3.note | vw3.reg.status of every frame (the requests: nothing).
PLUGIN_LINES = ["1||", "2||non-existent,ok,ok", "3||", "4||,,", "5||", "6||non-existent,ok,ok"]


@pytest.mark.parametrize("two_pass", [False, True])
def test_the_plugin_tells_no_story_from_a_bad_crc(tmp_path: Path, two_pass: bool) -> None:
    capture = _capture(tmp_path, BAD_ANSWER)
    done = run_tshark(capture, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|",
                      "-e", "frame.number", "-e", "vw3.note", "-e", "vw3.reg.status", two_pass=two_pass)
    assert done.returncode == 0, done.stderr
    assert not lua_errors(done.stdout + done.stderr)
    assert done.stdout.splitlines() == PLUGIN_LINES


@pytest.mark.parametrize("two_pass", [False, True])
def test_the_plugin_judges_no_status_on_noisy_bus_frame_17(two_pass: bool) -> None:
    done = run_tshark(ROOT / "captures" / "noisy_bus.pcap", "-o", "vw3.profiles:atv71", "-T", "fields",
                      "-E", "separator=|", "-e", "frame.number", "-e", "vw3.reg.value", "-e", "vw3.reg.status",
                      "-Y", "frame.number == 17", two_pass=two_pass)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["17|409,9664,486,519|,,,"]


# An exception 02 to a read of 8401..8402, its CRC 00 00 (the ATV71's answer when every parameter read is
# unreadable, p.38): its code's meaning only, no parameter named protected, no story; before, `8401..8402
# became protected (2): read in frame #2, exception 02 now` and frame 6 `readable again`.
BAD_EXCEPTION = [REQUEST, READ_3, "0C 03 20 D1 00 02 9E EF", "0C 83 02 00 00", REQUEST, READ_3]
MEANING = ("exception 02 from the VW3 A3 303: address does not exist (also: every parameter read is "
           "non-existent or protected)")


@pytest.mark.parametrize("pure", [False, True])
def test_a_bad_crc_exception_02_tells_no_story(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                               pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(_capture(tmp_path, BAD_EXCEPTION)), "--profile", "atv71", "--json"])
    assert status == 0, err
    records = [json.loads(line) for line in out.splitlines()]
    assert [(record["notes"], record.get("registers")) for record in records[3:6:2]] == [
        ([MEANING], None), ([], records[1]["registers"])]


@pytest.mark.parametrize("two_pass", [False, True])
def test_the_plugin_tells_no_story_from_a_bad_crc_exception(tmp_path: Path, two_pass: bool) -> None:
    done = run_tshark(_capture(tmp_path, BAD_EXCEPTION), "-o", "vw3.profiles:atv71", "-T", "fields",
                      "-E", "separator=|", "-e", "frame.number", "-e", "vw3.note", "-e", "vw3.reg.status",
                      two_pass=two_pass)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["1||", "2||non-existent,ok,ok", "3||", f"4|{MEANING}|", "5||",
                                        "6||non-existent,ok,ok"]


def test_hex_a_crc_typed_bad_is_judged_bad(tmp_path: Path) -> None:
    """--hex frames a CRC typed bad as the frame it mends (app/hexinput.py) and puts the typed bytes back
    before the frame is decoded (pipeline.Dissector.fix) and before profile `auto` judges it: the story
    and the evidence are as of the pcap (the hunt's repro; before, frame 4 `CHCF (8401) became protected`, the
    profile `traffic fits its map ... in frames #2 and #4`)."""
    hexes = [argument for frame in BAD_ANSWER for argument in ("--hex", frame)]
    status, out, err = run_cli(hexes)
    assert status == 0, err
    lines = out.splitlines()
    typo = " [warning: CRC bad: received 0x0000, expected 0x24CE (on the wire 00 00 typed, CE 24 expected)]"
    assert lines[3] == ("     4            -" + ANSWER + SHOWN + " [#3]" + typo
                        + "  CRC BAD (received 0x0000, expected 0x24CE)")
    assert lines[5] == "     6            -" + ANSWER + GOOD + " [#5]  CRC ok"
    status, out, err = run_cli(hexes + ["-V"])
    assert status == 0, err
    assert ("Profile: atv71 (traffic fits its map: function 3 at 8400..8402 in frames #2 and #6; 16#8000 at "
            "8400, its answer for a non-existent parameter)") in out
