"""--profile 0=NAME and --map 0=FILE: slave 0 is Modbus's broadcast address (no device has it, none answers
at it): refused with one line and exit 2, as a slave past 247 is, before the capture is read. Before, slave
0 was taken (a profile naming every broadcast write as one device's) and --profile 248 said `outside 0..247`."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli


@pytest.mark.parametrize(("option", "spec", "message"), [
    ("--profile", "0=atv71", "--profile '0=atv71': slave 0 is the broadcast address, which no device has (a slave is 1..247)"),
    ("--profile", "00 = atv71", "--profile '00 = atv71': slave 0 is the broadcast address, which no device has (a slave is 1..247)"),
    ("--map", "0=missing.csv", "--map '0=missing.csv': slave 0 is the broadcast address, which no device has (a slave is 1..247)"),
    ("--profile", "248=atv71", "--profile '248=atv71': slave 248 is outside 1..247"),
    ("--map", "300=missing.csv", "--map '300=missing.csv': slave 300 is outside 1..247"),
])
def test_slave_without_a_device_is_refused(tmp_path: Path, option: str, spec: str, message: str) -> None:
    capture = tmp_path / "c.bin"
    capture.write_bytes(rtu("0C03 20D1 0001") + rtu("0C03 02 0003"))
    code, out, err = run_cli([option, spec, str(capture)])
    assert (code, out, err) == (2, "", f"vw3-decode: {message}\n")


def test_a_map_file_named_with_0_is_a_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "0=plant.csv").write_text("address,code,name\n8401,MYCODE,My parameter\n")
    capture = tmp_path / "c.bin"
    capture.write_bytes(rtu("0C03 20D1 0001") + rtu("0C03 02 0003"))
    code, out, err = run_cli(["--profile", "atv71", "--map", "0=plant.csv", str(capture)])
    assert code == 0, err
    assert "MYCODE=3" in out
