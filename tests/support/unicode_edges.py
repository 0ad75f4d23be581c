"""Code points where str.isprintable()'s answer changes (the frozen table of dissector/data/nonprintable.toml),
for the tests that hold printable() (tests/unit/test_printable.py) and the plugin's python_repr
(tests/integration/test_lua_printable.py) to Python's repr."""
from __future__ import annotations

from dissector.codegen import printable_table


def boundaries() -> list[int]:
    """Code points below U+0800, and either side of each edge of the frozen table's ranges."""
    flat = printable_table.frozen()["ranges"]
    edges = {code + step for first, last in zip(flat[::2], flat[1::2]) for code, step in
             ((first, -1), (first, 0), (last, 0), (last, 1))}
    return sorted(set(range(0x800)) | {code for code in edges if 0 <= code <= 0x10FFFF})
