"""Notes a field engineer can read: one note per event, neighbouring addresses as ranges, a cap on the
summary line (everything kept in JSON and -V), the spec's exception name always and the device's
meaning once, key events highlighted."""
from __future__ import annotations

import json
from pathlib import Path

from helpers import rtu, run_cli

from dissector.devices.build import build_annotator
from dissector.model import Frame
from dissector.pipeline import dissect_bytes
from dissector.render.summary import summary_line, summary_text
from dissector.render.theme import STYLES
from dissector.sim.mixes import max_size_mix

ROOT = Path(__file__).resolve().parents[2]
P38 = ROOT / "captures" / "p38_protection.bin"


def _words(values: range | list[int]) -> str:
    return "".join(f"{value:04X}" for value in values)


def _frames(data: bytes, profile: str = "atv71") -> list[Frame]:
    return dissect_bytes(data, annotate=build_annotator([profile], []))  # type: ignore[return-value]


def test_p38_frame_10_names_the_spec_exception_and_the_device_meaning_once() -> None:
    line = run_cli([str(P38)])[1].splitlines()[9]
    assert line == (
        "    10            -  12 exception Read Holding Registers: exception 2 (Illegal Data Address) [#9] "
        "[exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: "
        "8400 non-existent, CHCF (8401) protected, COP (8402) protected] "
        "[COP (8402) became protected: read 2 in frame #8, exception 02 now]  CRC ok"
    )
    assert line.count("Illegal Data Address") == 1 and line.count("non-existent or protected") == 1
    # The device meaning stays a key of its own in JSON.
    frame = json.loads(run_cli([str(P38), "--json"])[1].splitlines()[9])
    assert frame["exception_name"] == "Illegal Data Address"
    assert frame["exception_meaning"] == "address does not exist (also: every parameter read is non-existent or protected)"  # (p.38: a read)


def test_readable_again_is_one_note_with_a_range() -> None:
    # The flood: 96 unmapped registers answered by exception 02, then read: one note, not 96.
    request = rtu(f"01 03 {39193:04X} 0060")
    data = request + rtu("01 83 02") + request + rtu("01 03 C0" + _words(range(28000, 28096)))
    frames = _frames(data)
    assert frames[1].notes == [
        "exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: "
        "39193..39288 non-existent (96)"
    ]
    assert frames[3].notes == ["39193..39288 readable again (96): non-existent in frame #2"]
    # One address alone keeps its value and past.
    single = rtu("01 03 9919 0002")
    data = single + rtu("01 03 04 8000 0005") + single + rtu("01 03 04 0007 0005")
    assert _frames(data)[3].notes == ["39193 readable again: non-existent in frame #2, 7 now"]


def test_scattered_addresses_are_capped_on_the_summary_line_and_whole_in_json() -> None:
    request = rtu("01 03 0064 0014")
    data = (request + rtu("01 03 28" + _words(range(1, 21)))
            + request + rtu("01 03 28" + _words([0x8000 if i % 2 == 0 else i for i in range(20)])))
    frame = _frames(data)[3]
    assert frame.notes == [
        "100, 102, 104, 106, 108, 110, 112, 114, 116, 118 became non-existent or protected (10): "
        "read in frame #2, 16#8000 now"
    ]
    assert summary_line(frame).endswith(
        "[#3] [100, 102, 104, 106, … (+6 more) became non-existent or protected (10): read in frame #2, "
        "16#8000 now]  CRC ok"
    )
    assert json.loads(run_cli(["-", "--profile", "atv71", "--json"], stdin=data)[1].splitlines()[3])["notes"] == [
        str(note) for note in frame.notes]


def test_notes_follow_the_address_style_of_the_screen() -> None:
    request = rtu("0C 03 20D0 0003")
    data = (request + rtu("0C 03 06 8000 0003 0002") + request + rtu("0C 03 06 8000 8000 0002"))
    frame = dissect_bytes(data, annotate=build_annotator(["atv71"], [], "plc"))[3]
    assert frame.notes == ["CHCF (48402) became protected: read 3 in frame #2, 16#8000 now"]


def test_key_events_are_highlighted_not_dim() -> None:
    frame = _frames(P38.read_bytes())[5]
    text = summary_text(frame)
    styled = {text.plain[span.start:span.end]: str(span.style) for span in text.spans}
    assert styled["[CHCF (8401) became protected: read 3 in frame #4, 16#8000 now]"] == "vw3.key"
    assert styled["[#5]"] == "vw3.pairing"
    assert "dim" not in STYLES["vw3.key"] and "dim" not in STYLES["vw3.note"]


def test_no_summary_line_over_1000_characters_on_the_max_size_session(tmp_path: Path) -> None:
    records = max_size_mix(6000, seed=3)
    capture = tmp_path / "max.bin"
    capture.write_bytes(b"".join(data for data, _ in records))
    for profile in ("auto", "atv71"):  # atv71: every random slave taken for a drive, the flood case
        status, out, _ = run_cli([str(capture), "--profile", profile])
        lines = out.splitlines()
        assert status == 0 and len(lines) >= 5900
        longest = max(lines, key=len)
        # Values stop at six (`… (+N)`), notes and warnings each at NOTES_BUDGET, then counted: 406 here,
        # an FC23 with two limit warnings and a read-only one counted (`[+1 more warning]`, 4ebcd87).
        assert len(longest) < 450, longest
