"""Noise in tshark's single pass (no -2, the documented command): bytes that are noise only once later records
came were kept in the record holding their last byte, which tshark had shown already, so no record showed
them (captures/noisy_bus.pcap: vw3-decode 2 noise items, the plugin's one pass 0). Now the record that decides
them shows them too, from their own bytes, naming the records they came from (`[Bytes from record 2]`, Info
`noise (4 bytes) from #2`); the later passes (-2, Wireshark's packet list) show them in the record holding their
last byte, as before. Bytes of a noise run whose end is not known yet say so (`noise (3 bytes so far)`), not
that they continue a frame; -2 says where a run's bytes went as noise (`(2 bytes of noise in #3)`). Exact Info,
the items' fields, and every item as vw3-decode reading the capture once (one pass) or as a file (-2)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import compare, lua_kind, lua_shown
from lua_harness import assert_as_vw3_decode_in_one_and_two_passes, ROOT, lua_errors, lua_items, python_items, run_tshark, write_pcap

pytestmark = pytest.mark.integration
# (what one pass cannot know when it shows a request: the answer after it, test_lua_parity_auto.py)
LATER = frozenset(["response_frame", "unanswered"])
REQUEST, ANSWER = rtu("01 01 0000 000A"), rtu("01 01 02 AA02")  # 01 01 00 00 00 0a bc 0d, 01 01 02 aa 02 46 9d
NOISE = bytes.fromhex("237b2ed9")  # slave 0x23, code 0x7b: no frame, known only with later bytes
READ, ANSWERED = "1 Read Coils request 0..9 (10)", "1 Read Coils response 0..9 (10)"
P = " [provisional]"  # (one pass: read before profile auto chose slave 1's device)


def _pcap(tmp_path: Path, records: list[bytes]) -> Path:
    # 2 ms apart: no silence of t3.5 at 19200 baud after these few bytes ends a noise run
    return write_pcap(tmp_path / "noise.pcap", [(data, 1700000000 + index * 0.002) for index, data in enumerate(records)])


def _infos(pcap: Path, two_pass: bool) -> list[str]:
    got = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=two_pass)
    assert got.returncode == 0 and not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
    return got.stdout.splitlines()


def _items(pcap: Path, two_pass: bool) -> list[tuple[int, str, int, int, int]]:
    """(record, kind, item, stream offset, length) of every item shown."""
    lua, _, _ = lua_items(pcap, two_pass=two_pass)
    return [(item.record, lua_kind(item), int(item.fields["item"]), int(item.fields["offset"]), item.length)
            for item in lua_shown(lua)]


def _same_as_vw3_decode(pcap: Path) -> None:
    assert_as_vw3_decode_in_one_and_two_passes(pcap, LATER)


def test_noise_between_records_is_shown_in_the_record_that_decides_it(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path, [REQUEST, NOISE, ANSWER])
    # (record 2: '23 7b 2e' are noise as soon as they come, 'd9' may begin a frame until record 3)
    assert _infos(pcap, two_pass=False) == [
        READ + P, "noise (3 bytes so far); (1 byte continues)", f"noise (4 bytes) from #2; {ANSWERED}{P}"]
    assert _infos(pcap, two_pass=True) == [READ, "noise (4 bytes)", ANSWERED]
    assert _items(pcap, two_pass=False) == [(1, "request", 1, 0, 8), (3, "noise", 2, 8, 4), (3, "response", 3, 12, 7)]
    assert _items(pcap, two_pass=True) == [(1, "request", 1, 0, 8), (2, "noise", 2, 8, 4), (3, "response", 3, 12, 7)]
    details = run_tshark(pcap, "-V", "-O", "vw3", two_pass=False).stdout
    record_3 = details[details.index("Frame 3:"):]
    assert "VW3 noise, 4 bytes: no valid frame\n" in record_3 and "    Data: 237b2ed9\n" in record_3, record_3
    assert "    [Bytes from record 2]\n" in record_3, record_3
    assert "Bytes from record" not in run_tshark(pcap, "-V", "-O", "vw3").stdout  # (-2: in its own record)
    _same_as_vw3_decode(pcap)


def test_noise_before_the_first_frame_and_after_a_frame_in_its_record(tmp_path: Path) -> None:
    first = _pcap(tmp_path, [NOISE, REQUEST, ANSWER])
    assert _infos(first, two_pass=False) == ["noise (3 bytes so far); (1 byte continues)", f"noise (4 bytes) from #1; {READ}{P}", ANSWERED + P]
    assert _items(first, two_pass=False)[0] == (2, "noise", 1, 0, 4)
    _same_as_vw3_decode(first)
    glued = _pcap(tmp_path, [REQUEST + NOISE[:2], ANSWER])
    assert _infos(glued, two_pass=False) == [f"{READ}{P}; (2 bytes continue)", f"noise (2 bytes) from #1; {ANSWERED}{P}"]
    assert _infos(glued, two_pass=True) == [f"{READ}; noise (2 bytes)", ANSWERED]
    _same_as_vw3_decode(glued)


def test_a_noise_run_over_two_records(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path, [REQUEST, NOISE[:2], NOISE[2:], ANSWER])
    # (record 3: '23 7b 2e' are noise already, the run goes on; 'd9' may still begin a frame)
    assert _infos(pcap, two_pass=False) == [
        READ + P, "(2 bytes continue)", "noise (1 byte so far); (1 byte continues)",
        f"noise (4 bytes) from #2, #3; {ANSWERED}{P}"]
    # (-2: record 2's bytes are noise shown in record 3, not bytes that continue a frame)
    assert _infos(pcap, two_pass=True) == [READ, "(2 bytes of noise in #3)", "noise (4 bytes)", ANSWERED]
    details = run_tshark(pcap, "-V", "-O", "vw3", two_pass=False).stdout
    assert "    [Bytes from records 2, 3]\n" in details[details.index("Frame 4:"):]
    assert "VW3 bytes of noise shown in a later record: 2 bytes of noise in item 2 (record 3)" in run_tshark(
        pcap, "-V", "-O", "vw3").stdout
    _same_as_vw3_decode(pcap)


def test_noise_at_the_end_of_the_capture(tmp_path: Path) -> None:
    # One pass never learns that a record is the capture's last: what is noise so far is said as such, the
    # rest waits for bytes that never come (-2 frames it at the end, as vw3-decode at the end of its input).
    pcap = _pcap(tmp_path, [REQUEST, ANSWER, NOISE])
    assert _infos(pcap, two_pass=False) == [READ + P, ANSWERED + P, "noise (3 bytes so far); (1 byte continues)"]
    assert _infos(pcap, two_pass=True) == [READ, ANSWERED, "noise (4 bytes)"]
    details = run_tshark(pcap, "-V", "-O", "vw3", two_pass=False).stdout
    assert "VW3 noise so far, 3 bytes\n    Data: 237b2e\n" in details, details
    two, _, _ = lua_items(pcap)
    assert not compare(python_items(pcap), two)


def test_noisy_bus_shows_its_noise_in_one_pass(tmp_path: Path) -> None:
    pcap = ROOT / "captures" / "noisy_bus.pcap"
    one, _, _ = lua_items(pcap, two_pass=False)
    stream = python_items(pcap, one_pass=True)
    assert [item.data["frame"] for item in stream if item.data["kind"] == "noise"] == [1, 34]
    differences = compare(stream, one, ignore=LATER)
    assert not differences, "\n".join(differences[:40])
    noise = [(item.record, int(item.fields["item"]), item.length) for item in lua_shown(one) if lua_kind(item) == "noise"]
    assert noise == [(2, 1, 4), (35, 34, 5)]
