"""The plugin's map reader shows a text as vw3-decode does (real tshark with lua/vw3.lua against
`vw3-decode --json --map`: a map whose names hold a bidi override, separators, private use, an emoji and
unassigned code points; a map that is not UTF-8, refused with the same message). Under plain Lua (lua/src/maps.lua printable and python_repr, by the
frozen table of dissector/data/nonprintable.toml): Python's repr of every code point either side of each
range's edges, under lua5.2 and lua5.4; and it refuses the bytes Python's strict UTF-8 decoder refuses
(maps.load_map_file: `not UTF-8 text`), for every two-byte string and the three- and four-byte strings
built from the bytes where UTF-8's rules change."""
from __future__ import annotations

import itertools
import subprocess
import sys
import unicodedata
from pathlib import Path

import pytest

from dissector.codegen import printable_table
from dissector.model import Kind
from lua_compare import compare
from lua_harness import PLUGIN, ROOT, ensure_tool, lua_items, python_items, write_pcap
from lua_session import frame
from unicode_edges import boundaries

REPR = """local vw3 = dofile(arg[1])
io.stdout:write(package.loaded["vw3.env"].python_repr(io.stdin:read("*a")))"""

# (one map text a line, as hex: 1 when the plugin reads it as UTF-8, 0 when it says `m: not UTF-8 text`, alone
# or with why: a UTF-16 byte order mark first, maps.py's utf16 message)
DECODES = """local vw3 = dofile(arg[1])
for line in io.stdin:lines() do
  local text = line:gsub("%x%x", function(hex) return string.char(tonumber(hex, 16)) end)
  local _, problem = package.loaded["vw3.env"].parse_map(text, "m")
  io.stdout:write(problem ~= nil and problem:find("^m: not UTF%-8 text") and "0" or "1")
end"""

EDGES = [0x00, 0x41, 0x7F, 0x80, 0x8F, 0x90, 0x9F, 0xA0, 0xBF, 0xC0, 0xC1, 0xC2, 0xDF, 0xE0, 0xE1, 0xEC, 0xED,
         0xEE, 0xEF, 0xF0, 0xF1, 0xF3, 0xF4, 0xF5, 0xF7, 0xF8, 0xFF]
LEADS4 = [0xEF, 0xF0, 0xF1, 0xF3, 0xF4, 0xF5, 0xF7, 0xF8]
SECONDS4 = [0x41, 0x7F, 0x80, 0x8F, 0x90, 0xBF, 0xC0]


def _lua(lua: str, script: str, data: bytes, folder: Path) -> str:
    path = folder / "script.lua"
    path.write_text(script, encoding="utf-8")
    result = subprocess.run([ensure_tool(lua, lua), str(path), str(PLUGIN)], input=data, capture_output=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr.decode(errors="replace")
    return result.stdout.decode("utf-8")


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_shows_what_python_repr_shows(lua: str, tmp_path: Path) -> None:
    if printable_table.frozen()["unicode"] != unicodedata.unidata_version:
        pytest.skip("the plugin's table is another Unicode version's than this Python's repr")
    text = "".join(chr(code) for code in boundaries() if not 0xD800 <= code <= 0xDFFF)  # (UTF-8 has none)
    for sample in (text, text + "'", text + "'\"", "\u202e\u2028\u3000\ufeff\ue000\U0001f600\u0378"):
        assert _lua(lua, REPR, sample.encode(), tmp_path) == repr(sample)


@pytest.mark.parametrize("lua", ["lua5.2", "lua5.4"])
def test_refuses_what_python_does_not_decode(lua: str, tmp_path: Path) -> None:
    samples = [bytes(pair) for pair in itertools.product(range(256), repeat=2)]
    samples += [bytes(three) for three in itertools.product(EDGES, repeat=3)]
    samples += [bytes([lead, second, *rest]) for lead in LEADS4 for second in SECONDS4
                for rest in itertools.product([0x41, 0x80, 0xBF, 0xC0], repeat=2)]

    def decodes(data: bytes) -> str:
        try:
            data.decode("utf-8")
        except UnicodeDecodeError:
            return "0"
        return "1"

    got = _lua(lua, DECODES, "".join(data.hex() + "\n" for data in samples).encode(), tmp_path)
    assert got == "".join(map(decodes, samples))


NAMES_MAP = ("address,code,name,unit,enum\n"
             "1,A\u202eB,x\u3000y\u200bz,\ufeffkm,\n"
             "2,C,\ue000\U0001f600\u0378\U000e0001,,1=\u202e;2=\U0001f600\n")  # (labels take no unit)


def _session(tmp_path: Path) -> Path:
    request = frame(5, 3, Kind.REQUEST, start=1, quantity=2)
    answer = frame(5, 3, Kind.RESPONSE, byte_count=4, values=[7, 2])
    return write_pcap(tmp_path / "names.pcap", [(request, 1767225600.0), (answer, 1767225600.02)])


def test_map_names_shown_as_vw3_decode_shows_them(tmp_path: Path) -> None:
    names = tmp_path / "names.csv"
    names.write_text(NAMES_MAP, encoding="utf-8")
    pcap = _session(tmp_path)
    python = python_items(pcap, [], "--map", str(names))
    lua, record_experts, _ = lua_items(pcap, "-o", f"vw3.maps:{names}")
    differences = compare(python, lua)
    assert not differences, "\n".join(differences[:40])
    assert not any("Preferences" in text for _, text in record_experts)
    texts = [reg.get("text", "") + reg.get("code", "") for item in python for reg in item.data.get("registers", [])]
    assert any("A\\u202eB" in text for text in texts) and any("\U0001f600" in text for text in texts), texts


def test_a_map_that_is_not_utf8_is_refused_alike(tmp_path: Path) -> None:
    bad = tmp_path / "latin1.csv"
    bad.write_bytes(b"address,code,name\n1,A,caf\xe9\n")
    pcap = _session(tmp_path)
    message = f"{bad}: not UTF-8 text"
    cli = subprocess.run([sys.executable, "-m", "dissector", str(pcap), "--map", str(bad)], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert cli.returncode != 0 and cli.stderr.strip().endswith(message), cli.stderr
    _, record_experts, _ = lua_items(pcap, "-o", f"vw3.maps:{bad}")
    assert any(text.endswith(message) for _, text in record_experts), (message, record_experts)
