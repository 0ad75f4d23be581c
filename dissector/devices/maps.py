"""Register maps: one CSV per device (data/maps/*.csv) naming, scaling and labelling register values.

Format (the plugin's map reader, lua/src/maps.lua, reads COLUMNS, TYPES, ORDERS, ACCESS and MESSAGES
from the data codegen writes into lua/vw3.lua): a header line naming the columns, then one row per
register. Lines starting with `#` are comments (the source legend lives there). Columns:

    address  logic address as sent on the wire (decimal, or 0x/16# hexadecimal); or, a map written as
             manuals number registers, a `reference` column in its place: PLC references, 4X (40001 for
             address 0, to 49999; six digits 400001..465536) or 3X (30001, 300001: input registers)
    code     short code shown to users (CHCF); one register's (ASCII case aside, as --watch matches codes)
    name     long name ([Profile])
    unit     unit of the scaled value (Hz)
    scale    multiply the raw value by this (0.1): shown with the decimals the scale is written with, a
             float32's product with the fewest digits that tell it from its neighbours'; empty: shown as is,
             in its unit; `?`: a scale the device's settings choose (the ATV71's ACC and DEC, by its ramp
             increment Inr), so the 16-bit raw value is shown unscaled, naming the unit it counts in
    access   R, W or RW
    enum     value labels: `value=LABEL;value=LABEL`
    bits     bit labels for status and control words: `bit=Label;bit=Label` (bits 0..15); a row has enum
             or bits, not both, and labels take no scale nor unit (the value is a label)
    signed   `1` when the raw word is a two's complement signed value, empty (or 0) otherwise; beside a
             type, it agrees with it (1: int16, int32; 0: uint16, uint32; a float32 takes none)
    source   where the row comes from (a letter explained in the file's legend comment)
    type     uint16 (the default), int16 (as signed = 1), or a 32-bit value over this register and the
             next: uint32, int32, float32
    order    word order of a 32-bit value: ABCD (the first register holds the high word, the default) or
             CDAB (the low word first, as many PLCs and meters send it); a 16-bit row has no CDAB

Maps come as spreadsheets save them: UTF-8 with or without a BOM, separated by `,` or, as European
Excel writes CSV, `;` (or a tab), told from the header line (cells holding the separator are quoted).
A row is one line: a quote left open at a line's end (a cell with a line break, saved over two lines) is
refused by its line number.
Only `address` and `code` are required in a user's map; the other columns may be left out of the header.
Every malformed line is reported as `file:line: what is wrong`, never skipped.
"""
from __future__ import annotations

from dissector.errors import ProfileError
from dissector.devices.readfile import read_capped
from dissector.protocol.printable import printable
from dissector.protocol.rules import text as say_text
import csv
import math
import re
import struct
from dataclasses import dataclass, field
from decimal import Decimal, InvalidOperation
from importlib import resources
from pathlib import Path

