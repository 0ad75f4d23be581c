"""`-T fields -e KEY ... -E option=value`: one line of chosen fields per item, as tshark writes them.

A KEY is any key of the NDJSON object (`frame`, `time`, `slave`, `response_time`, ...), a key inside
`fields` as `fields.KEY`, `time_relative`, `time_delta` or `time_delta_displayed` (seconds, as tshark's
frame.time_* fields: from the first item, the previous captured, the previous shown), or a register key
(`address`, `value`, `code`, `name`, `scaled`, `status`, ...), written as tshark writes the plugin's
vw3.reg.KEY: a text key (`code`, `name`, `status`, ...) has one occurrence per register (and bit) the frame
carries, empty where that register has none (as the plugin's hidden empty text field), so that
`-E occurrence=f` names the first register's; a number key (`value`, `scaled`, `words`) has only the values
there are (tshark writes no empty number); `address` (and `label`, where there is one) then lists the
addresses the frame names without carrying them (a read request's window), which -Y's `address` tests too,
as the plugin's hidden vw3.reg.address (a request's `value` is empty, not `,,`). Lists
(`warnings`, `notes`, a `fields.KEY` such as `fields.values`) have one occurrence per element. A key the Wireshark plugin has a field for is
written as tshark 4.0 writes that field (data/fields.toml): `crc` 0x7734, `scaled` 4, `response_time`
0.020000000, and `broadcast`, `unanswered` nothing where false; `time` as tshark's frame.time_epoch (9 decimals). As tshark: `-E occurrence=f|l|a` picks the first, last or all
occurrences, joined by `-E aggregator=` (default ,); `-E separator=` (default tab; /t tab, /s space)
goes between fields; `-E quote=d|s|n` surrounds every value (the header is never quoted);
(a field without occurrence stays empty, unquoted, as tshark's) `-E header=y` names the fields on a first line; `-E bom=y` starts with a UTF-8 byte order mark.
With quote=d a double quote inside a value is doubled (RFC 4180), so a spreadsheet reads it back.

Values are data from the bus and from map files: control characters are written as escapes (\x1b).
With a `,` or `;` separator (a CSV for a spreadsheet) no cell a spreadsheet reads starts a formula
(`=`, `+`, `-`, `@`, a tab or a CR, not a plain number), as OWASP advises against CSV injection:
- a value that starts so gets a leading `'` (`=HYPERLINK(...)` from an FC17 answer stays text);
- a value that holds a `,`, a `;` or a `"` (the separator, the aggregator, or the separator of a
  spreadsheet in another locale) would split into cells nobody checked (`SEL,@SUM(1+1)`, the codes
  `,=1+1,COP` joined by the aggregator): it is written between double quotes, `"` doubled (RFC 4180, as
  tshark's `-E quote=d`), so it stays one cell and its value stays exact; with `-E quote=d` every value
  is so already; with `-E quote=s` (single quotes, which a spreadsheet does not read as quoting) each
  piece after a `,` or `;` that would start a formula gets the `'` instead.
`-E formulas=y` keeps values as they are. A tab or space separator is not a CSV: values stay exact, as
tshark writes them.
"""
from __future__ import annotations

import decimal
import json
import re
from dataclasses import dataclass
from typing import Any

from dissector.errors import UsageError
from dissector.render.filter_fields import (  # not filters: -Y only
    ALIASES, CATALOGUE, DERIVED_KEYS, FRAME_FIELDS, ONLY_TRUE, RECORD_KEYS, REGISTER_FIELDS, pdu_values,
)
from dissector.render.filter_match import item_elements, register_value
from dissector.protocol.printable import printable
from dissector.render.timefmt import TIME_FIELDS

# Keys of the NDJSON object the filter does not list (kept in step with render.jsonout).
EXTRA_FRAME_KEYS = ("span_label", "write_span_label", "exception_meaning", "objects", "fields", "bits", "registers",
                    "file")
SWITCHES = ("y", "n")
QUOTES = {"d": '"', "s": "'", "n": ""}
OCCURRENCES = ("f", "l", "a")


@dataclass(frozen=True, slots=True)
class FieldsOptions:
    fields: tuple[str, ...]
    separator: str = "\t"
    aggregator: str = ","
    quote: str = "n"  # d | s | n
    occurrence: str = "a"  # f | l | a
    header: bool = False
    bom: bool = False
    formulas: bool = False  # -E formulas=y: keep values that a spreadsheet would run as formulas


SPREADSHEET_SEPARATORS = (",", ";")
_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
_NUMBER = re.compile(r"[-+]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?")


_SPLITS = re.compile(r"([,;])")  # where a spreadsheet may start a cell inside an unquoted value
_NEEDS_QUOTES = re.compile(r'[,;"]')


