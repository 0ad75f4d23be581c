"""The item sink of vw3-decode: summary, detail, hex or NDJSON; rich on a terminal, plain when piped.

Plain output is built as strings and written in batches, which is what makes a piped decode fast.
"""
from __future__ import annotations

import json
import shutil
from dataclasses import dataclass
from collections.abc import Callable
from typing import TYPE_CHECKING, TextIO

from dissector.model import Frame, Item
from dissector.protocol.printable import printable
from dissector.render.summary import summary_line, summary_text, typed_bytes
from dissector.render.timefmt import Clock, detail_digits

# The writers of -V, -x, --json and -T are imported by the output that uses them (a one-frame summary
# starts faster without them).

if TYPE_CHECKING:
    from dissector.render.fields import FieldsOptions
    from dissector.render.registers import RegistersWriter
    from rich.console import Console

BATCH = 512
# Text is written in pieces of about 64 KiB: one join and one write each, small enough that the
# joined text is not a fresh memory mapping each time (malloc maps blocks over 128 KiB, page faults
# and all): -V on the plant mix wrote ~2 MB per write before, 30-90 ms more for its 39 MB.
FLUSH_CHARS = 1 << 16
# rich's width where it must not wrap (a line longer than this is not a frame's)
UNWRAPPED = 1 << 20


@dataclass(frozen=True, slots=True)
class OutputOptions:
    detail: bool = False
    hexdump: bool = False
    json: bool = False
    color: str = "auto"  # auto | always | never
    time_format: str = "r"  # tshark -t: r a ad adoy d dd e u ud udoy (render.timefmt)
    fields: FieldsOptions | None = None  # -T fields
    registers: RegistersWriter | None = None  # -T registers

    @property
    def records(self) -> bool:
        """Items are written from their NDJSON dicts (--json, -T fields, -T registers)."""
        return self.json or self.fields is not None or self.registers is not None


def provisional_notice(number: int, fields: FieldsOptions | None) -> str:
    """What -T fields and -T registers say (on standard error, once) of a provisional row their
    columns cannot show (summary, -V and --json mark each item themselves)."""
    marked = "-e provisional marks them" if fields is not None else "--json or -T fields -e provisional mark them"
    return (
        f"warning: rows from frame {number} on of slaves whose device profile auto has not chosen yet are "
        f"provisional (read once, named with spec semantics only); {marked}"
    )


def quiet_console(stream: TextIO, **options: object) -> Console:
    """rich's Console on `stream`, except that a reader gone away (`| head -1`) is a BrokenPipeError
    for main() to end quietly with exit 0, as a plain run does, not rich's own exit 1
    (Console.on_broken_pipe)."""
    from rich.console import Console as RichConsole

    class QuietConsole(RichConsole):
        def on_broken_pipe(self) -> None:
            self.quiet = True
            raise BrokenPipeError

    return QuietConsole(file=stream, **options)  # type: ignore[arg-type]


