"""The plugin's mode sample (lua/src/dissector.lua sample_and_dissect) asked sample_mode twice for each record it
held: whether the bytes so far tell, then what they would tell were the capture to end there, each a scan of up to
MODE_REACH (1026) bytes for a whole ASCII frame and for two RTU frames back to back (66faf8e), the RTU one from
every start again at each record. On an RTU line that leaves a glitch byte FE after each frame (the sigrok-dumps
wizmodbus line leaves FE after responses; its 00 after requests reads as the request's last byte, CRC-16 having no
final XOR, so its frames are back to back) no two frames are: each record of the first 1026 bytes was held and
scanned twice (bench/lua_throughput.py --instructions on 2,000 such records: 4.46 M instructions a record).
Now sample_modes gives both answers from one look, and rtu_pair_end runs a CRC from each possible start a byte
a step, carried from record to record (sample.scan). The decision is protocol/ascii.py sample_mode's, unchanged:
Lua's rtu_pair_end is Python's on each sample, both answers are Python's at each record's end with the scan
carried, and the plugin decodes the glitchy line as vw3-decode does."""
from __future__ import annotations

import random
import subprocess
from pathlib import Path

import pytest

from helpers import rtu
from lua_compare import assert_same_as_vw3_decode
from lua_harness import PLUGIN, ensure_tool, run_tshark, write_pcap
from test_mode_after_long_noise import RTU_PAIR, _samples

from dissector.protocol.ascii import MODE_REACH, rtu_pair_end, sample_mode

pytestmark = pytest.mark.integration

POLL, ANSWER = rtu("01 03 0000 0002") + b"\xfe", rtu("01 03 04 0001 0002") + b"\xfe"
GLITCHY = (POLL + ANSWER) * 60  # (1200 bytes: no two frames back to back)


def _literal(sample: bytes) -> str:
    return '"' + "".join(f"\\{byte:03d}" for byte in sample) + '"'


def _run(lua: str, body: str, tmp_path: Path) -> list[str]:
    script = tmp_path / "modes.lua"
    header = f"dofile({str(PLUGIN)!r})\nlocal env = package.loaded[\"vw3.env\"]\n"
    script.write_text(header + body, encoding="utf-8")
    result = subprocess.run([ensure_tool(lua, lua), str(script)], capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr[-2000:]
    return result.stdout.splitlines()


def _samples_with_pairs() -> list[bytes]:
    rng = random.Random(7)
    frames = [RTU_PAIR[:8], RTU_PAIR[8:], POLL[:-1], ANSWER[:-1], rtu("F7 10 0006 0002 04 41700000"),
              rtu("11 0F 0013 000A 02 CD01"), rtu("01 2B 0E 01 00")]
    glue = [b"", b"", b"\x00", b"\xfe", b"\xff\xff", bytes(rng.randrange(256) for _ in range(5))]
    out = []
    for _ in range(120):
        out.append(b"".join(rng.choice(glue) + rng.choice(frames) for _ in range(rng.randint(1, 12))))
    out += [bytes(rng.randrange(256) for _ in range(rng.randint(10, 600))) for _ in range(40)]
    return out + [GLITCHY[:MODE_REACH], GLITCHY[:MODE_REACH] + RTU_PAIR]


def test_the_glitchy_line_holds_no_pair() -> None:
    assert rtu_pair_end(GLITCHY[:MODE_REACH]) is None and sample_mode(GLITCHY, False) == "rtu"


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_the_pair_scan_finds_where_pythons_does(lua: str, tmp_path: Path) -> None:
    samples = _samples_with_pairs()
    expected = [str(rtu_pair_end(sample)) for sample in samples]
    assert sum(text != "None" for text in expected) > 100  # (pairs found, and not)
    literals = ", ".join(map(_literal, samples))
    body = f"for _, s in ipairs({{ {literals} }}) do print(tostring(env.rtu_pair_end(s))) end\n"
    lines = _run(lua, body, tmp_path)
    assert lines == [text.replace("None", "nil") for text in expected]


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_both_answers_at_each_record_are_pythons(lua: str, tmp_path: Path) -> None:
    """Records of 1 to 40 bytes: sample_modes on the sample so far, its scan carried from record to record
    (as dissector.lua calls it), is (sample_mode(sample, False), sample_mode(sample, True)) at each."""
    rng = random.Random(11)
    samples = [*_samples(), *_samples_with_pairs(), GLITCHY]
    cuts, expected = [], []
    for sample in samples:
        ends, at = [], 0
        while at < min(len(sample), MODE_REACH):
            at = min(at + rng.randint(1, 40), len(sample), MODE_REACH)
            ends.append(at)
            expected.append(f"{sample_mode(sample[:at], False)} {sample_mode(sample[:at], True)}")
        cuts.append("{" + ", ".join(map(str, ends)) + "}")
    assert {"None rtu", "None ascii", "rtu rtu", "ascii ascii"} <= set(expected)  # (every answer exercised)
    body = (f"local samples, cuts = {{ {', '.join(map(_literal, samples))} }}, {{ {', '.join(cuts)} }}\n"
            "for index, sample in ipairs(samples) do\n"
            "  local scan = env.pair_scan()\n"
            "  for _, at in ipairs(cuts[index]) do\n"
            "    local now, ended = env.sample_modes(sample:sub(1, at), scan)\n"
            '    print(tostring(now) .. " " .. tostring(ended))\n'
            "  end\nend\n")
    assert _run(lua, body, tmp_path) == [text.replace("None", "nil") for text in expected]


def test_the_plugin_decodes_the_glitchy_line_as_vw3_decode(tmp_path: Path) -> None:
    records = [(frame, 1_700_000_000 + index * 0.05) for index, frame in enumerate([POLL, ANSWER] * 60)]
    pcap = write_pcap(tmp_path / "glitchy.pcap", records)
    info = run_tshark(pcap, "-T", "fields", "-e", "_ws.col.Info").stdout.splitlines()
    assert info == ["1 Read Holding Registers request 0..1 (2); noise (1 byte)",
                    "1 Read Holding Registers response 0..1 (2); noise (1 byte)"] * 60
    assert_same_as_vw3_decode(pcap)
