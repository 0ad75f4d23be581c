"""Text from the bus or from a file, made safe to show: control characters as escapes.

Bus bytes and file contents are data: an ESC from an FC43 object or a map cell must not reach a
terminal as an escape sequence (OSC 8 links, cursor moves, a cleared screen), nor a bidi override
reorder what is shown. Everything that is not printable (C0, DEL, C1, format characters such as
U+202E, line and paragraph separators, private use, unassigned code points) is written as Python writes
it in a string literal: \\xNN below U+0100, \\uNNNN below U+10000, \\UNNNNNNNN above.

The plugin's map reader (lua/src/maps.lua printable, python_repr) escapes the same characters: the code
points str.isprintable() refuses, as Python 3.11 (Unicode 14.0.0) answered, are frozen in
dissector/data/nonprintable.toml (codegen/printable_table.py) and generated into the plugin's data. A Python
of another Unicode version differs from it on the code points Unicode assigned in between (tests/unit/
test_printable.py compares them when the versions are the same).
"""
from __future__ import annotations

# A byte as it is written in a Python bytes literal between single quotes (repr(b"...") with that quote):
# printable ASCII as itself, the quote and the backslash escaped (\' and \\), \t \n \r, every other byte
# \xNN. So the text holds no control character, and `\xc3` (the byte C3) never reads as the four bytes
# 5C 78 63 33 (those are `\\xc3`): ast.literal_eval("b'" + text + "'") gives the bytes back.
_BYTE_TEXT = [chr(byte) if 0x20 <= byte < 0x7F else f"\\x{byte:02x}" for byte in range(256)]
_BYTE_TEXT[0x27], _BYTE_TEXT[0x5C] = "\\'", "\\\\"
_BYTE_TEXT[0x09], _BYTE_TEXT[0x0A], _BYTE_TEXT[0x0D] = "\\t", "\\n", "\\r"
_BYTE_TABLE = {byte: text for byte, text in enumerate(_BYTE_TEXT)}


def _escape(char: str) -> str:
    code = ord(char)
    if code < 0x100:
        return f"\\x{code:02x}"
    return f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"


def printable(text: str) -> str:
    """`text` with every non-printable character escaped (most text passes unchanged, fast)."""
    if text.isprintable():
        return text
    return "".join(char if char.isprintable() else _escape(char) for char in text)



def bytes_text(data: bytes) -> str:
    """`data` as a bytes literal's text between single quotes (_BYTE_TEXT), shown as `'` + it + `'`."""
    return data.decode("latin-1").translate(_BYTE_TABLE)
