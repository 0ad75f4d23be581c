"""`vw3-decode FILE -w COPY` carries the capture's end into COPY (app/inputs.py CopyEnd).

A capture's end is its last record, empty or not (Source.recorded_until: live -w's closing record, another
interface's records, a frame's last record; a hex dump's last timed line): the last request is judged to it
('[no response]' past its --timeout). COPY writes an item a record, so without more its end was its last
item's time: FILE's '[no response]' became 'the capture ends before any response: not known' in COPY.
COPY now closes with a record of no byte at FILE's end when that is later than its last record, as live -w
does, and COPY decodes as FILE does: by the engine, VW3_PURE_PYTHON=1 and the plugin (tshark -2).

Decided: -Y keeps the closing record (the copy spans the capture it filtered: a request FILE -Y shows
'[no response]' stays so; tshark -Y -w drops the empty record, and makes it 'not known'); a -b ring's
closing record ends its last file (no file for it alone); -c N ends the copy at the Nth item (no closing
record, as tshark -c N -w); an untimed input (raw bytes) has no time to close at: no closing record, its
last request 'not known' in FILE and COPY alike.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from dissector.model import Stamp
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import PcapWriter
from live_bus import ROOT, read_pcap
from lua_harness import lua_errors, run_tshark

pytestmark = pytest.mark.integration
REQUEST = bytes.fromhex("010300000002C40B")  # slave 1 reads 0..1
ANSWER = bytes.fromhex("010304000100022A32")
T0 = 1_767_225_600_000_000  # us
# A poll answered, a request unanswered, and the closing record live -w wrote 1.5 s after it.
RECORDS = [(REQUEST, 0), (ANSWER, 10_000), (REQUEST, 1_000_000), (b"", 2_500_000)]
FIRST = [
    "     1     0.000000   1 request   Read Holding Registers 0..1 (2)  CRC ok",
    "     2     0.010000   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1, 10.0 ms]  CRC ok",
]
NO_RESPONSE = "     3     1.000000   1 request   Read Holding Registers 0..1 (2) [no response]  CRC ok"
NOT_KNOWN = ("     3     1.000000   1 request   Read Holding Registers 0..1 (2) [the capture ends before any "
             "response: not known whether it was answered]  CRC ok")
FIELDS = ["-T", "fields", "-E", "separator=;", "-e", "frame.time_relative", "-e", "vw3.kind",
          "-e", "vw3.response_frame", "-e", "vw3.unanswered", "-e", "vw3.note"]
PLUGIN = ["0.000000000;1;2;;", "0.010000000;2;;;", "1.000000000;1;;1;", "2.500000000;;;;"]


def capture(path: Path, records: list[tuple[bytes, int]] = RECORDS) -> Path:
    with path.open("wb") as stream:
        pcapng = path.suffix == ".pcapng"
        writer = PcapngWriter(stream, flush=False) if pcapng else PcapWriter(stream, flush=False)
        for data, micros in records:
            writer.write(data, Stamp((T0 + micros) * 1000))
    return path


def run(*arguments: object, pure: bool = False) -> list[str]:
    env = dict(os.environ)
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", *map(str, arguments)], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and not done.stderr, done.stderr
    return done.stdout.splitlines()


def plugin(path: Path) -> list[str]:
    result = run_tshark(path, *FIELDS)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize("source", ["pcap", "pcapng"])
@pytest.mark.parametrize("copy", ["pcap", "pcapng"])
@pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])
def test_copy_ends_where_the_capture_ends(tmp_path: Path, source: str, copy: str, pure: bool) -> None:
    original = capture(tmp_path / f"live.{source}")
    assert run(original, pure=pure) == [*FIRST, NO_RESPONSE]
    written = tmp_path / f"copy.{copy}"
    assert run(original, "-w", written, pure=pure) == []
    assert run(written, pure=pure) == [*FIRST, NO_RESPONSE]  # was NOT_KNOWN
    if copy == "pcap":
        assert [(round(time - T0 / 1e6, 6), data) for time, data in read_pcap(written)] == [
            (0.0, REQUEST), (0.01, ANSWER), (1.0, REQUEST), (2.5, b"")]


def test_the_plugin_reads_the_copy_as_the_capture(tmp_path: Path) -> None:
    original = capture(tmp_path / "live.pcap")
    written = tmp_path / "copy.pcap"
    run(original, "-w", written)
    assert plugin(original) == PLUGIN
    assert plugin(written) == PLUGIN  # was 1.000000000;1;;;the capture ends before any response: ...


def test_a_filtered_copy_keeps_the_end(tmp_path: Path) -> None:
    original = capture(tmp_path / "live.pcap")
    shown = run(original, "-Y", 'kind == "request"')
    assert shown == [FIRST[0], NO_RESPONSE]
    written = tmp_path / "requests.pcap"
    run(original, "-Y", 'kind == "request"', "-w", written)
    # Its answer is not in the copy: the first request is unanswered there (as tshark -Y -w makes it).
    assert run(written) == [
        "     1     0.000000   1 request   Read Holding Registers 0..1 (2) [no response]  CRC ok",
        "     2     1.000000   1 request   Read Holding Registers 0..1 (2) [no response]  CRC ok",
    ]
    assert [data for _time, data in read_pcap(written)] == [REQUEST, REQUEST, b""]


def test_a_ring_ends_with_the_closing_record(tmp_path: Path) -> None:
    """-b duration:0.5 splits on the records' times: the closing record 1.5 s after the last request goes
    into the file being written, not a file of its own; the ring read as one capture, and the ring copied
    to one file, say what the capture says."""
    original = capture(tmp_path / "live.pcap")
    run(original, "-w", tmp_path / "ring.pcap", "-b", "duration:0.5")
    files = sorted(tmp_path.glob("ring_*.pcap"))
    records = [[data for _time, data in read_pcap(path)] for path in files]
    assert records == [[REQUEST, ANSWER], [REQUEST, b""]]
    assert run(*files) == [*FIRST, NO_RESPONSE]
    joined = tmp_path / "joined.pcapng"
    run(*files, "-w", joined)
    assert run(joined) == [*FIRST, NO_RESPONSE]


def test_another_interface_is_the_end(tmp_path: Path) -> None:
    """A pcapng of two buses: bus A's last request waited as long as bus B's records went on (past its
    timeout); its copy keeps both buses and says the same of every frame."""
    path = tmp_path / "two.pcapng"
    with path.open("wb") as stream:
        writer = PcapngWriter(stream, flush=False, if_name="A")
        for name, data, micros in [("A", REQUEST, 0), ("A", ANSWER, 10_000), ("A", REQUEST, 1_000_000),
                                   ("B", REQUEST, 1_500_000), ("B", ANSWER, 2_600_000)]:
            writer.use_interface(name, None)
            writer.write(data, Stamp((T0 + micros) * 1000))
    decoded = run(path)
    assert decoded[3] == NO_RESPONSE
    written = tmp_path / "copy.pcapng"
    run(path, "-w", written)
    assert run(written) == [line.replace(str(path), str(written)) for line in decoded]


def test_a_pcap_copy_of_two_buses_says_it_joins_them(tmp_path: Path) -> None:
    """pcap has no interfaces: the copy holds bus A's records, then bus B's, one stream that decodes as one
    bus (B's request after A's, time going back). Said once, as the line speed pcap loses is (was silent)."""
    path = tmp_path / "two.pcapng"
    with path.open("wb") as stream:
        writer = PcapngWriter(stream, flush=False, if_name="A")
        for name, data, micros in [("A", REQUEST, 0), ("B", REQUEST, 500_000), ("A", ANSWER, 10_000)]:
            writer.use_interface(name, None)
            writer.write(data, Stamp((T0 + micros) * 1000))
    written = tmp_path / "joined.pcap"
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", str(path), "-w", str(written)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert (done.returncode, done.stdout) == (0, "")
    assert done.stderr == (
        f"vw3-decode: warning: -w {written}: pcap has no interfaces: the buses of {path} are written one "
        "after the other as one stream, which decodes as one bus (write pcapng, -F pcapng, to keep them "
        "apart)\n")
    assert [data for _time, data in read_pcap(written)] == [REQUEST, ANSWER, REQUEST]
    assert run(tmp_path / "joined.pcap")[2].startswith("     3     0.500000   1 request ")
    assert run(path, "-w", tmp_path / "kept.pcapng") == []  # (run: no warning for pcapng)


def test_a_frame_ends_in_its_last_line(tmp_path: Path) -> None:
    """A hex dump's last request in two timed lines, 300 ms apart: the capture ends at its second line
    (hexdump.StampedLines), in the copy too, where it is the two records it came in, each at its time (so
    the silence inside it stays: sources/trail.py; before, one record at its first byte's time, and a
    closing record of no byte at 1.3 s, lost the silence)."""
    dump = tmp_path / "split.txt"
    dump.write_text("1767225600.000 01 03 00 00 00 02 C4 0B\n1767225600.010 01 03 04 00 01 00 02 2A 32\n"
                    "1767225601.000 01 03 00 00\n1767225601.300 00 02 C4 0B\n")
    ends = ("the capture ends 300.0 ms after the request, within the 1000 ms timeout: not known whether it "
            "was answered")
    last = f"     3     1.000000   1 request   Read Holding Registers 0..1 (2) [{ends}]"
    assert run(dump)[2] == (f"{last} [warning: silence of 297.708 ms inside the frame before byte 4 (longer "
                            "than t1.5 = 0.859 ms at 19200 baud)]  CRC ok")
    written = tmp_path / "copy.pcap"
    run(dump, "-w", written)
    assert run(written) == run(dump)
    assert [(round(time - T0 / 1e6, 6), data.hex()) for time, data in read_pcap(written)] == [
        (0.0, REQUEST.hex()), (0.01, ANSWER.hex()), (1.0, "01030000"), (1.3, "0002c40b")]


def test_no_closing_record_after_count_or_untimed(tmp_path: Path) -> None:
    original = capture(tmp_path / "live.pcap")
    counted = tmp_path / "two.pcap"
    run(original, "-c", "2", "-w", counted)
    assert [data for _time, data in read_pcap(counted)] == [REQUEST, ANSWER]
    raw = tmp_path / "bus.bin"
    raw.write_bytes(REQUEST + ANSWER + REQUEST)
    untimed = ["     1            -   1 request   Read Holding Registers 0..1 (2)  CRC ok",
               "     2            -   1 response  Read Holding Registers 0..1 (2): 0=1 1=2 [#1]  CRC ok",
               "     3            -   1 request   Read Holding Registers 0..1 (2) [the capture ends before "
               "any response: not known whether it was answered]  CRC ok"]
    assert run(raw) == untimed
    written = tmp_path / "raw.pcap"
    run(raw, "-w", written)
    assert [data for _time, data in read_pcap(written)] == [REQUEST, ANSWER, REQUEST]
    assert run(written) == untimed
