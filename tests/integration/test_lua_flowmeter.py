"""The flow meter's real recordings (sigrok-dumps uart/modbus_rtu/flowmeter,
tests/support/flowmeter_corpus.py; tests/unit/test_corpus_flowmeter.py) in the plugin and in tshark's own
mbrtu: as the recording's bursts and as reads cut anywhere, the plugin's items are vw3-decode's, and each
record of the bursts is the frame mbrtu shows there (slave 247, its function code, CRC good)."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from flowmeter_corpus import CAPTURES, cut_anywhere, pcap, records
from lua_compare import assert_same_as_vw3_decode, tshark_fields

pytestmark = pytest.mark.integration

MBRTU = ["-o", 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""', "-o", "mbrtu.crc_verification:TRUE"]
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "vw3.kind", "-e", "vw3.slave", "-e", "vw3.function"]


@pytest.mark.parametrize("name", sorted(CAPTURES))
def test_the_plugin_and_mbrtu_on_the_recordings(name: str, tmp_path: Path) -> None:
    recorded = records(name)
    bursts = pcap(tmp_path / "bursts.pcap", recorded)
    expected = [f"{1 + k % 2};247;{data[1]}" for k, (_time, data) in enumerate(recorded)]
    assert tshark_fields(bursts, FIELDS) == expected
    assert_same_as_vw3_decode(bursts)
    assert_same_as_vw3_decode(pcap(tmp_path / "reads.pcap", cut_anywhere(recorded, 3)))
    shown = subprocess.run(["tshark", *MBRTU, "-r", str(bursts), "-T", "fields", "-E", "separator=;", "-e",
                            "mbrtu.unit_id", "-e", "modbus.func_code", "-e", "mbrtu.crc16.status"],
                           capture_output=True, text=True, timeout=300)
    assert shown.stdout.splitlines() == [f"247;{data[1]};1" for _time, data in recorded]
