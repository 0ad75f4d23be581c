"""`-T registers`: one line per register (and coil) occurrence, for a spreadsheet or a trend.

Rows are the NDJSON records' `registers` and `bits` lists, flattened: the same item, the same values,
so `-T registers` cannot disagree with `--json` (and `--parquet`'s registers table is made by the same
`register_rows`). `access` says what the occurrence is:
- `read`: a value a read answered (FC1-4, the read half of FC23), its `status` as the profile judged it
  (`ok`, `protected`, `non-existent`, `ambiguous`; empty without a profile);
- `write`: a value a request writes (FC5/6/15/16, the write half of FC23; a broadcast too);
- `echo`: the value a write's answer repeats (FC5, FC6): the write confirmed;
- a Mask Write (FC22, [confirm] "mask") is one `write` row of its request and one `echo` row of its
  answer, at the register's address: `text` shows its masks as the summary does (`AND 0x00F2 OR 0x0025`);
  the register then holds (its value before AND and_mask) OR (or_mask AND NOT and_mask) (Application
  Protocol 6.16), so `value` is or_mask where and_mask is 0 and empty elsewhere (the value before is
  not in the frame; the text says so rather than guess): --json's register of the frame (mask_register);
- `exception`: a register an exception tells the status of (ATV71 exception 02 to a read whose every
  parameter is non-existent or protected, p.38), `value` empty.
`write` says what became of a written value (the codes of data/modbus.toml [confirm] write, and it says
how each is confirmed), as `--stats` counts it (render/history.py): `confirmed` (a normal answer; for a
code confirmed by its echo, the echo repeats this value: the echo row itself is `confirmed`), `differs`
(the echo answers another value, or FC22 other masks: the echo row's is the one confirmed), `refused` (an exception answered,
its code in `exception_code`), `unanswered`, `broadcast` (no answer comes to a broadcast) or `unknown`
(the capture ends before any answer, or the request or its answer failed its check: --stats takes it as
neither confirmed nor refused); empty on a read. `exception_code` is also an exception row's own.
`time` is the time column as `-t` shows it (empty for a capture without timestamps). `text` is
what the summary shows for the value: an enumeration's or a bit field's words, a scaled value and its
unit, or the status.
"""
from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from dissector.model import Frame, Item, Kind
from dissector.protocol.rules import CONFIRM, Confirm, confirmed_by, text
from dissector.protocol.printable import printable

COLUMNS = (
    "frame", "time", "slave", "function", "access", "address", "label", "code", "name", "value", "scaled",
    "unit", "status", "text", "write", "exception_code",  # (the last two added later: positions kept)
)
# Keys a row takes as they are from the register (or bit) object of the NDJSON record.
REGISTER_KEYS = ("address", "label", "code", "name", "value", "scaled", "unit", "status", "text")
ECHOES = confirmed_by(Confirm.ECHO)  # whose answer repeats the values written (FC5, FC6): `echo` rows
MASKS = confirmed_by(Confirm.MASK)  # whose answer repeats the masks written (FC22): `echo` rows too
MASK_FIELDS = ("address", "and_mask", "or_mask")


def access_of(record: dict[str, Any]) -> str:
    kind = record["kind"]
    if kind == "request":
        return "write"
    if kind == "exception":
        return "exception"
    return "echo" if record["function"] in ECHOES or record["function"] in MASKS else "read"


def _echoed(frame: Frame) -> dict[int | None, Any]:
    """The values an answer repeats, by address (its registers, or its coil)."""
    return {element.address: element.value for element in (frame.registers or ()) or (frame.bits or ())}


def write_outcome(record: dict[str, Any], item: Item | None) -> tuple[str | None, int | None, dict | None]:
    """(`write`, `exception_code`, the echo's values by address or None) of a record's rows (the module's
    doc); `item` is the record's frame: a request's answer is known from it only (None: what the record
    tells alone, an answered request's outcome unknown to the caller: empty)."""
    kind, function = record["kind"], record["function"]
    if kind == "exception":
        return None, record["exception_code"], None
    how = CONFIRM.get(function)
    if how is None:
        return None, None, None
    if kind == "response":  # an echo confirms its own values (--stats CONFIRM)
        echoes = how is Confirm.ECHO or how is Confirm.MASK
        return ("confirmed" if record["crc_ok"] else "unknown") if echoes else None, None, None
    if record["broadcast"]:
        return "broadcast", None, None
    if record["unanswered"]:
        return "unanswered", None, None
    answer = item.response if isinstance(item, Frame) else None
    if answer is None:
        # (no answer in the capture: it ends first; or the caller has not the frame)
        return ("unknown" if item is not None or "response_frame" not in record else None), None, None
    if not (record["crc_ok"] and answer.crc_ok):
        return "unknown", None, None  # (--stats takes neither as a refusal or a confirmation)
    if answer.kind is Kind.EXCEPTION:
        return "refused", answer.exception_code, None
    if how is Confirm.MASK:  # (the echo's masks: another mask than asked is not the write confirmed)
        masks = _masks(answer.fields)
        return ("confirmed" if masks == _masks(record.get("fields") or item.fields) else "differs"), None, None
    return "confirmed", None, _echoed(answer) if how is Confirm.ECHO else None


