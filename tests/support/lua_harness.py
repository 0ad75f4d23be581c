"""Running the Wireshark Lua plugin (lua/vw3.lua) under real tshark, and the Python decoder beside it.

Both sides read the same pcap (one record per pcap record, linktype 147). Items are compared by where
their bytes are: (record number, offset in the record), since Wireshark numbers records while the
Python decoder numbers items of one byte stream.
"""
from __future__ import annotations

import json
import fcntl
import os
import re
import struct
import sys
import shutil
import subprocess
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from dissector.framing.ascii import AsciiFramer
from dissector.framing.rtu import RtuFramer
from dissector.render.pcapwriter import PcapWriter
from dissector.pipeline import Dissector
from dissector.devices.build import build_annotator
from dissector.render.jsonout import item_to_dict
from dissector.sources.reader import open_source

ROOT = Path(__file__).resolve().parents[2]
PLUGIN = ROOT / "lua" / "vw3.lua"
CLI_TIMEOUT = 1.0  # vw3-decode's --timeout default, and the plugin's preference default
# Linktype 147 mapped to the plugin as a user does it (Preferences > Protocols > DLT_USER): the plugin
# does not take USER0 over.
USER_DLT = 'uat:user_dlts:"User 0 (DLT=147)","vw3","0","","0",""'


def ensure_tool(command: str, package: str) -> str:
    """The path of `command`, installing the Debian package when we are root; fail (never skip) otherwise."""
    path = shutil.which(command)
    if path is not None:
        return path
    install_package(package, lambda: shutil.which(command) is not None, command)
    path = shutil.which(command)
    if path is None:
        pytest.fail(f"{package} installed but {command} is still not on PATH")
    return path


