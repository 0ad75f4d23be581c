"""Issue 31: the serial tap as a Wireshark capture interface (extcap), under a real tshark 4.0.

The extcap is installed (`vw3-extcap --install`, the launcher Wireshark runs) into the personal
configuration folder of a temporary Wireshark configuration (WIRESHARK_CONFIG_DIR: tshark 4.0's
personal extcap folder is its `extcap/`), never into the machine's own folders. The bus is made of
pseudo-terminals (tests/support/live_bus.py) with a pymodbus master; a tee gives the same bytes to two
sniffers: tshark capturing through the extcap with the Lua plugin, and `vw3-decode --live`.
"""
from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import threading
import time
from collections import Counter
from pathlib import Path

import pytest

from extcap_harness import AS_DATA, Collector, Reader, Tee, holds, none_left, pcapng_records, processes
from live_bus import ROOT, Bus, our_master
from lua_compare import compare
from lua_harness import PLUGIN, USER_DLT, ensure_tool, parse_pdml, place_items, lua_errors

BAUD = 115200
IFACE = "vw3-socket"
PREF = "extcap.vw3_socket."
JITTER = 0.200  # two sniffers on a loaded two-core machine stamp the same bytes this far apart at most
OPTIONS = ("port", "baud", "parity", "stopbits", "bytesize", "mode", "detect", "detectseconds", "description")


@pytest.fixture()
def config(tmp_path: Path) -> dict[str, str]:
    """The environment of a tshark whose personal extcap folder holds our launcher (and nothing of
    this checkout's PYTHONPATH: the launcher alone must find the package)."""
    ensure_tool("tshark", "tshark")
    env = dict(os.environ, WIRESHARK_CONFIG_DIR=str(tmp_path / "config"))
    env.pop("PYTHONPATH", None)
    done = subprocess.run([sys.executable, "-m", "dissector.app.extcap", "--install"], cwd=ROOT,
                          env=dict(env, PYTHONPATH=str(ROOT)), capture_output=True, text=True, timeout=120)
    launcher = tmp_path / "config" / "extcap" / "vw3-extcap"
    assert (done.returncode, done.stdout, done.stderr) == (0, f"vw3-extcap: wrote {launcher}\n", "")
    assert os.access(launcher, os.X_OK)
    return env


def tshark(env: dict[str, str], *args: str, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["tshark", *args], env=env, capture_output=True, text=True, timeout=timeout)


def extcap(*args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "dissector.app.extcap", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=timeout)


def pymodbus_traffic(bus: Bus, story: bool) -> None:
    """An independent master (pymodbus) on the bus; with `story`, the atv71's 16#8000 story on slave 12:
    CHCF (8401) read as IO, then protected."""
    import pymodbus.client as pymodbus_client  # a test extra: missing it is a failure, not a skip

    client = pymodbus_client.ModbusSerialClient(port=bus.a_path, baudrate=BAUD, parity="N", stopbits=1,
                                                bytesize=8, timeout=2, retries=0)
    assert client.connect()
    rng = random.Random(31)
    bus.slave.registers.update({8400: 0x8000, 8401: 3, 8402: 2})
    try:
        for index in range(40):
            if story and index in (5, 20, 35):
                if index == 35:
                    bus.slave.registers[8401] = 0x8000
                result = client.read_holding_registers(8400, count=3, device_id=12)
            elif index % 3 == 0:
                result = client.write_registers(rng.randrange(200), [rng.randrange(0x10000) for _ in range(3)],
                                                device_id=rng.randint(1, 3))
            else:
                result = client.read_holding_registers(rng.randrange(200), count=rng.randint(1, 10),
                                                       device_id=rng.randint(1, 3))
            assert not result.isError(), result
    finally:
        client.close()


