"""A pcapng with packets from several interfaces (Wireshark capturing two serial lines at once) is one
input per interface, each its own bus: its own framer, pairing and device memory (sources/interfaces.py).
Before, both lines' bytes were one stream: bus A's answer paired with bus B's request, a frame split over
two records with bus B's record between them was noise, slave 12 of bus B recalled bus A's values.
"""
from __future__ import annotations

import json
import shutil
import struct
import subprocess
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

REQUEST = bytes.fromhex("0C0320D000030EEF")
ANSWER_A = bytes.fromhex("0C030680000003000217E4")  # 8400 non-existent, CHCF=IO, COP=Cd
ANSWER_B = bytes.fromhex("0C0306000100020003A5E4")  # 8400=1, CHCF=SEP, COP=ALL
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def _block(kind: int, body: bytes) -> bytes:
    total = 12 + len(body)
    return struct.pack("<II", kind, total) + body + struct.pack("<I", total)


def _option(code: int, text: str) -> bytes:
    value = text.encode()
    return struct.pack("<HH", code, len(value)) + value + b"\0" * (-len(value) % 4)


def _pcapng(names: list[str | None], packets: list[tuple[int, int, bytes]]) -> bytes:
    """Interfaces (if_name, or none) and packets (interface, microseconds, bytes)."""
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    for name in names:
        options = _option(2, name) + _option(3, f"serial port {name}, 19200 baud") + b"\0" * 4 if name else b""
        out += _block(1, struct.pack("<HHI", 147, 0, 0) + options)
    for interface, micros, data in packets:
        stamp = 1_767_225_600_000_000 + micros
        out += _block(6, struct.pack("<IIIII", interface, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data))
                      + data + b"\0" * (-len(data) % 4))
    return out


# Bus A's answer split over two records, bus B's answer between them (two_bus_split.pcapng).
SPLIT = [(0, 0, REQUEST), (1, 1000, REQUEST), (0, 10_000, ANSWER_A[:5]), (1, 11_000, ANSWER_B),
         (0, 12_000, ANSWER_A[5:])]
READ = "12 request   Read Holding Registers 8400..8402 (3)  CRC ok"


def _decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool, stdin: bytes = b"") -> tuple[int, str, str]:
    use_engine(monkeypatch, pure)
    return run_cli(argv, stdin)


