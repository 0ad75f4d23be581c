"""The recorded request/response pairs of a minimalmodbus instrument test, as hex lines.

    python3 tests/corpus/minimalmodbus_responses.py test_omegacn7500.py > omegacn7500.records

minimalmodbus's tests replay traffic recorded from real instruments: `RESPONSES[request] = response`,
each a Python 2 byte string literal, in recording order, with a comment naming the call that made it.
This prints, for each pair in file order, `# <comment>` (the last comment above it, when it changed),
then `request_hex | response_hex`; the first line of a block of comments names the call.
Commented-out pairs are skipped. See SOURCES.md.
"""
from __future__ import annotations

import ast
import re
import sys

PAIR = re.compile(r"^RESPONSES\[(?P<request>'(?:[^'\\]|\\.)*')\]\s*=\s*(?P<response>'(?:[^'\\]|\\.)*')")


def pairs(text: str) -> list[tuple[str, bytes, bytes]]:
    out = []
    comment = ""
    in_block = False  # a block of comment lines: its first line names the call
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("#"):
            if not in_block and not stripped.startswith("#RESPONSES"):
                comment = stripped.lstrip("# ").strip()
            in_block = True
            continue
        in_block = False
        found = PAIR.match(stripped)
        if found:
            request = ast.literal_eval(found["request"]).encode("latin-1")
            response = ast.literal_eval(found["response"]).encode("latin-1")
            out.append((comment, request, response))
    return out


def main(argv: list[str]) -> int:
    last = None
    for comment, request, response in pairs(open(argv[1], encoding="utf-8").read()):
        if comment != last:
            print(f"# {comment}")
            last = comment
        print(f"{request.hex(' ')} | {response.hex(' ')}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
