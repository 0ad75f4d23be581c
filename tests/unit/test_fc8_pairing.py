"""FC8 pairing as the spec states it (data/modbus.toml [pairing]): Force Listen Only Mode (08/04) is never
answered (Modbus Application Protocol 6.8.1: "No response is returned"), so it awaits nothing, is noted
as such and is never unanswered, though an exception (a server that does not support it) still answers
it; an FC8 answer echoes its request's sub-function, so an FC8 frame that does not is no answer but the
master's next request (requests and answers have the same shape). Before, an 08/04 took the next FC8 request of its slave for its answer and every later
diagnostic of that slave shifted by one. Exact outputs for exact bytes, the summary, -V, --json, --stats
and --report, under the compiled engine and the Python stages (VW3_PURE_PYTHON=1) alike."""
from __future__ import annotations

import io
import json
import re
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run
from dissector.render.pcapwriter import PcapWriter
from helpers import rtu, use_engine

T0 = 1767225600.0
LISTEN_ONLY = rtu("01 08 0004 0000")  # 01 08 00 04 00 00 A1 CA
RESTART = rtu("01 08 0001 0000")  # 01 08 00 01 00 00 B1 CB
REGISTER_QUERY, REGISTER_ANSWER = rtu("01 08 0002 0000"), rtu("01 08 0002 0007")
REFUSED = rtu("01 88 01")  # exception 1: a server that does not support 04 says so
NOTE = "no response expected: the spec's server returns none"
# (after 08/04 the slave is in listen-only mode: it answers nothing, 08/01 included, which ends the mode)
ENDS = "slave 1 leaves listen-only mode (since #1, 08/04): the spec's server does not answer this"
ENDS_CUT = "the capture ends before any response: not known whether it was answered"
# 08/04, then 08/01 (unanswered: it ends the mode), the master's repeat of it and its echo
SESSION = [LISTEN_ONLY, RESTART, RESTART, RESTART]


def decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    use_engine(monkeypatch, pure)
    out, err = io.StringIO(), io.StringIO()
    assert run([*argv, "-n"], Environment(io.BytesIO(b""), out, err, False, False)) == 0
    assert err.getvalue() == ""
    return out.getvalue()


def both(argv: list[str], monkeypatch: pytest.MonkeyPatch) -> str:
    """The output, the same under the engine and the Python stages."""
    engine, pure = decode(argv, monkeypatch, False), decode(argv, monkeypatch, True)
    assert engine == pure
    return engine


def hexes(*frames: bytes) -> list[str]:
    return [argument for frame in frames for argument in ("--hex", frame.hex(" "))]


def capture(path: Path, frames: list[bytes], step: float = 0.010) -> Path:
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index, frame in enumerate(frames):
            writer.write(frame, T0 + step * index)
    return path


def lines(text: str) -> list[str]:
    return [re.sub(r"\s+", " ", line.strip()) for line in text.splitlines()]


def test_listen_only_awaits_nothing_summary(monkeypatch: pytest.MonkeyPatch) -> None:
    # The reviewer's bytes: 08/04, then 08/01 and the same again, the master's repeat (the slave in the mode
    # does not answer the 08/01 that ends it: before, the third frame was taken for its echo).
    assert lines(both(hexes(LISTEN_ONLY, RESTART, RESTART), monkeypatch)) == [
        f"1 - 1 request Diagnostics 04h Force Listen Only Mode = 0 [{NOTE}] CRC ok",
        f"2 - 1 request Diagnostics 01h Restart Communications Option = 0 [{ENDS}] CRC ok",
        f"3 - 1 request Diagnostics 01h Restart Communications Option = 0 [{ENDS_CUT}] CRC ok",
    ]
    assert lines(both(hexes(*SESSION), monkeypatch))[2:] == [
        "3 - 1 request Diagnostics 01h Restart Communications Option = 0 CRC ok",
        "4 - 1 response Diagnostics 01h Restart Communications Option = 0 [#3] CRC ok",
    ]


def test_listen_only_then_another_sub_function(monkeypatch: pytest.MonkeyPatch) -> None:
    # 08/04 then 08/02 and its answer: the 08/02 is a request, never the 08/04's answer; the slave answers it,
    # so it is not in listen-only mode (pairing.py _heard: no "it does not answer" on a request it answers)
    assert lines(both(hexes(LISTEN_ONLY, REGISTER_QUERY, REGISTER_ANSWER), monkeypatch)) == [
        f"1 - 1 request Diagnostics 04h Force Listen Only Mode = 0 [{NOTE}] CRC ok",
        "2 - 1 request Diagnostics 02h Return Diagnostic Register = 0 CRC ok",
        "3 - 1 response Diagnostics 02h Return Diagnostic Register = 7 [#2] [slave 1 answers: it is not in "
        "listen-only mode (#1, 08/04)] CRC ok",
    ]


