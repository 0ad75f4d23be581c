"""tshark's -2 (two-pass analysis), which Wireshark users type out of habit: vw3-decode always reads a file
whole before showing it (profile auto, pairing), so -2 is taken and changes nothing; before, argparse read it
as a capture's name ('-2: no such file', exit 2). A file that is named -2 is still read."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli

ROOT = Path(__file__).resolve().parents[2]
P38_PCAP = str(ROOT / "captures" / "p38_protection.pcap")
P38_BIN = str(ROOT / "captures" / "p38_protection.bin")


@pytest.mark.parametrize("argv", [["-2", "-r", P38_PCAP], ["-r", P38_PCAP, "-2"], ["-2", P38_BIN]])
def test_two_pass_is_taken_and_changes_nothing(argv: list[str]) -> None:
    capture = P38_PCAP if "-r" in argv else P38_BIN
    plain = run_cli(["-c", "2", capture])
    status, out, err = run_cli(["-c", "2", *argv])
    assert (status, err) == (0, "")
    assert out == plain[1]
    assert plain[0] == 0
    assert "12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) " \
        "COP=Cd (command) [#1" in out.splitlines()[1]


def test_a_file_named_minus_two_is_read(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "-2").write_bytes(Path(P38_BIN).read_bytes())
    monkeypatch.chdir(tmp_path)
    status, out, err = run_cli(["-c", "1", "-2"])
    assert (status, err) == (0, "")
    assert out == "     1            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"


def test_count_minus_two_is_still_refused() -> None:
    status, out, err = run_cli(["-c", "-2", P38_BIN])
    assert (status, out) == (2, "")
    assert err.endswith("argument -c/--count: '-2' must be more than 0 (see vw3-decode --help)\n")
