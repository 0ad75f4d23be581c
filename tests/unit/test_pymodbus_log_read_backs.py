"""pymodbus logs whose recv lines all read back the bytes sent before them (sources/pymodbus_log.py _Mirror):

- a log of both ends of one link (a client and a server in one process) without pymodbus's decode lines and without
  the ends' own lines (`Server listening.`, `Connecting to ...`; logged at another level, or the log cut) showed
  every frame twice: the first of each pair `[no response]`, the second `[no request]`. A read-back of a frame
  only a server sends (a response, an exception) or of a request whose answer cannot repeat it (a read: its
  answer's length differs) was read by the other end, in the same log: each frame once, as with decode lines;
- a one-end log of echo functions only (a client's FC6 writes, each answer its request again) was held undecided
  up to 64 replies: through a live pipe (`tail -f log | vw3-decode -`) nothing was shown until then. Its read-backs
  in a row are not pairs of one frame (`A B C`), or decoded alike (a client's decode lines: two responses): one
  end's, known at its second or third reply."""
from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path

from dissector.sources.common import Input, WarningLog
from dissector.sources.pymodbus_log import read_pymodbus
from helpers import rtu, run_cli
from test_pymodbus_log_both_ends import BOTH, ONCE


def _bare(text: str) -> str:
    """The log without pymodbus's decode lines and the ends' own lines."""
    own = re.compile(r"decoded PDU|Server listening\.|Connecting to |Awaiting connections ")
    return "".join(line for line in text.splitlines(keepends=True) if not own.search(line))


def _log(tmp_path: Path, text: str) -> str:
    path = tmp_path / "pymodbus.log"
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_both_ends_without_decode_or_startup_lines_show_each_frame_once(tmp_path: Path) -> None:
    bare = _bare(BOTH)
    assert "decoded PDU" not in bare and "listening" not in bare and bare.count(" send: ") == 6
    assert run_cli(["-n", _log(tmp_path, bare)]) == (0, ONCE, "")
    assert run_cli(["-n", "-"], stdin=bare.encode()) == (0, ONCE, "")


def _writes(values: list[int], decoded: bool = False) -> list[str]:
    """A client's log (one end) of FC6 writes of `values` to register 5 of device 7, each echoed 20 ms later."""
    lines = []
    for second, value in enumerate(values):
        frame = " ".join(f"{byte:#x}" for byte in rtu(f"0706 0005 {value:04x}"))
        lines.append(f"2026-12-07 17:40:{second:02d},000 DEBUG transport:357 send: {frame}\n")
        lines.append(f"2026-12-07 17:40:{second:02d},020 DEBUG transport:308 recv: {frame} extra data: \n")
        if decoded:
            lines.append(f"2026-12-07 17:40:{second:02d},020 DEBUG decoders:86 decoded PDU function_code(6 sub -1) "
                         f"-> WriteSingleRegisterResponse(dev_id=0, address=5, registers=[{value}])\n")
    return lines


class _Live:
    """A pipe whose writer has written `lines` and goes on later: reading past them is `_Waiting`."""

    def __init__(self, lines: list[str]) -> None:
        self._lines = [line.encode() for line in lines]

    def read1(self, _count: int) -> bytes:
        if not self._lines:
            raise _Waiting
        return self._lines.pop(0)

    read = read1


class _Waiting(Exception):
    pass


def _given(lines: list[str]) -> list[bytes]:
    """The frames' bytes the reader gives out before the log goes on."""
    chunks: Iterator = read_pymodbus(Input(_Live(lines), "-"), WarningLog(), 4096)  # type: ignore[arg-type]
    given = []
    try:
        for chunk in chunks:
            given.append(chunk.data)
    except _Waiting:
        pass
    return given


def test_a_one_end_log_of_echoes_is_known_at_its_third_send() -> None:
    lines = _writes([100, 200, 300, 400])
    frames = [rtu(f"0706 0005 {value:04x}") for value in (100, 200, 300)]
    assert _given(lines[:5]) == [frames[0], frames[0], frames[1], frames[1], frames[2]]  # (its third send)
    assert _given(lines[:6]) == _given(lines[:5])  # (the last recv run: open until the next send)
    assert _given(lines[:4]) == []  # (A B: still both ends' request and echo, or one end's two writes)
    decoded = _writes([100, 100, 100], decoded=True)  # (the same write again: decoded twice a response)
    assert _given(decoded[:7]) == [frames[0]] * 5  # (at its third send, the second reply decoded)
    assert _given(decoded[:6]) == []


def test_a_one_end_log_of_echoes_through_a_pipe(tmp_path: Path) -> None:
    lines = _writes([100, 200, 300])
    assert run_cli(["-n", "-"], stdin="".join(lines).encode()) == (0, (
        "     1     0.000000   7 request   Write Single Register 5 = 100  CRC ok\n"
        "     2     0.020000   7 response  Write Single Register 5 = 100 [#1, 20.0 ms]  CRC ok\n"
        "     3     1.000000   7 request   Write Single Register 5 = 200  CRC ok\n"
        "     4     1.020000   7 response  Write Single Register 5 = 200 [#3, 20.0 ms]  CRC ok\n"
        "     5     2.000000   7 request   Write Single Register 5 = 300  CRC ok\n"
        "     6     2.020000   7 response  Write Single Register 5 = 300 [#5, 20.0 ms]  CRC ok\n"), "")
