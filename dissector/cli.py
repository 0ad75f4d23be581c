"""`vw3-decode`: decode Modbus serial captures the way tshark shows packets.

The terminal is injected (`Environment`) so tests can run the whole CLI on strings.
"""
from __future__ import annotations

import argparse
import io
import json
import os
import sys
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from enum import IntEnum
from typing import BinaryIO, TextIO

from rich.console import Console

from .model import Chunk, Frame, Item
from .pipeline import Annotator, Dissector
from .render.detail import detail_tree, render_plain, render_rich
from .render.hexdump import hexdump
from .render.jsonout import item_to_dict
from .render.summary import summary_line, summary_text
from .render.theme import THEME

PROG = "vw3-decode"


class ExitStatus(IntEnum):
    OK = 0
    ERROR = 1  # a failure while running (a device vanished, an output could not be written)
    BAD_INPUT = 2  # usage errors, unreadable inputs, bad maps or filters


class UsageError(Exception):
    """A bad command line or input: one line for stderr, exit status 2."""


@dataclass
class Environment:
    stdin: BinaryIO
    stdout: TextIO
    stderr: TextIO
    stdout_isatty: bool
    stderr_isatty: bool

    @classmethod
    def from_process(cls) -> Environment:
        return cls(
            stdin=sys.stdin.buffer,
            stdout=sys.stdout,
            stderr=sys.stderr,
            stdout_isatty=sys.stdout.isatty(),
            stderr_isatty=sys.stderr.isatty(),
        )


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog=PROG,
        description="Decode Modbus RTU/ASCII serial captures (Altivar 71 VW3 A3 303, SEL-749M) "
        "frame by frame, the way tshark shows packets.",
    )
    parser.add_argument("files", nargs="*", metavar="FILE", help="capture files; - reads stdin")
    parser.add_argument(
        "--hex",
        action="append",
        default=[],
        metavar="BYTES",
        help='decode bytes typed from a manual, e.g. --hex "0C 03 20 D0 00 03 0E EF"',
    )
    output = parser.add_argument_group("output")
    output.add_argument("-V", dest="detail", action="store_true", help="detail tree of every field")
    output.add_argument("-x", dest="hexdump", action="store_true", help="hex dump of every item")
    output.add_argument("--json", action="store_true", help="NDJSON, one object per item")
    output.add_argument(
        "--color",
        choices=["auto", "always", "never"],
        default="auto",
        help="colour and layout with rich (auto: only on a terminal)",
    )
    decoding = parser.add_argument_group("decoding")
    decoding.add_argument(
        "--timeout",
        type=float,
        default=1.0,
        metavar="SECONDS",
        help="flag responses later than this (needs timestamps; default 1 s)",
    )
    return parser


class UnreadableInput(UsageError):
    pass


def _hex_chunk(text: str) -> Chunk:
    cleaned = "".join(text.replace(",", " ").replace("0x", " ").split())
    try:
        return Chunk(bytes.fromhex(cleaned))
    except ValueError:
        raise UsageError(f"--hex: not a string of hex byte pairs: {text!r}") from None


def _read_file_chunks(path: str, env: Environment, chunk_size: int = 1 << 16) -> Iterator[Chunk]:
    if path == "-":
        stream = env.stdin
        close = False
    else:
        if os.path.isdir(path):
            raise UnreadableInput(f"{path}: is a directory")
        try:
            stream = open(path, "rb")
        except OSError as error:
            raise UnreadableInput(f"{path}: {error.strerror or error}") from None
        close = True
    try:
        while True:
            try:
                data = stream.read(chunk_size)
            except OSError as error:
                raise UnreadableInput(f"{path}: {error.strerror or error}") from None
            if not data:
                return
            yield Chunk(data)
    finally:
        if close:
            stream.close()


class Output:
    """Writes items as the options ask: summary, detail, hex, or NDJSON; plain or rich."""

    def __init__(self, args: argparse.Namespace, env: Environment) -> None:
        self.args = args
        self.env = env
        use_rich = args.color == "always" or (args.color == "auto" and env.stdout_isatty)
        self.console: Console | None = None
        if use_rich and not args.json:
            self.console = Console(
                file=env.stdout,
                theme=THEME,
                force_terminal=True if args.color == "always" else None,
                highlight=False,
                soft_wrap=False,
            )
        self.base: float | None = None
        self._buffer: list[str] = []

    def write(self, items: Iterable[Item]) -> None:
        args = self.args
        out = self._buffer
        for item in items:
            if self.base is None and item.time is not None:
                self.base = item.time
            if args.json:
                out.append(json.dumps(item_to_dict(item)))
                continue
            if self.console is not None:
                self._write_rich(item)
                continue
            if args.detail:
                out.append(render_plain(detail_tree(item, self.base)))
            else:
                out.append(summary_line(item, self.base))
            if args.hexdump:
                out.append(hexdump(item.raw))
            if args.detail or args.hexdump:
                out.append("")
        if len(out) > 512:
            self.flush()

    def _write_rich(self, item: Item) -> None:
        console = self.console
        assert console is not None
        if self.args.detail:
            console.print(render_rich(detail_tree(item, self.base)))
        else:
            console.print(summary_text(item, self.base))
        if self.args.hexdump:
            console.print(hexdump(item.raw), style="vw3.hex", highlight=False)
        if self.args.detail or self.args.hexdump:
            console.print()

    def flush(self) -> None:
        if self._buffer:
            self.env.stdout.write("\n".join(self._buffer) + "\n")
            self._buffer.clear()
        self.env.stdout.flush()


def decode_stream(
    chunks: Iterable[Chunk],
    output: Output,
    annotate: Annotator | None,
    timeout: float | None,
) -> None:
    dissector = Dissector(annotate=annotate, timeout=timeout)
    for chunk in chunks:
        output.write(dissector.feed(chunk))
    output.write(dissector.finish())


def run(argv: list[str] | None, env: Environment) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exit_:
        return int(exit_.code or 0) and ExitStatus.BAD_INPUT
    if not args.files and not args.hex:
        parser.print_usage(env.stderr)
        env.stderr.write(f"{PROG}: give a capture FILE, - for stdin, or --hex BYTES\n")
        return ExitStatus.BAD_INPUT
    output = Output(args, env)
    annotate: Annotator | None = None
    try:
        if args.hex:
            # All --hex arguments form one stream, so a request and its response pair up.
            chunks = [_hex_chunk(text) for text in args.hex]
            decode_stream(chunks, output, annotate, args.timeout)
        for path in args.files:
            decode_stream(_read_file_chunks(path, env), output, annotate, args.timeout)
        output.flush()
    except UsageError as error:
        output.flush()
        env.stderr.write(f"{PROG}: {error}\n")
        return ExitStatus.BAD_INPUT
    return ExitStatus.OK


def main(argv: list[str] | None = None) -> int:
    env = Environment.from_process()
    try:
        status = run(argv, env)
    except KeyboardInterrupt:
        env.stderr.write(f"{PROG}: interrupted\n")
        return 130
    except BrokenPipeError:
        # The reader (head, less) went away: stop quietly, as tshark does.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return ExitStatus.OK
    return int(status)


if __name__ == "__main__":
    sys.exit(main())
