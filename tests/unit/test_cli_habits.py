"""tshark's habits (issue 15): -T fields / -e / -E, -t time formats, a reader that goes away, usage
errors on one line, contradicting options refused, times from the capture's integer microseconds."""
from __future__ import annotations

import json
import re
import os
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import run_cli

ROOT = Path(__file__).resolve().parents[2]
P38 = str(ROOT / "captures" / "p38_protection.pcap")
PROG = "vw3-decode"


def _cli(*argv: str, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "dissector", *argv], cwd=ROOT, capture_output=True, text=True, timeout=120,
        env=None if env is None else dict(os.environ, **env),
    )


# -- -T fields ------------------------------------------------------------------------------------

def test_fields_csv_with_header_and_double_quotes() -> None:
    status, out, err = run_cli(
        ["-T", "fields", "-e", "frame", "-e", "kind", "-e", "response_time", "-e", "code", "-e", "value",
         "-E", "header=y", "-E", "separator=,", "-E", "quote=d", "-c", "2", "--profile", "atv71", P38]
    )
    assert (status, err) == (0, "")
    assert out.splitlines() == [
        "frame,kind,response_time,code,value",  # the header is never quoted, as tshark
        '"1","request",,,',  # the read window: no code, no value, nothing quoted (as tshark writes the plugin's)
        '"2","response","0.010157000",",CHCF,COP","32768,3,2"',  # 8400 has no code: one occurrence each
    ]


def test_fields_default_tab_separator_and_occurrences() -> None:
    argv = ["-T", "fields", "-e", "frame", "-e", "address", "-Y", "frame == 2", P38]
    assert run_cli(argv)[1] == "2\t8400,8401,8402\n"
    assert run_cli([*argv, "-E", "occurrence=f"])[1] == "2\t8400\n"
    assert run_cli([*argv, "-E", "occurrence=l"])[1] == "2\t8402\n"
    assert run_cli([*argv, "-E", "aggregator=/s", "-E", "separator=;"])[1] == "2;8400 8401 8402\n"
    assert run_cli([*argv, "-E", "quote=s", "-E", "separator=/s"])[1] == "'2' '8400,8401,8402'\n"


def test_register_keys_have_one_occurrence_per_register() -> None:
    # Frame 2 reads 8400 (non-existent: no code), CHCF and COP: every register column has three
    # occurrences, so the columns line up and occurrence=f names the same register everywhere.
    # Under profile auto (the file read twice: frame 2 is named, issue 27) and forced alike.
    for profile in ([], ["--profile", "atv71"]):
        argv = ["-T", "fields", "-e", "frame", "-e", "address", "-e", "code", "-e", "value", "-e", "status",
                *profile, P38]
        assert run_cli([*argv, "-Y", "frame == 2"])[1] == "2\t8400,8401,8402\t,CHCF,COP\t32768,3,2\tnon-existent,ok,ok\n"
        assert run_cli([*argv, "-Y", "frame == 2", "-E", "occurrence=f"])[1] == "2\t8400\t\t32768\tnon-existent\n"
        assert run_cli([*argv, "-Y", "frame == 2", "-E", "occurrence=l"])[1] == "2\t8402\tCOP\t2\tok\n"
        # The p.38 exception lists its registers without a value: no value (a number has no empty one).
        assert run_cli([*argv, "-Y", "frame == 10"])[1] == (
            "10\t8400,8401,8402\t,CHCF,COP\t\tnon-existent,protected,protected\n"
        )


