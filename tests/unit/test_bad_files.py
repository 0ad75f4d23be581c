"""Bad files through the real command (`python3 -m dissector`, from the repo root): a clear one-line
message, the documented exit status, no traceback, and bounded memory on a 2 GB input.

Exit statuses (README "Errors"): 2 for an input that cannot be read at all; 0 for an empty file and
for a capture that is damaged but readable (a cut last record, unknown pcapng blocks): what is there
is decoded and a warning on stderr says what was wrong, as tshark does for a cut capture.
"""
from __future__ import annotations

import json
import io
import os
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from dissector.app.cli import Environment, run

from helpers import hx

ROOT = Path(__file__).resolve().parents[2]
PROG = "vw3-decode: "

REQUEST = hx("0C 03 20 D0 00 03 0E EF")
RESPONSE = hx("0C 03 06 80 00 00 03 00 02 17 E4")
EXCEPTION = hx("0C 83 02 51 32")
T0 = 1_700_000_000


def cli(*args: str, stdin: bytes | None = None, timeout: float = 60) -> tuple[int, list[str], list[str]]:
    done = subprocess.run(
        [sys.executable, "-m", "dissector", *args], cwd=ROOT, input=stdin, capture_output=True,
        timeout=timeout,
    )
    out = done.stdout.decode()
    err = done.stderr.decode()
    assert "Traceback" not in err and "Traceback" not in out
    lines = err.splitlines()
    assert all(line.startswith(PROG) for line in lines), lines
    return done.returncode, out.splitlines(), lines


def pcap(records: list[bytes], linktype: int = 147) -> bytes:
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, linktype)
    for index, data in enumerate(records):
        out += struct.pack("<IIII", T0 + index, 0, len(data), len(data)) + data
    return out


