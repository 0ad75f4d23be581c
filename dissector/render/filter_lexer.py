"""The display filter's tokens (render/filters.py parses them), read as Wireshark 4.0 reads them: numbers
with exponents (13.5e-3), strings with \\x and octal escapes, byte strings (0c:03, 0c-03, 0c.03, 0c03) and
slices (raw[0:2]). What a literal means depends on the field it is compared with: parse_bytes and
the parser's parse_value read a token's text for that field."""
from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from dissector.render.filter_error import FilterError


@dataclass(slots=True)
class Token:
    kind: str  # name, number, bytes, string, char, slice, op, punct, keyword, reference (${slave}), end
    text: str
    value: Any
    position: int
    data: bytes | None = None  # a string's bytes, as Wireshark compares it with a bytes field


# A byte string: pairs of hex digits joined by one separator, as tshark's frame takes them, or a run of hex
# digits starting with a digit and holding a letter (0c03); 12-34 and 12.50 are numbers to a number field.
_BYTES = (r"[0-9A-Fa-f]{2}(?:[:.-][0-9A-Fa-f]{2})+(?![0-9A-Za-z_#:.-])"
          r"|[0-9][0-9A-Fa-f]*[A-Fa-f][0-9A-Fa-f]*(?![0-9A-Za-z_#:.+-])")  # (1e-3: a number)
_TOKEN = re.compile(
    r"""
    (?P<space>\s+)
  | (?P<slice>\[[^\]]*\])
  | (?P<bytes>""" + _BYTES + r""")
  | (?P<dashed>\d+-\d+)(?![0-9A-Za-z_#.])
  | (?P<number>(?:0[xX][0-9A-Fa-f]+|\d+\#[0-9A-Za-z_]+|-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)(?![0-9A-Za-z_#]))
  | (?P<string>[rR]?")
  | (?P<char>')
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*(?:\.[A-Za-z_][A-Za-z0-9_]*)*)
  | (?P<reference>\$\{[^}]*\})
  | (?P<layer>\#(?:\d+|\[[^\]]*\]))
  | (?P<op>===|!==|==|!=|~=|<=|>=|&&|\|\||<|>|!|&|~|[-+*/%])
  | (?P<punct>\.\.|[(){},])
    """,
    re.VERBOSE,
)
NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
_WORD_OPS = {
    "eq": "==", "ne": "!=", "all_ne": "!=", "any_ne": "~=", "all_eq": "===", "lt": "<", "le": "<=", "gt": ">",
    "ge": ">=",
}
_KEYWORDS = {"and", "or", "not", "in", "contains", "matches", "true", "false"}
_ESCAPES = {'"': '"', "\\": "\\", "n": "\n", "t": "\t", "r": "\r", "a": "\a", "b": "\b", "f": "\f", "v": "\v"}
_NUMERIC_ESCAPE = re.compile(r"x[0-9A-Fa-f]{1,2}|[0-7]{1,3}")


def _string(text: str, start: int) -> tuple[str, bytes, int]:
    """The string at `start` (its opening quote, or the r of a raw string r"..."): its text, its bytes
    (typed characters in UTF-8, each \\xhh or octal \\ooo escape the one byte it names, as Wireshark's)
    and where it ends. A raw string keeps its backslashes (r"\\s+" is the regular expression \\s+), and
    \\" in it does not end it, as tshark 4.0.17 reads one."""
    out: list[str] = []
    data = bytearray()
    raw = text[start] in "rR"
    i = start + 1 + raw
    while i < len(text):
        char = text[i]
        if char == '"':
            return "".join(out), bytes(data), i + 1
        if char == "\\":
            if i + 1 >= len(text):
                break
            if raw:
                out.append(text[i:i + 2])
                data += text[i:i + 2].encode()
                i += 2
                continue
            numeric = _NUMERIC_ESCAPE.match(text, i + 1)
            if numeric is not None:
                digits = numeric.group()
                code = int(digits[1:], 16) if digits[0] == "x" else int(digits, 8)
                if code > 0xFF:
                    raise FilterError(f"\\{digits} is more than one byte (\\377 at most)", text, i)
                out.append(chr(code))
                data.append(code)
                i = numeric.end()
                continue
            escaped = _ESCAPES.get(text[i + 1])
            if escaped is None:
                known = "\\\" \\\\ \\n \\t \\xhh \\ooo ..."
                raise FilterError(f"unknown escape \\{text[i + 1]} in a string ({known})", text, i)
            out.append(escaped)
            data += escaped.encode()
            i += 2
            continue
        out.append(char)
        data += char.encode()
        i += 1
    raise FilterError("string not closed (a \" is missing)", text, start)


