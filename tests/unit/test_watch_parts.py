"""--watch keeps, for a parameter that codes of two protocol tables set (an ATV71's 3201, read by FC4 and
written by FC6: the ATV71 reads both with one table), each table's last state, and parts the parameter into
them when profile `auto` takes the choice back (Watcher.rehomed, as the store parts its counts,
stats_store.ParameterTable._part): the next FC4 read compares with what FC4 read, the next FC3 read with what
FC6 wrote. Before, the state stayed a holding register's: the FC4 read had no old state (no line)."""
from __future__ import annotations

from dissector.devices.profiles import ONE_TABLE, TABLES
from dissector.model import Frame, Kind, Register
from dissector.render.history import CONFIRM, READ
from dissector.render.stats_store import table_homes
from dissector.render.watch import Watcher


def answer(number: int, function: int) -> Frame:
    return Frame(0, bytes([247, function]), None, Kind.RESPONSE, 247, function, 0, 0, number=number)


def test_a_state_two_tables_set_parts_when_the_choice_is_taken_back() -> None:
    changes = []
    watcher = Watcher(frozenset(), frozenset({3201}), changes.append)
    history = watcher.history
    history.tables = lambda slave: ONE_TABLE  # (the ATV71 chosen)
    watcher.state(answer(2, 4), Register(3201, 5), READ, False)
    watcher.state(answer(4, 6), Register(3201, 9), CONFIRM, True)
    history.tables = lambda slave: TABLES  # (taken back: `generic`)
    watcher.rehomed(247, table_homes(TABLES))
    watcher.state(answer(6, 4), Register(3201, 4), READ, True)
    watcher.state(answer(8, 3), Register(3201, 7), READ, True)
    assert [(change.frame, change.label, change.old, change.new) for change in changes] == [
        (4, None, "5", "9"), (6, "input 3201", "5", "4"), (8, None, "9", "7"),
    ]
