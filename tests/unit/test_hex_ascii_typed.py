"""--hex with a Modbus ASCII frame typed as manuals and the README print it: with its CR LF written as the
`\\r\\n` escape (the README's Inputs list), as words (CR LF, <CR><LF>), with spaces between bytes. Before,
each was 20-23 bytes of noise with exit 0. Anything else after the ':' is refused in one line, exit 2, as
RTU --hex refuses what is not hex. Vector: the VW3-A3-303 manual's :02062329000AA2 (Write Single Register
9001 = 10, LRC A2)."""
from __future__ import annotations

import json

import pytest

from helpers import run_cli, use_engine

ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
ALONE = ("     1            -   2 request   Write Single Register 9001 = 10 "
         "[the capture ends before any response: not known whether it was answered]  LRC ok\n")
WIRE = "3a30323036323332393030304141320d0a"  # :02062329000AA2 CR LF, as a serial line carries it


@ENGINES
@pytest.mark.parametrize("typed", [
    ":02062329000AA2",
    ":02062329000AA2\\r\\n",  # a backslash and r, a backslash and n: the README's spelling in shell quotes
    ":02062329000AA2\r\n",  # real CR LF ($'...' in bash)
    ":0206 2329 000A A2",
    ": 02 06 23 29 00 0A A2 ",
    ":02062329000AA2 CR LF",
    ":02062329000AA2 CRLF",
    ":02062329000AA2<CR><LF>",
    ":02062329000AA2 [cr][lf]",
    ":02062329000AA2\\n",
    ":02062329000AA2 0D 0A",  # the CR LF as the hex of its bytes, as manuals print a frame's bytes
    ":0206 2329 000A A2 0d 0a",
])
def test_an_ascii_frame_typed_as_printed_is_decoded(typed: str, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    assert run_cli(["--hex", typed]) == (0, ALONE, "")
    record = json.loads(run_cli(["--json", "--hex", typed])[1])
    assert (record["raw"], record["crc_ok"]) == (WIRE, True)  # every byte is the frame's: none left as noise


@ENGINES
def test_frames_in_one_argument_and_a_missing_lrc(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    assert run_cli(["--hex", ":02062329000AA2\\r\\n:02062329000AA2\\r\\n"]) == (0, (
        "     1            -   2 request   Write Single Register 9001 = 10  LRC ok\n"
        "     2            -   2 response  Write Single Register 9001 = 10 [#1]  LRC ok\n"), "")
    assert run_cli(["--hex", ":0206 2329 000A\\r\\n"]) == (0, (
        "     1            -   2 request   Write Single Register 9001 = 10 [the capture ends before any response: "
        "not known whether it was answered] [no LRC typed: append A2]  LRC computed (none typed)\n"), "")
    # 0D 0A that the LRC says are data stay data: 0206 2329 0D0A is a write of 0x0D0A, its LRC typed after
    assert run_cli(["--hex", ":0206 2329 0D 0A 95"])[1].endswith(
        "Write Single Register 9001 = 3338 [the capture ends before any response: not known whether it was answered]  "
        "LRC ok\n")
    # a bad LRC is the framer's to show, typed with spaces or not
    assert run_cli(["--hex", ":0206 2329 000A A3 CR LF"])[1].endswith("LRC BAD (received 0xA3, expected 0xA2)\n")
    # `0D 0A` after a frame whose LRC is good without them is its CR LF typed as the hex of its bytes (before:
    # two more digits of the frame, 21 bytes of noise): -x shows the 17 bytes of the wire
    status, out, err = run_cli(["-x", "--hex", ":02062329000AA2 0D 0A"])
    assert (status, err) == (0, "")
    assert out.splitlines()[1:] == [
        "0000  3a 30 32 30 36 32 33 32 39 30 30 30 41 41 32 0d   :02062329000AA2.",
        "0010  0a                                                .",
        "",
    ]


@ENGINES
@pytest.mark.parametrize(("typed", "message"), [
    (":0206x\\r\\n", "'x' in ':0206x\\r\\n' is not a hex digit (an ASCII frame is ':', hex digits and CR LF, "
     "which may be typed as \\r\\n or CR LF, or left out)"),
    (":0206232", "'0206232' is an odd number of hex digits (each group is whole bytes)"),
    (":020 62329000AA2", "'020' is an odd number of hex digits (each group is whole bytes)"),
    (":", "no hex digits after a ':' in ':'"),
    (":02062329000AA2\\r\\n:", "no hex digits after a ':' in ':02062329000AA2\\r\\n:'"),
    (":0206é", "'é' in ':0206é' is not a hex digit (an ASCII frame is ':', hex digits and CR LF, which may be "
     "typed as \\r\\n or CR LF, or left out)"),
    (":0206\t\x1b", "'\\x1b' in ':0206\\t\\x1b' is not a hex digit (an ASCII frame is ':', hex digits and CR LF, "
     "which may be typed as \\r\\n or CR LF, or left out)"),  # (escaped: no control character reaches the terminal)
])
def test_anything_else_is_refused_in_one_line(
    typed: str, message: str, pure: bool, monkeypatch: pytest.MonkeyPatch
) -> None:
    use_engine(monkeypatch, pure)
    assert run_cli(["--hex", typed]) == (2, "", f"vw3-decode: --hex: {message}\n")


def test_the_argument_is_named_when_there_are_several() -> None:
    assert run_cli(["--hex", ":02062329000AA2", "--hex", ":0206 CR 2329"]) == (2, "", (
        "vw3-decode: --hex argument 2: 'R' in ':0206 CR 2329' is not a hex digit (an ASCII frame is ':', hex "
        "digits and CR LF, which may be typed as \\r\\n or CR LF, or left out)\n"))
