"""Profile `auto` (the default): each slave gets a device profile from evidence in the capture, and
no device claims are made about a slave before (or without) evidence."""
from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
from pathlib import Path

from helpers import rtu, run_cli

from dissector.render.detail import PROVISIONAL_LINE
from dissector.app.cli import Environment, run
from dissector.devices.build import build_annotator
from dissector.devices.selection import FIT_ANSWERS, ProfileChoice
from dissector.pipeline import dissect_bytes

ROOT = Path(__file__).resolve().parents[2]
P38 = ROOT / "captures" / "p38_protection.bin"
SEL = ROOT / "captures" / "sel749m_polling.pcap"

# A libmodbus slave (17) polled by a master: coils, inputs, a coil write, coils written, Report Server ID
# (the spec's worked examples; FC17 as a libmodbus 3.1.6 slave answers it).
LIBMODBUS = b"".join(
    rtu(text)
    for text in [
        "11 01 00 13 00 25", "11 01 05 CD 6B B2 0E 1B",
        "11 02 00 C4 00 16", "11 02 03 AC DB 35",
        "11 05 00 AC FF 00", "11 05 00 AC FF 00",
        "11 0F 00 13 00 0A 02 CD 01", "11 0F 00 13 00 0A",
        "11 11", "11 11 0A B4 FF 4C 4D 42 33 2E 31 2E 36",
        "11 03 00 00 00 02", "11 03 04 00 01 00 02",
    ]
)


def cli(*args: str, stdin: bytes = b"") -> tuple[int, str, str]:
    """vw3-decode with stderr on a terminal, where the profile lines are written."""
    out, err = io.StringIO(), io.StringIO()
    env = Environment(io.BytesIO(stdin), out, err, stdout_isatty=False, stderr_isatty=True)
    return run(list(args), env), out.getvalue(), err.getvalue()


P38_REASON = ("traffic fits its map: function 3 at 8400..8402 in frames #2 and #4; 16#8000 at 8400, its answer "
              "for a non-existent parameter")


def test_p38_is_told_as_with_the_atv71_profile_by_traffic_fit() -> None:
    # The capture has no identification: frame 2 answers FC3 at 8401/8402 (CHCF, COP, in the ATV71 map)
    # and 16#8000 at 8400, the value the card returns for a non-existent parameter: only atv71 fits. One
    # answer is no evidence (issue 26); frame 4 answers the read again, with 16#8000 again: chosen there,
    # over the whole file before the decode (issue 27), so frame 2 is named too.
    status, auto, err = cli(str(P38))
    forced = cli(str(P38), "--profile", "atv71")[1]
    assert status == 0 and auto == forced
    assert auto.splitlines()[1] == (
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O "
        "profile) COP=Cd (command) [#1]  CRC ok")
    assert err == f"vw3-decode: profile slave 12: atv71 ({P38_REASON})\n"
    assert "CHCF (8401) became protected: read 3 in frame #4, 16#8000 now" in auto.splitlines()[5]
    # The pcap gives the same lines with times, through the Python stages instead of the compiled path.
    pcap = cli(str(P38.with_suffix(".pcap")))[1].splitlines()
    untimed = [re.sub(r", [0-9.]+ ms\]", "]", line[25:]) for line in pcap]
    assert untimed == [line[25:] for line in auto.splitlines()]


def test_no_vw3_text_about_the_sel_relay_under_the_default_profile() -> None:
    status, out, err = cli(str(SEL))
    assert status == 0 and out.count("\n") == 68
    assert "VW3" not in out and "ATV" not in out
    assert err == "vw3-decode: profile slave 1: generic (no evidence of a device: spec semantics only)\n"
    assert "    14     0.713249   1 exception Read Holding Registers: exception 2 (Illegal Data Address) [#13, 12.0 ms]  CRC ok" in out.splitlines()
    json_out = cli(str(SEL), "--json")[1]
    assert "VW3" not in json_out
    # Forced, the relay is an Altivar: the test above can fail.
    assert "exception 02 from the VW3 A3 303" in cli(str(SEL), "--profile", "atv71")[1]


def test_no_vw3_text_about_a_libmodbus_slave() -> None:
    status, out, err = cli("-", stdin=LIBMODBUS)
    assert status == 0
    assert "VW3" not in out and "warning" not in out
    assert out.splitlines()[1] == (
        "     2            -  17 response  Read Coils 19..55 (37): 10110011110101100100110101110000… (+5) [#1] "
        "[provisional]  CRC ok"
    )  # read once (stdin), and slave 17's device could still have been identified: provisional
    assert err == "vw3-decode: profile slave 17: generic (no evidence of a device: spec semantics only)\n"
    forced = run_cli(["-", "--profile", "atv71"], stdin=LIBMODBUS)[1]
    assert "Read Coils (1) is not supported by the VW3 A3 303" in forced


