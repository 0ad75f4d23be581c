"""The plugin shows the Modbus ASCII line ends of tests/unit/test_ascii_line_end_faults.py as vw3-decode does:
a line ended by CR at the end of the capture and one ended by CR CR LF are frames with a warning (before: noise),
and after 08/03 set ';' for slave 2, a request to it ending CR LF and a line of another slave ending CR ';' are
warned (before: no warning). Real tshark with -X lua_script:lua/vw3.lua, -2, the bytes in one record and a
line a record; the warnings are those of vw3-decode's summary lines."""
from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from lua_harness import ROOT, lua_errors, run_tshark, write_pcap

sys.path.insert(0, str(ROOT / "tests" / "unit"))
from test_ascii_line_end_faults import CASES  # noqa: E402

pytestmark = pytest.mark.integration

T0 = 1767225600.0
FIELDS = ["-T", "fields", "-E", "separator=|", "-E", "occurrence=a", "-e", "vw3.kind", "-e", "vw3.warning",
          "-e", "vw3.noise.reason"]
KINDS = {"request": "1", "response": "2"}


def expected(lines: list[str]) -> list[tuple[str, str]]:
    """(kind, warnings) of each of vw3-decode's summary lines, as the plugin's fields give them."""
    return [(KINDS[line.split()[3]], ",".join(re.findall(r"\[warning: ([^\]]*)\]", line))) for line in lines]


def tshark(pcap: Path) -> list[str]:
    result = run_tshark(pcap, *FIELDS)
    assert result.returncode == 0 and not lua_errors(result.stdout + result.stderr), result.stderr[-2000:]
    return result.stdout.splitlines()


@pytest.mark.parametrize("case", list(CASES))
def test_as_vw3_decode(case: str, tmp_path: Path) -> None:
    data, lines = CASES[case]
    wanted = expected(lines)
    one = write_pcap(tmp_path / "one.pcap", [(data, T0)])
    kinds = ",".join(kind for kind, _ in wanted)
    assert tshark(one) == [f"{kinds}|{','.join(warning for _, warning in wanted if warning)}|"]
    records = [b":" + part for part in data.split(b":")[1:]]  # (a line a record: no ':' inside these lines)
    each = write_pcap(tmp_path / "lines.pcap", [(record, T0 + 0.01 * at) for at, record in enumerate(records)])
    assert tshark(each) == [f"{kind}|{warning}|" for kind, warning in wanted]
