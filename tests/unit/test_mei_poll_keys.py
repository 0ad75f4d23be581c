"""--stats' poll cycle keeps FC43 (Read Device Identification) requests of different read device id codes
(01 basic, 02 regular, 03 extended, 04 one object) or object ids apart: each is its own poll, named as the
summary names what it asks (`basic, from object 0`), where all were one row without addresses before.
--json's rows give mei_type, read_code and object_id. Under the compiled engine (which hands FC43 over to
the Python stages; its key alike: accel/_stats.h request_key) and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from helpers import rtu, run_cli, use_engine
from lua_harness import write_pcap

ASKED = [(1, 0), (2, 0), (3, 0), (4, 5)]  # (read code, object id)
HEAD = "slave  function                             addresses                  count  period  jitter  misses"


def capture(tmp_path: Path) -> Path:
    records, time = [], 1000.0
    for cycle in range(3):
        for code, obj in ASKED:
            records.append((rtu(f"01 2B 0E {code:02X} {obj:02X}"), time))
            records.append((rtu(f"01 2B 0E {code:02X} 01 00 00 01 {obj:02X} 03 41 42 43"), time + 0.01))
            time += 0.1
    return write_pcap(tmp_path / "mei.pcap", records)


@pytest.mark.parametrize("pure", [False, True])
def test_poll_rows(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    use_engine(monkeypatch, pure)
    pcap = capture(tmp_path)
    status, out, err = run_cli(["--stats", str(pcap)])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    at = lines.index("Poll cycle (requests repeated 3 times or more)")
    assert lines[at + 1: at + 7] == [
        HEAD, "-" * len(HEAD),
        "    1  43 Encapsulated Interface Transport  basic, from object 0           3   400.0     0.0       0",
        "    1  43 Encapsulated Interface Transport  regular, from object 0         3   400.0     0.0       0",
        "    1  43 Encapsulated Interface Transport  extended, from object 0        3   400.0     0.0       0",
        "    1  43 Encapsulated Interface Transport  individual, from object 5      3   400.0     0.0       0",
    ]
    status, out, err = run_cli(["--stats", "--json", str(pcap)])
    rows = json.loads(out)["poll_cycle"]
    assert [(row["mei_type"], row["read_code"], row["object_id"], row["start"], row["count"]) for row in rows] == [
        (14, code, obj, None, 3) for code, obj in ASKED]


@pytest.mark.parametrize("pure", [False, True])
def test_diagnostics_rows_name_their_subfunction(tmp_path: Path, pure: bool, monkeypatch: pytest.MonkeyPatch) -> None:
    # FC8's poll rows showed the sub-function as an address in decimal (`11`, --json "start": 11): now as
    # the summary names it, and --json's "subfunction".
    use_engine(monkeypatch, pure)
    records, time = [], 1000.0
    for cycle in range(3):
        for sub in (0x0B, 0x0C):
            records += [(rtu(f"01 08 00{sub:02X} 0000"), time), (rtu(f"01 08 00{sub:02X} 0005"), time + 0.01)]
            time += 0.1
    pcap = write_pcap(tmp_path / "fc8.pcap", records)
    status, out, err = run_cli(["--stats", str(pcap)])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    at = lines.index("Poll cycle (requests repeated 3 times or more)")
    assert lines[at + 3: at + 5] == [
        "    1  8 Diagnostics  0Bh Return Bus Message Count                  3   200.0     0.0       0",
        "    1  8 Diagnostics  0Ch Return Bus Communication Error Count      3   200.0     0.0       0",
    ]
    status, out, err = run_cli(["--stats", "--json", str(pcap)])
    rows = json.loads(out)["poll_cycle"]
    assert [(row["subfunction"], row["start"]) for row in rows] == [(11, None), (12, None)]
