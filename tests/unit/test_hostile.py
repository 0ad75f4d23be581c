"""Bus and file data is hostile (issue 32): every reproducer of the review, with what a user must see.

Strings from the bus and from files are data (never rich markup, never a terminal escape, never a
spreadsheet formula); no option turns odd numbers into a traceback; no output overwrites an input or
another output; a failed -w keeps whole records only and says how many.
"""
from __future__ import annotations

import json
import os
import re
import resource
import struct
import subprocess
import sys
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run
from dissector.devices.maps import ProfileError, load_map_file
from dissector.devices.profiles import load_profile
from dissector.sources.reader import open_source
from helpers import rtu, run_cli

ROOT = Path(__file__).resolve().parents[2]
PROG = "vw3-decode: "
ESC = "\x1b"


def _fc43(value: bytes, slave: int = 1) -> bytes:
    """A Read Device Identification answer (basic) whose VendorName is `value`."""
    return rtu(f"{slave:02x}2b0e0101000001" + f"00{len(value):02x}" + value.hex())


# An FC43 vendor name that would be an OSC 8 hyperlink, a hidden text and a cleared screen.
OSC_VENDOR = b"\x1b]8;;http://x\x1b\\LINK\x1b]8;;\x1b\\ [conceal]hid[/x] :smile: \x1b[2J"


def _no_escape_but_styles(text: str) -> None:
    """Only rich's own SGR styles (ESC [ ... m) may be in coloured output: no OSC, no other CSI."""
    assert re.sub(r"\x1b\[[0-9;]*m", "", text).count(ESC) == 0, text


# -- injection ---------------------------------------------------------------------------------------
def test_registers_spelling_markup_are_text_in_a_coloured_hex_dump() -> None:
    status, out, err = run_cli(["-x", "--color", "always", "--hex", "01 03 04 5B 2F 78 5D"])
    assert (status, err) == (0, "")
    plain = re.sub(r"\x1b\[[0-9;]*m", "", out)
    # (the bytes typed: the CRC computed for them is no byte received, issue 27)
    assert "0000  01 03 04 5b 2f 78 5d                              ...[/x]\n" in plain
    assert "0=23343 1=30813" in plain.replace("?+", "").replace("\n", " ") or "[/x]" in plain


@pytest.mark.parametrize("options", [["-V"], ["-x"], [], ["-V", "-x"]])
def test_an_fc43_vendor_name_is_data_in_coloured_output(tmp_path: Path, options: list[str]) -> None:
    capture = tmp_path / "fc43.bin"
    capture.write_bytes(_fc43(OSC_VENDOR))
    status, out, err = run_cli([*options, "--color", "always", str(capture)])
    assert (status, err) == (0, "")
    _no_escape_but_styles(out)
    plain = re.sub(r"\x1b\[[0-9;]*m", "", out)
    # Markup and emoji codes literal (rich wraps the line at 80 columns: pieces are checked).
    assert "[/x] :smile:" in plain
    if options != ["-x"]:  # the name as the summary writes it, ESC as \x1b
        assert re.search(r"VendorName(=|: )'\\x1b\]8;;http://x\\x1b\\\\LINK", plain), plain
        assert "[conceal]hid[/x] :smile: \\x1b[2J'" in plain


