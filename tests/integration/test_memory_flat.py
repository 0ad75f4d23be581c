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

from dissector.render.pcapwriter import PcapWriter
from dissector.sim.mixes import max_size_mix

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
