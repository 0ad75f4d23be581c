"""Memory stays flat with the capture's size (issue 28: under 100 MB at 1 GB): the peak RSS of a decode
of N frames and of 4N frames of the same bus, each in a fresh process, differ by a few MB at most.

The bus is the max-size mix (every public code at random slaves, random response times and poll
intervals: what made --stats keep 1.3 GB at 1 GB of pcap), drawn from a pool of 300 transactions so
that its parameters are all seen by N frames. Its histograms fill MAX_TALLY entries a kind long before
1 GB; here the limit is lowered to 4096 in the decoding process, so that N frames fill it already and
4N show whether anything else grows.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from dissector.protocol.crc import with_crc
from dissector.render.pcapwriter import PcapWriter
from dissector.sim.mixes import max_size_mix
from dissector.sim.simulate import EPOCH_US

ROOT = Path(__file__).resolve().parents[2]
FRAMES = 100_000
SLACK_KB = 4 * 1024  # the summary's bounded caches still fill from N to 4N (2 MB)

# Run in a process of its own (VmHWM: the peak RSS of this process alone, not of pytest's fork).
DECODE = """
import sys
from dissector.render import stats_store
stats_store.MAX_TALLY = 4096
if len(sys.argv) > 1 and sys.argv[1].startswith("--columns="):  # before the modules that import COLUMNS
    from dissector.render.report import collect
    collect.COLUMNS = int(sys.argv.pop(1).split("=")[1])
from dissector.app.cli import main
status = main(sys.argv[1:])
sys.stdout.flush()
with open("/proc/self/status") as status_file:
    peak = next(line.split()[1] for line in status_file if line.startswith("VmHWM:"))
sys.stderr.write(f"peak {peak}\\n")
sys.exit(status)
"""


def peak_kb(arguments: list[str], output: Path, columns: int | None = None) -> int:
    lowered = [f"--columns={columns}"] if columns is not None else []
    with output.open("wb") as sink:
        result = subprocess.run([sys.executable, "-c", DECODE, *lowered, *arguments], stdout=sink, stderr=subprocess.PIPE,
                                cwd=ROOT, check=True)
    return int(result.stderr.decode().rsplit("peak ", 1)[1])


@pytest.fixture(scope="module")
def captures(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    folder = tmp_path_factory.mktemp("flat")
    records = max_size_mix(4 * FRAMES, seed=3, pool_size=300)
    paths = []
    for name, count in (("n", FRAMES), ("4n", 4 * FRAMES)):
        path = folder / f"{name}.pcap"
        with path.open("wb") as stream:
            writer = PcapWriter(stream, flush=False)
            for data, time in records[:count]:
                writer.write(data, time)
        paths.append(path)
    return paths[0], paths[1]


@pytest.mark.parametrize("options", [["--stats"], []], ids=["stats", "summary"])
def test_peak_memory_does_not_grow_with_the_capture(options: list[str], captures: tuple[Path, Path],
                                                    tmp_path: Path) -> None:
    small, large = captures
    arguments = ["--profile", "generic", *options]
    at_n = peak_kb([str(small), *arguments], tmp_path / "n.txt")
    at_4n = peak_kb([str(large), *arguments], tmp_path / "4n.txt")
    assert (tmp_path / "4n.txt").stat().st_size > 0
    assert at_4n - at_n < SLACK_KB, f"peak RSS {at_n} kB at {FRAMES} frames, {at_4n} kB at {4 * FRAMES}"


def test_peak_memory_of_a_report_does_not_grow_with_the_capture(captures: tuple[Path, Path], tmp_path: Path) -> None:
    """--report: its page is bounded by construction (COLUMNS pixel columns of MAX_SERIES parameters and
    of each slave's response times), and so is what it keeps while collecting. COLUMNS is lowered to 64
    in the decoding process, so that N frames fill each slave's columns already (about 300 answers each)."""
    small, large = captures
    pages = []
    for name, capture in (("n", small), ("4n", large)):
        page = tmp_path / f"{name}.html"
        pages.append(peak_kb([str(capture), "--profile", "generic", "--report", str(page)], tmp_path / f"{name}.txt",
                             columns=64))
        text = page.read_text("utf-8")
        assert text.startswith("<!DOCTYPE html>") and text.endswith("</body></html>\n")
        assert '"parameters":[{"slave":' in text
    at_n, at_4n = pages
    assert at_4n - at_n < SLACK_KB, f"peak RSS {at_n} kB at {FRAMES} frames, {at_4n} kB at {4 * FRAMES}"


# Every slave of a bus, polled in turn, each for one register (a value that changes): each slave's
# response times and its register's trend are a point per answer, evenly spread. With COLUMNS lowered
# to 150, N frames give each slave 2 x COLUMNS answers: columns are at least as wide as a slave's poll
# period before their last doubling, every one holds a point, the charts are full; 4N frames are two
# doublings later, and what is kept per column is the same.
SLAVES = 247
POLL_COLUMNS = 150
POLL_FRAMES = 4 * SLAVES * POLL_COLUMNS


def polled_capture(path: Path, frames: int) -> Path:
    requests = [with_crc(bytes([slave, 3, 0x10, slave, 0, 1])) for slave in range(1, SLAVES + 1)]
    answers = [[with_crc(bytes([slave, 3, 2, 0, value])) for value in range(16)] for slave in range(1, SLAVES + 1)]
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for index in range(frames // 2):
            slave, cycle = index % SLAVES, index // SLAVES
            start = EPOCH_US + index * 20_000  # a request every 20 ms, answered 7.5 ms later
            writer.write(requests[slave], start / 1e6)
            writer.write(answers[slave][(cycle * 7 + slave) % 16], (start + 7_500) / 1e6)
    return path


def test_peak_memory_of_a_report_of_every_slave_does_not_grow(tmp_path: Path) -> None:
    """--report of 247 slaves each answering all the time: their response-time charts and trends keep
    COLUMNS + 1 columns each once every column holds a point, whatever the capture's length (the
    response times' were let grow to 3 x COLUMNS a slave: 5.4 MB more at 4N here, 32 MB at 1 GB; now
    2.4 MB, as --stats' 1.1 MB, the heap as the input streams through)."""
    pages = []
    for name, frames in (("n", POLL_FRAMES), ("4n", 4 * POLL_FRAMES)):
        capture = polled_capture(tmp_path / f"{name}.pcap", frames)
        page = tmp_path / f"{name}.html"
        pages.append(peak_kb([str(capture), "--profile", "generic", "--report", str(page)], tmp_path / f"{name}.txt",
                             columns=POLL_COLUMNS))
        text = page.read_text("utf-8")
        assert text.count('<div class="chart rtt" data-slave=') == SLAVES
        assert f'"slave":{SLAVES},"answers":{frames // 2 // SLAVES}' in text
        capture.unlink()
    at_n, at_4n = pages
    assert at_4n - at_n < SLACK_KB, f"peak RSS {at_n} kB at {POLL_FRAMES} frames, {at_4n} kB at {4 * POLL_FRAMES}"
