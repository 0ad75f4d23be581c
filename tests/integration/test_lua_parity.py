"""Acceptance of the Wireshark Lua plugin: real tshark with lua/vw3.lua against `vw3-decode --json`.

Every capture in captures/ and a large random session are decoded by both, and compared frame by frame:
kind, slave, function, CRC, item number, start, quantity, request and response frames, every register's
address, value, code, status, text and label, bits, device objects, warnings and notes. Zero differences.
tshark is installed by the test when missing (we run as root); the test fails, never skips, without it.
"""
from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from lua_compare import compare
from lua_harness import ROOT, LuaItem, PythonItem, lua_items, python_items, write_pcap
from lua_session import SessionBuilder

CAPTURES = sorted((ROOT / "captures").glob("*.pcap"))
# The profile choices the captures' README gives, as vw3-decode options and as the plugin's preference.
PROFILES = {"sel749m_polling.pcap": ["1=sel749m"]}


def _check(python: list[PythonItem], lua: list[LuaItem], ignore: frozenset[str] = frozenset()) -> None:
    differences = compare(python, lua, ignore)
    assert not differences, f"{len(differences)} differences, first ones:\n" + "\n".join(differences[:40])


def test_captures_exist() -> None:
    # The parity test below must have something to compare (captures/ is part of the repository).
    assert len(CAPTURES) >= 5, CAPTURES


@pytest.mark.parametrize("capture", CAPTURES, ids=[path.name for path in CAPTURES])
def test_capture_parity(capture: Path) -> None:
    profiles = PROFILES.get(capture.name, [])
    options = [f"-o", f"vw3.profiles:{','.join(profiles)}"] if profiles else []
    python = python_items(capture, profiles)
    lua, _, _ = lua_items(capture, *options)
    frames = [item for item in python if item.data["kind"] != "noise"]
    assert frames, f"{capture.name}: the decoder found no frame"
    _check(python, lua)


def test_capture_parity_with_default_profile_on_the_sel_capture() -> None:
    # The same capture with every slave taken as an ATV71: other names, other warnings; still equal.
    capture = ROOT / "captures" / "sel749m_polling.pcap"
    _check(python_items(capture), lua_items(capture)[0])


def test_random_session_parity(tmp_path: Path) -> None:
    records = SessionBuilder(seed=20261121).session(3000)
    pcap = write_pcap(tmp_path / "session.pcap", records)
    python = python_items(pcap)
    lua, record_experts, _ = lua_items(pcap)
    _check(python, lua)
    # The session exercises what the plugin must mirror; a session without these would prove little.
    frames = [item.data for item in python if item.data["kind"] != "noise"]
    kinds = Counter(frame["kind"] for frame in frames)
    assert len(records) > 5000 and kinds["request"] > 2500 and kinds["exception"] > 150, kinds
    assert sum(not frame["crc_ok"] for frame in frames) > 100
    assert sum(frame.get("unanswered", False) for frame in frames) > 100
    assert sum(frame["broadcast"] for frame in frames) > 50
    assert sum(item.data["kind"] == "noise" for item in python) > 50
    statuses = Counter(reg.get("status") for frame in frames for reg in frame.get("registers", []))
    assert statuses["protected"] > 50 and statuses["non-existent"] > 50 and statuses["ok"] > 1000, statuses
    warnings = " | ".join(text for frame in frames for text in frame["warnings"])
    for phrase in ("timeout", "outside the spec's", "beyond the VW3 A3 303's limit", "not supported by",
                   "cannot be broadcast", "disagrees with", "unexpected bytes", "not defined by the spec"):
        assert phrase in warnings, phrase
    notes = " | ".join(text for frame in frames for text in frame["notes"])
    for phrase in ("became protected", "readable again", "every parameter of this read",
                   "response without a matching request", "not in the MMmm form", "sub-function 0F"):
        assert phrase in notes, phrase
    objects = [obj for frame in frames for obj in frame.get("objects", [])]
    assert any(obj.get("text") == "V2.1" for obj in objects)
    # Records holding a request and its response are flagged as such.
    assert sum("holds 2 frames" in text for _, text in record_experts) > 50


