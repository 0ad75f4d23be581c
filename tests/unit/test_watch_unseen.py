"""--watch ADDRESS or CODE that the input never gives a register of is said at the end (Watcher.unseen, for
stderr), with the first request that carries that address as a bit (coils, discrete inputs: FC1/2/5/15, which
the parameter history --watch follows does not keep). Before, `--watch 172` on a capture reading coil 172
printed nothing and said nothing."""
from __future__ import annotations

from dissector.pipeline import dissect_bytes
from dissector.render.watch import Watcher

from helpers import rtu

COILS = (rtu("0101 00AC 0008") + rtu("0101 01 05")  # 1, 2: Read Coils 172..179
         + rtu("0105 00AC FF00") + rtu("0105 00AC FF00")  # 3, 4: Write Single Coil 172
         + rtu("010F 00AA 0004 01 0F") + rtu("010F 00AA 0004")  # 5, 6: Write Multiple Coils 170..173
         + rtu("0102 00B4 0001") + rtu("0102 01 01")  # 7, 8: Read Discrete Inputs 180
         + rtu("0103 00B5 0001") + rtu("0103 02 0007"))  # 9, 10: Read Holding Registers 181


def _unseen(data: bytes, addresses: set[int], by_add: bool = False) -> tuple[list[str], list[object]]:
    changes: list[object] = []
    watcher = Watcher(frozenset(), frozenset(addresses), changes.append)
    items = list(dissect_bytes(data))
    if by_add:  # (live: each item through add)
        for item in items:
            watcher.add(item)
    else:  # (a file: the run's items observed, the history fed by its owner)
        watcher.observe(items)
        for item in items:
            watcher.history.add(item)
        watcher.done()
    watcher.finish()
    return watcher.unseen(), changes


def test_a_coil_watched_is_said_with_where_it_is_a_bit() -> None:
    for by_add in (False, True):
        lines, changes = _unseen(COILS, {172, 171, 180, 181, 190}, by_add)
        assert changes == []
        assert lines == [
            "--watch 171: no register 171 in the capture (bit 171: Write Multiple Coils to slave 1 in frame #5; "
            "--watch follows registers only)",
            "--watch 172: no register 172 in the capture (bit 172: Read Coils to slave 1 in frame #1; "
            "--watch follows registers only)",
            "--watch 180: no register 180 in the capture (bit 180: Read Discrete Inputs to slave 1 in frame #7; "
            "--watch follows registers only)",
            "--watch 190: no register 190 in the capture",
        ]


def test_a_register_read_once_is_no_note() -> None:
    # 181 read once: no change to show, and nothing to say (it is in the capture)
    assert _unseen(COILS, {181})[0] == []


def test_a_broadcast_coil_write_names_no_slave() -> None:
    lines, _ = _unseen(rtu("0005 00AC FF00"), {172})
    assert lines == ["--watch 172: no register 172 in the capture (bit 172: Write Single Coil to every slave (broadcast) in "
                     "frame #1; --watch follows registers only)"]
