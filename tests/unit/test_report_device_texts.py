"""--report says of a register and of an exception what the summary and --stats say (hunt 55 #3, #10), under
the compiled engine and VW3_PURE_PYTHON=1, from a file and from standard input:
- a value its map row reads as a number without scaling it (ATV71 ACC: a unit and no scale; a user map's row
  with a unit and no scale) was taken for an enumeration: drawn as steps with its own text as a label, its
  unit lost (`"unit":null,"step":true,"labels":{"10":"10 (unscaled, in s)"}`), and the table of parameters
  with a single value said `10 10 (unscaled, in s)`; a scaled value lost its decimals (`4 kHz` where --stats
  says `4.0 kHz`). Now: the unit the register's interpretation gives, steps and labels only from a map's
  enumeration or bit field, the value's text as --stats says it.
- an exception the SEL-749M profile explains by causes (Appendix D) was told with the code's plain meaning
  (`exception 02 to function 3: Illegal Data Address`) where the summary's note says the cause and the
  counters it increments: now the cause the note gives, picked by the request (FC16's byte count)."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from dissector.accel import reportfeed
from dissector.render.pcapwriter import PcapWriter
from helpers import rtu, run_cli, use_engine

T0 = 1767225600.0
# Slave 2 an ATV71: SFR (3102 = 16#0C1E) 40 = 4.0 kHz and ACC (9001 = 16#2329) 10, each read once.
ATV71 = ["02 03 0C1E 0001", "02 03 02 0028", "02 03 2329 0001", "02 03 02 000A"]
# A user map's row with a unit and no scale (B, at 2), read as 475 then 476.
USER_MAP = "address,code,unit,scale,type\n2,B,Hz,,\n"
USER = ["01 03 0002 0001", "01 03 02 01DB", "01 03 0002 0001", "01 03 02 01DC"]
# Slave 1 a SEL-749M: a read at 500 (exception 02), FC16 of 2 registers at 302 with a byte count of 2
# (exception 03: the byte count's cause), FC16 of 126 registers with 4 bytes (exception 03: both causes).
SEL = ["01 03 01F4 0001", "01 83 02",
       "01 10 012E 0002 02 0001", "01 90 03",
       "01 10 012E 007E 04 0001 0002", "01 90 03"]
SEL_EVENTS = [
    "exception 02 to function 3: illegal register to read (increments the Invalid Address counter)",
    "exception 03 to function 16: wrong byte count (increments the Bad Packet Format and Illegal Write counters)",
    "exception 03 to function 16: illegal number of registers (increments the Illegal Register and Illegal Write "
    "counters) or wrong byte count (increments the Bad Packet Format and Illegal Write counters)",
]


def _pcap(path: Path, frames: list[str]) -> Path:
    with path.open("wb") as stream:
        writer = PcapWriter(stream)
        for index, frame in enumerate(frames):
            writer.write(rtu(frame), T0 + 0.05 * index)
        writer.close()
    return path


def _report(tmp_path: Path, argv: list[str], stdin: bytes = b"") -> tuple[str, dict]:
    page = tmp_path / "report.html"
    status, _out, err = run_cli([*argv, "--report", str(page)], stdin=stdin)
    assert status == 0, err
    html = page.read_text()
    found = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', html, re.S)
    assert found is not None
    return html, json.loads(found.group(1))


def _parameter(data: dict, code: str) -> dict:
    found = [parameter for parameter in data["parameters"] if parameter["code"] == code]
    assert len(found) == 1, data["parameters"]
    return {key: found[0][key] for key in ("unit", "step", "labels", "y")}


def _single_value(html: str, code: str) -> str:
    found = re.search(rf'<td>{code}</td><td>[^<]*</td><td>([^<]*)</td>', html)
    assert found is not None, code
    return found.group(1)


def _stats_texts(argv: list[str]) -> dict[str, str]:
    status, out, err = run_cli([*argv, "--stats", "--json"])
    assert status == 0, err
    stats = json.loads(out.strip().splitlines()[-1])
    return {parameter["code"]: parameter["last_text"] for parameter in stats["parameters"]}


@pytest.mark.parametrize("pure", [False, True])
def test_a_number_without_a_scale_keeps_its_unit_and_says_what_stats_says(tmp_path: Path,
                                                                        monkeypatch: pytest.MonkeyPatch,
                                                                        pure: bool) -> None:
    use_engine(monkeypatch, pure)
    argv = [str(_pcap(tmp_path / "atv71.pcap", ATV71)), "--profile", "atv71"]
    html, data = _report(tmp_path, argv)
    # (ACC's unit as its value's text says it, report.js's tooltip `10 (unscaled, in s)`: test_report_unscaled_tooltip)
    assert _parameter(data, "ACC") == {"unit": "(unscaled, in s)", "step": False, "labels": {}, "y": [10]}
    assert _parameter(data, "SFR") == {"unit": "kHz", "step": False, "labels": {}, "y": [4]}
    said = _stats_texts(argv)
    assert _single_value(html, "SFR") == said["SFR"] == "4.0 kHz"
    assert _single_value(html, "ACC") == said["ACC"]
    assert not said["ACC"].startswith("10 10")


@pytest.mark.parametrize("pure", [False, True])
def test_a_user_map_row_with_a_unit_and_no_scale_is_no_enumeration(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                 pure: bool) -> None:
    use_engine(monkeypatch, pure)
    (tmp_path / "map.csv").write_text(USER_MAP)
    argv = [str(_pcap(tmp_path / "user.pcap", USER)), "--map", str(tmp_path / "map.csv")]
    _html, data = _report(tmp_path, argv)
    assert _parameter(data, "B") == {"unit": "Hz", "step": False, "labels": {}, "y": [475, 476]}


@pytest.mark.parametrize("pure", [False, True])
def test_values_read_before_auto_chose_are_read_again_as_numbers(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                                  pure: bool) -> None:
    """Standard input, one pass: ACC is read before profile `auto` chooses the ATV71 (by the reads of CHCF
    becoming protected, p.38), its state held back until then: drawn as the file draws it."""
    use_engine(monkeypatch, pure)
    frames = ["0C 03 2329 0001", "0C 03 02 000A"] + [
        "0C 03 20D0 0003", "0C 03 06 8000 0003 0002", "0C 03 20D0 0003", "0C 03 06 8000 0003 0002",
        "0C 03 20D0 0003", "0C 03 06 8000 8000 0002", "0C 03 20D0 0003", "0C 03 06 8000 8000 0002"]
    capture = _pcap(tmp_path / "auto.pcap", frames)
    from_file, file_data = _report(tmp_path, [str(capture)])
    from_stdin, stdin_data = _report(tmp_path, ["-"], stdin=capture.read_bytes())
    for html, data in ((from_file, file_data), (from_stdin, stdin_data)):
        assert _parameter(data, "ACC") == {"unit": "(unscaled, in s)", "step": False, "labels": {}, "y": [10]}
        assert _single_value(html, "ACC") == _stats_texts([str(capture)])["ACC"]


@pytest.mark.parametrize("pure", [False, True])
def test_sel_exception_events_say_the_cause_the_summary_says(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                             pure: bool) -> None:
    use_engine(monkeypatch, pure)
    told: list[str] = []
    making = reportfeed.exception_event

    def counting(annotator: object) -> object:
        text = making(annotator)

        def telling(*args: object) -> str:
            told.append(text(*args))  # type: ignore[operator]
            return told[-1]

        return telling

    monkeypatch.setattr(reportfeed, "exception_event", counting)
    argv = [str(_pcap(tmp_path / "sel.pcap", SEL)), "--profile", "1=sel749m"]
    _html, data = _report(tmp_path, argv)
    assert [event[3] for event in data["events"] if event[1] == "exception"] == SEL_EVENTS
    assert pure or told  # the engine told some itself
    status, out, err = run_cli(argv)
    assert status == 0, err
    for event in SEL_EVENTS:  # the summary's note says the same meaning
        meaning = event.split(": ", 1)[1]
        assert f": {meaning}]" in out
