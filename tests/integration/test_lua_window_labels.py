"""A PLC-style device's request windows carry their labels in the plugin as vw3-decode's filter gives them
(render/filter_match.py item_elements: `label == "40102"` finds the read request that asked for 40102, the
FC16 answer, FC23's read window): each address the frame names without its value is a hidden vw3.reg.label
beside its hidden vw3.reg.address (show.lua add_named). Before, only vw3.reg.address was there: `vw3.reg.label
== "40102"` missed frames 1, 4 and 9."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [
    "01 03 0064 0003", "01 03 06 0001 0002 0003",  # read 40101..40103
    "01 10 0064 0002 04 000A 000B", "01 10 0064 0002",  # write 40101..40102
    "01 04 0010 0001", "01 04 02 0005",  # read input 30017
    "01 06 0065 0007", "01 06 0065 0007",  # write 40102
    "01 17 0064 0002 0070 0001 02 0009", "01 17 04 0001 0002",  # read 40101..40102, write 40113
]
PLC = ("-o", "vw3.profiles:generic", "-o", "vw3.address_style:plc")
# frame | vw3.span_label | vw3.reg.label (the registers' first, then the window's) | vw3.reg.address
FIELDS = [
    "1|40101..40103|40101,40102,40103|100,101,102",
    "2|40101..40103|40101,40102,40103|100,101,102",
    "3|40101..40102|40101,40102|100,101",
    "4|40101..40102|40101,40102|100,101",
    "5|30017|30017|16",
    "6|30017|30017|16",
    "7|40102|40102|101",
    "8|40102|40102|101",
    "9|40101..40102|40113,40101,40102|112,100,101",
    "10|40101..40102|40101,40102|100,101",
]


@pytest.fixture
def capture(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "windows.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                                  for index, frame in enumerate(FRAMES)])


@pytest.mark.parametrize("two_pass", [True, False])
def test_each_window_address_has_its_label(capture: Path, two_pass: bool) -> None:
    got = run_tshark(capture, *PLC, "-T", "fields", "-E", "separator=|", "-e", "frame.number", "-e", "vw3.span_label",
                     "-e", "vw3.reg.label", "-e", "vw3.reg.address", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == FIELDS


@pytest.mark.parametrize("two_pass", [True, False])
def test_a_label_filter_finds_what_vw3_decode_finds(capture: Path, two_pass: bool) -> None:
    status, out, err = run_cli([str(capture), "--profile", "generic", "--address-style", "plc",
                                "-Y", 'label == "40102"'])
    assert (status, err) == (0, "")
    assert [int(line.split()[0]) for line in out.splitlines()] == [1, 2, 3, 4, 7, 8, 9, 10]
    got = run_tshark(capture, *PLC, "-Y", 'vw3.reg.label == "40102"', "-T", "fields", "-e", "frame.number",
                     two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.split() == ["1", "2", "3", "4", "7", "8", "9", "10"]


# A window across 49999: the registers' labels turn 6-digit (naming.plc_label: 49999, 410000, 410001), and so
# do the window's. vw3-decode's filter gave the request's window 50000 (49999 + 1), which no screen shows.
ACROSS = ["01 03 270E 0003", "01 03 06 0001 0002 0003", "01 10 270E 0002 04 000A 000B", "01 10 270E 0002"]


@pytest.mark.parametrize("label, frames", [("410000", [1, 2, 3, 4]), ("49999", [1, 2, 3, 4]), ("50000", [])])
def test_a_window_across_49999_is_labelled_as_its_registers(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                            label: str, frames: list[int]) -> None:
    capture = write_pcap(tmp_path / "across.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                                    for index, frame in enumerate(ACROSS)])
    for pure in (False, True):
        use_engine(monkeypatch, pure)
        status, out, err = run_cli([str(capture), "--profile", "generic", "--address-style", "plc",
                                    "-Y", f'label == "{label}"'])
        assert (status, err) == (0, "")
        assert [int(line.split()[0]) for line in out.splitlines()] == frames
    got = run_tshark(capture, *PLC, "-Y", f'vw3.reg.label == "{label}"', "-T", "fields", "-e", "frame.number")
    assert not lua_errors(got.stdout + got.stderr)
    assert [int(number) for number in got.stdout.split()] == frames


def test_fields_and_bit_windows_as_the_plugin(capture: Path, tmp_path: Path) -> None:
    # vw3-decode -T fields' `label` lists a register window's labels after its registers', as vw3.reg.label;
    # a coil window has none (bits carry no label: `label == "00002"` found the coil read, not its answer).
    status, out, err = run_cli([str(capture), "--profile", "generic", "--address-style", "plc", "-T", "fields",
                                "-e", "frame", "-e", "label", "-E", "aggregator=,"])
    assert (status, err) == (0, "")
    assert out.splitlines()[:4] == ["1\t40101,40102,40103", "2\t40101,40102,40103", "3\t40101,40102",
                                    "4\t40101,40102"]
    coils = write_pcap(tmp_path / "coils.pcap", [(rtu("01 01 0000 0003"), 1700000000.0),
                                                 (rtu("01 01 01 05"), 1700000000.01)])
    status, out, err = run_cli([str(coils), "--profile", "generic", "--address-style", "plc", "-Y", 'label == "00002"'])
    assert (status, out, err) == (0, "", "")
    got = run_tshark(coils, *PLC, "-Y", 'vw3.reg.label == "00002"', "-T", "fields", "-e", "frame.number")
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout == ""