def neutralise(text: str) -> str:
    """A CSV value a spreadsheet reads as text, never as a formula (numbers such as -12.5 stay)."""
    if text.startswith(_FORMULA_START) and not _NUMBER.fullmatch(text):
        return "'" + text
    return text


def spreadsheet_cell(text: str, quote: str) -> str:
    """`text` as one CSV cell no spreadsheet runs as a formula, whatever `,` or `;` it holds: quoted
    (double quotes, doubled inside) where it holds one and no quote was asked, each piece neutralised
    under single quotes (no quoting a spreadsheet knows), else as `quote` asks."""
    text = neutralise(text)
    if quote == "'":
        pieces = _SPLITS.split(text)
        text = "".join(piece if index % 2 else neutralise(piece) for index, piece in enumerate(pieces))
    elif not quote and _NEEDS_QUOTES.search(text):
        quote = '"'
    if quote:
        return quote + text.replace(quote, quote + quote) + quote
    return text


def _character(text: str, option: str) -> str:
    if text == "/t":
        return "\t"
    if text == "/s":
        return " "
    if not text:
        raise UsageError(f"-E {option}= needs a character (/t tab, /s space, or the character)")
    if len(text) != 1:  # (-E separator=ab was taken whole, as the rows' one-character separator)
        raise UsageError(f"-E {option}={text}: one character (/t tab, /s space, or the character)")
    return text


def parse_fields_options(fields: list[str], settings: list[str]) -> FieldsOptions:
    """FieldsOptions from the -e KEY and -E name=value arguments; UsageError names what is wrong."""
    for key in fields:
        check_field(key)
    values: dict[str, Any] = {}
    for setting in settings:
        name, equals, value = setting.partition("=")
        if not equals:
            raise UsageError(f"-E {setting}: expected name=value, e.g. -E separator=,")
        if name == "separator" or name == "aggregator":
            values[name] = _character(value, name)
        elif name in ("header", "bom", "formulas"):
            if value not in SWITCHES:
                raise UsageError(f"-E {name}={value}: expected y or n")
            values[name] = value == "y"
        elif name == "quote":
            if value not in QUOTES:
                raise UsageError(f"-E quote={value}: expected d (double), s (single) or n (none)")
            values[name] = value
        elif name == "occurrence":
            if value not in OCCURRENCES:
                raise UsageError(f"-E occurrence={value}: expected f (first), l (last) or a (all)")
            values[name] = value
        else:
            raise UsageError(
                f"-E {name}: unknown option; use header, separator, quote, occurrence, aggregator, bom or formulas"
            )
    return FieldsOptions(tuple(fields), **values)


def check_field(key: str) -> None:
    key = ALIASES.get(key, key)  # (-e exception: the exception_code column, headed as asked)
    head = key.split(".", 1)[0]
    if key in TIME_FIELDS:
        return
    ours = _foreign(key)
    if ours is not None:  # a name from a tshark command line (frame.number, mbrtu.unit_id): said as -Y says it
        raise UsageError(f"-e {key}: not a field (vw3-decode names it {ours})")
    if head in FRAME_FIELDS or head in REGISTER_FIELDS or head in EXTRA_FRAME_KEYS:
        if "." in key and head != "fields":
            raise UsageError(f"-e {key}: only fields.KEY names a key inside a value")
        if head == "fields" and "." in key:
            from dissector.render.filter_fields import unknown_pdu_key

            problem = unknown_pdu_key(key[7:])
            if problem is not None:
                raise UsageError(f"-e {key}: {problem}")
        return
    import difflib

    names = [*FRAME_FIELDS, *REGISTER_FIELDS, *EXTRA_FRAME_KEYS, *TIME_FIELDS, *ALIASES]
    close = difflib.get_close_matches(key, names, n=1)
    hint = f" (did you mean {close[0]}?)" if close else " (see the NDJSON keys in the README)"
    raise UsageError(f"-e {key}: not a field{hint}")


def _foreign(key: str) -> str | None:
    """vw3-decode's key for a Wireshark field name (filter_fields.foreign_name; frame.time_delta_displayed,
    which -Y refuses, is a -T fields key), None for any other."""
    from dissector.render.filter_fields import foreign_name

    if key.startswith("frame.") and key[6:] in TIME_FIELDS:
        return key[6:]
    return foreign_name(key) if "." in key and not key.startswith("fields.") else None


def _text(value: Any) -> str:
    if value is None:
        return ""
    if value is True or value is False:
        return "1" if value else "0"  # as tshark 4.0 prints booleans
    if isinstance(value, (dict, list)):
        return json.dumps(value, separators=(",", ":"))
    return str(value)