@BOTH
def test_each_interface_is_its_own_bus(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = tmp_path / "two_bus_split.pcapng"
    path.write_bytes(_pcapng([None, None], SPLIT))
    status, out, err = _decode([str(path)], monkeypatch, pure)
    assert (status, err) == (0, "")
    assert out.splitlines() == [
        f"==> {path}: interface 0 <==",
        f"     1     0.000000  {READ}",
        "     2     0.010000  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 "
        "[#1, 10.0 ms]  CRC ok",
        f"==> {path}: interface 1 <==",  # (from the file's first packet, interface 0's, as tshark's)
        f"     1     0.001000  {READ}",
        "     2     0.011000  12 response  Read Holding Registers 8400..8402 (3): 8400=1 8401=2 8402=3 "
        "[#1, 10.0 ms]  CRC ok",
    ]
    items = [json.loads(line) for line in _decode([str(path), "--json"], monkeypatch, pure)[1].splitlines()]
    assert [(item["file"], item["frame"], item.get("request_frame")) for item in items] == [
        (f"{path}: interface 0", 1, None), (f"{path}: interface 0", 2, 1),
        (f"{path}: interface 1", 1, None), (f"{path}: interface 1", 2, 1)]


@BOTH
def test_interfaces_are_named_and_have_their_own_devices(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    # Slave 12 of /dev/pts/1 answers 8400=1: readable, and no "readable again" recalled from /dev/pts/0's
    # slave 12, for which 8400 does not exist.
    path = tmp_path / "ext_two.pcapng"
    packets = []
    for cycle in range(2):
        base = cycle * 200_000
        packets += [(0, base, REQUEST), (1, base + 2000, REQUEST), (0, base + 8000, ANSWER_A),
                    (1, base + 11_000, ANSWER_B)]
    path.write_bytes(_pcapng(["/dev/pts/0", "/dev/pts/1"], packets))
    status, out, err = _decode([str(path), "--profile", "atv71"], monkeypatch, pure)
    assert (status, err) == (0, "")
    a = ("12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) "
         "COP=Cd (command)")
    b = ("12 response  Read Holding Registers 8400..8402 (3): 8400=1 CHCF=SEP (separate) "
         "COP=ALL (command and reference)")
    assert out.splitlines() == [
        f"==> {path}: /dev/pts/0 <==",
        f"     1     0.000000  {READ}",
        f"     2     0.008000  {a} [#1, 8.0 ms]  CRC ok",
        f"     3     0.200000  {READ}",
        f"     4     0.208000  {a} [#3, 8.0 ms]  CRC ok",
        f"==> {path}: /dev/pts/1 <==",
        f"     1     0.002000  {READ}",
        f"     2     0.011000  {b} [#1, 9.0 ms]  CRC ok",
        f"     3     0.202000  {READ}",
        f"     4     0.211000  {b} [#3, 9.0 ms]  CRC ok",
    ]


@BOTH
def test_w_keeps_each_interface(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path, written = tmp_path / "two.pcapng", tmp_path / "w.pcapng"
    path.write_bytes(_pcapng(["/dev/pts/0", "/dev/pts/1"], SPLIT))
    status, _, err = _decode([str(path), "-w", str(written)], monkeypatch, pure)
    assert (status, err) == (0, "")
    again = _decode([str(written)], monkeypatch, pure)[1].splitlines()
    assert [line for line in again if line.startswith("==>")] == [
        f"==> {written}: /dev/pts/0 <==", f"==> {written}: /dev/pts/1 <=="]
    tshark = shutil.which("tshark")
    if tshark:  # the oracle: each record on its interface, named as in the input
        fields = subprocess.run([tshark, "-r", str(written), "-T", "fields", "-e", "frame.interface_name",
                                 "-e", "frame.len"], capture_output=True, text=True, check=True).stdout
        # /dev/pts/0's answer in the two records it came in, 2 ms apart (sources/trail.py: before, one record
        # at the first's time). Then the closing record at the input's end, /dev/pts/0's last record 12 ms in
        # (its answer's second half), later than the copy's last (app/inputs.py CopyEnd).
        assert fields.splitlines() == ["/dev/pts/0\t8", "/dev/pts/0\t5", "/dev/pts/0\t6", "/dev/pts/1\t8",
                                       "/dev/pts/1\t11", "/dev/pts/1\t0"]


@BOTH
def test_one_interface_with_packets_is_one_input(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    path = tmp_path / "one.pcapng"
    path.write_bytes(_pcapng(["/dev/pts/0", "/dev/pts/1"], [(1, 0, REQUEST), (1, 9000, ANSWER_B)]))
    status, out, err = _decode([str(path)], monkeypatch, pure)
    assert (status, err) == (0, "")
    assert out.splitlines()[0] == f"     1     0.000000  {READ}"


@BOTH
def test_standard_input_stays_one_stream_and_says_so(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    status, out, err = _decode(["-"], monkeypatch, pure, stdin=_pcapng([None, None], SPLIT))
    assert status == 0
    assert err == ("vw3-decode: warning: packets come from several interfaces; their bytes are decoded as one "
                   "stream (vw3-decode FILE decodes each interface as its own bus: save standard input to a file)\n")


def test_parquet_makes_one_capture_per_interface(tmp_path: Path) -> None:
    pq = pytest.importorskip("pyarrow.parquet")
    path = tmp_path / "two.pcapng"
    path.write_bytes(_pcapng(["/dev/pts/0", "/dev/pts/1"], SPLIT))
    status, out, err = run_cli(["--parquet", str(tmp_path / "pq"), str(path)])
    assert (status, err) == (0, "")
    assert out.splitlines() == [f"{path}: /dev/pts/0: 2 frames, 3 registers, 0 events",
                                f"{path}: /dev/pts/1: 2 frames, 3 registers, 0 events"]
    tables = [pq.read_table(file) for file in sorted((tmp_path / "pq" / "frames").iterdir())]
    assert [(table.column("capture").to_pylist(), table.column("request_frame").to_pylist()) for table in tables] == [
        ([f"{path}#0"] * 2, [None, 1]), ([f"{path}#1"] * 2, [None, 1])]