def test_filters_know_every_fields_key_and_list_them() -> None:
    p38 = P38.replace(".bin", ".pcap")
    status, out, err = run_cli(["-T", "fields", "-e", "frame", "-Y", "time_relative > 2", p38])
    assert (status, out, err) == (0, "9\n10\n11\n12\n", "")
    assert run_cli(["-T", "fields", "-e", "frame", "-Y", "time_delta > 0.5", p38])[1] == "3\n5\n7\n9\n11\n"
    assert run_cli(["-T", "fields", "-e", "frame", "-Y", "fields.start == 8400 and frame < 4", p38])[1] == "1\n3\n"
    assert run_cli(["-T", "fields", "-e", "frame", "-Y", "fields.byte_count == 6 and frame > 7", p38])[1] == "8\n"
    assert run_cli(["-T", "fields", "-e", "frame", "-Y", "exception_meaning contains \"exist\"", p38])[1] == "10\n12\n"
    status, out, err = run_cli(["-Y", "time > 1", p38])
    assert status == 2 and err.splitlines()[0] == (
        "vw3-decode: time is seconds since the epoch (as --json prints it), and 1 is no date: "
        "time_relative counts from the first item, as the time column (column 8)"
    )
    status, out, err = run_cli(["-Y", 'code == "CHFC"', p38])
    assert status == 2 and err.splitlines()[0] == (
        "vw3-decode: code 'CHFC' is no parameter code of this run's maps (did you mean 'CHCF'?) (column 9)"
    )
    status, out, err = run_cli(["-Y", "help"])
    lines = out.splitlines()
    assert status == 0 and err == ""  # (-G fields: tshark's tab-separated form, test_glossary.py)
    names = {line.split()[0] for line in lines[1:-1]}
    from dissector.render.fields import EXTRA_FRAME_KEYS
    from dissector.render.filters import FRAME_FIELDS, REGISTER_FIELDS
    from dissector.render.timefmt import TIME_FIELDS

    # Every key -T fields takes is listed, and the filter takes it.
    from dissector.render.filter_fields import pdu_keys

    keys = {*FRAME_FIELDS, *REGISTER_FIELDS, *TIME_FIELDS, *EXTRA_FRAME_KEYS, *("fields." + key for key in pdu_keys())}
    assert keys <= names and "fields.start" in names
    for key in keys - {"time_delta_displayed"}:
        assert run_cli(["-Y", key, "-c", "1", p38])[0] == 0, key


def test_fields_lists_nested_keys_booleans_and_quotes_doubled() -> None:
    status, out, _err = run_cli(
        ["-T", "fields", "-e", "frame", "-e", "crc_ok", "-e", "fields.start", "-e", "exception_name",
         "-e", "notes", "-E", "quote=d", "-E", "occurrence=f", "-Y", "frame == 9 or frame == 10", P38]
    )
    lines = out.splitlines()
    assert lines[0] == '"9"\t"1"\t"8400"\t\t'  # (no exception name, no note: nothing quoted, as tshark)
    assert lines[1].startswith('"10"\t"1"\t\t"Illegal Data Address"\t"')


def test_fields_quote_inside_a_value_is_doubled_as_a_spreadsheet_expects(tmp_path: Path) -> None:
    from dissector.render.fields import FieldsWriter, parse_fields_options

    writer = FieldsWriter(parse_fields_options(["text"], ["quote=d", "separator=,"]))
    assert writer.line({"registers": [{"address": 1, "value": 2, "text": 'say "hi", twice'}]}) == (
        '"say ""hi"", twice"'
    )


