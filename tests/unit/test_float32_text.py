"""A float32 map value is written with the fewest significant digits (up to 9) that read back as the same
float32, as %.7g writes them (maps.float32_text): two values that differ never print alike, so --watch
(which skips a line whose old and new text match) sees every change. Python stages and compiled engine."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine

from dissector.devices.maps import float32_text

MAP = "address,code,type\n100,TEMPF,float32\n"


def _float(bits: int) -> float:
    return struct.unpack(">f", bits.to_bytes(4, "big"))[0]


@pytest.mark.parametrize(("bits", "text"), [
    (0x3F800000, "1"), (0x3F800001, "1.0000001"),  # %.7g gave "1" for both
    (0x3DCCCCCD, "0.1"), (0x42480000, "50"),  # no 5e+01: %.7g's form where 7 digits hold the value
    (0x4B7FFFFF, "16777215"), (0x4CBEBC20, "1e+08"),
    (0x7F7FFFFF, "3.4028235e+38"),  # %.7g's 3.402823e+38 reads back as another float32
    (0x00000001, "1e-45"), (0x00800000, "1.1754944e-38"), (0x80000000, "-0"),
])
def test_texts(bits: int, text: str) -> None:
    assert float32_text(_float(bits)) == text
    assert struct.pack(">f", float(text)) == bits.to_bytes(4, "big")


@pytest.mark.parametrize("pure", [False, True])
def test_summary_and_watch(monkeypatch: pytest.MonkeyPatch, pure: bool, tmp_path: Path) -> None:
    use_engine(monkeypatch, pure)
    (tmp_path / "f.csv").write_text(MAP)
    capture = tmp_path / "f.bin"
    capture.write_bytes(rtu("01 03 0064 0002") + rtu("01 03 04 3F80 0000") + rtu("01 03 0064 0002")
                        + rtu("01 03 04 3F80 0001"))
    status, out, err = run_cli(["--map", str(tmp_path / "f.csv"), str(capture)])
    assert status == 0, err
    assert out.splitlines()[1].endswith("Read Holding Registers 100..101 (2): TEMPF=1 [#1]  CRC ok")
    assert out.splitlines()[3].endswith("Read Holding Registers 100..101 (2): TEMPF=1.0000001 [#3]  CRC ok")
    status, out, err = run_cli(["--map", str(tmp_path / "f.csv"), str(capture), "--watch", "TEMPF"])
    assert status == 0, err
    assert out.splitlines() == ["     4            -   1 TEMPF 1 -> 1.0000001"]
