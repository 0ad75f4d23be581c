"""`tshark -T fields` with the plugin lines its register columns up as `vw3-decode -T fields` does (issue
27): each text field of a register (`vw3.reg.code`, `.name`, `.unit`, `.text`, `.source`, `.label`,
`.status`) has one occurrence per register, empty where the register has no such key, so `-e
vw3.reg.address -e vw3.reg.code` pairs them and `-E occurrence=f` names the first register's code, not
the first code; the statuses are vw3-decode's words (ok, protected, non-existent, ambiguous).

A frame's `vw3.reg.address` (`vw3.bit.address`) then lists, hidden, the addresses it names without their
values (a read request's window), as vw3-decode's `address` does after its registers, and a register
window's `vw3.reg.label` its PLC labels, as vw3-decode's `label`: no other key has occurrences for them.

Numbers (`vw3.reg.value`, `.scaled`, `.words`) keep their types (`vw3.reg.scaled > 5`): tshark 4.0 cannot
print an empty number, and a text field of the same name makes it crash on `vw3.reg.value == 3`. Their
occurrences are compared with vw3-decode's non-empty ones, in order.

Every shipped capture and a simulator session, real tshark 4.0.17, against vw3-decode's own -T fields.
"""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from lua_harness import PLUGIN, ROOT, USER_DLT, ensure_tool, lua_errors, write_pcap
from lua_session import SessionBuilder

TEXT_KEYS = ("code", "name", "unit", "text", "source", "label", "status")
NUMBER_KEYS = ("value", "scaled")  # and address
SEP = "^"  # the aggregator: no value of these captures holds it
CAPTURES = sorted((ROOT / "captures").glob("*.pcap"))


def plugin_rows(pcap: Path, *options: str, two_pass: bool = True, first: bool = False) -> dict[int, dict]:
    """Per record: its item numbers and, per register key, the occurrences tshark prints."""
    tshark = ensure_tool("tshark", "tshark")
    keys = [f"vw3.reg.{key}" for key in ("address", *TEXT_KEYS, *NUMBER_KEYS)] + ["vw3.bit.address", "vw3.bit.value"]
    command = [tshark, "-n", *(["-2"] if two_pass else []), "-X", f"lua_script:{PLUGIN}", "-o", USER_DLT,
               *options, "-r", str(pcap), "-T", "fields", "-E", f"aggregator={SEP}",
               *(["-E", "occurrence=f"] if first else []), "-e", "frame.number", "-e", "vw3.item"]
    for key in keys:
        command += ["-e", key]
    result = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    rows = {}
    for line in result.stdout.splitlines():
        cells = line.split("\t")
        values = {key.split(".", 1)[1]: _split(cell) for key, cell in zip(keys, cells[2:])}
        # (not the named addresses, nor a register window's labels)
        registers = max(len(values[f"reg.{key}"]) for key in ("value", *TEXT_KEYS) if key != "label")
        for key in TEXT_KEYS:
            # (one register's empty occurrence prints as an empty cell, as no occurrence would)
            if registers == 1 and not values[f"reg.{key}"]:
                values[f"reg.{key}"] = [""]
        rows[int(cells[0])] = {"items": [int(item) for item in _split(cells[1])], **values}
    return rows


def python_rows(pcap: Path, *options: str, stdin: bool = False, first: bool = False) -> dict[int, dict]:
    """Per item: vw3-decode's occurrences of each register key (registers, then bits, as it lists them)."""
    keys = ("address", *TEXT_KEYS, *NUMBER_KEYS)
    command = [sys.executable, "-m", "dissector", "-" if stdin else str(pcap), *options, "-T", "fields",
               "-E", f"aggregator={SEP}", *(["-E", "occurrence=f"] if first else []), "-e", "frame"]
    for key in ("registers", "bits", *keys):
        command += ["-e", key]
    run = subprocess.run(command, capture_output=True, cwd=ROOT, timeout=600,
                         input=pcap.read_bytes() if stdin else None)
    assert run.returncode == 0, run.stderr.decode(errors="replace")[-2000:]
    rows = {}
    for line in run.stdout.decode().splitlines():
        cells = line.split("\t")
        count = len(json.loads(cells[1])) if cells[1] else 0  # the registers it carries (a bit has no text)
        values = {}
        for key, cell in zip(keys, cells[3:]):
            # (one register without the key prints an empty cell: one empty occurrence, not none)
            if key == "address":  # (then the addresses named without values)
                values[key] = cell.split(SEP) if cell else []  # (a number: none for a register without one)
                continue
            # (a text key: one occurrence per carried register, then, for label, a register window's PLC
            # labels, as the plugin's hidden vw3.reg.label; a number key: only the values there are, as tshark)
            occurrences = cell.split(SEP) if cell or (key in TEXT_KEYS and count) else []
            if key in TEXT_KEYS and key != "label":
                assert len(occurrences) == count or (first and len(occurrences) == 1), (key, line)
            values[key] = occurrences
        rows[int(cells[0])] = values
    return rows


def _split(cell: str) -> list[str]:
    return cell.split(SEP) if cell else []


