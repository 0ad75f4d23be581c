"""An FC43/14 object longer than its device allows (max_length in a profile's [objects] tables): the ATV71 card's
[DEVICE NAME], UserApplicationName, holds 16 bytes at most (seed 001, p.32: "Maximum size 16 bytes").
Same lines under the engine and VW3_PURE_PYTHON=1; the plugin's in tests/integration/test_lua_object_length.py."""
from __future__ import annotations

import pytest

from helpers import run_cli, use_engine

REQUEST = "01 2B 0E 02 06 F0 85"  # regular identification from object 6
NAME_17 = "01 2B 0E 02 02 00 00 01 06 11 " + b"ABCDEFGHIJKLMNOPQ".hex(" ") + " 9A 45"
NAME_16 = "01 2B 0E 02 02 00 00 01 06 10 " + b"ABCDEFGHIJKLMNOP".hex(" ") + " F3 4A"


@pytest.mark.parametrize("pure", [False, True])
def test_a_device_name_past_16_bytes_is_warned(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    args = [arg for frame in (REQUEST, NAME_17, REQUEST, NAME_16) for arg in ("--hex", frame)]
    status, out, err = run_cli([*args, "--profile", "atv71"])
    assert (status, err) == (0, "")
    assert out.splitlines()[1::2] == [
        "     2            -   1 response  Encapsulated Interface Transport Read Device Identification, regular: "
        "UserApplicationName='ABCDEFGHIJKLMNOPQ' [#1] "
        "[warning: UserApplicationName of 17 bytes is longer than the VW3 A3 303's 16]  CRC ok",
        "     4            -   1 response  Encapsulated Interface Transport Read Device Identification, regular: "
        "UserApplicationName='ABCDEFGHIJKLMNOP' [#3]  CRC ok",
    ]
