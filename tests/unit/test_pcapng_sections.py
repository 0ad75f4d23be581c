"""A pcapng of several sections (`cat a.pcapng b.pcapng`: each file's section header and interface description
again): an interface a later section describes as an earlier section did is the same interface, one bus, as tshark
4.0 (frame.interface_id 0 in both) and the plugin read it (its answer paired with the request of the first
section). Before, the second section's interface was another bus: the answer `[no request]`, the request `[the
capture ends ...]`. Interfaces described differently (another if_name) stay two buses; two interfaces in each
section pair up by their descriptions. Both byte orders, the engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_harness import run_tshark

REQUEST, ANSWER = bytes.fromhex("010300000002C40B"), bytes.fromhex("010304000100022A32")
T = 1_767_225_600_000_000  # us


def _block(order: str, kind: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack(order + "II", kind, 12 + len(body)) + body + struct.pack(order + "I", 12 + len(body))


def _section(order: str, names: list[bytes], packets: list[tuple[int, int, bytes]]) -> bytes:
    out = _block(order, 0x0A0D0D0A, struct.pack(order + "IHHq", 0x1A2B3C4D, 1, 0, -1))
    for name in names:
        option = struct.pack(order + "HH", 2, len(name)) + name + b"\0" * (-len(name) % 4) if name else b""
        out += _block(order, 1, struct.pack(order + "HHI", 147, 0, 0) + option + (b"\0" * 4 if name else b""))
    for interface, micros, data in packets:
        stamp = T + micros
        out += _block(order, 6, struct.pack(order + "IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, len(data),
                                            len(data)) + data)
    return out


PAIRED = ("     1     0.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok\n"
          "     2     0.010000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok\n")


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("second", ["<", ">"], ids=["same-order", "big-endian-second"])
def test_cat_sections_are_one_bus(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool, second: str) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "cat.pcapng"
    path.write_bytes(_section("<", [b""], [(0, 0, REQUEST)]) + _section(second, [b""], [(0, 10_000, ANSWER)]))
    assert run_cli(["-n", str(path)]) == (0, PAIRED, "")
    plugin = run_tshark(path, "-T", "fields", "-e", "frame.interface_id", "-e", "vw3.response_frame")
    assert plugin.stdout.splitlines() == ["0\t2", "0\t"]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_sections_pair_their_interfaces_by_description(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                       pure: bool) -> None:
    use_engine(monkeypatch, pure)
    path = tmp_path / "two.pcapng"
    path.write_bytes(_section("<", [b"ttyA", b"ttyB"], [(0, 0, REQUEST), (1, 20_000, REQUEST)])
                     + _section("<", [b"ttyA", b"ttyB"], [(0, 10_000, ANSWER), (1, 30_000, ANSWER)]))
    out = run_cli(["-n", "-t", "ud", str(path)])[1].splitlines()
    assert out == [
        f"==> {path}: ttyA <==",
        "     1 2026-01-01 00:00:00.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
        "     2 2026-01-01 00:00:00.010000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok",
        f"==> {path}: ttyB <==",
        "     1 2026-01-01 00:00:00.020000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
        "     2 2026-01-01 00:00:00.030000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok"]
    other = tmp_path / "other.pcapng"
    other.write_bytes(_section("<", [b"ttyA"], [(0, 0, REQUEST)]) + _section("<", [b"ttyB"], [(0, 10_000, ANSWER)]))
    out = run_cli(["-n", str(other)])[1]
    assert f"==> {other}: ttyB <==" in out and "[no request]" in out
