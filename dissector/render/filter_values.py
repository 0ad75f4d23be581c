"""What a literal of a display filter means for a value of a given tshark type (-G fields' FT_UINT8,
FT_RELATIVE_TIME...: render/glossary.py field_type), as tshark 4.0.17 reads one: a time takes seconds
written in decimals only, an unsigned field no number past its width, a character constant ('a', '\\x0c')
is the number of that character. render/filters.py and render/filter_expr.py read literals with it."""
from __future__ import annotations

import re
from typing import Any

TIME_TYPES = ("FT_RELATIVE_TIME", "FT_ABSOLUTE_TIME")
# Seconds as tshark 4.0.17 takes them for a time (1.5, 014 is 14, -1): no exponent, no hex, 9 decimals at most
TIME_LITERAL = re.compile(r"[-+]?\d+(?:\.\d{1,9})?")
_TYPE_NAMES = {"FT_RELATIVE_TIME": "time", "FT_ABSOLUTE_TIME": "date and time",
               "FT_DOUBLE": "decimal number", "FT_STRING": "text", "FT_BYTES": "byte string",
               "FT_BOOLEAN": "true/false", "FT_NONE": "structure", "FT_FRAMENUM": "frame number"}


def kind_of(ftype: str) -> str:
    """int, float, time, str, bytes, bool or none: what arithmetic and comparisons a tshark type allows."""
    if ftype.startswith("FT_UINT") or ftype.startswith("FT_INT") or ftype == "FT_FRAMENUM":
        return "int"
    return {"FT_DOUBLE": "float", "FT_RELATIVE_TIME": "time", "FT_ABSOLUTE_TIME": "time", "FT_STRING": "str",
            "FT_BYTES": "bytes", "FT_BOOLEAN": "bool"}.get(ftype, "none")


def type_name(ftype: str) -> str:
    """`an unsigned 8-bit number (FT_UINT8)`, `a text (FT_STRING)`: a type said to a reader."""
    if ftype.startswith("FT_UINT"):
        return f"an unsigned {ftype[7:]}-bit number ({ftype})"
    word = _TYPE_NAMES.get(ftype, "value")
    return f"{'an' if word[0] in 'aeiou' else 'a'} {word} ({ftype})"


def time_literal(text: str) -> float | None:
    """The seconds a literal names for a time, None when tshark 4.0.17 refuses it (1e-3, 0x1, .5)."""
    return float(text) if TIME_LITERAL.fullmatch(text) else None


def uint_limit(ftype: str) -> int | None:
    """The largest value of an unsigned type (FT_UINT8: 255), which tshark takes as a literal for it."""
    if ftype == "FT_FRAMENUM":
        return 0xFFFFFFFF
    if ftype.startswith("FT_UINT") and ftype[7:].isdigit():
        return (1 << int(ftype[7:])) - 1
    return None


def wire_size(ftype: str) -> int:
    """len() of a value of this type, as tshark 4.0.17 gives it for a number: the bytes of an integer
    type (FT_UINT16: 2, FT_FRAMENUM: 4), 0 for a decimal number, a time or a true/false."""
    if ftype == "FT_FRAMENUM":
        return 4
    limit = uint_limit(ftype)
    return 0 if limit is None else limit.bit_length() // 8


def bool_literal(token: Any, text: str, field: str) -> bool:
    """What a literal means for a true/false field (FT_BOOLEAN), as tshark 4.0.17 reads it: true or false
    in any case, quoted or not (crc_ok == "TRUE"), a whole number or a character, true unless 0
    (crc_ok == 2, 0x10, '\\0'); a negative number, a decimal or another text refused as tshark refuses them."""
    from dissector.render.filter_error import FilterError
    from dissector.render.filter_lexer import number

    if token.kind == "keyword" and token.value in ("true", "false"):
        return token.value == "true"
    if token.kind == "string" and token.value.lower() in ("true", "false"):
        return token.value.lower() == "true"
    value = token.value
    if token.kind == "bytes" and token.text[:2] in ("0b", "0B"):  # (0b10 is read as bytes first)
        value = number(token.text, text, token.position)
    elif token.kind not in ("number", "char"):
        value = None
    if isinstance(value, int) and value < 0:
        raise FilterError(f"{field} is true or false: it takes no negative number (tshark: FT_BOOLEAN "
                          "cannot -)", text, token.position)
    if not isinstance(value, int) or value >= 1 << 64:
        raise FilterError(f"{token.text} cannot be found among the possible values for {field}: true, false "
                          "or a whole number (0 is false, any other true)", text, token.position)
    return value != 0


def unsigned_type(ftype: str) -> bool:
    """An unsigned integer type (FT_UINT16, a frame number), which tshark 4.0.17 compares with no negative number."""
    return ftype.startswith("FT_UINT") or ftype == "FT_FRAMENUM"


def negative_for_unsigned(field: str, value: Any) -> bool:
    """Is `value` a negative number for an unsigned field (slave > -1)? tshark 4.0.17 reads the - as an
    operation whose signed result compares with no unsigned value: ==, <, >, in, ~= never hold, while
    != (none is equal) and === (none differs) hold wherever the field is."""
    from dissector.render.glossary import field_type

    if not isinstance(value, (int, float)) or isinstance(value, bool) or value >= 0:
        return False
    return unsigned_type(field_type(field))
