"""The bus simulator: reproducible captures, the seed frames, device semantics, timing, benchmark sessions."""
from __future__ import annotations

import struct
from pathlib import Path

import pytest

from seed_frames import DEVICE_ID_REQUEST, DEVICE_ID_RESPONSE

from dissector.framing.ascii import AsciiFramer
from dissector.protocol.crc import crc16, lrc
from dissector.model import Chunk
from dissector.pipeline import dissect, dissect_bytes
from dissector.render.jsonout import item_to_dict
from dissector.sim.devices import Atv71, Sel749m
from dissector.sim.simulate import BAUD, SESSIONS, Bus, encode_ascii, generate_session, main

from conftest import ROOT
from helpers import hx

CAPTURES = ROOT / "captures"
NAMES = sorted(SESSIONS)


def read_pcap(path: Path) -> tuple[int, list[tuple[float, bytes]]]:
    data = path.read_bytes()
    magic, major, minor, _zone, _sigfigs, _snaplen, linktype = struct.unpack_from("<IHHiIII", data)
    assert (magic, major, minor) == (0xA1B2C3D4, 2, 4)
    records, offset = [], 24
    while offset < len(data):
        seconds, micros, included, original = struct.unpack_from("<IIII", data, offset)
        assert included == original
        records.append((seconds + micros / 1e6, data[offset + 16 : offset + 16 + included]))
        offset += 16 + included
    return linktype, records


def frames(name: str) -> list[dict]:
    data = (CAPTURES / f"{name}.bin").read_bytes()
    if name == "ascii_session":
        return [item_to_dict(item) for item in dissect([Chunk(data)], framer=AsciiFramer())]
    return [item_to_dict(item) for item in dissect_bytes(data)]


def test_generator_reproduces_the_committed_captures_byte_for_byte(tmp_path: Path) -> None:
    assert main(["--out", str(tmp_path)]) == 0
    made = sorted(path.name for path in tmp_path.iterdir())
    assert made == sorted(f"{name}.{ext}" for name in NAMES for ext in ("bin", "pcap"))
    for name in made:
        assert (tmp_path / name).read_bytes() == (CAPTURES / name).read_bytes(), name


def test_readme_describes_every_capture() -> None:
    readme = (CAPTURES / "README.md").read_text(encoding="utf-8")
    for name in NAMES:
        assert f"## {name} (" in readme


@pytest.mark.parametrize("name", NAMES)
def test_pcap_holds_the_bin_frames_one_a_record_at_19200_baud(name: str) -> None:
    linktype, records = read_pcap(CAPTURES / f"{name}.pcap")
    assert linktype == 147
    assert b"".join(data for _time, data in records) == (CAPTURES / f"{name}.bin").read_bytes()
    bits = 10 if name == "ascii_session" else 11
    for (start, data), (following, _next) in zip(records, records[1:]):
        # The next frame starts after this one is on the wire (bytes x bits / baud) plus a gap of at
        # least 3 ms (turnaround) or 4 ms (master idle): never inside it.
        on_wire = len(data) * bits / BAUD
        assert following - start >= on_wire + 0.003 - 2e-6


def test_p38_session_is_the_seed_page_frame_for_frame() -> None:
    request = hx("0C 03 20 D0 00 03 0E EF")
    scenario1 = hx("0C 03 06 80 00 00 03 00 02 17 E4")
    scenario2 = hx("0C 03 06 80 00 80 00 00 02 CE 24")
    scenario3 = hx("0C 83 02 51 32")
    expected = [request, scenario1, request, scenario1, request, scenario2]
    expected += [request, scenario2, request, scenario3, request, scenario3]
    assert (CAPTURES / "p38_protection.bin").read_bytes() == b"".join(expected)
    _linktype, records = read_pcap(CAPTURES / "p38_protection.pcap")
    assert [data for _time, data in records] == expected


def test_commissioning_session_carries_the_manual_frames() -> None:
    data = (CAPTURES / "atv71_commissioning.bin").read_bytes()
    # The seed page's request and its 55-byte answer, as test_seed_vectors spells them out.
    assert data.startswith(DEVICE_ID_REQUEST + DEVICE_ID_RESPONSE)
    assert hx("02 03 0C 1E 00 04 27 6C 02 03 08 00 28 02 58 01 F4 00 00 52 B0") in data


def test_commissioning_session_story() -> None:
    items = frames("atv71_commissioning")
    assert len(items) == 104
    assert all(item["crc_ok"] for item in items)
    refused = [item for item in items if item["kind"] == "exception"]
    assert [(item["frame"], item["function"], item["exception_code"]) for item in refused] == [(64, 6, 7)]
    assert items[62]["registers"] == [{"address": 8401, "value": 3}]  # CHCF = 3 while running
    assert items[61]["registers"] == [{"address": 3201, "value": 0x0237}, {"address": 3202, "value": 300}]
    assert items[103]["kind"] == "response" and items[103]["registers"] == [{"address": 8401, "value": 3}]
    scanner = [item for item in items if item["function"] == 23 and item["kind"] == "response"]
    assert len(scanner) == 40
    eta = [item["registers"][0]["value"] for item in scanner]
    assert sorted(set(eta)) == [0x0231, 0x0233, 0x0237]
    rfr = [item["registers"][1]["value"] for item in scanner]
    assert max(rfr) == 300 and rfr[0] == 0 and rfr[-1] == 0


def test_sel_session_exceptions_follow_appendix_d() -> None:
    items = frames("sel749m_polling")
    assert len(items) == 68
    exceptions = [
        (item["function"], item["exception_code"]) for item in items if item["kind"] == "exception"
    ]
    assert exceptions == [(3, 2), (3, 3), (6, 3), (6, 2), (23, 1), (16, 3), (16, 3), (16, 2)]
    assert all(item["crc_ok"] for item in items)


