"""Damage inside a pcapng read as a ring buffer's files (app/rings.py) or with --parquet (app/jobs.py) ends the
capture there, as a plain decode of one damaged file does (test_pcapng_damage_after_packets.py): the packets
before it are shown (written by -w, in the Parquet tables), then the run is refused in one line, exit 2. The files
after the damaged one are not read. Before, the ring and --parquet were refused with nothing shown or written.
Damage before the capture's first packet is refused at once, as before. Engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from test_pcapng_damage_after_packets import ANSWER, DAMAGES, HEAD, REQUEST, _packet

BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
READ = "   1 request   Read Holding Registers 0..1 (2)  CRC ok"
ANSWERED = "   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#{}, 10.0 ms]  CRC ok"
SHOWN = [f"     1     0.000000{READ}", f"     2     0.010000{ANSWERED.format(1)}",
         f"     3     1.000000{READ}", f"     4     1.010000{ANSWERED.format(3)}"]
DAMAGE, MESSAGE = DAMAGES["length"]


def _ring(folder: Path, second: bytes) -> list[str]:
    """A ring of three files, a poll each second; `second`: the second file's bytes after its header."""
    folder.mkdir()
    files = []
    for number, body in enumerate([_packet(0, REQUEST) + _packet(10_000, ANSWER), second,
                                   _packet(2_000_000, REQUEST) + _packet(2_010_000, ANSWER)], 1):
        path = folder / f"bus_{number:05d}_2026010100000{number}.pcapng"
        path.write_bytes(HEAD + body)
        files.append(str(path))
    return files


@BOTH
def test_a_ring_shows_the_packets_before_the_damage(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                    pure: bool) -> None:
    use_engine(monkeypatch, pure)
    files = _ring(tmp_path / "ring", _packet(1_000_000, REQUEST) + _packet(1_010_000, ANSWER) + DAMAGE)
    status, out, err = run_cli(files)
    assert (status, out.splitlines(), err) == (2, SHOWN, f"vw3-decode: {files[1]}: {MESSAGE}\n")
    assert run_cli(["-n", *files])[:2] == (2, "\n".join(SHOWN) + "\n")  # (profile auto read it twice above)
    copy = tmp_path / "copy.pcap"
    assert run_cli(["-n", "-q", "-w", str(copy), *files]) == (2, "", f"vw3-decode: {files[1]}: {MESSAGE}\n")
    assert run_cli(["-n", str(copy)]) == (0, "\n".join(SHOWN) + "\n", "")


@BOTH
def test_a_ring_file_damaged_before_its_first_packet(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     pure: bool) -> None:
    use_engine(monkeypatch, pure)
    files = _ring(tmp_path / "ring", DAMAGE)
    status, out, err = run_cli(files)
    assert (status, out.splitlines(), err) == (2, SHOWN[:2], f"vw3-decode: {files[1]}: block at byte 48 has an "
                                                             "invalid length 33 (corrupt file?)\n")
    # (the ring's first file damaged before any packet: refused at once, nothing shown)
    files = _ring(tmp_path / "first", b"")
    Path(files[0]).write_bytes(HEAD + DAMAGE)
    assert run_cli(files) == (2, "", f"vw3-decode: {files[0]}: block at byte 48 has an invalid length 33 "
                                     "(corrupt file?)\n")


def _frames(folder: Path) -> list[tuple[str, int]]:
    pq = pytest.importorskip("pyarrow.parquet")
    table = pq.read_table(str(folder / "frames"))
    return sorted(zip(table.column("file").to_pylist(), table.column("frame").to_pylist()))


@pytest.mark.parametrize("jobs", ["1", "2"])
def test_parquet_writes_the_rows_before_the_damage(tmp_path: Path, jobs: str) -> None:
    pytest.importorskip("pyarrow")
    damaged = tmp_path / "damaged.pcapng"
    damaged.write_bytes(HEAD + _packet(0, REQUEST) + _packet(10_000, ANSWER) + DAMAGE)
    tables = tmp_path / "tables"
    status, out, err = run_cli(["--parquet", str(tables), "--jobs", jobs, str(damaged)])
    assert (status, out, err) == (2, f"{damaged}: 2 frames, 2 registers, 0 events\n",
                                  f"vw3-decode: {damaged}: {MESSAGE}\n")
    assert _frames(tables) == [("damaged.pcapng", 1), ("damaged.pcapng", 2)]
    files = _ring(tmp_path / "ring", _packet(1_000_000, REQUEST) + _packet(1_010_000, ANSWER) + DAMAGE)
    ring = tmp_path / "ring_tables"
    status, out, err = run_cli(["--parquet", str(ring), "--jobs", jobs, *files])
    assert (status, out, err) == (2, f"{tmp_path / 'ring' / 'bus.pcapng'}: 4 frames, 4 registers, 0 events\n",
                                  f"vw3-decode: {files[1]}: {MESSAGE}\n")
    first, second = (Path(name).name for name in files[:2])
    assert _frames(ring) == [(first, 1), (first, 2), (second, 3), (second, 4)]
