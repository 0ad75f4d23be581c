"""The -V detail tree: every field of a frame, as tshark's packet details pane shows it.

`detail_tree` builds a neutral tree of `Node`s; `render_plain` and `render_rich` draw it, so the layout
is decided once and a terminal only adds colour.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from datetime import datetime, timezone
from operator import itemgetter
from typing import TYPE_CHECKING, Any

from dissector.model import BitList, Frame, Item, Kind, Noise, Register
from dissector.protocol.spec import SPEC
from dissector.render.summary import crc_text, noise_info

if TYPE_CHECKING:
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


def _utc(seconds: float) -> str:
    try:
        moment = datetime.fromtimestamp(seconds, tz=timezone.utc)
    except (OverflowError, OSError, ValueError):
        return f"{seconds:.6f}"
    return moment.strftime("%Y-%m-%d %H:%M:%S.%f UTC")


# A detail is laid out once, as a flat list of (depth, text, style) lines whose text carries its
# indentation (four spaces a level): plain output only joins the texts, never building a tree (a Node
# per line cost -V half its time); a terminal builds rich's Tree from the same lines.
Line = tuple[int, str, "str | None"]
_PROTECTED = frozenset(("protected", "non-existent", "ambiguous"))
_INDENT = ["    " * depth for depth in range(32)]
_KIND_TEXT = {kind: kind.value for kind in Kind}
_EXCEPTION = Kind.EXCEPTION
_MODBUS_RTU: Line = (1, "    Modbus RTU", None)
_FUNCTION_LINES: dict[int, Line] = {}  # spec names only: a profile's names vary per slave
_FIELD_LABELS: dict[str, str] = {}

# A register's lines depend on its fields only; polled blocks repeat them, so they are kept by
# content (bounded: cleared when full, so memory stays flat on values that never repeat).
_REGISTER_BLOCKS: dict[tuple[Any, ...], tuple[Line, ...]] = {}
_REGISTER_BLOCKS_MAX = 1 << 16


def _register_block(register: Register) -> tuple[Line, ...]:
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
    lines: list[Line] = [(2, head, style)]
    if register.text is not None:
        lines.append((3, f"            Value: {register.text}", None))
    if register.words == 2:
        lines.append((3, "            32-bit value: this register and the next", None))
    if status is not None:
        lines.append((3, f"            Status: {status}", style))
    if register.unit:
        lines.append((3, f"            Unit: {register.unit}", None))
    if register.source:
        lines.append((3, f"            Source: {register.source}", None))
    return tuple(lines)


def _register_lines(out: list[Line], registers: list[Register]) -> None:
    blocks = _REGISTER_BLOCKS
    append = out.append
    for register in registers:
        if (
            register.code is None and register.text is None and register.status is None
            and not register.unit and not register.source
        ):
            # Unannotated (a relay's block, a meter's readings): one line, formatted directly.
            address = register.label
            if address is None:
                address = "?" if register.address is None else register.address
            value = register.value
            append((2, f"        Register {address}: {value} (0x{value:04X})", None))
            continue
        key = (register.address, register.value, register.code, register.name, register.text,
               register.status, register.unit, register.source, register.label, register.words)
        block = blocks.get(key)
        if block is None:
            if len(blocks) >= _REGISTER_BLOCKS_MAX:
                blocks.clear()
            block = blocks[key] = _register_block(register)
        out.extend(block)


def _field_lines(out: list[Line], depth: int, name: str, value: Any) -> None:
    label = _INDENT[depth] + name.replace("_", " ").capitalize()
    if isinstance(value, dict):
        out.append((depth, label, None))
        for key, inner in value.items():
            if key.startswith("_") or inner is None or (key == "trailing" and not inner):
                continue
            _field_lines(out, depth + 1, key, inner)
    elif isinstance(value, list):
        out.append((depth, f"{label} ({len(value)})", None))
        for index, inner in enumerate(value):
            _field_lines(out, depth + 1, f"[{index}]", inner)
    elif isinstance(value, bytes):
        out.append((depth, f"{label}: {value.hex(' ') or '(empty)'}", None))
    elif isinstance(value, int) and not isinstance(value, bool):
        out.append((depth, f"{label}: {value} (0x{value:X})", None))
    else:
        out.append((depth, f"{label}: {value}", None))


def detail_lines(item: Item, base: float | None = None) -> list[Line]:
    """The detail of one item as (depth, text, style) lines, the root at depth 0; texts are indented."""
    out: list[Line] = []
    add = out.append
    if isinstance(item, Noise):
        add((0, f"Item {item.number}: noise, {item.length} bytes at offset {item.offset}", "vw3.noise"))
        add((1, f"    {noise_info(item)}", None))
        add((1, f"    Reason: {item.reason}", None))
        return out
    frame: Frame = item
    kind = frame.kind
    rtu = frame.mode == "rtu"
    mode = "RTU" if rtu else frame.mode.upper()
    add((0, f"Frame {frame.number}: {len(frame.raw)} bytes at offset {frame.offset}, {_KIND_TEXT[kind]} ({mode})", None))
    if frame.time is not None:
        add((1, f"    Arrival time: {_utc(frame.time)} ({frame.time - (base or 0.0):.6f} s since the first item)", None))
    add(_MODBUS_RTU if rtu else (1, f"    Modbus {mode}", None))
    add((2, f"        Slave: {frame.slave} (broadcast)" if frame.broadcast else f"        Slave: {frame.slave}", None))
    function = frame.function
    function_text = frame.function_text
    if kind is _EXCEPTION:
        code = function | 0x80
        add((2, f"        Function: {code} (0x{code:02X}) {function_text or SPEC.function_name(function)}", None))
    elif function_text is None:
        line = _FUNCTION_LINES.get(function)
        if line is None:
            name = SPEC.function_name(function)
            line = _FUNCTION_LINES[function] = (2, f"        Function: {function} (0x{function:02X}) {name}", None)
        add(line)
    else:
        add((2, f"        Function: {function} (0x{function:02X}) {function_text}", None))
    if kind is _EXCEPTION:
        exception = frame.exception_code
        add((2, f"        Exception: {exception} {SPEC.exception_name(exception)}", "vw3.exception"))
        if frame.exception_text is not None:
            add((2, f"        Meaning on this device: {frame.exception_text}", "vw3.exception"))
    elif frame.fields is not None:
        registers = frame.registers
        for key, value in frame.fields.items():
            if value is None or key[0] == "_" or key in ("values", "status") and registers:
                continue
            if type(value) is int:  # the common case, inline: `Start: 8400 (0x20D0)`
                label = _FIELD_LABELS.get(key)
                if label is None:
                    label = _FIELD_LABELS[key] = "        " + key.replace("_", " ").capitalize()
                add((2, f"{label}: {value} (0x{value:X})", None))
                continue
            if key == "trailing" and not value:
                continue
            _field_lines(out, 2, key, value)
    if frame.subfunction is not None:
        sub_name = frame.subfunction_text or SPEC.diagnostics.get(frame.subfunction, "unknown")
        add((2, f"        Sub-function name: {sub_name}", None))
    if frame.registers:
        _register_lines(out, frame.registers)
    bits = frame.bits
    if bits is not None:
        add((2, f"        Bits ({len(bits)})", None))
        if isinstance(bits, BitList):  # in bulk: no Bit object per coil
            out.extend([(3, f"            {'?' if address is None else address}: {value}", None)
                        for address, value in zip(bits.addresses, bits.values)])
        else:
            out.extend([(3, f"            {'?' if bit.address is None else bit.address}: {bit.value}", None)
                        for bit in bits])
    for obj in frame.objects or ():
        add((2, f"        Object {obj.id} {obj.name}: {obj.value!r}" + (f" ({obj.text})" if obj.text else ""), None))
    if rtu and frame.crc == frame.crc_expected:
        add((2, f"        CRC: 0x{frame.crc:04X} [CRC ok]", "vw3.crc.ok"))
    else:
        style = "vw3.crc.ok" if frame.crc_ok else "vw3.crc.bad"
        add((2, f"        {'LRC' if frame.mode == 'ascii' else 'CRC'}: 0x{frame.crc:04X} [{crc_text(frame)}]", style))
    request = frame.request
    if request is not None:
        add((1, f"    Request in frame: {request.number}", None))
        if frame.time is not None and request.time is not None:
            response_time = frame.response_time
            add((1, f"    Response time: {response_time * 1000:.3f} ms", None))
    response = frame.response
    if response is not None:
        add((1, f"    Response in frame: {response.number}", None))
    if frame.unanswered:
        add((1, "    No response", "vw3.warning"))
    for note in frame.notes:
        add((1, f"    Note: {note}", "vw3.key" if getattr(note, "key", False) else "vw3.note"))
    for warning in frame.warnings:
        add((1, f"    Warning: {warning}", "vw3.warning"))
    return out


_TEXT = itemgetter(1)


def detail_text(item: Item, base: float | None = None) -> str:
    """The plain -V text of one item (render_plain(detail_tree(...)), without the tree)."""
    return "\n".join(map(_TEXT, detail_lines(item, base)))


def detail_tree(item: Item, base: float | None = None) -> Node:
    """The detail as a tree of Nodes (what a terminal draws)."""
    lines = detail_lines(item, base)
    _depth, label, style = lines[0]
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

    tree = Tree(node.label, style=node.style or "", guide_style="dim")
    _rich_children(tree, node)
    return tree


def _rich_children(tree: Tree, node: Node) -> None:
    for child in node.children:
        branch = tree.add(child.label, style=child.style or "")
        _rich_children(branch, child)
