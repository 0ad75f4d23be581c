"""--watch: one line per change of a watched parameter, values named and scaled as in the summary."""
from __future__ import annotations

import json

from conftest import ROOT
from helpers import run_cli

CAPTURES = ROOT / "captures"


def test_p38_is_one_change_per_parameter() -> None:
    # Frames 2/4 read CHCF 3, 6/8 read 16#8000 (protected), 10/12 draw exception 02 (still protected):
    # one change, the one the summary notes in frame 6; COP's in frame 10.
    status, out, err = run_cli([str(CAPTURES / "p38_protection.pcap"), "--watch", "CHCF,COP"])
    assert (status, err) == (0, "")
    assert out.splitlines() == [
        "     6     1.059949  12 CHCF IO (I/O profile) -> protected",
        "    10     2.105960  12 COP Cd (command) -> protected (exception 02)",
    ]


def test_untimed_capture_codes_case_and_addresses_json() -> None:
    # (forced: under profile auto frame 2 is before the evidence, issue 26)
    status, out, err = run_cli([str(CAPTURES / "p38_protection.bin"), "--watch", "chcf,8400,COP", "--json",
                                "--profile", "atv71"])
    assert (status, err) == (0, "")
    changes = [json.loads(line) for line in out.splitlines()]
    assert [(c["frame"], c["address"], c["code"], c["old"], c["new"]) for c in changes] == [
        (6, 8401, "CHCF", "IO (I/O profile)", "protected"),
        (10, 8402, "COP", "Cd (command)", "protected (exception 02)"),
    ]
    assert all(c["time"] is None and c["time_relative"] is None for c in changes)
    status, out, _ = run_cli([str(CAPTURES / "p38_protection.bin"), "--watch", "chcf,8400,COP", "--profile", "atv71"])
    assert out.splitlines() == [
        "     6            -  12 CHCF IO (I/O profile) -> protected",
        "    10            -  12 COP Cd (command) -> protected (exception 02)",
    ]


def test_commissioning_writes_scaled_reads_and_status_words() -> None:
    status, out, _ = run_cli([str(CAPTURES / "atv71_commissioning.pcap"), "--watch", "CHCF,HSP,ETA"])
    assert status == 0
    bits = {
        0x231: "Ready to switch on, Voltage enabled, Quick stop inactive, Remote",
        0x233: "Ready to switch on, Switched on, Voltage enabled, Quick stop inactive, Remote",
        0x237: "Ready to switch on, Switched on, Operation enabled, Voltage enabled, Quick stop inactive, Remote",
    }

    def eta(old: int, new: int) -> str:  # a status word as the manuals write it: 16#0231
        return f"2 ETA 16#{old:04X} ({bits[old]}) -> 16#{new:04X} ({bits[new]})"

    assert out.splitlines() == [
        "     8     0.111429   2 CHCF IO (I/O profile) -> SEP (separate)",  # FC6 echo confirms the write
        "    26     0.404108   " + eta(0x231, 0x233),
        "    32     0.549622   " + eta(0x233, 0x237),
        "    66     1.366757   2 HSP 50.0 -> 55.0 (Hz)",
        "    76     1.596870   " + eta(0x237, 0x233),
        "   100     2.193622   " + eta(0x233, 0x231),
        # CHCF = 3 refused with exception 07 while running (frame 64) changes nothing; accepted at the end.
        "   104     2.289814   2 CHCF SEP (separate) -> IO (I/O profile)",
    ]
    status, out, _ = run_cli([str(CAPTURES / "atv71_commissioning.pcap"), "--watch", "RFR"])
    lines = out.splitlines()
    assert lines[0] == "    34     0.593146   2 RFR 0.0 -> 2.1 (Hz)" and lines[-1] == "   102     2.242107   2 RFR 0.7 -> 0.0 (Hz)"
    assert len(lines) == 26  # 13 steps up to 30.0 Hz, 13 down to 0.0


def test_time_column_follows_t_and_ignores_the_display_filter() -> None:
    capture = str(CAPTURES / "p38_protection.pcap")
    status, out, _ = run_cli([capture, "--watch", "CHCF", "-Y", "frame >= 3"])
    # -Y chooses the frames watched (frame 4 is the first CHCF seen); times still count from frame 1.
    assert status == 0 and out.splitlines() == ["     6     1.059949  12 CHCF IO (I/O profile) -> protected"]
    # The same time column as the summary line of frame 6 with the same -t.
    status, out, _ = run_cli([capture, "--watch", "CHCF", "-t", "e"])
    assert out.splitlines() == ["     6 1767225601.069064  12 CHCF IO (I/O profile) -> protected"]
    status, out, _ = run_cli([capture, "--watch", "CHCF", "-t", "ud"])
    assert out.splitlines() == ["     6 2026-01-01 00:00:01.069064  12 CHCF IO (I/O profile) -> protected"]
    status, out, _ = run_cli([capture, "--watch", "CHCF", "-t", "d"])  # from frame 5, captured before
    assert out.splitlines() == ["     6     0.009832  12 CHCF IO (I/O profile) -> protected"]


def test_misspelt_and_unknown_names_are_errors_with_suggestions() -> None:
    capture = str(CAPTURES / "p38_protection.pcap")
    for value, message in [
        ("CHFC", "--watch CHFC: no map of this run has that parameter code (did you mean CHCF?)"),
        ("FOO", "--watch FOO: no map of this run has that parameter code"),
        ("CHCF,HPS", "--watch HPS: no map of this run has that parameter code (did you mean HSP"),
    ]:
        status, out, err = run_cli([capture, "--watch", value])
        assert (status, out) == (2, "") and err.startswith(f"vw3-decode: {message}"), (value, err)
        assert len(err.splitlines()) == 1
    status, out, err = run_cli([capture, "--watch", "ETA", "-n"])
    assert (status, out) == (2, "") and err == (
        "vw3-decode: --watch ETA: codes are the device profiles' names, and -n turns profiles off: "
        "give register addresses\n"
    )
    assert run_cli([capture, "--watch", "8401", "-n"]) == (
        0, "     6     1.059949  12 8401 3 -> 32768\n", ""
    )


