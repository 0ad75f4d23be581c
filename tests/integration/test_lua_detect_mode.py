"""The plugin tells a stream's mode from its first bytes as vw3-decode does (protocol/ascii.py sample_mode,
detect_mode and holds_frame; lua/src/ascii.lua sample_mode and detect_mode, whose holds_frame reads the hex
pairs with the ASCII framer's hex_pairs and checks them with its lrc): the same answer for the same sample
(a whole input: `complete`; test_mode_after_long_noise.py covers the samples still growing), under plain
lua5.2 and lua5.4 (the pure modules, no tshark), on samples made to sit either side of each rule and on random
mixes of ':', hex digits, CR, LF and binary bytes."""
from __future__ import annotations

import random
import subprocess
from pathlib import Path

import pytest

from lua_harness import PLUGIN, ensure_tool

from dissector.protocol.ascii import detect_mode, sample_mode
from dissector.sources.reader import MODE_SAMPLE

LINE = b":02062329000AA2\r\n"  # slave 2 writes 10 to register 9001 (its LRC A2 good)

# (sample, the mode vw3-decode tells from it)
SAMPLES = [
    (LINE, "ascii"),
    (b"\xff" * 40 + LINE, "ascii"),  # a whole frame after noise
    (b"\xff" * 40 + LINE.replace(b"\r", b""), "ascii"),  # a line that lost its CR
    (b"\xff" * 40 + LINE.lower(), "ascii"),  # lower-case digits
    (b"\xff" * 40 + LINE.replace(b"A2", b"A3"), "rtu"),  # its LRC bad
    (b"\xff" * 40 + b":020623\r\n", "rtu"),  # odd digits
    (b"\xff" * 40 + b":02FC\r\n", "rtu"),  # no LRC: fewer than three binary bytes
    (b"\xff" * 40 + b":0101FE\r\n", "ascii"),  # three binary bytes, the LRC good
    (b"\xff" * 40 + b":020623290", "rtu"),  # no line end
    (b"\xff" * 40 + b":02062329000AA2\r\r\n", "rtu"),  # CR CR LF: no line end after the digits
    (b"\xff" * 40 + b":02062329000AA2 \r\n", "rtu"),  # a space before the line end
    (b"\xff" * 40 + b":0206:2329000AA2\r\n", "rtu"),  # cut by a ':' (the second has a bad LRC)
    (b"\xff" * 30 + b":0206" + LINE, "ascii"),  # a ':' cut short, then a whole frame
    (b"\xff" * 30 + b":02062329000AA3\r\n" + LINE, "ascii"),  # a bad LRC, then a good one
    # RTU whose bytes hold ':' and hex digits, and CR LF: no whole frame, mostly binary
    (bytes.fromhex("0C 03 20 D0 00 03 0E EF") + b":0102\r\n" + bytes(range(0x80, 0xB2)), "rtu"),
    (b":0102030405060708090A0B0C0D0E0F10", "ascii"),  # no whole frame, nine bytes in ten of the alphabet
    (b"", "rtu"),
]


def _random_samples(count: int) -> list[bytes]:
    pieces = [b":", b"\r", b"\n", b"\r\n", b"0", b"1", b"F", b"a", b"A2", b"\x00", b"\xff", b"G", LINE[:-2]]
    rng = random.Random(30)
    samples = []
    for _ in range(count):
        sample = b"".join(rng.choice(pieces) for _ in range(rng.randint(1, 30)))
        samples.append(sample[:MODE_SAMPLE])
    return samples


def _lua_modes(lua: str, samples: list[bytes], tmp_path: Path) -> list[str]:
    """The plugin's mode of each sample as a whole input, run under `lua` on the pure modules."""
    literals = ", ".join('"' + "".join(f"\\{byte:03d}" for byte in sample) + '"' for sample in samples)
    script = tmp_path / "modes.lua"
    script.write_text(
        f"dofile({str(PLUGIN)!r})\n"
        'local sample_mode = package.loaded["vw3.env"].sample_mode\n'
        f"for _, sample in ipairs({{ {literals} }}) do print(sample_mode(sample, true)) end\n",
        encoding="utf-8")
    result = subprocess.run([ensure_tool(lua, lua), str(script)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr[-2000:]
    return result.stdout.split()


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_the_plugin_tells_the_mode_vw3_decode_tells(lua: str, tmp_path: Path) -> None:
    samples = [sample for sample, _ in SAMPLES]
    assert [detect_mode(sample) for sample in samples] == [mode for _, mode in SAMPLES]
    assert [sample_mode(sample, True) for sample in samples] == [mode for _, mode in SAMPLES]
    assert _lua_modes(lua, samples, tmp_path) == [mode for _, mode in SAMPLES]


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_random_samples_get_the_same_mode(lua: str, tmp_path: Path) -> None:
    samples = _random_samples(400)
    expected = [sample_mode(sample, True) for sample in samples]
    assert expected.count("ascii") >= 40 and expected.count("rtu") >= 40  # (both answers exercised)
    assert _lua_modes(lua, samples, tmp_path) == expected
