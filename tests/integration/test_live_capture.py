"""Issue 14: a capture that never loses a byte, whose every line is final, and its files.

On a pseudo-terminal bus (tests/support/live_bus.py): a stream at line rate into a sniffer whose
output nobody reads; pymodbus master and slave, live --json against the decode of the -w file; -w -
into tshark; the ring buffer; pcapng written live, read back by vw3-decode and tshark.
"""
from __future__ import annotations

import argparse
import io
import json
import os
import re
import signal
import statistics
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from dissector.app import live_view
from dissector.app.live import run_live
from dissector.protocol.crc import with_crc
from dissector.render.summary import summary_line
from live_bus import ROOT, Bus, PymodbusSlave, Sniffer, byte_records, our_master, paced_writer, read_pcap, transactions
from lua_harness import ensure_tool

pytestmark = pytest.mark.integration
BAUD = 115200
USER0 = 'uat:user_dlts:"User 0 (DLT=147)","mbrtu","0","","0",""'
# What a live line and the decode of the -w file must agree on (the list), and the rest.
KEYS = ("frame", "kind", "raw", "slave", "function", "request_frame", "response_frame", "unanswered",
        "response_time")


def need_tshark() -> str:
    """tshark, installed when missing (never a silent skip)."""
    return ensure_tool("tshark", "tshark")


def tshark(*args: str, stdin: bytes | None = None) -> list[str]:
    done = subprocess.run(
        [need_tshark(), "-o", USER0, "-o", "mbrtu.crc_verification:TRUE", *args],
        input=stdin, capture_output=True, timeout=120,
    )
    assert done.returncode == 0, done.stderr.decode()
    return done.stdout.decode().splitlines()


def decode_file(path: Path, *options: str) -> list[dict]:
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", "--json", *options, str(path)],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return [json.loads(line) for line in done.stdout.splitlines()]


def start(path: str, *options: str) -> subprocess.Popen[bytes]:
    """vw3-decode --live, its stdout a pipe the test reads only when it chooses to."""
    process = subprocess.Popen(
        [sys.executable, "-m", "dissector", "--live", path, "-n", "--baud", str(BAUD), *options],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )
    assert process.stderr is not None
    assert process.stderr.readline().startswith(b"vw3-decode: listening on ")
    return process


def test_output_nobody_reads_loses_no_byte(tmp_path: Path) -> None:
    """116 KB at 115200 baud (11 s) while vw3-decode's stdout is not read: 0 bytes lost at the port,
    the -w file holds every byte before the test reads a line, and every line is then the file's."""
    stream = transactions(3000, seed=21)
    assert len(stream) > 110_000
    bus = Bus(slave=False)
    pcap, raw = tmp_path / "tap.pcap", tmp_path / "tap.bin"
    process = start(bus.c_path, "--json", "-w", str(pcap), "--raw", str(raw))
    try:
        started = time.monotonic()
        lost = paced_writer(bus.c, stream, BAUD)
        seconds = time.monotonic() - started
        time.sleep(0.5)  # the last frame is closed by the silence
        records = [record for _, record in read_pcap(pcap)]  # stdout still unread
        on_disk = raw.read_bytes()
        assert process.stdout is not None
        chunks: list[bytes] = []
        reader = threading.Thread(target=lambda: chunks.append(process.stdout.read()))  # type: ignore[union-attr]
        reader.start()
        time.sleep(1.0)
        process.send_signal(signal.SIGINT)
        status = process.wait(30)
        reader.join(30)
        stderr = process.stderr.read().decode()  # type: ignore[union-attr]
    finally:
        bus.close()
    print(f"\n{len(stream)} bytes in {seconds:.1f} s, stdout unread: {lost} bytes lost at the port, "
          f"{sum(map(len, records))} bytes in -w")
    assert lost == 0
    assert b"".join(records) == stream and on_disk == stream
    assert status == 0, stderr
    assert "6000 frames (3000 requests, 3000 responses, 0 exceptions)" in stderr
    live = [json.loads(line) for line in chunks[0].decode().splitlines()]
    assert live == decode_file(pcap)  # every key of every line, the time to the microsecond included


