"""What -w keeps of a decoded capture, checked with Wireshark's own tools on the written files.

- the pcapng interface (name, description: the line speed a decode reads back), as tshark -w and editcap
  keep it; `--baud N` describes the speed decoded at; pcap cannot keep it and says so once;
- `-b duration:S` on the records' time, split as `editcap -i S` splits (the oracle), each file named for
  its first record's time; `-b filesize:` leaves no header-only file to count against `files:N`;
- `-c N` counts items (frames and noise runs): N lines, N NDJSON objects, N records, as tshark -c N.
Under the compiled engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import re
import struct
import subprocess
import time
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine, write_9600_tap

ROOT = Path(__file__).resolve().parents[2]
COMMISSIONING = str(ROOT / "captures" / "atv71_commissioning.pcap")
NOISY = str(ROOT / "captures" / "noisy_bus.pcap")
ENGINES = [False, True]  # pure
T0 = 1767225600  # 2026-01-01 00:00:00 UTC
LINE_9600 = "line: 9600 baud (pcapng interface description), 11 bits a character, t3.5 4.010 ms, timeout 1000 ms"


@pytest.fixture(autouse=True)
def utc(monkeypatch: pytest.MonkeyPatch) -> None:
    """Ring file names are local time (as dumpcap's): this process's and editcap's are UTC."""
    monkeypatch.setenv("TZ", "UTC")
    time.tzset()


def interfaces(path: Path) -> list[tuple[str, str]]:
    """capinfos' Name and Description of each interface ('' when absent)."""
    text = subprocess.run(["capinfos", str(path)], capture_output=True, text=True, check=True).stdout
    found = []
    for block in text.split("Interface #")[1:]:
        name = re.search(r"^\s+Name = (.*)$", block, re.M)
        description = re.search(r"^\s+Description = (.*)$", block, re.M)
        found.append((name.group(1) if name else "", description.group(1) if description else ""))
    return found


def packets(path: Path) -> int:
    text = subprocess.run(["capinfos", "-c", "-M", str(path)], capture_output=True, text=True, check=True).stdout
    return int(re.search(r"Number of packets:\s+(\d+)", text).group(1))  # type: ignore[union-attr]


def stats_line(path: Path) -> str:
    status, out, _err = run_cli(["--stats", str(path)])
    assert status == 0
    return next(line for line in out.splitlines() if line.startswith("line: "))


TAP_INTERFACE = ("/dev/ttyUSB0", "serial port /dev/ttyUSB0, 9600 baud, 8 data bits, even parity, 1 stop bit (9600 8E1)")


@pytest.mark.parametrize("pure", ENGINES)
@pytest.mark.parametrize("options", [[], ["-Y", "slave == 12"], ["-c", "3"], ["-b", "filesize:1"]])
def test_the_interface_and_its_line_speed_are_kept(pure: bool, options: list[str], tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: the rewritten file had no interface name or description and read at 19200 baud (assumed),
    t3.5 2.005 ms."""
    use_engine(monkeypatch, pure)
    tap = tmp_path / "tap.pcapng"
    write_9600_tap(tap)
    assert stats_line(tap) == LINE_9600
    status, _out, err = run_cli([str(tap), "-w", str(tmp_path / "re.pcapng"), *options])
    assert (status, err) == (0, "")
    written = sorted(tmp_path.glob("re*.pcapng"))
    assert len(written) == 1
    assert interfaces(written[0]) == [TAP_INTERFACE]
    assert stats_line(written[0]) == LINE_9600


@pytest.mark.parametrize("pure", ENGINES)
def test_baud_typed_is_the_description(pure: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    tap = tmp_path / "tap.pcapng"
    write_9600_tap(tap)
    status, _out, err = run_cli([str(tap), "--baud", "4800", "-w", str(tmp_path / "re.pcapng")])
    assert (status, err) == (0, "")
    assert interfaces(tmp_path / "re.pcapng") == [("/dev/ttyUSB0", "4800 baud (--baud)")]
    assert stats_line(tmp_path / "re.pcapng") == (
        "line: 4800 baud (pcapng interface description), 11 bits a character, t3.5 8.021 ms, timeout 1000 ms")
    # A pcap input has no interface: --baud gives it one.
    status, _out, err = run_cli([COMMISSIONING, "--baud", "9600", "-w", str(tmp_path / "c.pcapng")])
    assert (status, err) == (0, "")
    assert interfaces(tmp_path / "c.pcapng") == [("", "9600 baud (--baud)")]


@pytest.mark.parametrize("pure", ENGINES)
def test_pcap_says_the_line_speed_is_lost(pure: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    tap = tmp_path / "tap.pcapng"
    write_9600_tap(tap)
    out_path = tmp_path / "re.pcap"
    status, _out, err = run_cli([str(tap), "-w", str(out_path)])
    assert status == 0
    assert err == (
        f"vw3-decode: warning: -w {out_path}: pcap has no interface description: the line speed 9600 baud of "
        f"{tap} is not kept (write pcapng, -F pcapng, to keep it; or read it back with --baud 9600)\n")
    assert packets(out_path) == 9  # (each request in the two records it came in: sources/trail.py)
    # Typed, the speed is the user's to type again; no description, nothing lost.
    assert run_cli([str(tap), "--baud", "9600", "-w", str(out_path)])[2] == ""
    assert run_cli([COMMISSIONING, "-w", str(out_path)])[2] == ""


@pytest.mark.parametrize("pure", ENGINES)
def test_each_capture_keeps_its_interface(pure: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Two captures decoded into one pcapng: the tap's 9 records on its interface (each request in the two
    records it came in, 1.2 and 2 ms apart), the pcap's 104 on one without a description (as mergecap
    writes them)."""
    use_engine(monkeypatch, pure)
    tap = tmp_path / "tap.pcapng"
    write_9600_tap(tap)
    out_path = tmp_path / "both.pcapng"
    status, _out, err = run_cli([str(tap), COMMISSIONING, "-w", str(out_path)])
    assert (status, err) == (0, "")
    assert interfaces(out_path) == [TAP_INTERFACE, ("", "")]
    ids = subprocess.run(["tshark", "-r", str(out_path), "-T", "fields", "-e", "frame.interface_id"],
                         capture_output=True, text=True, check=True).stdout.split()
    assert ids == ["0"] * 9 + ["1"] * 104


def write_pcap(path: Path, times: list[tuple[int, int]]) -> None:
    """A pcap (linktype 147) of one read request per (seconds after T0, microseconds)."""
    frame = rtu("01 03 0000 0001")
    with open(path, "wb") as stream:
        stream.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147))
        for seconds, micros in times:
            stream.write(struct.pack("<IIII", T0 + seconds, micros, len(frame), len(frame)) + frame)


