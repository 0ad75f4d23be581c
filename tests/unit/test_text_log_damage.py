"""Text logs (hex dumps, traffic logs, xxd and hexdump -C dumps) as they come from the field: a stray line,
a last line cut short, a time of day that does not exist, standard input. Through the command line, engine and VW3_PURE_PYTHON=1.

Before: one bad line among the first ~19 (the sample the format is judged on) made the whole log raw
ASCII bytes, exit 0, with only `the input is text, but neither a hex dump nor Modbus ASCII` (the same line
at line 20+ was `line 20: ...`, exit 2); a log cut mid-line (no line end at the end) printed nothing, exit
2, and -w wrote nothing; -w's records were deleted after a bad line; `99:99:99.000` and `10:00:60.010`
were times (362439 s, 60 s); standard input was `<stdin>` in some messages, `standard input` in others.
Vectors: the VW3-A3-303 manual's p.38 frames (request 0C 03 20 D0 00 03 0E EF and its answers)."""
from __future__ import annotations

from pathlib import Path

import pytest

from dissector.sources.reader import open_source
from helpers import run_cli, use_engine

ENGINES = pytest.mark.parametrize("pure", [False, True], ids=["engine", "pure"])
REQUEST = "0C 03 20 D0 00 03 0E EF"
ANSWER = "0C 03 06 80 00 00 03 00 02 17 E4"
PAIR = ("     1            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
        "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 [#1]  CRC ok\n")
# p.38's story, 12 lines: two reads, CHCF then COP protected, the exceptions 02.
P38 = [REQUEST, ANSWER, REQUEST, ANSWER, REQUEST, "0C 03 06 80 00 80 00 00 02 CE 24", REQUEST,
       "0C 03 06 80 00 80 00 00 02 CE 24", REQUEST, "0C 83 02 51 32", REQUEST, "0C 83 02 51 32"]
P38_SHOWN = (
    "     1            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
    "     2            -  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) COP=Cd (command) [#1]  CRC ok\n"
    "     3            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
    "     4            -  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=IO (I/O profile) COP=Cd (command) [#3]  CRC ok\n"
    "     5            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
    "     6            -  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=protected COP=Cd (command) [#5] [CHCF (8401) became protected: read 3 in frame #4, 16#8000 now]  CRC ok\n"
    "     7            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
    "     8            -  12 response  Read Holding Registers 8400..8402 (3): 8400=non-existent CHCF=protected COP=Cd (command) [#7]  CRC ok\n"
    "     9            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
    "    10            -  12 exception Read Holding Registers: exception 2 (Illegal Data Address) [#9] [exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: 8400 non-existent, CHCF (8401) protected, COP (8402) protected] [COP (8402) became protected: read 2 in frame #8, exception 02 now]  CRC ok\n"
    "    11            -  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
    "    12            -  12 exception Read Holding Registers: exception 2 (Illegal Data Address) [#11] [exception 02 from the VW3 A3 303: every parameter of this read is non-existent or protected: 8400 non-existent, CHCF (8401) protected, COP (8402) protected]  CRC ok\n"
)


def _decode(tmp_path: Path, text: str, *options: str) -> tuple[int, str, str]:
    path = tmp_path / "log.txt"
    path.write_bytes(text.encode())
    status, out, err = run_cli([*options, str(path)])
    return status, out, err.replace(str(path), "FILE")


def _records(path: Path) -> int:
    with open_source(str(path)) as source:
        return sum(1 for _chunk in source)


def _typo(lines: list[str], number: int) -> list[str]:
    """The log with line `number`'s last character dropped (`... CE 2`)."""
    return [line[:-1] if index == number else line for index, line in enumerate(lines, start=1)]


# -- one stray line: the log is still the format most of its lines are, and the line is named ------------