COLUMNS = (
    "address", "code", "name", "unit", "scale", "access", "enum", "bits", "signed", "source", "type", "order",
)
TYPES = {"uint16": 1, "int16": 1, "uint32": 2, "int32": 2, "float32": 2}  # registers each type spans
ORDERS = ("ABCD", "CDAB")  # ABCD: the first register holds the high word (Modbus' big-endian); CDAB: swapped
# (an empty order is the first; an empty type is the first, or the second when `signed` is 1)
DEFAULT_TYPES = ("uint16", "int16")
SIGNED_TYPES = frozenset(["int16", "int32"])
PAIRS = {"enum": (0, 0xFFFF), "bits": (0, 15)}  # the numbers an enum or bits entry may label
SEPARATORS = (",", ";", "\t")  # a map's separator: the one of these that splits its header most
REQUIRED = ("address", "code")
# The column a map written in PLC references has in place of `address`, and the references' bases: 4X
# (holding registers) and 3X (input registers), five digits (40001 + address up to 49999) or six (400001 +
# address: naming.plc_label's rule, base * 10 - 9). 3X rows are kept apart (ReferenceRows.inputs): they
# name FC4's input registers, 4X rows the holding registers (DeviceBuilder.build says where FC4 reads both).
REFERENCE = "reference"
REFERENCE_BASES = (40001, 30001)
ACCESS = frozenset(["R", "W", "RW"])
MEMO_LIMIT = 4096
# 65,536 addresses of a few hundred bytes each at most: anything bigger is not a map, and reading
# it whole (a 2 GB file given by mistake) would take the memory of the machine.
MAX_MAP_BYTES = 16 << 20
UTF16_BOMS = (b"\xff\xfe", b"\xfe\xff")  # the byte order marks of UTF-16 (little, big endian): MESSAGES utf16
# Scales a device could mean (0.001 Hz .. GWh): any 16- or 32-bit raw value times one stays a finite
# number with a bounded count of digits (1e308 times FFFF is inf; 1e-300 would print 300 decimals).
SCALE_MIN, SCALE_MAX = 1e-12, 1e12
SCALE_UNKNOWN = "?"  # the scale cell of a value whose scale the device's settings choose
# What a malformed map is told (after `file:line: `), by key. The plugin's map reader (lua/src/maps.lua)
# says the same texts: codegen/lua.py writes this table into lua/vw3.lua, `{NAME!r}` as Python's repr.
MESSAGES = {
    "unknown_column": "unknown column {name!r} (columns: " + ", ".join(COLUMNS) + ")",
    "missing_column": "the header lacks the {name!r} column",
    "column_twice": "a column is named twice in the header",
    "fields": "{count:d} fields, the header has {header:d} (quote a field that holds a {separator})",
    # A spreadsheet's cell with a line break (Excel's Alt+Enter) is saved as a quoted field over two lines;
    # a row is one line here, and a quote left open would silently take the rest of the line into a cell.
    # (after `file: `; the file's bytes, not a line) Excel's "Unicode Text" saves UTF-16 with a UTF16_BOMS mark
    "not_utf8": "not UTF-8 text",
    "utf16": "not UTF-8 text (UTF-16, as Excel's \"Unicode Text\" saves: save the map as \"CSV UTF-8\")",
    "open_quote": "a quoted field is not closed on this line (a line break inside a cell? write each row "
                  "on one line)",
    "address_twice": "address {address:d} already defined on line {line:d}",
    "second_register": "address {address:d} is the second register of {code} ({kind}, line {line:d})",
    "no_header": "no header line (expected: " + ",".join(COLUMNS) + ")",
    "address": "address {text!r} is not a number",
    "address_range": "address {address:d} is outside 0..65535",
    "code": "code is empty",
    "scale": "scale {text!r} is not a number",
    "scale_range": "scale {text!r} is outside " + f"±{SCALE_MIN:g}..{SCALE_MAX:g}",
    "scale_zero": "scale {text!r} would make every value 0",
    "scale_unknown_unit": f"scale {SCALE_UNKNOWN!r} (the device sets it) needs the unit the value counts in",
    "scale_unknown_wide": f"scale {SCALE_UNKNOWN!r} (the device sets it) is for a 16-bit register: type "
                          "{kind} is two",
    "access": "access {text!r} is not R, W or RW",
    "pair": "{what} entry {part!r} is not `number=label`",
    "pair_number": "{what} entry {part!r}: {key!r} is not a number",
    "pair_range": "{what} entry {part!r}: {number:d} is outside {low:d}..{high:d}",
    "pair_twice": "{what} entry {part!r}: {number:d} given twice",
    "signed": "signed {text!r} is not 1, 0 or empty",
    "type": "type {text!r} is not one of " + ", ".join(TYPES),
    "order": "order {text!r} is not " + " or ".join(ORDERS),
    "wide_labels": "a {kind} value cannot carry enum or bit labels",
    "wide_last": "a {kind} value needs two registers: {address:d} is the last address",
    # Enumerations are listed as unsigned words; a signed register with labels is a map error.
    "signed_enum": "a signed register cannot carry enum labels",
    # Columns that say opposite things: refused rather than one of them silently ignored.
    "signed_type": "signed {text!r} contradicts type {kind}",
    "order_one_word": "order {text!r} swaps the words of a 32-bit value: type {kind} is one register",
    "enum_bits": "a register cannot carry both enum and bit labels",
    "labels_quantity": "a register with {what} labels cannot carry a {column} (its value is a label)",
    "code_twice": "code {code} already names address {address:d} (line {line:d})",
    "reference_and_address": f"a map gives each row an address or a {REFERENCE}, not both",
    # (two references of one register: 40002 and 400002, or 30002 and 300002; a manual's 30001 and 40001
    # are two registers, input and holding register 0)
    "reference_twice": "reference {text!r} is {table} register {address:d}, as {first!r} on line {line:d}: a map "
                       "names each register once",
    "reference": "reference {text!r} is not a 4X or 3X register reference (" + "; ".join(
        f"{base}..{base + 9998}, {base * 10 - 9}..{base * 10 - 9 + 0xFFFF}" for base in REFERENCE_BASES) + ")",
    # Not a line's error: what the traffic tells of a map written in PLC references (maps_refs.py, the
    # plugin's device.lua), a frame's note and a warning. {offset}: `40001`, or `40001 or 30001` (FC4's 3X).
    # (short: Wireshark cuts an expert info's text at 240 bytes)
    "references": "map {map} names {shifted:d} of the {unnamed:d} unnamed registers slave {slave:d} reads or "
                  "writes at address + {offset}: PLC references? A map takes protocol addresses (reference - "
                  "{offset}){column}",
    # ({column} of references: where the map's rows are the references themselves, not one less)
    "references_column": f" or a {REFERENCE} column",
}

