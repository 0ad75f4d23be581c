"""Differential fuzz of the compiled summary path against the Python stages.

    python3 bench/fastsummary_fuzz.py [SECONDS] [FIRST_SEED] [--stats]

Random sessions of transactions of every public code (ATV71 addresses, 16#8000 values, the CHCF/CMD
bits_depend case, FC8 Return Query Data echoes of any size (found by a CRC scan) and other sub-functions, coils up to and past the spec limits, ON/OFF and other coil values, retries, unanswered
requests, exceptions to every code the compiled path shows, other function codes, noise, bit flips, dropped and
inserted bytes, stray 00 bytes), cut into random chunks, decoded by both paths with the ATV71 annotator,
with none, with profile `auto` and with the SEL-749M profile (PLC-style addresses): every line must be equal. A mismatch is
reduced to a minimal reproducer; one where the Python framer alone disagrees with itself when the stream
is cut differently is reported as such. tests/differential/test_fastsummary.py holds a bounded version of this.
With --stats it compares --stats instead: the report and the tables counted by the engine (and the
Python stages for what it hands back) against the Python stages' alone (tests/differential/test_fast_stats.py).
"""
from __future__ import annotations

import argparse
import random
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "tests"), str(ROOT / "tests" / "support"), str(ROOT / "tests" / "differential")]

from dissector.model import Chunk  # noqa: E402
from dissector.pipeline import Dissector  # noqa: E402
from dissector.devices.build import build_annotator  # noqa: E402
from dissector.render.summary import summary_line  # noqa: E402
from helpers import rtu  # noqa: E402
from test_fastsummary import fast_lines, python_lines  # noqa: E402
from test_fast_stats import compiled_stats, python_stats  # noqa: E402

STATS = "--stats" in sys.argv


def py_split(data: bytes, annotator: object, splits: list[int]) -> list[str]:
    """The Python stages alone, fed the same chunks."""
    dissector = Dissector(annotate=annotator)  # type: ignore[arg-type]
    cuts = [0, *sorted(set(splits)), len(data)]
    items = []
    for start, end in zip(cuts, cuts[1:]):
        items += dissector.feed(Chunk(data[start:end]))
    items += dissector.finish()
    return [summary_line(item) for item in items]


ADDR = [8400, 8401, 8402, 8501, 3201, 3104, 8410, 0, 65534, 65535, 8500, 8502]
VALS = [0, 1, 3, 5, 7, 0x8000, 0xFFFF, 0x000F, 296, 0x0637, 150, 2, 0x7FFF, 0x20]
SLAVES = [12, 12, 12, 12, 12, 1, 3, 247, 0, 248]
CLEAN = 0.85  # share of transactions drawn from the clean kinds
CORRUPT = 0.03  # share of transactions damaged
OTHER = ["01", "02", "05", "08", "0b", "0f", "11", "16", "18", "2b", "41", "60"]
FACTORIES = {
    "atv71": lambda: build_annotator([], [], None),
    "none": lambda: None,
    "sel749m": lambda: build_annotator(["sel749m"], [], None),
    "auto": lambda: build_annotator([], [], None),  # the default: profiles chosen from the traffic
}


def w(v):
    return f"{v & 0xFFFF:04x}"


def words(rng, k):
    return [rng.choice(VALS) if rng.random() < 0.8 else rng.randrange(65536) for _ in range(k)]


def qty(rng):
    r = rng.random()
    if r < 0.93:
        return rng.randint(1, 8)
    return rng.choice([0, 1, 2, 3, 20, 21, 61, 62, 63, 64, 100, 121, 122, 123, 124, 125, 126])


def bit_qty(rng, limit):
    if rng.random() < 0.9:
        return rng.randint(1, 40)
    return rng.choice([0, 1, 7, 8, 9, 31, 32, 33, limit - 1, limit, limit + 1])


def packed(rng, n):
    return "".join(f"{rng.randrange(256):02x}" for _ in range(n))


