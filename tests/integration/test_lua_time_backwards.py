"""The plugin on a capture whose time goes backwards (tests/differential/test_time_backwards.py for
vw3-decode): a response stamped before its request keeps its pairing, shows its negative response time
as it is (both parts of the nstime negative: -0.02 s, not -1.98) and is warned with vw3-decode's words."""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

from lua_harness import lua_items

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "differential"))
from test_time_backwards import WARNING, backwards_pcap  # noqa: E402

pytestmark = pytest.mark.integration


def test_response_before_its_request(tmp_path: Path) -> None:
    items, _, _ = lua_items(backwards_pcap(tmp_path))
    assert [item.record for item in items] == list(range(1, 11))
    assert [item.texts.get("warning", []) for item in items] == [[], [], [], [WARNING], [], [], [], [], [], []]
    assert [item.fields.get("request_frame") for item in items] == [None, "1", None, "3", None, "5", None, "7", None, "9"]
    times = [round(float(item.fields["response_time"]) * 1000, 3) for item in items if "response_time" in item.fields]
    assert times == [10.0, -20.0, 12.0, 11.0, 9.0]  # (the plugin's times are floats near 1.7e9 s: us rounded)
