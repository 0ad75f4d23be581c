"""A pymodbus debug log of a client and a server in one process (both ends' transports log at DEBUG): each
frame is there twice, the sender's `send:` line and the other end's `recv:` line of the same bytes. Every frame
was decoded twice, the first of each pair `[no response]` and the second `[no request]` (hunt64-66 left open).
One bus carries each frame once: where the log shows both ends (a recv the server decoded as a request, one the
client decoded as a response, or their own lines: `Server listening.`, `Connecting to ...`), a recv run that
reads back the bytes sent since the last one is the other end's read, not a frame. Two real transactions with
the same bytes stay two; a one-end log (a client's FC6 echo, a server's two identical writes) is as before.

BOTH is pymodbus 3.16.1's log (7 December 2026) of an AsyncModbusTcpClient (RTU framer) reading holding
registers 0..2 of device 7 twice and writing register 5, and the ModbusTcpServer (RTU framer) it talks to, in one
asyncio loop; SERVER a ModbusTcpServer's own log of two identical writes from a client in another process."""
from __future__ import annotations

from pathlib import Path

from helpers import run_cli

BOTH = """\
2026-12-07 17:22:27,873 DEBUG transport:234 Awaiting connections server_listener
2026-12-07 17:22:27,882 INFO  base:91 Server listening.
2026-12-07 17:22:28,178 DEBUG base:56 Connecting to 127.0.0.1:15077.
2026-12-07 17:22:28,179 DEBUG transport:220 Connecting comm
2026-12-07 17:22:28,179 DEBUG transport:256 Connected to server
2026-12-07 17:22:28,180 DEBUG transport:256 Connected to comm
2026-12-07 17:22:28,180 DEBUG transport:357 send: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 17:22:28,180 DEBUG transport:308 recv: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad extra data: 
2026-12-07 17:22:28,180 DEBUG base:76 Processing: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 17:22:28,180 DEBUG decoders:86 decoded PDU function_code(3 sub -1) -> ReadHoldingRegistersRequest(dev_id=0, transaction_id=0, address=0, count=3, bits=[], registers=[], status=1, retries=0) 
2026-12-07 17:22:28,180 DEBUG transport:357 send: 0x7 0x3 0x6 0x0 0x0 0x0 0x0 0x0 0x1 0xcb 0x15
2026-12-07 17:22:28,180 DEBUG transport:308 recv: 0x7 0x3 0x6 0x0 0x0 0x0 0x0 0x0 0x1 0xcb 0x15 extra data: 
2026-12-07 17:22:28,180 DEBUG base:76 Processing: 0x7 0x3 0x6 0x0 0x0 0x0 0x0 0x0 0x1 0xcb 0x15
2026-12-07 17:22:28,181 DEBUG decoders:86 decoded PDU function_code(3 sub -1) -> ReadHoldingRegistersResponse(dev_id=0, transaction_id=0, address=0, count=0, bits=[], registers=[0, 0, 1], status=1, retries=0) 
2026-12-07 17:22:28,181 DEBUG transport:357 send: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 17:22:28,181 DEBUG transport:308 recv: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad extra data: 
2026-12-07 17:22:28,181 DEBUG base:76 Processing: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad
2026-12-07 17:22:28,181 DEBUG decoders:86 decoded PDU function_code(3 sub -1) -> ReadHoldingRegistersRequest(dev_id=0, transaction_id=0, address=0, count=3, bits=[], registers=[], status=1, retries=0) 
2026-12-07 17:22:28,181 DEBUG transport:357 send: 0x7 0x3 0x6 0x0 0x0 0x0 0x0 0x0 0x1 0xcb 0x15
2026-12-07 17:22:28,181 DEBUG transport:308 recv: 0x7 0x3 0x6 0x0 0x0 0x0 0x0 0x0 0x1 0xcb 0x15 extra data: 
2026-12-07 17:22:28,181 DEBUG base:76 Processing: 0x7 0x3 0x6 0x0 0x0 0x0 0x0 0x0 0x1 0xcb 0x15
2026-12-07 17:22:28,181 DEBUG decoders:86 decoded PDU function_code(3 sub -1) -> ReadHoldingRegistersResponse(dev_id=0, transaction_id=0, address=0, count=0, bits=[], registers=[0, 0, 1], status=1, retries=0) 
2026-12-07 17:22:28,181 DEBUG transport:357 send: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 17:22:28,181 DEBUG transport:308 recv: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30 extra data: 
2026-12-07 17:22:28,194 DEBUG base:76 Processing: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 17:22:28,194 DEBUG decoders:86 decoded PDU function_code(6 sub -1) -> WriteSingleRegisterRequest(dev_id=0, transaction_id=0, address=5, count=0, bits=[], registers=[1234], status=1, retries=0) 
2026-12-07 17:22:28,195 DEBUG transport:357 send: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 17:22:28,195 DEBUG transport:308 recv: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30 extra data: 
2026-12-07 17:22:28,195 DEBUG base:76 Processing: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 17:22:28,195 DEBUG decoders:86 decoded PDU function_code(6 sub -1) -> WriteSingleRegisterResponse(dev_id=0, transaction_id=0, address=5, count=0, bits=[], registers=[1234], status=1, retries=0) 
2026-12-07 17:22:28,195 DEBUG requesthandler:48 Handler for stream [server] has been canceled
2026-12-07 17:22:28,195 INFO  base:95 Server graceful shutdown.
"""
SERVER = """\
2026-12-07 17:23:41,868 DEBUG transport:234 Awaiting connections server_listener
2026-12-07 17:23:41,869 INFO  base:91 Server listening.
2026-12-07 17:23:42,479 DEBUG transport:256 Connected to server
2026-12-07 17:23:42,482 DEBUG transport:308 recv: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30 extra data: 
2026-12-07 17:23:42,482 DEBUG base:76 Processing: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 17:23:42,483 DEBUG decoders:86 decoded PDU function_code(6 sub -1) -> WriteSingleRegisterRequest(dev_id=0, transaction_id=0, address=5, count=0, bits=[], registers=[1234], status=1, retries=0) 
2026-12-07 17:23:42,483 DEBUG transport:357 send: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 17:23:42,490 DEBUG transport:308 recv: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30 extra data: 
2026-12-07 17:23:42,490 DEBUG base:76 Processing: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 17:23:42,490 DEBUG decoders:86 decoded PDU function_code(6 sub -1) -> WriteSingleRegisterRequest(dev_id=0, transaction_id=0, address=5, count=0, bits=[], registers=[1234], status=1, retries=0) 
2026-12-07 17:23:42,491 DEBUG transport:357 send: 0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30
2026-12-07 17:23:42,506 DEBUG transport:320 -> transport: received eof
2026-12-07 17:23:42,506 DEBUG transport:268 Connection lost server due to None
"""
ONCE = (
    "     1     0.000000   7 request   Read Holding Registers 0..2 (3)  CRC ok\n"
    "     2     0.000000   7 response  Read Holding Registers 0..2 (3): 0=0 1=0 2=1 [#1, 0.0 ms]  CRC ok\n"
    "     3     0.001000   7 request   Read Holding Registers 0..2 (3)  CRC ok\n"
    "     4     0.001000   7 response  Read Holding Registers 0..2 (3): 0=0 1=0 2=1 [#3, 0.0 ms]  CRC ok\n"
    "     5     0.001000   7 request   Write Single Register 5 = 1234  CRC ok\n"
    "     6     0.015000   7 response  Write Single Register 5 = 1234 [#5, 14.0 ms]  CRC ok\n")