# The escapes a character constant takes, as tshark 4.0.17 reads them (not \n, which it refuses)
_CHAR_ESCAPES = {"a": 7, "b": 8, "f": 12, "r": 13, "t": 9, "v": 11, "\\": 92, "'": 39, '"': 34}


def _char(text: str, start: int) -> tuple[int, int]:
    """The character constant at `start` (its opening quote): its value (a number, 'a' is 97, as
    Wireshark's) and where it ends; refused as tshark 4.0.17 refuses it."""
    i = start + 1
    while i < len(text) and text[i] != "'":
        i += 2 if text[i] == "\\" else 1
    if i >= len(text):
        raise FilterError("the final quote was missing from a character constant", text, start)
    inside, written = text[start + 1:i], text[start:i + 1]
    if not inside:
        raise FilterError("empty character constant", text, start)
    if inside[0] != "\\":
        if len(inside) > 1:
            raise FilterError(f"{written} is too long to be a valid character constant", text, start)
        if not " " <= inside <= "~":
            raise FilterError(f"{written}: a character constant is printable ASCII (write '\\xhh')", text,
                              start)
        return ord(inside), i + 1
    if inside[1:] in _CHAR_ESCAPES:
        return _CHAR_ESCAPES[inside[1:]], i + 1
    numeric = _NUMERIC_ESCAPE.match(inside, 1)
    if numeric is None:  # ('\n' too: tshark 4.0.17 refuses it)
        raise FilterError(f"{written} isn't a valid character constant", text, start)
    if numeric.end() < len(inside):
        raise FilterError(f"{written} is too long to be a valid character constant", text, start)
    digits = numeric.group()
    code = int(digits[1:], 16) if digits[0] == "x" else int(digits, 8)
    if code > 0xFF:
        raise FilterError(f"{written} is too large to be a valid character constant", text, start)
    return code, i + 1


def number(word: str, text: str, position: int) -> int | float:
    """0x8000, 16#8000 (IEC 61131-3 radix#digits, as the notes print values), 12, 1.5 or 13.5e-3; as
    Wireshark's, 0b1100 binary and 014 octal (a leading 0: vw3.slave == 014 is slave 12)."""
    if word[:2] in ("0x", "0X"):
        return int(word, 16)
    if word[:2] in ("0b", "0B"):
        try:
            return int(word[2:], 2)
        except ValueError:
            raise FilterError(f"{word}: not binary digits", text, position) from None
    if re.fullmatch(r"-?0\d+", word):
        try:
            return int(word, 8)
        except ValueError:
            raise FilterError(f"{word}: a leading 0 is octal (as in Wireshark), and 8 and 9 are no octal "
                              "digits", text, position) from None
    if "#" in word:
        radix, digits = word.split("#", 1)
        if radix not in ("2", "8", "16"):
            raise FilterError(f"{word}: the radix before # is 2, 8 or 16", text, position)
        try:
            return int(digits.replace("_", ""), int(radix))
        except ValueError:
            raise FilterError(f"{word}: {digits!r} are not base-{radix} digits", text, position) from None
    return float(word) if any(c in word for c in ".eE") else int(word)


def strtol(text: str) -> int | None:
    """`text` read as C's strtol(text, &end, 0) reads a whole number (a slice's offsets in tshark 4.0.17):
    a sign, then 0x hex, a leading 0 octal, or decimal; None when any of it is left unread."""
    match = re.fullmatch(r"([-+]?)(0[xX][0-9A-Fa-f]+|0[0-7]*|[1-9][0-9]*)", text)
    if match is None:
        return None
    sign, digits = match.groups()
    value = int(digits, 16) if digits[:2] in ("0x", "0X") else int(digits, 8) if digits[0] == "0" else int(digits)
    return -value if sign == "-" else value


