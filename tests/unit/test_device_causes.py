"""Exception 03 from the ATV71's card tied to what made the request illegal (atv71.toml
[[exception_causes]] when = "quantity"): a quantity past the card's [limits] (the request's warning) is
named as the cause; any other exception 03 keeps the card's meaning "value not permitted". Python
stages, compiled engine and the Lua plugin (which reads the same profile data through codegen)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import run_tshark, write_pcap

OVER = "0C 03 0C 81 00 40 16 5F"  # read 3201..3264: 64 words, the card's limit is 63
WITHIN = "0C 03 0C 81 00 3F 57 BF"  # read 3201..3263: 63 words
REFUSED = "0C 83 03 90 F2"  # exception 03
OVER_WRITE = rtu("0C 10 0C 81 00 3E 7C" + "0000" * 62).hex()  # FC16 of 62 words: the limit is 61

CAUSE = ("[exception 03 from the VW3 A3 303 to Read Holding Registers: quantity beyond the card's limit]")
PLAIN = "[exception 03 from the VW3 A3 303 to Read Holding Registers: value not permitted]"


def _lines(*hexes: str) -> list[str]:
    argv = ["--profile", "atv71"]
    for item in hexes:
        argv += ["--hex", item]
    status, out, err = run_cli(argv)
    assert status == 0, err
    return out.splitlines()


@pytest.mark.parametrize("pure", [False, True])
def test_quantity_past_the_limit_is_the_cause(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    lines = _lines(OVER, REFUSED)
    assert lines[0].endswith("Read Holding Registers 3201..3264 (64) [warning: quantity 64 is beyond the "
                             "VW3 A3 303's limit of 63 words for Read Holding Registers]  CRC ok")
    assert lines[1] == ("     2            -  12 exception Read Holding Registers: exception 3 (Illegal Data Value)"
                        f" [#1] {CAUSE}  CRC ok")


@pytest.mark.parametrize("pure", [False, True])
def test_within_the_limit_keeps_the_meaning(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    lines = _lines(WITHIN, REFUSED)
    assert "warning" not in lines[0]
    assert lines[1] == ("     2            -  12 exception Read Holding Registers: exception 3 (Illegal Data Value)"
                        f" [#1] {PLAIN}  CRC ok")


@pytest.mark.parametrize("pure", [False, True])
def test_verbose_says_the_cause(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    # (the meaning is the cause the note and --report give, test_cause_meaning; within the limit the card's)
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--profile", "atv71", "-V", "--hex", OVER, "--hex", REFUSED])
    assert status == 0, err
    frame = out.split("Frame 2:")[1]
    assert "        Exception meaning on this device: quantity beyond the card's limit\n" in frame
    assert "    Note: exception 03 from the VW3 A3 303 to Read Holding Registers: quantity beyond the card's limit\n" in frame


def test_write_past_the_limit() -> None:
    status, out, err = run_cli(["--profile", "atv71", "--hex", OVER_WRITE, "--hex", "0C 90 03 9D C2"])
    assert status == 0, err
    assert out.splitlines()[1].endswith(
        "[exception 03 from the VW3 A3 303 to Write Multiple Registers: quantity beyond the card's limit]  CRC ok")


def test_plugin_names_the_cause(tmp_path: Path) -> None:
    def notes(request: str) -> list[str]:
        records = [(bytes.fromhex(request), 1.0), (bytes.fromhex(REFUSED), 1.1)]
        pcap = write_pcap(tmp_path / "exc.pcap", records)
        done = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-T", "fields", "-e", "vw3.note")
        assert done.returncode == 0, done.stderr
        return done.stdout.splitlines()

    assert notes(OVER)[1] == CAUSE[1:-1]
    assert notes(WITHIN)[1] == PLAIN[1:-1]
