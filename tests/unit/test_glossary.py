"""`-G fields` in tshark 4.0.17's -G fields format (render/glossary.py): `P\tname\tabbrev` for the protocol,
`F\tname\tabbrev\ttype\tparent\tbase\tbitmask\tblurb` for each field, the abbrev the key -Y and -e take.
Before, it printed -Y help's readable table ('frame                  frame     number         item
number...'). tests/integration/test_glossary_tshark.py holds each row equal to tshark's for the plugin's
field of the same key.
"""
from __future__ import annotations

import re
from pathlib import Path

from helpers import run_cli

ROOT = Path(__file__).resolve().parents[2]


def _glossary() -> list[str]:
    status, out, err = run_cli(["-G", "fields"])
    assert (status, err) == (0, "")
    return out.splitlines()


def test_tsharks_columns() -> None:
    lines = _glossary()
    assert lines[:3] == [
        "P\tVW3 Modbus serial (Altivar 71, SEL-749M)\tvw3",
        "F\tItem\tframe\tFT_UINT32\tvw3\tBASE_DEC\t0x0\titem number, 1-based, as vw3-decode counts them",
        "F\tKind\tkind\tFT_STRING\tvw3\t\t0x0\trequest, response, exception or noise",  # text here
    ]
    for line in [
        "F\tCRC\tcrc\tFT_UINT16\tvw3\tBASE_HEX\t0x0\treceived check value",
        "F\tCRC OK\tcrc_ok\tFT_BOOLEAN\tvw3\t0\t0x0\tthe CRC/LRC checks",
        "F\tTime since request\tresponse_time\tFT_RELATIVE_TIME\tvw3\t\t0x0\tseconds after the request",
        # tshark's frame.time_epoch, as -T fields writes it (was FT_DOUBLE)
        "F\tTime\ttime\tFT_RELATIVE_TIME\tvw3\t\t0x0\tseconds since the epoch of the item's first byte",
        "F\tTime relative\ttime_relative\tFT_RELATIVE_TIME\tvw3\t\t0x0\tseconds since the first item of the input "
        "(a network, RTAC or several-interface capture's first packet)",
        "F\tValue\tvalue\tFT_UINT16\tvw3\tBASE_DEC_HEX\t0x0\tregister value",
        "F\tRegister\tregisters\tFT_NONE\tvw3\t\t0x0\tregister values (presence)",
        "F\tPDU start\tfields.start\tFT_UINT16\tvw3\tBASE_DEC\t0x0\tPDU key of functions 1 2 3 4 15 16",
        "F\tPDU data\tfields.data\tFT_BYTES\tvw3\t\t0x0\tPDU key of function 8 and unknown functions",
    ]:
        assert line in lines
    assert all(len(line.split("\t")) == 8 for line in lines[1:])


def test_every_key_of_y_help_is_listed() -> None:
    status, out, _err = run_cli(["-Y", "help"])
    readable = {line.split()[0] for line in out.splitlines()[1:-1]}
    assert {line.split("\t")[2] for line in _glossary()[1:]} == readable


def test_the_protocol_is_the_plugins() -> None:
    proto = re.search(r'Proto\("(\w+)", "([^"]+)"\)', (ROOT / "lua" / "src" / "fields.lua").read_text())
    assert proto is not None and _glossary()[0] == f"P\t{proto[2]}\t{proto[1]}"
