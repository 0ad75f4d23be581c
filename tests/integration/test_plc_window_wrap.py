"""`--address-style plc`, a window that runs past address 65535: one rule in vw3-decode and the plugin. The
window is said as the request asks it, as the warning names it (`465535..465538` beside `addresses
65534..65537 run past 65535`: summary, -V, --json span_label/write_span_label, the plugin's Info and
vw3.span_label), and each address it names is the address on the wire, wrapped (0, 1: `address`), labelled
as that address is (40001, 40002), as the registers the answer carries are (`40001=3`). Before, vw3-decode
labelled a request's window addresses before wrapping (`label` 465537, 465538, which no register shows,
so `-Y 'label == "40001"'` found the answer but not its request) while the plugin labelled them after."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import lua_errors, run_tshark, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [
    "01 03 FFFE 0004", "01 03 08 0001 0002 0003 0004",  # read 65534..65537
    "01 10 FFFF 0002 04 0001 0002", "01 10 FFFF 0002",  # write 65535..65536
    "01 17 FFFE 0002 FFFF 0002 04 0009 000A", "01 17 04 0001 0002",  # read 65534..65535, write 65535..65536
]
PLC = ("-o", "vw3.profiles:generic", "-o", "vw3.address_style:plc")
# frame | span_label | write_span_label | label | address
FIELDS = [
    "1|465535..465538||465535,465536,40001,40002|65534,65535,0,1",
    "2|465535..465538||465535,465536,40001,40002|65534,65535,0,1",
    "3|465536..465537||465536,40001|65535,0",
    "4|465536..465537||465536,40001|65535,0",
    "5|465535..465536|465536..465537|465536,40001,465535|65535,0,65534",
    "6|465535..465536||465535,465536|65534,65535",
]


@pytest.fixture
def capture(tmp_path: Path) -> Path:
    return write_pcap(tmp_path / "wrap.pcap", [(rtu(frame), 1700000000 + index * 0.01)
                                               for index, frame in enumerate(FRAMES)])


@pytest.mark.parametrize("pure", [False, True])
def test_window_labels_wrap_as_their_addresses(capture: Path, monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([str(capture), "--profile", "generic", "--address-style", "plc", "-T", "fields",
                                "-E", "separator=|", "-e", "frame", "-e", "span_label", "-e", "write_span_label",
                                "-e", "label", "-e", "address"])
    assert (status, err) == (0, "")
    assert out.splitlines() == FIELDS
    status, out, err = run_cli([str(capture), "--profile", "generic", "--address-style", "plc",
                                "-Y", 'label == "40001"', "-T", "fields", "-e", "frame"])
    assert (status, err) == (0, "")
    assert out.split() == ["1", "2", "3", "4", "5"]
    status, out, err = run_cli([str(capture), "--profile", "generic", "--address-style", "plc", "-c", "2"])
    assert out.splitlines() == [
        "     1     0.000000   1 request   Read Holding Registers 465535..465538 (4)"
        " [warning: addresses 65534..65537 run past 65535]  CRC ok",
        "     2     0.010000   1 response  Read Holding Registers 465535..465538 (4): 465535=1 465536=2 40001=3"
        " 40002=4 [#1, 10.0 ms]  CRC ok",
    ]


def test_the_plugin_labels_the_window_alike(capture: Path) -> None:
    got = run_tshark(capture, *PLC, "-T", "fields", "-E", "separator=|", "-e", "frame.number", "-e", "vw3.span_label",
                     "-e", "vw3.write_span_label", "-e", "vw3.reg.label", "-e", "vw3.reg.address")
    assert not lua_errors(got.stdout + got.stderr)
    assert got.stdout.splitlines() == FIELDS
    got = run_tshark(capture, *PLC, "-Y", 'vw3.reg.label == "40001"', "-T", "fields", "-e", "frame.number")
    assert got.stdout.split() == ["1", "2", "3", "4", "5"]
    got = run_tshark(capture, *PLC, "-T", "fields", "-e", "_ws.col.Info", "-c", "2")
    assert got.stdout.splitlines() == ["1 Read Holding Registers request 465535..465538 (4)",
                                       "1 Read Holding Registers response 465535..465538 (4)"]