# Cells of a row that contradict each other, refused rather than one of them silently ignored, in the order
# they are judged: (MESSAGES key, fact, fact[, the message's own parameters]), refused where both facts hold
# (_row's facts; the plugin's map_row reads this table: codegen/profiles_lua.py).
CONFLICTS = (
    ("order_one_word", "one_word", "swapped"),
    ("wide_labels", "wide", "labels"),
    ("wide_last", "wide", "last"),
    ("signed_enum", "signed", "enum"),
    ("enum_bits", "enum", "bits"),
    *(("labels_quantity", labels, column, {"what": what, "column": column})
      for labels, what in (("enum", "enum"), ("bits", "bit")) for column in ("scale", "unit")),
    ("scale_unknown_wide", "scale_unknown", "wide"),
    ("scale_unknown_unit", "scale_unknown", "no_unit"),
)


def _say(key: str, /, **values: object) -> str:
    return MESSAGES[key].format(**values)


@dataclass(slots=True)
class RegisterDef:
    address: int
    code: str
    name: str | None = None
    unit: str | None = None
    scale: float | None = None
    access: str | None = None
    enum: dict[int, str] = field(default_factory=dict)
    bits: dict[int, str] = field(default_factory=dict)
    signed: bool = False
    source: str | None = None
    # Derived at load so that annotation is only lookups: digits to show after scaling (0.1 -> 1).
    decimals: int = 0
    scale_unknown: bool = False  # scale `?`: the value counts in `unit` at a scale the device sets
    # 16#8000 is a value this register can really hold (signed, bit 15 labelled, or enumerated),
    # so a read of 16#8000 cannot be called protected with certainty.
    ambiguous_8000: bool = False
    words: int = 1  # registers the value spans (2: type uint32, int32, float32)
    kind: str = "uint16"  # the type column
    swapped: bool = False  # order CDAB
    # interpret() results by raw value, filled by the annotator: captures repeat values, and this makes
    # annotation a dictionary lookup per register. Bounded by MEMO_LIMIT.
    memo: dict[int, tuple[float | int | None, str | None]] = field(
        default_factory=dict, repr=False, compare=False
    )


RegisterMap = dict[int, RegisterDef]


# What both readers strip from a cell or a line, and the case they fold: ASCII's, as the plugin's Lua
# patterns and string.upper know it (not str.strip()'s no-break space, nor upper()'s ß -> SS).
_SPACE = " \t\n\r\x0b\x0c"
_UPPER = {letter: letter - 32 for letter in range(ord("a"), ord("z") + 1)}  # (str.translate tables)
_LOWER = {letter: letter + 32 for letter in range(ord("A"), ord("Z") + 1)}
_HEX_DIGITS = frozenset("0123456789abcdefABCDEF")


def _parse_int(text: str) -> int:
    """A number in a map (an address, an enum or bits entry): decimal, or hexadecimal after 0x or 16#, as
    the plugin reads it (maps.lua map_int): not int()'s 1_0, 0x_10, 16#0x10 nor Unicode digits."""
    text = text.strip(_SPACE)
    digits = text[1:] if text[:1] in ("+", "-") else text
    if digits.isascii() and digits.isdecimal():
        return int(text)
    for prefix in ("0x", "0X", "16#"):
        digits = text[len(prefix):]
        if text.startswith(prefix) and digits and _HEX_DIGITS.issuperset(digits):
            return int(digits, 16)
    raise ValueError(text)


