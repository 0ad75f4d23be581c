"""A request the capture ends after, before its answer: a master gives up only at its timeout, so whether it
was answered is known only when the capture runs on past that (pairing.py capture_ended). Before, each of
these requests was '[no response]', counted 'no reply' (--stats), an 'unanswered' event (--report),
`unanswered: true` (--json, -T fields, --parquet) and found by -Y unanswered, though the capture had
stopped (live -c, a file cut) before the slave could have answered. Now such a request is not counted, and
its note says that it is not known; one the capture runs on past its timeout (here: noise 1.5 s later)
stays unanswered. The engine and VW3_PURE_PYTHON=1 alike."""
from __future__ import annotations

import glob
import json
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_harness import write_pcap

ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
REQUEST = bytes.fromhex("010300000002C40B")  # slave 1 reads 0..1
ANSWER = bytes.fromhex("01030400010002" "2A32")
UNKNOWN = "the capture ends before any response: not known whether it was answered"
WITHIN = "the capture ends 200.0 ms after the request, within the 1000 ms timeout: not known whether it was answered"
PAIR = ("     1     0.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok\n"
        "     2     0.010000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok\n")
THIRD = "     3     1.000000   1 request   Read Holding Registers 0..1 (2) "
# A poll answered, then a request the capture ends with: its own record last, noise 200 ms later (within the
# 1 s timeout), noise 1.5 s later (past it: the master gave up), the first 3 bytes of its answer.
ENDS = {
    "last": ([], THIRD + f"[{UNKNOWN}]  CRC ok\n"),
    "within": ([(b"\x55\x55", 1001.2)], THIRD + f"[{WITHIN}]  CRC ok\n"
               "     4     1.200000   - noise     2 bytes of noise at offset 25: 55 55\n"),
    "past": ([(b"\x55\x55", 1002.5)], THIRD + "[no response]  CRC ok\n"
             "     4     2.500000   - noise     2 bytes of noise at offset 25: 55 55\n"),
    "cut": ([(ANSWER[:3], 1001.02)], THIRD + "[the capture ends inside the response (3 of 9 bytes)]  CRC ok\n"
            "     4     1.020000   - noise     3 bytes of noise at offset 25: 01 03 04\n"),
}


def capture(tmp_path: Path, end: str) -> Path:
    return write_pcap(tmp_path / f"{end}.pcap",
                      [(REQUEST, 1000.0), (ANSWER, 1000.01), (REQUEST, 1001.0)] + ENDS[end][0])


@ENGINES
@pytest.mark.parametrize("end", list(ENDS))
def test_summary(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, end: str) -> None:
    use_engine(monkeypatch, pure)
    assert run_cli([str(capture(tmp_path, end))]) == (0, PAIR + ENDS[end][1], "")


@ENGINES
@pytest.mark.parametrize(("end", "unanswered", "note"), [
    ("last", False, UNKNOWN), ("within", False, WITHIN), ("past", True, None),
    ("cut", False, "the capture ends inside the response (3 of 9 bytes)")])
def test_json_fields_filter_stats(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, end: str,
                                  unanswered: bool, note: str) -> None:
    use_engine(monkeypatch, pure)
    pcap = str(capture(tmp_path, end))
    status, out, _err = run_cli(["--json", pcap])
    third = json.loads(out.splitlines()[2])
    assert (status, third["unanswered"], third["notes"]) == (0, unanswered, [note] if note else [])
    assert run_cli(["-T", "fields", "-e", "frame", "-e", "unanswered", pcap])[1].splitlines()[:3] == [
        "1\t", "2\t", "3\t1" if unanswered else "3\t"]  # (as the plugin: present when true)
    assert run_cli(["-Y", "unanswered", pcap])[1] == (ENDS[end][1].splitlines(keepends=True)[0] if unanswered else "")
    stats = run_cli(["--stats", "-n", pcap])[1].splitlines()
    row = stats[stats.index("slave  function                  req  resp  exceptions  no reply  bad CRC") + 2]
    assert row == f"    1  3 Read Holding Registers    2     1                     {int(unanswered)}        0"


@ENGINES
def test_untimed_detail_and_json(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "one.bin"
    path.write_bytes(REQUEST)  # (no times: nothing tells how long the capture ran on)
    assert run_cli([str(path)]) == (
        0, f"     1            -   1 request   Read Holding Registers 0..1 (2) [{UNKNOWN}]  CRC ok\n", "")
    assert run_cli(["-V", str(path)])[1].splitlines()[-3:] == ["        CRC: 0x0BC4 [CRC ok]", f"    Note: {UNKNOWN}", ""]
    row = json.loads(run_cli(["--json", str(path)])[1])
    assert (row["unanswered"], row["notes"]) == (False, [UNKNOWN])


@ENGINES
@pytest.mark.parametrize(("end", "events"), [("within", 0), ("past", 1)])
def test_report_and_parquet(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, end: str,
                            events: int) -> None:
    use_engine(monkeypatch, pure)
    pcap = str(capture(tmp_path, end))
    report = tmp_path / "report.html"
    assert run_cli(["--report", str(report), pcap])[0] == 0
    assert report.read_text(encoding="utf-8").count("<td>function 3 unanswered</td>") == events
    import pyarrow.parquet as pq

    assert run_cli(["--parquet", str(tmp_path / "data"), pcap])[0] == 0
    frames = pq.read_table(glob.glob(str(tmp_path / "data" / "frames" / "*.parquet"))[0])
    assert frames.column("unanswered").to_pylist() == [False, None, bool(events), None]
