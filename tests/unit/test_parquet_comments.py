"""`--parquet`'s frames table keeps a pcapng's packet comments (`comments`, a list, as --json's): a frame gets
the comments of every record it has bytes in; vw3-decode's own noise comments (a -w copy's) are no packet
comment, read back (sources/trail.py own_comment). Before, the dataset had no comments (no column)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import run_cli
from test_pcapng_comments import ANSWER, REQUEST, pcapng

pq = pytest.importorskip("pyarrow.parquet")


def test_frames_keep_the_packet_comments(tmp_path: Path) -> None:
    capture = tmp_path / "noted.pcapng"
    capture.write_bytes(pcapng([
        (0, REQUEST, ["poll of the drive"]),
        (20_000, ANSWER[:5], ["answer, first read"]), (21_000, ANSWER[5:], ["answer, second read", "ok"]),
        (500_000, bytes.fromhex("ff00ff"), ["noise: 3 bytes, no valid frame"]),
        (600_000, REQUEST, []),
    ]))
    status, out, err = run_cli(["--parquet", str(tmp_path / "data"), str(capture)])
    assert status == 0, err
    (table,) = (tmp_path / "data" / "frames").glob("*.parquet")
    rows = pq.read_table(table, columns=["frame", "kind", "comments"]).to_pylist()
    assert [(row["frame"], row["kind"], row["comments"]) for row in rows] == [
        (1, "request", ["poll of the drive"]),
        (2, "response", ["answer, first read", "answer, second read", "ok"]),
        (3, "noise", []),
        (4, "request", []),
    ]
    status, out, err = run_cli(["--json", str(capture)])
    assert [json.loads(line).get("comments", []) for line in out.splitlines()] == [row["comments"] for row in rows]
