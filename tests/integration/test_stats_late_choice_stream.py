"""--stats and --report of standard input where profile `auto` chooses a slave's device after the slave settled
without one (hunt60-report.md F2): slave 12's frames #1..#11 settle it (8 answers) with no device, the FC43
ProductCode 'ATV71H' in #12 chooses the ATV71. The file is named with the ATV71 from #1 (app/preselect.py), so
16#8000 at 65535 in #6 is `non-existent`; standard input counted #11 and the frames before it with spec semantics
(`65535 reads 1, last 32768`). Now the history holds a slave's frames until its choice is final (or the input
ends) and reads them with it (render/history.py held), and the engine leaves such a slave to the Python stages:
each input gives the file's lines, read either way, engine or Python stages. Past history.MAX_HELD frames held
the stream counts as it goes, and --stats says which choice came after frames so counted."""
from __future__ import annotations

import json

import pytest

from helpers import rtu, run_cli, stats_section, use_engine

from dissector.pipeline import dissect_bytes
from dissector.render import history

MIN = bytes.fromhex(
    "0c10ffff000381310c04027d91740d0c08000b000090d40c08000b000090d40c04fffe000620f10c040c000280000128000f0002ffffc95d"
    "0c030c0002002000010637bdfe0096ec9c0c17040128000225d20c030c9ce600070096ffffffff0005d4aa0c080000fa9257f2fd39da1f"
    "f4518c287048e366ff9ff90c080000fa9257f2fd39da1ff4518c287048e366ff9ff90c2b0e0102ff00020003e974e90106415456373148dc0d"
)
MIN_PARAMETERS = [
    "slave   address  code  reads  unreadable  writes  refused  last          changes",
    "--------------------------------------------------------------------------------",
    "   12  0..3 (4)            1           0       0        0  (various)           0",
    "   12     65534            1           0       0        0  2                   0",
    "   12     65535            0           1       0        0  non-existent        0",
    "  all  6 params            5           1       0        0                      0",
]


def _poll5(value: int) -> bytes:
    """Slave 5, never identified (generic): 16#8000 in its multi-register read stays the value 32768."""
    return rtu("050300000003") + rtu("050306" + f"{value:04x}" + "80000002")


def _min_cut_after(frames: int) -> int:
    return dissect_bytes(MIN)[frames].offset


# Slave 5 settles generic first; slave 12's frames with a slave 5 poll after its #6 (the FC4 read of 16#8000).
CUT = _min_cut_after(6)
TWO = b"".join(_poll5(v) for v in range(1, 10)) + MIN[:CUT] + _poll5(7) + MIN[CUT:] + _poll5(8)
TWO_PARAMETERS = [
    "slave   address  code  reads  unreadable  writes  refused  last          changes",
    "--------------------------------------------------------------------------------",
    "    5         0           11           0       0        0  8                  10",
    "    5         1           11           0       0        0  32768               0",
    "    5         2           11           0       0        0  2                   0",
    "   12  0..3 (4)            1           0       0        0  (various)           0",
    "   12     65534            1           0       0        0  2                   0",
    "   12     65535            0           1       0        0  non-existent        0",
    "  all  9 params           38           1       0        0                     10",
]
# The choice in the middle: after it, 65535 non-existent again (#14), then readable (#16: 9).
AFTER = MIN + rtu("0c04fffe0002") + rtu("0c040400028000") + rtu("0c04fffe0002") + rtu("0c040400030009")
AFTER_PARAMETERS = [
    "slave   address  code  reads  unreadable  writes  refused  last       changes",
    "-----------------------------------------------------------------------------",
    "   12  0..3 (4)            1           0       0        0  (various)        0",
    "   12     65534            3           0       0        0  3                1",
    "   12     65535            1           2       0        0  9                1",
    "  all  6 params            8           2       0        0                   2",
]
VECTORS = {"min-choice-in-last-frame": (MIN, MIN_PARAMETERS), "one-of-two-slaves": (TWO, TWO_PARAMETERS),
           "choice-then-more": (AFTER, AFTER_PARAMETERS)}


def _stats(data: bytes, read: str, tmp_path, *options: str) -> str:
    if read == "stdin":
        status, out, err = run_cli(["--stats", *options, "-"], data)
    else:
        path = tmp_path / "capture.bin"
        path.write_bytes(data)
        status, out, err = run_cli(["--stats", *options, str(path)])
    assert status == 0, err
    return out


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
@pytest.mark.parametrize("read", ["stdin", "file"])
@pytest.mark.parametrize("name", list(VECTORS))
def test_a_choice_after_settling_counts_as_the_file(name: str, read: str, pure: bool, tmp_path, monkeypatch) -> None:
    use_engine(monkeypatch, pure)
    data, parameters = VECTORS[name]
    out = _stats(data, read, tmp_path)
    assert stats_section(out) == parameters
    assert "counted as named then" not in out


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_min_stats_json_and_report_agree_with_the_file(pure: bool, tmp_path, monkeypatch) -> None:
    use_engine(monkeypatch, pure)
    assert _stats(MIN, "stdin", tmp_path, "--json") == _stats(MIN, "file", tmp_path, "--json")
    row = [p for p in json.loads(_stats(MIN, "stdin", tmp_path, "--json"))["parameters"] if p["address"] == 65535]
    assert (row[0]["reads"], row[0]["unreadable"], row[0]["last_text"]) == (0, 1, "non-existent")
    (tmp_path / "min.bin").write_bytes(MIN)
    pages = []
    for source, stdin in ((str(tmp_path / "min.bin"), b""), ("-", MIN)):
        page = tmp_path / "page.html"
        status, _out, err = run_cli(["--report", str(page), source], stdin)
        assert status == 0, err
        pages.append(page.read_text().replace(str(tmp_path / "min.bin"), "-"))
    assert "protection: 1," in pages[1]  # (was 0 read once: 16#8000 a value)
    assert pages[0] == pages[1]


@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_past_the_cap_the_stream_counts_as_it_goes_and_says_so(pure: bool, tmp_path, monkeypatch) -> None:
    use_engine(monkeypatch, pure)
    monkeypatch.setattr(history, "MAX_HELD", 3)  # (slave 12's frame #11 passes it: held #1..#11 counted as named)
    out = _stats(MIN, "stdin", tmp_path)
    assert stats_section(out)[4] == "   12     65535            1           0       0        0  32768            0"
    assert stats_section(out, "Device profiles")[-1] == (
        "slave 12: its frames before #12 counted as named then, not with this choice (read once, the history holds "
        "3 frames at most for a choice, none with --watch): the file's counts may differ")
    assert json.loads(_stats(MIN, "stdin", tmp_path, "--json"))["counted_before_choice"] == [{"slave": 12, "frame": 12}]
    assert stats_section(_stats(MIN, "file", tmp_path)) == MIN_PARAMETERS  # (the file holds nothing)
