"""Inputs that sniffers and masters write (issue 15): xxd and hexdump -C dumps made by the real tools,
Modbus Poll / Modbus Slave traffic logs, detected from the content. Vectors: the p.38 seed frames."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from helpers import run_cli
from lua_harness import ensure_tool

ROOT = Path(__file__).resolve().parents[2]
P38_BIN = ROOT / "captures" / "p38_protection.bin"
REQUEST = "0C 03 20 D0 00 03 0E EF"
RESPONSE = "0C 03 06 80 00 00 03 00 02 17 E4"
EXCEPTION = "0C 83 02 51 32"


def _decoded(path: Path) -> str:
    status, out, err = run_cli([str(path)])
    assert (status, err) == (0, ""), err
    return out


@pytest.mark.parametrize(
    ("tool", "package", "options"),
    [
        ("xxd", "xxd", []),
        ("xxd", "xxd", ["-u", "-g", "1"]),
        ("xxd", "xxd", ["-a"]),  # squeezes the zero lines into *
        ("hexdump", "bsdextrautils", ["-C"]),  # squeezes repeated lines into * by default
    ],
)
def test_dumps_of_the_real_tools_decode_as_the_bytes(tmp_path: Path, tool: str, package: str, options: list[str]) -> None:
    binary = tmp_path / "capture.bin"
    # zero lines first, so that both tools squeeze them (and the reader must expand the *)
    binary.write_bytes(bytes(100) + P38_BIN.read_bytes())
    dump = tmp_path / "capture.dump"
    dump.write_bytes(subprocess.run([ensure_tool(tool, package), *options, str(binary)], check=True,
                                    capture_output=True).stdout)
    if "-a" in options or tool == "hexdump":
        assert b"\n*\n" in dump.read_bytes()
    assert _decoded(dump) == _decoded(binary)
    assert "noise     100 bytes of noise at offset 0" in _decoded(dump)


def test_a_dump_with_a_line_missing_is_refused(tmp_path: Path) -> None:
    dump = tmp_path / "cut.xxd"
    lines = subprocess.run([ensure_tool("xxd", "xxd"), str(P38_BIN)], check=True, capture_output=True,
                           text=True).stdout.splitlines()
    dump.write_text("\n".join(lines[:2] + lines[3:]) + "\n")
    status, out, err = run_cli([str(dump)])
    assert status == 2
    assert err == f"vw3-decode: {dump} line 3: offset 0x30 where 0x20 was expected (bytes missing or repeated)\n"


TRAFFIC_FORMS = [
    # older Modbus Poll: direction, then the counter
    f"Tx:000000-{REQUEST}\nRx:000001-{RESPONSE}\n",
    # newer: counter, then the direction
    f"000000-Tx:{REQUEST}\n000001-Rx:{RESPONSE}\n",
    # short counters, Windows line ends
    f"000-Tx:{REQUEST}\r\n001-Rx:{RESPONSE}\r\n",
]


@pytest.mark.parametrize("log", TRAFFIC_FORMS)
def test_modbus_poll_traffic_logs(tmp_path: Path, log: str) -> None:
    path = tmp_path / "traffic.txt"
    path.write_text(log, newline="")
    assert _decoded(path).splitlines() == [
        "     1            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
        # (one answer is no evidence of an ATV71 under profile auto: issue 26)
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#1]  CRC ok",
    ]


@pytest.mark.parametrize(
    "log",
    [
        f"Tx:000000-10:15:30.125-{REQUEST}\nRx:000001-10:15:30.136-{RESPONSE}\n",
        f"000000-[10:15:30.125]-Tx:{REQUEST}\n000001-[10:15:30.136]-Rx:{RESPONSE}\n",
        f"000000-2026-01-01 10:15:30.125-Tx:{REQUEST}\n000001-2026-01-01 10:15:30.136-Rx:{RESPONSE}\n",
    ],
)
def test_traffic_logs_with_time_stamps(tmp_path: Path, log: str) -> None:
    path = tmp_path / "traffic.log"
    path.write_text(log)
    lines = _decoded(path).splitlines()
    assert lines[1].startswith("     2     0.011000  12 response")
    assert lines[1].endswith("[#1, 11.0 ms]  CRC ok")


def test_a_slave_simulator_log_with_a_timeout_line_and_an_exception(tmp_path: Path) -> None:
    # Modbus Slave logs what it received (Rx, the requests) and sent (Tx); a line without bytes is skipped
    path = tmp_path / "slave.txt"
    path.write_text(f"Rx:000000-{REQUEST}\nTx:000001-{EXCEPTION}\nRx:000002-\n")
    lines = _decoded(path).splitlines()
    assert len(lines) == 2
    assert lines[1].startswith("     2            -  12 exception Read Holding Registers: exception 2")


def test_a_bad_traffic_line_is_named(tmp_path: Path) -> None:
    path = tmp_path / "traffic.txt"
    path.write_text(f"Tx:000000-{REQUEST}\nRx:000001-{RESPONSE}\nRx:000002-0C 03 0\n")
    status, out, err = run_cli(["--format", "traffic", str(path)])
    assert status == 2
    assert err.endswith(f"vw3-decode: {path} line 3: not a Tx:/Rx: traffic line: 'Rx:000002-0C 03 0'\n")


def test_a_midnight_time_stamp_is_a_time(tmp_path: Path) -> None:
    path = tmp_path / "midnight.txt"
    path.write_text(f"000000-Tx:00:00:00.000-{REQUEST}\n000001-Rx:00:00:00.011-{RESPONSE}\n")
    assert _decoded(path).splitlines()[1].endswith("[#1, 11.0 ms]  CRC ok")


def test_lines_of_spaces_are_refused_at_once(tmp_path: Path) -> None:
    # Regression: one regular expression with optional parts on both sides of Tx: backtracked
    # exponentially on such a line (51 s at 200 spaces); the reader now cuts the line in steps.
    path = tmp_path / "spaces.txt"
    path.write_text(f"Tx:000000-{REQUEST}\n" + " " * 2000 + "Tx:" + " " * 2000 + "0\n")
    status, _out, err = run_cli(["--format", "traffic", str(path)])
    assert status == 2 and "line 2: not a Tx:/Rx: traffic line" in err
