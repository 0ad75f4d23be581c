"""vw3-decode -V as the plugin's tree: a one-byte LRC shown as one byte; FC43/14's MEI type, read code and
conformity named from the spec's tables (data/modbus.toml), the number kept beside the name."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def decode(*args: str) -> str:
    done = subprocess.run([sys.executable, "-m", "dissector", *args], cwd=ROOT, capture_output=True, text=True,
                          check=True)
    return done.stdout


def test_ascii_lrc_is_one_byte() -> None:
    lines = decode("-V", "--hex", ":010300000001FB\r\n").splitlines()
    assert "        LRC: 0xFB [LRC ok]" in lines
    bad = decode("-V", "--hex", ":010300000001FA\r\n").splitlines()
    assert "        LRC: 0xFA [LRC BAD (received 0xFA, expected 0xFB)]" in bad


REQUEST = "0C 2B 0E 01 00 5D B6"  # FC43/14: basic, from object 0
RESPONSE = "0c 2b 0e 01 83 00 00 01 00 03 41 42 43 46 88"  # conformity 0x83, VendorName 'ABC'
ODD = "0c 2b 0e 09 05 00 00 01 00 03 41 42 43 8d 04"  # read code 9, conformity 5: no names


def test_device_id_request_names() -> None:
    lines = decode("-V", "--hex", REQUEST).splitlines()
    assert lines[4:8] == [
        "        MEI type: Read Device Identification (14)",
        "        Body",
        "            Read code: basic (1)",
        "            Object id: 0 (0x0)",
    ]


def test_device_id_response_conformity_named() -> None:
    lines = decode("-V", "--hex", RESPONSE).splitlines()
    assert lines[4:8] == [
        "        MEI type: Read Device Identification (14)",
        "        Body",
        "            Read code: basic (1)",
        "            Conformity: extended, stream and individual access (131)",
    ]
    odd = decode("-V", "--hex", ODD).splitlines()
    assert odd[6:8] == ["            Read code: Unknown (9)", "            Conformity: Unknown (5)"]


def test_json_keeps_numbers_and_adds_names() -> None:
    assert json.loads(decode("--json", "--hex", REQUEST))["fields"] == {
        "mei_type": 14, "mei_type_name": "Read Device Identification",
        "body": {"read_code": 1, "read_code_name": "basic", "object_id": 0}}
    body = json.loads(decode("--json", "--hex", RESPONSE))["fields"]["body"]
    assert (body["conformity"], body["conformity_name"]) == (131, "extended, stream and individual access")
    odd = json.loads(decode("--json", "--hex", ODD))["fields"]["body"]
    assert (odd["read_code"], odd["read_code_name"], odd["conformity"], odd["conformity_name"]) == (9, None, 5, None)
