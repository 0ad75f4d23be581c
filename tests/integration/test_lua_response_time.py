"""vw3.response_time, -V's `[Time since request: ...]`, is the capture's own difference of the two records'
times, to the nanosecond (0.010157000 where frame.time_delta says 0.010157000), not a difference of
absolute times as doubles near 1.7e9 (0.010157108), so `-Y 'vw3.response_time == 0.010157'` finds the frame
as vw3-decode's `-Y 'response_time == 0.010157'` does. Real tshark with the plugin, two passes and one."""
from __future__ import annotations

import pytest

from lua_harness import ROOT, lua_errors, run_tshark

pytestmark = pytest.mark.integration

P38 = ROOT / "captures" / "p38_protection.pcap"


@pytest.mark.parametrize("two_pass", [True, False])
def test_response_time_is_the_capture_difference(two_pass: bool) -> None:
    got = run_tshark(P38, "-T", "fields", "-e", "frame.number", "-e", "frame.time_delta", "-e",
                     "vw3.response_time", two_pass=two_pass)
    assert not lua_errors(got.stdout + got.stderr)
    rows = [line.split("\t") for line in got.stdout.splitlines()]
    answers = [row for row in rows if row[2]]
    assert [row[0] for row in answers] == ["2", "4", "6", "8", "10", "12"]
    assert answers[0] == ["2", "0.010157000", "0.010157000"]
    assert all(row[1] == row[2] for row in answers)  # each answer follows its request directly


def test_response_time_filters_and_shows_exactly() -> None:
    found = run_tshark(P38, "-T", "fields", "-e", "frame.number", "-Y", "vw3.response_time == 0.010157")
    assert found.stdout.splitlines() == ["2"]
    shown = run_tshark(P38, "-V", "-Y", "frame.number == 2")
    assert [line.strip() for line in shown.stdout.splitlines() if "Time since request" in line] == [
        "[Time since request: 0.010157000 seconds]"]
