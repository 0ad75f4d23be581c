"""The plugin, as vw3-decode (tests/integration/test_rtac_short_records.py): an RTAC serial record shorter than
its 12-byte header, in a capture whose RTAC data Decode As gives to VW3, is VW3's bytes at its record's time
(vw3-decode: noise, sources/common.py rtac_header). Before, Wireshark's RTAC dissector took none of it and
tshark showed it as Data (5 bytes), the VW3 stream never had those bytes: the next frames' offsets slid by
them and vw3-decode's noise item was missing. A record of 8 to 11 bytes was read as an RTAC time besides.
Real tshark 4.0 with -X lua_script:lua/vw3.lua -d rtacser.data,vw3; pcap and pcapng."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, lua_errors, run_tshark

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_rtac_odd_records import _ng, _pcap  # noqa: E402

pytestmark = pytest.mark.integration

WRITERS = pytest.mark.parametrize("write", [_pcap, _ng], ids=["pcap", "pcapng"])
FIELDS = ["-T", "fields", "-E", "separator=|", "-E", "occurrence=a", "-e", "frame.number", "-e", "vw3.kind",
          "-e", "vw3.item", "-e", "vw3.offset", "-e", "vw3.noise.reason", "-e", "vw3.response_time",
          "-e", "_ws.col.Protocol", "-e", "_ws.col.Info"]
EVENT = "1||||||RTAC Serial|DATA_TX_START         ( /CTS, /DCD, /DSR, /RTS, /DTR, /RING, /MBOK )"
READ = "12 Read Holding Registers request 8400..8402 (3)"
ANSWER = "12 Read Holding Registers response 8400..8402 (3)"
# (the odd record's bytes, the six records under -2, vw3-decode's (kind, offset, reason) of each item)
CASES = {
    "5 bytes": ("0102030405", [
        EVENT, f"2|1|1|0|||VW3|{READ}", "3|4|2|8|a silence cuts a request (5 of 8 bytes)||VW3|noise (5 bytes)",
        f"4|2|3|13||0.008000000|VW3|{ANSWER}", f"5|1|4|24|||VW3|{READ}", f"6|2|5|32||0.020000000|VW3|{ANSWER}"],
        [("request", 0, None), ("noise", 8, "a silence cuts a request (5 of 8 bytes)"), ("response", 13, None),
         ("request", 24, None), ("response", 32, None)]),
    "2 bytes": ("0c03", [
        EVENT, f"2|1|1|0|||VW3|{READ}", "3|4|2|8|a silence cuts the response (2 bytes of it)||VW3|noise (2 bytes)",
        f"4|2|3|10||0.008000000|VW3|{ANSWER}", f"5|1|4|21|||VW3|{READ}", f"6|2|5|29||0.020000000|VW3|{ANSWER}"],
        [("request", 0, None), ("noise", 8, "a silence cuts the response (2 bytes of it)"), ("response", 10, None),
         ("request", 21, None), ("response", 29, None)]),
    # (9 bytes: no RTAC time read from its first 8; a noise byte, then a request with a bad CRC that the answer
    # does not fit)
    "9 bytes": ("010203040506070809", [
        EVENT, f"2|1|1|0|||VW3|{READ}",
        "3|4,1|2,3|8,9|no valid frame||VW3|noise (1 byte); 2 Read Holding Registers request 1029..2571 (1543) BAD CRC",
        "4|2|4|17|||VW3|12 Read Holding Registers response (3)", f"5|1|5|28|||VW3|{READ}",
        f"6|2|6|36||0.020000000|VW3|{ANSWER}"],
        [("request", 0, None), ("noise", 8, "no valid frame"), ("request", 9, None), ("response", 17, None),
         ("request", 28, None), ("response", 36, None)]),
}


def _decoded(path: Path) -> list[tuple[str, int, str | None]]:
    run = subprocess.run([sys.executable, "-m", "dissector", str(path), "--json"], capture_output=True, text=True,
                         cwd=ROOT, timeout=300, check=True)
    items = [json.loads(line) for line in run.stdout.splitlines()]
    return [(item["kind"], item["offset"], item.get("reason")) for item in items]


@WRITERS
@pytest.mark.parametrize("case", sorted(CASES))
def test_a_short_record_is_vw3s_as_vw3_decode_reads_it(tmp_path: Path, write, case: str) -> None:  # type: ignore[no-untyped-def]
    odd, shown, decoded = CASES[case]
    path = write(tmp_path / "short.cap", bytes.fromhex(odd))
    assert _decoded(path) == decoded
    result = run_tshark(path, "-d", "rtacser.data,vw3", *FIELDS)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr
    assert result.stdout.splitlines() == shown


@WRITERS
def test_one_pass_shows_the_noise_once_it_ends(tmp_path: Path, write) -> None:  # type: ignore[no-untyped-def]
    path = write(tmp_path / "short.cap", bytes.fromhex("0102030405"))
    result = run_tshark(path, "-d", "rtacser.data,vw3", *FIELDS, two_pass=False)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr
    assert result.stdout.splitlines()[2:4] == [
        "3||||||VW3|(5 bytes continue)",
        "4|4,2|2,3|8,13|a silence cuts a request (5 of 8 bytes)|0.008000000|VW3|noise (5 bytes) from #3; "
        f"{ANSWER} [provisional]"]


@WRITERS
def test_without_decode_as_the_record_stays_data(tmp_path: Path, write) -> None:  # type: ignore[no-untyped-def]
    path = write(tmp_path / "short.cap", bytes.fromhex("0102030405"))
    result = run_tshark(path, "-T", "fields", "-e", "frame.number", "-e", "frame.protocols")
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[2] == "3\tvw3rtac:data"
