"""pymodbus debug logs as an input (hunt66b). A pymodbus program's log at DEBUG level
(pymodbus_apply_logging_config(logging.DEBUG)) was refused at its first line, `line 1: 'DEBUG' is not hex`
(exit 2), though the README reads Python logging's stamps and pymodbus's `0x..` notation.

The logs below are pymodbus 3.16.1's own, written on 7 December 2026: CLIENT an AsyncModbusTcpClient with the
RTU framer polling a ModbusTcpServer (RTU framer) in another process; SERIAL an AsyncModbusSerialClient on a
pseudo-terminal whose far end answered the read in two writes 20 ms apart (two recv lines, one frame); SYNC a
ModbusSerialClient (sync), which logs only its framer's buffers."""
from __future__ import annotations

from pathlib import Path

from dissector.sources.reader import detect_format, open_source
from helpers import run_cli

CLIENT = """\
2026-12-07 14:53:39,223 DEBUG base:56 Connecting to 127.0.0.1:15021.
2026-12-07 14:53:39,223 DEBUG transport:220 Connecting comm
2026-12-07 14:53:39,224 DEBUG transport:256 Connected to comm
2026-12-07 14:53:39,224 DEBUG transport:357 send: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 14:53:39,225 DEBUG transport:308 recv: 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xda 0xd4 extra data: 
2026-12-07 14:53:39,225 DEBUG base:76 Processing: 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xda 0xd4
2026-12-07 14:53:39,225 DEBUG decoders:86 decoded PDU function_code(3 sub -1) -> ReadHoldingRegistersResponse(dev_id=0, transaction_id=0, address=0, count=0, bits=[], registers=[0, 1, 2], status=1, retries=0) 
2026-12-07 14:53:39,225 DEBUG transport:357 send: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 14:53:39,225 DEBUG transport:308 recv: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30 extra data: 
2026-12-07 14:53:39,225 DEBUG base:76 Processing: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 14:53:39,225 DEBUG decoders:86 decoded PDU function_code(6 sub -1) -> WriteSingleRegisterResponse(dev_id=0, transaction_id=0, address=5, count=0, bits=[], registers=[1234], status=1, retries=0) 
"""
SERIAL = """\
2026-12-07 14:54:24,690 DEBUG base:56 Connecting to /dev/pts/0:0.
2026-12-07 14:54:24,690 DEBUG transport:220 Connecting comm
2026-12-07 14:54:24,691 DEBUG transport:256 Connected to comm
2026-12-07 14:54:24,691 DEBUG transport:357 send: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 14:54:24,691 DEBUG transport:308 recv: 0x7 0x3 0x6 0x0 0x0 extra data: 
2026-12-07 14:54:24,691 DEBUG base:76 Processing: 0x7 0x3 0x6 0x0 0x0
2026-12-07 14:54:24,691 DEBUG rtu:92 Frame - not ready
2026-12-07 14:54:24,691 DEBUG transport:316 extra:  unexpected data: 0x7 0x3 0x6 0x0 0x0
2026-12-07 14:54:24,711 DEBUG transport:308 recv: 0x0 0x1 0x0 0x2 0xda 0xd4 extra data: 0x7 0x3 0x6 0x0 0x0
2026-12-07 14:54:24,711 DEBUG base:76 Processing: 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xda 0xd4
2026-12-07 14:54:24,711 DEBUG decoders:86 decoded PDU function_code(3 sub -1) -> ReadHoldingRegistersResponse(dev_id=0, transaction_id=0, address=0, count=0, bits=[], registers=[0, 1, 2], status=1, retries=0) 
2026-12-07 14:54:24,712 DEBUG transport:357 send: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 14:54:24,712 DEBUG transport:308 recv: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30 extra data: 
2026-12-07 14:54:24,712 DEBUG base:76 Processing: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 14:54:24,712 DEBUG decoders:86 decoded PDU function_code(6 sub -1) -> WriteSingleRegisterResponse(dev_id=0, transaction_id=0, address=5, count=0, bits=[], registers=[1234], status=1, retries=0) 
"""
SYNC = """\
2026-12-07 14:54:14,318 DEBUG base:76 Processing: 0x7 0x3 0x6 0x0 0x0
2026-12-07 14:54:14,319 DEBUG rtu:92 Frame - not ready
2026-12-07 14:54:14,338 DEBUG base:76 Processing: 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xda 0xd4
"""


def _log(tmp_path: Path, text: str) -> str:
    path = tmp_path / "pymodbus.log"
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_client_log_decoded_with_its_times(tmp_path: Path) -> None:
    assert run_cli(["-n", _log(tmp_path, CLIENT)]) == (0, (
        "     1     0.000000   7 request   Read Holding Registers 0..2 (3)  CRC ok\n"
        "     2     0.001000   7 response  Read Holding Registers 0..2 (3): 0=0 1=1 2=2 [#1, 1.0 ms]  CRC ok\n"
        "     3     0.001000   7 request   Write Single Register 5 = 1234  CRC ok\n"
        "     4     0.001000   7 response  Write Single Register 5 = 1234 [#3, 0.0 ms]  CRC ok\n"), "")


