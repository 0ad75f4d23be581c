"""The plugin warns of FC5/FC6 answers that do not echo their request, with vw3-decode's words
(tests/unit/test_write_echo.py), and says nothing of an echo."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [
    "01 05 00 4A FF 00 AD EC", "01 05 00 47 00 00 7D DF",  # coil 74 ON answered by coil 71 OFF
    "01 06 00 37 00 63 78 2D", "01 06 00 37 00 62 B9 ED",  # register 55 = 99 answered by = 98
    "01 06 00 38 00 63 48 2E", "01 06 00 37 00 63 78 2D",  # register 56 = 99 answered for 55
    "01 05 00 4A FF 00 AD EC", "01 05 00 4A FF 00 AD EC",  # an echo
    "01 06 00 37 00 63 78 2D", "01 06 00 37 00 63 78 2D",  # an echo
]


def test_answers_that_are_not_the_echo_are_warned(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "echo.pcap", [(bytes.fromhex(frame), 1.0 + 0.01 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap)
    assert [item.texts.get("warning", []) for item in items] == [
        [], ["the response's address and value differ from the request's"],
        [], ["the response's value differs from the request's"],
        [], ["the response's address differs from the request's"],
        [], [], [], [],
    ]
    assert [item.fields["function"] for item in items] == ["5", "5", "6", "6", "6", "6", "5", "5", "6", "6"]