def test_a_value_read_before_the_profile_is_chosen_is_named_by_it(tmp_path) -> None:
    # Slave 12's first request writes LFR (8502) = 296 before any answer says it is an Altivar; its
    # answer decides (traffic fits the ATV71 map): the write reads 29.6 Hz, by address and by code.
    from helpers import rtu

    capture = tmp_path / "late.bin"
    request = rtu("0C 17 0C 81 00 02 21 35 00 02 04 00 0F 01 28")  # FC23 read 3201..3202, write 8501..8502
    answer = rtu("0C 17 04 02 31 00 95")
    # LFR = 461 -> 46.1 Hz, reading 3202..3203 (RFR, FRH): a second read the ATV71 map explains, which
    # profile auto needs (one is no evidence, issue 26)
    request2 = rtu("0C 17 0C 82 00 02 21 35 00 02 04 00 0F 01 CD")
    answer2 = rtu("0C 17 04 00 95 01 F4")
    capture.write_bytes(request + answer + request2 + answer2)
    for name in ("8502", "LFR", "lfr"):
        status, out, err = run_cli([str(capture), "--watch", name])
        assert (status, err) == (0, ""), err
        assert out.splitlines() == ["     4            -  12 LFR 29.6 -> 46.1 (Hz)"]  # confirmed by its answer, name
    # --stats names the value kept from before the choice by the device chosen.
    status, out, _ = run_cli([str(capture), "--stats", "--json"])
    (lfr,) = [row for row in json.loads(out)["parameters"] if row["address"] == 8502]
    assert (lfr["code"], lfr["last"], lfr["last_text"], lfr["changes"]) == ("LFR", 461, "46.1 Hz", 1)
    # Read once (standard input) too: frames 1 to 3 come before the choice and are read again with the
    # ATV71 once frame 4 made it, so frame 4's line (after the choice) compares with 29.6 Hz, and the
    # report's LFR trend and --stats are named by the device chosen (no 296 Hz point beside 46.1).
    import re

    data = capture.read_bytes()
    for source in (str(capture), "-"):
        assert run_cli([source, "--watch", "LFR"], stdin=data)[1:] == ("     4            -  12 LFR 29.6 -> 46.1 (Hz)\n", "")
        page = tmp_path / "late.html"
        assert run_cli([source, "--report", str(page)], stdin=data)[0] == 0
        report = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(encoding="utf-8")).group(1))
        assert [(p["x"], p["y"]) for p in report["parameters"] if p.get("code") == "LFR"] == [([2.0, 4.0], [29.6, 46.1])]
        (lfr,) = [row for row in json.loads(run_cli([source, "--stats", "--json"], stdin=data)[1])["parameters"]
                  if row["address"] == 8502]
        assert (lfr["code"], lfr["last"], lfr["last_text"], lfr["changes"]) == ("LFR", 461, "46.1 Hz", 1)


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


def test_json_time_is_the_items_time_whatever_t_says() -> None:
    # --json items carry seconds since the epoch under `time`: so does --watch --json (-t shapes the
    # text lines only); the relative time is under -T fields' key, time_relative.
    capture = str(CAPTURES / "p38_protection.pcap")
    (item,) = [json.loads(line) for line in run_cli([capture, "--json", "-Y", "frame == 6"])[1].splitlines()]
    expected = {"time": 1767225601.069064, "time_relative": 1.059949, "frame": 6, "slave": 12, "address": 8401,
                "code": "CHCF", "old": "IO (I/O profile)", "new": "protected", "unit": None}
    assert item["time"] == expected["time"]
    for extra in ([], ["-t", "e"], ["-t", "r"], ["-t", "d"], ["-t", "ud"]):
        status, out, err = run_cli([capture, "--watch", "CHCF", "--json", *extra])
        assert (status, err) == (0, "")
        assert [json.loads(line) for line in out.splitlines()] == [expected], extra
    fields = run_cli([capture, "-T", "fields", "-e", "time_relative", "-Y", "frame == 6"])[1]
    assert fields == "1.059949000\n"


def test_standard_input_marks_changes_before_any_device_and_writes_each_once() -> None:
    # CHCF (8401) read alone, 3 then 4: no device is ever chosen (one read), so both frames are
    # provisional: the change is written as it comes, marked, and once only when the input ends and the
    # history counts the frames it held.
    from helpers import rtu

    request = rtu("0C 03 20 D1 00 01")
    data = request + rtu("0C 03 02 00 03") + request + rtu("0C 03 02 00 04")
    for watched in ("8401", "CHCF"):
        assert run_cli(["-", "--watch", watched], stdin=data) == (
            0, "     4            -  12 8401 3 -> 4 [provisional]\n", "")
        status, out, _ = run_cli(["-", "--watch", watched, "--json"], stdin=data)
        assert json.loads(out) == {"time": None, "time_relative": None, "frame": 4, "slave": 12, "address": 8401,
                                   "code": None, "old": "3", "new": "4", "unit": None, "provisional": True}
    (row,) = json.loads(run_cli(["-", "--stats", "--json"], stdin=data)[1])["parameters"]
    assert (row["address"], row["reads"], row["last"], row["changes"]) == (8401, 2, 4, 1)
