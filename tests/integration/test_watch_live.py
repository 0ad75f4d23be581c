"""--watch on a live serial line (a pseudo-terminal): the p.38 story told as the frames arrive."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time

from conftest import ROOT
from live_bus import open_pty

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
        "12 CHCF 3 IO (I/O profile) -> protected",
        "12 COP 2 Cd (command) -> protected (exception 02)",
    ]
    assert [text.split()[0] for _count, text in lines] == ["6", "10"]  # the frame numbers
    # Each change was printed before the next frame went out: frame 6 and frame 10 (1-based).
    assert [count for count, _text in lines] == [6, 10]
