"""The README's `$ vw3-decode ...` examples are what vw3-decode prints: the shown lines are the real
output's, in order, and only a `...` line stands for lines left out (stdout, then stderr as a terminal
shows it after the run).
A change of output that leaves the README behind fails here, not in a user's terminal."""
from __future__ import annotations

import io
import re
import shlex

import pytest

from conftest import ROOT
from dissector.app.cli import Environment, run

README = (ROOT / "README.md").read_text(encoding="utf-8")
EXAMPLES = re.findall(r"```\n\$ vw3-decode (.*?)\n(.*?)```", README, re.S)


def test_the_readme_shows_examples() -> None:
    assert len(EXAMPLES) >= 4, [command for command, _ in EXAMPLES]


@pytest.mark.parametrize("command, shown", EXAMPLES, ids=[command for command, _ in EXAMPLES])
def test_an_example_is_what_vw3_decode_prints(command: str, shown: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(ROOT)
    out, err = io.StringIO(), io.StringIO()
    # stderr a terminal: the README shows what the person at it reads (profile auto's line).
    status = run(shlex.split(command), Environment(io.BytesIO(), out, err, stdout_isatty=False, stderr_isatty=True))
    assert status == 0, err.getvalue()
    printed = (out.getvalue() + err.getvalue()).splitlines()
    at, gap = 0, False  # gap: a `...` since the last line shown, so lines may be left out here
    for line in shown.splitlines():
        if line.strip() == "...":
            gap = True
            continue
        if gap:
            assert line in printed[at:], (line, printed[at:])
            at = printed.index(line, at)
        else:
            assert printed[at:at + 1] == [line], (line, printed[at:at + 3])
        at, gap = at + 1, False
