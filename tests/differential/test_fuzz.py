"""Fuzzing in the suite, bounded in time: hostile input never raises anything but the module's own error.

Each target gets a few hundred hypothesis examples (a few seconds each); bench/fuzz_campaign.py runs
the same properties for as long as asked. Inputs are biased towards what breaks parsers: valid frames
and files with a few bytes mutated, cut or spliced, rather than uniform random bytes that every check
rejects on the first byte.
"""
from __future__ import annotations

import io
import math
import random
import struct

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from dissector.framing.ascii import AsciiFramer
from dissector.app.cli import Environment, run
from dissector.render.filters import FilterError, compile_filter
from dissector.framing.rtu import RtuFramer
from dissector.framing.stream import NOISE_ITEM_MAX
from dissector.protocol.grammar import GrammarError, parse_pdu
from dissector.devices.maps import ProfileError, parse_map
from dissector.model import Chunk, Frame, Kind
from dissector.pipeline import Dissector, dissect
from dissector.devices.build import build_annotator
from dissector.render.jsonout import item_to_dict
from dissector.sources.reader import SourceError, open_source
from strategies import adu, transactions

FUZZ = settings(deadline=None, max_examples=300, suppress_health_check=list(HealthCheck))
FEW = settings(deadline=None, max_examples=120, suppress_health_check=list(HealthCheck))

# -- inputs ---------------------------------------------------------------------------------------
INTERESTING = [0, 1, 0x7F, 0x80, 0xFF, 0xFFFF, 0x7FFFFFFF, 0xFFFFFFFF, 12, 16, 28, 0x0A0D0D0A]


def mutate(data: bytes, seed: int, count: int) -> bytes:
    """`count` random edits: flip, set, insert, delete, cut, overwrite with an interesting integer."""
    rng = random.Random(seed)
    out = bytearray(data)
    for _ in range(count):
        how = rng.randrange(6)
        at = rng.randrange(len(out) + 1)
        if how == 0 and out and at < len(out):
            out[at] ^= 1 << rng.randrange(8)
        elif how == 1 and at < len(out):
            out[at] = rng.randrange(256)
        elif how == 2:
            out[at:at] = rng.randbytes(rng.randint(1, 8))
        elif how == 3:
            del out[at : at + rng.randint(1, 8)]
        elif how == 4:
            del out[at:]
        else:
            value = rng.choice(INTERESTING)
            out[at : at + 4] = struct.pack(rng.choice("<>") + "I", value)
    return bytes(out)


@st.composite
def rtu_streams(draw: st.DrawFn) -> bytes:
    """Valid transactions, random bytes and mutated frames, concatenated."""
    parts: list[bytes] = []
    for _ in range(draw(st.integers(0, 8))):
        kind = draw(st.sampled_from(["pair", "pair", "noise", "mutated", "cut"]))
        if kind == "noise":
            parts.append(draw(st.binary(max_size=40)))
            continue
        request, response, _ = draw(transactions())
        if kind == "pair":
            parts += [request, response]
        elif kind == "mutated":
            parts.append(mutate(request + response, draw(st.integers(0, 2**32)), draw(st.integers(1, 4))))
        else:
            parts.append((request + response)[: draw(st.integers(0, len(request) + len(response)))])
    return b"".join(parts)


def ascii_frame(binary: bytes) -> bytes:
    lrc = (-sum(binary)) & 0xFF
    return b":" + (binary + bytes([lrc])).hex().upper().encode() + b"\r\n"


@st.composite
def ascii_streams(draw: st.DrawFn) -> bytes:
    parts: list[bytes] = []
    for _ in range(draw(st.integers(0, 8))):
        request, response, _ = draw(transactions())
        text = ascii_frame(request[:-2]) + ascii_frame(response[:-2])
        kind = draw(st.sampled_from(["ok", "mutated", "noise", "alphabet"]))
        if kind == "mutated":
            text = mutate(text, draw(st.integers(0, 2**32)), draw(st.integers(1, 4)))
        elif kind == "noise":
            text = draw(st.binary(max_size=30))
        elif kind == "alphabet":
            text = bytes(draw(st.lists(st.sampled_from(b":0123456789ABCDEFabcdef\r\n"), max_size=80)))
        parts.append(text)
    return b"".join(parts)


def split(data: bytes, cuts: list[int]) -> list[Chunk]:
    points = sorted({cut % (len(data) + 1) for cut in cuts} | {0, len(data)})
    return [Chunk(data[a:b]) for a, b in zip(points, points[1:])]