def install_package(package: str, present: Callable[[], bool], what: str) -> None:
    """Install the Debian package unless `present()` (asked again under the lock), when we are root; fail (never
    skip) otherwise: `what` names what is missing."""
    if present():
        return
    if os.geteuid() != 0:
        pytest.fail(f"{what} is missing and we are not root to install {package}")
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    # (one install at a time: the README's command runs two pytest-xdist workers; the lock the serial tests' flock takes)
    with open("/tmp/apt.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not present():
            for args in (["apt-get", "update"], ["apt-get", "install", "-y", package]):
                result = subprocess.run(args, capture_output=True, text=True, env=env, timeout=1800)
                if result.returncode != 0:
                    pytest.fail(f"{' '.join(args)} failed: {result.stderr[-2000:]}")


def write_pcap(path: Path, records: Iterable[tuple[bytes, float]]) -> Path:
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for data, time in records:
            writer.write(data, time)
    return path


def run_tshark(pcap: Path, *args: str, timeout: float = 900, two_pass: bool = True) -> subprocess.CompletedProcess[str]:
    """tshark with the plugin, -2 unless `two_pass` is false (one pass: what tshark shows without -2)."""
    tshark = ensure_tool("tshark", "tshark")
    passes = ["-2"] if two_pass else []
    command = [tshark, "-n", *passes, "-X", f"lua_script:{PLUGIN}", "-o", USER_DLT, "-r", str(pcap), *args]
    # Replacement characters, not an exception, should tshark ever print bytes that are not UTF-8.
    return subprocess.run(command, capture_output=True, encoding="utf-8", errors="replace", timeout=timeout)



def assert_refused_as_tshark(path: Path, ours: str, wiresharks: str, said: str) -> None:
    """`vw3-decode -Y ours` is refused (exit 2, nothing on standard output) with a message starting `said` and
    the filter under it with a caret, as tshark with the plugin refuses `-Y wiresharks`."""
    mine = subprocess.run([sys.executable, "-m", "dissector", "-Y", ours, str(path)],
                          capture_output=True, text=True, timeout=300)
    assert (mine.returncode, mine.stdout) == (2, "") and "Traceback" not in mine.stderr
    lines = mine.stderr.splitlines()
    assert lines[0].startswith(said) and lines[1] == f"  {ours}" and lines[2].strip() == "^"
    result = run_tshark(path, "-Y", wiresharks)
    assert result.returncode != 0 and result.stdout == ""


def assert_same_frames(path: Path, ours: str, wiresharks: str) -> None:
    """`vw3-decode -Y ours` selects the frame numbers tshark with the plugin selects with `-Y wiresharks`."""
    command = [sys.executable, "-m", "dissector", "-Y", ours, "-T", "fields", "-e", "frame", str(path)]
    mine = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert mine.returncode == 0, mine.stderr
    result = run_tshark(path, "-Y", wiresharks, "-T", "fields", "-e", "frame.number")
    assert result.returncode == 0, result.stderr
    assert [int(n) for n in mine.stdout.split()] == [int(n) for n in result.stdout.split()]

# -- reading tshark's PDML ---------------------------------------------------------------------------
@dataclass
class LuaItem:
    record: int
    offset: int
    length: int
    fields: dict[str, str] = field(default_factory=dict)
    registers: list[dict[str, str]] = field(default_factory=list)
    bits: list[dict[str, str]] = field(default_factory=list)
    objects: list[dict[str, str]] = field(default_factory=list)
    experts: list[tuple[str, str]] = field(default_factory=list)  # (expert abbrev, message)
    texts: dict[str, list[str]] = field(default_factory=dict)  # "warning" / "note" -> full texts


def _experts(element: ET.Element) -> list[tuple[str, str]]:
    out = []
    for expert in element.iter("field"):
        if expert.get("name") != "_ws.expert":
            continue
        children = list(expert)
        abbrev = children[0].get("name", "") if children else ""
        message = ""
        for child in children:
            if child.get("name") == "_ws.expert.message":
                message = child.get("show", "")
        out.append((abbrev, message))
    return out


def _subtree(element: ET.Element, prefix: str) -> dict[str, str]:
    out = {}
    for child in element:
        name = child.get("name", "")
        # (a register's hidden empty text fields are -T fields' empty occurrences, not values)
        if name.startswith(prefix) and not (child.get("hide") == "yes" and child.get("show") == ""):
            out[name[len(prefix):]] = child.get("show", "")
    return out


def parse_pdml(text: str) -> tuple[list[LuaItem], list[tuple[int, str]]]:
    """Items per vw3 tree, and record-level experts (record, message) found outside them."""
    root = ET.fromstring(text)
    items: list[LuaItem] = []
    record_experts: list[tuple[int, str]] = []
    for packet in root.iter("packet"):
        number = 0
        for proto in packet.findall("proto"):
            if proto.get("name") == "geninfo":
                for child in proto:
                    if child.get("name") == "num":
                        number = int(child.get("show", "0"))
            if proto.get("name") != "vw3":
                continue
            item = LuaItem(number, int(proto.get("pos", "0")), int(proto.get("size", "0")))
            for child in proto:
                name = child.get("name", "")
                if name == "vw3.reg":
                    reg = _subtree(child, "vw3.reg.")
                    item.registers.append(reg)
                elif name == "vw3.bit":
                    item.bits.append(_subtree(child, "vw3.bit."))
                elif name == "vw3.object":
                    item.objects.append(_subtree(child, "vw3.object."))
                elif name in ("vw3.warning", "vw3.note"):
                    item.texts.setdefault(name[4:], []).append(child.get("show", ""))
                elif name.startswith("vw3."):
                    item.fields[name[4:]] = child.get("show", "")
            item.experts += _experts(proto)
            items.append(item)
        for expert in packet.iter("field"):
            if expert.get("name", "").startswith("vw3.expert.record") or expert.get("name") == "vw3.expert.preference":
                record_experts.append((number, expert.get("showname", "")))
    return items, record_experts


def lua_items(pcap: Path, *options: str, header: int = 0, two_pass: bool = True
              ) -> tuple[list[LuaItem], list[tuple[int, str]], str]:
    """The plugin's items (tshark -2, or one pass); `header`: bytes before the Modbus payload in each
    record (RTAC: 12)."""
    result = run_tshark(pcap, "-T", "pdml", *options, two_pass=two_pass)
    if result.returncode != 0:
        raise AssertionError(f"tshark failed ({result.returncode}): {result.stderr[-3000:]}")
    errors = lua_errors(result.stdout + result.stderr)
    if errors:
        raise AssertionError(f"Lua errors: {errors[:5]}")
    items, record_experts = parse_pdml(result.stdout)
    for item in items:
        item.offset -= header
    return items, record_experts, result.stderr


_LUA_ERROR = re.compile(r"Lua Error|lua_script|Error during loading|attempt to|stack traceback", re.I)


def lua_errors(text: str) -> list[str]:
    return [line for line in text.splitlines() if _LUA_ERROR.search(line)]


# -- the Python side ---------------------------------------------------------------------------------
@dataclass
class PythonItem:
    record: int
    offset: int
    data: dict[str, Any]
    stream_offset: int = 0  # where this item (or this record's piece of a noise run) starts in the stream


def record_lengths(pcap: Path) -> list[int]:
    """Captured length of every record of a classic pcap file (either byte order, us or ns)."""
    data = pcap.read_bytes()
    magic = data[:4]
    if magic in (bytes.fromhex("d4c3b2a1"), bytes.fromhex("4d3cb2a1")):
        order = "<"
    elif magic in (bytes.fromhex("a1b2c3d4"), bytes.fromhex("a1b23c4d")):
        order = ">"
    else:
        raise ValueError(f"{pcap}: not a classic pcap file")
    lengths, position = [], 24
    while position + 16 <= len(data):
        captured = struct.unpack_from(order + "I", data, position + 8)[0]
        lengths.append(captured)
        position += 16 + captured
    return lengths


def plugin_profiles(profiles: list[str] | None) -> list[str]:
    """vw3-decode's profiles as the plugin's `profiles` preference gives them: the same words, and the
    same default (profile `auto`) when no default is given."""
    return list(profiles or [])


def python_items(
    pcap: Path, profiles: list[str] | None = None, *options: str, header: int = 0, one_pass: bool = False
) -> list[PythonItem]:
    """The NDJSON items of `vw3-decode FILE --json` (python3 -m dissector), placed in their records: the
    file read twice, as the plugin shows it with tshark -2 (profile `auto` names a slave's frames with
    the choice made over the whole capture, issue 27). `one_pass`: the file on standard input, read
    once, as the plugin shows it in tshark's single pass (a slave's frames named as its choice stands
    then)."""
    command = [sys.executable, "-m", "dissector", "-" if one_pass else str(pcap), "--json", *options]
    for profile in plugin_profiles(profiles):
        command += ["--profile", profile]
    run = subprocess.run(command, capture_output=True, cwd=ROOT, timeout=900,
                         input=pcap.read_bytes() if one_pass else None)
    result = subprocess.CompletedProcess(run.args, run.returncode, run.stdout.decode(),
                                         run.stderr.decode(errors="replace"))
    if result.returncode != 0:
        raise AssertionError(f"{' '.join(command)} failed ({result.returncode}): {result.stderr[-3000:]}")
    dicts = [json.loads(line) for line in result.stdout.splitlines() if line.strip()]
    return place_items(dicts, [length - header for length in record_lengths(pcap)])


def python_items_library(pcap: Path, profiles: list[str] | None = None) -> list[PythonItem]:
    """The same through the library (pcap records as chunks, default profile, 1 s timeout)."""
    items = []
    with open_source(str(pcap)) as source:
        framer = AsciiFramer() if source.mode == "ascii" else RtuFramer()
        annotate = build_annotator(plugin_profiles(profiles), [])
        dissector = Dissector(framer=framer, annotate=annotate, timeout=CLI_TIMEOUT)
        for chunk in source:
            items += dissector.feed(chunk)
    items += dissector.finish()
    return place_items([item_to_dict(item) for item in items], record_lengths(pcap))


def place_items(dicts: list[dict[str, Any]], lengths: list[int]) -> list[PythonItem]:
    starts = [0]
    for length in lengths:
        starts.append(starts[-1] + length)
    out = []
    empty: set[int] = set()  # (the empty records an item was placed in)
    for data in dicts:
        record = _record_of(starts, data["offset"])
        if data["kind"] != "noise":
            out.append(PythonItem(record + 1, data["offset"] - starts[record], data, data["offset"]))
            continue
        if not data["length"]:  # (a record captured in part of no byte: the next empty record there)
            record = next(index for index, length in enumerate(lengths)
                          if starts[index] == data["offset"] and not length and index not in empty)
            empty.add(record)
            out.append(PythonItem(record + 1, 0, data, data["offset"]))
            continue
        # A noise run of the byte stream may cross records; Wireshark shows it record by record.
        offset, end = data["offset"], data["offset"] + data["length"]
        while offset < end:
            record = _record_of(starts, offset)
            stop = min(end, starts[record + 1])
            out.append(PythonItem(record + 1, offset - starts[record], data | {"length": stop - offset}, offset))
            offset = stop
    return out


def _record_of(starts: list[int], offset: int) -> int:
    low, high = 0, len(starts) - 2
    while low < high:
        middle = (low + high + 1) // 2
        if starts[middle] <= offset:
            low = middle
        else:
            high = middle - 1
    return low


def assert_as_vw3_decode_in_one_and_two_passes(pcap: Path, later: frozenset[str]) -> None:
    """The plugin's one pass shows what `vw3-decode -` shows (but for `later`: what one pass cannot know when it
    shows an item), and its two passes what `vw3-decode FILE` shows."""
    from lua_compare import compare  # (lua_compare imports this module)

    one, _, _ = lua_items(pcap, two_pass=False)
    differences = compare(python_items(pcap, one_pass=True), one, ignore=later)
    assert not differences, "\n".join(differences[:40])
    two, _, _ = lua_items(pcap)
    differences = compare(python_items(pcap), two)
    assert not differences, "\n".join(differences[:40])
