"""One truth across outputs: `vw3-decode -T fields -e KEY` and `tshark -T fields -e vw3.KEY` (the plugin,
tshark 4.0.17 -2) write the same text for every field both have (data/fields.toml: key and filter), and
`-Y 'address == N'` finds the frames `-Y 'vw3.reg.address == N'` finds.

- crc, crc_expected: as tshark writes a uint16 BASE_HEX, `0x7734`;
- scaled: as a double, 15 digits, `4` (not 4.0);
- response_time: as a relative time, `0.010157000`, to the nanosecond; from RTAC records' own times
  too (`0.020000000`, where the plugin said 0.019999981);
- broadcast, unanswered: nothing where false (the plugin adds them only where true);
- address: the registers a frame carries, then the addresses it names without their values (a read
  request's window, FC15/FC16's answer, FC23's read window), so `address == 8401` finds the request
  that asked for 8401 as well as its answer, in both.
The differences left are stated and checked too: vw3.kind is an integer with names (1 request: tshark
writes the number), and bits are vw3.bit.address and vw3.bit.value in the plugin. (A number key has no
empty occurrence, and a read window's addresses none of the other keys, in either: session 61; before,
vw3-decode lined its register columns up with empty ones.)
"""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from dissector.render.filter_fields import CATALOGUE
from dissector.render.pcapwriter import LINKTYPE_RTAC_SERIAL, PcapWriter
from helpers import run_cli, rtu, use_engine
from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

CAPTURES = sorted((ROOT / "captures").glob("*.pcap"))
P38 = ROOT / "captures" / "p38_protection.pcap"
# Every field both have, by vw3-decode's key and the plugin's name (registers: not the bits).
BOTH = [(entry["key"], entry["filter"]) for entry in CATALOGUE
        if "key" in entry and "filter" in entry and entry["type"] != "struct"]
KIND = {"1": "request", "2": "response", "3": "exception", "4": "noise"}


def cli_rows(path: Path, keys: list[str], *options: str) -> list[list[str]]:
    status, out, err = run_cli([str(path), *options, "-T", "fields", "-E", "aggregator=^",
                                *[x for key in keys for x in ("-e", key)]])
    assert (status, err) == (0, ""), err
    return [line.split("\t") for line in out.splitlines()]


def plugin_rows(path: Path, names: list[str], *options: str, two_pass: bool = True) -> list[list[str]]:
    done = run_tshark(path, *options, "-T", "fields", "-E", "aggregator=^",
                      *[x for name in names for x in ("-e", name)], two_pass=two_pass)
    assert done.returncode == 0 and not lua_errors(done.stdout + done.stderr), done.stderr[-2000:]
    return [line.split("\t") for line in done.stdout.splitlines()]


