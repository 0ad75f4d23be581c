"""-T fields register columns when a frame also names addresses without values (a read window), as tshark
writes the plugin's vw3.reg.* fields: `address` lists the carried registers, then the window; a number key
(value, scaled) has only the values there are and a text key (code) one occurrence per carried register,
none for a window address (was: an empty occurrence for each window address, `7,,` and `,,,` where tshark
writes `7` and nothing; tshark's own -E occurrence=l then pairs the window's last address with register
16's value, and so does vw3-decode's). The window still answers -Y 'address == N'. Under the engine and
VW3_PURE_PYTHON=1; tests/integration/test_fields_registers_as_tshark.py checks the same against tshark."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli, use_engine

ROOT = Path(__file__).resolve().parents[2]
FC23 = ["--hex", "17 17 0000 0002 0010 0001 02 00 07"]  # reads 0..1, writes 16 = 7
COLUMNS = ["-T", "fields", "-e", "address", "-e", "value", "-e", "scaled", "-e", "code"]


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("occurrence, line", [("a", "16,0,1\t7\t\t\n"), ("l", "1\t7\t\t\n"),
                                              ("f", "16\t7\t\t\n")])
def test_window_addresses_as_tshark_writes_them(monkeypatch: pytest.MonkeyPatch, pure: bool, occurrence: str,
                                               line: str) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([*FC23, *COLUMNS, "-E", f"occurrence={occurrence}"])
    assert (status, out, err) == (0, line, "")


@pytest.mark.parametrize("pure", [False, True])
def test_commissioning_read_request_and_answer(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    capture = str(ROOT / "captures" / "atv71_commissioning.pcap")
    status, out, err = run_cli([capture, "-T", "fields", "-e", "frame", "-e", "address", "-e", "scaled", "-e",
                                "value", "-Y", "address == 3103"])
    assert (status, err) == (0, "")
    assert out.splitlines()[:2] == ["3\t3102,3103,3104,3105\t\t", "4\t3102,3103,3104,3105\t4,60,50,0\t40,600,500,0"]
    status, out, err = run_cli([capture, "-T", "fields", "-e", "frame", "-e", "address", "-e", "value",
                                "-E", "occurrence=l", "-Y", "frame <= 4"])
    assert (status, out, err) == (0, "1\t\t\n2\t\t\n3\t3105\t\n4\t3105\t0\n", "")
