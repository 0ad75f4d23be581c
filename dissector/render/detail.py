"""The -V detail tree: every field of a frame, as tshark's packet details pane shows it.

`detail_tree` builds a neutral tree of `Node`s; `render_plain` and `render_rich` draw it, so the layout
is decided once and a terminal only adds colour.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from datetime import datetime, timezone
from typing import TYPE_CHECKING, Any

from dissector.model import Frame, Item, Kind, Noise, Register
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


def _register_node(parent: Node, register: Register) -> None:
    address = register.label or ("?" if register.address is None else str(register.address))
    if register.value is None:  # a status an exception tells, no value on the wire
        head = f"Register {address}: no value"
    else:
        head = f"Register {address}: {register.value} (0x{register.value:04X})"
    if register.code:
        head += f"  {register.code}"
        if register.name:
            head += f" [{register.name}]"
    style = "vw3.protected" if register.status in ("protected", "non-existent", "ambiguous") else None
    node = parent.add(head, style)
    if register.text is not None:
        node.add(f"Value: {register.text}")
    if register.words == 2:
        node.add("32-bit value: this register and the next")
    if register.status is not None:
        node.add(f"Status: {register.status}", style)
    if register.unit:
        node.add(f"Unit: {register.unit}")
    if register.source:
        node.add(f"Source: {register.source}")


def _fields_node(parent: Node, name: str, value: Any) -> None:
    label = name.replace("_", " ").capitalize()
    if isinstance(value, dict):
        node = parent.add(label)
        for key, inner in value.items():
            if key.startswith("_") or inner is None or (key == "trailing" and not inner):
                continue
            _fields_node(node, key, inner)
    elif isinstance(value, list):
        node = parent.add(f"{label} ({len(value)})")
        for index, inner in enumerate(value):
            _fields_node(node, f"[{index}]", inner)
    elif isinstance(value, bytes):
        parent.add(f"{label}: {value.hex(' ') or '(empty)'}")
    elif isinstance(value, int) and not isinstance(value, bool):
        parent.add(f"{label}: {value} (0x{value:X})")
    else:
        parent.add(f"{label}: {value}")


def detail_tree(item: Item, base: float | None = None) -> Node:
    if isinstance(item, Noise):
        root = Node(f"Item {item.number}: noise, {item.length} bytes at offset {item.offset}", style="vw3.noise")
        root.add(noise_info(item))
        root.add(f"Reason: {item.reason}")
        return root
    frame: Frame = item
    root = Node(
        f"Frame {frame.number}: {frame.length} bytes at offset {frame.offset}, {frame.kind.value}"
        f" ({frame.mode.upper()})"
    )
    if frame.time is not None:
        root.add(f"Arrival time: {_utc(frame.time)} ({frame.time - (base or 0.0):.6f} s since the first item)")
    modbus = root.add(f"Modbus {frame.mode.upper()}")
    modbus.add(f"Slave: {frame.slave}" + (" (broadcast)" if frame.broadcast else ""))
    code = frame.function | (0x80 if frame.kind is Kind.EXCEPTION else 0)
    function_name = frame.function_text or SPEC.function_name(frame.function)
    modbus.add(f"Function: {code} (0x{code:02X}) {function_name}")
    if frame.kind is Kind.EXCEPTION:
        exception = frame.exception_code
        modbus.add(f"Exception: {exception} {SPEC.exception_name(exception)}", "vw3.exception")
        if frame.exception_text is not None:
            modbus.add(f"Meaning on this device: {frame.exception_text}", "vw3.exception")
    elif frame.fields is not None:
        for key, value in frame.fields.items():
            if key.startswith("_") or value is None or key in ("values", "status") and frame.registers:
                continue
            if key == "trailing" and not value:
                continue
            _fields_node(modbus, key, value)
    if frame.subfunction is not None:
        sub_name = frame.subfunction_text or SPEC.diagnostics.get(frame.subfunction, "unknown")
        modbus.add(f"Sub-function name: {sub_name}")
    for register in frame.registers or ():
        _register_node(modbus, register)
    if frame.bits is not None:
        bits = modbus.add(f"Bits ({len(frame.bits)})")
        for bit in frame.bits:
            bits.add(f"{'?' if bit.address is None else bit.address}: {bit.value}")
    for obj in frame.objects or ():
        modbus.add(f"Object {obj.id} {obj.name}: {obj.value!r}" + (f" ({obj.text})" if obj.text else ""))
    style = "vw3.crc.ok" if frame.crc_ok else "vw3.crc.bad"
    modbus.add(f"{'LRC' if frame.mode == 'ascii' else 'CRC'}: 0x{frame.crc:04X} [{crc_text(frame)}]", style)
    if frame.request is not None:
        root.add(f"Request in frame: {frame.request.number}")
        if frame.response_time is not None:
            root.add(f"Response time: {frame.response_time * 1000:.3f} ms")
    if frame.response is not None:
        root.add(f"Response in frame: {frame.response.number}")
    if frame.unanswered:
        root.add("No response", "vw3.warning")
    for note in frame.notes:
        root.add(f"Note: {note}", "vw3.key" if getattr(note, "key", False) else "vw3.note")
    for warning in frame.warnings:
        root.add(f"Warning: {warning}", "vw3.warning")
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
