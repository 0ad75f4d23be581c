"""Ring buffer files that are not one run (hunt 58). dumpcap started again with the same `-w bus.pcap -b ...`
in the same folder numbers its files from 00001 again: `vw3-decode bus_*.pcap` read the two runs by number
alone, interleaved (run 1's 00001, run 2's 00001, run 1's 00002...): requests '[no response]', answers
'[no request]'. Each run is a capture of its own now, titled by its first file. A file missing inside a
run (00001, 00003) joined silently, and the request before the gap paired with an answer 534 ms later in
file 00003: a warning says the stream jumps there."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from helpers import run_cli

ROOT = Path(__file__).resolve().parents[2]
WHOLE = ROOT / "captures" / "atv71_commissioning.pcap"
OTHER = ROOT / "captures" / "p38_protection.pcap"


def _ring(capture: Path, folder: Path, split: str) -> list[Path]:
    folder.mkdir()
    status, _out, err = run_cli([str(capture), "-w", str(folder / "bus.pcap"), "-b", split])
    assert (status, err) == (0, "")
    return sorted(folder.iterdir())


def test_two_runs_of_one_name_are_two_captures(tmp_path: Path) -> None:
    first, second = _ring(WHOLE, tmp_path / "a", "filesize:1"), _ring(OTHER, tmp_path / "b", "duration:1")
    together = tmp_path / "together"
    together.mkdir()
    names = []
    for day, files in (("20260101", first), ("20260102", second)):  # the second run a day later
        for path in files:
            name = path.name.replace("_20260101", "_" + day)
            shutil.copy(path, together / name)
            names.append(str(together / name))
    assert [Path(name).name for name in names[:4]] == [
        "bus_00001_20260101000000.pcap", "bus_00002_20260101000000.pcap", "bus_00003_20260101000001.pcap",
        "bus_00001_20260102000000.pcap"]
    status, out, err = run_cli(sorted(names))  # as the shell's bus_*.pcap gives them: by name
    assert (status, err) == (0, "")
    alone = [run_cli(names[:3])[1], run_cli(names[3:])[1]]
    assert out == (f"==> {names[0]} <==\n{alone[0]}==> {names[3]} <==\n{alone[1]}")
    assert "[no request]" not in out


def test_a_missing_file_is_said(tmp_path: Path) -> None:
    files = _ring(OTHER, tmp_path / "a", "duration:0.5")
    assert len(files) >= 3
    status, out, err = run_cli([str(files[0]), str(files[2])])
    assert status == 0
    assert err == (f"vw3-decode: warning: {files[0]}: the ring buffer's file 00002 is missing before {files[2].name}:"
                   " what it held is not decoded, and a request at the end of this file may show no response or"
                   " pair with a later answer\n")
    assert run_cli([str(path) for path in files])[2] == ""


def test_a_missing_file_is_said_by_parquet(tmp_path: Path) -> None:
    pytest.importorskip("pyarrow")
    files = _ring(OTHER, tmp_path / "a", "duration:0.5")
    status, out, err = run_cli(["--parquet", str(tmp_path / "data"), str(files[0]), str(files[2])])
    assert (status, out) == (0, f"{tmp_path / 'a' / 'bus.pcap'}: 4 frames, 6 registers, 2 events\n")
    assert err == (f"vw3-decode: warning: {files[0]}: the ring buffer's file 00002 is missing before {files[2].name}:"
                   " what it held is not decoded, and a request at the end of this file may show no response or"
                   " pair with a later answer\n")
