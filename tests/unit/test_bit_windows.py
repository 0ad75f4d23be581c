"""Which codes' windows are bits (their lifting rule's values "bits" or "coil": no label for their
addresses) is one fact of the protocol table, table.bit_windows, which vw3-decode's -Y (render/filter_match.py
BIT_WINDOWS) and the plugin (DATA.bit_windows, written by codegen/display_lua.py render_display) both take.
Before, each computed it on its own from the rules."""
from __future__ import annotations

import pytest

from dissector.codegen import display_lua
from dissector.protocol import table
from dissector.render import filter_match


def test_the_bit_windows_are_the_coil_and_discrete_input_codes() -> None:
    assert table.bit_windows() == frozenset({1, 2, 5, 15})
    assert filter_match.BIT_WINDOWS == table.bit_windows()


def test_the_plugin_takes_them_from_the_table(monkeypatch: pytest.MonkeyPatch) -> None:
    def written() -> list[str]:
        return [line for line in display_lua.render_display() if line.startswith("DATA.bit_windows")]

    assert written() == ["DATA.bit_windows = { [1] = true, [2] = true, [5] = true, [15] = true }"]
    monkeypatch.setattr(table, "bit_windows", lambda: frozenset({1, 99}))
    assert written() == ["DATA.bit_windows = { [1] = true, [99] = true }"]
