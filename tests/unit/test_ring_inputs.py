"""The files of one `-w bus.pcap -b ...` ring buffer are one capture for every output (app/rings.py), as
tshark reads their mergecap and as --parquet already read them. Before, text, --json, -V and -T decoded
each file alone: `==> bus_00002_... <==` titles, frame numbers from 1 again, and the answer at the start
of file 2 was '[no request] [response without a matching request in the capture]' while the request at
the end of file 1 was '[the capture ends before any response...]'; --stats said 'from 3 captures counted
as one bus' and counted one Read/Write Multiple Registers transaction less.
"""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

ROOT = Path(__file__).resolve().parents[2]
WHOLE = ROOT / "captures" / "atv71_commissioning.pcap"
OTHER = ROOT / "captures" / "p38_protection.pcap"
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
# Frame 35 ends file 1, its answer begins file 2.
BOUNDARY = [
    "    35     0.630728   2 request   Read/Write Multiple Registers read 3201..3202 (2), write 8501=15 "
    "8502=300  CRC ok",
    "    36     0.645823   2 response  Read/Write Multiple Registers 3201..3202 (2): 3201=567 3202=47 "
    "[#35, 15.1 ms]  CRC ok",
]


@pytest.fixture(scope="module")
def ring(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    folder = tmp_path_factory.mktemp("ring")
    status, _out, err = run_cli([str(WHOLE), "-w", str(folder / "bus.pcap"), "-b", "filesize:1"])
    assert (status, err) == (0, "")
    files = sorted(folder.iterdir())
    assert [path.name for path in files] == [
        "bus_00001_20260101000000.pcap", "bus_00002_20260101000000.pcap", "bus_00003_20260101000001.pcap"]
    return files


def _decode(argv: list[str], monkeypatch: pytest.MonkeyPatch, pure: bool) -> str:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(argv)
    assert (status, err) == (0, "")
    return out


@BOTH
def test_ring_files_decode_as_the_whole_capture(ring: list[Path], monkeypatch: pytest.MonkeyPatch,
                                                pure: bool) -> None:
    # Named in any order: by file number.
    files = [str(path) for path in reversed(ring)]
    lines = _decode(["-n", *files], monkeypatch, pure).splitlines()
    assert lines[34:36] == BOUNDARY
    assert len(lines) == 104 and not any(line.startswith("==>") for line in lines)
    for options in ([], ["--json"], ["-V"], ["-x"], ["-T", "registers"], ["--stats"], ["--stats", "--json"],
                    ["-Y", "function == 23"], ["-c", "40"], ["-t", "d"]):
        whole = _decode([*options, str(WHOLE)], monkeypatch, pure)
        assert _decode([*options, *files], monkeypatch, pure) == whole, options


@BOTH
def test_a_ring_beside_another_capture_is_one_title(ring: list[Path], monkeypatch: pytest.MonkeyPatch,
                                                    pure: bool) -> None:
    lines = _decode(["-n", *map(str, ring), str(OTHER)], monkeypatch, pure).splitlines()
    assert [line for line in lines if line.startswith("==>")] == [
        f"==> {ring[0].parent / 'bus.pcap'} <==", f"==> {OTHER} <=="]
    assert lines[35:37] == BOUNDARY
    assert lines[106].startswith("     1 ")  # the other capture counts from 1
    registers = _decode(["-T", "registers", *map(str, ring), str(OTHER)], monkeypatch, pure).splitlines()
    assert registers[0].startswith(f"{ring[0].parent / 'bus.pcap'}\t4\t0.059787\t2\t3\tread\t3102\t")


def test_files_of_unrelated_names_stay_apart(ring: list[Path], tmp_path: Path) -> None:
    """Only dumpcap's ring names join: the same files renamed are two captures, each titled and numbered."""
    first, second = tmp_path / "part1.pcap", tmp_path / "part2.pcap"
    shutil.copy(ring[0], first)
    shutil.copy(ring[1], second)
    status, out, err = run_cli(["-n", str(first), str(second)])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    assert [line for line in lines if line.startswith("==>")] == [f"==> {first} <==", f"==> {second} <=="]
    assert lines[37] == ("     1     0.000000   2 response  Read/Write Multiple Registers (2): ?+0=567 "
                         "?+1=47 [no request] [response without a matching request in the capture]  CRC ok")


def _two_line_file(path: Path, packets: list[tuple[int, float, str]]) -> None:
    """A pcapng of two lines (/dev/pts/0, /dev/pts/1), as Wireshark capturing two vw3 extcap lines."""
    from dissector.render.pcapngwriter import PcapngWriter

    lines = [(name, f"serial port {name}, 19200 baud") for name in ("/dev/pts/0", "/dev/pts/1")]
    with open(path, "wb") as stream:
        writer = PcapngWriter(stream, if_name=lines[0][0], if_description=lines[0][1])
        writer.use_interface(*lines[1])
        for line, time, data in packets:
            writer.use_interface(*lines[line])
            writer.write(bytes.fromhex(data), 1767225600.0 + time)
        writer.close()


def test_a_two_line_ring_is_a_capture_a_line(tmp_path: Path) -> None:
    """Each line its own bus over every file of the ring: its request in file 1 answered in file 2. Before,
    --parquet decoded both lines as one stream ('4 frames' and a warning that packets come from several
    interfaces)."""
    request, answer = "0C0320D000030EEF", "0C030680000003000217E4"
    first, second = tmp_path / "two_00001_20260101000000.pcapng", tmp_path / "two_00002_20260101000001.pcapng"
    _two_line_file(first, [(0, 0.0, request), (1, 0.002, request), (0, 0.010, answer)])
    _two_line_file(second, [(1, 0.014, answer)])
    status, out, err = run_cli(["-n", str(first), str(second)])
    assert (status, err) == (0, "")
    shown = tmp_path / "two.pcapng"
    assert out.splitlines() == [
        f"==> {shown}: /dev/pts/0 <==",
        "     1     0.000000  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
        "     2     0.010000  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 "
        "[#1, 10.0 ms]  CRC ok",
        f"==> {shown}: /dev/pts/1 <==",
        "     1     0.000000  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
        "     2     0.012000  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 "
        "[#1, 12.0 ms]  CRC ok",
    ]
    pytest.importorskip("pyarrow")
    status, out, err = run_cli(["--parquet", str(tmp_path / "data"), str(first), str(second)])
    assert (status, err) == (0, "")
    assert out.splitlines() == [f"{shown}: /dev/pts/0: 2 frames, 3 registers, 0 events",
                                f"{shown}: /dev/pts/1: 2 frames, 3 registers, 0 events"]


def test_the_report_of_a_ring_is_the_whole_captures(ring: list[Path], tmp_path: Path) -> None:
    """Titled by the ring's name (before: its three files'), and the same page otherwise."""
    pages = []
    for name, inputs in (("ring", [str(path) for path in ring]), ("whole", [str(WHOLE)])):
        status, _out, err = run_cli(["--report", str(tmp_path / f"{name}.html"), *inputs])
        assert (status, err) == (0, "")
        pages.append((tmp_path / f"{name}.html").read_text())
    ringed, whole = pages
    assert f"<title>vw3-decode report: {ring[0].parent / 'bus.pcap'}</title>" in ringed
    assert ringed.replace(str(ring[0].parent / "bus.pcap"), str(WHOLE)) == whole