def ring_files(folder: Path, stem: str) -> list[tuple[str, int]]:
    return [(path.name, packets(path)) for path in sorted(folder.glob(f"{stem}_*"))]


def editcap_split(source: str, folder: Path, seconds: str) -> list[tuple[str, int]]:
    """editcap -i's files with records, numbered from 00001 as dumpcap numbers a ring (editcap: 00000,
    and a file for each window without records)."""
    folder.mkdir()
    subprocess.run(["editcap", "-i", seconds, source, str(folder / "x.pcap")], check=True, capture_output=True)
    kept = [(name, count) for name, count in ring_files(folder, "x") if count]
    return [(f"x_{number:05d}_{name.split('_')[2]}", count) for number, (name, count) in enumerate(kept, 1)]


@pytest.mark.parametrize("pure", ENGINES)
def test_duration_splits_on_the_records_time_as_editcap(pure: bool, tmp_path: Path,
                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: one file x_00001_<today>.pcap of all 104 records (2.29 s), the wall clock never reaching 1 s."""
    use_engine(monkeypatch, pure)
    gaps = tmp_path / "gaps.pcap"
    # 1.100000 is exactly the first window's end (stays in it); 5.5 s after 3 empty windows.
    write_pcap(gaps, [(0, 100000), (1, 100000), (1, 100001), (5, 500000), (7, 0)])
    for source, seconds, expected in [
        (COMMISSIONING, "1", [("x_00001_20260101000000.pcap", 50), ("x_00002_20260101000001.pcap", 42),
                              ("x_00003_20260101000002.pcap", 12)]),
        (str(gaps), "1", [("x_00001_20260101000000.pcap", 2), ("x_00002_20260101000001.pcap", 1),
                          ("x_00003_20260101000005.pcap", 1), ("x_00004_20260101000007.pcap", 1)]),
        (COMMISSIONING, "0.5", None),
    ]:
        out = tmp_path / f"out{len(list(tmp_path.iterdir()))}"
        out.mkdir()
        status, _out, err = run_cli([source, "-w", str(out / "x.pcap"), "-b", f"duration:{seconds}"])
        assert (status, err) == (0, "")
        oracle = editcap_split(source, tmp_path / f"editcap{out.name}", seconds)
        assert ring_files(out, "x") == oracle
        if expected is not None:
            assert oracle == expected


@pytest.mark.parametrize("pure", ENGINES)
def test_filesize_leaves_no_header_only_file(pure: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: s_00002..s_00004 (35, 34, 0 records): the header-only last file pushed out s_00001's 35."""
    use_engine(monkeypatch, pure)
    status, _out, err = run_cli([COMMISSIONING, "-w", str(tmp_path / "s.pcap"), "-b", "filesize:1", "-b", "files:3"])
    assert (status, err) == (0, "")
    assert ring_files(tmp_path, "s") == [
        ("s_00001_20260101000000.pcap", 35), ("s_00002_20260101000000.pcap", 35), ("s_00003_20260101000001.pcap", 34)]


NOISY_FIVE = [
    "     1     0.000000   - noise     4 bytes of noise at offset 0: 00 ff ff f0",
    "     2     0.008497  12 request   Read Holding Registers 3201..3202 (2)  CRC ok",
    "     3     0.016960  12 response  Read Holding Registers 3201..3202 (2): 3201=592 3202=0 [#2, 8.5 ms]  CRC ok",
    "     4     0.033086   1 request   Read Holding Registers 0..3 (4)  CRC ok",
    "     5     0.045527   1 response  Read Holding Registers 0..3 (4): 0=403 1=440 2=478 3=511 [#4, 12.4 ms]  CRC ok",
]


@pytest.mark.parametrize("pure", ENGINES)
def test_count_counts_noise_runs_as_packets(pure: bool, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Before: 6 lines (the noise run and 5 frames), 6 NDJSON objects, 6 records."""
    use_engine(monkeypatch, pure)
    status, out, _err = run_cli(["-c", "5", NOISY])
    assert (status, out.splitlines()) == (0, NOISY_FIVE)
    status, out, _err = run_cli(["-c", "5", "--json", NOISY])
    assert [line.split('"frame": ')[1].split(",")[0] for line in out.splitlines()] == ["1", "2", "3", "4", "5"]
    status, out, _err = run_cli(["-c", "5", "--stats", NOISY])
    assert out.splitlines()[0] == "4 frames, 4 noise bytes in 1 run"
    status, _out, err = run_cli(["-c", "5", NOISY, "-w", str(tmp_path / "c.pcap")])
    assert (status, err) == (0, "")
    assert packets(tmp_path / "c.pcap") == 5
    # After -Y: the first two items it keeps.
    status, out, _err = run_cli(["-c", "2", "-Y", "slave == 1", NOISY])
    assert [line.split()[0] for line in out.splitlines()] == ["4", "5"]
    # Stopped in the noise before the first frame: the capture is not judged "not a Modbus capture".
    assert run_cli(["-c", "1", NOISY]) == (0, NOISY_FIVE[0] + "\n", "")