def test_fields_bom_and_json_alias() -> None:
    _status, out, _err = run_cli(["-T", "fields", "-e", "frame", "-E", "bom=y", "-c", "1", P38])
    assert out == "\ufeff1\n"
    _status, json_out, _err = run_cli(["-T", "json", "-c", "1", P38])
    assert json_out == run_cli(["--json", "-c", "1", P38])[1]
    assert json.loads(json_out)["frame"] == 1


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["-T", "fields"], "-T fields needs at least one -e KEY"),
        (["-e", "frame"], "-e KEY needs -T fields"),
        (["-T", "fields", "-e", "frame", "-E", "quote=x"], "-E quote=x: expected d (double), s (single) or n (none)"),
        (["-T", "fields", "-e", "frame", "-E", "occurrence=2"], "-E occurrence=2: expected f (first), l (last) or a (all)"),
        (["-T", "fields", "-e", "frame", "-E", "header"], "-E header: expected name=value, e.g. -E separator=,"),
        (["-T", "registers", "-E", "separator=;;"],
         "-E separator=;;: one character (/t tab, /s space, or the character)"),
        (["-T", "fields", "-e", "frame", "-E", "colour=y"],
         "-E colour: unknown option; use header, separator, quote, occurrence, aggregator, bom or formulas"),
        (["-T", "fields", "-e", "slvae"], "-e slvae: not a field (did you mean slave?)"),
        (["-T", "fields", "-e", "frame", "-V"], "-V (detail tree) contradicts -T fields"),
        (["-V", "--json"], "-V (detail tree) and --json are two outputs: choose one"),
        (["-n", "--profile", "atv71"], "-n (no device profile) contradicts --profile"),
        (["-n", "--map", "x.csv"], "-n (no device profile) contradicts --map"),
        (["--raw", "out.bin"], "--raw (write the bytes heard) needs --live PORT"),
        (["-Y", "slave == 1", "-Y", "slave == 2"], "-Y given twice: combine the filters with and / or in one -Y"),
        (["-P"], "-P (print as well) needs -w FILE"),
        (["-w", "x.pcap", "-P", "-q"], "-P prints the items, -q prints none: choose one"),
        (["--stats", "-V"], "--stats replaces the items: -V and -x show none"),
        (["-T", "fields", "-e", "frame", "-E", "separator=ab"],
         "-E separator=ab: one character (/t tab, /s space, or the character)"),
        (["-T", "fields", "-e", "frame", "-E", "aggregator=xy"],
         "-E aggregator=xy: one character (/t tab, /s space, or the character)"),
        (["--report", "-"], "--report -: the report is an HTML file, not a stream: give a FILE "
                            "(-w - writes the capture to standard output)"),
        (["--parquet", "-"], "--parquet -: the dataset is a folder of Parquet files, not a stream: give a DIR"),
    ],
)
def test_contradicting_options_are_refused_with_one_line(argv: list[str], message: str, tmp_path: Path,
                                                         monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    status, out, err = run_cli([*argv, P38])
    assert (status, out, err) == (2, "", f"{PROG}: {message}\n")
    assert list(tmp_path.iterdir()) == []  # (--report - and --parquet - made a file or a folder named -)


def test_several_inputs_announce_a_header_only_over_what_is_shown(tmp_path: Path) -> None:
    bin38 = P38.replace(".pcap", ".bin")
    out_pcap = str(tmp_path / "out.pcap")
    for argv in (["-w", out_pcap], ["--stats"], ["--report", str(tmp_path / "r.html")], ["-q"]):
        status, out, err = run_cli([*argv, P38, bin38])
        assert (status, err) == (0, "")
        assert "==>" not in out, argv  # (-w FILE printed two ==> file <== lines with nothing under them)
    status, out, err = run_cli(["-w", out_pcap, "-P", P38, bin38])
    assert [line for line in out.splitlines() if line.startswith("==>")] == [f"==> {P38} <==", f"==> {bin38} <=="]


def test_q_prints_no_items_as_tshark_q(tmp_path: Path) -> None:
    # tshark -q -w: the file alone; -q --stats: the statistics alone (-q was refused before: not an option).
    out_pcap = str(tmp_path / "q.pcap")
    assert run_cli(["-q", P38]) == (0, "", "")
    assert run_cli(["-q", "-w", out_pcap, P38]) == (0, "", "")
    assert run_cli([out_pcap])[1] == run_cli([P38])[1]
    assert run_cli(["-q", "--stats", P38]) == run_cli(["--stats", P38])


def test_the_simulator_runs_as_a_package() -> None:
    done = subprocess.run([sys.executable, "-m", "dissector.sim", "--help"], cwd=ROOT, capture_output=True,
                          text=True, timeout=60)
    assert (done.returncode, done.stderr) == (0, "")
    assert done.stdout.startswith("usage: python3 -m dissector.sim.simulate [-h] [--out OUT]")


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--bogus"], "unrecognized arguments: --bogus"),
        (["-c", "0"], "argument -c/--count: '0' must be more than 0"),
        (["--color", "maybe"], "argument --color: invalid choice: 'maybe' (choose from 'auto', 'always', 'never')"),
        (["-t", "x"], "argument -t: invalid choice: 'x' (choose from 'r', 'a', 'ad', 'adoy', 'd', 'dd', 'e', 'u', 'ud', "
                       "'udoy')"),
    ],
)
def test_usage_errors_are_one_line_with_status_2(argv: list[str], message: str) -> None:
    done = _cli(*argv, P38)
    assert (done.returncode, done.stdout, done.stderr) == (2, "", f"{PROG}: {message} (see {PROG} --help)\n")