def _signature(items: list) -> list[tuple]:
    return [
        (item.offset, item.kind, item.raw, item.crc_ok if isinstance(item, Frame) else item.reason)
        for item in items
    ]


def _framer_property(data: bytes, cuts: list[int], make: type) -> None:
    one = make()
    reference = one.feed(Chunk(data)) + one.finish()
    pieces = make()
    items = []
    for chunk in split(data, cuts):
        items += pieces.feed(chunk)
    items += pieces.finish()
    # Every byte in exactly one item, in order, and the same answer for any split.
    assert b"".join(item.raw for item in reference) == data
    position = 0
    for item in reference:
        assert item.offset == position
        assert item.raw
        position += len(item.raw)
        if item.kind is Kind.NOISE:
            assert len(item.raw) <= NOISE_ITEM_MAX
    assert _signature(items) == _signature(reference)


@FUZZ
@given(rtu_streams(), st.lists(st.integers(0, 10_000), max_size=12))
def test_rtu_framer_conserves_bytes_and_ignores_splits(data: bytes, cuts: list[int]) -> None:
    _framer_property(data, cuts, RtuFramer)


@FUZZ
@given(st.binary(max_size=600), st.lists(st.integers(0, 10_000), max_size=12))
def test_rtu_framer_on_uniform_bytes(data: bytes, cuts: list[int]) -> None:
    _framer_property(data, cuts, RtuFramer)


@FUZZ
@given(ascii_streams(), st.lists(st.integers(0, 10_000), max_size=12))
def test_ascii_framer_conserves_bytes_and_ignores_splits(data: bytes, cuts: list[int]) -> None:
    _framer_property(data, cuts, AsciiFramer)


@FEW
@given(st.one_of(rtu_streams(), ascii_streams()), st.lists(st.integers(0, 10_000), max_size=8),
       st.sets(st.integers(0, 8)))
def test_live_idle_flushes_keep_every_byte(data: bytes, cuts: list[int], idle_after: set[int]) -> None:
    # Live capture calls flush_idle() after a silence: the framer gives up what it holds and goes on
    # with the next bytes. Frames may differ from a file's, but no byte may be lost or doubled.
    for make in (RtuFramer, AsciiFramer):
        dissector = Dissector(framer=make())
        items = []
        for index, chunk in enumerate(split(data, cuts)):
            items += dissector.feed(chunk)
            if index in idle_after:
                items += dissector.flush_idle()
        items += dissector.finish()
        assert b"".join(item.raw for item in items) == data
        assert [item.offset for item in items] == sorted(item.offset for item in items)


ANNOTATOR = build_annotator(["atv71", "3=sel749m"], [])


@FUZZ
@given(rtu_streams(), st.lists(st.integers(0, 10_000), max_size=6))
def test_whole_pipeline_with_profiles_renders_every_item(data: bytes, cuts: list[int]) -> None:
    # Decoding, annotation and the NDJSON view of damaged frames must not raise either.
    items = list(dissect(split(data, cuts), annotate=ANNOTATOR))
    assert b"".join(item.raw for item in items) == data
    for item in items:
        item_to_dict(item)


# -- grammars ------------------------------------------------------------------------------------
FUNCTIONS = st.one_of(
    st.sampled_from([1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 15, 16, 17, 20, 21, 22, 23, 24, 43, 0x60, 0x7D]),
    st.integers(0, 255),
)


@FUZZ
@given(FUNCTIONS, st.sampled_from([Kind.REQUEST, Kind.RESPONSE, Kind.EXCEPTION]), st.binary(max_size=300))
def test_grammars_raise_only_grammar_error(function: int, kind: Kind, data: bytes) -> None:
    try:
        parse_pdu(function, kind, data)
    except GrammarError as error:
        assert str(error) and "\n" not in str(error)


@FUZZ
@given(transactions(), st.integers(0, 2**32), st.integers(1, 3))
def test_grammars_on_mutated_valid_pdus(pair: tuple[bytes, bytes, dict], seed: int, count: int) -> None:
    for frame, kind in ((pair[0], Kind.REQUEST), (pair[1], Kind.RESPONSE)):
        data = mutate(frame[2:-2], seed, count)
        try:
            parse_pdu(frame[1] & 0x7F, kind, data)
        except GrammarError:
            pass


# -- capture readers -------------------------------------------------------------------------------
FRAMES = [adu(12, bytes.fromhex("0320D00003")), adu(12, bytes.fromhex("0306800000030002")),
          adu(12, bytes.fromhex("8302")), adu(2, bytes.fromhex("2B0E0100"))]


