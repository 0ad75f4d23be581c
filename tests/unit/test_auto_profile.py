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


def test_p38_is_told_as_with_the_atv71_profile_by_traffic_fit() -> None:
    # The capture has no identification: frame 2 answers FC3 at 8401/8402 (CHCF, COP, in the ATV71 map)
    # and 16#8000 at 8400, the value the card returns for a non-existent parameter: only atv71 fits.
    status, auto, err = cli(str(P38))
    forced = cli(str(P38), "--profile", "atv71")[1]
    assert status == 0 and auto == forced
    assert err == "vw3-decode: profile slave 12: atv71 (traffic fits its map: function 3 at 8400..8402 in frame #2)\n"
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
        "     2            -  17 response  Read Coils 19..55 (37): 10110011110101100100110101110000… (+5) [#1]  CRC ok"
    )
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
            + rtu("0C 01 00 00 00 08") + rtu("0C 01 01 FF"))  # but it answers Read Coils
    annotate = build_annotator([], [])
    items = dissect_bytes(data, annotate=annotate)
    assert [register.code for register in items[1].registers] == ["SFR", "TFR"]
    assert items[2].warnings == ["Read Coils (1) is not supported by the VW3 A3 303"]  # still the ATV71
    assert annotate.profile_report() == [
        "profile slave 12: generic (function 1 answered in frame #4, which the VW3 A3 303 does not support)"
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
    assert lines[1].endswith("Read Holding Registers 0..1 (2): 0=7 1=9 [#1]  CRC ok")
    assert lines[-1].endswith("Read Holding Registers 8401..8402 (2): CHCF=IO (I/O profile) COP=Cd (command) [#27]  CRC ok")
    assert compiled[2] == (
        "vw3-decode: profile slave 2: atv71 (Read Device Identification in frame #22: ProductCode 'ATV71HU15M3')\n"
    )


def test_json_and_choices_agree() -> None:
    out = cli(str(P38), "--json")[1]
    first = json.loads(out.splitlines()[1])
    assert [register.get("code") for register in first["registers"]] == [None, "CHCF", "COP"]
