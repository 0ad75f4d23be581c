"""A capture exported by tshark as text with details and bytes (tshark -V -x, what Wireshark's Export Packet
Dissections as plain text writes) decodes as the capture itself: every --json object and the --stats
equal, times and response times included (hunt64: the export was read untimed, response_time null)."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from helpers import run_cli
from lua_harness import ROOT, USER_DLT, ensure_tool

pytestmark = pytest.mark.integration
MBRTU = USER_DLT.replace('"vw3"', '"mbrtu"')


@pytest.mark.parametrize("capture", sorted((ROOT / "captures").glob("*.pcap")), ids=lambda path: path.name)
def test_export_decodes_as_its_capture(capture: Path, tmp_path: Path) -> None:
    tshark = ensure_tool("tshark", "tshark")
    export = tmp_path / "export.txt"
    with export.open("w") as stream:
        subprocess.run([tshark, "-n", "-o", MBRTU, "-V", "-x", "-r", str(capture)], stdout=stream, check=True,
                       stderr=subprocess.DEVNULL, timeout=300)
    for options in (["--json"], ["--stats"]):
        direct, exported = run_cli([*options, str(capture)]), run_cli([*options, str(export)])
        assert exported[0] == direct[0] == 0
        assert exported[1].replace(str(export), str(capture)) == direct[1]
