"""The flow meter's real recordings (tests/corpus/flowmeter_*.records): their bursts, as a pcap, and as the
reads of a USB adapter cut anywhere, for tests/unit/test_corpus_flowmeter.py and
tests/integration/test_lua_flowmeter.py.

- Origin: sigrok-dumps, `uart/modbus_rtu/flowmeter/*.sr` (https://github.com/sigrokproject/sigrok-dumps,
  commit 894a0ba "modbus: Add a few flowmeter dumps.", Uwe Hermann, 2019-06-30): five logic-analyzer
  recordings at 4 MHz of one half-duplex line, probe `RXTX`: a master polling a flow meter at slave 247.
- Licence: public domain ("Unless noted otherwise, all dump files are hereby released into the public domain
  by their authors", sigrok-dumps README; the directory notes nothing else).
- Derivation: `python3 tests/corpus/sr_uart.py FILE.sr RXTX 9600 --records > FILE.records`. 9600 baud: the
  shortest pulses are 403..418 samples (104 us); characters start 11 bit times apart with no parity that
  holds (the ninth bit is the first stop bit): 8N2, which the 8N1 decode reads alike. Idle high (the UART
  side).
- What the sources state: the files' names: the master sets a target flow of 0, 15 and 20 litres a minute,
  which the recordings write by FC16 to registers 6..7 as an IEEE 754 float (0x41700000 = 15.0, 0x41A00000 =
  20.0). The recordings are their own reference otherwise: 402 frames, each request answered, CRC good,
  slave 247 only; tshark's mbrtu shows each record as one such frame.
"""
from __future__ import annotations

import random
from pathlib import Path

from lua_harness import write_pcap

CORPUS = Path(__file__).resolve().parents[1] / "corpus"
CAPTURES = {  # name: the target the master writes (l/min; None: no write)
    "flowmeter_target_0liter_per_min": 0.0, "flowmeter_target_15liter_per_min": 15.0,
    "flowmeter_target_20liter_per_min": 20.0, "flowmeter_target0_val0": None, "flowmeter_graph_tool": None,
}
T0 = 1_561_932_305  # (the dumps' date, 2019-06-30)
CHARACTER = 11 / 9600  # 9600 baud, 8N2 (see above)


def records(name: str) -> list[tuple[float, bytes]]:
    out = []
    for line in (CORPUS / f"{name}.records").read_text().splitlines():
        time, _, data = line.partition(" ")
        out.append((float(time), bytes.fromhex(data)))
    return out


def pcap(path: Path, reads: list[tuple[float, bytes]]) -> Path:
    return write_pcap(path, [(data, T0 + time) for time, data in reads])


def cut_anywhere(recorded: list[tuple[float, bytes]], seed: int) -> list[tuple[float, bytes]]:
    """The bytes as a USB adapter's reads of 1..64 bytes would give them, each stamped at its last byte."""
    timed = [(time + k * CHARACTER, value) for time, data in recorded for k, value in enumerate(data)]
    rng, reads, at = random.Random(seed), [], 0
    while at < len(timed):
        piece = timed[at : at + rng.randint(1, 64)]
        at += len(piece)
        reads.append((piece[-1][0] + rng.random() * 0.002, bytes(value for _time, value in piece)))
    return reads
