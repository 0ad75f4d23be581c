"""The plugin frames an FC43/14 answer that declares more objects than it holds as vw3-decode does
(tests/unit/test_mei_object_count.py): by its CRC, paired, its objects shown, with the warning; an answer
truly cut by the end of the capture is noise and its request says so. Real tshark with
-X lua_script:lua/vw3.lua, each frame a record, and the answer in one record with the next request."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

T0 = 1767225600.0
REQUEST = bytes.fromhex("01 2b 0e 01 00 70 77")
SHORT = bytes.fromhex("01 2b 0e 01 01 00 00 03 00 03 41 42 43 01 02 58 59 03 7e")  # 3 declared, 2 sent
FULL = rtu("01 2b 0e 01 01 00 00 03 00 03 41 42 43 01 02 58 59 02 03 31 2e 30")
READ = bytes.fromhex("01 03 00 00 00 01 84 0a")
WARNING = "number of objects 3 disagrees with the objects present (2)"
UNKNOWN = "the capture ends before any response: not known whether it was answered"
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.request_frame", "-e", "vw3.response_frame",
          "-e", "vw3.unanswered", "-e", "vw3.note", "-e", "vw3.warning", "-e", "vw3.object.value", "-e", "vw3.crc_ok"]


def fields(path: Path, records: list[bytes]) -> list[str]:
    pcap = write_pcap(path, [(data, T0 + 0.05 * index) for index, data in enumerate(records)])
    result = run_tshark(pcap, *FIELDS)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


def test_the_answer_with_fewer_objects(tmp_path: Path) -> None:
    assert fields(tmp_path / "short.pcap", [REQUEST, SHORT]) == [
        "1;;2;;;;;1",
        f"2;1;;;;{WARNING};ABC,XY;1",
    ]


def test_in_one_record_with_the_next_request(tmp_path: Path) -> None:
    assert fields(tmp_path / "stream.pcap", [REQUEST, SHORT + READ]) == [
        "1;;2;;;;;1",
        f"2,1;1;;;{UNKNOWN};{WARNING};ABC,XY;1,1",
    ]


def test_a_walk_that_ends_with_the_record(tmp_path: Path) -> None:
    # 147 bytes in the record, as many as the walk asks for: the plugin checks the CRC there once and scans
    # where it fails (lua/src/layouts.lua's fourth value), as the Python stages do.
    poll = rtu("02 03 0000 0001")
    lines = fields(tmp_path / "record.pcap", [REQUEST, SHORT + poll * 16])
    ones = ",".join(["1"] * 16)
    assert lines == [
        "1;;2;;;;;1",
        f"2,{ones};1;;{ones[2:]};{UNKNOWN};{WARNING};ABC,XY;1,{ones}",  # (the last request: not known)
    ]


@pytest.mark.parametrize(("cut", "reason"), [(20, "20 of 24 bytes"), (15, "15 bytes of it")])
def test_an_answer_cut_by_the_end_of_the_capture(tmp_path: Path, cut: int, reason: str) -> None:
    assert fields(tmp_path / "cut.pcap", [REQUEST, FULL[:cut]]) == [
        f"1;;;;the capture ends inside the response ({reason});;;1",  # (it did answer)
        "4;;;;;;;",
    ]
