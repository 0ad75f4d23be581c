"""A file's line speed (framing/linespeed.py): `--baud`, else a pcapng interface's texts, else 19200, and
every stage of a decode gets the same one: the t1.5 check of silences inside frames as well as --stats."""
from __future__ import annotations

import json
from pathlib import Path

from helpers import run_cli, write_9600_tap
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import PcapWriter
from dissector.framing.linespeed import LineSettings, line_settings, settings_from_text
from dissector.sources.pcapng import first_interface


def _warnings(*argv: str) -> list[tuple[int, list[str]]]:
    status, out, err = run_cli(["--json", *argv])
    assert (status, err) == (0, "")
    return [(record["frame"], record["warnings"]) for record in map(json.loads, out.splitlines()) if record["warnings"]]


def test_the_interface_description_sets_the_speed_of_the_silence_checks(tmp_path: Path) -> None:
    tap = tmp_path / "tap.pcapng"
    write_9600_tap(tap)
    # 9600 baud: t1.5 is 1.719 ms; the 1.2 ms silence of frame 1 is allowed, frame 3's 2 ms is not.
    assert _warnings(str(tap)) == [
        (3, ["silence of 2.000 ms inside the frame before byte 4 (longer than t1.5 = 1.719 ms at 9600 baud)"])]
    # --baud wins over the file: at 19200 the first piece's 4 characters last 2.292 ms, not 4.583 ms (us stamps)
    assert _warnings("--baud", "19200", str(tap)) == [
        (1, ["silence of 3.491 ms inside the frame before byte 4 (longer than t1.5 = 0.859 ms at 19200 baud)"]),
        (3, ["silence of 4.291 ms inside the frame before byte 4 (longer than t1.5 = 0.859 ms at 19200 baud)"]),
        (5, ["silence of 2.291 ms inside the frame before byte 4 (longer than t1.5 = 0.859 ms at 19200 baud)"]),
    ]
    status, out, err = run_cli(["--stats", str(tap)])
    assert "line: 9600 baud (pcapng interface description), 11 bits a character, t3.5 4.010 ms" in out


def test_first_interface_texts_and_what_they_state(tmp_path: Path) -> None:
    tap = tmp_path / "tap.pcapng"
    write_9600_tap(tap)
    interface = first_interface(str(tap))
    assert interface is not None and interface.texts == (
        "/dev/ttyUSB0", "serial port /dev/ttyUSB0, 9600 baud, 8 data bits, even parity, 1 stop bit (9600 8E1)")
    assert line_settings(str(tap), "pcapng", None) == LineSettings(9600, 11, "pcapng interface description")
    assert line_settings(str(tap), "pcapng", 38400) == LineSettings(38400, None, "--baud")
    classic = tmp_path / "tap.pcap"
    with classic.open("wb") as stream:
        PcapWriter(stream).close()
    assert first_interface(str(classic)) is None
    assert line_settings(str(classic), "pcap", None) == LineSettings(19200, None, "assumed: --baud sets it")
    assert first_interface(str(tmp_path / "absent.pcapng")) is None
    bare = tmp_path / "bare.pcapng"
    with bare.open("wb") as stream:
        PcapngWriter(stream).close()
    assert first_interface(str(bare)).texts == ()  # type: ignore[union-attr]
    assert line_settings(str(bare), "pcapng", None).source == "assumed: --baud sets it"


def test_what_a_text_states() -> None:
    assert settings_from_text("COM3 38400 8N1") == LineSettings(38400, 10, "pcapng interface description")
    assert settings_from_text("RS-485 tap 19200/8/E/1") is None  # not a way the settings are written
    assert settings_from_text("port at 115200 bps") == LineSettings(115200, None, "pcapng interface description")
    assert settings_from_text("9600 8N1.5").bits == 10.5  # type: ignore[union-attr]
    # hostile texts: no speed of 0 (a division by zero in every timing), none below 50 baud
    assert settings_from_text("00 baud") is None and settings_from_text("00 8N1 at 19200 baud").baud == 19200  # type: ignore[union-attr]
