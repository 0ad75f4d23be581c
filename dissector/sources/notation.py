"""The ways people write a frame's bytes on a line, and which way a list of numbers is meant.

    0C 03 20 D0 00 03 0E EF           hex pairs, in groups of whole bytes (0C0320D0 000 3...)
    0x0C 0x03, 0x20 0xD0              C, C# and pymodbus: 0x5 is 05, 0x0C03 is 0C 03
    0C:03:20:D0:00:03:0E:EF           colon-separated (ESPHome and many device logs)
    0C-03-20-D0-00-03-0E-EF           dash-separated (C#'s BitConverter.ToString, .NET Modbus logs)
    [12, 3, 32, 208, 0, 3, 14, 239]   decimal lists (NModbus, Python and C# byte arrays)
    [0C][03][20][D0] or <0C><03>...   libmodbus's debug output (mbpoll -v): hex, a byte a bracket

Commas, and one pair of [ ] or { } around the list, are separators. A list is decimal when it cannot
be hex: some number has 1 or 3 digits (a hex byte has 2). A letter, a 0x, a colon, a dash or a group of
several bytes proves hex (and then a 1- or 3-digit number in the same list is a hex typo). Two-digit numbers alone prove nothing: they follow what the input has
shown so far. Before any proof a list without commas is hex (the hex dump's own notation) and one
with commas is refused, since `10, 20, 30` is as likely decimal. An input that shows both is
refused at the line that contradicts the first: reading on would decode wrong bytes without a word.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from dissector.errors import MalformedInput

HEX = "hex"
DECIMAL = "decimal"

_PREFIXED = re.compile(r"0[xX]([0-9A-Fa-f]{1,2}|(?:[0-9A-Fa-f]{2})+)")
_COLON = re.compile(r"[0-9A-Fa-f]{2}(?::[0-9A-Fa-f]{2})+|[0-9A-Fa-f]{2}(?:-[0-9A-Fa-f]{2})+")  # (one separator a token)
_GROUP = re.compile(r"(?:[0-9A-Fa-f]{2})+")
_SEPARATORS = re.compile(r"[\s,]+")
_BRACKETED = re.compile(r"(?:\[[0-9A-Fa-f]{2}\])+|(?:<[0-9A-Fa-f]{2}>)+")


class NotationError(MalformedInput):
    """A list of bytes that is no notation, or not the one the input uses."""


class RefusedList(NotationError):
    """A byte list in shape, refused for what it means: two-digit numbers with commas and nothing to
    say whether they are hex, a list that contradicts an earlier line, a decimal number over 255.
    Format detection takes such a line for a hex dump, so that reading it says why it is refused."""


def _problem(token: str) -> str:
    if re.fullmatch(r"[0-9A-Fa-f]+", token):
        return "an odd number of hex digits"
    if token.startswith("//"):  # a C-style note: the dump's comments are its own, and say so
        return "not hex (a comment starts with #)"
    return "not hex"


def _proof(token: str) -> str | None:
    """HEX or DECIMAL when the token alone says which, None for two decimal digits; error if neither."""
    if _PREFIXED.fullmatch(token) or _COLON.fullmatch(token):
        return HEX
    if token.isdigit() and token.isascii():
        if len(token) in (1, 3):
            return DECIMAL
        if len(token) == 2:
            return None
    if _GROUP.fullmatch(token):
        return HEX
    raise NotationError(f"{token!r} is {_problem(token)}")


def _hex_bytes(token: str) -> bytes:
    prefixed = _PREFIXED.fullmatch(token)
    if prefixed is not None:
        return bytes.fromhex(prefixed.group(1).zfill(2))
    return bytes.fromhex(token.replace(":", "").replace("-", ""))


def _decimal_byte(token: str) -> int:
    value = int(token)
    if value > 255:
        raise RefusedList(f"{token!r} is not a byte (0..255)")
    return value


def split_list(text: str) -> list[str]:
    """The numbers of a byte list: commas and spaces separate, one [ ] or { } around it is dropped."""
    body = text.strip()
    if body and all(_BRACKETED.fullmatch(word) for word in body.split()):  # (before a list's [ ] is dropped:
        return re.findall(r"[0-9A-Fa-f]{2}", body)                            # [01][03] would be 01][03)
    if body[:1] in ("[", "{") and body[-1:] in ("]", "}"):
        body = body[1:-1]
    return [token for token in _SEPARATORS.split(body) if token]


@dataclass(slots=True)
class Notation:
    """The notation of one input's byte lists: learned from the first proof, or given (`fixed`)."""

    kind: str | None = None
    fixed: bool = False
    learned: str = ""  # where the kind was learned, for the message when a later line contradicts it

    def read(self, text: str, where: str) -> bytes:
        """The bytes of one list; `where` ("line 3") names it in a later contradiction."""
        tokens = split_list(text)
        if not tokens:
            return b""
        proofs: dict[str, str] = {}
        for token in tokens:
            kind = _proof(token)
            if kind is not None:
                proofs.setdefault(kind, token)
        if self.fixed:
            self._fixed(proofs)
        elif len(proofs) == 2:  # decimal has no letters: a hex list with a digit missing or extra
            raise NotationError(f"{proofs[DECIMAL]!r} is {_problem(proofs[DECIMAL])}")
        kind = next(iter(proofs), None)
        if kind is not None:
            self._agree(kind, proofs[kind], where)
        elif self.kind is None:
            if "," in text:
                shown = text.strip()
                shown = shown if len(shown) <= 40 else shown[:40] + "..."
                raise RefusedList(
                    f"{shown!r} may be decimal or hex: write hex as 0x10 or without commas, "
                    "or give --format decimal or --format hex"
                )
            self.kind, self.learned = HEX, f"{where} (two-digit numbers without commas)"
        if self.kind == HEX:
            return b"".join(_hex_bytes(token) for token in tokens)
        return bytes(_decimal_byte(token) for token in tokens)

    def _fixed(self, proofs: dict[str, str]) -> None:
        if self.kind == HEX and DECIMAL in proofs:
            raise NotationError(f"{proofs[DECIMAL]!r} is {_problem(proofs[DECIMAL])}")
        if self.kind == DECIMAL and HEX in proofs:
            raise NotationError(f"{proofs[HEX]!r} is not a decimal byte (--format decimal)")

    def _agree(self, kind: str, token: str, where: str) -> None:
        if self.kind is None:
            self.kind, self.learned = kind, f"{where} ({token!r})"
            return
        if kind == self.kind:
            return
        raise RefusedList(f"{kind} {token!r}, but {self.learned} was read as {self.kind}: one notation an input")