def test_a_file_name_with_markup_is_text_in_the_rule_between_inputs(tmp_path: Path,
                                                                   monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    Path("mk[").mkdir()
    Path("mk[/x].bin").write_bytes(rtu("0103045b2f785d"))
    Path(f"esc{ESC}[2J.bin").write_bytes(rtu("010300000001"))
    status, out, err = run_cli(["--color", "always", "mk[/x].bin", f"esc{ESC}[2J.bin"])
    assert (status, err) == (0, "")
    _no_escape_but_styles(out)
    plain = re.sub(r"\x1b\[[0-9;]*m", "", out)
    assert " mk[/x].bin " in plain and r" esc\x1b[2J.bin " in plain
    status, out, err = run_cli(["mk[/x].bin", f"esc{ESC}[2J.bin"])  # piped: the tail(1) titles, escaped too
    assert "==> esc\\x1b[2J.bin <==" in out.splitlines()


def _fc17(additional: bytes) -> bytes:
    """A Report Server ID exchange whose answer's additional data is `additional`."""
    body = b"\x2a\xff" + additional  # server id 42, run indicator ON
    return rtu("0111") + rtu("0111" + f"{len(body):02x}" + body.hex())


@pytest.mark.parametrize("separator", [",", ";"])
def test_csv_cells_that_a_spreadsheet_would_run_get_a_quote(tmp_path: Path, separator: str) -> None:
    capture = tmp_path / "fc17.bin"
    capture.write_bytes(_fc17(b'=HYPERLINK("http://x","y")'))
    argv = ["-T", "fields", "-e", "frame", "-e", "fields.additional_data", "-E", f"separator={separator}", str(capture)]
    status, out, err = run_cli(argv)
    assert (status, err) == (0, "")
    # The value holds a `,`: one quoted cell (RFC 4180), not `'=HYPERLINK("http://x"` and `"y")`.
    assert out.splitlines() == ["1" + separator, f'2{separator}"\'=HYPERLINK(""http://x"",""y"")"']
    status, out, err = run_cli([*argv, "-E", "quote=d"])
    assert out.splitlines()[1] == f'"2"{separator}"\'=HYPERLINK(""http://x"",""y"")"'
    status, out, err = run_cli([*argv, "-E", "formulas=y"])  # the documented way to keep them
    assert out.splitlines()[1] == f"2{separator}=HYPERLINK(\"http://x\",\"y\")"
    status, out, err = run_cli(argv[:-3] + ["-E", "separator=/t", str(capture)])  # a tab: as tshark
    assert out.splitlines()[1] == "2\t=HYPERLINK(\"http://x\",\"y\")"


@pytest.mark.parametrize("separator", [",", ";"])
def test_a_value_holding_the_separator_is_one_cell_no_spreadsheet_runs(tmp_path: Path, separator: str) -> None:
    # Review of issue 32 (defect 2): only the whole value's first character was checked, so the piece
    # after the `,` of `SEL,@SUM(1+1)*cmd|calc` was a cell of its own that a spreadsheet ran.
    capture = tmp_path / "fc17b.bin"
    capture.write_bytes(_fc17(b"SEL,@SUM(1+1)*cmd|calc"))
    argv = ["-T", "fields", "-e", "frame", "-e", "fields.additional_data", "-E", f"separator={separator}", str(capture)]
    status, out, err = run_cli(argv)
    assert (status, err) == (0, "")
    assert out.splitlines() == ["1" + separator, f'2{separator}"SEL,@SUM(1+1)*cmd|calc"']  # exact, one cell
    status, out, err = run_cli([*argv, "-E", "quote=d"])
    assert out.splitlines()[1] == f'"2"{separator}"SEL,@SUM(1+1)*cmd|calc"'
    # Single quotes are no quoting to a spreadsheet: each piece that would start a formula gets its '.
    status, out, err = run_cli([*argv, "-E", "quote=s"])
    assert out.splitlines()[1] == f"'2'{separator}'SEL,''@SUM(1+1)*cmd|calc'"
    status, out, err = run_cli([*argv, "-E", "formulas=y"])
    assert out.splitlines()[1] == f"2{separator}SEL,@SUM(1+1)*cmd|calc"
    status, out, err = run_cli(argv[:-3] + ["-E", "separator=/t", str(capture)])  # not a CSV: as tshark
    assert out.splitlines()[1] == "2\tSEL,@SUM(1+1)*cmd|calc"


def test_codes_joined_by_the_aggregator_are_one_cell(tmp_path: Path) -> None:
    # A map code `=1+1` joined with the others by the aggregator `,` was the bare cell `=1+1` of `2,,=1+1,COP`.
    map_file = tmp_path / "map.csv"
    map_file.write_text("address,code,name\n8401,=1+1,x\n", encoding="utf-8")
    argv = ["--map", str(map_file), "-T", "fields", "-e", "frame", "-e", "code", "-E", "separator=,",
            str(ROOT / "captures" / "p38_protection.pcap")]
    status, out, err = run_cli(argv)
    assert (status, err) == (0, "")
    assert out.splitlines()[:2] == ['1,', '2,",=1+1,COP"']  # (1: a request, no code, as tshark writes it)
    status, out, err = run_cli([*argv, "-E", "aggregator=;"])
    assert out.splitlines()[1] == '2,";=1+1;COP"'
    status, out, err = run_cli([*argv, "-E", "aggregator=/s"])  # no splitting character: kept as it is
    assert out.splitlines()[1] == "2, =1+1 COP"
    status, out, err = run_cli([*argv, "-E", "quote=s"])
    assert out.splitlines()[1] == "'2',',''=1+1,COP'"
    status, out, err = run_cli(["--map", str(map_file), "-T", "registers", "-E", "separator=,",
                                str(ROOT / "captures" / "p38_protection.pcap")])
    assert out.splitlines()[1] == "2,0.010157,12,3,read,8401,,'=1+1,x,3,,,ok,,,"


@pytest.mark.parametrize("text, shown", [
    ("@SUM(A1:A9)", "'@SUM(A1:A9)"), ("+1+1", "'+1+1"), ("-1+cmd|' /C calc'!A0", "'-1+cmd|' /C calc'!A0"),
    ("-12.5", "-12.5"), ("+3", "+3"), ("1e-3", "1e-3"), ("plain", "plain"),
])
def test_map_texts_in_csv_cells(tmp_path: Path, text: str, shown: str) -> None:
    map_file = tmp_path / "map.csv"
    map_file.write_text(f'address,code,name\n8401,CHCF,"{text}"\n', encoding="utf-8")
    capture = tmp_path / "read.bin"
    capture.write_bytes(rtu("0c0320d10001") + rtu("0c03020003"))
    status, out, err = run_cli(["-n", "--map", str(map_file), "-T", "fields", "-e", "frame", "-e", "name",
                                "-E", "separator=,", str(capture)])
    status, out, err = run_cli(["--map", str(map_file), "-T", "fields", "-e", "frame", "-e", "name",
                                "-E", "separator=,", str(capture)])
    assert (status, err) == (0, "")
    assert out.splitlines()[1] == f"2,{shown}"


def test_control_characters_of_a_map_are_escaped_everywhere(tmp_path: Path) -> None:
    map_file = tmp_path / "map.csv"
    map_file.write_text("address,code,name,unit,scale\n8401,C\x1b[2JF,N\x07ame,\u202eHz,0.1\n", encoding="utf-8")
    capture = tmp_path / "read.bin"
    capture.write_bytes(rtu("0c0320d10001") + rtu("0c03020003") + rtu("0c0320d10001") + rtu("0c03020005"))
    for options in ([], ["-V"], ["--json"], ["-T", "fields", "-e", "code", "-e", "name", "-e", "status"],
                    ["--stats"], ["--watch", "8401"]):
        status, out, err = run_cli(["--map", str(map_file), *options, str(capture)])
        assert (status, err) == (0, ""), options
        assert ESC not in out and "\x07" not in out and "\u202e" not in out, options
        assert "\\x1b[2J" in out or "\\\\x1b[2J" in out, (options, out)


def test_the_reports_json_block_escapes_comment_openers(tmp_path: Path) -> None:
    map_file = tmp_path / "map.csv"
    map_file.write_text("address,code,name,unit,scale\n8401,HSP,<!-- a </script> b,Hz,0.1\n", encoding="utf-8")
    capture = tmp_path / "read.bin"
    capture.write_bytes((rtu("0c0320d10001") + rtu("0c03020003")) * 3)
    report = tmp_path / "report.html"
    status, out, err = run_cli(["--map", str(map_file), "--report", str(report), str(capture)])
    assert (status, err) == (0, "")
    page = report.read_text(encoding="utf-8")
    block = page.split('<script type="application/json" id="report-data">', 1)[1].split("</script>", 1)[0]
    assert "<!--" not in block and "</" not in block
    assert "<!-- a </script> b" in json.dumps(json.loads(block), ensure_ascii=False)


def test_control_characters_typed_or_in_file_names_are_escaped_in_error_lines(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "e\x1b[2Jmpty.bin").write_bytes(b"")
    capture = str(ROOT / "captures" / "p38_protection.pcap")
    cases = [
        (["e\x1b[2Jmpty.bin"], 0, "warning: e\\x1b[2Jmpty.bin: the input is empty"),
        (["no\x1b[31mfile"], 2, "no\\x1b[31mfile: no such file"),
        (["-Y", "slave == \x1b[31m", capture], 2,
         "unexpected character '\\x1b' (column 10)\n  slave == \\x1b[31m\n           ^"),
        (["-Y", 'code == "\x1b]8;;x\x07" or', capture], 2,
         "code '\\x1b]8;;x\\x07' is no parameter code of this run's maps (column 9)\n"
         '  code == "\\x1b]8;;x\\x07" or\n          ^'),
        (["-Y", "slave == 1 \x1b\x9b and", capture], 2,
         "unexpected character '\\x1b' (column 12)\n  slave == 1 \\x1b\\x9b and\n             ^"),
        (["--x\x1b[31m", capture], 2, "unrecognized arguments: --x\\x1b[31m (see vw3-decode --help)"),
        (["-w", "o\x1b[31m/x.pcap", capture], 2, "-w o\\x1b[31m/x.pcap: No such file or directory"),
        (["-T", "fields", "-e", "fr\x1bame", capture], 2, "-e fr\\x1bame: not a field (did you mean frame?)"),
        (["--live", "no\x1b[31mport"], 2, "cannot open no\\x1b[31mport: No such file or directory"),
    ]
    for argv, status, message in cases:
        assert run_cli(argv) == (status, "", f"{PROG}{message}\n"), argv
    assert not (tmp_path / "o\x1b[31m").exists()


# -- crashes -----------------------------------------------------------------------------------------
def test_a_filter_on_address_over_a_quantity_0_read() -> None:
    # It used to be an IndexError; the request names address 0 (tshark's reference_num) and is shown.
    status, out, err = run_cli(["-Y", "address == 0", "--hex", "01 03 00 00 00 00"])
    assert (status, err) == (0, "")
    assert len(out.splitlines()) == 1 and "1 request   Read Holding Registers" in out
    assert "[warning: quantity 0 outside the spec's 1..125]" in out
    status, out, err = run_cli(["-Y", "address == 1", "--hex", "01 03 00 00 00 00"])
    assert (status, out, err) == (0, "", "")


# A quantity-0 FC3 read and its empty answer, an FC23 reading 0 registers, an FC16 writing 0: the requests
# say quantity 0, which the spec forbids; no output invents a range wrapped back to start - 1 (issue 32).
QUANTITY_0 = [rtu(text) for text in ("010320d00000", "010300", "0117000a0000001400010200ff", "011700",
                                     "01100010000000", "011000100000")]


def test_a_quantity_0_span_is_what_the_request_says_in_every_output(tmp_path: Path) -> None:
    capture = tmp_path / "q0.bin"
    capture.write_bytes(b"".join(QUANTITY_0))
    lines = [
        "     1            -   1 request   Read Holding Registers {a} (0) [warning: quantity 0 outside the spec's 1..125]  CRC ok",
        "     2            -   1 response  Read Holding Registers {a} (0) [#1]  CRC ok",
        "     3            -   1 request   Read/Write Multiple Registers read {b} (0), write {c}=255 "
        "[warning: read quantity 0 outside the spec's 1..125]  CRC ok",
        "     4            -   1 response  Read/Write Multiple Registers {b} (0) [#3]  CRC ok",
        "     5            -   1 request   Write Multiple Registers {d} (0) [warning: quantity 0 outside the spec's 1..123]  CRC ok",
        "     6            -   1 response  Write Multiple Registers {d} (0) written [#5]  CRC ok",
    ]
    for style, names in ((None, ("8400", "10", "20", "16")), ("plc", ("48401", "40011", "40021", "40017"))):
        options = ["--address-style", style] if style else []
        for pure in ("0", "1"):  # the compiled path leaves such frames to the Python stages
            env = {**os.environ, "VW3_PURE_PYTHON": pure, "PYTHONPATH": str(ROOT)}
            done = subprocess.run([sys.executable, "-m", "dissector", str(capture), *options], capture_output=True,
                                  text=True, env=env, cwd=ROOT, timeout=60)
            assert (done.returncode, done.stderr) == (0, "")
            a, b, c, d = names
            assert done.stdout.splitlines() == [line.format(a=a, b=b, c=c, d=d) for line in lines]
    status, out, err = run_cli([str(capture), "-V"])
    assert (status, err) == (0, "")
    assert out.split("\n\n")[0].splitlines()[4:6] == ["        Start address: 8400 (0x20D0)", "        Quantity: 0 (0x0)"]
    status, out, err = run_cli([str(capture), "--json"])
    records = [json.loads(line) for line in out.splitlines()]
    assert [(r["start"], r["quantity"], r.get("registers"), "span_label" in r) for r in records] == [
        (8400, 0, None, False), (8400, 0, [], False), (10, 0, [{"address": 20, "value": 255}], False),
        (10, 0, [], False), (16, 0, [], False), (16, 0, None, False)]
    status, out, err = run_cli([str(capture), "-T", "fields", "-e", "frame", "-e", "start", "-e", "quantity",
                                "-e", "address", "-e", "value"])
    assert (status, err) == (0, "")
    # (`address` also lists what a frame names without a value, as -Y's address: its start, as reference_num)
    assert out.splitlines() == ["1\t8400\t0\t8400\t", "2\t8400\t0\t8400\t", "3\t10\t0\t20,10\t255",
                                "4\t10\t0\t10\t", "5\t16\t0\t16\t", "6\t16\t0\t16\t"]
    status, out, err = run_cli([str(capture), "-T", "registers"])
    assert (status, out, err) == (0, "3\t\t1\t23\twrite\t20\t\t\t\t255\t\t\t\t\tconfirmed\t\n", "")  # only frame 3 names a register


def test_a_polled_quantity_0_read_in_stats(tmp_path: Path) -> None:
    capture = tmp_path / "q0.pcap"
    records = b""
    for index, frame in enumerate(QUANTITY_0[:4] * 4):
        micros = 50_000 * (index + 1)
        records += struct.pack("<IIII", 1_700_000_000 + micros // 1_000_000, micros % 1_000_000, len(frame), len(frame))
        records += frame
    capture.write_bytes(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147) + records)
    for style, first, second in ((None, "8400 (0)", "read 10 (0), write 20"),
                                 ("plc", "48401 (0)", "read 40011 (0), write 40021")):
        status, out, err = run_cli([str(capture), "--stats", *(["--address-style", style] if style else [])])
        assert (status, err) == (0, "")
        rows = [line for line in out.splitlines() if line.startswith("    1  ") and "200.0" in line]
        assert [re.split(r"\s{2,}", line.strip()) for line in rows] == [
            ["1", "3 Read Holding Registers", first, "4", "200.0", "0.0", "0"],
            ["1", "23 Read/Write Multiple Registers", second, "4", "200.0", "0.0", "0"]]
    status, out, err = run_cli([str(capture), "--stats", "--json"])
    polls = json.loads(out)["poll_cycle"]
    assert [(p["function"], p["start"], p["quantity"], p["count"]) for p in polls] == [(3, 8400, 0, 4), (23, 10, 0, 4)]


def _block(block_type: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack("<II", block_type, len(body) + 12) + body + struct.pack("<I", len(body) + 12)


def _pcapng(offset: int | None, units: list[int]) -> bytes:
    """One interface (if_tsoffset `offset`), one read request a packet at each of `units` microseconds."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    options = struct.pack("<HHq", 14, 8, offset) + b"\0" * 4 if offset is not None else b""
    out += _block(1, struct.pack("<HHI", 147, 0, 0) + options)
    frame = rtu("0c0320d00003")
    for unit in units:
        out += _block(6, struct.pack("<IIIII", 0, unit >> 32, unit & 0xFFFFFFFF, len(frame), len(frame)) + frame)
    return out


# Times no output can show (years 1..9999 are what the calendar, -V, the report and --parquet hold):
# a pcapng stamp of 2^64 - 1 microseconds (the year 586524), an if_tsoffset of -2^62 s.
OUT_OF_RANGE = {"late": (None, [2**64 - 1]), "early": (-(2**62), [1_000_000])}
REFUSED = {
    "late": "t.pcapng: packet block at byte 48: time 18446744073709 s from 1970 is outside "
    "0001-01-02..9999-12-30 UTC, the times every output can show: a corrupt time stamp?",
    "early": "t.pcapng: packet block at byte 64: time -4611686018427387903 s from 1970 (if_tsoffset "
    "-4611686018427387904 s) is outside 0001-01-02..9999-12-30 UTC, the times every output can show: a corrupt "
    "time stamp?",
}
# Times the calendar holds that pcap (1970..2106) or pcapng (from 1970) do not: -w clamps them.
FORMAT_RANGE = {"before 1970": (-100, [1_000_000]), "first day": (-62_135_510_400, [1_000_000]),
                "year 2200": (7_258_118_400, [1_000_000])}
OUTPUTS = [[], ["-t", "a"], ["-t", "ad"], ["-t", "u"], ["-t", "ud"], ["-V"], ["--json"], ["-T", "fields", "-e", "time"],
           ["-T", "registers"], ["--stats"], ["--stats", "--json"], ["--report", "{out}/r.html"],
           ["--report", "{out}/r.html", "-t", "ud"], ["--parquet", "{out}/pq"], ["-w", "{out}/w.pcap"],
           ["-w", "{out}/w.pcapng"], ["-n", "-w", "{out}/w.pcap"]]


@pytest.mark.parametrize("case", sorted(OUT_OF_RANGE))
@pytest.mark.parametrize("output", OUTPUTS, ids=" ".join)
def test_times_no_output_can_show_are_refused_in_one_line(tmp_path: Path, case: str, output: list[str]) -> None:
    capture = tmp_path / "t.pcapng"
    capture.write_bytes(_pcapng(*OUT_OF_RANGE[case]))
    made = tmp_path / "out"
    made.mkdir()
    options = [option.format(out=made) for option in output]
    if "--parquet" in options:
        done = subprocess.run([sys.executable, "-m", "dissector", *options, str(capture)], capture_output=True,
                              text=True, cwd=tmp_path, env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=120)
        status, out, err = done.returncode, done.stdout, done.stderr
        # The parquet dataset's empty table folders are all it leaves; no data file.
        assert not [path for path in made.rglob("*") if path.is_file()]
    else:
        status, out, err = run_cli([*options, str(capture)])
        assert list(made.iterdir()) == []  # no header-only -w file, no empty report
    assert (status, out, err) == (2, "", f"{PROG}{tmp_path}/{REFUSED[case]}\n")
    if "--parquet" in options:
        return  # --parquet reads files only
    status, out, err = run_cli([*options, "-"], stdin=capture.read_bytes())  # read once, the same refusal
    assert (status, out, err[err.index(": packet"):]) == (2, "", REFUSED[case][REFUSED[case].index(": packet"):] + "\n")


@pytest.mark.parametrize("first, text", [
    ("0.5 01 03 00 00 00 01 84 0A", "100000000000000.5 01 03 00 00 00 01 84 0A"),
    ("0.5 01 03 00 00 00 01 84 0A", "0001-01-01T00:00:00 01 03 00 00 00 01 84 0A"),
    ("Tx:000001-[0.5]-01 03 00 00 00 01 84 0A", "Tx:000002-[100000000000000.5]-01 03 00 00 00 01 84 0A"),
])
def test_dump_times_no_output_can_show_are_refused_in_one_line(tmp_path: Path, first: str, text: str) -> None:
    dump = tmp_path / "d.txt"
    dump.write_text(f"{first}\n{text}\n", encoding="ascii")
    seconds = "-62135596800" if text.startswith("0001") else "100000000000000"
    for options in ([], ["-n"]):  # refused by the first pass, or after the first line's
        status, out, err = run_cli([str(dump), *options])
        assert (status, err) == (2, f"{PROG}{dump} line 2: time {seconds} s from 1970 is outside 0001-01-02..9999-12-30 "
                                    "UTC, the times every output can show: a corrupt time stamp?\n")


@pytest.mark.parametrize("case", sorted(FORMAT_RANGE))
@pytest.mark.parametrize("column", ["a", "ad", "u", "ud"])
def test_times_before_1970_and_on_the_first_day_show(tmp_path: Path, case: str, column: str) -> None:
    capture = tmp_path / "t.pcapng"
    capture.write_bytes(_pcapng(*FORMAT_RANGE[case]))
    status, out, err = run_cli(["-t", column, str(capture)])
    assert (status, err) == (0, "")
    day, clock = {"before 1970": ("1969-12-31", "23:58:21"), "first day": ("0001-01-02", "00:00:01"),
                  "year 2200": ("2200-01-01", "00:00:01")}[case]
    if column == "ud":
        assert out.startswith(f"     1 {day} {clock}.000000  12 request   Read Holding Registers 8400..8402 (3)")
    elif column == "u":
        assert out.startswith(f"     1 {clock}.000000  12 request   Read Holding Registers 8400..8402 (3)")
    else:  # local time: the test machine's zone
        assert re.match(r"     1 (\d{4}-\d\d-\d\d )?\d\d:\d\d:\d\d\.000000  12 request", out) and (
            (column == "ad") == bool(re.match(r"     1 \d{4}-", out)))
    status, out, err = run_cli(["-V", str(capture)])
    assert f"    Arrival time: {day} {clock}.000000 UTC (0.000000 s since the first item)" in out.splitlines()


def test_year_one_stamps_keep_their_microseconds(tmp_path: Path) -> None:
    # Review of issue 32 (minor): a year-1 time as a float (-6.2e10 s) keeps about 8 us, so .005000 showed
    # .004997; the stamp's integer nanoseconds are shown instead.
    capture = tmp_path / "t.pcapng"
    capture.write_bytes(_pcapng(-62_135_510_400, [86_400_005_000, 86_400_015_000]))
    status, out, err = run_cli(["-t", "ud", str(capture)])
    assert (status, err) == (0, "")
    assert [line.split()[1:3] for line in out.splitlines()] == [["0001-01-03", "00:00:00.005000"],
                                                                 ["0001-01-03", "00:00:00.015000"]]
    assert run_cli(["-t", "u", str(capture)])[1].splitlines()[0].startswith("     1 00:00:00.005000  12 request")
    status, out, err = run_cli(["-V", str(capture)])
    assert "    Arrival time: 0001-01-03 00:00:00.005000 UTC (0.000000 s since the first item)" in out.splitlines()


@pytest.mark.parametrize("case", sorted(FORMAT_RANGE))
@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_w_clamps_times_the_format_cannot_hold_and_says_so(tmp_path: Path, case: str, suffix: str) -> None:
    capture = tmp_path / "t.pcapng"
    capture.write_bytes(_pcapng(*FORMAT_RANGE[case]))
    written = tmp_path / f"out.{suffix}"
    status, out, err = run_cli([str(capture), "-w", str(written)])
    assert status == 0
    if case == "year 2200" and suffix == "pcapng":
        assert err == ""
        assert [chunk.time for chunk in open_source(str(written))] == [7_258_118_401.0]
        return
    assert err == (f"{PROG}warning: -w {written}: 1 record's time outside what {suffix} holds, "
                   "written at the nearest time it holds\n")
    chunks = list(open_source(str(written)))
    assert [chunk.data for chunk in chunks] == [rtu("0c0320d00003")]
    data = written.read_bytes()
    if suffix == "pcap":  # seconds and microseconds of the first record
        expected = (0xFFFFFFFF, 999_999) if case == "year 2200" else (0, 0)
        assert struct.unpack_from("<II", data, 24) == expected
    else:  # the packet block's 64-bit microseconds: 0, the earliest pcapng holds
        assert data.endswith(struct.pack("<IIIII", 0, 0, 0, 8, 8) + rtu("0c0320d00003") + struct.pack("<I", 40))


@pytest.mark.parametrize("scale", ["1e308", "1e999", "-1e999", "nan", "inf", "1e-300", "0", "1e13"])
def test_map_scales_are_finite_and_keep_results_in_range(tmp_path: Path, scale: str) -> None:
    map_file = tmp_path / "map.csv"
    map_file.write_text(f"address,code,scale\n8401,CHCF,{scale}\n", encoding="utf-8")
    with pytest.raises(ProfileError) as caught:
        load_map_file(map_file)
    why = ("is not a number" if scale in ("nan", "inf") else "would make every value 0" if scale == "0"
           else "is outside ±1e-12..1e+12")
    assert str(caught.value) == f"{map_file}:2: scale {scale!r} {why}"
    status, out, err = run_cli(["--map", str(map_file), "--hex", "0C 03 02 FF FF"])
    assert (status, out, err) == (2, "", f"{PROG}{caught.value}\n")


def test_the_largest_scale_with_ffff_on_the_bus(tmp_path: Path) -> None:
    map_file = tmp_path / "map.csv"
    map_file.write_text("address,code,scale,signed,unit\n8401,A,1e12,,Wh\n8402,B,-1e12,1,Wh\n", encoding="utf-8")
    status, out, err = run_cli(["--map", str(map_file), "--hex", rtu("0c0320d10002").hex(),
                                "--hex", rtu("0c0304ffffffff").hex()])
    assert (status, err) == (0, "")
    assert "A=65535000000000000 Wh" in out.replace("8401=", "") or "65535000000000000 Wh" in out
    assert "1000000000000 Wh" in out


def test_a_deeply_nested_profile_is_one_line(tmp_path: Path) -> None:
    profile = tmp_path / "deep.toml"
    profile.write_text("name = 'x'\nlimits = " + "[" * 5000 + "]" * 5000 + "\n", encoding="utf-8")
    status, out, err = run_cli(["--profile", str(profile), "--hex", "0C 03 20 D0 00 03"])
    assert (status, out) == (2, "")
    assert err == f"{PROG}{profile}: arrays or tables nested too deep for a profile\n"


@pytest.mark.parametrize("option, suffix, what", [("--profile", ".toml", "profile"), ("--map", ".csv", "map")])
def test_profiles_and_maps_refuse_fifos_devices_and_huge_files(tmp_path: Path, option: str, suffix: str,
                                                               what: str) -> None:
    fifo = tmp_path / f"fifo{suffix}"
    os.mkfifo(fifo)
    status, out, err = run_cli([option, str(fifo), "--hex", "0C 03 20 D0 00 03"])  # used to wait forever
    assert (status, err) == (2, f"{PROG}{fifo}: a FIFO, not a {what} file\n")
    zero = tmp_path / f"zero{suffix}"
    zero.symlink_to("/dev/zero")  # used to read 5 GB in 15 s
    status, out, err = run_cli([option, str(zero), "--hex", "0C 03 20 D0 00 03"])
    assert (status, err) == (2, f"{PROG}{zero}: a device, not a {what} file\n")
    folder = tmp_path / f"dir{suffix}"
    folder.mkdir()
    status, out, err = run_cli([option, str(folder), "--hex", "0C 03 20 D0 00 03"])
    assert status == 2 and err.startswith(f"{PROG}{folder}: ") and err.count("\n") == 1
    big = tmp_path / f"big{suffix}"
    with big.open("wb") as stream:
        stream.truncate(17 << 20)
    status, out, err = run_cli([option, str(big), "--hex", "0C 03 20 D0 00 03"])
    limit = "1 MiB, not a profile" if what == "profile" else "16 MiB, not a register map"
    assert (status, err) == (2, f"{PROG}{big}: larger than {limit}\n")


def test_a_non_utf8_file_name_in_a_report(tmp_path: Path) -> None:
    name = os.fsdecode(bytes(tmp_path) + b"/n\xff.bin")
    Path(name).write_bytes(rtu("0c0320d00003") + rtu("0c0306000100020003"))
    report = tmp_path / "report.html"
    status, out, err = run_cli([name, "--report", str(report)])
    assert (status, err) == (0, "")
    assert "n\\xff.bin" in report.read_text(encoding="utf-8")  # (its byte, as every title shows it)


def _vw3(*argv: str, env: dict[str, str] | None = None, limit: int | None = None) -> subprocess.CompletedProcess[str]:
    def cap() -> None:
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    return subprocess.run([sys.executable, "-m", "dissector", *argv], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT), **(env or {})}, cwd=ROOT,
                          preexec_fn=cap if limit is not None else None, timeout=120)


def test_noise_previews_under_an_ascii_only_locale(tmp_path: Path) -> None:
    capture = tmp_path / "noise.bin"
    capture.write_bytes(bytes(range(256)) * 4)
    for env in ({"PYTHONIOENCODING": "ascii", "VW3_PURE_PYTHON": "1"}, {"PYTHONIOENCODING": "ascii"}):
        done = _vw3(str(capture), env=env)  # the Python stages, then the compiled path's lines
        assert done.returncode == 0
        assert all(line.startswith(f"{PROG}warning: ") for line in done.stderr.splitlines()), done.stderr
        assert "bytes of noise at offset 0: 00 01 02 03 04 05 06 07 08 09 0a 0b 0c 0d 0e 0f\\u2026" in done.stdout


# -- lost captures -----------------------------------------------------------------------------------
def _capture(tmp_path: Path, name: str = "same.pcap") -> tuple[Path, bytes]:
    source = ROOT / "captures" / "atv71_commissioning.pcap"
    path = tmp_path / name
    data = source.read_bytes()
    path.write_bytes(data)
    return path, data


def test_an_output_that_is_the_input_is_refused(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    capture, data = _capture(tmp_path)
    link = tmp_path / "link.pcap"
    link.symlink_to(capture.name)
    hard = tmp_path / "hard.pcap"
    os.link(capture, hard)
    monkeypatch.chdir(tmp_path)
    cases = [
        (["same.pcap", "-w", "same.pcap"], "-w same.pcap is the input same.pcap"),
        (["same.pcap", "-w", "./same.pcap"], "-w ./same.pcap is the input same.pcap"),
        (["same.pcap", "--report", "link.pcap"], "--report link.pcap is the input same.pcap"),
        (["link.pcap", "-w", "hard.pcap"], "-w hard.pcap is the input link.pcap"),
        (["same.pcap", "-w", "x.pcap", "--report", "x.pcap"], "--report x.pcap is the -w file x.pcap"),
        (["same.pcap", "--map", "m.csv", "-w", "m.csv"], None),
    ]
    (tmp_path / "m.csv").write_text("address,code\n1,A\n", encoding="utf-8")
    cases[-1] = (cases[-1][0], "-w m.csv is the --map m.csv")
    for argv, message in cases:
        status, out, err = run_cli(argv)
        assert (status, out, err) == (2, "", f"{PROG}{message}: it would be overwritten; give another file\n"), argv
        assert capture.read_bytes() == data
    assert not (tmp_path / "x.pcap").exists()
    status, out, err = run_cli(["same.pcap", "-w", "/dev/null", "--report", "/dev/null"])  # a device is no file
    assert (status, err) == (0, "")


def _vw3_from(stdin: Path, *argv: str, cwd: Path, stdout: Path | None = None) -> tuple[int, str, str]:
    """vw3-decode with standard input (and stdout, when given) redirected from files, as a shell does."""
    with open(stdin, "rb") as source, (open(stdout, "ab") if stdout else open(os.devnull, "wb")) as sink:
        done = subprocess.run([sys.executable, "-m", "dissector", *argv], stdin=source,
                              stdout=sink if stdout else subprocess.PIPE, stderr=subprocess.PIPE,
                              env={**os.environ, "PYTHONPATH": str(ROOT)}, cwd=cwd, timeout=120)
    return done.returncode, (done.stdout or b"").decode(), done.stderr.decode()


def test_an_output_that_is_standard_input_is_refused(tmp_path: Path) -> None:
    capture, data = _capture(tmp_path, "st.pcap")
    tail = "is standard input (-): it would be overwritten; give another file\n"
    cases = [
        (["-", "-w", "st.pcap"], f"-w st.pcap {tail}"),
        (["-", "-w", "./st.pcap", "-P"], f"-w ./st.pcap {tail}"),
        (["--report", "st.pcap", "-"], f"--report st.pcap {tail}"),
        (["-", "--report", "r.html", "-w", "st.pcap", "-F", "pcapng"], f"-w st.pcap {tail}"),
        (["--parquet", "st.pcap", "-"], f"--parquet st.pcap {tail}"),
        (["--raw", "st.pcap", "-"], f"--raw st.pcap {tail}"),
        (["--live", "/dev/stdin", "-w", "st.pcap"],
         "-w st.pcap is the --live /dev/stdin: it would be overwritten; give another file\n"),
    ]
    for argv, message in cases:
        assert _vw3_from(capture, *argv, cwd=tmp_path) == (2, "", f"{PROG}{message}"), argv
        assert capture.read_bytes() == data
        assert sorted(path.name for path in tmp_path.iterdir()) == ["st.pcap"]
    # Standard output appended to the capture read: refused before a byte is read or written.
    for argv in (["st.pcap"], ["-"], ["-", "-w", "-"]):
        whose = "standard input (-)" if "-" in argv else "the input st.pcap"
        assert _vw3_from(capture, *argv, cwd=tmp_path, stdout=capture) == (
            2, "", f"{PROG}standard output is {whose}: redirect it to another file\n")
        assert capture.read_bytes() == data
    # Standard input that is not the output, and an output that is the input's device, still decode.
    status, out, err = _vw3_from(capture, "-", "-w", "copy.pcap", "-P", cwd=tmp_path)
    assert (status, err) == (0, "") and out.startswith("     1     0.000000") and (tmp_path / "copy.pcap").read_bytes()
    assert _vw3_from(capture, "-", "-w", "/dev/null", cwd=tmp_path) == (0, "", "")
    out_file = tmp_path / "out.pcap"
    assert _vw3_from(capture, "st.pcap", "-w", "/dev/stdout", cwd=tmp_path, stdout=out_file) == (0, "", "")
    assert out_file.read_bytes()[:24] == data[:24]


def test_a_refused_input_removes_only_regular_files_it_wrote(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # A refused input removes the header-only -w file and the empty report: never a symlink in its place
    # (-w link.pcap removed the link) nor a device (-w /dev/null, as root, would have removed /dev/null).
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.pcap").write_bytes(b"garbage, not a pcap")
    (tmp_path / "target").write_bytes(b"")
    (tmp_path / "link").symlink_to("target")
    names = ["link"]
    if os.geteuid() == 0:  # a device of our own, never the system's /dev/null
        os.mknod(tmp_path / "null", 0o666 | 0o020000, os.makedev(1, 3))
        names.append("null")
    refused = (2, "", f"{PROG}bad.pcap: not a pcap file (magic 67617262)\n")
    for name in names:
        for option in ("-w", "--report"):
            assert run_cli(["--format", "pcap", "bad.pcap", option, name]) == refused
            assert os.path.lexists(tmp_path / name), (option, name)
    assert (tmp_path / "link").is_symlink()
    assert run_cli(["--format", "pcap", "bad.pcap", "-w", "out.pcap", "--report", "out.html"]) == refused
    assert not (tmp_path / "out.pcap").exists() and not (tmp_path / "out.html").exists()


def test_live_w_and_raw_to_the_same_file_are_refused(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    status, out, err = run_cli(["--live", "loop://", "-w", "cap.pcap", "--raw", "./cap.pcap", "--duration", "0.1"])
    assert (status, err) == (2, f"{PROG}--raw ./cap.pcap is the -w file cap.pcap: it would be overwritten; "
                                "give another file\n")
    assert not (tmp_path / "cap.pcap").exists()


@pytest.mark.parametrize("suffix", ["pcap", "pcapng"])
def test_a_full_disk_keeps_whole_records_and_says_how_many(tmp_path: Path, suffix: str) -> None:
    # RLIMIT_FSIZE makes the kernel write part of a batch and then fail (EFBIG), as a full disk does.
    capture = tmp_path / "big.bin"
    capture.write_bytes((ROOT / "captures" / "atv71_commissioning.bin").read_bytes() * 200)
    written = tmp_path / f"out.{suffix}"
    done = _vw3(str(capture), "-w", str(written), limit=100_001)
    assert done.returncode == 1 and done.stdout == ""
    match = re.fullmatch(rf"vw3-decode: -w {written}: File too large; {written} keeps ([\d,]+) whole records "
                         r"\(([\d,]+) bytes\)\n", done.stderr)
    assert match, done.stderr
    records, size = (int(group.replace(",", "")) for group in match.groups())
    assert size == written.stat().st_size and 100_001 - 600 < size <= 100_001
    chunks = list(open_source(str(written)))  # every record whole: the reader finds no torn one
    assert len(chunks) == records > 1000
    source = open_source(str(written))
    list(source)
    assert source.warnings == []


# -- bounded cost ------------------------------------------------------------------------------------
def _write_flood(path: Path, slaves: int = 64) -> None:
    """FC16 writes (and their answers) over every address of `slaves` slaves: 9 MB for 64."""
    with path.open("wb") as stream:
        for slave in range(1, slaves + 1):
            for start in range(0, 65536, 123):
                count = min(123, 65536 - start)
                values = "".join(f"{(start + index) & 0xFFFF:04x}" for index in range(count))
                stream.write(rtu(f"{slave:02x}10{start:04x}{count:04x}{2 * count:02x}{values}"))
                stream.write(rtu(f"{slave:02x}10{start:04x}{count:04x}"))


@pytest.mark.parametrize("store", ["compiled", "python"])
def test_the_parameter_table_keeps_at_most_its_limit_and_counts_the_rest(store: str) -> None:
    from dissector.render.stats_store import READ, WRITE, CompiledStore, ParameterTable, parameter_rows

    if store == "compiled":
        assert CompiledStore is not None
        table = CompiledStore(10, 3)
    else:
        table = ParameterTable(3)
    for address in range(5):
        table.param(1, address, WRITE, 7, None, None)
    assert table.param(1, 0, READ, 8, None, "8") is False and table.param(1, 0, READ, 9, None, "9") is True
    assert table.param(1, 4, READ, 8, None, "8") is False  # beyond the limit: not kept, no change
    assert table.parameter_count == 3 and table.dropped == 3
    assert [row[:7] for row in parameter_rows(table)] == [
        (1, 0, None, 2, 0, 1, 0), (1, 1, None, 0, 0, 1, 0), (1, 2, None, 0, 0, 1, 0)]


def test_stats_on_a_write_flood_over_64_slaves_stays_under_200_mb(tmp_path: Path) -> None:
    flood = tmp_path / "flood.bin"
    _write_flood(flood)
    assert 8_900_000 < flood.stat().st_size < 9_100_000
    for options in (["--stats"], ["--stats", "--json"], ["--report", str(tmp_path / "r.html")]):
        status, out, peak = _peak_rss(tmp_path, *options, str(flood))
        assert status == 0
        # kB; it was 1.95 GB for --stats, 4.56 GB with --json, 2.1 GB for --report (whose page holds an
        # index of the 262,144 parameters kept: 45 MB of HTML, built in memory)
        assert peak < (200_000 if options[0] == "--stats" else 400_000), (options, peak)
        if options == ["--stats"]:
            assert out.splitlines()[0] == (
                "68224 frames, 0 noise bytes in 0 runs, 7864320 register values of parameters beyond the first "
                "262,144 not tracked")
        elif options[1:] == ["--json"]:
            report = json.loads(out)
            assert len(report["parameters"]) == report["parameter_limit"] == 262_144
            assert report["parameter_events_dropped"] == 7_864_320


# Started from a small process: a child forked (or vforked) straight from the test run inherits the run's
# own peak in ru_maxrss at exec (Linux keeps the old memory's high-water mark), so after a few hundred
# tests in one pytest process the figure was pytest's (295 MB to 2.7 GB), not vw3-decode's.
_MEASURE = (
    "import os, subprocess, sys\n"
    "process = subprocess.Popen(sys.argv[2:])\n"
    "_pid, status, usage = os.wait4(process.pid, 0)\n"
    "open(sys.argv[1], 'w').write(f'{os.waitstatus_to_exitcode(status)} {usage.ru_maxrss}')\n"
)


def _peak_rss(tmp_path: Path, *argv: str) -> tuple[int, str, int]:
    """(exit status, standard output, peak resident memory in kB) of one vw3-decode process."""
    out_path, measure = tmp_path / "out.txt", tmp_path / "measure.txt"
    with out_path.open("wb") as out:
        subprocess.run([sys.executable, "-c", _MEASURE, str(measure), sys.executable, "-m", "dissector", *argv],
                       stdout=out, cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)}, check=True)
    status, peak = map(int, measure.read_text().split())
    return status, out_path.read_text(encoding="utf-8"), peak


def test_register_lines_are_neutralised_for_a_spreadsheet_too(tmp_path: Path) -> None:
    map_file = tmp_path / "map.csv"
    map_file.write_text('address,code,name\n8401,=CMD,"@SUM(A1)"\n', encoding="utf-8")
    capture = tmp_path / "read.bin"
    capture.write_bytes(rtu("0c0320d10001") + rtu("0c03020003"))
    argv = ["--map", str(map_file), "-T", "registers", "-E", "separator=,", str(capture)]
    status, out, err = run_cli(argv)
    assert (status, err) == (0, "")
    assert out.splitlines()[0].split(",")[7:9] == ["'=CMD", "'@SUM(A1)"]
    status, out, err = run_cli([*argv, "-E", "formulas=y"])
    assert out.splitlines()[0].split(",")[7:9] == ["=CMD", "@SUM(A1)"]


def test_a_profiles_texts_are_escaped(tmp_path: Path) -> None:
    profile = tmp_path / "p.toml"
    profile.write_text('name = "p"\ntitle = "T\\u001b[2J"\n[exceptions]\n2 = "bad\\u001b]8;;x\\u0007 address"\n',
                       encoding="utf-8")
    status, out, err = run_cli(["--profile", str(profile), "--hex", rtu("0c0320d00003").hex(), "--hex",
                                rtu("0c8302").hex()])
    assert (status, err) == (0, "")
    assert ESC not in out and "\x07" not in out
    assert "bad\\x1b]8;;x\\x07 address" in out


def test_the_fuzz_campaign_runs_as_shipped(tmp_path: Path) -> None:
    # It failed with `ModuleNotFoundError: test_fuzz` without a PYTHONPATH.
    env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    done = subprocess.run([sys.executable, str(ROOT / "bench" / "fuzz_campaign.py"), "--inputs", "90",
                           "--seconds", "0", "--plugin-records", "0", "--json", str(tmp_path / "f.json")],
                          capture_output=True, text=True, cwd=tmp_path, env=env, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    figures = json.loads((tmp_path / "f.json").read_text())
    assert (figures["inputs"], figures["tracebacks"], figures["differences"]) == (90, 0, 0)
    assert len(figures["formats"]) == 10 and {o["target"] for o in figures["outcomes"]} >= {"cli", "engine", "readers"}
