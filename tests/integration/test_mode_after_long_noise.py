"""Modbus ASCII frames after more line noise than the MODE_SAMPLE bytes a mode used to be told from (session
53's hunt: 70 zero bytes before `:0C0320D10002FE` made the whole capture one run of RTU noise, in vw3-decode
and in the plugin). protocol/ascii.py sample_mode reads on, up to MODE_REACH bytes, until a whole ASCII frame
or two RTU frames back to back tell; lua/src/ascii.lua sample_mode is the same rule, and the plugin decodes
the records it held again when their bytes change the mode (lua/src/dissector.lua). An RTU bus is still told
in its first MODE_SAMPLE bytes, and an RTU capture after long noise stays RTU.
"""
from __future__ import annotations

import random
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest

from helpers import run_cli, use_engine
from lua_compare import compare
from lua_harness import PLUGIN, ensure_tool, lua_errors, lua_items, python_items, run_tshark, write_pcap

from dissector.model import Chunk
from dissector.protocol.ascii import MODE_REACH, MODE_SAMPLE, frame_end, rtu_pair_end, sample_mode
from dissector.protocol.crc import with_crc
from dissector.sources.reader import open_source, sampled_mode

REQUEST = b":0C0320D10002FE\r\n"  # slave 12 reads 8401..8402
RESPONSE = b":0C030400030002E8\r\n"  # 8401=3 8402=2
RTU_PAIR = with_crc(bytes.fromhex("0C0320D10002")) + with_crc(bytes.fromhex("0C030400030002"))


def _random_noise(count: int) -> bytes:
    """Random bytes without ':' that hold no pair of RTU frames (checked: the case the sample waits in)."""
    noise = bytes(random.Random(53).choice([b for b in range(256) if b != 0x3A]) for _ in range(count))
    assert rtu_pair_end(noise) is None
    return noise


NOISE = {
    "zeros30": bytes(30), "zeros50": bytes(50), "zeros60": bytes(60), "zeros70": bytes(70),
    "ff70": b"\xff" * 70, "random60": _random_noise(60), "zeros900": bytes(900),
}


def _lines(noise: bytes, end: str) -> list[str]:
    shown = " ".join(f"{byte:02x}" for byte in noise[:16]) + ("…" if len(noise) > 16 else "")
    lines = [f"     1            -   - noise     {len(noise)} bytes of noise at offset 0: {shown}"]
    for number in range(2, 12, 2):
        lines += [f"{number:6d}            -  12 request   Read Holding Registers 8401..8402 (2)  {end} ok",
                  f"{number + 1:6d}            -  12 response  Read Holding Registers 8401..8402 (2): 8401=3 "
                  f"8402=2 [#{number}]  {end} ok"]
    return lines


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("name", sorted(NOISE))
def test_ascii_frames_after_long_noise_are_decoded_as_ascii(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, name: str, pure: bool
) -> None:
    # (before: zeros50 and longer, ff70 and random60 were one noise run, with a `try --mode ascii` hint)
    path = tmp_path / f"{name}.bin"
    path.write_bytes(NOISE[name] + (REQUEST + RESPONSE) * 5)
    use_engine(monkeypatch, pure)
    assert run_cli([str(path)]) == (0, "\n".join(_lines(NOISE[name], "LRC")) + "\n", "")
    with open_source(str(path)) as source:
        assert (source.format, source.mode, source.warnings) == ("ascii", "ascii", [])


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_rtu_frames_after_long_noise_stay_rtu(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool
) -> None:
    path = tmp_path / "rtu.bin"
    path.write_bytes(bytes(100) + RTU_PAIR * 5)
    use_engine(monkeypatch, pure)
    assert run_cli([str(path)]) == (0, "\n".join(_lines(bytes(100), "CRC")) + "\n", "")


def _pieces(data: bytes, size: int) -> Iterator[Chunk]:
    for at in range(0, len(data), size):
        yield Chunk(data[at : at + size])


def test_a_stream_is_told_as_soon_as_its_bytes_tell_whatever_its_pieces() -> None:
    # An RTU bus: at MODE_SAMPLE bytes, as before (a live pipe shows its first frames at once).
    mode, head = sampled_mode(_pieces(RTU_PAIR * 10, 8))
    assert (mode, sum(len(chunk.data) for chunk in head)) == ("rtu", MODE_SAMPLE)
    # After 100 bytes of noise: the piece that ends the second frame.
    mode, head = sampled_mode(_pieces(bytes(100) + RTU_PAIR * 10, 8))
    assert (mode, sum(len(chunk.data) for chunk in head)) == ("rtu", 120)
    # ASCII after 70 zero bytes: the piece that ends the first frame; noise alone: MODE_REACH bytes.
    mode, head = sampled_mode(_pieces(bytes(70) + (REQUEST + RESPONSE) * 5, 8))
    assert (mode, sum(len(chunk.data) for chunk in head)) == ("ascii", 88)
    mode, head = sampled_mode(_pieces(bytes(4000), 8))
    assert (mode, sum(len(chunk.data) for chunk in head)) == ("rtu", MODE_REACH + 6)  # (1026 rounded up)
    for data in [*(noise + (REQUEST + RESPONSE) * 5 for noise in NOISE.values()), bytes(100) + RTU_PAIR * 5]:
        whole = sample_mode(data, True)
        assert all(sampled_mode(_pieces(data, size))[0] == whole for size in (1, 3, 7, 64, 4096))


