"""FC8 sub-functions the VW3 A3 303 does not answer (02 Return Diagnostic Register, 14 Clear Overrun Counter
and Flag: chapter 8 lists 00, 01, 03, 04, 0A..12; atv71.toml `subfunctions`) are warned on the request, as a
function the card lacks is; the spec's other sub-functions are not, nor under a profile without the list.
Exact summary lines under the compiled engine and VW3_PURE_PYTHON=1, and the plugin's vw3.warning (tshark
with -X lua_script:lua/vw3.lua, -2 and one pass) equal to vw3-decode's."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

REQUESTS = ["0C 08 0002 0000", "0C 08 0014 0000", "0C 08 000B 0000", "0C 08 0012 0000"]
WARNING = "sub-function {:02X}h ({}) is not supported by the VW3 A3 303"
WARNED = {
    1: WARNING.format(0x02, "Return Diagnostic Register"),
    2: WARNING.format(0x14, "Clear Overrun Counter and Flag"),
}


def _warnings(profile: str, pure: bool, monkeypatch: pytest.MonkeyPatch) -> list[str]:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli(["--hex", " ".join(rtu(frame).hex() for frame in REQUESTS), "--profile", profile])
    assert status == 0, err
    return out.splitlines()


LINES = [
    "     1            -  12 request   Diagnostics 02h Return Diagnostic Register = 0 [no response] "
    f"[warning: {WARNED[1]}]  CRC ok",
    "     2            -  12 request   Diagnostics 14h Clear Overrun Counter and Flag = 0 [no response] "
    f"[warning: {WARNED[2]}]  CRC ok",
    "     3            -  12 request   Diagnostics 0Bh Return Bus Message Count = 0 [no response]  CRC ok",
    "     4            -  12 request   Diagnostics 12h Return Bus Character Overrun Count = 0 [the capture ends before "
    "any response: not known whether it was answered]  CRC ok",
]


@pytest.mark.parametrize("pure", [False, True])
def test_the_card_warns_of_sub_functions_it_lacks(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    assert _warnings("atv71", pure, monkeypatch) == LINES


@pytest.mark.parametrize("pure", [False, True])
def test_a_profile_without_the_list_takes_every_sub_function(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    assert not any("[warning:" in line for line in _warnings("generic", pure, monkeypatch))


@pytest.mark.parametrize("two_pass", [True, False])
def test_the_plugin_warns_as_vw3_decode(tmp_path: Path, two_pass: bool) -> None:
    pcap = write_pcap(tmp_path / "fc8.pcap", [(rtu(frame), 1700000000 + index) for index, frame in enumerate(REQUESTS)])
    got = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                     "-e", "vw3.warning", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == [f"{number}|{WARNED.get(number, '')}" for number in range(1, len(REQUESTS) + 1)]


# Chapter 8: the card's 10 (NAK count) and 11 (slave-busy count) are always 0 (shared/reference); an answer
# with another value did not come from those counters (atv71.toml [diagnostic_constants]).
COUNTERS = [("0C 08 0010 0000", "0C 08 0010 0000"), ("0C 08 0011 0000", "0C 08 0011 0005"),
            ("0C 08 0010 0000", "0C 08 0010 0100"), ("0C 08 0012 0000", "0C 08 0012 0003")]
CONSTANT = "the VW3 A3 303 documents sub-function {:02X} as always 0: this answer says {}"
NAK = "sub-function 10 on the VW3 A3 303: NAK count (always 0 on this card)"
BUSY = "sub-function 11 on the VW3 A3 303: slave-busy count (always 0 on this card)"
COUNTER_LINES = [
    f"     1            -  12 request   Diagnostics 10h NAK count (always 0 on this card) = 0 [{NAK}]  CRC ok",
    f"     2            -  12 response  Diagnostics 10h NAK count (always 0 on this card) = 0 [#1] [{NAK}; value 0]"
    "  CRC ok",
    f"     3            -  12 request   Diagnostics 11h slave-busy count (always 0 on this card) = 0 [{BUSY}]  CRC ok",
    f"     4            -  12 response  Diagnostics 11h slave-busy count (always 0 on this card) = 5 [#3] [{BUSY}; "
    f"value 5] [warning: {CONSTANT.format(0x11, 5)}]  CRC ok",
    f"     5            -  12 request   Diagnostics 10h NAK count (always 0 on this card) = 0 [{NAK}]  CRC ok",
    f"     6            -  12 response  Diagnostics 10h NAK count (always 0 on this card) = 256 [#5] [{NAK}; "
    f"value 256] [warning: {CONSTANT.format(0x10, 256)}]  CRC ok",
    "     7            -  12 request   Diagnostics 12h Return Bus Character Overrun Count = 0  CRC ok",
    "     8            -  12 response  Diagnostics 12h Return Bus Character Overrun Count = 3 [#7]  CRC ok",
]


@pytest.mark.parametrize("pure", [False, True])
def test_the_cards_constant_counters_are_checked(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    frames = [frame for pair in COUNTERS for frame in pair]
    status, out, err = run_cli(["--hex", " ".join(rtu(frame).hex() for frame in frames), "--profile", "atv71"])
    assert status == 0, err
    assert out.splitlines() == COUNTER_LINES
    status, out, err = run_cli(["--hex", " ".join(rtu(frame).hex() for frame in frames), "--profile", "generic"])
    assert status == 0 and "[warning:" not in out and "always" not in out, out


def test_the_plugin_checks_the_constant_counters_as_vw3_decode(tmp_path: Path) -> None:
    frames = [frame for pair in COUNTERS for frame in pair]
    pcap = write_pcap(tmp_path / "fc8.pcap", [(rtu(frame), 1700000000 + 0.05 * index)
                                              for index, frame in enumerate(frames)])
    got = run_tshark(pcap, "-o", "vw3.profiles:atv71", "-T", "fields", "-E", "separator=|", "-e", "frame.number",
                     "-e", "vw3.warning")
    assert not lua_errors(got.stdout + got.stderr)
    warned = {4: CONSTANT.format(0x11, 5), 6: CONSTANT.format(0x10, 256)}
    assert got.stdout.splitlines() == [f"{number}|{warned.get(number, '')}" for number in range(1, 9)]
