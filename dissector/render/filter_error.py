"""The error of a display filter that cannot be compiled, apart from the filter compiler: vw3-decode
catches it on every run and imports the compiler only for -Y."""
from __future__ import annotations

from dissector.errors import MalformedInput


class FilterError(MalformedInput):
    """A filter that cannot be compiled; str() shows the expression and a caret under the token."""

    def __init__(self, message: str, text: str, position: int) -> None:
        self.message = message
        self.text = text
        self.position = position
        column = position + 1
        line = text.replace("\t", " ").replace("\n", " ").replace("\r", " ")
        super().__init__(f"{message} (column {column})\n  {line}\n  {' ' * position}^")
