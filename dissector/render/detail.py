"""The -V detail tree: every field of a frame, as tshark's packet details pane shows it.

`detail_tree` builds a neutral tree of `Node`s; `render_plain` and `render_rich` draw it, so the layout
is decided once and a terminal only adds colour.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from operator import attrgetter
from typing import TYPE_CHECKING, Any

from construct import ListContainer

from dissector.decode.fields import comm_event_bits
from dissector.model import BitList, Frame, Item, Kind, Noise, Register, RegisterList
from dissector.protocol.spec import SPEC
from dissector.render.runs import AddressPieces, BitRuns, Pieces, interleave
from dissector.protocol.printable import printable
from dissector.render.describe import UNKNOWN_SUBFUNCTION, count_text, named_value, pdu_fields, value_names
from dissector.render.detail_window import NESTED_HEX_WIDTHS, hex_width, implied_quantity, window_lines
from dissector.render.filter_fields import CATALOGUE
from dissector.render.registers import MASKS, mask_register
from dissector.render.summary import check_untyped, crc_text, noise_info
from dissector.render.timefmt import MICRO_DIGITS, arrival_line

if TYPE_CHECKING:
    from rich.text import Text
    from rich.tree import Tree


@dataclass(slots=True)
class Node:
    label: str
    children: list[Node] = field(default_factory=list)
    style: str | None = None

    def add(self, label: str, style: str | None = None) -> Node:
        child = Node(label, style=style)
        self.children.append(child)
        return child


# A detail is laid out once, as a flat list of texts that carry their indentation (four spaces a
# level) and the styles of the few lines that have one (by index): plain output only joins the texts,
# never building a tree (a Node per line cost -V half its time); a terminal builds rich's Tree from the
# same texts, a line's depth read back from its indentation.
Line = tuple[int, str, "str | None"]
_PROTECTED = frozenset(("protected", "non-existent", "ambiguous"))
_INDENT = ["    " * depth for depth in range(32)]
_KIND_TEXT = {kind: kind.value for kind in Kind}
_EXCEPTION = Kind.EXCEPTION
_RESPONSE = Kind.RESPONSE
_MODBUS_RTU = "    Modbus RTU"
_FUNCTION_LINES: dict[int, str] = {}  # spec names only: a profile's names vary per slave
_SLAVE_LINES: dict[int, str] = {}
_CRC_OK_LINES: dict[int, str] = {}
_INT_FIELD_LINES: dict[tuple[Any, int], str] = {}  # `        Start: 8400 (0x20D0)` by (key, value)
_INT_FIELD_LINES_MAX = 1 << 16
# A PDU field's label: its key's words, the first capitalized, the spec's acronyms as it writes them
# (`FIFO count`, `MEI type`); by (function, key), the spec's name of a field its key does not say (FC24's
# `address` is the FIFO Pointer Address, Application Protocol 6.18, as the Info text's `pointer`). The
# plugin's tree says the same (codegen/fields_lua.py start_words; data/pdu_fields.toml titles).
_ACRONYMS = {"fifo": "FIFO", "mei": "MEI"}
FUNCTION_LABELS: dict[tuple[int, str], str] = {(24, "address"): "FIFO pointer address"}
_LABELLED = frozenset(function for function, _key in FUNCTION_LABELS)


def _hex_names() -> dict[str, dict[int, str]]:
    """{PDU field key: its values' names} of the plugin's named fields of base HEX (data/fields.toml's
    vw3.run_indicator, its PDU fields by data/pdu_fields.toml [pdu]), which Wireshark writes `ON (0xff)`."""
    shows = pdu_fields()["pdu"]
    names: dict[str, dict[int, str]] = {}
    for entry in CATALOGUE:
        if "values" in entry and entry.get("base") == "HEX":
            for pdu in shows.get(entry["filter"], ()):
                names[pdu.split(".")[1]] = SPEC.names[entry["values"]]
    return names


_HEX_NAMES = _hex_names()


def _hex_named(key: str, value: Any) -> str:
    """A value of a field of _HEX_NAMES as the plugin's tree writes it: its name (`Unknown` for none) and its
    byte in lower-case hex, Wireshark's way. The decoder gives a named value as its name (`ON`)."""
    names = _HEX_NAMES[key]
    number = getattr(value, "intvalue", value)
    if isinstance(number, str):  # (a name without its number: the one the spec gives it)
        number = next(code for code, name in names.items() if name == number)
    return f"{names.get(number, 'Unknown')} (0x{number:02x})"


# The plugin's field titles and value strings (data/fields.toml) of the PDU keys it shows by a field of the
# key's own (vw3.start `Start address`, vw3.subfunction `Sub-function`, named by the spec's table as Wireshark
# writes a value string: `Return Query Data (0)`, `Unknown (99)`), so -V names them as its tree does.
_CATALOGUE_KEYS = {entry["key"]: entry for entry in CATALOGUE if "key" in entry and entry.get("ftype") != "none"}
_TITLES = {key: entry["title"] for key, entry in _CATALOGUE_KEYS.items() if "title" in entry}
_NAMED = {key: getattr(SPEC, entry["values"]) for key, entry in _CATALOGUE_KEYS.items()
          if entry.get("values") in ("diagnostics", "exceptions")}


def _key_words(key: str) -> str:
    words = [_ACRONYMS.get(word, word) for word in key.split("_")]
    words[0] = words[0][:1].upper() + words[0][1:]
    return " ".join(words)


# The plugin's spelling of a PDU key's own words (data/pdu_fields.toml: FC22's `AND mask`, as tshark titles
# modbus.and_mask), so -V writes them as its tree does; a title in other words (a list's `FIFO value`, one
# element's) is the plugin's field, not -V's label.
_SPELLED = {leaf: entry["title"] for entry in pdu_fields()["field"] for leaf in
            (path.rpartition(".")[2] for path in entry.get("pdu", ()))
            if entry["title"] != _key_words(leaf) and entry["title"].lower() == _key_words(leaf).lower()}


def field_label(key: str, function: int | None = None) -> str:
    label = FUNCTION_LABELS.get((function, key)) if function is not None else None
    if label is None:
        label = _TITLES.get(key)
    if label is None:
        label = _SPELLED.get(key) or _key_words(key)
    return label


# A register's lines depend on its fields only; polled blocks repeat them, so they are kept by
# content (bounded: cleared when full, so memory stays flat on values that never repeat): the texts,
# and the style of the lines that have one (offset in the block, style).
# The joined text is what plain output appends: one text per register instead of its lines.
Block = tuple[tuple[str, ...], tuple[tuple[int, str], ...], str]
_REGISTER_BLOCKS: dict[tuple[Any, ...], Block] = {}
_REGISTER_BLOCKS_MAX = 1 << 16
_REGISTER_KEY = attrgetter("address", "value", "code", "name", "text", "status", "unit", "source", "label", "words")
_MIDDLES: dict[tuple[Any, ...], str] = {}  # plain Slave..CRC texts of frames without values, by bytes
_MIDDLES_MAX = 1 << 14
_HEADS: dict[tuple[Any, ...], str] = {}  # Slave..fields texts of frames of values, by their header bytes

# Plain output writes a long run (a 2000-coil read, a 125-register block) from cached pieces (runs.py).
_BIT_RUNS = BitRuns("            %d: ", "0\n", "1\n")
# A register line's address part (its newline before it) by address or label; its value part by value.
_LINE_ADDRESS_HEADS = AddressPieces("\n        Register %d: ")
_LINE_LABEL_HEADS = Pieces("\n        Register %s: ")


class _Words(dict):  # type: ignore[type-arg]
    """`8400 (0x20D0)` by 16-bit value, made on first sight (65,536 at most)."""

    __slots__ = ()

    def __missing__(self, value: int) -> str:
        text = self[value] = f"{value} (0x{value:04X})"
        return text


_WORDS = _Words()


class _Detail:
    """The texts of one detail and the styles of its styled lines, by index."""

    __slots__ = ("texts", "styles", "joined")

    def __init__(self, joined: bool) -> None:
        self.texts: list[str] = []
        self.styles: dict[int, str] = {}
        # Plain output: a long run of lines (a 2000-coil read) may be one text holding newlines.
        self.joined = joined

    def styled(self, text: str, style: str) -> None:
        self.styles[len(self.texts)] = style
        self.texts.append(text)

    def run(self, texts: list[str]) -> None:
        if self.joined:
            if texts:
                self.texts.append("\n".join(texts))
        else:
            self.texts.extend(texts)


def _register_block(register: Register) -> Block:
    """The lines of one register under the Modbus node (depth 2)."""
    address = register.label
    if address is None:
        address = "?" if register.address is None else register.address
    value = register.value
    # No value: a status an exception tells (p.38 exception 02 to a read).
    shown = "no value" if value is None else f"{value} (0x{value:04X})"
    code = register.code
    if code:
        name = register.name
        head = (f"        Register {address}: {shown}  {code} [{name}]" if name
                else f"        Register {address}: {shown}  {code}")
    else:
        head = f"        Register {address}: {shown}"
    status = register.status
    style = "vw3.protected" if status in _PROTECTED else None
    lines = [head]
    styles: list[tuple[int, str]] = []
    if style is not None:
        styles.append((0, style))
    if register.text is not None:
        lines.append(f"            Value: {register.text}")
    if register.words == 2:
        lines.append("            32-bit value: this register and the next")
    if status is not None:
        if style is not None:
            styles.append((len(lines), style))
        lines.append(f"            Status: {status}")
    if register.unit:
        lines.append(f"            Unit: {register.unit}")
    if register.source:
        lines.append(f"            Source: {register.source}")
    return tuple(lines), tuple(styles), "\n".join(lines)


def _register_lines(detail: _Detail, registers: Sequence[Register]) -> None:
    if type(registers) is RegisterList and registers.plain:  # straight from the columns
        values = registers.values
        if registers.start is None:
            detail.run([f"        Register ?: {value} (0x{value:04X})" for value in values])
        elif detail.joined and values:
            labels = registers.labels
            heads = _LINE_ADDRESS_HEADS(registers.addresses) if labels is None else _LINE_LABEL_HEADS(labels)
            # (the pieces _values_middle writes: each line's address part has its newline before it)
            detail.texts.append(interleave((heads, map(_WORDS.__getitem__, values)), len(values))[1:])
        else:
            shown = registers.labels or registers.addresses
            detail.run([f"        Register {address}: {value} (0x{value:04X})" for address, value in zip(shown, values)])
        return
    blocks = _REGISTER_BLOCKS
    texts = detail.texts
    run: list[str] = []  # unannotated registers in a row (a relay's block, a meter's readings)
    for register in registers:
        if (
            register.code is None and register.text is None and register.status is None
            and not register.unit and not register.source
        ):
            address = register.label
            if address is None:
                address = "?" if register.address is None else register.address
            value = register.value
            run.append(f"        Register {address}: {value} (0x{value:04X})")
            continue
        if run:
            detail.run(run)
            run = []
        key = _REGISTER_KEY(register)  # what its lines depend on, read in C
        block = blocks.get(key)
        if block is None:
            if len(blocks) >= _REGISTER_BLOCKS_MAX:
                blocks.clear()
            block = blocks[key] = _register_block(register)
        if detail.joined:
            texts.append(block[2])
            continue
        lines, styles, _text = block
        for offset, style in styles:
            detail.styles[len(texts) + offset] = style
        texts.extend(lines)
    if run:
        detail.run(run)


def _field_lines(detail: _Detail, depth: int, name: str, value: Any) -> None:
    label = _INDENT[depth] + field_label(name)
    texts = detail.texts
    if isinstance(value, dict):
        texts.append(label)
        for key, inner in value.items():
            if key.startswith("_") or inner is None or (key == "trailing" and not inner):
                continue
            if key == "flags" and "event" in value:  # (FC12's event: each bit of its kind, as tshark -V)
                texts.append(_INDENT[depth + 1] + "Flags")
                texts.extend(_INDENT[depth + 2] + line for line in comm_event_bits(value["byte"]))
                continue
            _field_lines(detail, depth + 1, key, inner)
    elif isinstance(value, list):
        texts.append(f"{label} ({len(value)})")
        indent = _INDENT[depth + 1]
        if all(type(inner) is int for inner in value):  # words (file records, FIFO): formatted in bulk
            width = NESTED_HEX_WIDTHS.get(name, 0)  # (a word's four digits, as the plugin's vw3.file.value)
            detail.run([f"{indent}[{index}]: {inner} (0x{inner:0{width}X})" for index, inner in enumerate(value)])
            return
        for index, inner in enumerate(value):
            _field_lines(detail, depth + 1, f"[{index}]", inner)
    elif isinstance(value, bytes):
        # (none: no line, as the plugin's tree and Wireshark's modbus show no empty field, FC12's no events;
        # its hex as Wireshark writes a field of bytes: `Data: ff00`)
        if value:
            texts.append(f"{label}: {value.hex()}")
    elif name in _HEX_NAMES:  # `Run indicator: ON (0xff)`, `Unknown (0x76)`: named or not, as the plugin's
        texts.append(f"{label}: {_hex_named(name, value)}")
    elif isinstance(value, int) and not isinstance(value, bool):
        names = value_names().get(name)  # (the plugin's value strings: `Read code: basic (1)`)
        width = NESTED_HEX_WIDTHS.get(name, 0)  # (FC43's more-follows byte: two digits, detail_window)
        texts.append(f"{label}: {value} (0x{value:0{width}X})" if names is None else
                     f"{label}: {named_value(names, value)}")
    else:
        texts.append(f"{label}: {value}")


def _kept_text(cache: dict[tuple[Any, ...], str], key: tuple[Any, ...],
               lines: Callable[[_Detail, Frame], None], frame: Frame, most: int = _MIDDLES_MAX) -> str:
    """The joined text `lines` writes for `frame`, kept in `cache` by `key` (bounded: cleared when it
    holds `most`)."""
    text = cache.get(key)
    if text is None:
        if len(cache) >= most:
            cache.clear()
        part = _Detail(joined=True)
        lines(part, frame)
        text = cache[key] = "\n".join(part.texts)
    return text


def _head_key(frame: Frame) -> tuple[Any, ...] | None:
    """What the Slave..Sub-function lines of a frame of values depend on, when that is the bytes before
    the values (a read's answer, FC16 and FC23 requests: `values` end the PDU), else None."""
    fields = frame.fields
    if frame.mode != "rtu" or not isinstance(fields, dict):
        return None
    values = fields.get("values")
    if type(values) is not ListContainer or fields.get("trailing") != b"" or fields.get("odd_byte") is not None:
        return None
    raw = frame.raw
    cut = len(raw) - 2 - 2 * len(values)
    if cut < 2:
        return None
    return (raw[:cut], frame.kind, frame.function_text, frame.subfunction_text, frame.start, frame.quantity)


def _middle(detail: _Detail, frame: Frame) -> None:
    """The lines from Slave to the CRC (depth 2)."""
    if detail.joined and frame.registers and frame.kind is not _EXCEPTION:
        # Polled blocks repeat their head (Slave, Function, Byte count) with new values: kept by bytes.
        key = _head_key(frame)
        if key is not None:
            detail.texts.append(_kept_text(_HEADS, key, _head_lines, frame))
            _body_lines(detail, frame)
            return
    _head_lines(detail, frame)
    _body_lines(detail, frame)


def _head_lines(detail: _Detail, frame: Frame) -> None:
    """Slave to the sub-function name: what the frame's header bytes and its profile's words say."""
    out = detail.texts
    add = out.append
    kind = frame.kind
    slave = frame.slave
    if frame.broadcast:
        add(f"        Slave: {slave} (broadcast)")
    else:
        line = _SLAVE_LINES.get(slave)
        if line is None:
            line = _SLAVE_LINES[slave] = f"        Slave: {slave}"
        add(line)
    function = frame.function
    function_text = frame.function_text
    if kind is _EXCEPTION:
        # The function as -Y's `function` and --json hold it (tshark's modbus alike); the byte's high bit
        # said apart, as the exception it marks.
        name = function_text or SPEC.function_name(function)
        add(f"        Function: {function} (0x{function:02X}) {name}, exception (0x{function | 0x80:02X})")
    elif function_text is None:
        line = _FUNCTION_LINES.get(function)
        if line is None:
            name = SPEC.function_name(function)
            line = _FUNCTION_LINES[function] = f"        Function: {function} (0x{function:02X}) {name}"
        add(line)
    else:
        add(f"        Function: {function} (0x{function:02X}) {function_text}")
    if kind is _RESPONSE and (frame.start is not None or frame.quantity is not None):
        out.extend(window_lines(frame, FUNCTION_LABELS))
    if kind is _EXCEPTION:
        exception = frame.exception_code
        shown = "?" if exception is None else exception  # (none: a malformed exception, as its summary)
        # (as the plugin's vw3.exception_code, Wireshark's value string: `Illegal Data Address (2)`, `Unknown (9)`)
        name = SPEC.exception_name(None) if exception is None else _NAMED["exception_code"].get(exception, "Unknown")
        detail.styled(f"        {_TITLES['exception_code']}: {name} ({shown})", "vw3.exception")
        if frame.exception_text is not None:
            detail.styled(f"        {_TITLES['exception_meaning']}: {frame.exception_text}", "vw3.exception")
        trailing = frame.fields.get("trailing") if isinstance(frame.fields, dict) else None
        if trailing:  # (bytes after its code, as --json's fields.trailing and the plugin's vw3.trailing)
            add(f"        Trailing: {trailing.hex()}")
    elif frame.fields is not None:
        registers = frame.registers
        lines = _INT_FIELD_LINES
        labelled = function in _LABELLED  # (its lines kept by function too: `FIFO pointer address`)
        implied = implied_quantity(frame)  # (FC5's, FC6's, FC22's one address: `[Quantity: 1]` after it)
        for key, value in frame.fields.items():
            if value is None or key[0] == "_" or key in ("values", "status") and registers:
                continue
            if type(value) is int and key not in _HEX_NAMES:  # the common case, inline and kept: `Start: 8400 (0x20D0)`
                width = hex_width(frame, key)  # (a status word or a mask: all its digits, detail_window)
                kept = (function, kind, key) if width else (function, key) if labelled else key
                line = lines.get((kept, value))
                if line is None:
                    if len(lines) >= _INT_FIELD_LINES_MAX:
                        lines.clear()
                    label = "        " + field_label(key, function)
                    names = value_names().get(key) or _NAMED.get(key)
                    shown = f"{value} (0x{value:0{width}X})" if names is None else named_value(names, value)
                    line = lines[kept, value] = f"{label}: {shown}"
                add(line)
                if implied is not None and key == implied[0]:
                    add(implied[1])
                continue
            if key == "trailing" and not value:
                continue
            _field_lines(detail, 2, key, value)
    if frame.subfunction is not None:
        sub_name = frame.subfunction_text or SPEC.diagnostics.get(frame.subfunction, UNKNOWN_SUBFUNCTION)
        add(f"        Sub-function name: {sub_name}")


def _body_lines(detail: _Detail, frame: Frame) -> None:
    """Registers, bits and objects, then the check."""
    out = detail.texts
    add = out.append
    rtu = frame.mode == "rtu"
    if frame.span_label is not None:  # --address-style plc: the span as the summary shows it
        add(f"        PLC references{' (read)' if frame.function == 23 else ''}: {frame.span_label}")
    if frame.write_span_label is not None:  # (FC23's written window)
        add(f"        PLC references (write): {frame.write_span_label}")
    registers = frame.registers
    if not registers and frame.function in MASKS:  # (FC22's register, as --json lists it and the plugin shows it)
        mask = mask_register(frame)
        if mask is not None:
            registers = [Register(mask["address"], mask["value"], text=mask["text"], label=mask.get("label"))]
    if registers:
        _register_lines(detail, registers)
    bits = frame.bits
    if bits is not None:
        add(f"        Bits ({len(bits)})")
        if isinstance(bits, BitList):  # in bulk: no Bit object per coil
            if detail.joined and bits.start is not None and bits.count and bits.start + bits.count <= 0x10000:
                add(_BIT_RUNS(bits.start, bits.packed, bits.count)[:-1])
            elif bits.start is None:
                detail.run([f"            ?: {value}" for value in bits.values])
            else:
                detail.run([f"            {address}: {value}" for address, value in zip(bits.addresses, bits.values)])
        else:
            detail.run([f"            {'?' if bit.address is None else bit.address}: {bit.value}" for bit in bits])
    for obj in frame.objects or ():
        # `Object 5 ModelName: 'XY'`; one the spec does not name is `Object 128: 'ABC'` (its name says the id)
        head = f"Object {obj.id} {obj.name}" if obj.id in SPEC.device_id_objects else obj.name
        add(f"        {head}: '{obj.value}'" + (f" ({obj.text})" if obj.text else ""))
    crc = frame.crc
    if frame.notes and check_untyped(frame):  # --hex typed without its check: nothing was received
        detail.styled(f"        {'LRC' if frame.mode == 'ascii' else 'CRC'}: none typed "
                      f"[{crc_text(frame)}: 0x{frame.crc_expected:0{2 if frame.mode == 'ascii' else 4}X}, not checked]",
                      "vw3.note")
    elif rtu and crc == frame.crc_expected:
        line = _CRC_OK_LINES.get(crc)
        if line is None:
            line = _CRC_OK_LINES[crc] = f"        CRC: 0x{crc:04X} [CRC ok]"  # 16-bit keys: bounded
        detail.styles[len(out)] = "vw3.crc.ok"
        add(line)
    else:
        style = "vw3.crc.ok" if frame.crc_ok else "vw3.crc.bad"
        # (an ASCII frame's LRC is one byte: shown as one, as the plugin's tree and Wireshark's do)
        check, width = ("LRC", 2) if frame.mode == "ascii" else ("CRC", 4)
        detail.styled(f"        {check}: 0x{frame.crc:0{width}X} [{crc_text(frame)}]", style)


def _build(item: Item, base: float | None, joined: bool, digits: int = MICRO_DIGITS) -> _Detail:
    """The detail of one item; the root has no indentation; `digits`: its Arrival time's decimals."""
    detail = _Detail(joined)
    out = detail.texts
    add = out.append
    if isinstance(item, Noise):
        length = count_text(item.length, "byte")
        detail.styled(f"Item {item.number}: noise, {length} at offset {item.offset}", "vw3.noise")
        if item.time is not None:  # (a packet of its own, timed as tshark -V times every packet)
            add(arrival_line(item.time, base, digits))
        add(f"    {noise_info(item)}")
        add(f"    Reason: {item.reason}")
        return detail
    frame: Frame = item
    kind = frame.kind
    rtu = frame.mode == "rtu"
    mode = "RTU" if rtu else frame.mode.upper()
    add(f"Frame {frame.number}: {len(frame.raw)} bytes at offset {frame.offset}, {_KIND_TEXT[kind]} ({mode})")
    if frame.time is not None:
        add(arrival_line(frame.time, base, digits))
    add(_MODBUS_RTU if rtu else f"    Modbus {mode}")
    if (
        joined and kind is not _EXCEPTION and not frame.registers and frame.bits is None and frame.objects is None
    ):
        # Slave to CRC depend on the bytes and the profile's words only: a polled request repeats them.
        key = (frame.raw, kind, frame.mode, frame.function_text, frame.subfunction_text,
               bool(frame.notes) and check_untyped(frame), frame.span_label,  # the CRC line: typed?
               frame.start, frame.quantity)  # (an answer's window: its request's, detail_window)
        add(_kept_text(_MIDDLES, key, _middle, frame))
    else:
        _middle(detail, frame)
    request = frame.request
    if request is not None:
        add(f"    Request in frame: {request.number}")
        if frame.time is not None and request.time is not None:
            response_time = frame.response_time
            add(f"    Response time: {response_time * 1000:.3f} ms")
    response = frame.response
    if response is not None:
        add(f"    Response in frame: {response.number}")
    if frame.unanswered:
        detail.styled("    No response", "vw3.warning")
    if frame.profile_choice is not None:
        add(_profile_line(frame.profile_choice))
    elif frame.provisional:
        add(PROVISIONAL_LINE)
    for note in frame.notes:
        detail.styled(f"    Note: {note}", "vw3.key" if getattr(note, "key", False) else "vw3.note")
    for warning in frame.warnings:
        detail.styled(f"    Warning: {warning}", "vw3.warning")
    return detail


PROVISIONAL_LINE = (
    "    Profile: provisional (profile auto has not chosen this slave's device yet: values named with spec "
    "semantics only, which its device may name otherwise)"
)


def _profile_line(choice: Any) -> str:
    """Profile `auto`: which profile named this frame's registers, and why (selection.ProfileChoice)."""
    return f"    Profile: {choice.profile} ({choice.reason})"


def _depth(text: str) -> int:
    return (len(text) - len(text.lstrip(" "))) // 4


def detail_lines(item: Item, base: float | None = None, digits: int = MICRO_DIGITS) -> list[Line]:
    """The detail of one item as (depth, text, style) lines, the root at depth 0; texts are indented."""
    detail = _build(item, base, False, digits)
    styles = detail.styles
    return [(_depth(text), text, styles.get(index)) for index, text in enumerate(detail.texts)]


def detail_tree(item: Item, base: float | None = None, digits: int = MICRO_DIGITS) -> Node:
    """The detail as a tree of Nodes (what a terminal draws)."""
    lines = detail_lines(item, base, digits)
    _depth0, label, style = lines[0]
    root = Node(label, style=style)
    path = [root]
    for depth, text, style in lines[1:]:
        node = path[depth - 1].add(text[4 * depth :], style)
        del path[depth:]
        path.append(node)
    return root


def render_plain(node: Node, indent: int = 0) -> str:
    lines: list[str] = []
    _plain_lines(node, indent, lines)
    return "\n".join(lines)


def _plain_lines(node: Node, indent: int, lines: list[str]) -> None:
    lines.append("    " * indent + node.label)
    for child in node.children:
        _plain_lines(child, indent + 1, lines)


def render_rich(node: Node) -> Tree:
    from rich.tree import Tree  # only a terminal needs rich

    tree = Tree(_data(node.label), style=node.style or "", guide_style="dim")
    _rich_children(tree, node)
    return tree


def _data(label: str) -> Text:
    """A label as rich Text: never markup ([/x] from the bus, [link=...]) nor emoji codes."""
    from rich.text import Text

    return Text(printable(label))


def _rich_children(tree: Tree, node: Node) -> None:
    for child in node.children:
        branch = tree.add(_data(child.label), style=child.style or "")
        _rich_children(branch, child)
