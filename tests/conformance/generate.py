"""Shared conformance vectors: the Python reference's result of each stage, for a set of inputs, in files
every port is checked against (issue 30).

    python3 tests/conformance/generate.py          # rewrite vectors.json and vectors.lua
    python3 tests/conformance/generate.py --check  # exit 1 when they are stale

Inputs: the frames printed in the seed pages (tests/support/seed_frames.py), one frame alone and the
pages' transactions in order; crafted transactions that break each lifting rule of data/modbus.toml
[lift] once (limits, span, byte counts, coil values, echoes, FIFO counts); the shipped captures
(captures/*.bin). Stages, per input (see tests/conformance/README.md for the format):
framing -> pairing -> decoding -> profile selection -> annotation -> summary lines; the shipped maps
as map reading gives them, and map texts good and malformed as parse_map reads them (rows or message).
tests/unit/test_conformance.py fails when these files are stale and checks the compiled engine's summary
lines against them; the plugin's runner reads vectors.lua.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tests" / "support")]

from construct import Container, ListContainer  # noqa: E402

from dissector.app.preselect import choose_profiles  # noqa: E402
from dissector.codegen.rules_lua import lua_literal  # noqa: E402
from dissector.decode.fields import decode_frame  # noqa: E402
from dissector.decode.pairing import Pairer  # noqa: E402
from dissector.devices.build import build_annotator  # noqa: E402
from dissector.devices.maps import load_builtin_map, load_map_file, parse_map  # noqa: E402
from dissector.errors import ProfileError  # noqa: E402
from dissector.framing.ascii import AsciiFramer  # noqa: E402
from dissector.framing.rtu import RtuFramer  # noqa: E402
from dissector.model import Chunk, Frame, Item, Noise  # noqa: E402
from dissector.pipeline import Dissector  # noqa: E402
from dissector.protocol.crc import with_crc  # noqa: E402

JSON_FILE = HERE / "vectors.json"
LUA_FILE = HERE / "vectors.lua"
FORMAT = 1
PROFILE = "auto"  # the CLI's default: the selection stage is part of what is checked


def _crafted() -> list[tuple[str, bytes]]:
    """One transaction per lifting rule it breaks (request, then its answer where one is needed), and
    answers whose data do not fit their layout (malformed: a count past the end, a byte count too small)."""
    h = bytes.fromhex
    f = lambda text: with_crc(h(text))  # noqa: E731
    return [
        ("fc3 quantity above the limit", f("01030000007E")),
        ("fc3 zero quantity", f("010300000000")),
        ("fc1 span past 65535", f("0101FFF00020")),
        ("fc3 byte count disagrees", f("010300000002") + f("0103020007")),
        ("fc3 odd byte count", f("010300000002") + f("010303000102")),
        ("fc3 answer without its request", f("01030400010002")),
        ("fc1 byte count disagrees", f("010100000010") + f("01010105")),
        ("fc5 coil value neither on nor off", f("010500011234") + f("010500011234")),
        ("fc5 echo differs", f("01050001FF00") + f("010500020000")),
        ("fc6 echo value differs", f("010600100007") + f("010600100008")),
        ("fc15 byte count disagrees", f("010F0000000A0103FF")),
        ("fc15 answer start differs", f("010F0000000A0203FF") + f("010F0001000A")),
        ("fc16 quantity above the limit", f("01100000007C00")),
        ("fc16 byte count disagrees", f("011000000002020007") + f("011000000002")),
        ("fc22 mask write", f("011600040F0F00F0") + f("011600040F0F00F0")),
        ("fc23 limits", f("0117000000800010007A00")),
        ("fc23 write", f("0117000A00020014000102002A") + f("01170400010002")),
        ("fc24 fifo above 31", f("011804DE") + f("011800420020" + "0001" + "0002" * 31)),
        ("fc24 fifo byte count", f("011804DE") + f("011800080002000100020003")),
        ("fc24 fifo count past the end", f("011804DE") + f("011800060005" + "0001" * 2)),
        ("fc17 byte count below 2", f("0111") + f("01110100")),
        ("fc8 unknown sub-function", f("010800630000") + f("010800630000")),
        # (data/modbus.toml [pairing]: 04 is never answered, an answer echoes its request's sub-function)
        ("fc8 force listen only mode", f("010800040000") + f("010800010000") * 3),  # (08/01, repeat, echo)
        ("fc8 answer sub-function differs", f("010800010000") + f("010800020007") + f("010800020000") * 2),
        ("fc17 run indicator", f("0111") + f("011103011241")),
        ("fc17 version text", f("0111") + f("01110512FF56312E")),
        # (pymodbus: a name as the server id, the run indicator last)
        ("fc17 longer server id", f("0111") + f("01111F" + b"Telemecanique-ATV71HU15M3-0201".hex() + "FF")),
        ("fc12 event log", f("010C") + f("010C080000000100022040")),
        ("fc12 byte count below 6", f("010C") + f("010C0400000001")),
        ("fc20 file records", f("01140706000400010002") + f("0114060506000D00FE")),
        ("fc21 file record written", f("01150D0600040007000306AF04BE100D") * 2),
        ("fc22 echo differs", f("011600040F0F00F0") + f("011600040F0F00F1")),
        ("fc21 echo differs", f("01150D0600040007000306AF04BE100D") + f("01150D0600040007000306AF04BE100E")),
        ("fc20 sub-responses disagree", f("01140E0600040001000206000300090001") + f("0114080706000100020003")),
        ("fc20 reference type and record", f("01140705000427100002") + f("0114060506000D00FE")),
        ("fc21 reference type", f("011509070001270F00011234")),
        ("fc43 other MEI type", f("012B0D0102")),
        ("broadcast read", f("000300000001")),
        ("reserved slave", f("F80300000001")),
        # (the answer awaited cut by the end of the capture: noise saying so, and the note on its request)
        ("fc3 answer cut by the end", f("0C0320D00003") + h("0C0306800000 0300")),
    ]


def inputs() -> Iterator[tuple[str, str, bytes]]:
    """(name, mode, bytes) of every input, in a stable order."""
    import seed_frames

    singles = [(name, value) for name, value in vars(seed_frames).items() if name.isupper() and isinstance(value, bytes)]
    for name, value in singles:
        yield f"seed {name}", "rtu", value
    yield "seed pages in order", "rtu", b"".join(value for _, value in singles)
    for name, value in _crafted():
        yield name, "rtu", value
    for path in sorted((ROOT / "captures").glob("*.bin")):
        yield f"capture {path.name}", "ascii" if "ascii" in path.name else "rtu", path.read_bytes()


def plain(value: Any) -> Any:
    """A decoded value as JSON (bytes as hex, Construct containers as objects without their `_io`)."""
    if isinstance(value, (bytes, bytearray)):
        return value.hex()
    if isinstance(value, dict) or isinstance(value, Container):
        return {str(k): plain(v) for k, v in value.items() if not str(k).startswith("_")}
    if isinstance(value, (list, tuple, ListContainer)):
        return [plain(v) for v in value]
    if isinstance(value, bool) or value is None or isinstance(value, (int, float)):
        return value
    return str(value)  # enum names (the server id's run indicator), kinds


def _framer(mode: str) -> RtuFramer | AsciiFramer:
    return AsciiFramer() if mode == "ascii" else RtuFramer()


def _framing(mode: str, data: bytes) -> list[dict[str, Any]]:
    framer = _framer(mode)
    items = framer.feed(Chunk(data)) + framer.finish()
    return [_item(item) for item in items]


def _item(item: Item) -> dict[str, Any]:
    if isinstance(item, Noise):
        return {"noise": item.raw.hex(), "reason": item.reason}
    assert isinstance(item, Frame)
    return {
        "kind": str(item.kind), "slave": item.slave, "function": item.function, "raw": item.raw.hex(),
        "crc_ok": item.crc_ok, "warnings": list(item.warnings),
    }


def _pairing(items: list[Item]) -> list[dict[str, Any]]:
    out = []
    for item in items:
        row: dict[str, Any] = {"number": item.number}
        if isinstance(item, Frame):
            row.update(
                request=item.request.number if item.request is not None else None,
                unanswered=item.unanswered, broadcast=item.broadcast, notes=list(item.notes),
            )
        out.append(row)
    return out


def _decoding(frame: Frame) -> dict[str, Any]:
    return {
        "number": frame.number, "fields": plain(frame.fields), "start": frame.start, "quantity": frame.quantity,
        "subfunction": frame.subfunction,
        "registers": None if frame.registers is None else [[r.address, r.value] for r in frame.registers],
        "bits": None if frame.bits is None else [[b.address, b.value] for b in frame.bits],
        "objects": None if frame.objects is None else [[o.id, o.name, o.value] for o in frame.objects],
        "warnings": list(frame.warnings),
    }


def _annotation(frame: Frame) -> dict[str, Any]:
    registers = [
        {k: v for k, v in (("address", r.address), ("value", r.value), ("code", r.code), ("name", r.name),
                           ("unit", r.unit), ("text", r.text), ("status", r.status), ("label", r.label),
                           ("words", r.words)) if v is not None}
        for r in frame.registers or []
    ]
    return {
        "number": frame.number, "function_text": frame.function_text, "exception_text": frame.exception_text,
        "subfunction_text": frame.subfunction_text, "span_label": frame.span_label, "registers": registers,
        "notes": [str(note) for note in frame.notes], "warnings": list(frame.warnings),
    }


def summary_lines(mode: str, data: bytes, pure: bool) -> list[str]:
    """vw3-decode's summary output of the input as a raw file (the compiled engine's when not `pure`)."""
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "input.bin"
        path.write_bytes(data)
        env = dict(os.environ, PYTHONPATH=str(ROOT), NO_COLOR="1")
        env.pop("VW3_PURE_PYTHON", None)
        if pure:
            env["VW3_PURE_PYTHON"] = "1"
        command = [sys.executable, "-m", "dissector", str(path), "--mode", mode]
        result = subprocess.run(command, capture_output=True, env=env, timeout=120)
    if result.returncode not in (0, 1):
        raise RuntimeError(f"vw3-decode failed: {result.stderr.decode(errors='replace')}")
    return result.stdout.decode("utf-8").splitlines()


def case(name: str, mode: str, data: bytes) -> dict[str, Any]:
    framing = _framing(mode, data)
    framer, pairer = _framer(mode), Pairer()
    paired = pairer.push(framer.feed(Chunk(data)))
    paired += pairer.push(framer.finish()) + pairer.finish()
    pairing = _pairing(paired)
    decoding = [_decoding(decode_frame(item)) for item in paired if isinstance(item, Frame)]
    annotator = build_annotator([PROFILE], [])
    choose_profiles(annotator, [Chunk(data)], mode, None, None)
    dissector = Dissector(_framer(mode), annotate=annotator)
    annotated = dissector.feed(Chunk(data)) + dissector.finish()
    # (after the decode: choices() lists the slaves the decode met, each with its choice or none)
    selection = [{"slave": c.slave, "profile": c.profile, "reason": c.reason, "frame": c.frame} for c in annotator.choices()]
    annotation = [_annotation(item) for item in annotated if isinstance(item, Frame)]
    return {
        "name": name, "mode": mode, "input": data.hex(), "profile": PROFILE,
        "framing": framing, "pairing": pairing, "decoding": decoding, "selection": selection,
        "annotation": annotation, "summary": summary_lines(mode, data, pure=True),
    }


def maps() -> list[dict[str, Any]]:
    out = []
    for name in ("atv71", "sel749m"):
        rows = load_builtin_map(f"{name}.csv")
        out.append({"map": name, "rows": [
            {"address": address, "code": row.code, "name": row.name, "unit": row.unit, "scale": row.scale,
             "access": row.access, "enum": {str(k): v for k, v in row.enum.items()},
             "bits": {str(k): v for k, v in row.bits.items()}, "signed": row.signed, "words": row.words,
             "type": row.kind, "swapped": row.swapped}
            for address, row in sorted(rows.items())
        ]})
    return out


# Map texts as spreadsheets save them, good and malformed (map reading: parse_map's rows or its message).
MAP_TEXTS = {
    "plain": "address,code,name,unit,scale,access,enum,bits,signed,source,type,order\n"
             "# a comment line, then a blank one\n\n"
             "8401,CHCF,[Profile],,,RW,0=IO;3=SE8,,,A,,\n"
             "0x2001,HSP,High speed,Hz,0.1,R,,,,,,\n"
             "16#3203,ETA,Status,,,r,,0=Ready;15=Manual,,,,\n"
             "3000,TQ,Torque,%,1e-2,,,,1,,,\n"
             "3001,CNT,Count,,10,,,,0,,uint16,\n",
    "wide": "address,code,type,order,scale,unit\n100,E,uint32,,0.1,kWh\n102,F,float32,cdab,,\n"
            "104,G,int32,ABCD,,\n106,H,INT16,,,\n",
    "semicolons and decimal commas": "\ufeffaddress;code;name;scale\n1;A;\"x;y\";0,5\n2;B;\"say \"\"hi\"\"\";-1,25\n",
    "tab": "address\tcode\tunit\n1\tA\tV\n",
    "line ends": "address,code\r\n1,A\r\n2,B\x0c3,C\u20284,D\x855,E\r6,F\n",
    "escapes": "address,code,name,enum\n1,A\x1b[2J,N\x07,1=\u009bx\n2,\u00e9\u20ac,na\u00afme\u00ad,\n",
    # (what str.isprintable() refuses past U+00FF is escaped as Python writes it, \\uNNNN or \\UNNNNNNNN: a
    # bidi override, an ideographic space, a BOM inside a text, private use, a tag, unassigned code points;
    # a 4-byte emoji is printable)
    # (labels take no unit: the unit on a row of its own)
    "unicode texts": "address,code,name,unit,enum,source\n1,A\u202eB,x\u3000y\u200bz,,"
                     "1=\ue000;2=\U0001f600;3=\u0378\U000e0001\U0010ffff,s\U0001f600\n2,U,,\ufeffkm,,\n",
    "unicode in a message": "address,code,access\n1,A,\u202e\u3000\ufeff\ue000\U0001f600\u0378'\n",
    "quote left open": "address,code,name\n1,A,\"open, still\n",
    # (a cell with a line break, Excel's Alt+Enter, saved quoted over two lines: refused at its first line)
    "quote left open by a line break": "address,code,name,unit\n1,A,\"two\nlines\",Hz\n",
    "address": "address,code\nx1,A\n",
    "address range": "address,code\n70000,A\n",
    # (a number is decimal or 0x/16# hexadecimal in both readers: not int()'s 1_0, 16#0x10, Unicode digits)
    "address forms": "address,code\n0X1f,A\n16#ff,B\n+7,C\n-0,D\n",
    "address underscore": "address,code\n1_0,A\n",
    "address hex underscore": "address,code\n0x_10,A\n",
    "address prefix twice": "address,code\n16#0x10,A\n",
    "address unicode digits": "address,code\n\u0661\u0662,A\n",
    "enum key underscore": "address,code,enum\n1,A,1_0=x\n",
    # (what both strip and fold is ASCII's: a no-break space stays, ß is no SS)
    "address no-break space": "address,code\n\u00a012,A\n",
    "code no-break space": "address,code,name\n1,\u00a0A\u00a0, N\u00a0\n",
    "line of no-break space": "address,code\n\u00a0\n",
    "access sharp s": "address,code,access\n1,A,\u00df\n",
    "type dotted capital": "address,code,type\n1,A,\u0130nt16\n",
    "column capital": "Address,CODE,\u00c4\n",
    "scale unicode decimal comma": "address;code;scale\n1;A;\u0661,\u0665\n",
    "code empty": "address,code\n1, \n",
    "scale": "address,code,scale\n1,A,abc\n",
    "scale hex": "address,code,scale\n1,A,0x10\n",
    "scale underscore": "address,code,scale\n1,A,1_0\n",
    "scale nan": "address,code,scale\n1,A,nan\n",
    "scale dot": "address,code,scale\n1,A,.\n",
    "scale short forms": "address,code,scale\n1,A,5.\n2,B,.5E-1\n3,C,-2e+1\n",
    "scale range": "address,code,scale\n1,A,1e13\n",
    "scale zero": "address,code,scale\n1,A,0\n",
    "access": "address,code,access\n1,A,rx\n",
    "access quoted": "address,code,access\n1,A,it's\n",
    "access both quotes": "address,code,access\n1,A,\"a'b\"\"\"\n",
    "enum form": "address,code,enum\n1,A,foo\n",
    "enum number": "address,code,enum\n1,A,x=foo\n",
    "enum range": "address,code,enum\n1,A,70000=foo\n",
    "enum twice": "address,code,enum\n1,A,1=a;1=b\n",
    "bits range": "address,code,bits\n1,A,16=a\n",
    "signed": "address,code,signed\n1,A,2\n",
    "type": "address,code,type\n1,A,int64\n",
    "order": "address,code,type,order\n1,A,uint32,badc\n",
    "wide labels": "address,code,type,enum\n1,A,uint32,1=a\n",
    "wide last": "address,code,type\n65535,A,float32\n",
    "signed enum": "address,code,signed,enum\n1,A,1,1=a\n",
    "unknown column": "address,code,Colour\n",
    "missing column": "address,name\n",
    "column twice": "address,code,code\n",
    "fields comma": "address,code\n1,A,B\n",
    "fields semicolon": "address;code\n1;A;B\n",
    "fields tab": "address\tcode\n1\tA\tB\n",
    "address twice": "address,code\n1,A\n0x1,B\n",
    "second register": "address,code,type\n1,A,uint32\n3,C,uint32\n2,B,\n4,D,\n",
    "no header": "# only a comment\n\n",
    # A map written in PLC references (a `reference` column in place of `address`): 4X and 3X, five digits
    # and six, each range's ends; decimal digits only (no sign, no 0x, no other script's digits); refused
    # as either reader words it: both columns, a reference outside the ranges, two references of one address.
    "reference 4X": "reference,code\n40001,A\n40002,B\n 49999 ,C\n400010 ,D\n465536,E\n",
    "reference 3X": "Reference;code;scale\n30001;A;0,1\n300101;B;\n39999;C;\n365536;D;\n",
    "reference 32-bit": "reference,code,type,order\n40010,A,uint32,CDAB\n40012,B,float32,\n",
    "reference and address": "address,code,reference\n",
    "reference without code": "reference,name\n",
    "reference below 4X": "reference,code\n40000,A\n",
    "reference past 5 digits": "reference,code\n50000,A\n",
    "reference past 6 digits": "reference,code\n465537,A\n",
    "reference of an address": "reference,code\n12,A\n",
    "reference signed": "reference,code\n+40001,A\n",
    "reference hex": "reference,code\n0x9C41,A\n",
    "reference unicode digits": "reference,code\n\u0664\u0660\u0660\u0660\u0661,A\n",
    "reference empty": "reference,code\n,A\n",
    "reference twice": "reference,code\n40002,A\n400002,B\n",
    # (a manual's input and holding registers together: 30001 and 40001 are input and holding register 0)
    "reference 3X and 4X": "reference,code,type\n30001,IN,\n40001,HOLD,\n30003,IN2,uint32\n40004,HR3,\n",
    "reference 3X twice": "reference,code\n30001,IN\n300001,IN0\n",
    "reference 3X second register": "reference,code,type\n30001,A,int32\n40002,B,\n30002,C,\n",
    "reference code in both tables": "reference,code\n30001,A\n40002,a\n",
    "reference second register": "reference,code,type\n40001,A,int32\n40002,B,\n",
    "empty": "",
}


# Map files whose bytes are not UTF-8 (load_map_file's strict decode, no surrogateescape: refused).
MAP_BYTES = {
    "not utf-8 latin-1": b"address,code,name\n1,A,caf\xe9\n",
    # (Excel's "Unicode Text": UTF-16 with its byte order mark, tab separated; the message says what to save)
    "utf-16 little endian": "address\tcode\n1\tA\n".encode("utf-16-le").join([b"\xff\xfe", b""]),
    "utf-16 big endian": "address\tcode\n1\tA\n".encode("utf-16-be").join([b"\xfe\xff", b""]),
    "not utf-8 stray continuation": b"address,code\n1,\x80\n",
    "not utf-8 overlong": b"address,code\n1,\xc0\xaf\n",
    "not utf-8 surrogate": b"address,code\n1,\xed\xa0\x80\n",
    "not utf-8 past U+10FFFF": b"address,code\n1,\xf4\x90\x80\x80\n",
    "not utf-8 cut short": b"address,code\n1,A\xe2\x80",
    "utf-8 four bytes": b"address,code\n1,\xf0\x9f\x98\x80\xf4\x8f\xbf\xbf\n",
}

# Texts as Python's repr shows them (the plugin's python_repr): printable() escapes the same characters.
REPR_TEXTS = ["plain", "it's", "both ' and \"", "back\\slash\ttab\n", "\x1b[2J\x7f\x85\xa0\xad\xe9",
              "\u202e\u2028\u2029\u3000\u200b\ufeff\ue000\U0001f600\u0378\U000e0001\U0010ffff",
              "\uffff\U0001ffff\U000f0000\U00020000\u00ff\u0100"]


def _read(name: str, given: dict[str, str], read: Callable[[], Any]) -> dict[str, Any]:
    """What reading a map gives: its message, or its rows."""
    try:
        rows = read()
    except ProfileError as error:
        return {"name": name, **given, "error": str(error)}
    # (a map in references' 3X rows after its 4X rows, `table` "input": ReferenceRows.inputs)
    inputs = sorted(getattr(rows, "inputs", {}).items())
    return {"name": name, **given, "rows": [
        {**({"table": "input"} if table else {}),
         "address": address, "code": row.code, "name": row.name, "unit": row.unit, "scale": row.scale,
         "decimals": row.decimals, "enum": {str(k): v for k, v in row.enum.items()},
         "bits": {str(k): v for k, v in row.bits.items()}, "signed": row.signed, "words": row.words,
         "type": row.kind if row.words == 2 else None, "swapped": row.swapped, "source": row.source,
         "ambiguous_8000": row.ambiguous_8000}
        for table, (address, row) in [*((0, item) for item in sorted(rows.items())), *((1, item) for item in inputs)]
    ]}


def map_reading() -> list[dict[str, Any]]:
    out = [_read(name, {"text": text}, lambda text=text: parse_map(text, "map.csv"))
           for name, text in MAP_TEXTS.items()]
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "map.csv"
        for name, data in MAP_BYTES.items():  # (a file: the bytes as hex, the message with the name `map.csv`)
            path.write_bytes(data)
            entry = _read(name, {"hex": data.hex()}, lambda: load_map_file(path))
            if "error" in entry:
                entry["error"] = entry["error"].replace(str(path), "map.csv")
            out.append(entry)
    return out


def vectors() -> dict[str, Any]:
    return {
        "format": FORMAT,
        "refresh": "python3 tests/conformance/generate.py",
        "cases": [case(name, mode, data) for name, mode, data in inputs()],
        "maps": maps(),
        "map_reading": map_reading(),
        "repr": [{"text": text, "repr": repr(text)} for text in REPR_TEXTS],
    }


def render(data: dict[str, Any]) -> tuple[str, str]:
    """The JSON file and its Lua twin (`return {...}`, JSON null as the `NULL` sentinel's absence)."""
    text = json.dumps(data, indent=1, ensure_ascii=False, sort_keys=True) + "\n"
    lua = "-- GENERATED by python3 tests/conformance/generate.py: do not edit (vectors.json's twin).\n"
    return text, lua + "return " + lua_literal(data) + "\n"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 when the files are stale")
    args = parser.parse_args(argv)
    text, lua = render(vectors())
    stale = [path for path, new in ((JSON_FILE, text), (LUA_FILE, lua))
             if not path.exists() or path.read_text(encoding="utf-8") != new]
    if args.check:
        for path in stale:
            print(f"{path}: stale; run python3 tests/conformance/generate.py", file=sys.stderr)
        return 1 if stale else 0
    for path, new in ((JSON_FILE, text), (LUA_FILE, lua)):
        path.write_text(new, encoding="utf-8")
    print(f"{JSON_FILE}, {LUA_FILE}: written")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