def block(block_type: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack("<II", block_type, len(body) + 12) + body + struct.pack("<I", len(body) + 12)


def pcapng(blocks: list[bytes]) -> bytes:
    head = block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    return head + block(1, struct.pack("<HHI", 147, 0, 0)) + b"".join(blocks)


def epb(data: bytes, seconds: int) -> bytes:
    stamp = seconds * 1_000_000
    return block(6, struct.pack("<IIIII", 0, stamp >> 32, stamp & 0xFFFFFFFF, len(data), len(data)) + data)


# -- damaged but readable: decoded, with a warning -------------------------------------------------
def test_truncated_pcap_record_is_decoded_up_to_the_cut_with_a_warning(tmp_path: Path) -> None:
    path = tmp_path / "cut.pcap"
    path.write_bytes(pcap([REQUEST, RESPONSE, REQUEST])[:-3])  # the last record loses 3 of 8 bytes
    status, out, err = cli(str(path), "-n")
    assert status == 0
    assert out == [
        "     1     0.000000  12 request   Read Holding Registers 8400..8402 (3)  CRC ok",
        "     2     1.000000  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 "
        "[#1, 1000.0 ms]  CRC ok",
        "     3     2.000000   - noise     5 bytes of noise at offset 19: 0c 03 20 d0 00",
    ]
    assert err == [f"{PROG}warning: record 3 is cut short: 5 of 8 bytes (the capture ends inside it); "
                   "the bytes that are there are decoded"]


def test_pcap_cut_inside_a_record_header(tmp_path: Path) -> None:
    path = tmp_path / "cut.pcap"
    path.write_bytes(pcap([REQUEST, RESPONSE])[: 24 + 16 + 8 + 5])
    status, out, err = cli(str(path), "-n")
    assert status == 0 and len(out) == 1
    assert err == [f"{PROG}warning: record 2: the capture ends inside its header (5 of 16 bytes)"]


def test_pcapng_with_unknown_blocks_decodes_the_packets_and_counts_the_blocks(tmp_path: Path) -> None:
    unknown = [block(0x1234, b"x" * index) for index in range(7)]
    path = tmp_path / "odd.pcapng"
    path.write_bytes(pcapng([unknown[0], epb(REQUEST, T0), *unknown[1:], epb(EXCEPTION, T0 + 1)]))
    status, out, err = cli(str(path), "-n")
    assert status == 0
    assert [line.split()[3] for line in out] == ["request", "exception"]
    assert err[0] == f"{PROG}warning: skipped a pcapng block of unknown type 0x00001234 at byte 48"
    assert len(err) == 6 and err[5] == f"{PROG}warning: ... and 2 more pcapng blocks of type 0x1234"


def test_empty_file_is_no_frames(tmp_path: Path) -> None:
    path = tmp_path / "empty.bin"
    path.write_bytes(b"")
    assert cli(str(path)) == (0, [], [f"{PROG}warning: {path}: the input is empty"])


# -- unreadable: one line, exit 2 -------------------------------------------------------------------
@pytest.mark.parametrize(
    ("content", "fmt", "message"),
    [
        (b"garbage, not a capture", "pcap", "not a pcap file (magic 67617262)"),
        (b"", "pcap", "not a pcap file (magic missing)"),
        (pcap([REQUEST])[:10], None, "truncated pcap file header (10 of 24 bytes)"),
        (pcap([REQUEST], linktype=1), None,  # (RTU over TCP/UDP is read on the ports given: none here)
         "Ethernet (linktype 1): no TCP or UDP payload on the Modbus RTU ports (none given: --tcp-port and "
         "--udp-port, as the plugin's vw3.tcp_port and vw3.udp_port preferences, set them); its 1 packet: 1 not IP"),
        (pcap([REQUEST], linktype=105), None,
         "linktype 105 (not a serial line) carries no serial bytes; supported: 147 (USER0) and 250 (RTAC serial); "
         "Modbus RTU over TCP/UDP from 0, 1, 101, 113, 228, 229 and 276 (network links)"),
        (pcap([REQUEST]), "pcapng", "not a pcapng file (no section header block)"),
        (b"\x28\xb5\x2f\xfdrest", None, "compressed input (zstd): decompress it first (`zstd -d FILE`)"),
    ],
)
def test_unreadable_captures(tmp_path: Path, content: bytes, fmt: str | None, message: str) -> None:
    path = tmp_path / "capture"
    path.write_bytes(content)
    status, out, err = cli(str(path), *(["--format", fmt] if fmt else []))
    assert (status, out, err) == (2, [], [f"{PROG}{path}: {message}"])


def test_hex_dump_with_a_timestamp_no_float_holds(tmp_path: Path) -> None:
    # Regression (fuzzing): 400 digits made the time inf, and --json printed "time": Infinity.
    path = tmp_path / "stamps.hex"
    path.write_text("1" * 400 + ".5 0C 03 20 D0 00 03 0E EF\n")
    status, out, err = cli(str(path), "--format", "hex", "--json")
    assert (status, out) == (2, [])
    assert err == [f"{PROG}{path} line 1: timestamp {'1' * 24}... is out of range"]


def test_pcapng_block_with_a_corrupt_length(tmp_path: Path) -> None:
    data = bytearray(pcapng([epb(REQUEST, T0)]))
    data[52:56] = struct.pack("<I", 13)  # the EPB's total length: not a multiple of 4
    path = tmp_path / "corrupt.pcapng"
    path.write_bytes(bytes(data))
    status, out, err = cli(str(path))
    assert (status, out) == (2, [])
    assert err == [f"{PROG}{path}: block at byte 48 has an invalid length 13 (corrupt file?)"]


def test_a_directory(tmp_path: Path) -> None:
    assert cli(str(tmp_path)) == (2, [], [f"{PROG}{tmp_path}: is a directory, not a capture"])


def test_a_missing_file(tmp_path: Path) -> None:
    path = tmp_path / "nowhere.bin"
    assert cli(str(path)) == (2, [], [f"{PROG}{path}: no such file"])


def test_a_file_that_cannot_be_read() -> None:
    # chmod 000 does not stop root (these tests run as root in CI), so a file that opens but whose
    # read fails: /proc/self/mem (the reader's own memory at address 0 is unmapped: EIO).
    assert cli("/proc/self/mem") == (2, [], [f"{PROG}/proc/self/mem: cannot read: Input/output error"])


def test_a_file_without_read_permission(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # chmod 000 does not stop root (CI runs as root): the refusal is made by the opening itself.
    path = tmp_path / "secret.bin"
    path.write_bytes(REQUEST)
    real_open = open

    def refusing_open(file, *args, **kwargs):  # type: ignore[no-untyped-def]
        if str(file) == str(path):
            raise PermissionError(13, "Permission denied", str(file))
        return real_open(file, *args, **kwargs)

    monkeypatch.setattr("builtins.open", refusing_open)
    err = io.StringIO()
    env = Environment(io.BytesIO(), io.StringIO(), err, stdout_isatty=False, stderr_isatty=False)
    assert run([str(path)], env) == 2
    assert err.getvalue() == f"{PROG}{path}: permission denied\n"


# -- a FIFO: read as it comes -----------------------------------------------------------------------
def test_a_fifo_fed_by_a_writer(tmp_path: Path) -> None:
    fifo = tmp_path / "bus"
    os.mkfifo(fifo)
    stream = REQUEST + RESPONSE + REQUEST + EXCEPTION

    def writer() -> None:
        with open(fifo, "wb", buffering=0) as pipe:  # blocks until the reader opens it
            for start in range(0, len(stream), 5):
                pipe.write(stream[start : start + 5])
                time.sleep(0.01)

    thread = threading.Thread(target=writer, daemon=True)
    thread.start()
    status, out, err = cli(str(fifo), "-n", timeout=30)
    thread.join(5)
    assert (status, err) == (0, [])
    assert [line.split()[3] for line in out] == ["request", "response", "request", "exception"]
    assert out[3].endswith("Read Holding Registers: exception 2 (Illegal Data Address) [#3]  CRC ok")


# -- 2 GB: memory stays bounded --------------------------------------------------------------------
RUN_SECONDS = 12
# Runs the decoder for RUN_SECONDS, interrupts it as Ctrl-C would, and prints its peak RSS measured
# by getrusage: in a wrapper process of its own, so no other child of the test run counts.
WRAPPER = """
import resource, signal, subprocess, sys, time
child = subprocess.Popen([sys.executable, "-m", "dissector", *sys.argv[2:]], stdout=open(sys.argv[1], "wb"),
                         stderr=subprocess.PIPE)
time.sleep(%d)
child.send_signal(signal.SIGINT)
_, err = child.communicate(timeout=30)
sys.stderr.buffer.write(err)
print(child.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
""" % RUN_SECONDS


def _bounded_run(tmp_path: Path, *args: str) -> tuple[int, int, list[str], list[dict]]:
    """(exit status, peak RSS in kB, stderr lines, NDJSON items) of an interrupted run."""
    out = tmp_path / "out.json"
    done = subprocess.run(
        [sys.executable, "-c", WRAPPER, str(out), "-n", "--json", *args], cwd=ROOT, capture_output=True,
        timeout=RUN_SECONDS + 60,
    )
    status, peak_kb = map(int, done.stdout.split())
    err = done.stderr.decode()
    assert "Traceback" not in err
    items = []
    for line in out.read_text().splitlines():
        try:
            items.append(json.loads(line))
        except json.JSONDecodeError:
            break  # the last line may be cut by the interruption
    return status, peak_kb, err.splitlines(), items


def test_a_2gb_sparse_file_streams_in_bounded_memory(tmp_path: Path) -> None:
    path = tmp_path / "sparse.bin"
    with open(path, "wb") as handle:
        handle.truncate(2 << 30)
    status, peak_kb, err, items = _bounded_run(tmp_path, str(path))
    assert status == 130 and err == [f"{PROG}interrupted"]
    assert peak_kb < 100 * 1024, f"peak RSS {peak_kb} kB"
    # It was decoding all along: 4 KiB noise items, in order, several megabytes in.
    assert len(items) > 500
    assert {(item["kind"], item["length"]) for item in items} == {("noise", 4096)}
    assert items[-1]["offset"] == 4096 * (len(items) - 1)


def test_a_pcap_record_claiming_2gb_streams_in_bounded_memory(tmp_path: Path) -> None:
    path = tmp_path / "huge-record.pcap"
    size = (2 << 30) - 1
    with open(path, "wb") as handle:
        handle.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 0xFFFFFFFF, 147))
        handle.write(struct.pack("<IIII", T0, 0, size, size) + REQUEST)
        handle.truncate(24 + 16 + size)
    status, peak_kb, err, items = _bounded_run(tmp_path, str(path))
    assert status == 130 and err == [f"{PROG}interrupted"]
    assert peak_kb < 100 * 1024, f"peak RSS {peak_kb} kB"
    assert items[0]["kind"] == "request" and items[0]["time"] == T0
    assert len(items) > 500 and items[1]["kind"] == "noise"


