"""FC12's events as a field in the plugin as in vw3-decode: vw3-decode's derived key fields.event_list (one
occurrence an event, its byte, as tshark's Modbus/TCP modbus.event: render/filter_fields.py DERIVED_KEYS) is
the plugin's vw3.event_list (codegen/fields_lua.py derived_fields, the vw3.<key> of vw3-decode's fields.<key>), so
-T fields writes the same values and a -Y filter finds the same frames. Before, tshark refused the name
(`Some fields aren't valid: vw3.event_list`). Real tshark with -X lua_script:lua/vw3.lua."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from helpers import rtu, run_cli
from lua_harness import PLUGIN, ensure_tool, lua_errors, run_tshark, write_pcap

from dissector.render.filter_fields import DERIVED_KEYS, FOREIGN_NAMES

pytestmark = pytest.mark.integration

T0 = 1767225600.0
# An FC12 request and its answer (events 3, 32, 1, 64: newest first), then an answer with no event.
FRAMES = ["010C", "010C0A00000100020003200140", "010C", "010C06FFFF00080009"]


def _pcap(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "fc12.pcap", [(rtu(frame), T0 + 0.010 * index) for index, frame in enumerate(FRAMES)])


def _plugin(pcap: Path, *args: str) -> str:
    done = run_tshark(pcap, *args)
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr), done.stderr[-2000:]
    return done.stdout


def test_every_derived_key_is_a_plugin_field_of_the_same_values(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path)
    assert list(DERIVED_KEYS) == ["event_list"]  # (another: give it frames here)
    for key in DERIVED_KEYS:
        ours = run_cli(["-T", "fields", "-e", f"fields.{key}", "-e", "fields.event_count", str(pcap)])
        assert ours == (0, "\t\n3,32,1,64\t256\n\t\n\t8\n", "")
        assert _plugin(pcap, "-T", "fields", "-e", f"vw3.{key}", "-e", "vw3.event_count") == ours[1]
        last = run_cli(["-T", "fields", "-E", "occurrence=l", "-e", f"fields.{key}", str(pcap)])[1]
        assert last == "\n64\n\n\n" == _plugin(pcap, "-T", "fields", "-E", "occurrence=l", "-e", f"vw3.{key}")


def test_a_filter_on_the_events_finds_the_same_frames(tmp_path: Path) -> None:
    pcap = _pcap(tmp_path)
    for expression, frames in (("{events} == 64", "2\n"), ("{events} == 5", ""),
                               ("{events} & 0x40 && count({events}) == 4", "2\n"), ("{events}", "2\n"),
                               ("{events} > 3 && {events} < 32", "2\n"), ("!{events} && {count}", "4\n")):
        ours = expression.format(events="fields.event_list", count="fields.event_count")
        theirs = expression.format(events="vw3.event_list", count="vw3.event_count")
        assert run_cli(["-Y", ours, "-T", "fields", "-e", "frame", str(pcap)]) == (0, frames, ""), ours
        assert _plugin(pcap, "-Y", theirs, "-T", "fields", "-e", "frame.number") == frames, theirs


def test_the_tree_says_each_event_as_before(tmp_path: Path) -> None:
    tree = _plugin(_pcap(tmp_path), "-V", "-O", "vw3").splitlines()
    start = next(index for index, line in enumerate(tree) if line.strip() == "Event list (4)")
    assert [line.strip() for line in tree[start + 1:start + 4]] == ["[0]", "Byte: 3 (0x3)", "Event: Unknown Event"]


def test_titled_as_tsharks_field_of_the_same_events() -> None:
    """Each derived key's field is titled as tshark 4.0.17 titles its own field of the same occurrences (the
    foreign name vw3-decode maps to fields.<key>: modbus.event), by what one occurrence is, `Event`: what a
    column of it and the status bar show. Before: `Event list`, the name of the whole list."""
    tshark = ensure_tool("tshark", "tshark")
    listing = subprocess.run([tshark, "-G", "fields", "-X", f"lua_script:{PLUGIN}"], capture_output=True,
                             text=True, timeout=600, check=True).stdout.splitlines()
    rows = {line.split("\t")[2]: line.split("\t") for line in listing if line.startswith("F\t")}
    for key in DERIVED_KEYS:
        theirs = [name for name, ours in FOREIGN_NAMES.items() if ours == f"fields.{key}"]
        assert theirs == ["modbus.event"]  # (another: its tshark field here)
        plugin, tsharks = rows[f"vw3.{key}"], rows[theirs[0]]
        assert (plugin[1], plugin[3], plugin[5]) == (tsharks[1], tsharks[3], tsharks[5]) == ("Event", "FT_UINT8", "BASE_DEC")