@ENGINES
@pytest.mark.parametrize("line", [2, 6, 12, 20, 40])
def test_a_typo_is_named_wherever_it_is(tmp_path: Path, pure: bool, line: int,
                                        monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    digit = _typo(P38 * 4, line)[line - 1].split()[-1]
    assert _decode(tmp_path, "\n".join(_typo(P38 * 4, line)) + "\n") == (
        2, "", f"vw3-decode: FILE line {line}: {digit!r} is an odd number of hex digits\n")


@ENGINES
@pytest.mark.parametrize(("second", "error"), [
    ("0C 03 06 80 00 00 03 00 02 17 E", "'E' is an odd number of hex digits"),
    (ANSWER + " ZZ", "'ZZ' is not hex"),
])
def test_a_typo_in_a_two_line_log(tmp_path: Path, pure: bool, second: str, error: str,
                                  monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # One line good, one of bytes with a typo: a dump (before: raw text, exit 0).
    assert _decode(tmp_path, f"{REQUEST}\n{second}\n") == (2, "", f"vw3-decode: FILE line 2: {error}\n")


@ENGINES
def test_a_c_style_note_says_how_comments_are_written(tmp_path: Path, pure: bool,
                                                      monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    lines = P38 + P38
    lines[5] = REQUEST + "   // retry"
    assert _decode(tmp_path, "\n".join(lines) + "\n") == (
        2, "", "vw3-decode: FILE line 6: '//' is not hex (a comment starts with #)\n")
    lines[5] = REQUEST + "   # retry"  # the dump's own comment
    status, out, err = _decode(tmp_path, "\n".join(lines) + "\n")
    assert (status, err, out.count(" request ")) == (0, "", 13)


@ENGINES
def test_a_stray_line_in_a_traffic_log(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # Modbus Poll writes a direction with no bytes for a timeout (skipped); a bare word is no line of it.
    log = f"Tx:000000-{REQUEST}\nRx:000001-{ANSWER}\nTx:000002-{REQUEST}\nTimeout\nTx:000003-{REQUEST}\n"
    assert _decode(tmp_path, log) == (2, "", "vw3-decode: FILE line 4: not a Tx:/Rx: traffic line: 'Timeout'\n")
    assert _decode(tmp_path, log.replace("Timeout\n", "Rx:000003-\n"))[0] == 0


@ENGINES
def test_text_in_no_format_is_still_its_bytes(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # Half the lines hex, half not: not most; the text's characters, with the warning, as before.
    status, out, err = _decode(tmp_path, f"{REQUEST}\nhello there\n")
    assert (status, out) == (0, "     1            -   - noise     36 bytes of noise at offset 0: "
                                "30 43 20 30 33 20 32 30 20 44 30 20 30 30 20 30…\n")
    assert err.startswith("vw3-decode: warning: FILE: the input is text, but neither a hex dump nor Modbus ASCII: "
                          "decoded as raw bytes\n")


@ENGINES
def test_a_fraction_after_a_comma(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # ISO 8601 allows ',' before the fraction; Python's logging writes `2024-05-01 10:00:00,125`.
    shown = ("     1     0.000000  12 request   Read Holding Registers 8400..8402 (3)  CRC ok\n"
             "     2     0.010000  12 response  Read Holding Registers 8400..8402 (3): 8400=32768 8401=3 8402=2 "
             "[#1, 10.0 ms]  CRC ok\n")
    assert _decode(tmp_path, f"10:00:00,125 {REQUEST}\n10:00:00,135 {ANSWER}\n") == (0, shown, "")
    assert _decode(tmp_path, f"2024-05-01 10:00:00,125 {REQUEST}\n2024-05-01 10:00:00,135 {ANSWER}\n") == (0, shown, "")


# -- the last line cut short (no line end): the input cut short, as a pcap's cut record ---------------------

CUT = ("vw3-decode: warning: FILE line 13 is cut short (the input ends inside it, without a line end): "
       "its 2 whole bytes are decoded, the rest ('2') is not\n")


@ENGINES
def test_a_log_cut_mid_line(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    log = "\n".join(P38) + "\n0C 03 2"
    noise = "    13            -   - noise     2 bytes of noise at offset 102: 0c 03\n"
    assert _decode(tmp_path, log) == (0, P38_SHOWN + noise, CUT)
    written = tmp_path / "w.pcap"
    assert _decode(tmp_path, log, "-w", str(written)) == (0, "", CUT)
    assert _records(written) == 13
    status, out, err = _decode(tmp_path, log, "--json")
    assert (status, err, out.count("\n")) == (0, CUT, 13)
    assert out.splitlines()[-1] == ('{"frame": 13, "kind": "noise", "offset": 102, "length": 2, "time": null, '
                                    '"raw": "0c03", "reason": "the capture ends inside a request (2 of 8 bytes)", "warnings": []}')


@ENGINES
def test_a_log_cut_in_its_time_stamp(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    shown = ("     1     0.000000  12 request   Read Holding Registers 8400..8402 (3) "
             "[the capture ends before any response: not known whether it was answered]  CRC ok\n")
    assert _decode(tmp_path, f"10:00:00.000 {REQUEST}\n10:00:0") == (0, shown, (
        "vw3-decode: warning: FILE line 2 is cut short (the input ends inside it, without a line end): "
        "it holds no whole byte ('10:00:0' is not read)\n"))
    assert _decode(tmp_path, f"10:00:00.000 {REQUEST}\n10:00:00.010 0C 03 0")[2] == (
        "vw3-decode: warning: FILE line 2 is cut short (the input ends inside it, without a line end): "
        "its 2 whole bytes are decoded, the rest ('0') is not\n")


@ENGINES
def test_a_traffic_log_cut_mid_line(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    log = f"Tx:000000-{REQUEST}\nRx:000001-{ANSWER}\nTx:000002-{REQUEST}\nRx:000003-0C 03 06 8"
    shown = PAIR + ("     3            -  12 request   Read Holding Registers 8400..8402 (3) "
                    "[the capture ends inside the response (3 of 11 bytes)]  CRC ok\n"
                    "     4            -   - noise     3 bytes of noise at offset 27: 0c 03 06\n")
    assert _decode(tmp_path, log) == (0, shown, (
        "vw3-decode: warning: FILE line 4 is cut short (the input ends inside it, without a line end): "
        "its 3 whole bytes are decoded, the rest ('8') is not\n"))


@ENGINES
@pytest.mark.parametrize(("last", "error"), [
    ("0C 03 zz 00", "'zz' is not hex"),  # a bad word before the last: not a cut
    (f"{REQUEST} // end", "'//' is not hex (a comment starts with #)"),
    ("0C 03 2 # note", "'2' is an odd number of hex digits"),  # a comment after it: the line was whole
])
def test_a_bad_last_line_is_no_cut(tmp_path: Path, pure: bool, last: str, error: str,
                                   monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    assert _decode(tmp_path, "\n".join(P38) + "\n" + last) == (2, "", f"vw3-decode: FILE line 13: {error}\n")


@ENGINES
def test_the_same_line_with_its_line_end_is_an_error(tmp_path: Path, pure: bool,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    assert _decode(tmp_path, "\n".join(P38) + "\n0C 03 2\n") == (
        2, "", "vw3-decode: FILE line 13: '2' is an odd number of hex digits\n")


# xxd and hexdump -C of the p.38 request and answer, then the request and the answer's first 5 bytes.
XXD = ("00000000: 0c03 20d0 0003 0eef 0c03 0680 0000 0300  .. .............\n"
       "00000010: 0217 e40c 0320 d000 030e ef0c 0306 8000  ..... ..........\n")
HEXDUMP_C = ("00000000  0c 03 20 d0 00 03 0e ef  0c 03 06 80 00 00 03 00  |.. .............|\n"
             "00000010  02 17 e4 0c 03 20 d0 00  03 0e ef 0c 03 06 80 00  |..... ..........|\n")
THIRD = "     3            -  12 request   Read Holding Registers 8400..8402 (3) "
DUMP_CUTS = [
    (XXD[:111], "its 13 whole bytes are decoded, the rest ('0') is not",  # `... ef0c 030`: inside a byte
     THIRD + "[the capture ends inside the response (2 bytes of it)]  CRC ok\n"
     "     4            -   - noise     2 bytes of noise at offset 27: 0c 03\n"),
    (XXD[:108], "its 12 whole bytes are decoded",  # `... ef0c `: before the character column
     THIRD + "[the capture ends before any response: not known whether it was answered]  CRC ok\n"
     "     4            -   - noise     1 byte of noise at offset 27: 0c\n"),
    (HEXDUMP_C[:145], "its 16 whole bytes are decoded",  # `... 80 00  |.....`: in the character column
     THIRD + "[the capture ends inside the response (5 of 11 bytes)]  CRC ok\n"
     "     4            -   - noise     5 bytes of noise at offset 27: 0c 03 06 80 00\n"),
]


@ENGINES
@pytest.mark.parametrize(("dump", "said", "shown"), DUMP_CUTS, ids=["xxd-byte", "xxd-column", "hexdump-C"])
def test_an_xxd_or_hexdump_c_dump_cut_mid_line(tmp_path: Path, pure: bool, dump: str, said: str, shown: str,
                                               monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # Before: the cut last line made the whole dump raw text (`111 bytes of noise`), exit 0.
    assert _decode(tmp_path, dump) == (0, PAIR + shown, (
        f"vw3-decode: warning: FILE line 2 is cut short (the input ends inside it, without a line end): {said}\n"))
    # Half a byte before the last number is no cut (the bytes after it would be wrong): no xxd dump, as before.
    status, _out, err = _decode(tmp_path, XXD.splitlines(keepends=True)[0] + "00000010: 0217 e4 0c0 3")
    assert (status, err.splitlines()[0]) == (0, "vw3-decode: warning: FILE: the input is text, but neither a hex "
                                                "dump nor Modbus ASCII: decoded as raw bytes")


# -- -w keeps what it wrote when a later line is refused (tshark -w keeps its packets) ----------------------

@ENGINES
def test_w_keeps_its_records_after_a_bad_line(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    written = tmp_path / "st.pcap"
    lines = _typo(P38 * 100, 1098)
    status, _out, err = run_cli(["-", "-w", str(written)], stdin=("\n".join(lines) + "\n").encode())
    assert (status, err) == (2, "vw3-decode: standard input line 1098: '2' is an odd number of hex digits\n")
    # Before: deleted. The 1097 lines before the bad one, but the last request, which awaited its answer.
    assert _records(written) == 1096
    # Two inputs, the second refused: the first one's records stay.
    first = tmp_path / "good.txt"
    first.write_text("\n".join(P38) + "\n")
    bad = tmp_path / "bad.txt"
    bad.write_text("\n".join(_typo(P38, 6)) + "\n")
    status, _out, err = run_cli(["-w", str(written), str(first), str(bad)])
    assert (status, err) == (2, f"vw3-decode: {bad} line 6: '2' is an odd number of hex digits\n")
    assert _records(written) == 12
    # A refused input with nothing written: no header-only file, as before.
    written.unlink()
    assert run_cli(["-w", str(written), str(bad)])[0] == 2
    assert not written.exists()


# -- times of day that do not exist ------------------------------------------------------------------------

@ENGINES
@pytest.mark.parametrize(("stamp", "why"), [
    ("99:99:99.000", "hour must be in 0..23"),
    ("24:00:00.000", "hour must be in 0..23"),
    ("10:60:00.000", "minute must be in 0..59"),
    ("10:00:60.010", "second must be in 0..59"),
    ("23:59:60.500", "second must be in 0..59"),  # no leap second: a date-time refuses it, clocks never show it
    ("10:00:60,010", "second must be in 0..59"),
])
def test_a_time_of_day_out_of_range(tmp_path: Path, pure: bool, stamp: str, why: str,
                                    monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    assert _decode(tmp_path, f"23:59:59.000 {REQUEST}\n{stamp} {ANSWER}\n") == (
        2, "", f"vw3-decode: FILE line 2: bad time of day {stamp!r}: {why}\n")
    assert _decode(tmp_path, f"Tx:000000-23:59:59.000-{REQUEST}\nRx:000001-{stamp}-{ANSWER}\n") == (
        2, "", f"vw3-decode: FILE line 2: bad time of day {stamp!r}: {why}\n")


@ENGINES
def test_dates_that_do_not_exist(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # Before: every line refused by the sniffer, so the log was its characters decoded as bytes, exit 0.
    assert _decode(tmp_path, f"2024-02-30 10:00:00.000 {REQUEST}\n2024-13-45 25:61:61.000 {ANSWER}\n") == (
        2, "", "vw3-decode: FILE line 1: bad timestamp '2024-02-30T10:00:00.000': day is out of range for month\n")


@ENGINES
def test_colon_hex_alone_is_no_time(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    # `99:99:99` alone is the bytes 99 99 99 (colon hex), not a time of day without data.
    assert _decode(tmp_path, "0C:03:20:D0:00:03:0E:EF\n99:99:99\n") == (0, (
        "     1            -  12 request   Read Holding Registers 8400..8402 (3) "
        "[the capture ends before any response: not known whether it was answered]  CRC ok\n"
        "     2            -   - noise     3 bytes of noise at offset 8: 99 99 99\n"), "")
    assert _decode(tmp_path, "23:59:59.999 0C:03:20:D0:00:03:0E:EF\n")[0] == 0


# -- standard input: one name -------------------------------------------------------------------------------

@ENGINES
def test_standard_input_has_one_name(pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    assert run_cli(["-"]) == (0, "", "vw3-decode: warning: standard input: the input is empty\n")
    assert run_cli(["-"], stdin=b"0C 03 20 D0 00 03 0E EF\nhello\n0C 03 20 D0 00 03 0E EF\n") == (
        2, "", "vw3-decode: standard input line 2: 'hello' is not hex\n")
    status, _out, err = run_cli(["-"], stdin=b"\x00" * 8)
    assert err == ("vw3-decode: warning: standard input: no valid Modbus RTU frame in 8 bytes (every item is noise "
                   "or a frame with a bad check): not a Modbus capture, or another format or line speed?\n")
