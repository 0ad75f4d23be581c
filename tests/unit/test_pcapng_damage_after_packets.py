"""A pcapng damaged after its first packets (a block of an invalid length, a packet naming an interface not
described, a packet longer than its block) shows the packets before the damage, then refuses the file in one line,
exit 2, as tshark shows them before its `appears to be damaged or corrupt` (exit 2); a -w copy keeps them. Before,
nothing was shown: the whole decode was refused. Damage before any packet is refused at once, as before; --parquet
refuses the capture too, after writing its rows before the damage (test_damage_in_rings_and_parquet.py). Engine and VW3_PURE_PYTHON=1, -n and profile auto."""
from __future__ import annotations

import struct
import subprocess
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_harness import ensure_tool

REQUEST, ANSWER = bytes.fromhex("010300000002C40B"), bytes.fromhex("010304000100022A32")
T = 1_767_225_600_000_000


def _block(kind: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack("<II", kind, 12 + len(body)) + body + struct.pack("<I", 12 + len(body))


def _packet(micros: int, data: bytes, interface: int = 0, captured: int | None = None) -> bytes:
    stamp = T + micros
    size = len(data) if captured is None else captured
    return _block(6, struct.pack("<IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, size, len(data)) + data)


HEAD = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1)) + _block(1, struct.pack("<HHI", 147, 0, 0))
GOOD = HEAD + _packet(0, REQUEST) + _packet(10_000, ANSWER)
DAMAGES = {  # (the damage after the two packets, at byte 132; the message)
    "length": (struct.pack("<II", 6, 33) + bytes(40), "block at byte 132 has an invalid length 33 (corrupt file?)"),
    "interface": (_packet(20_000, REQUEST, interface=5), "packet at byte 132 refers to interface 5, but 1 are described"),
    "captured": (_packet(20_000, REQUEST, captured=100), "packet block at byte 132: 100 bytes do not fit in the block"),
}
SHOWN = ["     1     0.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
         "     2     0.010000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok"]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("damage", sorted(DAMAGES))
@pytest.mark.parametrize("profiles", [["-n"], []], ids=["n", "auto"])
def test_the_packets_before_the_damage_are_shown(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                                  damage: str, profiles: list[str]) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "damaged.pcapng"
    tail, message = DAMAGES[damage]
    path.write_bytes(GOOD + tail)
    status, out, err = run_cli([*profiles, str(path)])
    assert (status, out.splitlines()[:2], err) == (2, SHOWN, f"vw3-decode: {path}: {message}\n")
    theirs = subprocess.run([ensure_tool("tshark", "tshark"), "-r", str(path), "-T", "fields", "-e", "frame.number"],
                            capture_output=True, text=True, timeout=120)
    assert (theirs.returncode, theirs.stdout) == (2, "1\n2\n") and "damaged or corrupt" in theirs.stderr
    copy = tmp_path / "copy.pcap"
    assert run_cli(["-n", "-w", str(copy), str(path)])[0] == 2
    assert run_cli(["-n", str(copy)]) == (0, "\n".join(SHOWN) + "\n", "")


def test_damage_before_any_packet_and_parquet_are_refused_as_before(tmp_path: Path) -> None:
    path = tmp_path / "damaged.pcapng"
    path.write_bytes(HEAD + DAMAGES["length"][0])
    assert run_cli([str(path)]) == (2, "", f"vw3-decode: {path}: block at byte 48 has an invalid length 33 "
                                           "(corrupt file?)\n")
    path.write_bytes(GOOD + DAMAGES["length"][0])
    status, out, err = run_cli(["--parquet", str(tmp_path / "tables"), str(path)])
    assert status == 2 and err.endswith("block at byte 132 has an invalid length 33 (corrupt file?)\n"), err