@pytest.mark.parametrize(
    ("option", "message"),
    [
        (["--baud", "0"], "argument --baud: 0 baud is no Modbus serial line speed (50..4,000,000)"),
        (["--baud", "fast"], "argument --baud: 'fast' is not a whole number of baud"),
        # issue 29: 10**20 baud was taken (a t3.5 of 0); a Modbus serial line runs at 50..4,000,000 baud
        (["--baud", "99999999999999999999"],
         "argument --baud: 99999999999999999999 baud is no Modbus serial line speed (50..4,000,000)"),
        (["--baud", "49"], "argument --baud: 49 baud is no Modbus serial line speed (50..4,000,000)"),
        (["--live", "loop://", "--baud", "4000001"],
         "argument --baud: 4000001 baud is no Modbus serial line speed (50..4,000,000)"),
        (["--live", "loop://", "--duration", "nan"], "argument --duration: 'nan' must be a number of seconds more than 0"),
        (["--live", "loop://", "--count", "-1"], "argument -c/--count: '-1' must be more than 0"),
        (["--live", "loop://", "--detect", "0"], "argument --detect: '0' must be a number of seconds more than 0"),
    ],
)
def test_nonsense_line_settings_are_usage_errors(tmp_path: Path, option: list[str], message: str) -> None:
    # Regression (fuzzing the options): --baud 0 divided by zero in the gap check of a frame that
    # spans two pcap records, a traceback.
    path = tmp_path / "split.pcap"
    path.write_bytes(pcap([REQUEST[:3], REQUEST[3:]]))
    done = subprocess.run([sys.executable, "-m", "dissector", str(path), *option], cwd=ROOT,
                          capture_output=True, timeout=60)
    err = done.stderr.decode().splitlines()
    assert (done.returncode, done.stdout) == (2, b"")
    assert err == [f"vw3-decode: {message} (see vw3-decode --help)"]  # one line, no usage text


