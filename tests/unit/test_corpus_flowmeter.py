"""Real recordings of a flow meter polled at slave 247 (sigrok-dumps uart/modbus_rtu/flowmeter, their source:
tests/support/flowmeter_corpus.py): four captures in which the master sets a target flow by FC16 (0, 15
and 20 litres a minute, an IEEE 754 float in registers 6..7, as the files' names state) and one of a graph
tool's polling. Each decodes frame for frame as the recording's bursts, as raw bytes and as reads cut
anywhere with their times: every frame CRC ok, requests and answers alternate, each answered, slave 247
only (the highest device address); the engine and VW3_PURE_PYTHON=1 alike. The plugin and tshark's mbrtu:
tests/integration/test_lua_flowmeter.py."""
from __future__ import annotations

import json
import struct
from pathlib import Path

import pytest

from flowmeter_corpus import CAPTURES, cut_anywhere, pcap, records
from helpers import run_cli, use_engine

ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def items(*argv: str, stdin: bytes = b"") -> list[dict]:
    status, out, err = run_cli([*argv, "--json", "-n", "--baud", "9600"], stdin=stdin)
    assert status == 0, err
    return [json.loads(line) for line in out.splitlines()]



@ENGINES
@pytest.mark.parametrize("name", sorted(CAPTURES))
def test_each_recording_decodes_frame_for_frame(name: str, pure: bool, tmp_path: Path,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    recorded = records(name)
    frames = [(data.hex(), True) for _time, data in recorded]
    for decoded in (items(str(pcap(tmp_path / "bursts.pcap", recorded))),
                    items("-", stdin=b"".join(data for _time, data in recorded)),
                    items(str(pcap(tmp_path / "reads.pcap", cut_anywhere(recorded, len(name)))))):
        assert [(item["raw"], item.get("crc_ok")) for item in decoded] == frames
        assert [item["kind"] for item in decoded] == ["request", "response"] * (len(recorded) // 2)
        assert all(decoded[k + 1]["request_frame"] == decoded[k]["frame"] for k in range(0, len(decoded), 2))
        assert {item["slave"] for item in decoded} == {247}


@pytest.mark.parametrize("name", sorted(name for name, target in CAPTURES.items() if target is not None))
def test_the_target_written_is_the_one_the_file_names(name: str) -> None:
    decoded = items("-", stdin=b"".join(data for _time, data in records(name)))
    high, low = struct.unpack(">HH", struct.pack(">f", CAPTURES[name]))
    writes = [item for item in decoded if item["function"] == 16]
    pairs = len(writes) // 2
    assert pairs >= 1
    assert [(item["kind"], item["start"]) for item in writes] == [("request", 6), ("response", 6)] * pairs
    for request in writes[::2]:
        assert [(r["address"], r["value"]) for r in request["registers"]] == [(6, high), (7, low)]


def test_the_summary_of_a_write(tmp_path: Path) -> None:
    out = run_cli([str(pcap(tmp_path / "15.pcap", records("flowmeter_target_15liter_per_min"))), "-n"])[1]
    lines = out.splitlines()
    assert lines[26:28] == [
        "    27     0.953930 247 request   Write Multiple Registers 6..7 (2): 6=16752 7=0  CRC ok",
        "    28     0.972987 247 response  Write Multiple Registers 6..7 (2) written [#27, 19.1 ms]  CRC ok"]
    assert len(lines) == 132 and not [line for line in lines if not line.endswith("CRC ok")]