@pytest.mark.parametrize("pure", [False, True])
@pytest.mark.parametrize("capture", CAPTURES, ids=lambda path: path.name)
def test_every_field_both_have_says_the_same(capture: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    keys, names = [key for key, _ in BOTH], [name for _, name in BOTH]
    cli = cli_rows(capture, [*keys, "registers", "bits"])
    plugin = plugin_rows(capture, [*names, "vw3.bit.address", "vw3.bit.value"])
    assert len(cli) == len(plugin) and [row[0] for row in cli] == [row[0] for row in plugin]
    differences = []
    for ours, theirs in zip(cli, plugin):
        bits = dict(zip(("address", "value"), theirs[len(names):]))
        for index, key in enumerate(keys):
            mine, shown = ours[index], theirs[index]
            if key == "kind":
                shown = KIND.get(shown, shown)
            if key in bits and bits[key]:  # (registers, then bits, as vw3-decode lists them)
                shown = "^".join(value for value in (shown, bits[key]) if value)
            if mine != shown:
                differences.append(f"item {ours[0]} {key}: vw3-decode {mine!r}, plugin {shown!r}")
    assert not differences, "\n".join(differences[:20])


def test_p38_rows_exactly() -> None:
    keys = ["frame", "crc", "broadcast", "unanswered", "response_time", "address", "value"]
    names = ["vw3.item", "vw3.crc", "vw3.broadcast", "vw3.unanswered", "vw3.response_time", "vw3.reg.address",
             "vw3.reg.value"]
    rows = [
        ["1", "0xef0e", "", "", "", "8400^8401^8402", ""],  # (the window: no value)
        ["2", "0xe417", "", "", "0.010157000", "8400^8401^8402", "32768^3^2"],
        ["3", "0xef0e", "", "", "", "8400^8401^8402", ""],
        ["4", "0xe417", "", "", "0.007980000", "8400^8401^8402", "32768^3^2"],
        ["5", "0xef0e", "", "", "", "8400^8401^8402", ""],
        ["6", "0x24ce", "", "", "0.009832000", "8400^8401^8402", "32768^32768^2"],
        ["7", "0xef0e", "", "", "", "8400^8401^8402", ""],
        ["8", "0x24ce", "", "", "0.008603000", "8400^8401^8402", "32768^32768^2"],
        ["9", "0xef0e", "", "", "", "8400^8401^8402", ""],
        ["10", "0x3251", "", "", "0.009184000", "8400^8401^8402", ""],  # (the exception's registers: no value)
        ["11", "0xef0e", "", "", "", "8400^8401^8402", ""],
        ["12", "0x3251", "", "", "0.011942000", "8400^8401^8402", ""],
    ]
    assert cli_rows(P38, keys) == rows
    assert plugin_rows(P38, names) == rows
    # the scaled values of the card manual's example (p.38's SFr, tFr, HSP, LSP), as a double is written
    atv71 = ROOT / "captures" / "atv71_commissioning.pcap"
    assert cli_rows(atv71, ["scaled"])[3] == plugin_rows(atv71, ["vw3.reg.scaled"])[3] == ["4^60^50^0"]


def test_a_register_filter_finds_the_requests_too() -> None:
    for address in (8400, 8401, 8402):
        status, out, _ = run_cli([str(P38), "-Y", f"address == {address}", "-T", "fields", "-e", "frame"])
        assert (status, out.split()) == (0, [str(n) for n in range(1, 13)])
        done = run_tshark(P38, "-Y", f"vw3.reg.address == {address}", "-T", "fields", "-e", "vw3.item")
        assert done.stdout.split() == [str(n) for n in range(1, 13)]
    # FC23: the registers written (8501, 8502), then the read window (3201, 3202), in both
    atv71 = ROOT / "captures" / "atv71_commissioning.pcap"
    assert cli_rows(atv71, ["frame", "function", "address"])[18] == ["19", "23", "8501^8502^3201^3202"]
    assert plugin_rows(atv71, ["vw3.item", "vw3.function", "vw3.reg.address"])[18] == [
        "19", "23", "8501^8502^3201^3202"]
    # FC16's answer names what was written
    assert cli_rows(atv71, ["frame", "address"])[17] == plugin_rows(atv71, ["vw3.item", "vw3.reg.address"])[17] == [
        "18", "9001^9002"]


# Coils: FC1 read of 3 coils from 19 and its answer, FC15 writing 2 coils at 40 and its answer, FC5 at 7,
# an FC3 read of quantity 0 (it names its start, as tshark's reference_num). Bits are vw3.bit.address.
COILS = [rtu(text) for text in ("0401001300 03", "040101 05", "040f00280002 0103", "040f00280002",
                                "04050007ff00", "04050007ff00", "0403000a0000")]


@pytest.mark.parametrize("pure", [False, True])
def test_coil_windows_are_bit_addresses(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    pcap = write_pcap(tmp_path / "coils.pcap", [(frame, 1767225600 + 0.05 * k) for k, frame in enumerate(COILS)])
    expected = [["1", "19^20^21"], ["2", "19^20^21"], ["3", "40^41"], ["4", "40^41"], ["5", "7"], ["6", "7"],
                ["7", "10"]]
    assert cli_rows(pcap, ["frame", "address"]) == expected
    plugin = plugin_rows(pcap, ["vw3.item", "vw3.reg.address", "vw3.bit.address"])
    assert [[item, registers or bits] for item, registers, bits in plugin] == expected
    assert [bits for _, _, bits in plugin][:6] == [row[1] for row in expected[:6]]  # (coils: bits)
    for two_pass in (True, False):
        done = run_tshark(pcap, "-Y", "vw3.bit.address == 20", "-T", "fields", "-e", "vw3.item", two_pass=two_pass)
        assert done.stdout.split() == ["1", "2"]
    status, out, _ = run_cli([str(pcap), "-Y", "address == 20", "-T", "fields", "-e", "frame"])
    assert (status, out.split()) == (0, ["1", "2"])


def test_rtac_response_times_are_exact(tmp_path: Path) -> None:
    # The RTAC's own times (u32 seconds, u32 microseconds) near 1.77e9 s: 20 000 us and 20 001 us apart.
    pcap = tmp_path / "rtac.pcap"
    request, answer = rtu("0C 03 20 D0 00 03"), rtu("0C 03 06 8000 0003 0002")
    times = [(0, 123457), (0, 143457), (1, 5), (1, 20006)]
    with pcap.open("wb") as stream:
        writer = PcapWriter(stream, linktype=LINKTYPE_RTAC_SERIAL)
        for index, (seconds, micros) in enumerate(times):
            header = struct.pack(">IIBBH", 1767225600 + seconds, micros, 0, 0, 0)
            # (the pcap's own times are not the RTAC's: the record reached the capture later)
            writer.write(header + (answer if index % 2 else request), 1767225600 + seconds + micros / 1e6 + 0.0007 * index)
    expected = [["1", ""], ["2", "0.020000000"], ["3", ""], ["4", "0.020001000"]]
    assert cli_rows(pcap, ["frame", "response_time"]) == expected
    for two_pass in (True, False):
        assert plugin_rows(pcap, ["vw3.item", "vw3.response_time"], "-d", "rtacser.data,vw3",
                           two_pass=two_pass) == expected
