"""printable() escapes what str.isprintable() refuses, as Python writes it in a literal; the frozen table the
plugin escapes by (dissector/data/nonprintable.toml) is the running Python's answer when its Unicode is the
file's. (The plugin against both: tests/integration/test_lua_printable.py.)"""
from __future__ import annotations

import unicodedata

import pytest

from dissector.codegen import printable_table
from dissector.protocol.printable import printable
from unicode_edges import boundaries


@pytest.mark.parametrize("text, shown", [
    ("plain text", "plain text"),
    ("\x1b[2J\x07\x7f\x85", "\\x1b[2J\\x07\\x7f\\x85"),
    ("\xa0\xad\xe9", "\\xa0\\xad\xe9"),  # no-break space and soft hyphen refused, é shown
    ("a\u202eb", "a\\u202eb"),  # a bidi override never reaches the terminal
    ("\u2028\u2029\u3000\u200b\ufeff", "\\u2028\\u2029\\u3000\\u200b\\ufeff"),
    ("\ue000", "\\ue000"),  # private use
    ("\U0001f600\u20ac\U00020000", "\U0001f600\u20ac\U00020000"),  # printable past U+FFFF too
    ("\u0378\U000e0001\U0010ffff", "\\u0378\\U000e0001\\U0010ffff"),  # unassigned, a tag, a noncharacter
])
def test_escapes_what_isprintable_refuses(text: str, shown: str) -> None:
    assert printable(text) == shown


def test_escapes_as_repr_does() -> None:
    # (but those repr escapes by name: the backslash, its quote, \n, \r, \t)
    text = "".join(chr(code) for code in boundaries() if chr(code) not in "\\'\n\r\t")
    assert "'" + printable(text) + "'" == repr(text)


def test_frozen_table_is_this_pythons_answer() -> None:
    data = printable_table.frozen()
    if data["unicode"] != unicodedata.unidata_version:
        pytest.skip(f"the table is Unicode {data['unicode']}'s, this Python has {unicodedata.unidata_version}")
    flat = data["ranges"]
    assert [(flat[at], flat[at + 1]) for at in range(0, len(flat), 2)] == printable_table.ranges()


def test_frozen_table_is_well_formed() -> None:
    flat = printable_table.frozen()["ranges"]
    assert len(flat) % 2 == 0 and flat == sorted(flat) and flat[0] == 0 and flat[-1] == 0x10FFFF
    assert all(flat[at] <= flat[at + 1] and flat[at + 1] + 1 < flat[at + 2] for at in range(0, len(flat) - 2, 2))
