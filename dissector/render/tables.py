"""Tables for `--stats`: described once, written by rich on a terminal or as plain aligned text.

Rich lays out and colours tables for a terminal but costs milliseconds a row; piped output (a file,
`less`, a script) gets the plain writer: the same columns at full width, nothing cut, a few
microseconds a row.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from rich import box
from rich.console import Group, RenderableType
from rich.table import Table
from rich.text import Text

Cell = str | tuple[str, str]  # text, or (text, rich style name)


@dataclass(slots=True)
class TableSpec:
    title: str
    headers: list[str]
    right: list[bool]  # right-aligned columns
    rows: list[list[Cell]] = field(default_factory=list)
    caption: str | None = None
    # Columns rich may shorten on a narrow terminal (index -> max width); the plain writer never does.
    squeeze: dict[int, int] = field(default_factory=dict)


def _text(cell: Cell) -> str:
    return cell if isinstance(cell, str) else cell[0]


def plain(blocks: list[str | TableSpec]) -> str:
    """Blocks as plain text: a line of text, or a table (title, header, rule, rows, caption)."""
    out: list[str] = []
    for block in blocks:
        if isinstance(block, str):
            out.append(block)
            continue
        rows = [[_text(cell) for cell in row] for row in block.rows]
        widths = [len(header) for header in block.headers]
        for index, column in enumerate(zip(*rows)):  # (rows are as long as the headers)
            widths[index] = max(widths[index], *map(len, column))
        # One format a table: `{:>5}  {:<28}...`, rjust or ljust to each column's width.
        template = "  ".join(f"{{:{'>' if right else '<'}{width}}}" for right, width in zip(block.right, widths))

        def line(cells: list[str]) -> str:
            return template.format(*cells).rstrip()

        out.append(block.title)
        out.append(line(block.headers))
        out.append("-" * (sum(widths) + 2 * (len(widths) - 1)))
        out.extend(line(row) for row in rows)
        if block.caption:
            out.append(block.caption)
    return "\n".join(out) + "\n"


def rich(blocks: list[str | TableSpec]) -> RenderableType:
    parts: list[RenderableType] = []
    for block in blocks:
        if isinstance(block, str):
            parts.append(Text(block))
            continue
        table = Table(
            title=block.title, title_justify="left", box=box.SIMPLE_HEAD, show_edge=False, collapse_padding=True
        )
        for index, header in enumerate(block.headers):
            width = block.squeeze.get(index)
            table.add_column(
                header,
                justify="right" if block.right[index] else "left",
                no_wrap=True,
                max_width=width,
                overflow="ellipsis" if width else "fold",
            )
        for row in block.rows:
            table.add_row(*(Text(cell) if isinstance(cell, str) else Text(cell[0], style=cell[1]) for cell in row))
        if block.caption:
            table.caption = block.caption
            table.caption_justify = "left"
        parts.append(table)
    return Group(*parts)