def reference_address(text: str) -> int:
    """The address a PLC reference stands for (40001 -> 0, 30101 -> 100, 400001 -> 0), as the plugin reads
    it (maps.lua map_reference): decimal digits only."""
    text = text.strip(_SPACE)
    if text.isascii() and text.isdecimal():
        number = int(text)
        for base in REFERENCE_BASES:
            for first, last in ((base, base + 9998), (base * 10 - 9, base * 10 - 9 + 0xFFFF)):
                if first <= number <= last:
                    return number - first
    raise ValueError(_say("reference", text=text))


def reference_table(text: str) -> str:
    """The table a valid PLC reference names: "input" (3X) or "holding" (4X)."""
    return "input" if text.strip(_SPACE)[:1] == "3" else "holding"


class ReferenceRows(dict):  # type: ignore[type-arg]
    """The rows of a map written in PLC references (its `reference` column): a RegisterMap by address of
    its 4X rows (holding registers), and `inputs`, its 3X rows (input registers, FC4's)."""

    def __init__(self) -> None:
        super().__init__()
        self.inputs: RegisterMap = {}


class TableRows(dict):  # type: ignore[type-arg]
    """A candidate profile's rows as profile `auto` judges traffic against them (devices/build.py): the rows
    naming its holding registers, and `inputs`, those naming its input registers apart (DeviceBuilder's
    layered_rows: a map in PLC references with 3X rows)."""

    def __init__(self, rows: RegisterMap, inputs: RegisterMap) -> None:
        super().__init__(rows)
        self.inputs = inputs


def _pairs(text: str, what: str, low: int, high: int) -> dict[int, str]:
    out: dict[int, str] = {}
    for part in text.split(";"):
        part = part.strip(_SPACE)
        if not part:
            continue
        key, sep, label = part.partition("=")
        if not sep or not label.strip(_SPACE):
            raise ValueError(_say("pair", what=what, part=part))
        try:
            number = _parse_int(key)
        except ValueError:
            raise ValueError(_say("pair_number", what=what, part=part, key=key.strip(_SPACE))) from None
        if not low <= number <= high:
            raise ValueError(_say("pair_range", what=what, part=part, number=number, low=low, high=high))
        if number in out:
            raise ValueError(_say("pair_twice", what=what, part=part, number=number))
        out[number] = printable(label.strip(_SPACE))
    return out


def _decimals(scale: str) -> int:
    exponent = Decimal(scale).normalize().as_tuple().exponent
    return max(0, -int(exponent))