def test_send_and_recv_lines_are_the_wire(tmp_path: Path) -> None:
    """A recv line is one read (part of a frame on a serial line): the frame ends where the program sends again
    or the log ends. Processing: (the framer's buffer) and extra data: (bytes held over) are not read again."""
    chunks = list(open_source(_log(tmp_path, SERIAL)))
    assert [(chunk.data.hex(" "), chunk.time.ns, chunk.boundary) for chunk in chunks] == [
        ("07 03 00 00 00 03 05 ad", 1796655264691000000, True),
        ("07 03 06 00 00", 1796655264691000000, False),
        ("00 01 00 02 da d4", 1796655264711000000, True),
        ("07 06 00 05 04 d2 1b 30", 1796655264712000000, True),
        ("07 06 00 05 04 d2 1b 30", 1796655264712000000, True),
    ]
    out = run_cli(["-n", _log(tmp_path, SERIAL)])[1].splitlines()
    assert out[1].startswith("     2     0.000000   7 response  Read Holding Registers 0..2 (3): 0=0 1=1 2=2 [#1,")


def test_a_pipe_told_by_pymodbus_line_format() -> None:
    """A polling program's log piped in as it is written (`... 2>&1 | vw3-decode -`): judged on its first
    lines, which carry no bytes yet."""
    first = "".join(CLIENT.splitlines(keepends=True)[:3])
    assert detect_format(first.encode(), False) == ("pymodbus", None)
    assert run_cli(["-n", "-"], stdin=CLIENT.encode())[1].count("CRC ok") == 4


def test_basic_config_lines_untimed(tmp_path: Path) -> None:
    """logging.basicConfig(level=logging.DEBUG)'s format: `DEBUG:pymodbus.logging:send: ...`, no time."""
    text = ("DEBUG:pymodbus.logging:send: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad\n"
            "DEBUG:pymodbus.logging:recv: 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xda 0xd4 extra data: \n")
    assert run_cli(["-n", _log(tmp_path, text)]) == (0, (
        "     1            -   7 request   Read Holding Registers 0..2 (3)  CRC ok\n"
        "     2            -   7 response  Read Holding Registers 0..2 (3): 0=0 1=1 2=2 [#1]  CRC ok\n"), "")


def test_sync_client_log_says_what_it_lacks(tmp_path: Path) -> None:
    path = _log(tmp_path, SYNC)
    assert run_cli(["-n", path]) == (0, "", (
        f"vw3-decode: warning: {path}: no send: or recv: line, only the framer's Processing: buffers, which repeat"
        " bytes and hold no request sent (pymodbus's sync clients log no more): log an async client or the server,"
        " or capture the line\n"))


def test_bad_byte_and_bad_stamp_refuse_their_line(tmp_path: Path) -> None:
    path = _log(tmp_path, CLIENT.replace("0x5 0xad", "0x5 0xadd"))
    assert run_cli(["-n", path]) == (2, "", f"vw3-decode: {path} line 4: '0xadd' is not a byte in pymodbus's 0x.."
                                              " notation\n")
    path = _log(tmp_path, CLIENT.replace("2026-12-07 14:53:39,224 DEBUG transport:357", "2026-02-30 14:53:39,224"
                                         " DEBUG transport:357"))
    status, out, err = run_cli(["-n", path])
    assert (status, out) == (2, "") and err.startswith(f"vw3-decode: {path} line 4: bad timestamp '2026-02-30T14:53:39,224'")


def test_last_line_cut_short(tmp_path: Path) -> None:
    """The log copied while written: `0xd` may be `0xda` cut, so the last number of an unended line is not read."""
    path = _log(tmp_path, CLIENT.splitlines(keepends=True)[3] + "2026-12-07 14:53:39,225 DEBUG transport:308 recv:"
                " 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xd")
    status, out, err = run_cli(["-n", path])
    assert status == 0 and out.splitlines()[1].startswith("     2     0.001000   - noise     9 bytes")
    assert err == (f"vw3-decode: warning: {path} line 2 is cut short (the input ends inside it, without a line end):"
                   " its 9 whole bytes are decoded, the rest ('0xd') is not\n")