def test_display_that_falls_behind_drops_lines_not_bytes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A tiny display queue and an unread pipe: lines are dropped and counted, the files hold them."""
    monkeypatch.setattr(live_view, "PUMP_LIMIT", 50)
    stream = transactions(600, seed=22)
    bus = Bus(slave=False)
    pcap = tmp_path / "behind.pcap"
    read_end, write_end = os.pipe()
    out = os.fdopen(write_end, "w")
    err = io.StringIO()
    args = argparse.Namespace(
        live=bus.c_path, baud=BAUD, parity="E", stopbits=1, bytesize=8, raw=None, duration=None,
        count=None, detect=None, write=str(pcap), json=True, timeout=1.0, ring=None, file_format=None,
    )
    statuses: list[int] = []
    runner = threading.Thread(target=lambda: statuses.append(run_live(args, out, err, False, summary_line, None)))
    args.duration = len(stream) * 11 / BAUD + 1.0
    runner.start()
    try:
        time.sleep(0.3)
        assert paced_writer(bus.c, stream, BAUD) == 0  # the pipe is not read meanwhile
        chunks = bytearray()

        def read_all() -> None:
            while piece := os.read(read_end, 1 << 20):
                chunks.extend(piece)

        reader = threading.Thread(target=read_all)
        reader.start()
        runner.join(30)
        out.close()
        reader.join(10)
    finally:
        os.close(read_end)
        bus.close()
    assert statuses == [0], err.getvalue()
    shown = [json.loads(line) for line in chunks.decode().splitlines()]
    kept = decode_file(pcap)
    assert b"".join(bytes.fromhex(item["raw"]) for item in kept) == stream
    summary = err.getvalue().splitlines()[-1]
    match = re.search(r"; (\d+) items not shown \(the display fell behind\), the capture files hold them$", summary)
    assert match, summary
    assert len(shown) + int(match.group(1)) == len(kept) == 1200
    by_number = {item["frame"]: item for item in kept}
    assert all(item == by_number[item["frame"]] for item in shown)  # what is shown is still final


def final_latencies(lines: list[tuple[float, str]], bus: Bus, timeout: float) -> list[float]:
    """Seconds from the moment a line became final (its last byte, its response's last byte, or its
    timeout) to the line; offsets index the sniffer's byte stream."""
    items = [json.loads(line) for _, line in lines]
    by_number = {item["frame"]: item for item in items}
    figures = []
    for (stamp, _), item in zip(lines, items):
        end = item
        if item.get("response_frame") is not None:
            end = by_number[item["response_frame"]]
        final = bus.relay.time_of_byte(end["offset"] + end["length"] - 1)
        if item.get("unanswered"):
            final = item["time"] + timeout
        figures.append(stamp - final)
    return figures


