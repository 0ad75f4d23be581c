"""A refused write is not an accepted one: `--parquet`'s registers table says per row whether a write was
confirmed, refused (and by which exception), unanswered, a broadcast or unknown (render/registers.py
write_outcome), read back by DuckDB; the compiled engine and the Python stages write the same rows, and
they agree with what `--stats` counts.

The capture is a real master on a pseudo-terminal: mbpoll 1.0 writing to a pymodbus 3.16.1 RTU slave
(holding registers 0..99 writable, 100..109 read-only, nothing beyond), through a tap relaying both ptys
into a pcap, 2026-12-06 (frames and times below as the tap recorded them). Then, made up: a broadcast
write, an FC16 whose answer fails its CRC, and an FC6 the capture ends after."""
from __future__ import annotations

import json
import struct
from pathlib import Path

import duckdb
import pytest

from helpers import rtu, run_cli, use_engine

T0 = 1_765_000_000 * 1_000_000_000
SESSION = [  # (bytes as hex, ns after the first)
    ("01060005002a1814", 0), ("01060005002a1814", 3_980_000),  # 40006 = 42: echoed
    ("0106006400050816", 35_982_000), ("018602c3a1", 36_466_000),  # 40101 = 5: read-only, exception 02
    ("011000c7000204000500062e1a", 68_061_000), ("019002cdc1", 68_525_000),  # 40200..40201: none, 02
    ("0110000a0003060001000200031aa1", 93_163_000), ("0110000a0003a00a", 93_656_000),  # 40011..40013
    ("0506000a0009684a", 114_976_000), ("0586040262", 116_464_000),  # slave 5: pymodbus answers 04
    ("01050000ff008c3a", 3_030_212_000), ("01050000ff008c3a", 3_030_817_000),  # coil 1 ON: echoed
    ("01030064000285d4", 3_064_006_000), ("010304000700070a30", 3_067_947_000),  # read 40101..40102
    # The slave stopped: 40021 = 77 unanswered (mbpoll's timeout 0.3 s), then 40021 = 78, 332 ms later:
    # an FC6 request reads as the echo of the one before (within --timeout, 1 s by default).
    ("01060014004d09fb", 13_803_974_000), ("01060014004e49fa", 14_135_966_000),
]
MADE_UP = [
    (rtu("00 06 0020 0001").hex(), 20_000_000_000),  # a broadcast: no answer comes
    (rtu("01 10 0030 0001 02 0005").hex(), 21_000_000_000),
    ((rtu("01 10 0030 0001")[:-1] + b"\x00").hex(), 21_010_000_000),  # its answer, CRC damaged
    (rtu("01 06 0040 0009").hex(), 22_000_000_000),  # the capture ends before any answer
]
WRITES = [  # (frame, access, address, value, write, exception_code) of every write's row
    (1, "write", 5, 42, "confirmed", None), (2, "echo", 5, 42, "confirmed", None),
    (3, "write", 100, 5, "refused", 2),
    (5, "write", 199, 5, "refused", 2), (5, "write", 200, 6, "refused", 2),
    (7, "write", 10, 1, "confirmed", None), (7, "write", 11, 2, "confirmed", None),
    (7, "write", 12, 3, "confirmed", None),
    (9, "write", 10, 9, "refused", 4),
    (11, "write", 0, 1, "confirmed", None), (12, "echo", 0, 1, "confirmed", None),
    (15, "write", 20, 77, "differs", None), (16, "echo", 20, 78, "confirmed", None),
    (17, "write", 32, 1, "broadcast", None),
    (18, "write", 48, 5, "unknown", None),
    (20, "write", 64, 9, "unknown", None),
]


# The tap's pty relays mbpoll's frames faster than the 19200 baud assumed: --parquet says so, as the decode does.
OVERLAP = ("vw3-decode: warning: 19200 baud (assumed: --baud sets it): 7 frames would overlap the one before at "
           "19200 baud: the line is faster?\n")


def write_capture(path: Path) -> Path:
    with path.open("wb") as out:
        out.write(struct.pack("<IHHiIII", 0xA1B23C4D, 2, 4, 0, 0, 65535, 147))  # ns pcap, USER0
        for data, ns in SESSION + MADE_UP:
            seconds, fraction = divmod(T0 + ns, 1_000_000_000)
            out.write(struct.pack("<IIII", seconds, fraction, len(data) // 2, len(data) // 2) + bytes.fromhex(data))
    return path


def parquet_rows(capture: Path, out: Path, *options: str) -> list[tuple]:
    status, _out, err = run_cli(["--parquet", str(out), *options, str(capture)])
    assert (status, err) == (0, OVERLAP)
    return duckdb.connect().execute(
        "SELECT frame, access, address, value, write, exception_code "
        f"FROM read_parquet('{out}/registers/*.parquet') ORDER BY frame, address").fetchall()


@pytest.mark.parametrize("pure", [False, True])
def test_parquet_says_which_writes_the_slave_refused(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                     pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = write_capture(tmp_path / "mbpoll.pcap")
    rows = parquet_rows(capture, tmp_path / "data")
    assert [row for row in rows if row[1] != "read"] == WRITES
    assert [row for row in rows if row[1] == "read"] == [(14, "read", 100, 7, None, None),
                                                        (14, "read", 101, 7, None, None)]
    # Told the master gives up after 0.2 s, 40021 = 77 went unanswered and 78 is an answer without request.
    rows = parquet_rows(capture, tmp_path / "timeout", "--timeout", "0.2")
    assert [row for row in rows if row[0] in (15, 16)] == [(15, "write", 20, 77, "unanswered", None),
                                                          (16, "echo", 20, 78, "confirmed", None)]
    types = duckdb.connect().execute(
        f"DESCRIBE SELECT write, exception_code FROM read_parquet('{tmp_path}/data/registers/*.parquet')").fetchall()
    assert [column[:2] for column in types] == [("write", "VARCHAR"), ("exception_code", "SMALLINT")]


def test_refused_rows_are_what_stats_counts_refused(tmp_path: Path) -> None:
    capture = write_capture(tmp_path / "mbpoll.pcap")
    status, _out, err = run_cli(["--parquet", str(tmp_path / "data"), str(capture)])
    assert (status, err) == (0, OVERLAP)
    # (--stats counts registers' writes: FC6, 16, 23)
    rows = duckdb.connect().execute(
        "SELECT slave, address, count(*), count(*) FILTER (write = 'refused') "
        f"FROM read_parquet('{tmp_path}/data/registers/*.parquet') "
        "WHERE access = 'write' AND function IN (6, 16, 23) GROUP BY ALL ORDER BY ALL").fetchall()
    status, out, _err = run_cli(["--stats", "--json", str(capture)])
    assert status == 0
    counted = [(p["slave"], p["address"], p["writes"], p["refused"]) for p in json.loads(out)["parameters"]
               if p["writes"]]
    assert rows == counted
    assert sum(row[3] for row in rows) == 4  # 40101, 40200, 40201 of slave 1; 40011 of slave 5