def _pcap() -> bytes:
    out = struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 147)
    for index, frame in enumerate(FRAMES):
        out += struct.pack("<IIII", 1_700_000_000 + index, 500, len(frame), len(frame)) + frame
    return out


def _block(block_type: int, body: bytes) -> bytes:
    body += b"\0" * (-len(body) % 4)
    return struct.pack("<II", block_type, len(body) + 12) + body + struct.pack("<I", len(body) + 12)


def _pcapng() -> bytes:
    out = _block(0x0A0D0D0A, struct.pack("<IHHq", 0x1A2B3C4D, 1, 0, -1))
    # tsresol 10^-6 then end of options; one RTAC interface too
    out += _block(1, struct.pack("<HHI", 147, 0, 0) + struct.pack("<HHB3x", 9, 1, 6) + b"\0" * 4)
    out += _block(1, struct.pack("<HHI", 250, 0, 0))
    for index, frame in enumerate(FRAMES):
        stamp = (1_700_000_000 + index) * 1_000_000
        out += _block(6, struct.pack("<IIIII", 0, stamp >> 32, stamp & 0xFFFFFFFF, len(frame), len(frame)) + frame)
    rtac = struct.pack(">IIBBH", 1_700_000_009, 0, 2, 0, 0) + FRAMES[0]
    out += _block(6, struct.pack("<IIIII", 1, 0, 0, len(rtac), len(rtac)) + rtac)
    out += _block(3, struct.pack("<I", len(FRAMES[1])) + FRAMES[1])
    out += _block(0x0BAD, b"vendor data")
    out += _block(0x1234, b"unknown block")
    return out


def _hexdump() -> bytes:
    lines = ["# capture", *(f"1700000000.{i:03d} {frame.hex(' ')}" for i, frame in enumerate(FRAMES))]
    return ("\n".join(lines) + "\n").encode()


def _ascii() -> bytes:
    return b"".join(ascii_frame(frame[:-2]) for frame in FRAMES)


VALID_FILES = {"pcap": _pcap(), "pcapng": _pcapng(), "hex": _hexdump(), "ascii": _ascii(), "raw": b"".join(FRAMES)}


def read_all(data: bytes, fmt: str | None) -> int:
    """Open and read a capture from memory; the bytes delivered. Only SourceError may come out."""
    source = open_source("-", fmt, chunk_size=256, stdin=io.BufferedReader(io.BytesIO(data)))
    total = 0
    for chunk in source:
        total += len(chunk.data)
        assert chunk.time is None or math.isfinite(chunk.time)  # NDJSON has no Infinity
        assert len(chunk.data) <= 256 or source.format in ("hexdump",)
    for warning in source.warnings:
        assert "\n" not in warning
    return total


def test_the_valid_files_read_cleanly() -> None:
    for name, data in VALID_FILES.items():
        source = open_source("-", stdin=io.BufferedReader(io.BytesIO(data)))
        chunks = list(source)
        expected = {"hex": "hexdump"}.get(name, name)
        assert source.format == expected, name
        payload = b"".join(chunk.data for chunk in chunks)
        if name in ("pcap", "hex", "raw"):
            assert payload == b"".join(FRAMES), name
        assert source.warnings == ([] if name != "pcapng" else source.warnings)


@FUZZ
@given(st.sampled_from(sorted(VALID_FILES)), st.integers(0, 2**32), st.integers(1, 6),
       st.sampled_from([None, "same", "raw", "pcap", "pcapng", "hex", "ascii"]))
def test_readers_on_mutated_files_raise_only_source_error(
    name: str, seed: int, count: int, forced: str | None
) -> None:
    data = mutate(VALID_FILES[name], seed, count)
    fmt = name if forced == "same" else forced
    try:
        read_all(data, fmt)
    except SourceError as error:
        assert str(error) and "\n" not in str(error)


STAMPS = st.one_of(
    st.from_regex(r"\A\d{1,400}\.\d{1,30}\Z"),
    st.from_regex(r"\A\[?\d{4}-\d{2}-\d{2}[T ]\d{2}:\d{2}:\d{2}(\.\d{1,9})?(Z|[+-]\d{2}:?\d{2})?\]?:?\Z"),
    st.from_regex(r"\A\d{2}:\d{2}:\d{2}(\.\d{1,20})?\Z"),
)


@FEW
@given(st.lists(st.tuples(STAMPS, st.binary(min_size=1, max_size=12)), min_size=1, max_size=4))
def test_hexdump_timestamps_are_finite_or_refused(lines: list[tuple[str, bytes]]) -> None:
    # Regression: 400 digits before the point made float('inf'), and NDJSON printed "time": Infinity.
    text = "".join(f"{stamp} {data.hex(' ')}\n" for stamp, data in lines).encode()
    try:
        read_all(text, "hex")
    except SourceError as error:
        assert " line " in str(error) and "\n" not in str(error)


