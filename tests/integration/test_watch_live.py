"""--watch on a live serial line (a pseudo-terminal): the p.38 story told as the frames arrive."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time

from conftest import ROOT
from live_bus import live_on_pty, open_pty

P38 = [
    "0C 03 20 D0 00 03 0E EF", "0C 03 06 80 00 00 03 00 02 17 E4",
    "0C 03 20 D0 00 03 0E EF", "0C 03 06 80 00 00 03 00 02 17 E4",
    "0C 03 20 D0 00 03 0E EF", "0C 03 06 80 00 80 00 00 02 CE 24",
    "0C 03 20 D0 00 03 0E EF", "0C 03 06 80 00 80 00 00 02 CE 24",
    "0C 03 20 D0 00 03 0E EF", "0C 83 02 51 32",
    "0C 03 20 D0 00 03 0E EF", "0C 83 02 51 32",
]


def test_live_watch_prints_each_change_when_it_happens() -> None:
    line, device_fd, path = open_pty()
    process = subprocess.Popen(
        [sys.executable, "-m", "dissector", "--live", path, "--baud", "115200", "--watch", "CHCF,COP"],
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )
    lines: list[tuple[int, str]] = []  # (frames written so far, line)
    written = [0]
    try:
        assert process.stderr is not None and process.stdout is not None
        assert "listening on" in process.stderr.readline()

        def collect() -> None:
            for text in process.stdout:  # type: ignore[union-attr]
                lines.append((written[0], text.rstrip("\n")))

        reader = threading.Thread(target=collect, daemon=True)
        reader.start()
        for index, frame in enumerate(P38):
            written[0] = index + 1
            os.write(line, bytes.fromhex(frame.replace(" ", "")))
            time.sleep(0.15)  # a poll every 0.3 s; each frame is closed by its length and CRC
        process.send_signal(signal.SIGINT)
        process.wait(timeout=10)
        reader.join(2)
    finally:
        if process.poll() is None:
            process.kill()
        os.close(line)
        os.close(device_fd)
    texts = [text.split(None, 2)[2] for _count, text in lines]  # without the frame and time columns
    assert texts == [
        "12 CHCF IO (I/O profile) -> protected",
        "12 COP Cd (command) -> protected (exception 02)",
    ]
    assert [text.split()[0] for _count, text in lines] == ["6", "10"]  # the frame numbers
    # Each change was printed before the next frame went out: frame 6 and frame 10 (1-based).
    assert [count for count, _text in lines] == [6, 10]


def run_live(*options: str, pause: float = 0.1) -> tuple[list[str], str, int]:
    """The p.38 frames written to a pseudo-terminal one by one; vw3-decode --live on its other end."""
    return live_on_pty([bytes.fromhex(frame.replace(" ", "")) for frame in P38], *options, pause=pause)


def test_live_filter_json_gives_exactly_the_two_exceptions() -> None:
    lines, err, _status = run_live("-Y", 'kind == "exception"', "--json")
    records = [json.loads(text) for text in lines]
    assert [(r["frame"], r["kind"], r["exception_code"], r["request_frame"]) for r in records] == [
        (10, "exception", 2, 9), (12, "exception", 2, 11)]
    assert [[(reg["address"], reg["status"]) for reg in r["registers"]] for r in records] == [
        [(8400, "non-existent"), (8401, "protected"), (8402, "protected")]] * 2


def test_live_honours_detail_hex_and_fields() -> None:
    lines, _err, _status = run_live("-Y", "frame == 6", "-V")
    assert lines[0].startswith("Frame 6:") and any("CHCF" in text and "protected" in text for text in lines)
    lines, _err, _status = run_live("-Y", "frame <= 2", "-x")
    assert lines[0].startswith("     1 ") and lines[1].startswith("0000  0c 03 20 d0 00 03 0e ef")
    lines, _err, _status = run_live("-T", "fields", "-e", "frame", "-e", "code", "-e", "status",
                                    "-Y", "code == \"COP\" and status == \"protected\"", "-E", "header=y")
    assert lines == ["frame\tcode\tstatus", "10\t,CHCF,COP\tnon-existent,protected,protected",
                     "12\t,CHCF,COP\tnon-existent,protected,protected"]


def test_live_refuses_a_bad_filter_or_watch_name_before_listening() -> None:
    line, device_fd, path = open_pty()
    try:
        for options, message in [
            (["-Y", 'code == "CHFC"'], "vw3-decode: code 'CHFC' is no parameter code of this run's maps"),
            (["-Y", "kind ="], "vw3-decode: a single = is not an operator"),
            (["--watch", "CHFC"], "vw3-decode: --watch CHFC: no map of this run has that parameter code"),
            (["-V", "--json"], "vw3-decode: -V (detail tree) and --json are two outputs: choose one"),
        ]:
            result = subprocess.run([sys.executable, "-m", "dissector", "--live", path, *options], cwd=ROOT,
                                    capture_output=True, text=True, timeout=30)
            assert result.returncode == 2 and result.stdout == "", options
            assert result.stderr.startswith(message) and "listening" not in result.stderr, result.stderr
    finally:
        os.close(line)
        os.close(device_fd)


def test_live_watch_says_what_it_never_heard_as_a_file_does(tmp_path) -> None:
    """A watched address or code the line never carried is said at the end on stderr, as a file's decode
    says it (was: nothing, with --live)."""
    lines, err, status = run_live("--watch", "CHCF,9999,HSP")
    assert status == 0
    assert [text.split(None, 2)[2] for text in lines] == ["12 CHCF IO (I/O profile) -> protected"]
    said = [text for text in err.splitlines() if "--watch" in text]
    assert said == ["vw3-decode: --watch 9999: no register 9999 in the capture",
                    "vw3-decode: --watch HSP: no register named HSP in the capture"]
    capture = tmp_path / "p38.bin"
    capture.write_bytes(b"".join(bytes.fromhex(frame.replace(" ", "")) for frame in P38))
    decoded = subprocess.run([sys.executable, "-m", "dissector", str(capture), "--watch", "CHCF,9999,HSP"],
                             cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert [text for text in decoded.stderr.splitlines() if "--watch" in text] == said
