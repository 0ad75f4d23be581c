"""Real captures (tests/corpus, SOURCES.md): a real RS-485 line with a glitch byte after every frame, and
the same transactions as the node's two UART sides saw them. Every frame found, as raw bytes, as a pcap
of serial reads and as a hex dump; no slave that is not on the bus; exact frames and values."""
from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from dissector.render.pcapwriter import PcapWriter
from helpers import run_cli

CORPUS = Path(__file__).resolve().parents[1] / "corpus"


def records(name: str) -> list[tuple[float, bytes]]:
    """(time, bytes) of each line `time hex...` of a corpus .records file."""
    out = []
    for line in (CORPUS / name).read_text().splitlines():
        time, _, data = line.partition(" ")
        out.append((float(time), bytes.fromhex(data)))
    return out


BUS = records("wizmodbus_bus.records")  # the bus channel (BA+): frame, then its glitch byte
SIDES = records("wizmodbus_rxtx.records")  # RX (requests) and TX (responses) of the node, merged by time


def items(*argv: str, stdin: bytes = b"") -> list[dict]:
    status, out, err = run_cli([*argv, "--json", "-n"], stdin=stdin)
    assert status == 0, err
    return [json.loads(line) for line in out.splitlines()]


def pcap(path: Path, recs: list[tuple[float, bytes]]) -> Path:
    with path.open("wb") as stream:
        writer = PcapWriter(stream, flush=False)
        for time, data in recs:
            writer.write(data, 1_561_939_200 + time)  # (the dump's date, 2019-07-01)
    return path


def frames_of(decoded: list[dict]) -> list[tuple[str, str, bool]]:
    return [(item["kind"], item["raw"], item["crc_ok"]) for item in decoded if item["kind"] != "noise"]


def test_the_two_uart_sides_decode_frame_for_frame() -> None:
    """The clean capture: 44 requests of slave 1 (reads of 1000..1023 two registers at a time, single
    reads and writes of 1024..1032), each answered."""
    decoded = items("-", stdin=b"".join(data for _time, data in SIDES))
    assert len(decoded) == 88 and all(item["kind"] != "noise" and item["crc_ok"] for item in decoded)
    assert [item["kind"] for item in decoded] == ["request", "response"] * 44
    assert {item["slave"] for item in decoded} == {1}
    assert all(decoded[k + 1]["request_frame"] == decoded[k]["frame"] for k in range(0, 88, 2))
    first = decoded[1]
    assert (first["start"], [r["value"] for r in first["registers"]]) == (1000, [0x5266, 0x5707])
    writes = [item for item in decoded if item["function"] == 6]
    assert [(item["kind"], item["fields"]["address"], item["fields"]["value"]) for item in writes] == [
        ("request", 1028, 1), ("response", 1028, 1), ("request", 1029, 0), ("response", 1029, 0)] * 2


@pytest.fixture(scope="module")
def expected() -> list[tuple[str, str, bool]]:
    return frames_of(items("-", stdin=b"".join(data for _time, data in SIDES)))


def test_the_bus_line_as_raw_bytes(expected) -> None:
    decoded = items("-", stdin=b"".join(data for _time, data in BUS))
    assert frames_of(decoded) == expected
    noise = [item["raw"] for item in decoded if item["kind"] == "noise"]
    assert noise == ["00", "fe"] * 21 + ["00", "00"] + ["00", "fe"] * 21 + ["00", "00"]
    assert {item["slave"] for item in decoded if item["kind"] != "noise"} == {1}


def test_the_bus_line_as_a_pcap_of_reads_and_as_a_hex_dump(tmp_path: Path, expected) -> None:
    assert frames_of(items(str(pcap(tmp_path / "bus.pcap", BUS)))) == expected
    stream = b"".join(data for _time, data in BUS)
    rng = random.Random(26)
    for count in (20, 200, 600):
        cuts = sorted(rng.sample(range(1, len(stream)), count))
        reads = [(index * 0.002, stream[a:b]) for index, (a, b) in enumerate(zip([0, *cuts], [*cuts, len(stream)]))]
        assert frames_of(items(str(pcap(tmp_path / "reads.pcap", reads)))) == expected, count
        dump = tmp_path / "bus.txt"
        dump.write_text("".join(data.hex(" ") + "\n" for _time, data in reads))
        assert frames_of(items(str(dump))) == expected, count


def omega_pairs() -> list[tuple[str, bytes, bytes]]:
    """(call, request, response) recorded from an Omega CN7500 by minimalmodbus's tests (SOURCES.md)."""
    out, call = [], ""
    for line in (CORPUS / "omegacn7500.records").read_text().splitlines():
        if line.startswith("# "):
            call = line[2:]
            continue
        request, _, response = line.partition(" | ")
        out.append((call, bytes.fromhex(request), bytes.fromhex(response)))
    return out