def _masks(fields: Any) -> tuple[int, int, int] | None:
    """(address, and_mask, or_mask) of an FC22 frame's fields (a Frame's or a record's), None: malformed."""
    return None if fields is None else tuple(fields[name] for name in MASK_FIELDS)  # type: ignore[return-value]


def mask_register(frame: Frame) -> dict[str, Any] | None:
    """The register element an FC22 request or echo carries in --json's `registers` (render/jsonout.py) and
    so in -T registers, -T fields, -Y and --parquet (the module's doc): its address, its value where it does
    not depend on the value before, its masks as text; None: not one, or malformed."""
    if frame.function not in MASKS or frame.kind is Kind.EXCEPTION:
        return None
    masks = _masks(frame.fields)
    if masks is None:
        return None
    address, and_mask, or_mask = masks
    known = and_mask == 0  # (every bit from or_mask: the value before does not matter)
    out: dict[str, Any] = {"address": address, "value": or_mask if known else None,
                           "text": text("mask_written" if known else "mask_prior", and_mask=and_mask, or_mask=or_mask)}
    if frame.span_label is not None:
        out["label"] = frame.span_label
    return out


def register_rows(record: dict[str, Any], item: Item | None = None) -> Iterator[dict[str, Any]]:
    """One dict per register and bit of an NDJSON record (none for noise), keys as COLUMNS but `time`
    (the record's epoch seconds are the caller's to show); `item`: the record's frame (write_outcome)."""
    elements = (record.get("registers") or []) + (record.get("bits") or [])
    if not elements:
        return
    write, code, echoed = write_outcome(record, item)
    head = {
        "frame": record["frame"], "slave": record["slave"], "function": record["function"],
        "access": access_of(record), "write": write, "exception_code": code,
    }
    for element in elements:
        row = dict(head)
        for key in REGISTER_KEYS:
            row[key] = element.get(key)
        if echoed is not None and echoed.get(row["address"], None) != row["value"]:
            row["write"] = "differs"
        yield row


def _text(value: Any) -> str:
    if value is None:
        return ""
    if value is True or value is False:
        return "1" if value else "0"
    return str(value)


class RegistersWriter:
    """Formats records as register lines with `-E` separator, quote, header and bom (FieldsOptions)."""

    def __init__(self, separator: str = "\t", quote: str = "", header: bool = False, bom: bool = False,
                 with_file: bool = False, formulas: bool = False) -> None:
        from dissector.render.fields import SPREADSHEET_SEPARATORS

        self.separator = separator
        # Values are data (map texts, FC17 bytes): as -T fields, escaped, and made single cells no
        # spreadsheet runs as formulas with a , or ; separator unless -E formulas=y (fields.spreadsheet_cell).
        self._neutralise = separator in SPREADSHEET_SEPARATORS and not formulas
        self.quote = quote
        self.header = header
        self.bom = bom
        self.columns = (("file",) if with_file else ()) + COLUMNS

    def preamble(self) -> tuple[str | None, str]:
        """(the header line or None, what the first line starts with: the BOM or nothing)."""
        return (self.separator.join(self.columns) if self.header else None), ("\ufeff" if self.bom else "")

    def lines(self, record: dict[str, Any], time: str | None, item: Item | None = None) -> list[str]:
        """`item`: the record's frame, whose answer tells what became of its writes (write_outcome)."""
        from dissector.render.fields import spreadsheet_cell

        quote, separator = self.quote, self.separator
        file = record.get("file")
        out = []
        for row in register_rows(record, item):
            row["time"] = time
            if file is not None:
                row["file"] = file
            values = [printable(_text(row.get(column))) for column in self.columns]
            if self._neutralise:
                values = [spreadsheet_cell(value, quote) for value in values]
            elif quote:
                values = [quote + value.replace(quote, quote + quote) + quote for value in values]
            out.append(separator.join(values))
        return out


def parse_registers_options(settings: list[str], with_file: bool) -> RegistersWriter:
    """The writer for `-E` settings; occurrence and aggregator mean nothing with one value a line."""
    from dissector.errors import UsageError
    from dissector.render.fields import QUOTES, parse_fields_options

    for setting in settings:
        name = setting.partition("=")[0]
        if name in ("occurrence", "aggregator"):
            raise UsageError(f"-E {name}: -T registers has one value a line; use header, separator, quote or bom")
    options = parse_fields_options([], settings)
    return RegistersWriter(options.separator, QUOTES[options.quote], options.header, options.bom, with_file,
                           options.formulas)