@pytest.mark.parametrize("style", ["profile", "plc", "protocol"])
def test_session_with_per_slave_profiles_and_address_styles(tmp_path: Path, style: str) -> None:
    records = SessionBuilder(seed=7).session(800)
    pcap = write_pcap(tmp_path / "profiles.pcap", records)
    profiles = ["sel749m", "12=atv71", "2=generic"]
    cli_style = [] if style == "profile" else ["--address-style", style]
    python = python_items(pcap, profiles, *cli_style)
    lua, record_experts, _ = lua_items(
        pcap, "-o", "vw3.profiles:sel749m,12=atv71,2=generic", "-o", f"vw3.address_style:{style}"
    )
    _check(python, lua)
    labels = [reg.get("label") for item in python for reg in item.data.get("registers", [])]
    if style == "protocol":
        assert set(labels) == {None}
    else:
        # sel749m (the default here) shows 4X references; under "plc" the ATV71 slave does too.
        assert any(label is not None and label.startswith("4") for label in labels)
    assert not any("Preferences" in text for _, text in record_experts)


def test_preference_errors_are_shown(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "one.pcap", SessionBuilder(seed=3).session(3))
    _, record_experts, _ = lua_items(pcap, "-o", "vw3.profiles:12=atv99,nonsense")
    texts = [text for _, text in record_experts]
    assert any('profile "atv99" for slave 12 is not built in' in text for text in texts), texts
    assert any('"nonsense" is neither a built-in profile, auto, nor SLAVE=PROFILE' in text for text in texts), texts


def test_random_ascii_session_parity(tmp_path: Path) -> None:
    from lua_session import ascii_session

    records = ascii_session(31, 1500)
    pcap = write_pcap(tmp_path / "ascii.pcap", records)
    python = python_items(pcap)
    lua, _, _ = lua_items(pcap)
    _check(python, lua)
    frames = [item.data for item in python if item.data["kind"] != "noise"]
    assert len(frames) > 2000 and all(frame["mode"] == "ascii" for frame in frames)
    assert sum(not frame["crc_ok"] for frame in frames) > 50
    assert any("lower-case hex digits" in text for frame in frames for text in frame["warnings"])
    assert sum(item.data["kind"] == "noise" for item in python) > 40


RAW_CAPTURES = sorted((ROOT / "captures").glob("*.bin"))


@pytest.mark.parametrize("capture", RAW_CAPTURES, ids=[path.name for path in RAW_CAPTURES])
def test_raw_capture_written_with_w_opens_the_same_in_wireshark(tmp_path: Path, capture: Path) -> None:
    # vw3-decode FILE.bin -w out.pcap, then Wireshark on out.pcap: the same items as vw3-decode FILE.bin.
    import json
    import subprocess
    import sys

    from lua_harness import place_items, record_lengths

    written = tmp_path / "written.pcap"
    subprocess.run([sys.executable, "-m", "dissector", str(capture), "-w", str(written)], cwd=ROOT, check=True,
                   capture_output=True, timeout=300)
    # Both with their default profile, auto, over the whole file (read twice; tshark -2: issue 27).
    result = subprocess.run([sys.executable, "-m", "dissector", str(capture), "--json"], cwd=ROOT, check=True,
                            capture_output=True, timeout=300)
    python = place_items([json.loads(line) for line in result.stdout.decode().splitlines()], record_lengths(written))
    # A raw capture has no times; the pcap written from it has records at the epoch, read as untimed.
    _check(python, lua_items(written)[0])


