"""Read Device Identification (FC43/14) answers: one with no objects is warned that the basic objects are
mandatory (Application Protocol 6.21: VendorName, ProductCode, MajorMinorRevision; data/modbus.toml
[limits] device_id_mandatory), and one with More Follows FF says so in its Info text with the object id the
rest follows from (describe._mei). Before, 'basic: [#1]' with no warning, and nothing of more to
follow. vw3-decode (compiled engine, VW3_PURE_PYTHON=1) and the plugin's warning."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import decode_frames, rtu
from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

REQUEST = rtu("01 2B 0E 01 00")
FRAMES = [REQUEST, rtu("01 2B 0E 01 83 00 00 00"),  # no objects
          REQUEST, rtu("01 2B 0E 01 83 FF 03 03 00 03 41 42 43 01 02 50 31 02 04 56 31 2E 30")]  # more from 3
NONE = "no objects: VendorName, ProductCode, MajorMinorRevision are mandatory"
MORE = "VendorName='ABC' ProductCode='P1' MajorMinorRevision='V1.0' (more follows from object 3)"


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    out = decode_frames(FRAMES, tmp_path, monkeypatch, pure)
    name = "Encapsulated Interface Transport Read Device Identification, basic:"
    assert out.splitlines()[1::2] == [
        f"     2            -   1 response  {name} [#1] [warning: {NONE}]  CRC ok",
        f"     4            -   1 response  {name} {MORE} [#3]  CRC ok",
    ]


def test_the_plugin_warns_of_no_objects(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "fc43.pcap", [(frame, 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap)
    assert [item.texts.get("warning", []) for item in items] == [[], [NONE], [], []]

