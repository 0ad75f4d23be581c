"""FC5/FC6 answers echo their request (issue 26): one that does not gets a warning, as FC15/FC16's start
and quantity already do. Vectors from the issue: `01 05 00 4A FF 00 AD EC` (coil 74 ON) answered by
`01 05 00 47 00 00 7D DF` (coil 71 OFF); `01 06 00 37 00 63 78 2D` (register 55 = 99) answered by
`01 06 00 37 00 62 B9 ED` (= 98). The compiled path gives the same lines (tests/differential)."""
from __future__ import annotations

import json

from helpers import run_cli

COIL = ["--hex", "01 05 00 4A FF 00 AD EC", "--hex", "01 05 00 47 00 00 7D DF"]
REGISTER = ["--hex", "01 06 00 37 00 63 78 2D", "--hex", "01 06 00 37 00 62 B9 ED"]


def test_a_coil_answer_that_is_not_the_echo_is_warned() -> None:
    assert run_cli(COIL) == (0, (
        "     1            -   1 request   Write Single Coil 74 = ON  CRC ok\n"
        "     2            -   1 response  Write Single Coil 71 = OFF [#1] "
        "[warning: the response's address and value differ from the request's]  CRC ok\n"), "")


def test_a_register_answer_that_is_not_the_echo_is_warned() -> None:
    assert run_cli(REGISTER) == (0, (
        "     1            -   1 request   Write Single Register 55 = 99  CRC ok\n"
        "     2            -   1 response  Write Single Register 55 = 98 [#1] "
        "[warning: the response's value differs from the request's]  CRC ok\n"), "")
    status, out, _ = run_cli([*REGISTER, "--json"])
    assert json.loads(out.splitlines()[1])["warnings"] == ["the response's value differs from the request's"]


def test_only_the_address_differs_and_the_echo_is_quiet() -> None:
    # 01 06 00 38 00 63 48 2E: register 56 = 99, answered for 55
    status, out, _ = run_cli(["--hex", "01 06 00 38 00 63 48 2E", "--hex", "01 06 00 37 00 63 78 2D"])
    assert out.splitlines()[1].endswith("[warning: the response's address differs from the request's]  CRC ok")
    status, out, _ = run_cli(["--hex", "01 05 00 4A FF 00 AD EC", "--hex", "01 05 00 4A FF 00 AD EC"])
    assert out.splitlines()[1] == "     2            -   1 response  Write Single Coil 74 = ON [#1]  CRC ok"
