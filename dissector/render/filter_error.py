"""The error of a display filter that cannot be compiled, apart from the filter compiler: vw3-decode
catches it on every run and imports the compiler only for -Y."""
from __future__ import annotations

from dissector.errors import MalformedInput
from dissector.protocol.printable import printable


class FilterError(MalformedInput):
    """A filter that cannot be compiled; str() shows the expression and a caret under the token.

    The expression is typed text: its control characters are shown escaped (`\\x1b`), as every error
    line shows them (app/options.py shown()), and the caret stands under the escaped token. `lines`
    are the three lines, each safe for a terminal."""

    def __init__(self, message: str, text: str, position: int) -> None:
        self.message = message
        self.text = text
        self.position = position
        column = position + 1

        def shown(part: str) -> str:
            return printable(part.replace("\t", " ").replace("\n", " ").replace("\r", " "))

        self.lines = (printable(f"{message} (column {column})"), f"  {shown(text)}",
                      f"  {' ' * len(shown(text[:position]))}^")
        super().__init__("\n".join(self.lines))
