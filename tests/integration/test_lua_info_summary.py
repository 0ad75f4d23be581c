"""The plugin's Info column says what vw3-decode's summary line says, field by field, for every public
function code and kind: the slave, the function's name (the device's, SEL-749M's 96..126), the kind, the
description (render/describe.py info_text), `[provisional]` and a bad check. Table-driven over small
vectors (FC1..8 with FC8's sub-functions, 11, 12, 15, 16, 17, 20..24, 43/14 and another MEI, exceptions,
user-defined codes, broadcast, malformed frames, noise, bad CRC), generic, ATV71 and SEL-749M (PLC style),
RTU and ASCII; tshark -2 against `vw3-decode FILE`, one pass against `vw3-decode -` (reading once).

The differences kept by design (BY_DESIGN below, and the tails):
- the plugin's text is `SLAVE NAME KIND DESCRIPTION` (Wireshark has no slave or kind column of vw3's); an
  exception's kind word takes the place of the summary's colon (`3 Read Holding Registers exception 2
  (Illegal Data Address)`);
- registers' values and bits are left out (`5..7 (3)`, not `5..7 (3): 5=1 6=2 7=3`; FC23's request its read
  and write windows): the plugin's quick lanes keep one Info text for every answer to a window and for a write's
  request met again with other values (lua/src/records.lua), and the tree holds each value;
- the pairing, notes and warnings of the summary's tail are the tree's fields and expert infos, not the
  Info column (`[provisional]` is in both; a bad check is ` BAD CRC` / ` BAD LRC` there, the summary's
  CRC column here);
- noise is `noise (4 bytes)`: its offset and bytes are the tree's and the bytes pane's.
Real tshark 4.0 with -X lua_script:lua/vw3.lua; vw3-decode under the compiled engine."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from helpers import rtu
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

from dissector.protocol.spec import SPEC

pytestmark = pytest.mark.integration

T0 = 1767225600.0  # 2026-01-01 00:00:00 UTC; one record a second
EIGHTEEN = "0102030405060708090a0b0c0d0e0f101112"
DEVICE_ID = "2B 0E 01 01 00 00 03 00 07 436F6D70616E79 01 05 504D313233 02 05 56322E3131"

# The vectors by group: (profile, frames as hex without the check; "!" after one: its check damaged,
# "noise:" its bytes as they are). Requests and their answers in turn, one record each, a second apart.
GROUPS: dict[str, tuple[str, list[str]]] = {
    "reads": ("", [
        "01 01 0000 000A", "01 01 02 CD01", "01 02 0010 0003", "01 02 01 05", "01 03 0005 0003",
        "01 03 06 0001 0002 0003", "01 04 0007 0001", "01 04 02 1234", "01 03 0064 0000", "01 03 0064 0001",
        "01 03 02 0007", "01 03 FFFE 0004", "01 03 08 0001 0002 0003 0004", "01 03 04 000A 000B",
        "01 01 02 0A 0B",  # (answers with no request: their values alone)
    ]),
    "writes": ("", [
        "01 05 0002 FF00", "01 05 0002 FF00", "01 05 0003 0000", "01 05 0003 0000", "01 05 0004 1234",
        "01 06 0005 BEEF", "01 06 0005 BEEF", "01 0F 0013 000A 02 CD01", "01 0F 0013 000A",
        "01 10 0001 0002 04 000A 0102", "01 10 0001 0002", "01 16 0004 00F2 0025", "01 16 0004 00F2 0025",
        "01 17 0003 0006 000E 0003 06 00FF 00FF 00FF", "01 17 0C 00FE 0ACD 0001 0003 000D 00FF",
        "00 06 0001 0003", "00 05 0001 FF00", "00 10 0001 0001 02 0007",
    ]),
    "serial_line": ("", [
        "01 07", "01 07 6D", "01 0B", "01 0B FFFF 0108", "01 0C", "01 0C 08 0000 0108 0121 2000",
        "01 11", "01 11 05 12 FF 56 31 2E", "01 11", "01 11 00", "01 11", "01 11 01 07",
        "01 14 07 06 0004 0001 0002", "01 14 06 05 06 0DFE 0020",
        "01 15 0D 06 0004 0007 0003 06AF 04BE 100D", "01 15 0D 06 0004 0007 0003 06AF 04BE 100D",
        "01 18 04DE", "01 18 0006 0002 01B8 1284", "01 18 0010",
        "01 18 0014 0009 000100020003000400050006000700080009",
        "01 2B 0E 01 00", f"01 {DEVICE_ID}", "01 2B 0E 02 00", "01 2B 0E 02 01 FF 02 01 00 07 436F6D70616E79",
        "01 2B 0D 00 01",
    ]),
    "diagnostics": ("", [
        "01 08 0000 A537", "01 08 0000 A537", "01 08 0000", "01 08 0000", f"01 08 0000 {EIGHTEEN}",
        f"01 08 0000 {EIGHTEEN}", "01 08 0001 FF00", "01 08 0001 FF00", "01 08 000A 0000", "01 08 000A 0000",
        "01 08 000B 0000", "01 08 000B 0004", "01 08 0012 0000", "01 08 0012 0003", "01 08 0014 0000",
        "01 08 0014 0000", "01 08 0063 0000", "01 08 0063 0000", "01 08 0004 0000",
    ]),
    "others": ("", [
        "01 83 02", "01 86 03", "01 81 01", "01 90 04", "01 AB 0B", "01 83 20", "01 41 0102", "01 41 0102",
        "01 64", "01 64 00", "01 6E 01020304 05", "01 03 0001", "01 03 04 0001", "01 06 0001 0003 00",
        "noise:55 12 FF 00", "01 03 0005 0003!", "01 03 06 0001 0002 0003", "01 06 0005 0001!",
    ]),
    "atv71": ("atv71", [
        "0C 03 0C81 0002", "0C 03 04 0003 FFCE", "0C 03 20D0 0003", "0C 03 06 8000 0003 0002",
        "0C 06 0C1F 01F4", "0C 06 0C1F 01F4", "0C 06 20D1 0003", "0C 06 20D1 0003", "0C 06 20D5 0009",
        "0C 06 2136 FFCE", "0C 10 2135 0002 04 000F 01F4", "0C 10 2135 0002", "0C 83 02", "0C 86 07",
        "0C 08 0000 1234", "0C 08 0000 1234", "0C 08 000B 0000", "0C 08 000B 0004", "0C 2B 0E 01 00",
        "0C 2B 0E 01 01 00 00 03 00 0D 54656C656D6563616E69717565 01 08 4154563731484435 02 04 30323031",
        "0C 03 1B59 0001", "0C 83 02",
    ]),
    "sel749m": ("sel749m", [
        "03 03 0001 0002", "03 03 04 0001 0002", "03 04 0010 0001", "03 04 02 0005", "03 06 0001 0003",
        "03 06 0001 0003", "03 10 0001 0002 04 000A 0102", "03 10 0001 0002", "03 83 02", "03 90 03",
        "03 60 0001", "03 60 0001 0002", "03 7E", "03 7E", "03 08 0001 0000", "03 08 0001 0000",
    ]),
}


def ascii_frame(body: bytes) -> bytes:
    return b":" + (body + bytes([-sum(body) & 0xFF])).hex().upper().encode() + b"\r\n"


def record(text: str, ascii: bool) -> bytes:
    if text.startswith("noise:"):
        return bytes.fromhex(text[6:])
    body = bytes.fromhex(text.rstrip("!"))
    frame = ascii_frame(body) if ascii else rtu(body.hex())
    if text.endswith("!"):  # (its check damaged)
        frame = frame[:-3] + b"00\r\n" if ascii else frame[:-1] + bytes([frame[-1] ^ 0xFF])
    return frame


# By design (the module's docstring): the plugin's description from the summary's, by function code and
# kind, where the plugin leaves the values out.
def values_left_out(description: str) -> str:
    """`5..7 (3)` of `5..7 (3): 5=1 6=2 7=3`; nothing of an answer's values alone (no request)."""
    return description.split(": ")[0] if ": " in description else ""