def differences(plugin: dict[int, dict], python: dict[int, dict]) -> list[str]:
    out = []
    for record, row in plugin.items():
        expected: dict[str, list[str]] = {key: [] for key in ("address", *TEXT_KEYS, *NUMBER_KEYS)}
        for item in row["items"]:
            for key, values in python[item].items():
                expected[key] += values
        # registers, then bits, as vw3-decode lists them (a bit has an address and a value, no text)
        shown = {"address": row["reg.address"] + row["bit.address"]}
        for key in TEXT_KEYS:  # (none for a bit: tshark has no vw3.bit.code, and vw3-decode no empty one)
            shown[key] = row[f"reg.{key}"]
        shown["value"] = row["reg.value"] + row["bit.value"]
        shown["scaled"] = [float(value) for value in row["reg.scaled"]]
        wanted = {key: expected[key] for key in TEXT_KEYS}
        # (an answer nobody asked for has registers without addresses)
        wanted["address"] = [value for value in expected["address"] if value]
        wanted["value"] = [value for value in expected["value"] if value]
        wanted["scaled"] = [float(value) for value in expected["scaled"] if value]
        for key, values in wanted.items():
            if shown[key] != values:
                out.append(f"record {record} (items {row['items']}) {key}: plugin {shown[key]} vw3-decode {values}")
    return out


@pytest.mark.parametrize("capture", CAPTURES, ids=lambda path: path.name)
def test_register_columns_line_up_as_vw3_decode_one_pass(capture: Path) -> None:
    # tshark's single pass against vw3-decode reading the same bytes once (standard input)
    found = differences(plugin_rows(capture, two_pass=False), python_rows(capture, stdin=True))
    assert not found, "\n".join(found[:20])


@pytest.mark.parametrize("capture", CAPTURES, ids=lambda path: path.name)
def test_register_columns_line_up_as_vw3_decode_two_pass(capture: Path) -> None:
    # tshark -2 against vw3-decode reading the file (twice: profile auto chosen over the whole capture)
    found = differences(plugin_rows(capture), python_rows(capture))
    assert not found, "\n".join(found[:20])


def test_register_columns_of_a_simulator_session(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "session.pcap", SessionBuilder(seed=27).session(500))
    found = differences(plugin_rows(pcap, two_pass=False), python_rows(pcap, stdin=True))
    assert not found, "\n".join(found[:20])
    found = differences(plugin_rows(pcap), python_rows(pcap))
    assert not found, "\n".join(found[:20])
    # PLC addresses: vw3.reg.label on every register of an ATV71 slave, empty on the others
    found = differences(plugin_rows(pcap, "-o", "vw3.address_style:plc", "-o", "vw3.profiles:12=atv71", two_pass=False),
                        python_rows(pcap, "--address-style", "plc", "--profile", "auto", "--profile", "12=atv71",
                                    stdin=True))
    assert not found, "\n".join(found[:20])


def test_p38_rows_exactly() -> None:
    p38 = ROOT / "captures" / "p38_protection.pcap"
    rows = plugin_rows(p38, two_pass=False)
    # (the requests name 8400..8402 too: hidden vw3.reg.address, no other register field)
    assert [(record, row["reg.address"], row["reg.code"]) for record, row in rows.items() if record % 2] == [
        (record, ["8400", "8401", "8402"], []) for record in (1, 3, 5, 7, 9, 11)]
    assert [(record, row["reg.address"], row["reg.code"], row["reg.status"]) for record, row in rows.items()
            if row["reg.status"]] == [
        (2, ["8400", "8401", "8402"], ["", "", ""], ["", "", ""]),  # (one pass: slave 12 is still generic)
        (4, ["8400", "8401", "8402"], ["", "CHCF", "COP"], ["non-existent", "ok", "ok"]),
        (6, ["8400", "8401", "8402"], ["", "CHCF", "COP"], ["non-existent", "protected", "ok"]),
        (8, ["8400", "8401", "8402"], ["", "CHCF", "COP"], ["non-existent", "protected", "ok"]),
        (10, ["8400", "8401", "8402"], ["", "CHCF", "COP"], ["non-existent", "protected", "protected"]),
        (12, ["8400", "8401", "8402"], ["", "CHCF", "COP"], ["non-existent", "protected", "protected"]),
    ]
    # -2: slave 12's profile, chosen at frame 4, names frame 2 too (vw3-decode reading the file)
    two = plugin_rows(p38)
    assert (two[2]["reg.code"], two[2]["reg.status"]) == (["", "CHCF", "COP"], ["non-existent", "ok", "ok"])
    assert {record: row for record, row in two.items() if record != 2} == {
        record: row for record, row in rows.items() if record != 2}
    # -E occurrence=f: the first register's code (8400 has none), as vw3-decode says it
    first = plugin_rows(p38, two_pass=False, first=True)
    assert [row["reg.code"] for row in first.values() if row["reg.status"]] == [[""]] * 6  # (it said CHCF)
    python = python_rows(p38, stdin=True, first=True)
    assert [row["code"] for row in python.values() if row["status"]] == [[""]] * 6
    # Filters keep their types: codes and statuses by name, values as numbers.
    tshark = ensure_tool("tshark", "tshark")
    for expression, frames in (('vw3.reg.code == "CHCF" && vw3.reg.status == "protected"', "6 8 10 12"),
                               ("vw3.reg.value == 3", "2 4"), ('vw3.reg.status == "non-existent"', "4 6 8 10 12"),
                               ('vw3.reg.code == "COP" && vw3.reg.status == "ok"', "4 6 8")):
        command = [tshark, "-n", "-X", f"lua_script:{PLUGIN}", "-o", USER_DLT, "-r", str(p38), "-Y", expression,
                   "-T", "fields", "-e", "frame.number"]
        result = subprocess.run(command, capture_output=True, text=True, timeout=300)
        assert result.returncode == 0, (expression, result.stderr)
        assert " ".join(result.stdout.split()) == frames, expression
