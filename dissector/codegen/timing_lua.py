"""The line's timing as the plugin takes it (lua/src/stream.lua, DATA.timing): written from
dissector/framing/timing.py and linespeed.py, the single statement of the serial line's timing facts (bits a
character, t1.5 and t3.5, their fixed values above 19200 baud, ASCII's silence limit, the speeds --baud takes)
and of how a silence inside a frame names its limit."""
from __future__ import annotations

import inspect
from typing import Any

from dissector.framing import linespeed, timing
from dissector.sources import pcap, reader


def timing_data() -> dict[str, Any]:
    from dissector.codegen.rules_lua import lua_format

    return {
        "default_baud": timing.DEFAULT_BAUD,
        "rtu_bits": timing.RTU_BITS_PER_CHAR,
        "ascii_bits": timing.ASCII_BITS_PER_CHAR,
        "fixed_above": timing.FIXED_TIMING_ABOVE,
        "fixed_t15": timing.FIXED_T15,
        "fixed_t35": timing.FIXED_T35,
        "ascii_max_silence": timing.ASCII_MAX_SILENCE,
        "min_baud": linespeed.MIN_BAUD,
        "max_baud": linespeed.MAX_BAUD,
        # (LineTiming.describe_limit: string.format patterns, the RTU one taking t1.5 in ms and the speed)
        "rtu_limit": lua_format(timing.RTU_LIMIT),
        "ascii_limit": timing.ASCII_LIMIT,
        # A capture's first record at the epoch is held (pcap.py EpochRecord) when one chunk holds it.
        # ... and timed only when the second record falls within day 0 (pcap.py within_day_zero).
        "day_zero_end": pcap.DAY_ZERO_END,
        "held_record_max": inspect.signature(reader.open_source).parameters["chunk_size"].default,
    }