def test_noisy_session() -> None:
    items = frames("noisy_bus")
    assert len(items) == 38
    noise = [(item["frame"], item["raw"]) for item in items if item["kind"] == "noise"]
    assert noise == [(1, "00fffff0"), (34, "fee03cff1f")]
    assert [item["frame"] for item in items if item.get("crc_ok") is False] == [17]
    assert [item["frame"] for item in items if item.get("unanswered")] == [28, 29]
    assert {items[27]["slave"], items[28]["slave"]} == {5}


def test_ascii_session() -> None:
    data = (CAPTURES / "ascii_session.bin").read_bytes()
    assert b":02062329000AA2\r\n" in data
    lines = data.split(b"\r\n")
    assert lines[-1] == b"" and len(lines) == 11
    for line in lines[:-1]:
        binary = bytes.fromhex(line[1:].decode())
        assert line[:1] == b":" and lrc(binary[:-1]) == binary[-1]
    items = frames("ascii_session")
    assert [(item["kind"], item["function"]) for item in items] == [
        ("request", 3), ("response", 3), ("request", 6), ("response", 6), ("request", 3),
        ("response", 3), ("request", 3), ("exception", 3), ("request", 43), ("response", 43),
    ]
    assert all(item["crc_ok"] for item in items)
    assert encode_ascii(2, hx("06 23 29 00 0A")) == b":02062329000AA2\r\n"


# -- devices -------------------------------------------------------------------------------------


def test_atv71_limits_and_refusals() -> None:
    drive = Atv71(2)
    now = 1.0
    assert drive.handle(hx("03 0C 1E 00 3F"), now)[:2] == hx("03 7E")  # 63 words: the card's limit
    assert drive.handle(hx("03 20 D0 00 01"), now) == hx("83 02")  # only 8400, which does not exist
    assert drive.handle(hx("03 0C 1E 00 40"), now) == hx("83 03")  # 64 words: over the card's 63
    assert drive.handle(hx("06 0C 81 00 01"), now) == hx("86 02")  # ETA is read-only
    assert drive.handle(hx("06 00 01 00 01"), now) == hx("86 02")  # not in the map
    assert drive.handle(hx("01 00 00 00 01"), now) == hx("81 01")  # FC1 not on this card
    assert drive.handle(hx("17 0C 81 00 15 21 35 00 01 02 00 0F"), now) == hx("97 03")  # 21 reads
    drive.handle(hx("06 21 35 00 0F"), now)  # CMD: enable operation
    drive.handle(hx("06 21 36 01 2C"), now)  # LFR 30.0 Hz
    assert drive.running
    assert drive.handle(hx("06 20 D1 00 02"), now + 0.1) == hx("86 07")  # CHCF while running
    assert drive.handle(hx("06 0C 20 02 26"), now + 0.1) == hx("06 0C 20 02 26")  # HSP: adjustment


def test_sel_semantics_and_bad_crc_gets_no_reply() -> None:
    relay = Sel749m(1)
    assert relay.handle(hx("03 00 00 00 7E"), 0.0) == hx("83 03")
    assert relay.handle(hx("03 01 F4 00 01"), 0.0) == hx("83 02")
    assert relay.handle(hx("2B 0E 01 00"), 0.0) == hx("AB 01")
    bus = Bus([relay], seed=1)
    assert bus.read(1, 0, 2, damage_request=3) is None
    assert len(bus.records) == 1
    frame = bus.records[0][0]
    assert crc16(frame[:-2]) != frame[-2] | frame[-1] << 8


# -- benchmark sessions --------------------------------------------------------------------------


def test_generate_session_is_deterministic_and_decodes() -> None:
    first = generate_session(500, seed=3)
    assert first == generate_session(500, seed=3)
    assert first != generate_session(500, seed=4)
    times = [stamp for _data, stamp in first]
    assert times == sorted(times) and len(set(times)) == len(times)
    items = [item_to_dict(item) for item in dissect(Chunk(data, stamp) for data, stamp in first)]
    assert len(items) == len(first)
    assert all(item["kind"] != "noise" and item["crc_ok"] for item in items)
    requests = sum(1 for item in items if item["kind"] == "request")
    assert requests == 500
    answered = sum(1 for item in items if item["kind"] in ("response", "exception"))
    assert answered + sum(1 for item in items if item.get("unanswered")) == 500


def test_generate_session_of_100k_transactions() -> None:
    # How fast it generates is bench/throughput.py's to measure, not a timed unit test's.
    records = generate_session(100_000, seed=0)
    assert len(records) > 190_000
    times = [stamp for _data, stamp in records]
    assert times == sorted(times)


def test_cli_one_session_and_a_benchmark_file(tmp_path: Path) -> None:
    assert main(["--out", str(tmp_path), "--session", "p38_protection"]) == 0
    assert sorted(path.name for path in tmp_path.iterdir()) == ["p38_protection.bin", "p38_protection.pcap"]
    assert main(["--out", str(tmp_path / "bench"), "--transactions", "50", "--seed", "2"]) == 0
    records = generate_session(50, seed=2)
    assert (tmp_path / "bench" / "bench-50-2.bin").read_bytes() == b"".join(data for data, _t in records)
    linktype, stored = read_pcap(tmp_path / "bench" / "bench-50-2.pcap")
    assert linktype == 147 and [data for _t, data in stored] == [data for data, _t in records]
    assert [round(t * 1e6) for t, _data in stored] == [round(t * 1e6) for _data, t in records]


def test_cli_rejects_a_negative_count(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as caught:
        main(["--out", str(tmp_path), "--transactions", "-1"])
    assert caught.value.code == 2
    assert "--transactions must be 0 or more" in capsys.readouterr().err