ASCII = """\
2026-12-07 14:58:37,478 DEBUG transport:357 send: 0x3a 0x30 0x37 0x30 0x33 0x30 0x30 0x30 0x30 0x30 0x30 0x30 0x33 0x46 0x33 0xd 0xa
2026-12-07 14:58:37,483 DEBUG transport:308 recv: 0x3a 0x30 0x37 0x30 0x33 0x30 0x36 0x30 0x30 0x30 0x30 0x30 0x30 0x30 0x31 0x30 0x30 0x30 0x32 0x45 0x44 0xd 0xa extra data: 
2026-12-07 14:58:37,483 DEBUG transport:357 send: 0x3a 0x30 0x37 0x30 0x36 0x30 0x30 0x30 0x35 0x30 0x34 0x44 0x32 0x31 0x38 0xd 0xa
2026-12-07 14:58:37,483 DEBUG transport:308 recv: 0x3a 0x30 0x37 0x30 0x36 0x30 0x30 0x30 0x35 0x30 0x34 0x44 0x32 0x31 0x38 0xd 0xa extra data: 
"""


def test_ascii_framer_log(tmp_path: Path) -> None:
    """pymodbus's ASCII framer: its send:/recv: bytes are the characters on the wire, the mode read from them."""
    assert run_cli(["-n", _log(tmp_path, ASCII)]) == (0, (
        "     1     0.000000   7 request   Read Holding Registers 0..2 (3)  LRC ok\n"
        "     2     0.005000   7 response  Read Holding Registers 0..2 (3): 0=0 1=1 2=2 [#1, 5.0 ms]  LRC ok\n"
        "     3     0.005000   7 request   Write Single Register 5 = 1234  LRC ok\n"
        "     4     0.005000   7 response  Write Single Register 5 = 1234 [#3, 0.0 ms]  LRC ok\n"), "")


# pymodbus 3.7.4 (in a venv), an async serial server on a pseudo-terminal, the read request written in two parts
# 20 ms apart: its recv lines end `old_data:  addr=None`, not `extra data:`.
SERVER_37 = """\
2026-12-07 15:00:49,799 DEBUG transport:250 Awaiting connections server_listener
2026-12-07 15:00:49,800 INFO  async_io:301 Server listening.
2026-12-07 15:00:49,800 DEBUG transport:270 Connected to server
2026-12-07 15:00:50,808 DEBUG transport:322 recv: 0x7 0x3 0x0 old_data:  addr=None
2026-12-07 15:00:50,808 DEBUG async_io:123 Handling data: 0x7 0x3 0x0
2026-12-07 15:00:50,808 DEBUG base:92 Processing: 0x7 0x3 0x0
2026-12-07 15:00:50,808 DEBUG rtu:105 Short frame: 0x7 0x3 0x0 wait for more data
2026-12-07 15:00:50,823 DEBUG transport:322 recv: 0x0 0x0 0x3 0x5 0xad old_data:  addr=None
2026-12-07 15:00:50,823 DEBUG async_io:123 Handling data: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 15:00:50,823 DEBUG base:92 Processing: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 15:00:50,823 DEBUG decoders:103 decode PDU for 3
2026-12-07 15:00:50,823 DEBUG base:102 Frame advanced, resetting header!!
2026-12-07 15:00:50,823 DEBUG context:131 validate: fc-[3] address-1: count-3
2026-12-07 15:00:50,823 DEBUG context:144 getValues: fc-[3] address-1: count-3
2026-12-07 15:00:50,823 DEBUG transport:379 send: 0x7 0x3 0x6 0x0 0x1 0x0 0x2 0x0 0x3 0xd6 0xd4
2026-12-07 15:00:51,326 DEBUG transport:322 recv: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30 old_data:  addr=None
2026-12-07 15:00:51,326 DEBUG async_io:123 Handling data: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 15:00:51,326 DEBUG base:92 Processing: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 15:00:51,326 DEBUG decoders:103 decode PDU for 6
2026-12-07 15:00:51,326 DEBUG base:102 Frame advanced, resetting header!!
2026-12-07 15:00:51,326 DEBUG context:131 validate: fc-[6] address-6: count-1
2026-12-07 15:00:51,326 DEBUG context:156 setValues[6] address-6: count-1
2026-12-07 15:00:51,326 DEBUG context:144 getValues: fc-[6] address-6: count-1
2026-12-07 15:00:51,326 DEBUG transport:379 send: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
"""


def test_server_log_of_pymodbus_37(tmp_path: Path) -> None:
    assert run_cli(["-n", _log(tmp_path, SERVER_37)]) == (0, (
        "     1     0.000000   7 request   Read Holding Registers 0..2 (3) [warning: silence of 13.281 ms inside the frame"
        " before byte 3 (longer than t1.5 = 0.859 ms at 19200 baud)]  CRC ok\n"
        "     2     0.015000   7 response  Read Holding Registers 0..2 (3): 0=1 1=2 2=3 [#1, 15.0 ms]  CRC ok\n"
        "     3     0.518000   7 request   Write Single Register 5 = 1234  CRC ok\n"
        "     4     0.518000   7 response  Write Single Register 5 = 1234 [#3, 0.0 ms]  CRC ok\n"), "")