def test_no_input_is_one_line() -> None:
    done = _cli()
    assert (done.returncode, done.stderr) == (
        2, f"{PROG}: give a capture FILE, - for stdin, --hex BYTES or --live PORT (see {PROG} --help)\n"
    )


# -- -t -------------------------------------------------------------------------------------------

def _time_column(out: str) -> list[str]:
    # number, then the time (dates have a space inside: take what lies before the slave column)
    return [line[7:line.index("  12 ")].strip() for line in out.splitlines()]


@pytest.mark.parametrize(
    ("fmt", "expected"),
    [
        ("r", ["0.010157", "0.526253"]),  # from frame 1, which the filter hides
        ("d", ["0.010157", "0.516096"]),  # from the previous frame captured
        ("dd", ["0.000000", "0.516096"]),  # from the previous frame displayed
        ("e", ["1767225600.019272", "1767225600.535368"]),
        ("u", ["00:00:00.019272", "00:00:00.535368"]),
        ("ud", ["2026-01-01 00:00:00.019272", "2026-01-01 00:00:00.535368"]),
        ("a", ["01:00:00.019272", "01:00:00.535368"]),  # local time: Paris is UTC+1 in January
        ("ad", ["2026-01-01 01:00:00.019272", "2026-01-01 01:00:00.535368"]),
    ],
)
def test_time_formats_as_tshark_and_independent_of_the_filter(fmt: str, expected: list[str]) -> None:
    done = _cli("-t", fmt, "-Y", "frame >= 2 and frame <= 3", P38, env={"TZ": "Europe/Paris"})
    assert (done.returncode, done.stderr) == (0, "")
    assert _time_column(done.stdout) == expected


def test_relative_time_of_frame_17_does_not_depend_on_the_filter() -> None:
    sel = str(ROOT / "captures" / "sel749m_polling.pcap")
    shown = run_cli(["-Y", "frame >= 17", "-c", "1", sel])[1]
    whole = run_cli([sel])[1].splitlines()[16]
    assert shown.splitlines()[0] == whole
    assert shown.split()[1] != "0.000000"


def test_untimed_input_shows_a_dash_in_every_format() -> None:
    for fmt in ("r", "d", "dd", "e", "ud"):
        out = run_cli(["-t", fmt, "--hex", "0C 03 20 D0 00 03 0E EF"])[1]
        assert out.split()[1] == "-"


# -- a reader that goes away ---------------------------------------------------------------------

@pytest.mark.parametrize("view", [[], ["-V"], ["--json"], ["-T", "fields", "-e", "frame"], ["--color", "always"],
                                  ["--color", "always", "-V"]])
def test_a_reader_that_goes_away_ends_quietly(tmp_path: Path, view: list[str]) -> None:
    capture = tmp_path / "big.bin"
    capture.write_bytes((ROOT / "captures" / "atv71_commissioning.bin").read_bytes() * 300)
    producer = subprocess.Popen(
        [sys.executable, "-m", "dissector", *view, str(capture)], cwd=ROOT,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )
    assert producer.stdout is not None
    first = producer.stdout.readline()  # like head -1: read one line, then close the pipe
    producer.stdout.close()
    _out, err = producer.communicate(timeout=120)
    assert first
    assert (producer.returncode, err) == (0, b"")


