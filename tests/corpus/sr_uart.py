"""Bytes from a sigrok session file (.sr): a plain UART decode of one logic channel.

    python3 tests/corpus/sr_uart.py FILE.sr CHANNEL BAUD [--parity none|even|odd] [--invert] [--records]

A .sr file is a zip holding `metadata` (probe names, samplerate) and `logic-1-N` chunks of samples,
`unitsize` bytes a sample, bit k of a sample being probe k+1. The decoder is the textbook one (sigrok's
own UART decoder does the same for these settings): on a falling edge of an idle (high) line, sample
each bit at its middle (start + 1.5, 2.5, ... bit times), 8 data bits LSB first, the parity bit if any,
then the stop bit; a byte whose stop bit reads low (a framing error: a break, a line that falls when its
driver lets go) is kept, as a UART hands it on. With --records, the bytes are printed one line a
burst: a new line wherever the line stayed idle for --gap characters or more (1.5: the spec's limit
inside a frame), as a serial tap's reads would separate them; each line `time_in_seconds hex bytes`.

This is how tests/corpus/wizmodbus_bus.txt was made from sigrok-dumps uart/modbus_rtu/wizmodbus (see
SOURCES.md); it is kept in the repository so that the derivation can be checked and repeated.
"""
from __future__ import annotations

import argparse
import configparser
import sys
import zipfile


def samples(path: str) -> tuple[bytes, int, int, dict[str, int]]:
    """(samples, unitsize, samplerate in Hz, probe name -> bit) of a .sr file's logic channels."""
    with zipfile.ZipFile(path) as archive:
        meta = configparser.ConfigParser()
        meta.read_string(archive.read("metadata").decode())
        device = meta["device 1"]
        rate_text = device["samplerate"].split()
        scale = {"Hz": 1, "kHz": 1_000, "MHz": 1_000_000, "GHz": 1_000_000_000}[rate_text[1]]
        rate = int(float(rate_text[0]) * scale)
        unit = int(device.get("unitsize", "1"))
        base = device["capturefile"]
        names = sorted((name for name in archive.namelist() if name.startswith(base + "-")),
                       key=lambda name: int(name.rsplit("-", 1)[1]))
        data = b"".join(archive.read(name) for name in names)
        probes = {value: int(key[5:]) - 1 for key, value in device.items() if key.startswith("probe")}
    return data, unit, rate, probes


def uart(
    data: bytes, unit: int, bit: int, rate: int, baud: int, parity: str = "none", invert: bool = False
) -> list[tuple[float, int]]:
    """(time of the start bit in seconds, byte) of every character on channel `bit`; `invert`: the
    probe sits on an RS-232 line (idle low at logic level)."""
    flip = 1 if invert else 0
    level = [((data[i * unit + bit // 8] >> (bit % 8)) & 1) ^ flip for i in range(len(data) // unit)]
    per_bit = rate / baud
    extra = 0 if parity == "none" else 1
    out: list[tuple[float, int]] = []
    i, n = 1, len(level)
    while i < n:
        if level[i - 1] == 1 and level[i] == 0:  # a start bit begins
            value = 0
            for k in range(8):
                at = int(i + (1.5 + k) * per_bit)
                if at >= n:
                    return out
                value |= level[at] << k
            out.append((i / rate, value))
            i = int(i + (9 + extra + 0.5) * per_bit)  # the middle of the stop bit: wait for the next fall
            continue
        i += 1
    return out


def bursts(chars: list[tuple[float, int]], baud: int, gap: float, bits: int = 10) -> list[tuple[float, bytes]]:
    """Characters grouped where the line was idle for `gap` characters (`bits` bits each) or more."""
    char = bits / baud
    groups: list[tuple[float, bytearray]] = []
    last = None
    for time, value in chars:
        if last is None or time - last > char + gap * char:
            groups.append((time, bytearray()))
        groups[-1][1].append(value)
        last = time
    return [(time, bytes(group)) for time, group in groups]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument("channel", help="probe name (metadata) or bit number")
    parser.add_argument("baud", type=int)
    parser.add_argument("--parity", choices=("none", "even", "odd"), default="none")
    parser.add_argument("--records", action="store_true")
    parser.add_argument("--invert", action="store_true", help="an RS-232 line: idle reads low")
    parser.add_argument("--gap", type=float, default=1.5, help="idle characters that end a record (default 1.5)")
    args = parser.parse_args(argv)
    data, unit, rate, probes = samples(args.file)
    bit = probes[args.channel] if args.channel in probes else int(args.channel)
    chars = uart(data, unit, bit, rate, args.baud, args.parity, args.invert)
    if args.records:
        bits = 10 if args.parity == "none" else 11
        for time, group in bursts(chars, args.baud, args.gap, bits):
            print(f"{time:.6f} {group.hex(' ')}")
    else:
        print(bytes(value for _time, value in chars).hex(" "))
    return 0


if __name__ == "__main__":
    sys.exit(main())
