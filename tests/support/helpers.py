"""Test helpers: build RTU frames from hex with the *reference* CRC, decode to NDJSON dicts."""
from __future__ import annotations

import io
import os
import struct
import subprocess
import sys
import time
from pathlib import Path

from dissector.app.cli import Environment, run
from dissector.framing.ascii import AsciiFramer
from dissector.model import Chunk
from dissector.protocol.crc import crc16_reference
from dissector.pipeline import dissect_bytes
from dissector.render.jsonout import item_to_dict


def rtu(hex_text: str) -> bytes:
    """Slave + PDU from hex, with the CRC appended by the reference algorithm (low byte first)."""
    body = bytes.fromhex(hex_text.replace(" ", ""))
    return body + crc16_reference(body).to_bytes(2, "little")


def write_rtu(path: Path, frames: list[str]) -> Path:
    """A raw capture of RTU frames given as hex (rtu: their CRC appended), one after the other."""
    path.write_bytes(b"".join(rtu(frame) for frame in frames))
    return path


def stats_section(out: str, title: str = "Parameters") -> list[str]:
    """The lines of one --stats section, from under its title to the blank line after it."""
    lines = out.splitlines()
    start = lines.index(title) + 1
    return lines[start : lines.index("", start)]


def decode(data: bytes, **options: object) -> list[dict]:
    return [item_to_dict(item) for item in dissect_bytes(data, **options)]


def hx(text: str) -> bytes:
    return bytes.fromhex(text.replace(" ", ""))


def run_cli(argv: list[str], stdin: bytes = b"", tty: bool = False) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    env = Environment(io.BytesIO(stdin), out, err, stdout_isatty=tty, stderr_isatty=False)
    status = run(argv, env)
    return status, out.getvalue(), err.getvalue()


