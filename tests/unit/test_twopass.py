"""Issue 27: profile `auto` chooses over the whole file before the decode, so a slave's values are named
with its profile from its first frame, in every output; standard input is read once (its rule)."""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

from helpers import rtu, run_cli

ROOT = Path(__file__).resolve().parents[2]
P38 = ROOT / "captures" / "p38_protection.bin"
REASON = ("traffic fits its map: function 3 at 8400..8402 in frames #2 and #4; 16#8000 at 8400, its answer "
          "for a non-existent parameter")


def test_p38_frame_2_is_named_in_json() -> None:
    status, out, _ = run_cli([str(P38), "--json"])
    frame = json.loads(out.splitlines()[1])
    assert status == 0 and frame["frame"] == 2
    assert (frame["profile"], frame["profile_reason"]) == ("atv71", REASON)
    assert [(r["address"], r["value"], r.get("code"), r.get("status"), r["text"]) for r in frame["registers"]] == [
        (8400, 32768, None, "non-existent", "16#8000: non-existent (address not in the map)"),
        (8401, 3, "CHCF", "ok", "IO (I/O profile)"),
        (8402, 2, "COP", "ok", "Cd (command)"),
    ]


def test_p38_chcf_rows_with_auto() -> None:
    status, out, _ = run_cli(["-T", "registers", "-E", "separator=,", "-Y", 'code == "CHCF"', str(P38)])
    rows = [line.split(",") for line in out.splitlines()]
    chcf = [(row[0], row[4], row[9], row[12], row[13]) for row in rows if row[7] == "CHCF"]
    assert status == 0 and chcf == [
        ("2", "read", "3", "ok", "IO (I/O profile)"),
        ("4", "read", "3", "ok", "IO (I/O profile)"),
        ("6", "read", "32768", "protected", "16#8000: protected"),
        ("8", "read", "32768", "protected", "16#8000: protected"),
        ("10", "exception", "", "protected", "no value: exception 02"),
        ("12", "exception", "", "protected", "no value: exception 02"),
    ]


def test_standard_input_is_read_once() -> None:
    # A pipe cannot be read twice: frame 2 is decoded before frame 4 decides, as on a live line.
    out = run_cli(["-"], stdin=P38.read_bytes())[1].splitlines()
    # Named before the choice, and said so (issue 27): the lines of frames 1-3 are provisional.
    assert out[1] == ("     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#1] "
                      "[provisional]  CRC ok")
    assert [line.endswith("[provisional]  CRC ok") for line in out] == [True] * 3 + [False] * 9
    assert out[3].startswith("     4            -  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO")


def test_a_meter_polling_3203_stays_generic_and_a_drive_is_named_from_its_first_answer(tmp_path: Path) -> None:
    # iEM3255 (slave 1) reading its INT64 energy at 3203..3206 five times: one read, no evidence (issue 26).
    meter = (rtu("01 03 0C 83 00 04") + rtu("01 03 08 00 00 00 00 00 01 E2 40")) * 5
    drive = rtu("02 03 0C 82 00 02") + rtu("02 03 04 01 F4 00 07") + rtu("02 03 20 D1 00 02") + rtu("02 03 04 00 03 00 02")
    path = tmp_path / "meter.bin"
    path.write_bytes(meter + drive)
    items = [json.loads(line) for line in run_cli([str(path), "--json"])[1].splitlines()]
    assert [item.get("profile") for item in items] == ["generic"] * 10 + ["atv71"] * 4
    assert all("code" not in register for item in items[:10] for register in item.get("registers", []))
    assert [r.get("code") for r in items[11]["registers"]] == ["RFR", "FRH"] and items[11]["frame"] == 12


def test_a_choice_taken_back_holds_for_the_whole_file(tmp_path: Path) -> None:
    # Two reads the ATV71 map explains, then an answer to FC1, which the VW3 A3 303 does not support.
    data = (rtu("09 03 20 D1 00 02") + rtu("09 03 04 00 03 00 02") + rtu("09 03 0C 82 00 02")
            + rtu("09 03 04 01 F4 00 07") + rtu("09 01 00 00 00 08") + rtu("09 01 01 05"))
    path = tmp_path / "back.bin"
    path.write_bytes(data)
    items = [json.loads(line) for line in run_cli([str(path), "--json"])[1].splitlines()]
    assert all("code" not in r for item in items for r in item.get("registers", []))
    assert items[5]["profile"] == "generic"


def test_compiled_path_equals_python_stages() -> None:
    outputs = []
    for pure in ("", "1"):
        env = dict(os.environ, VW3_PURE_PYTHON=pure)
        if not pure:
            env.pop("VW3_PURE_PYTHON")
        result = subprocess.run([sys.executable, "-m", "dissector", str(P38)], capture_output=True, env=env,
                                cwd=ROOT, timeout=120)
        outputs.append(result.stdout)
    assert outputs[0] == outputs[1] and b"8400=32768" not in outputs[0]


def test_standard_input_on_a_terminal_marks_provisional_lines() -> None:
    # The terminal's styled line (summary_text: the live view's too) says it as the plain one does.
    out = run_cli(["-", "--color", "always"], stdin=P38.read_bytes(), tty=True)[1]
    lines = re.sub(r" \n", " ", re.sub(r"\x1b\[[0-9;]*m", "", out)).splitlines()  # rich wraps at 80 columns
    assert lines[1] == ("     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 "
                        "8402=2 [#1] [provisional]  CRC ok")
    assert "[provisional]" not in lines[3]


def test_fields_and_registers_read_once_say_rows_are_provisional() -> None:
    data = P38.read_bytes()
    warning = ("vw3-decode: warning: rows from frame 1 on of slaves whose device profile auto has not chosen yet are "
               "provisional (read once, named with spec semantics only); {}\n")
    status, out, err = run_cli(["-", "-T", "fields", "-e", "frame", "-e", "value"], stdin=data)
    assert (status, err) == (0, warning.format("-e provisional marks them"))
    assert out.splitlines()[:4] == ["1\t", "2\t32768,3,2", "3\t", "4\t32768,3,2"]
    status, out, err = run_cli(["-", "-T", "fields", "-e", "frame", "-e", "provisional"], stdin=data)
    assert (status, err) == (0, "") and out.splitlines()[:5] == ["1\t1", "2\t1", "3\t1", "4\t", "5\t"]
    status, out, err = run_cli(["-", "-T", "registers"], stdin=data)
    assert (status, err) == (0, warning.format("--json or -T fields -e provisional mark them"))
    assert out.splitlines()[0] == "2\t\t12\t3\tread\t8400\t\t\t\t32768\t\t\t\t\t\t"
    # Read twice (a file by its name), nothing is provisional and nothing is said.
    assert run_cli([str(P38), "-T", "fields", "-e", "frame", "-e", "provisional"])[1:] == (
        "".join(f"{n}\t\n" for n in range(1, 13)), "")