def _log(tmp_path: Path, text: str) -> str:
    path = tmp_path / "pymodbus.log"
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_both_ends_in_one_log_show_each_frame_once(tmp_path: Path) -> None:
    assert run_cli(["-n", _log(tmp_path, BOTH)]) == (0, ONCE, "")
    assert run_cli(["-n", "-"], stdin=BOTH.encode()) == (0, ONCE, "")  # (read as it comes: a pipe)


def test_both_ends_told_by_their_decodes(tmp_path: Path) -> None:
    """The log started after both connected (no Server listening. nor Connecting to): the first read back is
    the server's decode of a request, with no client known yet; it is held until the client's first decoded
    response tells both ends, then passed over. Before, the first request was there twice."""
    lines = BOTH.splitlines(keepends=True)
    cut = "".join(lines[lines.index(next(line for line in lines if " send: " in line)):])
    assert run_cli(["-n", _log(tmp_path, cut)]) == (0, ONCE, "")
    assert run_cli(["-n", "-"], stdin=cut.encode()) == (0, ONCE, "")


def test_a_gateway_keeps_the_bytes_it_forwards(tmp_path: Path) -> None:
    """A one-process gateway (its server end reads a client's FC6 write from another process, its client end
    forwards the exact bytes to the device, whose echo it reads and passes back): four frames, the device's echo
    among them, though the log shows both ends and each recv after the first reads back what was sent before it.
    Its first recv read what no send gave: not a log of both ends of one link."""
    write = "0x7 0x6 0x0 0x5 0x4 0xd2 0x1b 0x30"
    log = (f"2026-12-07 17:30:00,000 INFO  base:91 Server listening.\n"
           f"2026-12-07 17:30:00,001 DEBUG base:56 Connecting to 127.0.0.1:15078.\n"
           f"2026-12-07 17:30:01,000 DEBUG transport:308 recv: {write} extra data: \n"
           f"2026-12-07 17:30:01,000 DEBUG decoders:86 decoded PDU function_code(6 sub -1) -> "
           f"WriteSingleRegisterRequest(dev_id=0, address=5, registers=[1234])\n"
           f"2026-12-07 17:30:01,001 DEBUG transport:357 send: {write}\n"
           f"2026-12-07 17:30:01,020 DEBUG transport:308 recv: {write} extra data: \n"
           f"2026-12-07 17:30:01,020 DEBUG decoders:86 decoded PDU function_code(6 sub -1) -> "
           f"WriteSingleRegisterResponse(dev_id=0, address=5, registers=[1234])\n"
           f"2026-12-07 17:30:01,021 DEBUG transport:357 send: {write}\n")
    assert run_cli(["-n", _log(tmp_path, log)]) == (0, (
        "     1     0.000000   7 request   Write Single Register 5 = 1234  CRC ok\n"
        "     2     0.001000   7 response  Write Single Register 5 = 1234 [#1, 1.0 ms]  CRC ok\n"
        "     3     0.020000   7 request   Write Single Register 5 = 1234  CRC ok\n"
        "     4     0.021000   7 response  Write Single Register 5 = 1234 [#3, 1.0 ms]  CRC ok\n"), "")