def test_omega_cn7500_recordings_decode_pair_for_pair_with_the_values_the_tests_state() -> None:
    pairs = omega_pairs()
    assert len(pairs) == 102
    decoded = items("-", stdin=b"".join(request + response for _call, request, response in pairs))
    assert [(item["kind"], bytes.fromhex(item["raw"]), item["crc_ok"]) for item in decoded] == [
        (kind, raw, True) for _call, request, response in pairs
        for kind, raw in (("request", request), ("response", response))]
    assert all(decoded[k + 1]["request_frame"] == decoded[k]["frame"] for k in range(0, len(decoded), 2))
    by_call: dict[str, list[dict]] = {}
    for (call, _request, _response), response in zip(pairs, decoded[1::2]):
        by_call.setdefault(call, []).append(response)

    def value(call: str, index: int = 0) -> int:
        return by_call[call][index]["registers"][0]["value"]

    # minimalmodbus's assertions: get_pv() 24.6 (slave 1) and 25.9 (slave 10), one decimal
    assert value("Slave address 1, get_pv()") == 246 and value("Slave address 10, get_pv()") == 259
    assert value("Slave address 1, get_setpoint()") == 1000  # 100.0
    assert value("Slave address 1, get_control_mode()") == 0  # 'PID'
    assert value("Slave address 1, get_start_pattern_no()") == 2
    assert by_call["Slave address 1, is_running()"][0]["bits"][0]["value"] == 0  # False
    # get_all_pattern_variables(0): SP0..SP7, Time0..Time7, actual step, cycles, linked pattern
    pattern = [response["registers"][0]["value"] for response in by_call["Slave address 1, get_all_pattern_variables()"]]
    assert pattern == [100, 200, 300, 3333, 500, 600, 700, 800, 10, 20, 30, 45, 50, 60, 70, 80, 7, 4, 1]


def test_omega_cn7500_recordings_on_a_glitching_line(tmp_path: Path) -> None:
    """The same transactions over the wizmodbus line's driver (00 after requests, FE after responses),
    read in random bursts: the same frames, slaves 1 and 10 only."""
    pairs = omega_pairs()
    clean = frames_of(items("-", stdin=b"".join(request + response for _call, request, response in pairs)))
    stream = b"".join(request + b"\x00" + response + b"\xfe" for _call, request, response in pairs)
    assert frames_of(items("-", stdin=stream)) == clean
    rng = random.Random(7500)
    cuts = sorted(rng.sample(range(1, len(stream)), 300))
    reads = [(index * 0.002, stream[a:b]) for index, (a, b) in enumerate(zip([0, *cuts], [*cuts, len(stream)]))]
    decoded = items(str(pcap(tmp_path / "omega.pcap", reads)))
    assert frames_of(decoded) == clean
    assert {item["slave"] for item in decoded if item["kind"] != "noise"} == {1, 10}


def test_pymodbus_vectors_of_the_spec_example_clean_and_glitched() -> None:
    """pymodbus's RTU framer vectors (test_check_frame): the specification's FC3 example answer of slave
    17, valid with CRC 49 AD and invalid with 49 AC, after its request (aiomodbus's test of the same
    pair asserts the registers 0xAE41, 0x5652, 0x4340)."""
    request = bytes.fromhex("11 03 00 6B 00 03 76 87")
    answer = bytes.fromhex("11 03 06 AE 41 56 52 43 40 49 AD")
    for stream in (request + answer, request + b"\x00" + answer + b"\xfe", b"\xfe" + request + b"\x00" + answer):
        decoded = [item for item in items("-", stdin=stream) if item["kind"] != "noise"]
        assert [(item["kind"], item["crc_ok"]) for item in decoded] == [("request", True), ("response", True)]
        assert [(r["address"], r["value"]) for r in decoded[1]["registers"]] == [(107, 0xAE41), (108, 0x5652), (109, 0x4340)]
    damaged = answer[:-1] + b"\xac"
    decoded = items("-", stdin=request + b"\x00" + damaged)
    assert [(item["kind"], item.get("crc_ok")) for item in decoded] == [("request", True), ("noise", None), ("response", False)]
    assert decoded[2]["crc"] == 0xAC49 and decoded[2]["crc_expected"] == 0xAD49
    (single,) = items("-", stdin=bytes.fromhex("02 01 01 00 51 CC"))  # slave 2's FC1 answer, one byte
    assert (single["kind"], single["slave"], single["crc_ok"], single["fields"]["byte_count"]) == ("response", 2, True, 1)


def test_brainchild_io16do_decodes_as_its_activity_script_says() -> None:
    """sigrok-dumps brainchild_io_16do: a PC running minimalmodbus (8E1, 19200 baud) polls slave 1 with
    one request of each of FC1..FC6, FC15, FC16, as its brainchild-io-16do-activity.py script says."""
    stream = b"".join(data for _time, data in records("brainchild_io16do.records"))
    decoded = items("-", stdin=stream)
    assert len(decoded) == 30 and all(item["kind"] != "noise" and item["crc_ok"] for item in decoded)
    assert [item["kind"] for item in decoded] == ["request", "response"] * 15
    assert {item["slave"] for item in decoded} == {1}
    assert [item["function"] for item in decoded[:16:2]] == [1, 2, 3, 4, 5, 6, 15, 16]
    requests = decoded[:16:2]
    assert [(item["start"], item["quantity"]) for item in requests[:4]] == [(3, 1), (0, 1), (99, 1), (120, 1)]
    assert (requests[4]["fields"]["address"], requests[4]["fields"]["value"]) == (3, 0xFF00)  # write_bit(3, True)
    assert (requests[5]["fields"]["address"], requests[5]["fields"]["value"]) == (1, 0b01010101)
    assert (requests[6]["start"], [bit["value"] for bit in requests[6]["bits"]]) == (2, [1])  # write_bit(2, True) by FC15
    assert (requests[7]["start"], [r["value"] for r in requests[7]["registers"]]) == (1, [0b10101010])
    answers = decoded[1:16:2]
    assert [bit["value"] for bit in answers[0]["bits"]] == [1] and [bit["value"] for bit in answers[1]["bits"]] == [0]
    assert [r["value"] for r in answers[2]["registers"]] == [513] and [r["value"] for r in answers[3]["registers"]] == [19200]
