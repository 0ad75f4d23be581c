"""-Y and -T fields as Wireshark 4.0 has them (session 54's hunt, defects 5, 6a, 9, 10): the frames each
filter selects on the shipped captures, checked with tshark 4.0.17 running the plugin (`vw3.*`) or on
tshark's own `frame` fields, and the exact text -T fields writes."""
from __future__ import annotations

import pytest

from helpers import run_cli

from conftest import ROOT

NOISY = str(ROOT / "captures" / "noisy_bus.pcap")
ATV71 = str(ROOT / "captures" / "atv71_commissioning.pcap")
SEL = str(ROOT / "captures" / "sel749m_polling.pcap")


def frames(expression: str, *inputs: str) -> list[int]:
    status, out, err = run_cli(["-Y", expression, "-T", "fields", "-e", "frame", *inputs])
    assert (status, err) == (0, ""), err
    return [int(line) for line in out.split()]


ALL_NOISY = list(range(1, 39))
NOISE = [1, 34]


@pytest.mark.parametrize(("expression", "expected"), [
    # A bare field tests presence (tshark -Y vw3.crc_ok: 36 frames, !vw3.crc_ok: 1 34): frame 17's bad CRC
    # has a crc_ok, false. Before: "present and not false", 35 and 1 17 34.
    ("crc_ok", [n for n in ALL_NOISY if n not in NOISE]),
    ("not crc_ok", NOISE),
    ("!crc_ok", NOISE),
    ("crc_ok == 1", [n for n in ALL_NOISY if n not in (*NOISE, 17)]),
    ("crc_ok == 0", [17]),
    # The plugin adds vw3.unanswered and vw3.broadcast only where true (tshark -2 -Y vw3.unanswered: 28 29;
    # vw3.unanswered == 0 and vw3.broadcast: none)
    ("unanswered", [28, 29]),
    ("not unanswered", [n for n in ALL_NOISY if n not in (28, 29)]),
    ("unanswered == 0", []),
    ("broadcast", []),
    ("!broadcast", ALL_NOISY),
    ("broadcast == false", []),
])
def test_a_bare_field_tests_its_presence(expression: str, expected: list[int]) -> None:
    assert frames(expression, NOISY) == expected


def test_a_crc_typed_nowhere_is_no_crc_ok() -> None:
    typed = ["--hex", "0C 03 20 D0 00 03"]
    assert frames("crc_ok", *typed) == []
    assert frames("!crc_ok", *typed) == [1]
    assert frames("crc_typed == 0", *typed) == [1]
    assert frames("crc_ok", "--hex", "0C 03 20 D0 00 03 0E EE") == [1]  # a bad CRC typed: checked


def test_time_is_written_as_tshark_writes_frame_time_epoch() -> None:
    # tshark -r atv71_commissioning.pcap -c 3 -T fields -e frame.time_epoch -e frame.time_relative
    # -e vw3.response_time (before: 1767225600.00659 then 1767225600.052897)
    status, out, err = run_cli([ATV71, "-c", "3", "-T", "fields", "-e", "time", "-e", "time_relative",
                                "-e", "response_time"])
    assert (status, err) == (0, "")
    assert out == ("1767225600.006590000\t0.000000000\t\n"
                   "1767225600.017320000\t0.010730000\t0.010730000\n"
                   "1767225600.052897000\t0.046307000\t\n")
    assert run_cli(["--hex", "01 06 00 20 3F 00", "-T", "fields", "-e", "time", "-e", "frame"])[1] == "\t1\n"