def test_a_2gb_map_is_refused_without_reading_it(tmp_path: Path) -> None:
    # Regression: --map read the whole file into memory before parsing it.
    path = tmp_path / "huge.csv"
    with open(path, "wb") as handle:
        handle.truncate(2 << 30)
    started = time.monotonic()
    status, out, err = cli(str(ROOT / "captures" / "p38_protection.bin"), "--map", str(path), timeout=30)
    assert (status, out) == (2, [])
    assert err == [f"{PROG}{path}: larger than 16 MiB, not a register map"]
    assert time.monotonic() - started < 10


# -- outputs that fail -------------------------------------------------------------------------------
def _run_raw(command: list[str], **options: object) -> tuple[int, str]:
    done = subprocess.run(command, cwd=ROOT, stderr=subprocess.PIPE, timeout=60, **options)  # type: ignore[call-overload]
    return done.returncode, done.stderr.decode()


@pytest.mark.parametrize("where", ["-w", "stdout", "stats"])
def test_an_output_that_cannot_be_written_is_one_line_and_status_1(where: str) -> None:
    # README: exit 1 for "an output that cannot be written". /dev/full fails every write with ENOSPC;
    # today the error escapes from Sinks.close() (called in decode_files' finally, outside its
    # `except OSError`) as a traceback.
    capture = str(ROOT / "captures" / "p38_protection.bin")
    if where == "-w":
        status, err = _run_raw([sys.executable, "-m", "dissector", capture, "-w", "/dev/full"])
    else:
        with open("/dev/full", "w") as full:
            extra = ["--stats"] if where == "stats" else []
            status, err = _run_raw([sys.executable, "-m", "dissector", capture, *extra], stdout=full)
    assert "Traceback" not in err
    assert status == 1
    (line,) = err.splitlines()
    assert line.startswith(PROG) and "No space left on device" in line


@pytest.mark.parametrize("closed", ["<&-", ">&-"])
def test_a_closed_standard_stream_is_no_traceback(closed: str) -> None:
    # Started from a daemon or cron with fd 0 or 1 closed, Python sets sys.stdin / sys.stdout to
    # None; Environment.from_process() then fails with AttributeError on `.buffer` / `.isatty()`,
    # even when stdin is not used (a file argument). Expected: decode a file without stdin; with
    # stdout closed, one line on stderr and status 1.
    capture = str(ROOT / "captures" / "p38_protection.bin")
    status, err = _run_raw(["sh", "-c", f'exec "$0" -m dissector "$1" {closed}', sys.executable, capture],
                           stdout=subprocess.DEVNULL if closed == "<&-" else None)
    assert "Traceback" not in err
    if closed == "<&-":
        assert (status, err) == (0, "")
    else:
        (line,) = err.splitlines()
        assert status == 1 and line.startswith(PROG)
