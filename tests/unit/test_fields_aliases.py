"""-T fields -e takes the other names -Y takes and -G fields lists (`exception_code ... (alias: exception)`):
`-e exception` is the exception code's column, headed as asked. Under the engine and VW3_PURE_PYTHON=1."""
from __future__ import annotations

import pytest

from helpers import run_cli, use_engine

ARGV = ["--hex", "0C 03 20 D0 00 03 0E EF", "--hex", "0C 83 02 51 32", "-T", "fields", "-E", "header=y"]


@pytest.mark.parametrize("pure", [False, True])
def test_exception_alias_column(monkeypatch: pytest.MonkeyPatch, pure: bool) -> None:
    use_engine(monkeypatch, pure)
    status, out, err = run_cli([*ARGV, "-e", "frame", "-e", "exception", "-e", "exception_code"])
    assert (status, out) == (0, "frame\texception\texception_code\n1\t\t\n2\t2\t2\n"), err
    status, out, err = run_cli([*ARGV, "-e", "frame", "-e", "exception", "-Y", "exception == 2"])
    assert (status, out) == (0, "frame\texception\n2\t2\n"), err


ENERGY_MAP = """address,code,name,unit,scale,access,enum,bits,signed,source,type,order
106,ENE,Energy,kWh,0.1,R,,,,,uint32,
"""
# Reads of ENE (uint32 at 106..107): 70000 (7000.0 kWh)
ENERGY_READ = ["--hex", "07 03 00 6a 00 02 e4 71", "--hex", "07 03 04 00 01 11 70 c0 47"]


@pytest.mark.parametrize("pure", [False, True])
def test_words_is_a_register_key_of_e_and_y(monkeypatch: pytest.MonkeyPatch, pure: bool, tmp_path) -> None:
    """`words` (README: 2 on a 32-bit value's first register, 0 on its second) is a register key as --json
    has it and the plugin's vw3.reg.words: -e lists it, -Y tests it."""
    use_engine(monkeypatch, pure)
    energy = tmp_path / "energy.csv"
    energy.write_text(ENERGY_MAP)
    argv = ["--map", str(energy), *ENERGY_READ]
    status, out, err = run_cli([*argv, "-T", "fields", "-e", "frame", "-e", "address", "-e", "words"])
    # (the request names 106 and 107 without values: `address` lists them, as -Y tests them; no words)
    assert (status, out) == (0, "1\t106,107\t\n2\t106,107\t2,0\n"), err
    status, out, err = run_cli([*argv, "-Y", "words == 2", "-T", "fields", "-e", "frame"])
    assert (status, out) == (0, "2\n"), err
