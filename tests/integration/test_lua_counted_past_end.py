"""A counted field whose count points past the frame's end is a malformed frame, in vw3-decode (engine and
VW3_PURE_PYTHON=1) as in the plugin: an FC15 request framed by its quantity (4 coils: one status byte, its
CRC good) whose byte count says 137. Construct's compiled Bytes read what was there (`io.read(137)` gave 1
byte), so vw3-decode showed start, quantity and bits 1 0 1 0 with 'byte count 137 disagrees with the
quantity 4', where the interpreted grammar and the plugin said malformed (protocol/layouts.py _Exact)."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [rtu("01 0F 0000 0004 89 05"), rtu("01 0F 0000 0004")]
WARNING = "malformed request: byte_count past the end"  # (the plugin's words: grammar.shortfall)


@pytest.mark.parametrize("pure", [False, True])
def test_vw3_decode_says_malformed(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    capture = tmp_path / "fc15.bin"
    capture.write_bytes(b"".join(FRAMES))
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(capture), "--json"])
    assert (status, err) == (0, "")
    request = json.loads(out.splitlines()[0])
    assert request["warnings"] == [WARNING]
    assert "start" not in request and "bits" not in request and request["response_frame"] == 2


def test_the_plugin_says_malformed_too(tmp_path: Path) -> None:
    capture = write_pcap(tmp_path / "fc15.pcap", [(frame, 1700000000 + index * 0.01) for index, frame in enumerate(FRAMES)])
    got = run_tshark(capture, "-T", "fields", "-E", "separator=|", "-e", "frame.number", "-e", "vw3.warning",
                     "-e", "vw3.start")
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == ["1|malformed request: byte_count past the end|", "2||0"]