def test_pymodbus_live_json_equals_the_decode_of_its_file(tmp_path: Path) -> None:
    import pymodbus.client as pymodbus_client  # a test extra: missing it is a failure, not a skip
    from pymodbus.exceptions import ModbusIOException

    bus = Bus(slave=False, seed=6)
    slave = PymodbusSlave(bus.b_path)
    slave.start()
    assert slave.ready.wait(10)
    time.sleep(0.2)
    pcap = tmp_path / "pymodbus.pcap"
    sniffer = Sniffer.start(bus.c_path, "--baud", str(BAUD), "--json", "-w", str(pcap))
    client = pymodbus_client.ModbusSerialClient(
        port=bus.a_path, baudrate=BAUD, parity="N", stopbits=1, bytesize=8, timeout=0.3, retries=0
    )
    assert client.connect()
    absent = 0
    try:
        for index in range(60):
            device = 9 if index % 20 == 7 else 1 + index % 3  # slave 9 is not on the bus
            try:
                if index % 3 == 0:
                    result = client.write_registers(index, [index, 2 * index], device_id=device)
                else:
                    result = client.read_holding_registers(index, count=1 + index % 5, device_id=device)
                assert device != 9 and not result.isError(), result
            except ModbusIOException:
                assert device == 9
                absent += 1
        # Last, a request nobody answers: its line comes once its timeout has passed, not at the end.
        with pytest.raises(ModbusIOException):
            client.read_holding_registers(0, count=1, device_id=9)
        absent += 1
        sniffer.wait_lines(2 * 60 - 3 + 1, timeout=3)
        shown_in_time = len(sniffer.lines)
        # One more transaction: the file's last frame is then no request (a last request is
        # test_live_capture_end.py's).
        assert not client.read_holding_registers(0, count=1, device_id=1).isError()
        sniffer.wait_lines(2 * 60 - 3 + 3, timeout=3)
        status, stderr = sniffer.interrupt()
    finally:
        client.close()
        slave.close()
        bus.close()
    assert status == 0, stderr
    assert absent == 4 and shown_in_time == 2 * 60 - 3 + 1
    live = [json.loads(line) for _, line in sniffer.lines]
    assert [(item["slave"], item["unanswered"]) for item in live if item.get("unanswered")] == [(9, True)] * 4
    assert live[shown_in_time - 1]["slave"] == 9 and live[shown_in_time - 1]["unanswered"] is True
    kept = decode_file(pcap)
    assert [{key: item.get(key) for key in KEYS} for item in live] == [
        {key: item.get(key) for key in KEYS} for item in kept
    ]
    assert live == kept  # and every other key too
    figures = sorted(final_latencies(sniffer.lines, bus, 1.0))
    p50, p99 = statistics.median(figures), figures[int(len(figures) * 0.99)]
    print(f"\nlatency from final to shown over {len(figures)} lines: median {p50 * 1e3:.2f} ms, "
          f"p99 {p99 * 1e3:.2f} ms")
    assert p50 < 0.1  # the tail is printed: a loaded machine may delay single lines


def test_pcap_to_standard_output_into_tshark(tmp_path: Path) -> None:
    """-w -: the pcap on stdout, each record as it is heard; tshark -r - decodes every frame."""
    bus = Bus(seed=7)
    process = start(bus.c_path, "-w", "-")
    data = bytearray()
    assert process.stdout is not None
    reader = threading.Thread(target=lambda: [data.extend(piece) for piece in iter(lambda: os.read(process.stdout.fileno(), 65536), b"")])  # type: ignore[union-attr]
    reader.start()
    try:
        our_master(bus.a_slave, 100, seed=13)
        deadline = time.monotonic() + 2
        while len(data) < 24 + sum(16 + len(frame) for frame in bus.slave.frames) and time.monotonic() < deadline:
            time.sleep(0.01)
        # Every record reached the pipe while the capture runs (flushed per record).
        assert len(data) == 24 + sum(16 + len(frame) for frame in bus.slave.frames)
        process.send_signal(signal.SIGINT)
        status = process.wait(10)
        reader.join(10)
        stderr = process.stderr.read().decode()  # type: ignore[union-attr]
    finally:
        bus.close()
    assert status == 0, stderr
    assert "200 frames (100 requests, 100 responses, 0 exceptions)" in stderr
    assert "wrote standard output" in stderr
    fields = tshark("-r", "-", "-T", "fields", "-e", "mbrtu.unit_id", "-e", "modbus.func_code",
                    "-e", "mbrtu.crc16.status", stdin=bytes(data))
    frames = bus.slave.frames
    # (then the closing record, at the stop: a frame of no byte, nothing of Modbus in it)
    assert [line.split("\t") for line in fields] == [[str(f[0]), str(f[1]), "1"] for f in frames] + [["", "", ""]]


def test_ring_buffer_files_are_each_valid_and_hold_every_byte(tmp_path: Path) -> None:
    bus = Bus(seed=8)
    ring = tmp_path / "ring.pcap"
    sniffer = Sniffer.start(bus.c_path, "--baud", str(BAUD), "-w", str(ring), "-b", "filesize:2")
    try:
        our_master(bus.a_slave, 150, seed=14)
        sniffer.wait_lines(300)
        status, stderr = sniffer.interrupt()
    finally:
        bus.close()
    assert status == 0, stderr
    files = sorted(tmp_path.glob("ring_*.pcap"))
    assert len(files) >= 3
    for number, path in enumerate(files, 1):
        assert re.fullmatch(rf"ring_{number:05d}_\d{{14}}\.pcap", path.name)
        records = [record for _, record in read_pcap(path)]
        assert len(tshark("-r", str(path))) == len(records)
        if path != files[-1]:
            assert 2000 <= path.stat().st_size < 2000 + 16 + 256  # switched after the record reaching 2 kB
    together = [*(record for path in files[:-1] for record in read_pcap(path)), *byte_records(files[-1])]
    assert [record for _, record in together] == bus.slave.frames
    assert f"wrote {files[0]} .. {files[-1]}" in stderr


