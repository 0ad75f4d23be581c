"""The plugin checks FC22, FC21 and FC20 as vw3-decode does (tests/unit/test_file_mask_checks.py), with its
words: an answer that does not repeat its request, a sub-response of another length than asked, a reference
type other than 6, a record number past 0x270F; and nothing of answers that fit."""
from __future__ import annotations

from pathlib import Path

import pytest

from lua_harness import lua_items, write_pcap

pytestmark = pytest.mark.integration

FRAMES = [
    "01 16 00 04 00 F2 00 25 67 EE", "01 16 00 04 00 F2 00 26 27 EF",  # OR mask 0x25 answered with 0x26
    "01 16 00 04 00 F2 00 25 67 EE", "01 16 00 04 00 F2 00 25 67 EE",  # an echo
    "01 15 0D 06 00 04 00 07 00 03 06 AF 04 BE 10 0D D6 0B",  # file 4, record 7, 3 words
    "01 15 0D 06 00 04 00 07 00 03 06 AF 04 BE 10 0E 96 0A",  # its last word 0x100E in the answer
    "01 15 0D 06 00 04 00 07 00 03 06 AF 04 BE 10 0D D6 0B", "01 15 0D 06 00 04 00 07 00 03 06 AF 04 BE 10 0D D6 0B",
    "01 14 07 06 00 04 00 01 00 02 D8 E5", "01 14 08 07 06 00 01 00 02 00 03 DE 7F",  # 2 words asked, 3 sent
    "01 14 07 05 00 04 27 10 00 02 B1 54", "01 14 06 05 06 00 01 00 02 39 CB",  # type 5, record 0x2710; 2 words
    "01 14 0E 06 00 04 00 01 00 02 06 00 03 00 09 00 01 B4 FC", "01 14 06 05 06 00 01 00 02 39 CB",  # 2 asked, 1 sent
    "01 15 09 07 00 01 27 0F 00 01 12 34 34 73",  # type 7 at the last record, 0x270F
]


def test_file_and_mask_answers_are_checked(tmp_path: Path) -> None:
    pcap = write_pcap(tmp_path / "checks.pcap", [(bytes.fromhex(frame), 1.0 + 0.1 * n) for n, frame in enumerate(FRAMES)])
    items, _, _ = lua_items(pcap)
    assert [item.texts.get("warning", []) for item in items] == [
        [], ["the response's or_mask differs from the request's"], [], [],
        [], ["the response's data differs from the request's"], [], [],
        [], ["sub-response 1's length 7 holds registers (3), not the record length asked (2)"],
        ["sub-request 1's reference type 5 is not the spec's 6",
         "sub-request 1's record number 10000 outside the spec's 0..9999"], [],
        [], ["number of sub-responses 1 disagrees with the request's (2)"],
        ["record 1's reference type 7 is not the spec's 6"],
    ]
    assert [item.fields["function"] for item in items] == ["22"] * 4 + ["21"] * 4 + ["20"] * 6 + ["21"]
