"""--parquet DIR says of a capture whose frames overlap at the line speed used what the decode says (bus
timing's overlap_warning: a wrong or assumed baud rate, so t3.5 and the outages are judged at the wrong
speed). Before (hunt67b), --parquet said nothing of it, where `vw3-decode capture.pcap` warns `19200 baud
(assumed: --baud sets it): 1 frame would overlap the one before at 19200 baud: the line is faster?`: a
request answered 1 ms after it began, 8 bytes taking 4.6 ms at 19200 baud (a pty's pymodbus does)."""
from __future__ import annotations

import struct
from pathlib import Path

from helpers import run_cli

REQUEST = bytes.fromhex("01 03 00 00 00 01 84 0A")
ANSWER = bytes.fromhex("01 03 02 00 07 F9 86")


def _pcap(path: Path) -> str:
    header = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)
    records = b"".join(struct.pack("<IIII", 1_767_225_600, micros, len(frame), len(frame)) + frame
                       for micros, frame in ((0, REQUEST), (1000, ANSWER)))
    path.write_bytes(header + records)
    return str(path)


def test_parquet_warns_as_the_decode(tmp_path: Path) -> None:
    path = _pcap(tmp_path / "fast.pcap")
    said = run_cli(["-q", "--stats", path])[2]
    assert said == ("vw3-decode: warning: 19200 baud (assumed: --baud sets it): 1 frame would overlap the one before "
                    "at 19200 baud: the line is faster?\n")
    assert run_cli(["--parquet", str(tmp_path / "data"), path]) == (0, f"{path}: 2 frames, 1 register, 0 events\n",
                                                                     said)
    # named with several captures, as their record warnings are
    other = _pcap(tmp_path / "other.pcap")
    status, out, err = run_cli(["--parquet", str(tmp_path / "data"), path, other])
    assert sorted(err.splitlines()) == [f"vw3-decode: warning: {name}: {said[len('vw3-decode: warning: '):-1]}"
                                        for name in sorted([other, path])]
    # --baud 115200 fits them: nothing said
    assert run_cli(["--parquet", str(tmp_path / "data"), "--baud", "115200", path])[2] == ""