def _row(values: dict[str, str]) -> RegisterDef:
    raw_address = values.get("address", "")
    try:
        address = _parse_int(raw_address)
    except ValueError:
        raise ValueError(_say("address", text=raw_address)) from None
    if not 0 <= address <= 0xFFFF:
        raise ValueError(_say("address_range", address=address))
    code = printable(values.get("code", "").strip(_SPACE))  # a map's texts are shown: control characters escaped
    if not code:
        raise ValueError(_say("code"))
    scale: float | None = None
    decimals = 0
    raw_scale = values.get("scale", "").strip(_SPACE)
    if raw_scale and raw_scale != SCALE_UNKNOWN:
        if not _SCALE.fullmatch(raw_scale):  # not float()'s 1_0, nan, inf, nor Unicode digits
            raise ValueError(_say("scale", text=raw_scale))
        try:
            scale = float(raw_scale)
            decimals = _decimals(raw_scale)
        except (ValueError, InvalidOperation):
            raise ValueError(_say("scale", text=raw_scale)) from None
        if scale == 0:
            raise ValueError(_say("scale_zero", text=raw_scale))
        if not SCALE_MIN <= abs(scale) <= SCALE_MAX:  # also inf (1e999)
            raise ValueError(_say("scale_range", text=raw_scale))
    access = values.get("access", "").strip(_SPACE).translate(_UPPER) or None
    if access is not None and access not in ACCESS:
        raise ValueError(_say("access", text=access))
    enum = _pairs(values.get("enum", ""), "enum", *PAIRS["enum"])
    bits = _pairs(values.get("bits", ""), "bits", *PAIRS["bits"])
    signed_text = values.get("signed", "").strip(_SPACE)
    if signed_text not in ("", "0", "1"):
        raise ValueError(_say("signed", text=signed_text))
    signed = signed_text == "1"
    kind_text = values.get("type", "").strip(_SPACE).translate(_LOWER)
    kind = kind_text or DEFAULT_TYPES[signed]
    if kind not in TYPES:
        raise ValueError(_say("type", text=kind))
    agrees = "" if kind == "float32" else "01"[kind in SIGNED_TYPES]  # (a float32 takes no signed cell)
    if kind_text and signed_text and signed_text != agrees:
        raise ValueError(_say("signed_type", text=signed_text, kind=kind))
    signed = signed or kind in SIGNED_TYPES
    words = TYPES[kind]
    order = values.get("order", "").strip(_SPACE).translate(_UPPER) or ORDERS[0]
    if order not in ORDERS:
        raise ValueError(_say("order", text=order))
    unit = printable(values.get("unit", "").strip(_SPACE)) or None
    facts = {"one_word": words == 1, "wide": words == 2, "swapped": order != ORDERS[0], "last": address == 0xFFFF,
             "signed": signed, "enum": bool(enum), "bits": bool(bits), "labels": bool(enum or bits),
             "scale": bool(raw_scale), "unit": unit is not None, "no_unit": unit is None,
             "scale_unknown": raw_scale == SCALE_UNKNOWN}
    for message, first, second, *given in CONFLICTS:
        if facts[first] and facts[second]:
            raise ValueError(_say(message, text=order, kind=kind, address=address, **(given[0] if given else {})))
    return RegisterDef(
        address=address,
        code=code,
        name=printable(values.get("name", "").strip(_SPACE)) or None,
        unit=unit,
        scale=scale,
        access=access,
        enum=enum,
        bits=bits,
        signed=signed,
        source=printable(values.get("source", "").strip(_SPACE)) or None,
        decimals=decimals,
        scale_unknown=raw_scale == SCALE_UNKNOWN,
        ambiguous_8000=signed or 15 in bits or 0x8000 in enum or words == 2,
        words=words,
        kind=kind,
        swapped=order == "CDAB",
    )


_DECIMAL_COMMA = re.compile(r"[-+]?[0-9]+,[0-9]+")
# A scale is a plain decimal number, as the plugin reads it (maps.lua scale_decimals).
_SCALE = re.compile(r"[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?")


def _sniff(header: str) -> str:
    """The separator of a map from its header line: the one of SEPARATORS that splits it most."""
    counts = {separator: header.count(separator) for separator in SEPARATORS}
    best = max(counts, key=lambda separator: counts[separator])
    return best if counts[best] else SEPARATORS[0]


def _cells(line: str, delimiter: str) -> list[str]:
    """A map line's cells. A cell may be as long as a map may be, as in the plugin's reader: csv's own
    limit (131,072 characters) refused a long name with csv's words, where the plugin took it."""
    limit = csv.field_size_limit(MAX_MAP_BYTES)
    try:
        # (with the line's end given back: it is inside a cell only when a quote is left open)
        cells = next(csv.reader([line + "\n"], delimiter=delimiter))
    finally:
        csv.field_size_limit(limit)
    if cells and cells[-1].endswith("\n"):
        raise ValueError(_say("open_quote"))
    return cells


