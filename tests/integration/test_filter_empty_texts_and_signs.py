"""-Y as tshark 4.0.17 reads it with the plugin, on two points where vw3-decode read otherwise before:

1. A register's text keys (code, name, unit, text, status, source, label) are "" on a register without them,
   as the plugin's hidden empty items are values to tshark's -Y, and as -T fields already wrote them: on
   p38_protection, 8400 has no code or name, so `code == name` selects frames 2, 4, 6, 8, 10 and 12 (before:
   none), `code == ""` the same (before: refused, "no parameter code"), `status == ""` none (every
   register there has a status).
2. A set member may carry a sign (`value in {-slave}`, before refused: "value is a number, not '-'"): a
   negated unsigned field is a signed number, which an unsigned field never equals nor lies above or below
   (tshark: no relation holds, none fails), so `value in {-slave}` selects nothing, `value in {-value}` the
   frames with a 0, and `all value in {-slave..5}` those whose values are all 5 at most. The same rule in
   relations and arithmetic: `value > -slave` and `value ~= -slave` select nothing, `value === -slave`
   every frame with a value (before: the reverse), `value + -slave > 0` the frames with a 0 (32-bit
   unsigned arithmetic: 0xfffffffe; no value from 2 up, where it overflows).
3. `contains ""` holds for no text and not for raw as a whole (tshark's frame), for a slice it does (before:
   everywhere). A decimal divided by 0 is an infinity, 0 / 0 NaN (equal to every number), and a decimal
   takes no % (before: no value, and a remainder).
Against tshark with the plugin; and -T fields writes no empty text for a bit (tshark has no vw3.bit.code:
before, `-e code` of a Write Multiple Coils request of 3 coils wrote `,,`), nor quotes where a field has no
occurrence (`-E quote=d`: before `""`, tshark nothing; an empty occurrence is `""` in both)."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, assert_refused_as_tshark, assert_same_frames, run_tshark, write_pcap

P38, ATV = "p38_protection.pcap", "atv71_commissioning.pcap"
CASES = [
    (P38, "code == name", "vw3.reg.code == vw3.reg.name"),
    (P38, 'code == ""', 'vw3.reg.code == ""'),
    (P38, 'status == ""', 'vw3.reg.status == ""'),
    (P38, 'name in {"", "Profile"}', 'vw3.reg.name in {"", "Profile"}'),
    (P38, 'code === ""', 'vw3.reg.code === ""'),
    (P38, "len(code) == 0", "len(vw3.reg.code) == 0"),
    (P38, 'code matches "^$" and slave == 12', 'vw3.reg.code matches "^$" and vw3.slave == 12'),
    (P38, "not code", "not vw3.reg.code"),
    (ATV, "value in {-slave}", "vw3.reg.value in {-vw3.slave}"),
    (ATV, "value in {-value}", "vw3.reg.value in {-vw3.reg.value}"),
    (ATV, "value in {+slave, -slave}", "vw3.reg.value in {+vw3.slave, -vw3.slave}"),
    (ATV, "value in {-slave..5}", "vw3.reg.value in {-vw3.slave..5}"),
    (ATV, "all value in {-slave..5}", "all vw3.reg.value in {-vw3.slave..5}"),
    (ATV, "all value in {-slave, 3}", "all vw3.reg.value in {-vw3.slave, 3}"),
    (ATV, "value in {-len(code)}", "vw3.reg.value in {-len(vw3.reg.code)}"),
    (ATV, "value > -slave", "vw3.reg.value > -vw3.slave"),
    (ATV, "value ~= -slave", "vw3.reg.value ~= -vw3.slave"),
    (ATV, "value === -slave", "vw3.reg.value === -vw3.slave"),
    (ATV, "-value < -slave", "-vw3.reg.value < -vw3.slave"),
    (ATV, "value + -slave > 0", "vw3.reg.value + -vw3.slave > 0"),
    (ATV, "slave * -2 == -4", "vw3.slave * -2 == -4"),
    # a text contains no empty text, nor the frame as a whole no empty bytes; a slice (bytes) does
    (P38, 'code contains "" or function_name contains ""', 'vw3.reg.code contains "" or vw3.function_name contains ""'),
    (P38, 'raw contains ""', 'frame contains ""'),
    (P38, 'upper(function_name) contains ""', 'upper(vw3.function_name) contains ""'),
    # a decimal divided by 0 is an infinity (0 / 0 NaN, equal to every number), as tshark's (before: no value)
    (ATV, "scaled / 0 > 1", "vw3.reg.scaled / 0 > 1"),
    (ATV, "scaled / 0 != 1", "vw3.reg.scaled / 0 != 1"),
    (ATV, "scaled * 0 / 0 == 7", "vw3.reg.scaled * 0 / 0 == 7"),
    (P38, 'raw[0:2] contains "" and function_name[0:1] contains ""',
     'frame[0:2] contains "" and vw3.function_name[0:1] contains ""'),
]


@pytest.mark.parametrize(("capture", "ours", "wiresharks"), CASES)
def test_selects_what_tshark_selects(capture: str, ours: str, wiresharks: str) -> None:
    assert_same_frames(ROOT / "captures" / capture, ours, wiresharks)


@pytest.mark.parametrize(("ours", "wiresharks", "said"), [
    ("value in {-(slave)}", "vw3.reg.value in {-(vw3.slave)}", "vw3-decode: '(' was unexpected in this context"),
    ("value in {--slave}", "vw3.reg.value in {--vw3.slave}", "vw3-decode: '-' was unexpected in this context"),
    ("code in {-code}", "vw3.reg.code in {-vw3.reg.code}", "vw3-decode: code is a text (FT_STRING): it cannot take"),
    ("scaled % 2 > 0", "vw3.reg.scaled % 2 > 0", "vw3-decode: scaled is a decimal number (FT_DOUBLE): it cannot %"),
])
def test_refuses_what_tshark_refuses(ours: str, wiresharks: str, said: str) -> None:
    assert_refused_as_tshark(ROOT / "captures" / ATV, ours, wiresharks, said)


def test_the_selections_before_and_after() -> None:
    """The figures of the docstring, as vw3-decode prints them (frames of p38_protection)."""
    def frames(expression: str) -> str:
        command = [sys.executable, "-m", "dissector", "-Y", expression, "-T", "fields", "-e", "frame",
                   str(ROOT / "captures" / P38)]
        run = subprocess.run(command, capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, run.stderr
        return " ".join(run.stdout.split())

    assert frames("code == name") == frames('code == ""') == frames("code") == "2 4 6 8 10 12"
    assert frames('status == ""') == frames("value in {-slave}") == ""


def test_no_empty_text_for_a_bit(tmp_path: Path) -> None:
    """FC15 writing 3 coils and its answer, FC1's answer of 10 bits: no `code` occurrence, as tshark."""
    path = write_pcap(tmp_path / "coils.pcap", [
        (rtu("11 0F 0013 0003 01 05"), 1767225600.0), (rtu("11 0F 0013 0003"), 1767225600.01),
        (rtu("11 01 0013 000A"), 1767225600.5), (rtu("11 01 02 CD 01"), 1767225600.51)])
    keys = ["address", "value", "code", "status", "label"]
    mine = subprocess.run([sys.executable, "-m", "dissector", str(path), "-T", "fields", "-e", "frame",
                           *[x for key in keys for x in ("-e", key)]], capture_output=True, text=True, timeout=300)
    assert mine.returncode == 0, mine.stderr
    names = ["vw3.reg.address", "vw3.bit.address", "vw3.reg.value", "vw3.bit.value", "vw3.reg.code",
             "vw3.reg.status", "vw3.reg.label"]
    theirs = run_tshark(path, "-T", "fields", "-e", "vw3.item", *[x for name in names for x in ("-e", name)])
    assert theirs.returncode == 0, theirs.stderr
    # vw3-decode's address and value are the registers' then the bits' (tshark: vw3.reg.X, then vw3.bit.X)
    joined = []
    for line in theirs.stdout.splitlines():
        cells = line.split("\t")
        address, value = (",".join(filter(None, cells[k:k + 2])) for k in (1, 3))
        joined.append("\t".join([cells[0], address, value, *cells[5:]]))
    assert mine.stdout.splitlines() == joined
    assert [line.split("\t")[3] for line in mine.stdout.splitlines()] == ["", "", "", ""]