def test_identification_chooses_the_profile_and_nothing_is_claimed_before() -> None:
    # Seed 001 (p.32): the FC43 answer names ProductCode ATV71HU15M3.
    capture = ROOT / "captures" / "atv71_commissioning.pcap"
    status, out, err = cli(str(capture))
    assert status == 0
    assert err == "vw3-decode: profile slave 2: atv71 (Read Device Identification in frame #2: ProductCode 'ATV71HU15M3')\n"
    assert out == cli(str(capture), "--profile", "atv71")[1]


def test_sel_function_codes_choose_the_relay() -> None:
    # 60h Read Parameter Information, asked of slave 3: only the SEL-749M speaks it.
    data = rtu("03 60 00 00") + rtu("03 03 00 00 00 01") + rtu("03 83 02")
    annotate = build_annotator([], [])
    items = dissect_bytes(data, annotate=annotate)
    assert items[0].function_text == "Read Parameter Information"
    assert items[2].notes == [
        "exception 02 from the SEL-749M to Read Holding Registers: illegal register to read "
        "(increments the Invalid Address counter)"
    ]
    assert annotate.choices() == [
        ProfileChoice(3, "sel749m", "function 60h (Read Parameter Information) in frame #1", 1, True)
    ]


def test_a_traffic_choice_is_taken_back_by_an_answer_the_device_cannot_give() -> None:
    data = (rtu("0C 03 0C 1E 00 02") + rtu("0C 03 04 00 28 02 58")  # SFR, TFR: fits the ATV71
            + rtu("0C 03 20 D1 00 02") + rtu("0C 03 04 00 03 00 02")  # CHCF, COP: a second read, chosen
            + rtu("0C 01 00 00 00 08") + rtu("0C 01 01 FF"))  # but it answers Read Coils
    annotate = build_annotator([], [])
    items = dissect_bytes(data, annotate=annotate)
    assert [register.code for register in items[1].registers] == [None, None]  # one read: no evidence
    assert [register.code for register in items[3].registers] == ["CHCF", "COP"]
    assert items[4].warnings == ["Read Coils (1) is not supported by the VW3 A3 303"]  # still the ATV71
    assert annotate.profile_report() == [
        "profile slave 12: generic (function 1 answered in frame #6, which the VW3 A3 303 does not support)"
    ]


def test_the_profile_lines_are_for_a_terminal_only() -> None:
    # Redirected stderr (a script, a log) stays free of them; --stats carries the choices.
    status, out, err = run_cli([str(P38)])
    assert status == 0 and err == "" and out == cli(str(P38))[1]


def test_choices_name_forced_profiles() -> None:
    annotate = build_annotator(["atv71", "3=sel749m"], [])
    dissect_bytes(rtu("0C 03 0C 1E 00 01") + rtu("03 03 00 00 00 01"), annotate=annotate)
    assert annotate.choices() == [
        ProfileChoice(3, "sel749m", "--profile", None, True),
        ProfileChoice(12, "atv71", "--profile", None, True),
    ]
    assert annotate.profile_report() == []


def _late_identification() -> bytes:
    """Slave 2 polled at addresses no map knows (settles as generic), then identified as an ATV71,
    then polled at CHCF/COP: the compiled path must forget what it knew of slave 2."""
    poll = rtu("02 03 00 00 00 02") + rtu("02 03 04 00 07 00 09")
    ident = rtu("02 2B 0E 01 00") + rtu(
        "02 2B 0E 01 02 00 00 02 00 0D" + b"Telemecanique".hex() + "01 0B" + b"ATV71HU15M3".hex())
    chcf = rtu("02 03 20 D1 00 02") + rtu("02 03 04 00 03 00 02")
    return poll * (FIT_ANSWERS + 2) + ident + chcf * 3


def test_compiled_path_follows_a_late_choice() -> None:
    data = _late_identification()
    compiled = cli("-", stdin=data)
    env = dict(os.environ, VW3_PURE_PYTHON="1")
    pure = subprocess.run([sys.executable, "-m", "dissector", "-"], input=data, capture_output=True, cwd=ROOT,
                          env=env, check=True)
    assert compiled[1] == pure.stdout.decode()
    lines = compiled[1].splitlines()
    assert lines[1].endswith("Read Holding Registers 0..1 (2): 0=7 1=9 [#1] [provisional]  CRC ok")  # read once
    assert lines[19].endswith("Read Holding Registers 0..1 (2): 0=7 1=9 [#19]  CRC ok")  # 8 answers: settled
    assert lines[-1].endswith("Read Holding Registers 8401..8402 (2): CHCF=IO (I/O profile) COP=Cd (command) [#27]  CRC ok")
    assert compiled[2] == (
        "vw3-decode: profile slave 2: atv71 (Read Device Identification in frame #22: ProductCode 'ATV71HU15M3')\n"
    )