def transaction(rng):
    s = rng.choice(SLAVES)
    kind = rng.choice([0,0,0,0,1,2,2,3,3,4,4,8,8,9,10,12,12,13,14,15,16,16,17,17,18,18]) if rng.random() < CLEAN else rng.randrange(19)
    a = rng.choice(ADDR) if rng.random() < 0.9 else rng.randrange(65536)
    q = qty(rng)
    frames = []
    if kind in (0, 1):  # FC3/FC4 read
        fc = 3 if kind == 0 else 4
        vals = words(rng, q if rng.random() < 0.9 else max(0, q + rng.choice([-1, 1])))
        frames.append(rtu(f"{s:02x}{fc:02x}{w(a)}{w(q)}"))
        if rng.random() < 0.9:
            body = "".join(map(w, vals[:125]))
            frames.append(rtu(f"{s:02x}{fc:02x}{len(body)//2 & 0xff:02x}{body}"))
    elif kind == 2:  # FC6
        v = rng.choice(VALS)
        f = rtu(f"{s:02x}06{w(a)}{w(v)}")
        frames.append(f)
        r = rng.random()
        if r < 0.8:
            frames.append(f)
        elif r < 0.9:
            frames.append(rtu(f"{s:02x}06{w(rng.choice(ADDR))}{w(rng.choice(VALS))}"))
    elif kind == 3:  # FC16
        vals = words(rng, min(q, 123))
        body = "".join(map(w, vals))
        bc = len(body) // 2 if rng.random() < 0.95 else rng.randrange(256)
        frames.append(rtu(f"{s:02x}10{w(a)}{w(q)}{bc & 0xff:02x}{body}"))
        r = rng.random()
        if r < 0.85:
            frames.append(rtu(f"{s:02x}10{w(a)}{w(q)}"))
        elif r < 0.92:
            frames.append(rtu(f"{s:02x}10{w(a)}{w(q + 1)}"))
    elif kind == 4:  # FC23
        rq = q
        wq = qty(rng)
        wa = rng.choice(ADDR)
        wv = words(rng, min(wq, 121))
        body = "".join(map(w, wv))
        frames.append(rtu(f"{s:02x}17{w(a)}{w(rq)}{w(wa)}{w(wq)}{len(body)//2 & 0xff:02x}{body}"))
        if rng.random() < 0.9:
            rv = words(rng, rq if rng.random() < 0.95 else rq + 1)
            rb = "".join(map(w, rv[:125]))
            frames.append(rtu(f"{s:02x}17{len(rb)//2 & 0xff:02x}{rb}"))
    elif kind == 5:  # exception answer
        fc = rng.choice([3, 4, 6, 16, 23])
        frames.append(rtu(f"{s:02x}{fc:02x}{w(a)}{w(q)}") if fc in (3, 4, 6) else rtu(f"{s:02x}03{w(a)}{w(q)}"))
        frames.append(rtu(f"{s:02x}{(fc if fc in (3,4,6) else 3) | 0x80:02x}{rng.randint(1, 11):02x}"))
    elif kind == 6:  # noise
        frames.append(bytes(rng.randrange(256) for _ in range(rng.randint(1, 8))))
    elif kind == 7:  # other codes
        fc = rng.choice(OTHER)
        frames.append(rtu(f"{s:02x}{fc}" + "".join(f"{rng.randrange(256):02x}" for _ in range(rng.randint(0, 6)))))
    elif kind == 8:  # CHCF story: read 8401 alone or with 8400..8402
        v = rng.choice([3, 1, 0x8000, 3])
        if rng.random() < 0.5:
            frames.append(rtu(f"{s:02x}03{w(8401)}0001"))
            frames.append(rtu(f"{s:02x}0302{w(v)}"))
        else:
            frames.append(rtu(f"{s:02x}03{w(8400)}0003"))
            frames.append(rtu(f"{s:02x}0306{w(rng.choice(VALS))}{w(v)}{w(rng.choice(VALS))}"))
    elif kind == 9:  # CMD write
        v = rng.choice([0x000F, 0x0006, 0x0080, 0])
        f = rtu(f"{s:02x}06{w(8501)}{w(v)}")
        frames += [f, f]
    elif kind == 10:  # unanswered read
        frames.append(rtu(f"{s:02x}03{w(a)}{w(q)}"))
    elif kind == 12:  # FC1/FC2 read bits
        fc = rng.choice([1, 2])
        qb = bit_qty(rng, 2000)
        frames.append(rtu(f"{s:02x}{fc:02x}{w(a)}{w(qb)}"))
        if rng.random() < 0.9:
            n = (qb + 7) // 8 if rng.random() < 0.95 else rng.randrange(0, 260)
            frames.append(rtu(f"{s:02x}{fc:02x}{n & 0xff:02x}{packed(rng, min(n, 250))}"))
    elif kind == 13:  # FC5 write single coil
        v = rng.choice([0xFF00, 0, 0xFF00, 0, 0x1234, 0x00FF])
        f = rtu(f"{s:02x}05{w(a)}{w(v)}")
        frames.append(f)
        r = rng.random()
        if r < 0.85:
            frames.append(f)
        elif r < 0.92:
            frames.append(rtu(f"{s:02x}05{w(a + 1)}{w(rng.choice([0xFF00, 0, 7]))}"))
    elif kind == 14:  # FC15 write multiple coils
        qb = bit_qty(rng, 1968)
        n = (qb + 7) // 8 if rng.random() < 0.95 else rng.randrange(0, 250)
        frames.append(rtu(f"{s:02x}0f{w(a)}{w(qb)}{n & 0xff:02x}{packed(rng, min(n, 246))}"))
        r = rng.random()
        if r < 0.85:
            frames.append(rtu(f"{s:02x}0f{w(a)}{w(qb)}"))
        elif r < 0.92:
            frames.append(rtu(f"{s:02x}0f{w(a)}{w(qb + 1)}"))
    elif kind == 15:  # an exception to any code the compiled path shows
        fc = rng.choice([1, 2, 3, 4, 5, 6, 15, 16, 23])
        if fc in (1, 2, 3, 4):
            frames.append(rtu(f"{s:02x}{fc:02x}{w(a)}{w(q)}"))
        elif fc in (5, 6):
            frames.append(rtu(f"{s:02x}{fc:02x}{w(a)}{w(rng.choice([0xFF00, 0, 3]))}"))
        elif fc == 15:
            frames.append(rtu(f"{s:02x}0f{w(a)}{w(q)}{(q + 7) // 8:02x}{packed(rng, (q + 7) // 8)}"))
        elif fc == 16:
            body = "".join(map(w, words(rng, min(q, 123))))
            frames.append(rtu(f"{s:02x}10{w(a)}{w(q)}{len(body) // 2:02x}{body}"))
        else:
            body = "".join(map(w, words(rng, 2)))
            frames.append(rtu(f"{s:02x}17{w(a)}{w(q)}{w(8501)}0002{len(body) // 2:02x}{body}"))
        code = rng.choice([1, 2, 2, 3, 4, 6, 7, 7, 9, 11, 0x80])
        frames.append(rtu(f"{s:02x}{fc | 0x80:02x}{code:02x}"))
    elif kind == 16:  # FC7, FC11, FC12, FC22, FC24, sometimes with counts that disagree
        fc = rng.choice([7, 11, 12, 22, 24])
        odd = rng.random() < 0.1
        if fc == 7:
            frames += [rtu(f"{s:02x}07"), rtu(f"{s:02x}07{rng.randrange(256):02x}")]
        elif fc == 11:
            frames += [rtu(f"{s:02x}0b"), rtu(f"{s:02x}0b{w(rng.choice([0, 0xFFFF, 5]))}{w(rng.randrange(65536))}")]
        elif fc == 12:
            events = packed(rng, rng.randint(0, 64))
            count = len(events) // 2 + 6 if not odd else rng.randrange(6)
            frames += [rtu(f"{s:02x}0c"), rtu(f"{s:02x}0c{count:02x}{w(rng.choice([0, 0xFFFF, 0x12]))}{w(7)}{w(9)}{events}")]
        elif fc == 22:
            f = rtu(f"{s:02x}16{w(a)}{w(rng.randrange(65536))}{w(rng.randrange(65536))}")
            frames += [f, f]
        else:
            count = rng.choice([0, 1, 5, 8, 9, 31]) if not odd else 32
            values = "".join(w(rng.randrange(65536)) for _ in range(count))
            size = 2 + 2 * count + (rng.choice([-2, 2]) if odd and rng.random() < 0.5 else 0)
            frames += [rtu(f"{s:02x}18{w(a)}"), rtu(f"{s:02x}18{w(size)}{w(count)}{values}")]
    elif kind == 17:  # FC17, FC20, FC21, FC43: texts from the Python stages, answered or not
        fc = rng.choice([17, 20, 21, 43])
        if fc == 17:
            text = "".join(f"{ord(c):02x}" for c in rng.choice(["LMB3.1.6", "ATV71", "", "x\ty"]))
            frames.append(rtu(f"{s:02x}11"))
            answer = rtu(f"{s:02x}11{len(text) // 2 + 2:02x}{rng.randrange(256):02x}{rng.choice(['00', 'ff', '7f'])}{text}")
        elif fc == 20:
            groups = "".join(f"06{w(rng.randrange(10))}{w(rng.randrange(9999))}{w(rng.randint(1, 4))}" for _ in range(rng.randint(1, 3)))
            frames.append(rtu(f"{s:02x}14{len(groups) // 2:02x}{groups}"))
            body = "".join(f"{2 * k + 1:02x}06" + "".join(w(rng.randrange(65536)) for _ in range(k)) for k in (1, 2))
            answer = rtu(f"{s:02x}14{len(body) // 2:02x}{body}")
        elif fc == 21:
            body = f"06{w(1)}{w(2)}{w(2)}{w(7)}{w(8)}"
            frames.append(rtu(f"{s:02x}15{len(body) // 2:02x}{body}"))
            answer = frames[-1]
        else:
            frames.append(rtu(f"{s:02x}2b0e01{rng.choice(['00', '02'])}"))
            objects = [rng.choice(["Schneider", "ATV71H", "0201", "a'b\"c", "\u00e9t\u00e9"]) for _ in range(rng.randint(0, 3))]
            encoded = "".join(f"{k:02x}{len(o.encode('latin-1')):02x}{o.encode('latin-1').hex()}" for k, o in enumerate(objects))
            answer = rtu(f"{s:02x}2b0e0102{rng.choice(['00', 'ff'])}00{len(objects):02x}{encoded}")
        if rng.random() < 0.85:
            frames.append(answer)
    elif kind == 18:  # FC8: Return Query Data echoes (a CRC scan finds their end), other sub-functions
        sub = rng.choice([0, 0, 0, 0, 1, 2, 4, 10, 11, 15, 15, 20, 5, 99, 0x1234])
        if sub == 0:
            size = rng.choice([0, 1, 2, 3, 4, 16, 17, 18, rng.randint(0, 40), rng.randint(0, 250)])
            data = packed(rng, size) if rng.random() < 0.8 else "00" * size
        else:
            data = w(rng.choice([0, 0xFF00, 7, rng.randrange(65536)]))
        frame = rtu(f"{s:02x}08{w(sub)}{data}")
        frames.append(frame)
        r = rng.random()
        if r < 0.75:
            frames.append(frame)  # the echo
        elif r < 0.85:
            frames.append(rtu(f"{s:02x}08{w(sub)}{packed(rng, rng.choice([0, 2, 4]))}"))
        elif r < 0.92:
            frames.append(rtu(f"{s:02x}88{rng.choice([1, 2, 3, 4, 11]):02x}"))
    else:  # retry: same request twice then answer
        f = rtu(f"{s:02x}03{w(a)}{w(q)}")
        body = "".join(map(w, words(rng, min(q, 125))))
        frames += [f, f, rtu(f"{s:02x}03{len(body)//2 & 0xff:02x}{body}")]
    out = b"".join(frames)
    if rng.random() < CORRUPT and out:  # corruption
        b = bytearray(out)
        how = rng.randrange(4)
        i = rng.randrange(len(b))
        if how == 0:
            b[i] ^= 1 << rng.randrange(8)
        elif how == 1:
            del b[i]
        elif how == 2:
            b.insert(i, rng.randrange(256))
        else:
            b.insert(i, 0)
        out = bytes(b)
    if rng.random() < 0.03:
        out += b"\x00"
    return out