class Output:
    def __init__(
        self, options: OutputOptions, stream: TextIO, isatty: bool, notice: Callable[[str], None] | None = None
    ) -> None:
        """`notice`: where -T fields and -T registers say once that rows are provisional."""
        self.options = options
        self.stream = stream
        self._notice = notice
        use_rich = options.color == "always" or (options.color == "auto" and isatty)
        self.console: Console | None = None
        if use_rich and not options.records:
            from dissector.render.theme import THEME  # only a terminal needs rich

            self.console = quiet_console(
                stream,
                theme=THEME,
                force_terminal=True if options.color == "always" else None,
                highlight=False,
                soft_wrap=False,
                # No line break of rich's own: a frame's line and a -V line are one line each, as tshark
                # prints them (the terminal wraps them; `| less -R` and grep see whole lines).
                width=UNWRAPPED,
            )
        self._buffer: list[str] = []
        self._held: str | None = None  # a title waiting for its input's first item shown (new_input)
        self.fields = None
        if options.fields is not None:
            from dissector.render.fields import FieldsWriter

            self.fields = FieldsWriter(options.fields)
        time_keys = self.fields.time_keys if self.fields is not None else ()
        self.clock = Clock(options.time_format, deltas="time_delta" in time_keys)
        self._prefix = ""  # written before the first line (-E bom=y)
        self.registers = options.registers
        preamble = self.fields or self.registers
        if preamble is not None:
            header, self._prefix = preamble.preamble()
            if header is not None:
                self._buffer.append(header)

    def rule(self, title: object) -> None:
        """A title rule across the terminal (rich only)."""
        from rich.rule import Rule

        self.print_fitted(Rule(title))  # type: ignore[arg-type]

    def print_fitted(self, renderable: object) -> None:
        """A rule or table laid out for the terminal's width (80 columns when not one, as rich's
        default), not the unwrapped console's (rich only)."""
        assert self.console is not None
        self.console.print(renderable, width=shutil.get_terminal_size().columns)

    def new_input(self, title: str | None = None, held: bool = False) -> None:
        """Times restart at each input; several inputs are announced as tail(1) does. `held` (-Y): the
        title waits for the input's first item shown, as grep -H names only the files that match: a
        title over nothing would read as a match (head's title over an empty file is kept without -Y)."""
        self.clock.reset()
        self._held = None
        if title is None:
            return
        title = printable(title)  # a file name is data: `mk[/x].bin`, an ESC in a name
        if held:
            self._held = title
            return
        self._announce(title)

    def _announce(self, title: str) -> None:
        self._held = None
        if self.console is not None:
            from rich.text import Text

            self.rule(Text(title))
        elif not self.options.records:
            self._buffer.append(f"==> {title} <==")

    def write(
        self,
        items: list[Item],
        extra: dict[str, object] | None = None,
        records: list[dict] | None = None,
        comments: dict[int, list[str]] | None = None,
    ) -> None:
        """Show items; `records` are their NDJSON dicts when the caller has them already; `comments`: the
        packet comments of the items that have some, by id(item) (sources/trail.py): -V shows them
        above the frame as tshark -V does ("Packet comments"), --json as the list `comments`, -T fields
        as the key `comment` (tshark's frame.comment).

        The clock must have observed them (and every item the filter dropped) before.
        """
        if self._held is not None and items:
            self._announce(self._held)
        options = self.options
        out = self._buffer
        clock = self.clock
        if comments and (options.detail or options.json or self.fields is not None):
            self._write_commented(items, extra, records, comments)
            return
        if options.detail and not (options.hexdump or options.records) and self.console is None:
            self._write_details(items)
            return
        if options.records:
            from dissector.render.jsonout import exact_time, item_to_dict, item_to_json
        if options.detail:
            from dissector.render.detail_plain import detail_text
        if options.hexdump:
            from dissector.render.hexdump import hexdump
        size = 0  # characters appended since the last flush (by this call)
        for index, item in enumerate(items):
            if options.records:
                if self._notice is not None and getattr(item, "provisional", False):
                    self._tell_provisional(item.number)
                if self.registers is not None:
                    record = records[index] if records is not None else item_to_dict(item)
                    if extra:
                        record.update(extra)
                    # (the item: a write's answer tells whether it was confirmed or refused)
                    lines = self.registers.lines(record, None if item.time is None else clock.text(item), item)
                    out.extend(lines)
                    size += sum(map(len, lines))
                    continue
                if records is None and self.fields is None:
                    text = item_to_json(item, extra)  # json.dumps(item_to_dict(item)), faster
                else:
                    record = records[index] if records is not None else item_to_dict(item)
                    if extra:
                        record.update(extra)
                    if self.fields is None:
                        text = json.dumps(record)
                    else:
                        for key in self.fields.time_keys:
                            record[key] = clock.seconds(item, key)
                        text = self.fields.line(record)
                if self.fields is None and clock.units is not None:
                    text = exact_time(text, item.time, clock.units)  # (a nanosecond capture's digits)
                out.append(text)
                size += len(text)
            elif self.console is not None:
                self._write_rich(item)
                continue
            elif options.detail:
                text = detail_text(item, clock.first, detail_digits(clock.units))
                out.append(text)
                size += len(text)
                if options.hexdump:
                    text = hexdump(typed_bytes(item))
                    out.append(text)
                    size += len(text)
                out.append("")
            else:
                out.append(summary_line(item, column=clock.text(item)))
                if options.hexdump:
                    text = hexdump(typed_bytes(item))
                    out.append(text)
                    size += len(text)
                    out.append("")
            if size > FLUSH_CHARS:
                self.flush()
                size = 0
        if len(out) > BATCH:
            self.flush()

    def _write_commented(self, items: list[Item], extra: dict[str, object] | None, records: list[dict] | None,
                         comments: dict[int, list[str]]) -> None:
        """write() of items some of which have packet comments: each commented one on its own."""
        for index, item in enumerate(items):
            texts = comments.get(id(item))
            record = None if records is None else records[index : index + 1]
            if texts is None:
                self.write([item], extra, record)
            elif self.options.json or self.fields is not None:  # (-T fields -e comment: tshark's frame.comment)
                if record is not None:
                    record[0]["comments"] = texts
                self.write([item], {**(extra or {}), "comments": texts}, record)
            else:
                block = "\n".join(["Packet comments", *(f"    {printable(text)}" for text in texts)])
                if self.console is not None:
                    from rich.text import Text

                    self.console.print(Text(block))
                else:
                    self._buffer.append(block)
                self.write([item], extra, record)

    def _write_details(self, items: list[Item]) -> None:
        """write() for plain -V alone: each item's detail and an empty line."""
        from dissector.render.detail_plain import detail_text, plain_frame_text

        out = self._buffer
        append = out.append
        first, digits = self.clock.first, detail_digits(self.clock.units)
        size = 0
        for item in items:
            text = plain_frame_text(item, first, digits) if type(item) is Frame else detail_text(item, first, digits)
            append(text)
            append("")
            size += len(text)
            if size > FLUSH_CHARS:
                self.flush()
                size = 0
        if len(out) > BATCH:
            self.flush()

    def _tell_provisional(self, number: int) -> None:
        notice, self._notice = self._notice, None  # once
        fields = self.options.fields
        if self.registers is None and (fields is None or "provisional" in fields.fields):
            return  # --json has the key; -e provisional shows the column
        assert notice is not None
        notice(provisional_notice(number, fields))

    @property
    def plain_summary(self) -> bool:
        """One plain summary line per item and nothing else (what write_encoded may add to)."""
        options = self.options
        return self.console is None and not (options.detail or options.hexdump or options.records)

    def write_encoded(self, lines: bytes) -> None:
        """Summary lines made elsewhere (the compiled path), UTF-8, each ending in a newline."""
        if self._held is not None and lines:
            self._announce(self._held)
        binary = getattr(self.stream, "buffer", None)
        encoding = (getattr(self.stream, "encoding", None) or "").lower().replace("-", "")
        if binary is None or encoding != "utf8":
            self._buffer.append(lines.decode()[:-1])
            if len(self._buffer) > BATCH:
                self.flush()
            return
        self.flush()  # what the text layer holds goes first
        binary.write(lines)

    def _write_rich(self, item: Item) -> None:
        console = self.console
        assert console is not None
        from dissector.render.hexdump import hexdump

        if self.options.detail:
            from dissector.render.detail import detail_tree, render_rich


            console.print(render_rich(detail_tree(item, self.clock.first, detail_digits(self.clock.units))))
        else:
            console.print(summary_text(item, column=self.clock.text(item)))
        if self.options.hexdump:
            console.print(hexdump(typed_bytes(item)), style="vw3.hex", highlight=False, markup=False, emoji=False)
        if self.options.detail or self.options.hexdump:
            console.print()

    def flush(self) -> None:
        if self._buffer:
            self._buffer.append("")  # the last line's newline, from the join: no copy of the text to add it
            self.stream.write(self._prefix + "\n".join(self._buffer))
            self._prefix = ""
            self._buffer.clear()
        self.stream.flush()
