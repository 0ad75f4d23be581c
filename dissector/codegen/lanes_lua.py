"""What the plugin's quick lanes (lua/src/records.lua lane.answer, lane.request) take of the protocol table,
as data (DATA.lanes): which answers are a run of what their request asked for, and how long a writing
request is before its values. Derived here from the lifting and length rules (protocol/rules.py LIFTS,
protocol/table.py) rather than by the plugin as it loads.
"""
from __future__ import annotations

from typing import Any

from dissector.model import Kind
from dissector.protocol import table
from dissector.protocol.rules import LIFTS, ValueKind

RUNS = (ValueKind.REGISTERS, ValueKind.BITS)


def lanes_data() -> dict[str, Any]:
    """`run_answers`: the functions whose answer is a run of the registers or bits its request asked for,
    from its fourth byte (its lifting rule: the request's start, a count of the request's quantity by a
    unit, 0: bits; its length rule: that count in its third byte plus `extra`). `header_lengths`: the
    requests that write a block of values (a lifting rule that reads registers or bits, a length rule
    counting in one byte the values' bytes), by the length of their bytes before the values."""
    handlers = table.by_kind("handler")
    run_answers, header_lengths = {}, {}
    for code, request, response in table.known_layouts():
        answer = LIFTS.get(handlers[Kind.RESPONSE].get(code, ""))
        length = response.length
        if (answer is not None and answer.start == "request.start" and answer.count is not None
                and answer.count.of == "request.quantity" and answer.values is not None
                and answer.values.kind in RUNS and isinstance(length, table.Counted) and length.width == 1
                and length.position == 2):
            run_answers[code] = {"bits": answer.values.kind == ValueKind.BITS, "extra": length.extra,
                                 "unit": answer.count.unit}
        asked = LIFTS.get(handlers[Kind.REQUEST].get(code, ""))
        length = request.length
        if (asked is not None and asked.values is not None and asked.values.kind in RUNS
                and isinstance(length, table.Counted) and length.width == 1):
            header_lengths[code] = length.position + 1
    return {"run_answers": run_answers, "header_lengths": header_lengths}
