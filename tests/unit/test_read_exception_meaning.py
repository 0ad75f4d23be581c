"""p.38: exception 02 from the ATV71 to a read means every parameter read is non-existent or protected. Since
761369d the meaning of the code was 'address does not exist' for every function, so on p38_protection.pcap
(FC3 reads answered 02, explained register by register) the clause was in no meaning: not -V's 'Meaning on
this device', --json exception_meaning, the report's exception event, nor the plugin's expert info. Now the
meaning to a read (FC3, FC4, FC23) says it; to a write, 'address does not exist' alone
(test_atv71_write_exceptions). Engine and VW3_PURE_PYTHON=1; the plugin: test_lua_exception_info."""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from helpers import run_cli, use_engine

ROOT = Path(__file__).resolve().parents[2]
P38 = str(ROOT / "captures" / "p38_protection.pcap")
READ = "address does not exist (also: every parameter read is non-existent or protected)"


@pytest.mark.parametrize("pure", [False, True])
def test_p38_read_exceptions_say_the_clause(pure: bool, monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    use_engine(monkeypatch, pure)
    frames = [json.loads(line) for line in run_cli([P38, "--json"])[1].splitlines()]
    assert [(frame["frame"], frame["exception_meaning"]) for frame in frames if frame["kind"] == "exception"] == [
        (10, READ), (12, READ)]
    verbose = run_cli([P38, "-V", "-Y", "kind == \"exception\""])[1]
    assert [line.strip() for line in verbose.splitlines() if "Exception meaning on this device" in line] == [
        f"Exception meaning on this device: {READ}"] * 2
    status, out, err = run_cli([P38, "-Y", f'exception_meaning == "{READ}"', "-T", "fields", "-e", "frame"])
    assert (status, out, err) == (0, "10\n12\n", "")
    page = tmp_path / "p38.html"
    assert run_cli([P38, "--report", str(page)])[0] == 0
    data = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(encoding="utf-8")).group(1))
    assert [event[3] for event in data["events"] if event[1] == "exception"] == [
        f"exception 02 to function 3: {READ}"] * 2
