"""Register naming: the address a screen shows (protocol or PLC style) and a register named and read
from its map row. One job: what a register is called and what its value means."""
from __future__ import annotations

from collections.abc import Sequence

from dissector.devices.maps import MEMO_LIMIT, RegisterDef, interpret, interpret_wide
from dissector.model import Register
from dissector.protocol.rules import text


def plc_label(base: int, address: int) -> str:
    """`40001 + address` up to 49999, then 6-digit references (`400001 + address`); coils as 00001."""
    digits = max(5, len(str(base)))  # coil references (base 1) are written with their zeros: 00001
    power = 10 ** (digits - 1)
    top = (base // power + 1) * power - 1
    number = base + address
    if number > top:
        number = base * 10 - 9 + address
        digits += 1
    return f"{number:0{digits}d}"


def window_label(labels: dict[int, str], base: int, start: int, quantity: int | None) -> str:
    """`40501..40504`, one label for a quantity of 0 or 1; past 65535 as asked, as describe.span_text and
    the warning `span` show it."""
    first = labels.get(start)
    if first is None:
        first = labels[start] = plc_label(base, start)
    if not quantity or quantity == 1:
        return first
    end = start + quantity - 1
    last = labels.get(end)
    if last is None:
        last = labels[end] = plc_label(base, end)
    return f"{first}..{last}"


def address_name(row: RegisterDef | None, address: int, label: str | None = None) -> str:
    """`CHCF (8401)` for a mapped register, `8400` otherwise (`label`: the address as the screen shows it)."""
    shown = label if label is not None else str(address)
    return f"{row.code} ({shown})" if row is not None else shown


def name_register(register: Register, row: RegisterDef, used: RegisterDef) -> None:
    """Name and read a register from its map row (`used`: the row, or its plain form under bits_depend)."""
    register.code = row.code
    register.name = row.name
    register.unit = row.unit
    register.source = row.source
    value = register.value
    memo = used.memo
    reading = memo.get(value)
    if reading is None:
        reading = interpret(used, value)
        if len(memo) < MEMO_LIMIT:
            memo[value] = reading
    register.scaled, register.text = reading


def name_wide(registers: Sequence[Register], index: int, row: RegisterDef) -> None:
    """A 32-bit row over registers[index] and the next: one value, read on the first register."""
    first = registers[index]
    first.code = row.code
    first.name = row.name
    first.unit = row.unit
    first.source = row.source
    second = registers[index + 1] if index + 1 < len(registers) else None
    if second is None or second.address != (first.address + 1) & 0xFFFF:  # type: ignore[operator]
        first.text = text("first_word", kind=row.kind)
        return
    first.scaled, first.text = interpret_wide(row, first.value, second.value)
    first.words = 2
    second.code = row.code
    second.name = row.name
    second.unit = row.unit
    second.source = row.source
    second.text = text("second_word", code=row.code)
    second.words = 0


def wide_before(rows: dict[int, RegisterDef], address: int) -> RegisterDef | None:
    """The 32-bit row whose second register `address` is (the row at the address before), or None."""
    before = rows.get((address - 1) & 0xFFFF)
    return before if before is not None and before.words == 2 else None


def name_second_alone(rows: dict[int, RegisterDef], register: Register) -> None:
    """A frame's first register when it is the second of a 32-bit row (the row before) whose first is not in
    the frame: named, its value unread (it needs the first word), as name_wide names a first word alone."""
    row = wide_before(rows, register.address)  # type: ignore[arg-type]
    if row is None:
        return
    register.code = row.code
    register.name = row.name
    register.unit = row.unit
    register.source = row.source
    register.text = text("second_word_alone", kind=row.kind)


def name_from_map(registers: Sequence[Register], index: int, rows: dict[int, RegisterDef]) -> None:
    """Name registers[index] (consecutive registers) from the map: its row, 32-bit or not, or the row whose
    second word it is when that row's first is not in the frame (Annotator.reread; _annotate inlines it)."""
    register = registers[index]
    row = rows.get(register.address)  # type: ignore[arg-type]
    if row is None:
        if index == 0:  # (a second word without its first can only come first)
            name_second_alone(rows, register)
    elif register.words == 0:
        return  # the second word of the value before: named with it
    elif row.words == 2:
        name_wide(registers, index, row)
    else:
        name_register(register, row, row)
