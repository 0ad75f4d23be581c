"""vw3-decode's `-G fields` rows (render/glossary.py) as tshark 4.0.17 lists the plugin's fields: for each
key with a plugin field (data/fields.toml `filter`), the same name, type, parent, base, bitmask and blurb;
only the abbrev is vw3-decode's key (and the blurb may add what only vw3-decode takes). Where vw3-decode
compares a key otherwise (`kind`: text here, a number there), the type is its own."""
from __future__ import annotations

import subprocess

from helpers import run_cli
from lua_harness import PLUGIN, ensure_tool

from dissector.render.filter_fields import CATALOGUE

OWN_TYPES = {"kind"}  # (the plugin's uint8 with value strings; vw3-decode's text)


def test_rows_are_tsharks() -> None:
    tshark = ensure_tool("tshark", "tshark")
    listing = subprocess.run([tshark, "-G", "fields", "-X", f"lua_script:{PLUGIN}"], capture_output=True,
                             text=True, timeout=600, check=True).stdout.splitlines()
    theirs = {line.split("\t")[2]: line.split("\t") for line in listing if "\tvw3" in line}
    ours = {line.split("\t")[2]: line.split("\t") for line in run_cli(["-G", "fields"])[1].splitlines()}
    assert ours["vw3"] == theirs["vw3"]  # the protocol
    compared = 0
    for entry in CATALOGUE:
        if "key" not in entry or "filter" not in entry or entry["key"] in OWN_TYPES:
            continue
        row, plugin = ours[entry["key"]], theirs[entry["filter"]]
        assert row[:2] + row[3:7] == plugin[:2] + plugin[3:7], entry["key"]
        assert row[7].startswith(plugin[7]), entry["key"]
        compared += 1
    assert compared == 43  # (write_span_label: hunt68)
