"""`-T registers` (issue 29): one line per register occurrence, exact lines for exact captures, and the
same registers as `--json` says, capture by capture."""
from __future__ import annotations

import csv
import io
import json

import pytest

from conftest import ROOT
from helpers import rtu, run_cli

CAPTURES = ROOT / "captures"
P38 = str(CAPTURES / "p38_protection.pcap")
HEADER = "frame,time,slave,function,access,address,label,code,name,value,scaled,unit,status,text,write,exception_code"


def test_p38_one_row_per_register_of_frames_2_to_12() -> None:
    # (forced: under profile auto frame 2 is before the evidence, issue 26)
    status, out, err = run_cli(["-T", "registers", "-E", "header=y", "-E", "separator=,", "--profile", "atv71", P38])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    assert lines[0] == HEADER
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [int(row["frame"]) for row in rows] == [2] * 3 + [4] * 3 + [6] * 3 + [8] * 3 + [10] * 3 + [12] * 3
    chcf = [row for row in rows if row["code"] == "CHCF"]
    assert [(row["frame"], row["access"], row["value"], row["status"]) for row in chcf] == [
        ("2", "read", "3", "ok"), ("4", "read", "3", "ok"),
        ("6", "read", "32768", "protected"), ("8", "read", "32768", "protected"),
        ("10", "exception", "", "protected"), ("12", "exception", "", "protected"),
    ]
    assert lines[2] == "2,0.010157,12,3,read,8401,,CHCF,Profile,3,,,ok,IO (I/O profile),,"
    assert lines[-2] == "12,2.627401,12,3,exception,8401,,CHCF,Profile,,,,protected,no value: exception 02,,2"


def test_writes_echoes_and_fc23_halves_with_units_and_scaled_values() -> None:
    argv = ["-T", "registers", "-t", "ud", "-Y", "frame in {7, 8, 19, 20}", str(CAPTURES / "atv71_commissioning.pcap")]
    status, out, _err = run_cli(argv)
    assert status == 0
    assert out.splitlines() == [
        "7\t2026-01-01 00:00:00.109240\t2\t6\twrite\t8401\t\tCHCF\tProfile\t2\t\t\t\tSEP (separate)\tconfirmed\t",
        "8\t2026-01-01 00:00:00.118019\t2\t6\techo\t8401\t\tCHCF\tProfile\t2\t\t\t\tSEP (separate)\tconfirmed\t",
        "19\t2026-01-01 00:00:00.234752\t2\t23\twrite\t8501\t\tCMD\tControl word\t6\t\t\t\tEnable voltage, No quick stop"
        "\tconfirmed\t",
        "19\t2026-01-01 00:00:00.234752\t2\t23\twrite\t8502\t\tLFR\tFrequency reference\t0\t0.0\tHz\t\t0.0 Hz\tconfirmed\t",
        "20\t2026-01-01 00:00:00.251380\t2\t23\tread\t3201\t\tETA\tStatus word\t561\t\t\tok\t"
        "Ready to switch on, Voltage enabled, Quick stop inactive, Remote\t\t",
        "20\t2026-01-01 00:00:00.251380\t2\t23\tread\t3202\t\tRFR\tOutput frequency\t0\t0.0\tHz\tok\t0.0 Hz\t\t",
    ]


def test_coils_are_rows_too_and_untimed_input_has_no_time() -> None:
    # FC1 read of 10 coils from 19 (the spec's example: CD 6B 05 -> 0xCD, 0x6B, 0x05 ... 3 bytes).
    request, response = rtu("11 01 0013 000A"), rtu("11 01 02 CD 01")
    status, out, _err = run_cli(["-T", "registers", "-E", "quote=d", "--hex", request.hex(), "--hex", response.hex()])
    assert status == 0
    rows = [line.split("\t") for line in out.splitlines()]
    assert [row[5] for row in rows] == [f'"{address}"' for address in range(19, 29)]
    assert [row[9] for row in rows] == ['"1"', '"0"', '"1"', '"1"', '"0"', '"0"', '"1"', '"1"', '"1"', '"0"']
    assert {row[1] for row in rows} == {'""'} and {row[4] for row in rows} == {'"read"'}


def test_quote_bom_and_file_column_with_several_inputs() -> None:
    status, out, _err = run_cli(
        ["-T", "registers", "-E", "quote=d", "-E", "bom=y", "-E", "header=y", "-Y", "frame == 2", P38, P38]
    )
    assert status == 0
    lines = out.splitlines()
    assert lines[0] == "\ufefffile\t" + HEADER.replace(",", "\t")
    assert lines[1].startswith(f'"{P38}"\t"2"\t"0.010157"\t"12"')
    assert len(lines) == 1 + 3 + 3


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["-E", "occurrence=f"], "-E occurrence: -T registers has one value a line; use header, separator, quote or bom"),
        (["-V"], "-V and -x contradict -T registers: one line per register"),
        (["--stats"], "--stats replaces the items: -T registers shows none"),
        (["--watch", "CHCF"], "--watch replaces the items: -T registers shows none"),
        (["-e", "frame"], "-e KEY needs -T fields"),
        (["-E", "quote=x"], "-E quote=x: expected d (double), s (single) or n (none)"),
    ],
)
def test_contradictions_are_refused(argv: list[str], message: str) -> None:
    assert run_cli(["-T", "registers", *argv, P38]) == (2, "", f"vw3-decode: {message}\n")


@pytest.mark.parametrize("capture", sorted(path.name for path in CAPTURES.iterdir() if path.suffix in (".pcap", ".bin")))
def test_rows_are_the_json_registers(capture: str) -> None:
    """Independently of the writer: each row is one element of a record's registers/bits, in order; a Mask
    Write's (FC22, no value in its frame) is its `fields`' address, its value or_mask where and_mask is 0."""
    path = str(CAPTURES / capture)
    _status, json_out, _err = run_cli(["--json", path])
    expected = []
    for line in json_out.splitlines():
        record = json.loads(line)
        elements = (record.get("registers") or []) + (record.get("bits") or [])
        fields = record.get("fields")
        if record.get("function") == 22 and record["kind"] != "exception" and fields and not elements:
            masks = f"AND 0x{fields['and_mask']:04X} OR 0x{fields['or_mask']:04X}"
            known = fields["and_mask"] == 0
            elements = [{"address": fields["address"], "value": fields["or_mask"] if known else None,
                         "text": masks if known else masks + ": the result depends on the value before"}]
        for element in elements:
            expected.append([
                str(record["frame"]), str(record["slave"]), str(record["function"]),
                *("" if element.get(key) is None else str(element[key])
                  for key in ("address", "code", "value", "scaled", "unit", "status", "text")),
            ])
    status, out, _err = run_cli(["-T", "registers", "-E", "separator=,", "-E", "quote=d", path])
    assert status == 0
    rows = list(csv.reader(io.StringIO(out)))
    got = [[row[0], row[2], row[3], row[5], row[7], row[9], row[10], row[11], row[12], row[13]] for row in rows]
    assert got == expected and len(got) > 0


def test_live_refuses_what_reads_files() -> None:
    assert run_cli(["--live", "loop://", "-T", "registers"]) == (
        2, "", "vw3-decode: -T registers reads files: capture with -w FILE, then -T registers FILE\n")
    assert run_cli(["--live", "loop://", "--parquet", "d"]) == (
        2, "", "vw3-decode: --parquet reads files: capture with -w FILE, then --parquet DIR FILE\n")