def test_noise_past_the_reach_leaves_rtu_and_the_mode_ascii_hint(tmp_path: Path) -> None:
    path = tmp_path / "late.bin"
    path.write_bytes(bytes(1100) + REQUEST + RESPONSE)
    assert run_cli([str(path)])[2].endswith("(it holds Modbus ASCII frames: try --mode ascii)\n")


# The plugin's Info column for the records of vw3-decode -w's pcap: the noise run, then one a frame.
PLUGIN_INFO = ["12 Read Holding Registers request 8401..8402 (2)",
               "12 Read Holding Registers response 8401..8402 (2)"] * 5


@pytest.mark.parametrize("name", ["zeros50", "zeros70", "ff70", "random60", "zeros900"])
def test_the_plugin_decodes_ascii_after_long_noise_as_vw3_decode_does(tmp_path: Path, name: str) -> None:
    path, written = tmp_path / f"{name}.bin", tmp_path / f"{name}.pcap"
    path.write_bytes(NOISE[name] + (REQUEST + RESPONSE) * 5)
    assert run_cli([str(path), "-w", str(written)]) == (0, "", "")
    result = run_tshark(written, "-T", "fields", "-e", "_ws.col.Info")
    assert not lua_errors(result.stdout + result.stderr)
    assert result.stdout.splitlines() == [f"noise ({len(NOISE[name])} bytes)", *PLUGIN_INFO]
    differences = compare(python_items(written, []), lua_items(written)[0])
    assert not differences, "\n".join(differences[:40])


@pytest.mark.parametrize("data", [bytes(70) + (REQUEST + RESPONSE) * 5, bytes(100) + RTU_PAIR * 5],
                         ids=["ascii", "rtu"])
def test_the_plugin_holds_records_in_pieces_until_their_bytes_tell(tmp_path: Path, data: bytes) -> None:
    """Records of 1 to 5 bytes: the mode is told past MODE_SAMPLE, inside a record; those held until then
    are decoded again as if the mode had been known."""
    records, at, size = [], 0, 1
    while at < len(data):
        records.append((data[at : at + size], 1_700_000_000 + len(records) * 0.01))
        at, size = at + size, size % 5 + 1
    pcap = write_pcap(tmp_path / "pieces.pcap", records)
    python = python_items(pcap, [])
    kinds = [item.data["kind"] for item in python]
    assert [kind for kind in kinds if kind != "noise"] == ["request", "response"] * 5
    differences = compare(python, lua_items(pcap)[0])
    assert not differences, "\n".join(differences[:40])


def _samples() -> list[bytes]:
    rng = random.Random(5)
    pieces = [b"\x00", b"\xff", REQUEST, RESPONSE, RTU_PAIR[:8], RTU_PAIR[8:], b":", b"0C03", b"\r\n",
              b"\x0c\x03"]
    samples = [noise + (REQUEST + RESPONSE) * 5 for noise in NOISE.values()] + [bytes(100) + RTU_PAIR * 5]
    samples += [b"".join(rng.choice(pieces) for _ in range(rng.randint(1, 120))) for _ in range(150)]
    return [sample[:length] for sample in samples for length in (40, 64, 90, len(sample))]


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_the_plugin_tells_the_mode_of_each_sample_as_vw3_decode_does(lua: str, tmp_path: Path) -> None:
    samples = _samples()
    expected = [str(sample_mode(sample, complete)) for sample in samples for complete in (False, True)]
    assert {"ascii", "rtu", "None"} <= set(expected)  # (every answer exercised)
    both = [sample for sample in samples if None not in (frame_end(sample), rtu_pair_end(sample))]
    assert len(both) > 5  # (which ends first tells)
    literals = ", ".join('"' + "".join(f"\\{byte:03d}" for byte in sample) + '"' for sample in samples)
    script = tmp_path / "modes.lua"
    script.write_text(
        f"dofile({str(PLUGIN)!r})\n"
        'local sample_mode = package.loaded["vw3.env"].sample_mode\n'
        f"for _, sample in ipairs({{ {literals} }}) do\n"
        "  print(tostring(sample_mode(sample, false)))\n  print(tostring(sample_mode(sample, true)))\nend\n",
        encoding="utf-8")
    result = subprocess.run([ensure_tool(lua, lua), str(script)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout.split() == [text.replace("None", "nil") for text in expected]
