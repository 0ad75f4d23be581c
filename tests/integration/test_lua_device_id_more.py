"""The plugin's Info text of a Read Device Identification answer with More Follows FF says so, with the object
id the rest follows from, as vw3-decode does (tests/integration/test_device_id_answers.py; tree.lua
BY_NAME.mei, describe._mei). Before, nothing of more to follow."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import run_tshark, write_pcap
from test_device_id_answers import FRAMES, MORE

pytestmark = pytest.mark.integration


def test_the_plugin_says_more_follows(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "fc43.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    info = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info", two_pass=True).stdout.splitlines()
    assert info[3] == f"1 Encapsulated Interface Transport response Read Device Identification, basic: {MORE}"