def session(rng):
    return [transaction(rng) for _ in range(rng.randint(1, 40))]


def splits_for(rng, n):
    r = rng.random()
    if r < 0.3 or n == 0:
        return []
    if r < 0.5:
        step = rng.randint(1, 9)
        return list(range(step, n, step))
    return sorted({rng.randrange(n) for _ in range(rng.randint(1, 12))})


class StatsLines:
    """--stats compared as lines: the JSON report, then the tables; the frames the engine counted."""

    def __init__(self, collector) -> None:
        self.lines = [repr(collector.report()), *collector.render_plain().splitlines()]
        self.engine_lines = collector.store.frames


def check(parts, name, splits):
    data = b"".join(parts)
    splits = [c for c in splits if c < len(data)]
    if STATS:
        got = StatsLines(compiled_stats(data, FACTORIES[name](), splits))
        exp = StatsLines(python_stats(data, FACTORIES[name]())).lines
        return got.lines == exp, got, exp
    exp = python_lines(data, FACTORIES[name]())
    got = fast_lines(data, FACTORIES[name](), splits)
    return got.lines == exp, got, exp


def minimize(parts, name, splits):
    # drop whole transactions, then splits
    changed = True
    while changed:
        changed = False
        for i in range(len(parts)):
            trial = parts[:i] + parts[i + 1:]
            if not check(trial, name, splits)[0]:
                parts = trial
                changed = True
                break
    for s in list(splits):
        trial = [x for x in splits if x != s]
        if not check(parts, name, trial)[0]:
            splits = trial
    return parts, splits


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("seconds", type=float, nargs="?", default=300, help="how long to run (default 300)")
    parser.add_argument("first_seed", type=int, nargs="?", default=0)
    parser.add_argument("--stats", action="store_true", help="compare --stats instead (read at import: STATS)")
    arguments = parser.parse_args()
    budget, seed0 = arguments.seconds, arguments.first_seed
    end = time.time() + budget
    seed = seed0
    runs = engine = total = 0
    failures = {}
    pysplit_count = [0]
    while time.time() < end:
        rng = random.Random(seed)
        parts = session(rng)
        data_len = sum(map(len, parts))
        splits = splits_for(rng, data_len)
        for name in FACTORIES:
            ok, got, exp = check(parts, name, splits)
            runs += 1
            engine += got.engine_lines
            total += len(exp)
            if not ok:
                data = b"".join(parts)
                cls = "pysplit" if not STATS and py_split(data, FACTORIES[name](), [c for c in splits if c < len(data)]) != exp else "C?"
                if cls == "pysplit":
                    pysplit_count[0] += 1
                    if pysplit_count[0] <= 2:
                        print("python-only split variance, seed", seed, name)
                    continue
                if name in failures:
                    continue
                mparts, msplits = minimize(parts, name, splits)
                _, g2, e2 = check(mparts, name, msplits)
                failures[name] = (seed, mparts, msplits)
                print("MISMATCH", name, "seed", seed)
                print(" data", b"".join(mparts).hex())
                print(" splits", msplits)
                for a, b in zip(g2.lines + [""] * 5, e2 + [""] * 5):
                    if a != b:
                        print("  fast:", a)
                        print("  py  :", b)
                sys.stdout.flush()
        seed += 1
    print("python-only split-variance mismatches:", pysplit_count[0]); print(f"seeds {seed0}..{seed - 1}, comparisons {runs}, lines {total}, engine-written {engine}, "
          f"mismatching annotators {sorted(failures)}")


if __name__ == "__main__":
    main()