def start_tshark(env: dict[str, str], port: str, *args: str) -> subprocess.Popen[str]:
    command = ["tshark", "-i", IFACE, "-o", f"{PREF}port:{port}", "-o", f"{PREF}baud:{BAUD}",
               "-X", f"lua_script:{PLUGIN}", "-o", USER_DLT, "-n", "-l", *args]
    process = subprocess.Popen(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # Capturing once the extcap has the port open: bytes from then on wait in the terminal for it.
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and not any(holds(pid, port) for pid, _ in processes(f"--port {port}")):
        time.sleep(0.02)
    assert any(holds(pid, port) for pid, _ in processes(f"--port {port}")), "the extcap did not open the port"
    return process


def live_decode(port: str, *options: str) -> subprocess.Popen[str]:
    process = subprocess.Popen([sys.executable, "-m", "dissector", "--live", port, "--baud", str(BAUD), "--json",
                                *options],
                               cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert process.stderr is not None
    assert process.stderr.readline().startswith("vw3-decode: listening on ")
    return process


def test_listed_with_its_options_and_link_type(config: dict[str, str]) -> None:
    listed = tshark(config, "-D")
    assert listed.returncode == 0, listed.stderr
    names = [line.split(". ", 1)[1] for line in listed.stdout.splitlines()]
    assert f"{IFACE} (Modbus serial tap: RTU over TCP gateway (socket://host:port))" in names
    # One interface per serial port pyserial finds, named after the device.
    from serial.tools.list_ports import comports

    for port in comports():
        assert any(name.startswith(f"vw3-{os.path.basename(port.device)} (Modbus serial tap: {port.device}")
                   for name in names), (port.device, names)
    # tshark parsed every argument of --extcap-config into a preference (an argument it cannot parse
    # is dropped: none is).
    prefs = tshark(config, "-G", "currentprefs").stdout
    for option in OPTIONS:
        assert f"#{PREF}{option}:" in prefs, option
    assert f"#{PREF}detectseconds: 2\n" in prefs and f"#{PREF}detect: false\n" in prefs
    dlts = tshark(config, "-i", IFACE, "-L")
    assert dlts.returncode == 0, dlts.stderr
    assert "USER0 (Modbus serial bytes as heard (map USER0 to vw3))" in dlts.stdout


def test_tshark_decodes_live_what_vw3_decode_live_shows(config: dict[str, str], tmp_path: Path) -> None:
    bus = Bus(baud=BAUD, seed=31)
    tee = Tee(bus)
    tee.start()
    saved = tmp_path / "extcap.pcapng"
    ours = tmp_path / "live.pcapng"
    wire, file = tee.paths
    decoder = live_decode(file, "-w", str(ours))
    sharked = start_tshark(config, wire, "-T", "pdml", "-w", str(saved), "-P")
    collected = Collector(sharked)
    try:
        pymodbus_traffic(bus, story=True)
        time.sleep(0.1)
        os.write(bus.c, bytes.fromhex("ff00ff00ff"))  # noise, a record of its own with its comment
        time.sleep(0.5)
        our_master(bus.a_slave, 5, seed=3)
        time.sleep(1.0)
        running = processes(f"--port {wire}")
        assert len(running) == 1 and "dissector.app.extcap --capture" in running[0][1]
        # Decoded as they arrive: every record's packet is out before tshark is told to stop.
        deadline = time.monotonic() + 10
        while collected.text().count("</packet>") < 2 * 45 + 1 and time.monotonic() < deadline:
            time.sleep(0.05)
        assert collected.text().count("</packet>") == 2 * 45 + 1
        sharked.send_signal(signal.SIGINT)
        sharked.wait(30)
        collected.join(10)
        pdml, shark_err = collected.text(), sharked.stderr.read()  # type: ignore[union-attr]
        decoder.send_signal(signal.SIGINT)
        lines, decode_err = decoder.communicate(timeout=30)
    finally:
        for process in (sharked, decoder):
            if process.poll() is None:
                process.kill()
        bus.close()
        tee.close()
    assert sharked.returncode == 0, shark_err
    assert decoder.returncode == 0, decode_err
    # Stopping tshark leaves no process behind: neither the extcap nor dumpcap on its fifo.
    assert none_left(f"--port {wire}") == []
    assert none_left("wireshark_extcap_vw3-socket") == []
    assert not lua_errors(pdml + shark_err)

    live = [json.loads(line) for line in lines.splitlines()]
    sent = bus.slave.frames
    frames = [bytes.fromhex(item["raw"]) for item in live if item["kind"] != "noise"]
    assert frames == sent and len(sent) == 2 * 45
    assert [item["kind"] for item in live].count("noise") == 1
    # The extcap's capture: one record per frame or noise run, as vw3-decode --live -w writes them.
    description, records = pcapng_records(saved)
    assert description == (f"serial port {wire}, 115200 baud, 8 data bits, even parity, "
                           f"1 stop bit (115200 8E1)")
    assert [data for _, data, _ in records] == [bytes.fromhex(item["raw"]) for item in live]
    assert [comment for _, _, comment in records] == [
        "noise: 5 bytes, no valid frame" if item["kind"] == "noise" else None for item in live]
    # ... with the same bytes, comments and times (each sniffer stamps its own reads) as -w writes.
    _, written = pcapng_records(ours)
    assert written[-1][1:] == (b"", None)  # -w's closing record, at the stop (the extcap's file has dumpcap's)
    written = written[:-1]
    assert [(data, comment) for _, data, comment in written] == [(data, comment) for _, data, comment in records]
    gaps = sorted(abs(a[0] - b[0]) for a, b in zip(written, records))
    print(f"\nextcap vs -w time stamps over {len(gaps)} records: median {gaps[len(gaps) // 2] * 1e6:.0f} us, "
          f"max {gaps[-1] * 1e6:.0f} us")
    assert gaps[len(gaps) // 2] < 0.002 and gaps[-1] < JITTER, gaps

    # What tshark showed live, frame by frame, equals what vw3-decode --live showed. tshark cannot
    # decode a live capture in two passes: a request is shown before its response is heard, so its
    # link to the response is left to the two-pass decode of the file below. Bytes a later record settles
    # (the noise run) are shown by the record that settles them, on its first dissection (lua/README.md's
    # "What one pass shows"; live, its own record shows the extcap's comment). Each sniffer stamps its own
    # reads: response times are compared to the machine's scheduling jitter.
    lua, record_experts = parse_pdml(pdml)
    python = place_items(live, [len(data) for _, data, _ in records])
    single_pass = frozenset(["response_frame", "unanswered", "response_time"])
    differences = compare(python, lua, ignore=single_pass)
    assert differences == [], "\n".join(differences)
    # Live lines say they are provisional (issue 27), in tshark as in vw3-decode --live: a slave's frames
    # until profile auto is settled for it, its 8th answer (8 requests and 7 answers of slaves 1 to 3, which
    # no profile fits), or until its choice (slave 12: chosen at its second answer, the 16#8000 one).
    said = [(item["frame"], item["slave"]) for item in live if item.get("provisional")]
    shown = [(int(item.fields["item"]), int(item.fields["slave"])) for item in lua
             if item.fields.get("provisional") in ("1", "True", "true")]
    assert shown == said
    assert Counter(slave for _, slave in said) == {1: 15, 2: 15, 3: 15, 12: 3}
    assert 'show="noise: 5 bytes, no valid frame"' in pdml
    noise_record = 1 + [item["kind"] for item in live].index("noise")
    # (one pass: ff 00 ff 00 are noise already, the last ff may begin a frame until the next record)
    assert record_experts == [
        (noise_record, "The record ends inside a noise run: 4 bytes of noise so far, shown as an item with the "
                       "next records' bytes that end the run"),
        (noise_record, "The record ends inside a frame: its last byte is framed with the next records'")]
    times = {item["frame"]: item.get("response_time") for item in live if item["kind"] == "response"}
    shown = {int(item.fields["item"]): item.fields.get("response_time") for item in lua
             if item.fields.get("kind") == "2"}
    assert times.keys() == shown.keys()
    assert all(abs(float(shown[key]) - times[key]) < JITTER for key in times)
    # The names and the 16#8000 story, live in Wireshark: CHCF read as IO, then protected (the first
    # answer is no evidence for profile auto, issue 26: the second, the same read with 16#8000, is).
    story = [item for item in lua if item.fields.get("slave") == "12" and item.fields.get("kind") == "2"]
    assert [[(reg.get("code"), reg.get("status")) for reg in item.registers] for item in story] == [
        [(None, None)] * 3, [(None, "non-existent"), ("CHCF", "ok"), ("COP", "ok")],
        [(None, "non-existent"), ("CHCF", "protected"), ("COP", "ok")]]
    assert story[-1].texts["note"] == ["CHCF (8401) became protected: read 3 in frame #42, 16#8000 now"]

    # The saved capture, decoded in two passes by the plugin, equals vw3-decode of it, every key.
    two_pass = subprocess.run(["tshark", "-n", "-2", "-X", f"lua_script:{PLUGIN}", "-o", USER_DLT, "-r",
                               str(saved), "-T", "pdml"], capture_output=True, text=True, timeout=120)
    assert two_pass.returncode == 0, two_pass.stderr
    # (The file read twice, as tshark -2 shows it: profile auto names slave 12 from its first answer, issue 27.)
    decoded = subprocess.run([sys.executable, "-m", "dissector", str(saved), "--json"], cwd=ROOT,
                             capture_output=True, timeout=120)
    assert decoded.returncode == 0, decoded.stderr
    decoded_twice = [json.loads(line) for line in decoded.stdout.decode().splitlines()]
    assert compare(place_items(decoded_twice, [len(data) for _, data, _ in records]),
                   parse_pdml(two_pass.stdout)[0]) == []
    # The saved capture read once (on stdin, as live reads the line) gives what live showed.
    once = subprocess.run([sys.executable, "-m", "dissector", "-", "--json"], cwd=ROOT,
                          capture_output=True, input=saved.read_bytes(), timeout=120)
    assert once.returncode == 0, once.stderr
    kept = [json.loads(line) for line in once.stdout.decode().splitlines()]
    keys = ("frame", "kind", "raw", "slave", "function", "request_frame", "response_frame", "registers", "notes")
    assert [{key: item.get(key) for key in keys} for item in kept] == [
        {key: item.get(key) for key in keys} for item in live]


def test_quiet_bus_stops_when_tshark_stops_itself(config: dict[str, str]) -> None:
    """tshark -c: dumpcap ends and the fifo closes while the bus is silent; the extcap sees it."""
    bus = Bus(baud=BAUD, seed=5)
    try:
        sharked = start_tshark(config, bus.c_path, "-c", "4")
        our_master(bus.a_slave, 2, seed=1)
        out, err = sharked.communicate(timeout=30)
        assert sharked.returncode == 0, err
        assert len(out.splitlines()) == 4
        assert none_left(f"--port {bus.c_path}", seconds=3) == []
    finally:
        bus.close()


def test_every_option_round_trips_through_tshark(config: dict[str, str]) -> None:
    """Each dialog option set through tshark's preferences reaches the capture as the extcap's own
    argument, and the capture uses it: 9600 7N2 Modbus ASCII, described."""
    bus = Bus(baud=BAUD, seed=6)
    settings = {"parity": "N", "stopbits": "2", "bytesize": "7", "mode": "ascii", "description": "line 3 drives"}
    try:
        command = ["tshark", "-i", IFACE, "-o", f"{PREF}port:{bus.c_path}", "-o", f"{PREF}baud:9600", "-n", "-l",
                   "-c", "2", "-X", f"lua_script:{PLUGIN}", "-o", USER_DLT, "-T", "fields",
                   "-e", "frame.interface_description", "-e", "vw3.mode", "-e", "vw3.slave", "-e", "vw3.start",
                   "-e", "vw3.kind"]
        for name, value in settings.items():
            command += ["-o", f"{PREF}{name}:{value}"]
        sharked = subprocess.Popen(command, env=config, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and not any(holds(pid, bus.c_path) for pid, _ in
                                                      processes(f"--port {bus.c_path}")):
            time.sleep(0.02)
        (_, extcap_command), = processes(f"--port {bus.c_path}")
        os.write(bus.c, b":02062329000AA2\r\n:02062329000AA2\r\n")  # Write Single Register 9001 = 10, and its echo
        out, err = sharked.communicate(timeout=30)
    finally:
        bus.close()
    assert sharked.returncode == 0, err
    arguments = extcap_command.split(" --fifo ")[1].split(" ", 1)[1]
    assert arguments == (f"--port {bus.c_path} --baud 9600 --parity N --stopbits 2 --bytesize 7 --mode ascii "
                         "--detect-seconds 2 --description line 3 drives ")
    description = (f"line 3 drives: serial port {bus.c_path}, 9600 baud, 7 data bits, no parity, 2 stop bits "
                   "(9600 7N2)")
    assert out.splitlines() == [f"{description}\tascii\t2\t9001\t1", f"{description}\tascii\t2\t9001\t2"]


def test_unplugged_adapter_is_one_error_line(config: dict[str, str]) -> None:
    """The port goes away mid-capture: tshark ends with the extcap's reason, every frame before kept."""
    bus = Bus(baud=BAUD, seed=7)
    try:
        sharked = start_tshark(config, bus.c_path, "-T", "fields", "-e", "vw3.kind")
        our_master(bus.a_slave, 5, seed=7)
        time.sleep(0.3)
        bus.relay.close_c()
        out, err = sharked.communicate(timeout=30)
    finally:
        bus.close()
    # (tshark 4.0 exits 0 once packets were captured: the line is what tells.)
    assert f"Error by extcap pipe: vw3-extcap: error: {bus.c_path} went away (" in err, err
    assert "Traceback" not in err
    assert out.splitlines() == ["1", "2"] * 5
    assert none_left(f"--port {bus.c_path}", seconds=3) == []


def test_errors_reach_tshark_as_one_line(config: dict[str, str]) -> None:
    cases = [
        ((), f"{IFACE} needs the gateway's address: --port socket://HOST:PORT"),
        (("-o", f"{PREF}port:/dev/nonexistent-vw3", ), "cannot open /dev/nonexistent-vw3: No such file or directory"),
        (("-o", f"{PREF}port:/dev/null", "-o", f"{PREF}baud:fast"),
         "argument --baud: 'fast' is not a whole number of baud (see vw3-extcap --help)"),
        (("-o", f"{PREF}port:/dev/null", "-f", "port 502"),
         "capture filters are not supported on a serial bus: use a display filter (vw3.slave == 12)"),
    ]
    for options, message in cases:
        done = tshark(config, "-i", IFACE, *options, "-c", "1", timeout=60)
        assert done.returncode != 0
        assert f"Error by extcap pipe: vw3-extcap: {message}\n" in done.stderr, done.stderr
        assert "Traceback" not in done.stderr
    assert none_left("dissector.app.extcap --capture", seconds=3) == []


def test_capture_filter_check_and_bad_arguments() -> None:
    """Wireshark's filter check (printed text: invalid), and one-line errors, exit 2."""
    assert extcap("--extcap-interface", IFACE, "--extcap-capture-filter", "").stdout == ""
    refused = extcap("--extcap-interface", IFACE, "--extcap-capture-filter", "tcp port 502")
    assert (refused.returncode, refused.stdout) == (0, "capture filters are not supported on a serial bus: "
                                                        "use a display filter (vw3.slave == 12)\n")
    for args, message in [
        (("--bogus",), "unrecognized arguments: --bogus (see vw3-extcap --help)"),
        (("--extcap-interface", "vw3-nope", "--extcap-config"),
         "no interface 'vw3-nope' (see vw3-extcap --extcap-interfaces)"),
        (("--extcap-interface", IFACE, "--capture"), "--capture needs --fifo PATH"),
        (("--extcap-interface", IFACE, "--capture", "--fifo", "x", "--parity", "X"),
         "argument --parity: invalid choice: 'X' (choose from 'E', 'N', 'O') (see vw3-extcap --help)"),
        # The speeds vw3-decode --baud takes, no others (a 1-baud capture used to start).
        (("--extcap-interface", IFACE, "--capture", "--fifo", "x", "--baud", "1"),
         "argument --baud: 1 baud is no Modbus serial line speed (50..4,000,000) (see vw3-extcap --help)"),
        (("--extcap-interface", IFACE, "--capture", "--fifo", "x", "--baud", "99999999"),
         "argument --baud: 99999999 baud is no Modbus serial line speed (50..4,000,000) (see vw3-extcap --help)"),
        (("--extcap-interface", IFACE, "--capture", "--fifo", "x", "--detect-seconds", "0"),
         "argument --detect-seconds: '0' must be a number of seconds more than 0 (see vw3-extcap --help)"),
        ((), "give --extcap-interfaces, or --extcap-interface NAME with --extcap-dlts, --extcap-config, "
             "--extcap-capture-filter or --capture (see vw3-extcap --help)"),
    ]:
        done = extcap(*args)
        assert (done.returncode, done.stdout, done.stderr) == (2, "", f"vw3-extcap: {message}\n"), args


def run_by_hand(bus: Bus, fifo: Path, *options: str) -> subprocess.Popen[str]:
    os.mkfifo(fifo)
    return subprocess.Popen(
        [sys.executable, "-m", "dissector.app.extcap", "--capture", "--extcap-interface", IFACE, "--fifo",
         str(fifo), "--port", bus.c_path, "--baud", str(BAUD), *options],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def records_of(data: bytes, path: Path) -> list[tuple[float, bytes, str | None]]:
    path.write_bytes(data)
    return pcapng_records(path)[1]


@pytest.mark.parametrize("how", ["SIGTERM", "fifo closed"])
def test_stops_cleanly_keeping_every_frame(tmp_path: Path, how: str) -> None:
    """Wireshark's SIGTERM, or the fifo closed on a silent bus (POLLERR): exit 0 within a second,
    nothing said, every frame heard in the capture."""
    bus = Bus(baud=BAUD, seed=8)
    try:
        process = run_by_hand(bus, tmp_path / "fifo")
        reader = Reader(tmp_path / "fifo")
        reader.started()
        our_master(bus.a_slave, 30, seed=8)
        time.sleep(0.3)
        stopped = time.monotonic()
        if how == "SIGTERM":
            process.send_signal(signal.SIGTERM)
        else:
            reader.close()
        out, err = process.communicate(timeout=10)
        took = time.monotonic() - stopped
        reader.join(5)
    finally:
        bus.close()
    assert (process.returncode, out, err) == (0, "", "")
    assert took < 2.0
    assert [record for _, record, _ in records_of(bytes(reader.data), tmp_path / "got.pcapng")] == bus.slave.frames
    assert len(bus.slave.frames) == 60


def test_a_file_given_by_hand(tmp_path: Path) -> None:
    """--fifo FILE outside Wireshark (to try a port): a pcapng file, written as heard."""
    bus = Bus(baud=BAUD, seed=12)
    path = tmp_path / "by-hand.pcapng"
    path.write_bytes(b"old content, longer than what the capture writes" * 100)
    try:
        process = subprocess.Popen(
            [sys.executable, "-m", "dissector.app.extcap", "--capture", "--extcap-interface", IFACE, "--fifo",
             str(path), "--port", bus.c_path, "--baud", str(BAUD)], cwd=ROOT, stdout=subprocess.PIPE,
            stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and not holds(process.pid, bus.c_path):
            time.sleep(0.02)
        our_master(bus.a_slave, 10, seed=12)
        time.sleep(0.3)
        process.send_signal(signal.SIGTERM)
        out, err = process.communicate(timeout=10)
    finally:
        bus.close()
    assert (process.returncode, out, err) == (0, "", "")
    assert [record for _, record, _ in pcapng_records(path)[1]] == bus.slave.frames


def test_reader_gone_during_traffic_ends_the_capture(tmp_path: Path) -> None:
    """The same with frames still coming: the next write fails with EPIPE, exit 0, nothing said."""
    bus = Bus(baud=BAUD, seed=10)
    stop = threading.Event()
    master = threading.Thread(target=our_master, args=(bus.a_slave, 2000, 10, stop), daemon=True)
    try:
        process = run_by_hand(bus, tmp_path / "fifo")
        reader = Reader(tmp_path / "fifo")
        reader.started()
        master.start()
        while bus.slave.transactions < 50:
            time.sleep(0.01)
        reader.close()
        out, err = process.communicate(timeout=10)
        stop.set()
        master.join(10)
    finally:
        bus.close()
    assert (process.returncode, out, err) == (0, "", "")


def test_detect_then_capture_through_tshark(config: dict[str, str]) -> None:
    """The dialog's --detect (a boolflag: `-o ...detect:true`) and description reach the capture."""
    bus = Bus(baud=BAUD, seed=11)
    stop = threading.Event()
    master = threading.Thread(target=our_master, args=(bus.a_slave, 100000, 11, stop), daemon=True)
    try:
        master.start()
        done = tshark(config, "-i", IFACE, "-o", f"{PREF}port:{bus.c_path}", "-o", f"{PREF}detect:true",
                      "-o", f"{PREF}detectseconds:0.1", "-o", f"{PREF}description:line 3", "-c", "8", "-n",
                      "-T", "fields", "-e", "frame.interface_description", "-e", "data", "-o", AS_DATA)
    finally:
        stop.set()
        master.join(10)
        bus.close()
    assert done.returncode == 0, done.stderr
    fields = [line.split("\t") for line in done.stdout.splitlines()]
    assert len(fields) == 8
    # A pseudo-terminal carries bytes at any setting: which one wins is not the point here.
    for description, data in fields:
        assert description.startswith(f"line 3: serial port {bus.c_path}, ")
        assert description.endswith(", found by --detect")
    # The capture starts mid-traffic: what comes before the first whole frame is the end of one cut by
    # the start (noise, in one or two records); from there on, the bus's frames in order.
    records = [bytes.fromhex(data) for _, data in fields]
    first = next(index for index, record in enumerate(records) if record in bus.slave.frames)
    assert first <= 2, records
    rest, sent = records[first:], bus.slave.frames
    assert any(sent[start:start + len(rest)] == rest for start in range(len(sent))), records
    assert none_left(f"--port {bus.c_path}", seconds=3) == []


def test_stopped_during_detect(config: dict[str, str]) -> None:
    """Stop pressed while --detect listens (15 settings of 1 s): gone at the next setting, no 10 s wait
    for a fifo reader that has left."""
    bus = Bus(baud=BAUD, seed=13)
    try:
        sharked = start_tshark(config, bus.c_path, "-o", f"{PREF}detect:true", "-o", f"{PREF}detectseconds:1")
        time.sleep(0.5)
        stopped = time.monotonic()
        sharked.send_signal(signal.SIGINT)
        sharked.communicate(timeout=30)
        left = none_left(f"--port {bus.c_path}", seconds=10)
        took = time.monotonic() - stopped
    finally:
        bus.close()
    assert left == []
    assert took < 3.0


def test_tshark_killed_on_a_silent_bus(config: dict[str, str]) -> None:
    """SIGKILL to tshark (no SIGTERM for the extcap, a silent bus): the extcap sees its parent gone or
    the fifo closed, and ends."""
    bus = Bus(baud=BAUD, seed=14)
    try:
        sharked = start_tshark(config, bus.c_path)
        our_master(bus.a_slave, 3, seed=14)
        sharked.kill()
        sharked.communicate(timeout=30)
        assert none_left(f"--port {bus.c_path}", seconds=3) == []
    finally:
        bus.close()