BY_DESIGN = {
    **{(code, "response"): values_left_out for code in (1, 2, 3, 4, 23)},
    **{(code, "request"): values_left_out for code in (15, 16)},
    (23, "request"): lambda description: write_window(description),
}


def write_window(description: str) -> str:
    """FC23's request: both windows, the write's values left out (`read 3..8 (6), write 14..16 (3)` of
    `read 3..8 (6), write 14=255 15=255 16=255`); a request that sends none already shows its window."""
    read, _, written = description.partition(", write ")
    addresses = [token.split("=")[0] for token in written.split(" ") if "=" in token]
    if not addresses:
        return description
    window = addresses[0] if len(addresses) == 1 else f"{addresses[0]}..{addresses[-1]} ({len(addresses)})"
    return f"{read}, write {window}"
CODES = {name: code for code, name in SPEC.functions.items()}


def summary_items(pcap: Path, profile: str, one_pass: bool) -> list[tuple[str, str, str, str]]:
    """vw3-decode's lines as (slave, kind, info and tail, check)."""
    argv = [sys.executable, "-m", "dissector", "-" if one_pass else str(pcap),
            *(["--profile", profile] if profile else [])]
    stdin = pcap.read_bytes() if one_pass else None
    out = subprocess.run(argv, capture_output=True, input=stdin, cwd=ROOT, timeout=300, check=True).stdout
    items = []
    for line in out.decode().splitlines():
        if line[24:29] == "noise":
            items.append(("-", "noise", line[34:], ""))
            continue
        rest, check = line[34:].rsplit("  ", 1)
        items.append((line[20:23].strip(), line[24:33].strip(), rest, check))
    return items