def parse_map(text: str, origin: str) -> RegisterMap:
    """Parse map text; `origin` names the file in error messages."""
    header: list[str] | None = None
    text = text.removeprefix("\ufeff")  # the BOM Excel writes in "CSV UTF-8"
    delimiter = ","
    rows: RegisterMap = {}
    # By table ("holding": the rows; "input": a reference map's 3X rows): address -> (its line, its reference)
    first_line: dict[str, dict[int, tuple[int, str]]] = {"holding": {}, "input": {}}
    named: dict[str, tuple[str, int]] = {}  # code, ASCII case folded as --watch matches it -> (table, address)
    wide: list[tuple[str, int]] = []  # 32-bit rows: (their table, first register)
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip(_SPACE)
        if not stripped or stripped.startswith("#"):
            continue
        if header is None:
            delimiter = _sniff(line)
        try:
            cells = _cells(line, delimiter)
        except (csv.Error, ValueError) as error:
            raise ProfileError(f"{origin}:{number}: {error}") from None
        if header is None:
            header = [cell.strip(_SPACE).translate(_LOWER) for cell in cells]
            unknown = [name for name in header if name not in COLUMNS and name != REFERENCE]
            if unknown:
                raise ProfileError(f"{origin}:{number}: " + _say("unknown_column", name=unknown[0]))
            if REFERENCE in header:
                if "address" in header:
                    raise ProfileError(f"{origin}:{number}: " + _say("reference_and_address"))
                rows = ReferenceRows()
            missing = [name for name in REQUIRED if name not in header and not (
                name == "address" and REFERENCE in header)]
            if missing:
                raise ProfileError(f"{origin}:{number}: " + _say("missing_column", name=missing[0]))
            if len(set(header)) != len(header):
                raise ProfileError(f"{origin}:{number}: " + _say("column_twice"))
            continue
        if len(cells) != len(header):
            separator = "comma" if delimiter == "," else repr(delimiter)
            raise ProfileError(
                f"{origin}:{number}: " + _say("fields", count=len(cells), header=len(header), separator=separator)
            )
        values = dict(zip(header, cells))
        scale = values.get("scale", "")
        if delimiter != "," and _DECIMAL_COMMA.fullmatch(scale.strip(_SPACE)):
            values["scale"] = scale.replace(",", ".")  # `0,1`: the decimal comma of the same spreadsheets
        reference = values.get(REFERENCE, "").strip(_SPACE)
        try:
            if REFERENCE in values:
                values["address"] = str(reference_address(values.pop(REFERENCE)))
            row = _row(values)
        except ValueError as error:
            raise ProfileError(f"{origin}:{number}: {error}") from None
        kind = reference_table(reference) if isinstance(rows, ReferenceRows) else "holding"
        table = rows.inputs if kind == "input" else rows  # type: ignore[attr-defined]
        lines = first_line[kind]
        if row.address in table:
            line, first = lines[row.address]
            raise ProfileError(f"{origin}:{number}: " + (_say(
                "reference_twice", text=reference, table=kind, address=row.address, first=first, line=line)
                if isinstance(rows, ReferenceRows) else _say("address_twice", address=row.address, line=line)))
        folded = row.code.translate(_UPPER)
        if folded in named:
            first_kind, first = named[folded]
            raise ProfileError(f"{origin}:{number}: " + _say(
                "code_twice", code=row.code, address=first, line=first_line[first_kind][first][0]))
        table[row.address] = row
        lines[row.address] = (number, reference)
        named[folded] = (kind, row.address)
        if row.words == 2:
            wide.append((kind, row.address))
    for kind, first in wide:
        table = rows.inputs if kind == "input" else rows  # type: ignore[attr-defined]
        lines, second = first_line[kind], first + 1
        if second in table:
            raise ProfileError(f"{origin}:{lines[second][0]}: " + _say(
                "second_register", address=second, code=table[first].code, kind=table[first].kind,
                line=lines[first][0]))
    if header is None:
        raise ProfileError(f"{origin}: " + _say("no_header"))
    return rows


def overlay(rows: RegisterMap, layer: RegisterMap) -> RegisterMap:
    """`rows` with a --map layer over them (a new map). A layer row hides every row it overlaps, a 32-bit
    row's two registers counted: the user's file says what those registers are (a built-in row it covers
    is what it corrects, and the built-in map is not the user's to edit), so each register is named one
    way in every output. parse_map refuses the same overlap inside one file, where both rows are the
    user's and neither can be taken for the correction."""
    merged = dict(rows)
    for address, row in layer.items():
        before = merged.get(address - 1)
        if before is not None and before.words == 2 and address - 1 not in layer:
            del merged[address - 1]  # (a 32-bit row whose second register the layer names)
        if row.words == 2 and address + 1 not in layer:
            merged.pop(address + 1, None)
    merged.update(layer)
    return merged


def load_map_file(path: str | Path) -> RegisterMap:
    path = Path(path)
    data = read_capped(path, MAX_MAP_BYTES, "map", "register map")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        raise ProfileError(f"{path}: " + _say("utf16" if data[:2] in UTF16_BOMS else "not_utf8")) from None
    # read_text() turned CR LF into LF; splitlines() in parse_map treats both alike.
    return parse_map(text, str(path))


def load_builtin_map(name: str) -> RegisterMap:
    """A map shipped in dissector/data/maps (name: `atv71.csv`)."""
    resource = resources.files("dissector").joinpath("data/maps", name)
    try:
        text = resource.read_text(encoding="utf-8")
    except (OSError, FileNotFoundError):
        raise ProfileError(f"data/maps/{name}: no such built-in map") from None
    return parse_map(text, f"data/maps/{name}")


