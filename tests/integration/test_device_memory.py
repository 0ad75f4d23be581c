"""The parameter memory ("became protected", "readable again": VW3 A3 303 manual p.38; devices/memory.py)
follows the device's tables: where its input registers are a table of their own (profile input_registers
"separate", the default), FC4's register 100 is not FC3's, and a 16#8000 read by one tells nothing of a
value the other read (Device.memory, Device.input_seen; the compiled engine hands those FC4 reads to the
annotator, whose memory it does not keep). Before, the memory was keyed by address alone: FC4's 16#8000
at 100 made holding register 100 "became protected", and the next FC3 read "readable again". On the ATV71
(input_registers "holding") an FC4 read is a read of the holding parameter: one memory
(tests/integration/test_device_tables.py)."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import run_cli, use_engine, write_rtu

MAP = "address,code,name\n100,SPD,Speed\n101,TRQ,Torque\n"
PROFILE = 'name = "relay"\ntitle = "A relay"\ndevice = "relay"\nmap = "relay.csv"\nprotected_value = 0x8000\n'


def _profile(tmp_path: Path, text: str) -> Path:
    (tmp_path / "relay.csv").write_text(MAP)
    profile = tmp_path / "relay.toml"
    profile.write_text(text)
    return profile


def _responses(tmp_path: Path, frames: list[str], pure: bool, monkeypatch: pytest.MonkeyPatch,
               profile: str = PROFILE) -> list[str]:
    use_engine(monkeypatch, pure)
    capture = write_rtu(tmp_path / "relay.bin", frames)
    status, out, err = run_cli([str(capture), "--profile", str(_profile(tmp_path, profile))])
    assert status == 0, err
    return [line for line in out.splitlines() if " response " in line]


@pytest.mark.parametrize("pure", [False, True])
def test_an_input_register_has_a_story_of_its_own(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                  pure: bool) -> None:
    frames = ["05 03 0064 0002", "05 03 04 0007 0001", "05 04 0064 0002", "05 04 04 8000 0002",
              "05 03 0064 0002", "05 03 04 0007 0001", "05 04 0064 0002", "05 04 04 0009 0002"]
    assert _responses(tmp_path, frames, pure, monkeypatch) == [
        "     2            -   5 response  Read Holding Registers 100..101 (2): SPD=7 TRQ=1 [#1]  CRC ok",
        "     4            -   5 response  Read Input Registers 100..101 (2): SPD=protected TRQ=2 [#3]  CRC ok",
        "     6            -   5 response  Read Holding Registers 100..101 (2): SPD=7 TRQ=1 [#5]  CRC ok",
        "     8            -   5 response  Read Input Registers 100..101 (2): SPD=9 TRQ=2 [#7]"
        " [SPD (100) readable again: protected in frame #4, 9 now]  CRC ok",
    ]


@pytest.mark.parametrize("pure", [False, True])
def test_the_engine_leaves_a_separate_memory_to_the_annotator(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                              pure: bool) -> None:
    """A quiet FC4 poll the engine would remember in the holding registers' memory (then FC3's 16#8000
    'became protected: read 5 in frame #6')."""
    frames = ["05 04 0064 0002", "05 04 04 0005 0002"] * 3 + ["05 03 0064 0002", "05 03 04 8000 0001"]
    assert _responses(tmp_path, frames, pure, monkeypatch)[-1] == (
        "     8            -   5 response  Read Holding Registers 100..101 (2): SPD=protected TRQ=1 [#7]  CRC ok")


@pytest.mark.parametrize("pure", [False, True])
def test_an_exception_for_every_input_register_leaves_the_holding_ones(tmp_path: Path,
                                                                      monkeypatch: pytest.MonkeyPatch,
                                                                      pure: bool) -> None:
    """all_protected_exception to an FC4 read tells the input registers' story (explain.py, memory.lost);
    before, FC3's next read of 100..101 was "readable again" and FC4's was not."""
    frames = ["05 03 0064 0002", "05 03 04 0007 0001", "05 04 0064 0002", "05 84 02",
              "05 03 0064 0002", "05 03 04 0007 0001", "05 04 0064 0002", "05 04 04 0003 0004"]
    lines = _responses(tmp_path, frames, pure, monkeypatch, PROFILE + "all_protected_exception = 2\n")
    assert lines[1:] == [
        "     6            -   5 response  Read Holding Registers 100..101 (2): SPD=7 TRQ=1 [#5]  CRC ok",
        "     8            -   5 response  Read Input Registers 100..101 (2): SPD=3 TRQ=4 [#7]"
        " [100..101 readable again (2): protected in frame #4]  CRC ok",
    ]


def test_the_plugins_profiles_that_follow_parameters_read_one_table() -> None:
    """The plugin keeps its memory by address (lua/src/story.lua): true while every built-in profile that
    follows parameters reads its input registers as holding registers (the plugin loads no user profile)."""
    from dissector.devices.profiles import BUILTIN_PROFILES, load_profile

    following = [load_profile(name) for name in BUILTIN_PROFILES]
    following = [profile for profile in following if profile.protected_value is not None or profile.bits_depend]
    assert [(profile.name, profile.input_registers) for profile in following] == [("atv71", "holding")]