def test_ring_buffer_on_time_and_keeping_the_last_files(tmp_path: Path) -> None:
    bus = Bus()
    ring = tmp_path / "quiet.pcap"
    sniffer = Sniffer.start(bus.c_path, "--duration", "1.3", "-w", str(ring), "-b", "duration:0.5",
                            "-b", "files:2")
    status, stderr = sniffer.wait()
    bus.close()
    assert status == 0, stderr
    names = sorted(path.name for path in tmp_path.glob("quiet_*.pcap"))
    assert [name[:11] for name in names] == ["quiet_00002", "quiet_00003"]  # 00001 is gone (files:2)
    for name in names:
        assert read_pcap(tmp_path / name) == []
        assert tshark("-r", str(tmp_path / name)) == []


@pytest.mark.parametrize("option", [("-F", "pcapng"), ()])
def test_pcapng_written_live_is_read_back_by_both(tmp_path: Path, option: tuple[str, ...]) -> None:
    bus = Bus(seed=9)
    path = tmp_path / ("live.pcapng" if not option else "live.cap")
    sniffer = Sniffer.start(bus.c_path, "--baud", str(BAUD), "--json", "-w", str(path), *option)
    noise = bytes.fromhex("ff00ff00ff")
    try:
        our_master(bus.a_slave, 20, seed=15)
        time.sleep(0.1)
        os.write(bus.c, noise)
        time.sleep(0.4)
        our_master(bus.a_slave, 20, seed=16)
        sniffer.wait_lines(81)
        status, stderr = sniffer.interrupt()
    finally:
        bus.close()
    assert status == 0, stderr
    assert path.read_bytes()[:4] == bytes.fromhex("0a0d0d0a")
    live = [json.loads(line) for _, line in sniffer.lines]
    assert decode_file(path) == live
    assert [item["kind"] for item in live].count("noise") == 1
    fields = tshark("-r", str(path), "-T", "fields", "-e", "frame.interface_name",
                    "-e", "frame.interface_description", "-e", "frame.comment", "-e", "mbrtu.unit_id")
    assert len(fields) == len(live) + 1 == 82  # (and the closing record)
    description = f"serial port {bus.c_path}, 115200 baud, 8 data bits, even parity, 1 stop bit (115200 8E1)"
    assert fields[-1] == f"{bus.c_path}\t{description}\t\t"
    for line, item in zip(fields, live):
        name, text, comment, unit = line.split("\t")
        assert (name, text) == (bus.c_path, description)
        if item["kind"] == "noise":
            assert comment == "noise: 5 bytes, no valid frame"
        else:
            assert (comment, unit) == ("", str(item["slave"]))


def _records_on_disk(folder: Path, pattern: str) -> int:
    """Whole packet records in the captures `pattern` names in `folder` (pcapng EPBs, pcap records)."""
    count = 0
    for path in folder.glob(pattern):
        data = path.read_bytes()
        ng = data[:4] == bytes.fromhex("0a0d0d0a")
        offset = 0 if ng else 24
        while offset + (12 if ng else 16) <= len(data):
            if ng:
                kind, length = struct.unpack_from("<II", data, offset)
                if length < 12 or offset + length > len(data):
                    break
                count += kind == 6
            else:
                length = 16 + struct.unpack_from("<I", data, offset + 8)[0]
                if offset + length > len(data):
                    break
                count += 1
            offset += length
    return count