# -- register maps ---------------------------------------------------------------------------------
CELLS = st.one_of(
    st.sampled_from(["", "8401", "0x20D1", "16#2000", "-1", "70000", "CHCF", "0.1", "0", "R", "RW", "X",
                     "1=a;2=b", "1=a;1=b", "=x", "16=bit", "1", "2", "Hz", '"a,b"', "nan", "1e999"]),
    st.text(st.characters(codec="utf-8", exclude_categories=("Cs",)), max_size=12),
)
HEADERS = st.sampled_from([
    "address,code,name,unit,scale,access,enum,bits,signed,source",
    "address,code",
    "address,code,scale,enum,bits,signed",
    "code,address,access",
])


@FUZZ
@given(HEADERS, st.lists(st.lists(CELLS, min_size=1, max_size=11).map(",".join), max_size=6))
def test_map_loader_names_the_line_of_every_error(header: str, rows: list[str]) -> None:
    text = "\n".join(["# a map", header, *rows])
    lines = text.splitlines()
    try:
        parse_map(text, "fuzz.csv")
    except ProfileError as error:
        message = str(error)
        assert "\n" not in message
        assert message.startswith("fuzz.csv:")
        number = message.split(":")[1]
        assert number.isdigit(), message
        assert 2 <= int(number) <= len(lines), message
        assert lines[int(number) - 1].strip(" \t\n\r\x0b\x0c"), message  # (blank: ASCII's, as both map readers see it)


# -- display filters --------------------------------------------------------------------------------
FILTER_WORDS = st.sampled_from([
    "slave", "function", "kind", "address", "value", "code", "status", "crc_ok", "warnings", "exception",
    "time", "scaled", "name", "==", "!=", "~=", "any_ne", "<", ">=", "eq", "and", "or", "not", "!", "&&", "||", "in",
    "contains", "(", ")", "{", "}", "..", ",", "12", "0x20D1", "1.5", "8400..8402", '"CHCF"', '"a\\"b"',
    "true", "false", '"', "\\", "9" * 30, "-", "#",
])


@FUZZ
@given(st.one_of(st.lists(FILTER_WORDS, max_size=12).map(" ".join), st.text(max_size=40)))
def test_filter_parser_raises_only_filter_error(text: str) -> None:
    try:
        predicate = compile_filter(text)
    except FilterError as error:
        assert 0 <= error.position <= len(text)
        return
    for item in SAMPLE_ITEMS:
        assert predicate(item) in (True, False)


def _sample_items() -> list[dict]:
    data = b"".join(FRAMES) + rtu_noise()
    return [item_to_dict(item) for item in dissect([Chunk(data)], annotate=ANNOTATOR)]


def rtu_noise() -> bytes:
    return bytes.fromhex("ff00ff")


SAMPLE_ITEMS = _sample_items()


# -- the whole CLI ---------------------------------------------------------------------------------
OPTIONS = st.lists(
    st.sampled_from([["--json"], ["-V"], ["-x"], ["--stats"], ["-n"], ["--format", "raw"],
                     ["--format", "pcap"], ["--format", "pcapng"], ["--format", "hex"],
                     ["--format", "ascii"], ["--mode", "ascii"], ["--mode", "rtu"],
                     ["--profile", "sel749m"], ["--address-style", "plc"]]),
    max_size=3,
)


@FEW
@given(st.sampled_from(sorted(VALID_FILES)), st.integers(0, 2**32), st.integers(0, 6), OPTIONS)
def test_cli_on_random_files_exits_cleanly(
    name: str, seed: int, count: int, options: list[list[str]]
) -> None:
    data = mutate(VALID_FILES[name], seed, count) if count else VALID_FILES[name]
    argv = ["-", *[word for option in options for word in option]]
    out, err = io.StringIO(), io.StringIO()
    env = Environment(io.BufferedReader(io.BytesIO(data)), out, err, stdout_isatty=False, stderr_isatty=False)
    status = run(argv, env)
    lines = err.getvalue().splitlines()
    assert "Traceback" not in err.getvalue()
    assert all(line.startswith("vw3-decode: ") for line in lines), lines
    errors = [line for line in lines if not line.startswith("vw3-decode: warning: ")]
    if status == 0:
        assert errors == []
    else:
        assert status == 2 and len(errors) == 1, (status, lines)