def test_one_end_logs_keep_their_echoes(tmp_path: Path) -> None:
    """A server's log of two identical FC6 writes: four frames, two requests each echoed."""
    assert run_cli(["-n", _log(tmp_path, SERVER)]) == (0, (
        "     1     0.000000   7 request   Write Single Register 5 = 1234  CRC ok\n"
        "     2     0.001000   7 response  Write Single Register 5 = 1234 [#1, 1.0 ms]  CRC ok\n"
        "     3     0.008000   7 request   Write Single Register 5 = 1234  CRC ok\n"
        "     4     0.009000   7 response  Write Single Register 5 = 1234 [#3, 1.0 ms]  CRC ok\n"), "")


def test_a_read_back_in_two_reads_is_the_other_end_too(tmp_path: Path) -> None:
    """On a serial line the server may read the request in two recv lines (as test_pymodbus_log's SERIAL): the
    run of both is the read-back of the one send."""
    first = "2026-12-07 17:22:28,180 DEBUG transport:308 recv: 0x7 0x3 0x0 0x0 0x0 0x3 0x5 0xad extra data: \n"
    split = ("2026-12-07 17:22:28,180 DEBUG transport:308 recv: 0x7 0x3 0x0 0x0 extra data: \n"
             "2026-12-07 17:22:28,180 DEBUG rtu:92 Frame - not ready\n"
             "2026-12-07 17:22:28,180 DEBUG transport:308 recv: 0x0 0x3 0x5 0xad extra data: 0x7 0x3 0x0 0x0\n")
    assert BOTH.count(first) == 1
    assert run_cli(["-n", _log(tmp_path, BOTH.replace(first, split, 1))]) == (0, ONCE, "")