def fed_piece_by_piece(args: list[str], pieces: list[bytes], pure: bool) -> str:
    """vw3-decode ARGS (engine, or the Python stages: `pure`) in a process whose standard input gets `pieces`
    a read each, 0.3 s apart, so the decode is no further than the frames fed (a taken-back choice is seen
    as a live line sees it); its standard output."""
    root = Path(__file__).resolve().parents[2]
    env = {key: value for key, value in os.environ.items() if key != "VW3_PURE_PYTHON"}
    env["PYTHONPATH"] = str(root)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    process = subprocess.Popen([sys.executable, "-m", "dissector", *args], cwd=root, env=env,
                               stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert process.stdin is not None
    for index, piece in enumerate(pieces):
        if index:
            time.sleep(0.3)  # (a piece a read, so the annotator is no further than the frames counted)
        process.stdin.write(piece)
        process.stdin.flush()
    out, err = process.communicate(timeout=60)
    assert process.returncode == 0, err
    return out.decode()


def write_9600_tap(path: object, t0: float = 1767225600.0) -> None:
    """A pcapng whose interface says 9600 8E1 (as `vw3-decode --live -w` writes it), three ATV71 reads of
    8401 (CHCF), each request read in two pieces: 1.2 ms of silence inside the first (below t1.5 =
    1.719 ms at 9600 baud, above 0.859 ms at 19200), 2 ms inside the second (above both), none in the
    third. Silences are after the first piece's 4 characters at 9600 baud (4.583 ms)."""
    from dissector.render.pcapngwriter import PcapngWriter

    request, response = rtu("0C 03 20 D1 00 01"), rtu("0C 03 02 0003")
    character = 11 / 9600
    with open(path, "wb") as stream:  # type: ignore[call-overload]
        writer = PcapngWriter(stream, if_name="/dev/ttyUSB0", if_description=(
            "serial port /dev/ttyUSB0, 9600 baud, 8 data bits, even parity, 1 stop bit (9600 8E1)"))
        for index, silence in enumerate((0.0012, 0.002, 0.0)):
            start = t0 + 0.2 * index
            writer.write(request[:4], start)
            writer.write(request[4:], start + 4 * character + silence)
            writer.write(response, start + 8 * character + silence + 0.015)
        writer.close()


def use_engine(monkeypatch: object, pure: bool) -> None:
    """Run what follows under VW3_PURE_PYTHON=1 (`pure`) or under the compiled engine, which must be built:
    a differential test that quietly ran Python twice would prove nothing."""
    if pure:
        monkeypatch.setenv("VW3_PURE_PYTHON", "1")  # type: ignore[attr-defined]
        return
    monkeypatch.delenv("VW3_PURE_PYTHON", raising=False)  # type: ignore[attr-defined]
    from dissector.accel import fastsummary

    assert fastsummary.available() and fastsummary.built(), "the compiled engine is not built"


def decode_frames(frames: list[bytes], tmp_path: object, monkeypatch: object, pure: bool, *options: str) -> str:
    """vw3-decode's output of `frames` written as one raw capture, by the engine or the Python stages (`pure`)."""
    use_engine(monkeypatch, pure)
    capture = tmp_path / "frames.bin"  # type: ignore[operator]
    capture.write_bytes(b"".join(frames))
    status, out, err = run_cli([str(capture), *options])
    assert status == 0, err
    return out


def decode_counting_frames(argv: list[str], monkeypatch: object, pure: bool, stdin: bytes = b"") -> tuple[str, list[int]]:
    """`vw3-decode argv`'s output (stdout then stderr, exit 0 asserted) and the numbers of the frames the
    compiled engine's frames path (accel/framespath.py) framed: none under VW3_PURE_PYTHON=1."""
    from dissector.accel import framespath

    use_engine(monkeypatch, pure)
    framed: list[int] = []
    make = framespath._Frames._frames

    def counting(self: framespath._Frames, records: bytes) -> None:
        accept = self.accept
        self.accept = lambda items: (framed.extend(item.number for item in items), accept(items))
        try:
            make(self, records)
        finally:
            self.accept = accept

    monkeypatch.setattr(framespath._Frames, "_frames", counting)  # type: ignore[attr-defined]
    stdout, stderr = io.StringIO(), io.StringIO()
    assert run(argv, Environment(io.BytesIO(stdin), stdout, stderr, False, False)) == 0
    monkeypatch.setattr(framespath._Frames, "_frames", make)  # type: ignore[attr-defined]  # (the next call wraps the original)
    return stdout.getvalue() + stderr.getvalue(), framed


def engine_output_as_python(argv: list[str], monkeypatch: object, stdin: bytes = b"") -> tuple[str, list[int]]:
    """The output of `vw3-decode argv` (asserted byte-identical under the engine and VW3_PURE_PYTHON=1) and
    the numbers of the frames the engine framed."""
    engine, framed = decode_counting_frames(argv, monkeypatch, pure=False, stdin=stdin)
    reference, none = decode_counting_frames(argv, monkeypatch, pure=True, stdin=stdin)
    assert none == []
    assert engine == reference, argv
    return engine, framed


def ascii_items(data: bytes, size: int | None = None) -> list[tuple[str, int, bytes, list[str]]]:
    """What the ASCII framer makes of `data` fed whole, or in chunks of `size` bytes: (kind, offset, raw,
    warnings) an item, so a test can check the framing does not depend on where the reads end."""
    chunks = [data] if size is None else [data[at : at + size] for at in range(0, len(data), size)]
    framer, out = AsciiFramer(), []
    for chunk in chunks:
        out += framer.feed(Chunk(chunk))
    out += framer.finish()
    return [(type(item).__name__, item.offset, item.raw, getattr(item, "warnings", [])) for item in out]


def pcapng_packets(path: Path, origin: int) -> list[tuple[int, bytes, list[str]]]:
    """(microseconds from `origin`, bytes, comments) of each packet block of a little-endian pcapng in us."""
    data, position, found = path.read_bytes(), 0, []
    while position < len(data):
        kind, total = struct.unpack_from("<II", data, position)
        if kind == 6:
            _interface, high, low, captured, _original = struct.unpack_from("<IIIII", data, position + 8)
            body = position + 28
            options, comments = body + captured + (-captured % 4), []
            while options < position + total - 4:
                code, length = struct.unpack_from("<HH", data, options)
                if code == 0:
                    break
                comments.append(data[options + 4 : options + 4 + length].decode())
                options += 4 + length + (-length % 4)
            found.append(((high << 32 | low) - origin, data[body : body + captured], comments))
        position += total
    return found