def interpret_wide(definition: RegisterDef, first: int, second: int) -> tuple[float | int | None, str]:
    """A 32-bit value from the words of its two registers, in the order they come on the wire."""
    high, low = (second, first) if definition.swapped else (first, second)
    raw32 = high << 16 | low
    value: float | int
    scale = definition.scale
    if definition.kind == "float32":
        value = struct.unpack(">f", raw32.to_bytes(4, "big"))[0]
        if not math.isfinite(value):
            return None, str(value)  # nan, inf: no number JSON can hold
        # A float has no fixed decimals: the scale multiplies, and the product is written as the float is
        # (its value, as the text says it).
        text = float32_text(value, 1.0 if scale is None else scale)
        if scale is not None:
            value = float(text)
    else:
        value = raw32 - 0x100000000 if definition.kind == "int32" and raw32 & 0x80000000 else raw32
        if scale is not None:
            value = round(value * scale, definition.decimals)
            if not definition.decimals:
                value = int(value)
            text = f"{value:.{definition.decimals}f}"
        else:
            text = str(value)
    unit = definition.unit
    return value, text if unit is None else f"{text} {unit}"


def float32_text(value: float, scale: float = 1.0) -> str:
    """The float32 `value` times `scale` in the fewest significant digits (1 to 9) that tell it from its
    neighbours' products (the scale 1: the text reads back as the same float32), written as `%.7g` writes
    them (no exponent below 1e7, trailing zeros dropped): two values that differ print differently (%.7g
    alone gave `1` for both 16#3F800000 and 16#3F800001). The plugin (device.lua) reads the same texts."""
    bits = int.from_bytes(struct.pack(">f", value), "big")
    exponent, fraction = bits >> 23 & 0xFF, bits & 0x7FFFFF
    spacing = 2.0 ** (max(exponent, 1) - 150)  # between this float32 and the next away from zero
    below = spacing / 2 if fraction == 0 and exponent > 1 else spacing  # (toward zero: half at a power of 2)
    size = abs(scale)
    return _shortest(value * scale, spacing * size, below * size, fraction % 2 == 0)


def _shortest(value: float, spacing: float, below: float, even: bool) -> str:
    """The fewest digits of `value` nearer to it than half the gap to a neighbour (`spacing` away from zero,
    `below` toward it); exactly half way, the neighbour whose fraction ends in 0 (`even`) takes it."""
    for digits in range(1, 9):
        text = f"{value:.{digits}g}"
        gap = abs(float(text)) - abs(value)
        half = (below if gap < 0 else spacing) / 2
        if abs(gap) < half or (abs(gap) == half and even):
            if value == 0:
                return text
            return f"{float(text):.{max(digits, 7)}g}"  # (the same digits: 50, not 5e+01)
    return f"{value:.9g}"  # 9 digits always tell a float32 from its neighbours


def interpret(definition: RegisterDef, value: int) -> tuple[float | int | None, str | None]:
    """The scaled value and its display text (`50.0 Hz`, `IO (I/O profile)`, bit names)."""
    raw = value - 0x10000 if definition.signed and value & 0x8000 else value
    if definition.enum:
        # The raw word already is the value; an enumeration or a bit field has no scaled value.
        label = definition.enum.get(value)
        return None, label if label is not None else say_text("not_listed", value=value)
    if definition.bits:
        names = [
            definition.bits.get(bit) or say_text("bit_unnamed", bit=bit) for bit in range(16) if value >> bit & 1
        ]
        return None, ", ".join(names) if names else say_text("no_bit_set")
    scale, unit = definition.scale, definition.unit
    if definition.scale_unknown:
        # The device's settings choose the scale (ACC/DEC: the ramp increment): the raw value speaks for
        # itself, signed with its sign, and names the unit it counts in unscaled.
        return (raw if definition.signed else None), say_text("unscaled", value=raw, unit=unit)
    if scale is None:
        # Shown as is: a number in its unit (as a 32-bit row's), or the word itself.
        if unit is not None:
            return raw, f"{raw} {unit}"
        if definition.signed:
            return raw, str(raw)
        return None, None
    scaled = round(raw * scale, definition.decimals)
    if not definition.decimals:
        scaled = int(scaled)
    text = f"{scaled:.{definition.decimals}f}"
    return scaled, text if unit is None else f"{text} {unit}"