# pymodbus 2.5.3 (in a venv), its sync ModbusSerialClient on a pseudo-terminal, logged in a format of its users' (module
# and line padded): SEND:/RECV: lines, the RECV a whole answer read in two parts.
CLIENT_25 = """\
2026-12-07 15:06:44,212 MainThread      DEBUG    transaction    :139      Current transaction state - IDLE
2026-12-07 15:06:44,212 MainThread      DEBUG    transaction    :144      Running transaction 1
2026-12-07 15:06:44,212 MainThread      DEBUG    transaction    :273      SEND: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 15:06:44,212 MainThread      DEBUG    sync           :76       New Transaction state 'SENDING'
2026-12-07 15:06:44,212 MainThread      DEBUG    transaction    :287      Changing transaction state from 'SENDING' to 'WAITING FOR REPLY'
2026-12-07 15:06:44,238 MainThread      DEBUG    transaction    :375      Changing transaction state from 'WAITING FOR REPLY' to 'PROCESSING REPLY'
2026-12-07 15:06:44,238 MainThread      DEBUG    transaction    :297      RECV: 0x7 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2 0xda 0xd4
2026-12-07 15:06:44,238 MainThread      DEBUG    rtu_framer     :185      Getting Frame - 0x3 0x6 0x0 0x0 0x0 0x1 0x0 0x2
2026-12-07 15:06:44,238 MainThread      DEBUG    factory        :266      Factory Response[ReadHoldingRegistersResponse: 3]
2026-12-07 15:06:44,238 MainThread      DEBUG    rtu_framer     :107      Frame advanced, resetting header!!
2026-12-07 15:06:44,238 MainThread      DEBUG    transaction    :454      Adding transaction 7
2026-12-07 15:06:44,238 MainThread      DEBUG    transaction    :465      Getting transaction 7
2026-12-07 15:06:44,238 MainThread      DEBUG    transaction    :224      Changing transaction state from 'PROCESSING REPLY' to 'TRANSACTION_COMPLETE'
2026-12-07 15:06:44,238 MainThread      DEBUG    transaction    :139      Current transaction state - TRANSACTION_COMPLETE
2026-12-07 15:06:44,238 MainThread      DEBUG    transaction    :144      Running transaction 2
2026-12-07 15:06:44,238 MainThread      DEBUG    transaction    :273      SEND: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 15:06:44,238 MainThread      DEBUG    rtu_framer     :267      Changing state to IDLE - Last Frame End - 1796656004.238116, Current Time stamp - 1796656004.238718
2026-12-07 15:06:44,238 MainThread      DEBUG    rtu_framer     :275      Waiting for 3.5 char before next send - 2.005 ms
2026-12-07 15:06:44,240 MainThread      DEBUG    sync           :76       New Transaction state 'SENDING'
2026-12-07 15:06:44,241 MainThread      DEBUG    transaction    :287      Changing transaction state from 'SENDING' to 'WAITING FOR REPLY'
2026-12-07 15:06:44,241 MainThread      DEBUG    transaction    :375      Changing transaction state from 'WAITING FOR REPLY' to 'PROCESSING REPLY'
2026-12-07 15:06:44,241 MainThread      DEBUG    transaction    :297      RECV: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 15:06:44,241 MainThread      DEBUG    rtu_framer     :185      Getting Frame - 0x6 0x0 0x5 0x4 0xd2
2026-12-07 15:06:44,241 MainThread      DEBUG    factory        :266      Factory Response[WriteSingleRegisterResponse: 6]
2026-12-07 15:06:44,241 MainThread      DEBUG    rtu_framer     :107      Frame advanced, resetting header!!
2026-12-07 15:06:44,241 MainThread      DEBUG    transaction    :454      Adding transaction 7
2026-12-07 15:06:44,241 MainThread      DEBUG    transaction    :465      Getting transaction 7
2026-12-07 15:06:44,241 MainThread      DEBUG    transaction    :224      Changing transaction state from 'PROCESSING REPLY' to 'TRANSACTION_COMPLETE'
"""


def test_client_log_of_pymodbus_25(tmp_path: Path) -> None:
    assert run_cli(["-n", _log(tmp_path, CLIENT_25)]) == (0, (
        "     1     0.000000   7 request   Read Holding Registers 0..2 (3)  CRC ok\n"
        "     2     0.026000   7 response  Read Holding Registers 0..2 (3): 0=0 1=1 2=2 [#1, 26.0 ms]  CRC ok\n"
        "     3     0.026000   7 request   Write Single Register 5 = 1234  CRC ok\n"
        "     4     0.029000   7 response  Write Single Register 5 = 1234 [#3, 3.0 ms]  CRC ok\n"), "")
