"""An answer later than --timeout, live as in the decode of the -w file (pairing.py Pairer._push_one).

Live shows a request unanswered once its timeout has passed (Pairer.expire, by the clock); the answer
that comes later was then 'response without a matching request in the capture' live, but 'response N ms
after request #1, later than the T ms timeout: not its answer' in the decode of the file, which learns that
the wait ended from the answer's own time. On a pseudo-terminal (tests/support/live_bus.py), the engine's
live path and VW3_PURE_PYTHON=1's, against the file decoded by both and by the plugin (tshark -2).
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from dissector.protocol.crc import with_crc
from live_bus import ROOT, run_live_on_pty
from lua_compare import compare
from lua_harness import lua_items, python_items

pytestmark = pytest.mark.integration
READ = with_crc(bytes.fromhex("010300000001"))
ANSWER = with_crc(bytes.fromhex("0103020007"))
LATE = re.compile(r"response (\d+\.\d) ms after request #1, later than the 200 ms timeout: not its answer")


def decoded(path: Path, env: dict[str, str]) -> list[dict]:
    done = subprocess.run([sys.executable, "-m", "dissector", "-n", "--json", "--timeout", "0.2", str(path)],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return [json.loads(text) for text in done.stdout.splitlines()]


@pytest.mark.parametrize("pure", [False, True], ids=["engine-live", "python-live"])
def test_an_answer_after_the_timeout(tmp_path: Path, pure: bool) -> None:
    env = dict(os.environ)
    env.pop("VW3_PURE_PYTHON", None)
    if pure:
        env["VW3_PURE_PYTHON"] = "1"
    path = tmp_path / "late.pcap"
    out, err, status = run_live_on_pty([(READ, 0.45), (ANSWER, 0.1)],
                                       ["-n", "--json", "--timeout", "0.2", "-w", str(path)], env)
    assert status == 0, err
    live = [json.loads(text) for text in out.decode().splitlines()]
    assert [(item["kind"], item.get("unanswered"), item["notes"]) for item in live] == [
        ("request", True, []), ("response", None, [])]
    assert len(live[1]["warnings"]) == 1 and LATE.fullmatch(live[1]["warnings"][0])
    assert decoded(path, {**env, "VW3_PURE_PYTHON": "1"}) == decoded(path, env) == live
    differences = compare(python_items(path, None, "--timeout", "0.2"), lua_items(path, "-o", "vw3.timeout_ms:200")[0])
    assert not differences, "\n".join(differences[:20])