SEL_MAP = """# a user's SEL-749M map (rows invented for the test)
address,code,name,unit,scale,signed,enum,bits
0,IA,"Phase A current, RMS",A,0.01,,,
1,IB,Phase B current,A,0.01,,,
2,VAB,Line voltage,V,1,,,
3,TEMP,Temperature,C,0.1,1,,
4,STAT,Status,,,,,0=Trip;1=Warn;15=Run
5,MODE,Mode,,,,1=Auto;2=Manual;32768=Off,
0x10,HEX,Hex addressed,,1e-2,,,
"""
OVERRIDE_MAP = """address,code,name,enum
8401,CHCF2,Profile (override),"1=A;3=IO;32768=Weird"
8400,NEW,Now mapped,
"""


def test_register_maps_preference(tmp_path: Path) -> None:
    # vw3-decode --map [SLAVE=|PROFILE=]FILE and the plugin's "maps" preference give the same names.
    sel, override = tmp_path / "sel.csv", tmp_path / "override.csv"
    sel.write_text(SEL_MAP)
    override.write_text(OVERRIDE_MAP)
    capture = ROOT / "captures" / "sel749m_polling.pcap"
    session = write_pcap(tmp_path / "session.pcap", SessionBuilder(seed=77).session(1500))
    for pcap in (capture, session):
        python = python_items(pcap, ["1=sel749m"], "--map", f"sel749m={sel}", "--map", str(override),
                              "--map", f"12={sel}")
        lua, record_experts, _ = lua_items(pcap, "-o", "vw3.profiles:1=sel749m",
                                           "-o", f"vw3.maps:sel749m={sel};{override};12={sel}")
        _check(python, lua)
        assert not any("Preferences" in text for _, text in record_experts)
        codes = {reg.get("code") for item in python for reg in item.data.get("registers", [])}
        assert {"IA", "TEMP"} <= codes if pcap == capture else "CHCF2" in codes


def test_register_map_errors_are_shown(tmp_path: Path) -> None:
    bad = tmp_path / "bad.csv"
    bad.write_text("address,code,colour\n1,X,red\n")
    worse = tmp_path / "worse.csv"
    worse.write_text("address,code,enum\n1,X,1=A;1=B\n")
    pcap = write_pcap(tmp_path / "one.pcap", SessionBuilder(seed=3).session(3))
    _, record_experts, _ = lua_items(pcap, "-o", f"vw3.maps:{bad};{worse};{tmp_path / 'none.csv'};9x={bad}")
    texts = [text for _, text in record_experts]
    expected = [
        f"{bad}:1: unknown column 'colour'",  # (vw3-decode's words: Python's repr)
        f"{worse}:2: enum entry '1=B': 1 given twice",
        f"{tmp_path / 'none.csv'}: cannot read the map",
        '"9x" is neither a slave address nor a profile in use',
    ]
    for phrase in expected:
        assert any(phrase in text for text in texts), (phrase, texts)


def test_forced_mode_preference(tmp_path: Path) -> None:
    # An ASCII capture read as RTU (vw3-decode --mode rtu): all noise, on both sides.
    capture = ROOT / "captures" / "ascii_session.pcap"
    python = python_items(capture, [], "--mode", "rtu")
    lua, _, _ = lua_items(capture, "-o", "vw3.mode:rtu")
    _check(python, lua)
    assert {item.data["kind"] for item in python} == {"noise"}
    # And an RTU session starting with a record that looks like ASCII, forced to RTU.
    records = [(b":0103", 1.0), *SessionBuilder(seed=5).session(50)]
    pcap = write_pcap(tmp_path / "rtu.pcap", records)
    _check(python_items(pcap, [], "--mode", "rtu"), lua_items(pcap, "-o", "vw3.mode:rtu")[0])