def parse_bytes(token: Token) -> bytes | None:
    """The bytes an unquoted literal names for a bytes field, as tshark reads one: pairs of hex digits
    with one separator (0c:03, 0c-03, 0c.03), a run of pairs (0c03) or one digit (1: 01); None if not."""
    word = token.text
    if token.kind not in ("bytes", "number", "name", "dashed") or not word:
        return None
    if re.fullmatch(r"[0-9A-Fa-f]{2}(?:([:.-])[0-9A-Fa-f]{2}(?:\1[0-9A-Fa-f]{2})*)?", word):
        return bytes.fromhex(re.sub(r"[:.-]", "", word))
    if re.fullmatch(r"(?:[0-9A-Fa-f]{2})+|[0-9A-Fa-f]", word):
        return bytes.fromhex(word.rjust(2, "0"))
    if re.fullmatch(r"0[xX][0-9A-Fa-f]{2}", word):  # one byte (raw[0] == 0x0c), as tshark 4.0.17: not 0xc
        return bytes.fromhex(word[2:])
    return None


def _ends_value(token: Token) -> bool:
    """Does `token` end an operand, so that a - after it subtracts?"""
    return token.kind in ("name", "number", "char", "slice") or token.text in (")", "}")


def tokenize(text: str) -> list[Token]:
    tokens: list[Token] = []
    i = 0
    while i < len(text):
        match = _TOKEN.match(text, i)
        if match is None:
            if text[i] == "=":
                raise FilterError("a single = is not an operator: use == to compare", text, i)
            if text[i] == "#":  # (a layer: slave#1, slave#[1-2], as tshark 4.0.17 reads one)
                raise FilterError(f"expected digit or \"[\" after # (a layer, as slave#1), not "
                                  f"{text[i + 1:i + 2] or 'the end'!r}", text, i + 1)
            raise FilterError(f"unexpected character {text[i]!r}", text, i)
        group = match.lastgroup
        word = match.group()
        if group == "string":
            value, data, end = _string(text, i)
            tokens.append(Token("string", text[i:end], value, i, data))
            i = end
            continue
        if group == "char":
            code, end = _char(text, i)
            tokens.append(Token("char", text[i:end], code, i))
            i = end
            continue
        if group == "number" and word[0] == "-" and tokens and _ends_value(tokens[-1]):
            # slave -1: a subtraction, as tshark reads it (slave-1, a name tshark refuses, too)
            if tokens[-1].position + len(tokens[-1].text) == i and tokens[-1].kind == "name":
                raise FilterError(f"{tokens[-1].text}{word} is no field: put spaces around - to subtract",
                                  text, tokens[-1].position)
            tokens.append(Token("op", "-", "-", i))
            i += 1
            continue
        if group in ("number", "bytes", "dashed") and len(word) > 40:  # (keeps int() below its digit limit)
            raise FilterError("number too long", text, i)
        if group == "number":
            tokens.append(Token("number", word, number(word, text, i), i))
        elif group in ("bytes", "dashed", "slice", "layer"):  # (read by the field they are compared with)
            tokens.append(Token(group, word, word, i))
        elif group == "name":
            lowered = word.lower()
            if word in ("any", "all"):  # (quantifiers, lowercase only, as tshark 4.0.17's)
                tokens.append(Token("keyword", word, word, i))
            elif lowered in _WORD_OPS:
                tokens.append(Token("op", word, _WORD_OPS[lowered], i))
            elif lowered in _KEYWORDS:
                tokens.append(Token("keyword", word, lowered, i))
            else:
                tokens.append(Token("name", word, word, i))
        elif group == "reference":  # ${slave}: the field's value in the selected frame (filter_ops.py)
            tokens.append(Token(group, word, word[2:-1], i))
        elif group == "op":
            tokens.append(Token(group, word, "~=" if word == "!==" else word, i))
        elif group == "punct":
            tokens.append(Token(group, word, word, i))
        i = match.end()
    tokens.append(Token("end", "", None, len(text)))
    return tokens