@pytest.mark.parametrize("color", ["always", "never"])
@pytest.mark.parametrize("view", [[], ["-V"], ["-x"], ["--stats"]])
def test_a_reader_gone_before_the_first_line_ends_quietly_coloured_or_not(color: str, view: list[str]) -> None:
    # `vw3-decode --color always p38.pcap | head -1` exited 1 with nothing said (rich's own broken-pipe
    # exit): the reader's end of a real pipe is closed before the first write, so every write fails.
    producer = subprocess.Popen([sys.executable, "-m", "dissector", "--color", color, *view, P38], cwd=ROOT,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert producer.stdout is not None
    producer.stdout.close()
    _out, err = producer.communicate(timeout=120)
    assert (producer.returncode, err) == (0, b"")


def test_a_live_view_whose_reader_is_gone_ends_quietly(tmp_path: Path) -> None:
    # The live view on a closed pipe hung for ever (rich's exit inside the sink, before the capture
    # thread started, then a wait for that thread to finish); now it ends as a file decode does.
    tap = tmp_path / "lv.pcap"
    producer = subprocess.Popen([sys.executable, "-m", "dissector", "--live", "loop://", "--duration", "1",
                                 "--color", "always", "-w", str(tap)], cwd=ROOT,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert producer.stdout is not None
    producer.stdout.close()
    try:
        _out, err = producer.communicate(timeout=60)
    finally:
        producer.kill()  # (it hung: no process left behind)
    assert (producer.returncode, err) == (0, f"{PROG}: listening on loop:// at 19200 8E1\n".encode())
    assert len(tap.read_bytes()) == 24  # the pcap header: nothing was heard


# -- integer microseconds ---------------------------------------------------------------------------

def test_response_times_from_integer_microseconds() -> None:
    out = run_cli(["--json", "-c", "4", P38])[1]
    times = [json.loads(line).get("response_time") for line in out.splitlines()]
    assert times == [None, 0.010157, None, 0.00798]
    assert '"response_time": 0.010157,' in out


def test_nanosecond_pcap_keeps_its_nanoseconds(tmp_path: Path) -> None:
    import struct

    from helpers import hx

    def record(seconds: int, nanos: int, data: bytes) -> bytes:
        return struct.pack("<IIII", seconds, nanos, len(data), len(data)) + data

    header = struct.pack("<IHHiIII", 0xA1B23C4D, 2, 4, 0, 0, 65535, 147)
    path = tmp_path / "ns.pcap"
    path.write_bytes(
        header
        + record(1767225600, 123456789, hx("0C 03 20 D0 00 03 0E EF"))
        + record(1767225600, 133614897, hx("0C 03 06 80 00 00 03 00 02 17 E4"))
    )
    records = [json.loads(line) for line in run_cli(["--json", str(path)])[1].splitlines()]
    assert records[1]["response_time"] == 0.010158108
    assert run_cli(["-t", "d", str(path)])[1].splitlines()[1].split()[1] == "0.010158108"  # (9 decimals, as tshark)


def test_time_fields_follow_the_capture_and_the_display() -> None:
    status, out, err = run_cli(["-T", "fields", "-e", "frame", "-e", "time_relative", "-e", "time_delta",
                                "-e", "time_delta_displayed", "-E", "header=y", "-Y", "frame >= 3 and frame <= 5", P38])
    assert (status, err) == (0, "")
    assert out.splitlines() == [
        "frame\ttime_relative\ttime_delta\ttime_delta_displayed",
        "3\t0.526253000\t0.516096000\t0.000000000",
        "4\t0.534233000\t0.007980000\t0.007980000",
        "5\t1.050117000\t0.515884000\t0.515884000",
    ]
    untimed = run_cli(["-T", "fields", "-e", "frame", "-e", "time_relative", "--hex", "0C 03 20 D0 00 03 0E EF"])
    assert untimed[1] == "1\t\n"


@pytest.mark.parametrize("view", [[], ["-V"], ["--stats"]])
def test_color_always_into_a_pipe_breaks_no_line(view: list[str]) -> None:
    # `--color always | less -R` (or grep): rich wrapped every line at 80 columns, `CRC` and `ok` on two
    # lines; tshark never breaks a line. The colored text is the plain text, line for line (-V: but the
    # tree's guides), with only the terminal's width for --stats' tables (fitted, as before).
    commissioning = str(ROOT / "captures" / "atv71_commissioning.pcap")
    env = {**os.environ, "COLUMNS": "80"}
    plain = _cli(commissioning, *view, env=env)
    colored = _cli(commissioning, *view, "--color", "always", env=env)
    assert (plain.returncode, colored.returncode) == (0, 0)
    lines = [re.sub(r"\x1b\[[0-9;]*m", "", line) for line in colored.stdout.splitlines()]
    if view == ["-V"]:
        lines = [line.lstrip(" │├└─") for line in lines]
        assert lines == [line.lstrip(" ") for line in plain.stdout.splitlines()]
    elif view == []:
        assert lines == plain.stdout.splitlines()
        assert max(map(len, lines)) > 200  # (the FC43 answer's line)
    else:  # (the bus timing's lines are written plain either way)
        assert [line for line in lines if len(line) > 80] == [
            line for line in plain.stdout.splitlines() if len(line) > 80 and line in lines]