def test_rtac_serial_session_parity(tmp_path: Path) -> None:
    # Linktype 250 records (12-byte RTAC header, then the serial bytes) through Decode As rtacser.data.
    import struct

    from dissector.render.pcapwriter import LINKTYPE_RTAC_SERIAL, PcapWriter

    pcap = tmp_path / "rtac.pcap"
    with pcap.open("wb") as stream:
        writer = PcapWriter(stream, linktype=LINKTYPE_RTAC_SERIAL)
        for data, time in SessionBuilder(seed=9).session(500):
            # The RTAC saw the bytes at `time`; the record was stored later, with some jitter.
            seconds, micros = divmod(round(time * 1_000_000), 1_000_000)
            stored = time + 0.5 + (len(data) % 7) * 0.1
            writer.write(struct.pack(">IIBBH", seconds, micros, 0, 0, 0) + data, stored)
    python = python_items(pcap, header=12)
    lua, _, _ = lua_items(pcap, "-d", "rtacser.data,vw3", header=12)
    _check(python, lua)
    assert len(python) > 900


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_fuzzed_byte_stream_in_one_record_parity(tmp_path: Path, seed: int) -> None:
    # 60 kB of glued, cut, mutated and random frames in one record: the framer's decisions on hostile
    # bytes (damaged frames, CRC scans, resynchronisation after noise) are the same as vw3-decode's,
    # which sees the same bytes as one stream. The record ends on an intact frame, where the two agree.
    from lua_session import random_records

    blob = b"".join(data for data, _ in random_records(seed, 600))[:60_000]
    blob += SessionBuilder(seed).transaction(12)[0]
    pcap = write_pcap(tmp_path / "blob.pcap", [(blob, 1.0)])
    python = python_items(pcap)
    _check(python, lua_items(pcap)[0])
    kinds = Counter(item.data["kind"] for item in python)
    assert kinds["noise"] > 30 and kinds["request"] + kinds["response"] > 100, kinds
    assert sum(not item.data.get("crc_ok", True) for item in python) > 5


def test_fuzzed_ascii_stream_in_one_record_parity(tmp_path: Path) -> None:
    # The same for Modbus ASCII: frames cut short, junk between them, bad LRCs, lower-case digits.
    import random

    from lua_session import ascii_session

    rng = random.Random(2)
    alphabet = b"0123456789ABCDEFabcdef:\r\n"
    parts = [b":02062329000AA2\r\n"]
    for data, _ in ascii_session(2, 400):
        roll = rng.random()
        if roll < 0.1:
            parts.append(bytes(rng.choice(alphabet) for _ in range(rng.randint(0, 60))))
        elif roll < 0.2:
            parts.append(data[: rng.randint(0, len(data))])
        else:
            parts.append(data)
    parts.append(b":02062329000AA2\r\n")
    pcap = write_pcap(tmp_path / "ascii-blob.pcap", [(b"".join(parts), 1.0)])
    python = python_items(pcap)
    _check(python, lua_items(pcap)[0])
    assert sum(item.data["kind"] == "noise" for item in python) > 50
    assert sum(item.data["kind"] != "noise" for item in python) > 600


def test_awaited_answer_followed_by_00_parity(tmp_path: Path) -> None:
    # CRC-16/MODBUS has no final XOR: an answer followed by a 00 byte also checks as an 8-byte request.
    # Both take the answer awaited (framing/rtu.py _match, vw3.lua match), in one record and across records.
    from dissector.protocol.crc import with_crc

    request = with_crc(bytes.fromhex("0c0320d10001"))
    answer = with_crc(bytes.fromhex("0c03020003"))
    assert len(answer) == 7
    following = with_crc(bytes.fromhex("0c0320d10001"))
    records = [(request, 1.0), (answer + b"\x00" + following, 1.1), (request + answer + b"\x00" + following, 1.2)]
    pcap = write_pcap(tmp_path / "zero.pcap", records)
    python = python_items(pcap)
    _check(python, lua_items(pcap)[0])
    kinds = [item.data["kind"] for item in python]
    assert kinds[:4] == ["request", "response", "noise", "request"], kinds
