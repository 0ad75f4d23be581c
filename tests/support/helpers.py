"""Test helpers: build RTU frames from hex with the *reference* CRC, decode to NDJSON dicts."""
from __future__ import annotations

import io

from dissector.app.cli import Environment, run
from dissector.protocol.crc import crc16_reference
from dissector.pipeline import dissect_bytes
from dissector.render.jsonout import item_to_dict


def rtu(hex_text: str) -> bytes:
    """Slave + PDU from hex, with the CRC appended by the reference algorithm (low byte first)."""
    body = bytes.fromhex(hex_text.replace(" ", ""))
    return body + crc16_reference(body).to_bytes(2, "little")


def decode(data: bytes, **options: object) -> list[dict]:
    return [item_to_dict(item) for item in dissect_bytes(data, **options)]


def hx(text: str) -> bytes:
    return bytes.fromhex(text.replace(" ", ""))


def run_cli(argv: list[str], stdin: bytes = b"", tty: bool = False) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    env = Environment(io.BytesIO(stdin), out, err, stdout_isatty=tty, stderr_isatty=False)
    status = run(argv, env)
    return status, out.getvalue(), err.getvalue()
