"""tshark -x style hex dump: offset, 16 bytes in hex, the printable ASCII."""
from __future__ import annotations


def hexdump(data: bytes, width: int = 16) -> str:
    lines = []
    for start in range(0, len(data), width):
        row = data[start : start + width]
        hex_part = " ".join(f"{byte:02x}" for byte in row)
        text = "".join(chr(byte) if 32 <= byte < 127 else "." for byte in row)
        lines.append(f"{start:04x}  {hex_part:<{width * 3 - 1}}   {text}")
    return "\n".join(lines)