def test_an_exception_still_answers_listen_only(monkeypatch: pytest.MonkeyPatch) -> None:
    # The exception answers the 08/04; an 08/04 at the end of the capture is not unanswered either.
    assert lines(both(hexes(LISTEN_ONLY, REFUSED, RESTART, RESTART, LISTEN_ONLY), monkeypatch)) == [
        f"1 - 1 request Diagnostics 04h Force Listen Only Mode = 0 [{NOTE}] CRC ok",
        "2 - 1 exception Diagnostics: exception 1 (Illegal Function) [#1] CRC ok",
        "3 - 1 request Diagnostics 01h Restart Communications Option = 0 CRC ok",
        "4 - 1 response Diagnostics 01h Restart Communications Option = 0 [#3] CRC ok",
        f"5 - 1 request Diagnostics 04h Force Listen Only Mode = 0 [{NOTE}] CRC ok",
    ]


RETURN_COUNT = rtu("01 08 000B 0000")  # 01 08 00 0B 00 00 91 C9: Return Bus Message Count


@pytest.mark.parametrize("answer", [False, True])
def test_a_frame_that_does_not_echo_the_sub_function_is_the_next_request(
    answer: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    # 08/0B unanswered, then 08/02: not 08/0B's answer (it would echo 000B) but the master's next request,
    # the same shape (the framer weighs the echo, data/modbus.toml [pairing]); its answer pairs with it.
    # Before, the 08/02 was "response [no request] [response without a matching request in the capture]"
    # and its answer a request.
    frames = (RETURN_COUNT, REGISTER_QUERY, REGISTER_ANSWER) if answer else (RETURN_COUNT, REGISTER_QUERY)
    assert lines(both(hexes(*frames), monkeypatch)) == [
        "1 - 1 request Diagnostics 0Bh Return Bus Message Count = 0 [no response] CRC ok",
        *(["2 - 1 request Diagnostics 02h Return Diagnostic Register = 0 CRC ok",
           "3 - 1 response Diagnostics 02h Return Diagnostic Register = 7 [#2] CRC ok"] if answer else
          ["2 - 1 request Diagnostics 02h Return Diagnostic Register = 0 "
           "[the capture ends before any response: not known whether it was answered] CRC ok"]),
    ]


def test_the_echo_is_weighed_in_one_run_of_bytes_and_in_a_pcap(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # (framed in one go, the framer's expectation decides; a pcap's records, the same)
    assert lines(both(["--hex", (RETURN_COUNT + REGISTER_QUERY + REGISTER_ANSWER).hex(" ")], monkeypatch)) == [
        "1 - 1 request Diagnostics 0Bh Return Bus Message Count = 0 [no response] CRC ok",
        "2 - 1 request Diagnostics 02h Return Diagnostic Register = 0 CRC ok",
        "3 - 1 response Diagnostics 02h Return Diagnostic Register = 7 [#2] CRC ok",
    ]
    pcap = capture(tmp_path / "echo.pcap", [RETURN_COUNT, REGISTER_QUERY, REGISTER_ANSWER, RESTART, RESTART])
    assert lines(both([str(pcap)], monkeypatch)) == [
        "1 0.000000 1 request Diagnostics 0Bh Return Bus Message Count = 0 [no response] CRC ok",
        "2 0.010000 1 request Diagnostics 02h Return Diagnostic Register = 0 CRC ok",
        "3 0.020000 1 response Diagnostics 02h Return Diagnostic Register = 7 [#2, 10.0 ms] CRC ok",
        "4 0.030000 1 request Diagnostics 01h Restart Communications Option = 0 CRC ok",
        "5 0.040000 1 response Diagnostics 01h Restart Communications Option = 0 [#4, 10.0 ms] CRC ok",
    ]


def test_an_answer_that_echoes_is_its_answer_whatever_its_data(monkeypatch: pytest.MonkeyPatch) -> None:
    # The echo is the sub-function alone: 08/02's answer carries the register, not the request's 0000.
    assert lines(both(hexes(REGISTER_QUERY, REGISTER_ANSWER), monkeypatch)) == [
        "1 - 1 request Diagnostics 02h Return Diagnostic Register = 0 CRC ok",
        "2 - 1 response Diagnostics 02h Return Diagnostic Register = 7 [#1] CRC ok",
    ]


def test_summary_of_a_capture(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pcap = capture(tmp_path / "fc8.pcap", SESSION)
    assert lines(both([str(pcap)], monkeypatch)) == [
        f"1 0.000000 1 request Diagnostics 04h Force Listen Only Mode = 0 [{NOTE}] CRC ok",
        f"2 0.010000 1 request Diagnostics 01h Restart Communications Option = 0 [{ENDS}] CRC ok",
        "3 0.020000 1 request Diagnostics 01h Restart Communications Option = 0 CRC ok",
        "4 0.030000 1 response Diagnostics 01h Restart Communications Option = 0 [#3, 10.0 ms] CRC ok",
    ]


def test_detail(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pcap = capture(tmp_path / "fc8.pcap", SESSION)
    detail = both([str(pcap), "-V"], monkeypatch)
    frames = detail.split("\n\n")
    assert frames[0].splitlines()[0] == "Frame 1: 8 bytes at offset 0, request (RTU)"
    assert frames[0].splitlines()[-1] == f"    Note: {NOTE}"
    assert "Response in frame" not in frames[0] and "no response" not in frames[0].replace(NOTE, "")
    assert frames[1].splitlines()[0] == "Frame 2: 8 bytes at offset 8, request (RTU)"
    assert frames[1].splitlines()[-1] == f"    Note: {ENDS}" and "Response in frame" not in frames[1]
    assert frames[2].splitlines()[0] == "Frame 3: 8 bytes at offset 16, request (RTU)"
    assert frames[2].splitlines()[-1] == "    Response in frame: 4"
    assert frames[3].splitlines()[0] == "Frame 4: 8 bytes at offset 24, response (RTU)"
    assert frames[3].splitlines()[-2:] == ["    Request in frame: 3", "    Response time: 10.000 ms"]


def test_json(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pcap = capture(tmp_path / "fc8.pcap", SESSION)
    records = [json.loads(line) for line in both([str(pcap), "--json"], monkeypatch).splitlines()]
    picked = [{key: record.get(key) for key in
               ("frame", "kind", "subfunction", "unanswered", "request_frame", "response_frame", "notes")}
              for record in records]
    assert picked == [
        {"frame": 1, "kind": "request", "subfunction": 4, "unanswered": False, "request_frame": None,
         "response_frame": None, "notes": [NOTE]},
        {"frame": 2, "kind": "request", "subfunction": 1, "unanswered": False, "request_frame": None,
         "response_frame": None, "notes": [ENDS]},
        {"frame": 3, "kind": "request", "subfunction": 1, "unanswered": False, "request_frame": None,
         "response_frame": 4, "notes": []},
        {"frame": 4, "kind": "response", "subfunction": 1, "unanswered": None, "request_frame": 3,
         "response_frame": None, "notes": []},
    ]
    assert records[3]["response_time"] == 0.01


def test_stats(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pcap = capture(tmp_path / "fc8.pcap", SESSION)
    stats = json.loads(both([str(pcap), "--stats", "--json"], monkeypatch))
    assert stats["functions"] == [{
        "slave": 1, "function": 8, "function_name": "Diagnostics", "requests": 3, "broadcasts": 0,
        "responses": 1, "exceptions": {}, "unanswered": 0, "crc_errors": 0,
        "response_time": {"count": 1, "min": 0.01, "median": 0.01, "p95": 0.01, "max": 0.01},
    }]
    table = both([str(pcap), "--stats"], monkeypatch)
    assert "    1  8 Diagnostics    3     1                     0        0\n" in table


def test_stats_poll_cycle(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # A master that sends 08/04 every 100 ms: three requests, none a miss, none unanswered.
    pcap = capture(tmp_path / "listen.pcap", [LISTEN_ONLY] * 3, step=0.100)
    stats = json.loads(both([str(pcap), "--stats", "--json"], monkeypatch))
    (function,) = stats["functions"]
    assert (function["requests"], function["responses"], function["unanswered"]) == (3, 0, 0)
    assert function["response_time"] is None
    (poll,) = stats["poll_cycle"]
    assert (poll["slave"], poll["function"], poll["count"], poll["no_answer"], poll["misses"]) == (1, 8, 3, 0, 0)
    assert poll["period"] == pytest.approx(0.1)
    assert stats["bus"]["outages"] == []


def test_report(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pcap = capture(tmp_path / "listen.pcap", [*SESSION, LISTEN_ONLY, LISTEN_ONLY], step=0.100)
    made = []
    for pure in (False, True):
        page = tmp_path / f"report{pure}.html"
        decode([str(pcap), "--report", str(page)], monkeypatch, pure)
        found = re.search(r'<script type="application/json" id="report-data">(.*?)</script>',
                          page.read_text(encoding="utf-8"), re.S)
        assert found is not None
        made.append(json.loads(found.group(1)))
    assert made[0] == made[1]
    data = made[0]
    assert data["event_counts"]["unanswered"] == 0
    assert [event for event in data["events"] if event[1] == "unanswered"] == []


def test_ascii_weighs_the_echo_as_rtu_does(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # The same exchange in Modbus ASCII (before: the 08/02 query 'response [no request]', its answer a
    # request, where RTU already paired them).
    text = tmp_path / "echo.txt"
    text.write_text(":0108000B0000EC\r\n:010800020000F5\r\n:010800020007EE\r\n")
    assert lines(both([str(text), "--mode", "ascii"], monkeypatch)) == [
        "1 - 1 request Diagnostics 0Bh Return Bus Message Count = 0 [no response] LRC ok",
        "2 - 1 request Diagnostics 02h Return Diagnostic Register = 0 LRC ok",
        "3 - 1 response Diagnostics 02h Return Diagnostic Register = 7 [#2] LRC ok",
    ]
