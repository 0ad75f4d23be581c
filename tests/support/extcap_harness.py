"""Helpers of the extcap tests (tests/integration/test_extcap.py): processes by command line, a tee
of the sniffer's terminal, dumpcap's part on a fifo, a process's output as it comes, pcapng records."""
from __future__ import annotations

import os
import select
import subprocess
import threading
import time
from pathlib import Path

from live_bus import Bus, open_pty

AS_DATA = 'uat:user_dlts:"User 0 (DLT=147)","data","0","","0",""'  # the record's bytes as `data`


def processes(marker: str) -> list[tuple[int, str]]:
    """Live processes whose command line holds `marker`."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit() or int(entry.name) == os.getpid():
            continue
        try:
            command = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
            state = (entry / "stat").read_text().split(")")[-1].split()[0]
        except OSError:
            continue
        if marker in command and state != "Z":
            found.append((int(entry.name), command))
    return found


def none_left(marker: str, seconds: float = 5.0) -> list[tuple[int, str]]:
    deadline = time.monotonic() + seconds
    while (left := processes(marker)) and time.monotonic() < deadline:
        time.sleep(0.05)
    return left


class Tee(threading.Thread):
    """The sniffer side of the bus copied to two pseudo-terminals: the same bytes for two sniffers."""

    def __init__(self, bus: Bus) -> None:
        super().__init__(daemon=True)
        self.source = bus.c_slave
        self.ends = [open_pty() for _ in range(2)]
        self.paths = [path for _, _, path in self.ends]

    def run(self) -> None:
        while True:
            try:
                ready, _, _ = select.select([self.source], [], [], 0.05)
                if ready:
                    data = os.read(self.source, 4096)
                    for master, _, _ in self.ends:
                        os.write(master, data)
            except (OSError, ValueError):
                return

    def close(self) -> None:
        for master, slave, _ in self.ends:
            for fd in (master, slave):
                try:
                    os.close(fd)
                except OSError:
                    pass


def pcapng_records(path: Path) -> tuple[str, list[tuple[float, bytes, str | None]]]:
    """(interface description, [(time, bytes, comment)]) of a pcapng file, as tshark reads it."""
    done = subprocess.run(["tshark", "-r", str(path), "-T", "fields", "-e", "frame.time_epoch", "-e", "data",
                           "-e", "frame.comment", "-e", "frame.interface_description", "-o", AS_DATA],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    records, description = [], ""
    for line in done.stdout.splitlines():
        stamp, data, comment, description = line.split("\t")
        records.append((float(stamp), bytes.fromhex(data), comment or None))
    return description, records


def holds(pid: int, path: str) -> bool:
    """Whether process `pid` has `path` open."""
    try:
        fds = list(Path(f"/proc/{pid}/fd").iterdir())
    except OSError:
        return False
    for fd in fds:
        try:
            if os.readlink(fd) == path:
                return True
        except OSError:
            pass
    return False


class Collector(threading.Thread):
    """A process's standard output as it comes."""

    def __init__(self, process: subprocess.Popen[str]) -> None:
        super().__init__(daemon=True)
        self.stream = process.stdout
        self.parts: list[str] = []
        self.start()

    def run(self) -> None:
        assert self.stream is not None
        for line in self.stream:
            self.parts.append(line)

    def text(self) -> str:
        return "".join(self.parts)


class Reader(threading.Thread):
    """dumpcap's part: reads the fifo until its end, or closes it when told (as Wireshark stops)."""

    def __init__(self, fifo: Path) -> None:
        super().__init__(daemon=True)
        self.fifo = fifo
        self.data = bytearray()
        self.hang_up = threading.Event()
        self.start()

    def run(self) -> None:
        fd = os.open(self.fifo, os.O_RDONLY | os.O_NONBLOCK)
        try:
            while not self.hang_up.is_set():
                if select.select([fd], [], [], 0.02)[0]:
                    piece = os.read(fd, 65536)
                    if not piece and self.data:
                        return
                    self.data.extend(piece)
        finally:
            os.close(fd)

    def started(self, timeout: float = 30) -> None:
        """Once the pcapng header is in: the extcap has its port open and writes."""
        deadline = time.monotonic() + timeout
        while not self.data and time.monotonic() < deadline:
            time.sleep(0.01)
        assert self.data, "the capture did not start"

    def close(self) -> None:
        self.hang_up.set()
        self.join(5)
        assert not self.is_alive()