def test_sigkill_leaves_valid_pcapng_and_ring_files(tmp_path: Path) -> None:
    pcapng, ring = tmp_path / "kill.pcapng", tmp_path / "kill.pcap"
    for seed, options in enumerate((("-w", str(pcapng)), ("-w", str(ring), "-b", "filesize:1"))):
        bus = Bus(seed=10 + seed)  # a fresh pty: a pty refuses PARENB a second time
        sniffer = Sniffer.start(bus.c_path, "--baud", str(BAUD), *options)
        assert sniffer.ready.startswith("vw3-decode: listening on "), sniffer.ready
        stop = threading.Event()
        master = threading.Thread(target=our_master, args=(bus.a_slave, 5000, 17, stop), daemon=True)
        master.start()
        while bus.slave.transactions < 100:
            time.sleep(0.001)
        # (killed once 150 records are on disk: how far the sniffer's reads lag the bus is the machine's load)
        deadline = time.monotonic() + 60
        while _records_on_disk(tmp_path, ("kill.pcapng", "kill_*.pcap")[seed]) < 150 and time.monotonic() < deadline:
            time.sleep(0.01)
        sniffer.process.send_signal(signal.SIGKILL)
        sniffer.process.wait(5)
        stop.set()
        master.join(5)
        bus.close()
    frames = decode_file(pcapng)
    assert len(frames) >= 150 and tshark("-r", str(pcapng)).__len__() == len(frames)
    files = sorted(tmp_path.glob("kill_*.pcap"))
    assert len(files) >= 2
    for path in files:
        assert len(tshark("-r", str(path))) == len(read_pcap(path))
    assert sum(len(read_pcap(path)) for path in files) >= 150


def test_bad_ring_options(tmp_path: Path) -> None:
    capture = ROOT / "captures" / "p38_protection.bin"
    for options, message in [
        (("-w", str(tmp_path / "x.pcap"), "-b", "files:3"), "-b needs filesize:KB or duration:SECONDS"),
        (("-w", "-", "-b", "filesize:10"), "-b needs -w FILE, not standard output"),
        (("-b", "filesize:10"), "-b (ring buffer) needs -w FILE"),
        (("-w", str(tmp_path / "x.pcap"), "-b", "size:3"), "-b size:3: give filesize:KB"),
        (("-w", str(tmp_path / "x.pcap"), "-b", "filesize:0"), "-b filesize:0: must be more than 0"),
    ]:
        done = subprocess.run([sys.executable, "-m", "dissector", str(capture), *options], cwd=ROOT,
                              capture_output=True, text=True, timeout=60)
        assert done.returncode == 2 and "Traceback" not in done.stderr
        assert done.stderr.startswith(f"vw3-decode: {message}"), done.stderr


def test_file_decode_writes_pcapng_ring_and_stdout(tmp_path: Path) -> None:
    capture = ROOT / "captures" / "p38_protection.bin"
    expected = decode_file(capture)
    done = subprocess.run([sys.executable, "-m", "dissector", str(capture), "-w", "-"], cwd=ROOT,
                          capture_output=True, timeout=60)
    assert done.returncode == 0 and done.stdout[:4] == bytes.fromhex("d4c3b2a1")
    assert len(tshark("-r", "-", stdin=done.stdout)) == len(expected)
    (tmp_path / "p38.pcap").write_bytes(done.stdout)
    assert decode_file(tmp_path / "p38.pcap") == expected
    subprocess.run([sys.executable, "-m", "dissector", str(capture), "-w", str(tmp_path / "p38.pcapng")],
                   cwd=ROOT, check=True, timeout=60)
    assert decode_file(tmp_path / "p38.pcapng") == expected


def test_timeout_rule_in_files_and_in_the_lua_plugin(tmp_path: Path) -> None:
    """The rule a live line waits for, as the decode of a file applies it, and vw3.lua alike: a
    response later than --timeout (1 s) after its request does not answer it."""
    from lua_compare import compare
    from lua_harness import lua_items, python_items, write_pcap

    read = with_crc(bytes.fromhex("010300000001"))
    answer = with_crc(bytes.fromhex("0103020007"))
    records = [(read, 10.0), (answer, 11.5), (read, 12.0), (answer, 12.9), (read, 14.0), (read, 14.2),
               (answer, 14.3)]
    pcap = write_pcap(tmp_path / "late.pcap", records)
    items = decode_file(pcap)
    assert [(item["kind"], item.get("request_frame"), item.get("unanswered")) for item in items] == [
        ("request", None, True), ("response", None, None), ("request", None, False),
        ("response", 3, None), ("request", None, True), ("request", None, False), ("response", 6, None),
    ]
    assert items[1]["warnings"] == ["response 1500.0 ms after request #1, later than the 1000 ms timeout: not its answer"]
    assert items[3]["response_time"] == 0.9
    assert decode_file(pcap, "--timeout", "2")[1]["response_time"] == 1.5
    python = python_items(pcap)
    differences = compare(python, lua_items(pcap)[0], frozenset())
    assert not differences, "\n".join(differences[:20])