_HEX_DIGITS = {"uint8": 2, "uint16": 4, "uint32": 8}


def _shown_as(entry: dict[str, Any]) -> Any:
    """How tshark 4.0 prints the plugin's field of a key (data/fields.toml), as a function of a value not
    None or bool; None: as _text. -T fields of both then write the same text for the same frame."""
    ftype = entry.get("ftype")
    if entry.get("base") == "HEX" and ftype in _HEX_DIGITS:
        return f"0x{{:0{_HEX_DIGITS[ftype]}x}}".format  # (crc 0x7734, not 30516)
    if ftype == "double":
        return "{:.15g}".format  # (scaled 4, not 4.0; 15 digits, as Wireshark shows a double)
    if ftype == "relative_time":
        return "{:.9f}".format  # (0.020000000: seconds and nanoseconds; vw3-decode's times are whole ns)
    return None


def epoch_text(time: float) -> str:
    """`time` as tshark 4.0 writes frame.time_epoch: seconds and nanoseconds, 9 decimals always
    (1767225600.006590000, not 1767225600.00659), exact from a Stamp's integer nanoseconds (a float near
    1.7e9 s keeps about 0.2 us), else from the float's shortest decimal form."""
    ns = getattr(time, "ns", None)
    if ns is None:
        ns = int(decimal.Decimal(repr(float(time))).scaleb(9).to_integral_value(decimal.ROUND_HALF_EVEN))
    sign = "-" if ns < 0 else ""
    whole, rest = divmod(abs(ns), 1_000_000_000)
    return f"{sign}{whole}.{rest:09d}"


SHOWN_AS = {entry["key"]: shown for entry in CATALOGUE if "key" in entry and (shown := _shown_as(entry))}
SHOWN_AS["time"] = epoch_text  # (no plugin field: tshark's own frame.time_epoch)


def _occurrences(record: dict[str, Any], key: str) -> list[Any]:
    head, _dot, rest = ALIASES.get(key, key).partition(".")
    if head in REGISTER_FIELDS:
        # As tshark writes the plugin's fields: a text key has one occurrence per register carried, empty
        # where the register has none (8400 has no code: the plugin's hidden empty text); a number has only
        # the values there are (an empty number field would crash tshark 4.0's comparisons). Then what the
        # frame names without carrying it (a read request's window): its addresses and labels, as -Y's
        # `address` and `label` test them and the plugin's hidden vw3.reg.address and vw3.reg.label have them.
        # (-Y reads the same occurrences: filter_match.register_value)
        return [value for element in item_elements(record)
                if (value := register_value(record, element, head)) is not None]
    if head == "fields" and rest in DERIVED_KEYS:  # (fields.event_list: each event's byte, as modbus.event)
        return pdu_values(record.get("fields"), rest)
    value = record.get(RECORD_KEYS.get(head, head))
    if rest:
        for part in rest.split("."):
            value = value.get(part) if isinstance(value, dict) else None
    if value is None or value is False and head in ONLY_TRUE:
        return []
    if isinstance(value, list) and head in ("warnings", "notes", "fields", "comment"):
        return value  # (a repeated field: fields.values, as -Y's fields.KEY tests each element)
    return [value]


class FieldsWriter:
    """Formats records as lines of fields."""

    def __init__(self, options: FieldsOptions) -> None:
        self.options = options
        self._quote = QUOTES[options.quote]
        self.time_keys = tuple(key for key in TIME_FIELDS if key in options.fields)  # from the Clock
        self._neutralise = options.separator in SPREADSHEET_SEPARATORS and not options.formulas

    def header(self) -> str:
        return self.options.separator.join(self.options.fields)

    def line(self, record: dict[str, Any]) -> str:
        options = self.options
        quote = self._quote
        out = []
        for key in options.fields:
            values = _occurrences(record, key)
            if not values:  # (no occurrence: nothing, not even quotes, as tshark; an empty one is quoted)
                out.append("")
                continue
            if options.occurrence == "f":
                values = values[:1]
            elif options.occurrence == "l":
                values = values[-1:]
            shown = SHOWN_AS.get(ALIASES.get(key, key))
            text = printable(options.aggregator.join(
                shown(value) if shown is not None and value is not None and not isinstance(value, bool)
                else _text(value) for value in values))
            if self._neutralise:
                out.append(spreadsheet_cell(text, quote))
            elif quote:
                out.append(quote + text.replace(quote, quote + quote) + quote)
            else:
                out.append(text)
        return options.separator.join(out)

    def preamble(self) -> tuple[str | None, str]:
        """(the header line or None, what the first line starts with: the BOM or nothing)."""
        bom = "\ufeff" if self.options.bom else ""
        return (self.header() if self.options.header else None), bom
