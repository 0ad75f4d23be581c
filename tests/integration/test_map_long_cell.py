"""A --map cell longer than Python csv's field limit (131,072 characters; hunt62): vw3-decode refused the
map with csv's words, `map.csv:2: field larger than field limit (131072)`, exit 2, where the plugin's
`vw3.maps` reads the same file and names the register. A cell may be as long as a map may be (16 MiB), in
both readers; csv's process-wide limit is left as it was."""
from __future__ import annotations

import csv
import subprocess
import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, run_tshark, write_pcap
from dissector.devices.maps import parse_map
from dissector.protocol.crc import with_crc

pytestmark = pytest.mark.integration
NAME = "Motor speed " * 12_000 + "(rpm)"  # 144,005 characters
READ = [(with_crc(bytes.fromhex("010300000002")), 1767225600.0),
        (with_crc(bytes.fromhex("0103040001000A")), 1767225600.01)]


def test_a_long_name_is_read_as_the_plugin_reads_it(tmp_path: Path) -> None:
    long = tmp_path / "map.csv"
    long.write_text(f"address,code,name\n1,SPD,{NAME}\n", encoding="utf-8")
    pcap = write_pcap(tmp_path / "read.pcap", READ)
    cli = subprocess.run([sys.executable, "-m", "dissector", str(pcap), "--map", f"1={long}", "-T", "fields",
                          "-e", "code", "-e", "name", "-E", "occurrence=l"], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert (cli.returncode, cli.stderr) == (0, "")
    assert cli.stdout.splitlines()[1] == f"SPD\t{NAME}"
    plugin = run_tshark(pcap, "-o", f"vw3.maps:1={long}", "-T", "fields", "-e", "vw3.reg.code", "-e", "vw3.reg.name",
                         "-E", "occurrence=l")
    assert plugin.stdout.splitlines()[1] == f"SPD\t{NAME}"


def test_the_csv_limit_is_left_as_it_was() -> None:
    before = csv.field_size_limit()
    assert parse_map(f"address,code,name\n1,SPD,{NAME}\n", "map.csv")[1].name == NAME
    assert csv.field_size_limit() == before
