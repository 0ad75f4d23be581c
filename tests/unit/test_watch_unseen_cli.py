"""vw3-decode --watch says at the end, on stderr, each watched address or code the input never gave a register
of (render/watch.py Watcher.unseen), with where the address is a bit; exit 0, stdout the watch lines alone.
Before, `--watch 172` on a capture reading coil 172 printed nothing and said nothing."""
from __future__ import annotations

from pathlib import Path

from helpers import rtu, run_cli


def test_watch_a_coil_says_so(tmp_path: Path) -> None:
    capture = tmp_path / "coils.bin"
    capture.write_bytes(rtu("0101 00AC 0008") + rtu("0101 01 05") + rtu("0103 00B5 0001") + rtu("0103 02 0007")
                        + rtu("0103 00B5 0001") + rtu("0103 02 0009"))
    code, out, err = run_cli(["-n", "--watch", "172,181", str(capture)])
    assert (code, out) == (0, "     6            -   1 181 7 -> 9\n")
    assert err == ("vw3-decode: --watch 172: no register 172 in the capture (bit 172: Read Coils to slave 1 in "
                   "frame #1; --watch follows registers only)\n")


def test_watch_a_code_never_read_says_so(tmp_path: Path) -> None:
    capture = tmp_path / "chcf.bin"
    capture.write_bytes(rtu("0C03 20D1 0001") + rtu("0C03 02 0003"))
    code, out, err = run_cli(["--profile", "atv71", "--watch", "CHCF,HSP", str(capture)])
    assert (code, out, err) == (0, "", "vw3-decode: --watch HSP: no register named HSP in the capture\n")