def test_json_and_choices_agree() -> None:
    out = cli(str(P38), "--json")[1]
    first, second = json.loads(out.splitlines()[1]), json.loads(out.splitlines()[3])
    # Chosen over the whole file (issue 27): frame 2 is named, with the reason that names frame 4.
    for frame in (first, second):
        assert [register.get("code") for register in frame["registers"]] == [None, "CHCF", "COP"]
        assert (frame["profile"], frame["profile_reason"]) == ("atv71", P38_REASON)
    # Read once (standard input), frame 2 comes before the evidence: no device named, generic's semantics.
    once = cli("-", "--json", stdin=P38.read_bytes())[1]
    first = json.loads(once.splitlines()[1])
    assert [register.get("code") for register in first["registers"]] == [None, None, None]
    assert first["profile"] == "generic" and "profile_reason" not in first


# Issue 26: a Schneider iEM3255 energy meter reads its INT64 energy at 3203..3206 (here 123456 Wh), which
# the ATV71 map happens to name FRH, LCR, OTR and ETI.
METER_READ = rtu("01 03 0C 83 00 04") + rtu("01 03 08 00 00 00 00 00 01 E2 40")
DRIVE_READS = (rtu("02 03 0C 82 00 02") + rtu("02 03 04 01 F4 00 07")  # RFR, FRH
               + rtu("02 03 20 D1 00 02") + rtu("02 03 04 00 03 00 02"))  # CHCF, COP
DRIVE_REASON = "traffic fits its map: function 3 at 3202..3203 in frame #2, function 3 at 8401..8402 in frame #4"


def test_an_energy_meter_polled_at_altivar_addresses_is_no_altivar() -> None:
    for polls in (1, 2, 5):  # one read, answered once or again and again: no evidence of a device
        status, out, err = cli("-", stdin=METER_READ * polls)
        assert status == 0 and "FRH" not in out and "Hz" not in out
        assert out.splitlines()[1] == (
            "     2            -   1 response  Read Holding Registers 3203..3206 (4): 3203=0 3204=0 3205=1 3206=57920 "
            "[#1] [provisional]  CRC ok")  # read once, and fewer than 8 answers: a device may still show
        assert err == "vw3-decode: profile slave 1: generic (no evidence of a device: spec semantics only)\n"


def test_a_map_must_explain_two_different_reads_and_every_answer() -> None:
    annotate = build_annotator([], [])
    dissect_bytes(DRIVE_READS, annotate=annotate)
    assert annotate.choices() == [ProfileChoice(2, "atv71", DRIVE_REASON, 4, False)]
    # an answer at an address the map does not know rules the ATV71 out for that slave
    unknown = rtu("02 03 00 00 00 01") + rtu("02 03 02 00 07")
    annotate = build_annotator([], [])
    dissect_bytes(unknown + DRIVE_READS, annotate=annotate)
    assert annotate.profile_report() == ["profile slave 2: generic (no evidence of a device: spec semantics only)"]


def test_minus_v_and_json_say_which_profile_named_the_registers_and_why() -> None:
    detail = cli("-V", "-", stdin=DRIVE_READS)[1]
    assert [line for line in detail.splitlines() if "Profile:" in line] == [PROVISIONAL_LINE] * 3 + [
        f"    Profile: atv71 ({DRIVE_REASON})"]  # read once: frames 1-3 before the choice
    assert detail.split("\n\n")[3].splitlines()[-2:] == ["    Request in frame: 3", f"    Profile: atv71 ({DRIVE_REASON})"]
    records = [json.loads(line) for line in cli("--json", "-", stdin=DRIVE_READS)[1].splitlines()]
    assert [(record.get("profile"), record.get("profile_reason")) for record in records] == (
        [("generic", None)] * 3 + [("atv71", DRIVE_REASON)])
    assert [register.get("code") for register in records[1]["registers"]] == [None, None]
    assert [register.get("code") for register in records[3]["registers"]] == ["CHCF", "COP"]
    forced = cli("--json", "--profile", "atv71", "-", stdin=DRIVE_READS)[1]
    assert "profile_reason" not in forced  # forced: the user said which, there is nothing to explain


def test_the_profile_and_its_reason_are_fields_and_filter_keys() -> None:
    out = cli("-T", "fields", "-e", "frame", "-e", "profile", "-e", "profile_reason", "-", stdin=DRIVE_READS)[1]
    # (the profile that annotated each frame, as the plugin's vw3.profile; the reason where auto chose)
    assert out.splitlines() == ["1\tgeneric\t", "2\tgeneric\t", "3\tgeneric\t", f"4\tatv71\t{DRIVE_REASON}"]
    shown = cli("-Y", 'profile == "atv71"', "-", stdin=DRIVE_READS)[1]
    assert [line.split()[0] for line in shown.splitlines()] == ["4"]
    assert [line.split()[0] for line in cli("-Y", "!profile_reason", "-", stdin=DRIVE_READS)[1].splitlines()] == ["1", "2", "3"]
    assert [line.split()[0] for line in cli("-Y", 'profile == "generic"', "-", stdin=DRIVE_READS)[1].splitlines()] == ["1", "2", "3"]
    forced = cli("-T", "fields", "-e", "profile", "--profile", "atv71", "-", stdin=DRIVE_READS)[1]
    assert forced.splitlines() == ["atv71"] * 4  # forced: named, as vw3.profile names it