def function_name(described: str, plugin: str, slave: str, kind: str) -> str:
    """The function's name: the longest start of the summary's info the plugin writes before the kind."""
    for end in range(len(described), 0, -1):
        if plugin.startswith(f"{slave} {described[:end]} {kind}"):
            return described[:end]
    raise AssertionError(f"no function name of {described!r} in {plugin!r}")


def expected_info(item: tuple[str, str, str, str], plugin: str) -> str:
    """The plugin's Info for vw3-decode's fields: the same fields, with the differences kept by design."""
    slave, kind, info, check = item
    if kind == "noise":
        count = int(info.split(" ")[0])
        return f"noise ({count} byte{'s' if count > 1 else ''})"
    described = info.split(" [")[0]  # (the tail: pairing, notes, warnings, provisional)
    name = function_name(described, plugin, slave, kind)
    description = described[len(name):]
    if kind == "exception":
        description = description.removeprefix(": exception ")
    else:
        description = description.removeprefix(" ")
        design = BY_DESIGN.get((CODES.get(name), kind))
        if design is not None and description != "(malformed)":
            description = design(description)
    tail = " [provisional]" if "[provisional]" in info else ""
    tail += {"CRC": " BAD CRC", "LRC": " BAD LRC"}[check[:3]] if "BAD" in check else ""
    return " ".join([slave, name, kind] + ([description] if description else [])) + tail


def compare(summary: list[tuple[str, str, str, str]], plugin: list[str]) -> list[str]:
    assert len(summary) == len(plugin), (summary, plugin)
    return [f"#{number}: plugin {shown!r}, summary {item[2]!r}, expected {expected_info(item, shown)!r}"
            for number, (item, shown) in enumerate(zip(summary, plugin), 1)
            if shown != expected_info(item, shown)]


@pytest.mark.parametrize("ascii", [False, True], ids=["rtu", "ascii"])
@pytest.mark.parametrize("group", sorted(GROUPS))
def test_plugin_info_is_the_summary_description(tmp_path: Path, group: str, ascii: bool) -> None:
    profile, texts = GROUPS[group]
    records = [(record(text, ascii), T0 + index) for index, text in enumerate(texts)]
    pcap = write_pcap(tmp_path / f"{group}.pcap", records)
    options = ["-o", f"vw3.profiles:{profile}"] if profile else []
    # (one pass: not where frames whose length disagrees with their layout wait for later bytes, shown in a
    # later record, `(6 bytes continue)`: test_lua_one_pass_framed_records)
    for one_pass in (False, True) if group != "others" else (False,):
        got = run_tshark(pcap, *options, "-T", "fields", "-e", "_ws.col.Info", two_pass=not one_pass)
        assert not lua_errors(got.stdout + got.stderr), got.stderr[-2000:]
        differences = compare(summary_items(pcap, profile, one_pass), got.stdout.splitlines())
        assert not differences, "\n".join(differences)
