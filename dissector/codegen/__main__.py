"""python3 -m dissector.codegen: write every generated file; --check: exit 1 naming the stale ones.

The generated files are checked in (a build or a Wireshark install needs no Python step):
  dissector/accel/_tables.h   the compiled summary path's per-code tables (codegen/c.py)
  lua/vw3.lua, the assembly of lua/src/*.lua with, between its GENERATED markers, the plugin's data
      (codegen/lua.py) and, between the RULES markers inside them, the lifting rules, layouts,
      confirmations and texts of data/modbus.toml (codegen/rules_lua.py) its modules interpret, and the
      layouts' readers and the lifting rules' handlers written out from them (codegen/decode_lua.py)
"""
from __future__ import annotations

import argparse
import sys

from dissector.errors import GenerateError

try:
    from dissector.codegen import c, lua, rules_lua
except ValueError as error:  # data/modbus.toml: a rule, layout or TOML the tables cannot be made from
    print(f"error: {error}", file=sys.stderr)
    raise SystemExit(2) from None


def stale() -> list[str]:
    """The generated files that differ from what the package's tables and data give now."""
    out = []
    if c.current_header() != c.render_header():
        out.append(str(c.HEADER))
    if lua.current_block() != lua.render_block() or not rules_lua.current_in(lua.PLUGIN):
        out.append(str(lua.PLUGIN))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m dissector.codegen", description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 when a generated file is stale")
    args = parser.parse_args(argv)
    try:
        if args.check:
            for path in stale():
                print(f"{path}: stale; run python3 -m dissector.codegen", file=sys.stderr)
            return 1 if stale() else 0
        for path, changed in ((c.HEADER, c.write_header()), (lua.PLUGIN, lua.write_block())):
            print(f"{path}: {'updated' if changed else 'up to date'}")
    except (OSError, GenerateError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