def test_quotes_only_occurrences() -> None:
    """-E quote=d on p38_protection, every register key and some frame keys, line for line as tshark."""
    path = ROOT / "captures" / P38
    keys = ["address", "value", "code", "name", "scaled", "text", "status", "label", "words"]
    frame = [("response_time", "vw3.response_time"), ("exception_code", "vw3.exception_code"), ("notes", "vw3.note")]
    options = ["-E", "quote=d", "-E", "separator=,", "-E", "aggregator=/s"]
    mine = subprocess.run([sys.executable, "-m", "dissector", str(path), "-T", "fields", *options, "-e", "frame",
                           *[x for key in keys for x in ("-e", key)], *[x for key, _ in frame for x in ("-e", key)]],
                          capture_output=True, text=True, timeout=300)
    assert mine.returncode == 0, mine.stderr
    theirs = run_tshark(path, "-T", "fields", *options, "-e", "vw3.item", *[x for key in keys for x in ("-e", f"vw3.reg.{key}")],
                        *[x for _, name in frame for x in ("-e", name)])
    assert theirs.returncode == 0, theirs.stderr
    assert mine.stdout.splitlines() == theirs.stdout.splitlines()
    assert mine.stdout.splitlines()[0] == '"1","8400 8401 8402"' + ',' * 11