def test_live_summary_lines_equal_the_decode_of_the_file(tmp_path: Path) -> None:
    """The plain lines too: numbers, time column, pairing [#N, ms], [no response], noise."""
    bus = Bus(seed=11)
    pcap = tmp_path / "lines.pcap"
    sniffer = Sniffer.start(bus.c_path, "--baud", str(BAUD), "-w", str(pcap), "--timeout", "0.2")
    try:
        our_master(bus.a_slave, 30, seed=18)
        os.write(bus.c, with_crc(bytes.fromhex("090300000001")))  # nobody answers slave 9
        time.sleep(0.4)
        os.write(bus.c, bytes.fromhex("00ff00"))
        time.sleep(0.4)
        our_master(bus.a_slave, 30, seed=19)
        sniffer.wait_lines(122)
        status, stderr = sniffer.interrupt()
    finally:
        bus.close()
    assert status == 0, stderr
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", "--timeout", "0.2", str(pcap)], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)
    lines = [line for _, line in sniffer.lines]
    assert lines == done.stdout.splitlines()
    assert "[no response]" in lines[60] and lines[61].split()[3] == "noise"


def test_pcap_to_a_terminal_is_refused(tmp_path: Path) -> None:
    import pty

    capture = ROOT / "captures" / "p38_protection.bin"
    for command in ([str(capture)], ["--live", "loop://", "--duration", "0.2"]):
        leader, follower = pty.openpty()
        done = subprocess.run([sys.executable, "-m", "dissector", *command, "-w", "-"], cwd=ROOT,
                              stdout=follower, stderr=subprocess.PIPE, text=True, timeout=60)
        os.close(follower)
        os.close(leader)
        assert done.returncode == 2, done.stderr
        assert done.stderr.splitlines()[-1] == (
            "vw3-decode: -w -: standard output is a terminal; pipe it (| wireshark -k -i -) or give a file"
        )


def test_vanishing_port_leaves_valid_pcapng_and_ring_files(tmp_path: Path) -> None:
    pcapng, ring = tmp_path / "gone.pcapng", tmp_path / "gone.pcap"
    for seed, options in enumerate((("-w", str(pcapng)), ("-w", str(ring), "-b", "filesize:1"))):
        bus = Bus(seed=12 + seed)
        sniffer = Sniffer.start(bus.c_path, "--baud", str(BAUD), "--json", *options)
        stop = threading.Event()
        master = threading.Thread(target=our_master, args=(bus.a_slave, 5000, 20 + seed, stop), daemon=True)
        master.start()
        while bus.slave.transactions < 100:
            time.sleep(0.001)
        bus.relay.close_c()
        status, stderr = sniffer.wait()
        stop.set()
        master.join(5)
        bus.close()
        assert status == 1 and "went away" in stderr and "Traceback" not in stderr
        shown = [json.loads(line)["raw"] for _, line in sniffer.lines]
        if seed == 0:
            kept = [item["raw"] for item in decode_file(pcapng)]
            assert len(tshark("-r", str(pcapng))) == len(kept) + 1  # (and the closing record)
        else:
            files = sorted(tmp_path.glob("gone_*.pcap"))
            assert len(files) >= 2 and all(len(tshark("-r", str(path))) == len(read_pcap(path)) for path in files)
            kept = [record.hex() for path in files[:-1] for _, record in read_pcap(path)]
            kept += [record.hex() for _, record in byte_records(files[-1])]
        assert kept == shown and len(kept) >= 150  # every line shown is on disk, and nothing else
