"""--watch: one line per change of a watched parameter, values named and scaled as in the summary."""
from __future__ import annotations

import json

from conftest import ROOT
from helpers import run_cli

CAPTURES = ROOT / "captures"


def test_p38_chcf_prints_the_two_changes_only() -> None:
    # Frames 2/4 read 3, 6/8 read 16#8000 (protected), 10/12 draw exception 02: two changes.
    status, out, err = run_cli([str(CAPTURES / "p38_protection.pcap"), "--watch", "CHCF"])
    assert (status, err) == (0, "")
    assert out.splitlines() == [
        "     1.059949  12 CHCF 3 IO (I/O profile) -> protected",
        "     2.105960  12 CHCF protected -> exception 02 (protected)",
    ]


def test_untimed_capture_codes_case_and_addresses_json() -> None:
    status, out, err = run_cli([str(CAPTURES / "p38_protection.bin"), "--watch", "chcf,8400,COP", "--json"])
    assert (status, err) == (0, "")
    changes = [json.loads(line) for line in out.splitlines()]
    assert [(c["frame"], c["address"], c["code"], c["old"], c["new"]) for c in changes] == [
        (6, 8401, "CHCF", "3 IO (I/O profile)", "protected"),
        (10, 8401, "CHCF", "protected", "exception 02 (protected)"),
        (10, 8402, "COP", "2 Cd (command)", "exception 02 (protected)"),
        (10, 8400, None, "non-existent", "exception 02 (non-existent)"),
    ]
    assert all(c["time"] is None for c in changes)


def test_commissioning_writes_and_scaled_reads() -> None:
    status, out, _ = run_cli([str(CAPTURES / "atv71_commissioning.pcap"), "--watch", "CHCF,HSP"])
    assert status == 0
    assert out.splitlines() == [
        "     0.111429   2 CHCF 3 IO (I/O profile) -> 2 SEP (separate)",  # FC6 echo confirms the write
        "     1.366757   2 HSP 50.0 -> 55.0 (Hz)",
        # CHCF = 3 refused with exception 07 while running (frame 64) changes nothing; accepted at the end.
        "     2.289814   2 CHCF 2 SEP (separate) -> 3 IO (I/O profile)",
    ]
    status, out, _ = run_cli([str(CAPTURES / "atv71_commissioning.pcap"), "--watch", "RFR"])
    lines = out.splitlines()
    assert lines[0] == "     0.593146   2 RFR 0.0 -> 2.1 (Hz)" and lines[-1] == "     2.242107   2 RFR 0.7 -> 0.0 (Hz)"
    assert len(lines) == 26  # 13 steps up to 30.0 Hz, 13 down to 0.0


def test_time_column_ignores_the_display_filter() -> None:
    status, out, _ = run_cli(
        [str(CAPTURES / "p38_protection.pcap"), "--watch", "CHCF", "-Y", "frame >= 3"]
    )
    # -Y chooses the frames watched (frame 4 is the first CHCF seen); times still count from frame 1.
    assert status == 0 and out.splitlines() == [
        "     1.059949  12 CHCF 3 IO (I/O profile) -> protected",
        "     2.105960  12 CHCF protected -> exception 02 (protected)",
    ]


def test_bad_watch_lists_are_one_line_errors() -> None:
    for value, message in [
        ("", "--watch: give parameter codes or addresses"),
        ("CH-CF", "--watch: 'CH-CF' is neither a parameter code nor an address"),
        ("70000", "--watch: address 70000 is beyond 65535"),
    ]:
        status, out, err = run_cli([str(CAPTURES / "p38_protection.pcap"), "--watch", value])
        assert status == 2 and out == "" and err.startswith(f"vw3-decode: {message}"), (value, err)
        assert len(err.splitlines()) == 1


def test_watch_contradictions_are_refused() -> None:
    capture = str(CAPTURES / "p38_protection.bin")
    for extra, message in [
        (["-V"], "--watch replaces the items: -V, -x and -T fields show none"),
        (["--stats"], "--watch and --stats are two outputs: choose one"),
    ]:
        assert run_cli([capture, "--watch", "CHCF", *extra]) == (2, "", f"vw3-decode: {message}\n")
