"""A packet dump with each packet's details (tshark -V -x, Wireshark's Export Packet Dissections as plain text)
says each packet's time, `Epoch Time: 1767225600.123456789 seconds` (Wireshark 4.2 on: `Epoch Arrival Time`):
its packets are timed by it, to the nanosecond, as the pcap it came from (hunt64). Before, the export was
read untimed: no time column, no response time ([#1], not [#1, 10.2 ms]), --stats without response times,
where the same capture's pcap had them all."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli

# tshark 4.0.17 -V -x of a nanosecond pcap (linktype 147, no DLT_USER mapping: its bytes as Data), a read
# of CHCF (8401) and its answer 10.157321 ms later
EXPORT = "".join(
    f"Frame {number}: {size} bytes on wire ({8 * size} bits), {size} bytes captured ({8 * size} bits)\n"
    "    Encapsulation type: USER 0 (45)\n"
    f"    Arrival Time: Jan  1, 2026 00:00:00.{epoch[-9:]} UTC\n"
    "    [Time shift for this packet: 0.000000000 seconds]\n"
    f"    Epoch Time: {epoch} seconds\n"
    f"    Frame Number: {number}\n"
    "User encapsulation not handled: DLT=147, check your Preferences->Protocols->DLT_USER\n"
    f"Data ({size} bytes)\n"
    f"    Data: {data.replace(' ', '')}\n"
    f"    [Length: {size}]\n"
    "\n"
    f"0000  {data}{' ' * (3 * (16 - size) + 2)}{chars}\n"
    "\n"
    for number, size, epoch, data, chars in [
        (1, 8, "1767225600.123456789", "0c 03 20 d1 00 01 de ee", ".. ....."),
        (2, 7, "1767225600.133614110", "0c 03 02 00 03 d5 84", "......."),
    ])
TIMED = ["     1  0.000000000  12 request   Read Holding Registers 8401  CRC ok",
         "     2  0.010157321  12 response  Read Holding Registers 8401: 8401=3 [#1, 10.2 ms]  CRC ok"]


def test_epoch_time_times_its_packet(tmp_path: Path) -> None:
    export = tmp_path / "export.txt"
    export.write_text(EXPORT)
    assert run_cli(["-n", str(export)]) == (0, "\n".join(TIMED) + "\n", "")
    status, out, err = run_cli(["-n", "-T", "fields", "-e", "time", "-e", "response_time", str(export)])
    assert (status, out, err) == (0, "1767225600.123456789\t\n1767225600.133614110\t0.010157321\n", "")


def test_wireshark_4_2_names_it_epoch_arrival_time(tmp_path: Path) -> None:
    export = tmp_path / "export.txt"
    export.write_text(EXPORT.replace("Epoch Time:", "Epoch Arrival Time:"))
    assert run_cli(["-n", str(export)])[1] == "\n".join(TIMED) + "\n"


@pytest.mark.parametrize("kept", [1, 2])
def test_a_packet_without_its_time_is_untimed(kept: int, tmp_path: Path) -> None:
    """(the time is the one given in the packet's own details, never the one before's)"""
    export = tmp_path / "export.txt"
    lines = EXPORT.splitlines(keepends=True)
    epochs = [index for index, line in enumerate(lines) if "Epoch Time" in line]
    del lines[epochs[2 - kept]]
    export.write_text("".join(lines))
    status, out, err = run_cli(["-n", "-T", "fields", "-e", "frame", "-e", "time", str(export)])
    assert (status, err) == (0, "")
    assert out == ("1\t1767225600.123456789\n2\t\n" if kept == 1 else "1\t\n2\t1767225600.133614110\n")


def test_bytes_alone_stay_untimed(tmp_path: Path) -> None:
    """tshark -x without -V says no time: untimed, as before."""
    export = tmp_path / "bytes.txt"
    export.write_text("".join(line for line in EXPORT.splitlines(keepends=True) if line.startswith("0000")))
    assert run_cli(["-n", str(export)])[1].splitlines()[1] == (
        "     2            -  12 response  Read Holding Registers 8401: 8401=3 [#1]  CRC ok")


@pytest.mark.parametrize("capture", ["p38_protection.pcap", "noisy_bus.pcap"])
def test_own_details_and_bytes_read_back_as_the_capture(capture: str, tmp_path: Path) -> None:
    """vw3-decode -V -x says each item's `Arrival time: 2026-01-01 00:00:00.010157 UTC (...)`: read back, its
    items are the capture's, times and response times included (before: untimed, '[#1]')."""
    from conftest import ROOT

    path = str(ROOT / "captures" / capture)
    status, dump, err = run_cli(["-V", "-x", path])
    assert (status, err) == (0, "")
    export = tmp_path / "details.txt"
    export.write_text(dump)
    assert run_cli(["--json", str(export)]) == run_cli(["--json", path])


def test_a_date_that_does_not_exist_times_nothing(tmp_path: Path) -> None:
    export = tmp_path / "details.txt"
    export.write_text("Frame 1: 8 bytes at offset 0, request (RTU)\n"
                      "    Arrival time: 2026-02-30 00:00:00.000000 UTC (0.000000 s since the first item)\n"
                      "0000  0c 03 20 d1 00 01 de ee                           .. .....\n")
    assert run_cli(["-n", "-T", "fields", "-e", "frame", "-e", "time", str(export)]) == (0, "1\t\n", "")


def test_a_noise_item_says_its_arrival_time_too() -> None:
    """-V gave a frame its `Arrival time` line and a noise item none, though its time is in the summary and
    --json (noisy_bus.pcap's item 1 at 0.000000): each item is a packet, timed as tshark -V times each."""
    from conftest import ROOT

    out = run_cli(["-V", "-c", "1", str(ROOT / "captures" / "noisy_bus.pcap")])[1]
    assert out.splitlines()[:4] == [
        "Item 1: noise, 4 bytes at offset 0",
        "    Arrival time: 2026-01-01 00:00:00.006072 UTC (0.000000 s since the first item)",
        "    4 bytes of noise at offset 0: 00 ff ff f0",
        "    Reason: no valid frame"]
