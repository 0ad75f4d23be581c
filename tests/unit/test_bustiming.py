"""Bus timing and slave health in --stats (issue 29): load, gaps against t3.5, master turnaround,
response times against --timeout, outages; the line's speed from --baud or a pcapng's description.
Figures are recomputed here from --json of the same capture, independently of render/bustiming.py."""
from __future__ import annotations

import json
import math
from pathlib import Path

from conftest import ROOT
from helpers import rtu, run_cli
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import PcapWriter

CAPTURES = ROOT / "captures"
T0 = 1767225600.0


def _stats(*argv: str) -> dict:
    status, out, err = run_cli(["--stats", "--json", *argv])
    assert (status, err) == (0, "")
    return json.loads(out)


def _items(path: str) -> list[dict]:
    return [json.loads(line) for line in run_cli(["--json", path])[1].splitlines()]


def _nearest(values: list[float], fraction: float) -> float:
    ordered = sorted(values)
    if fraction == 0.5 and len(ordered) % 2 == 0:
        return (ordered[len(ordered) // 2 - 1] + ordered[len(ordered) // 2]) / 2
    return ordered[max(1, math.ceil(fraction * len(ordered))) - 1]


def test_commissioning_load_and_turnaround_from_the_json() -> None:
    path = str(CAPTURES / "atv71_commissioning.pcap")
    bus = _stats("--baud", "19200", path)["bus"]
    char = 11 / 19200
    items = _items(path)
    busy = sum(item["length"] * char for item in items)
    span = items[-1]["time"] + items[-1]["length"] * char - items[0]["time"]
    assert 0 < bus["load"] < 1
    assert abs(bus["load"] - busy / span) < 1e-6
    assert (bus["baud"], bus["baud_source"], bus["bits_per_char"], bus["t35"]) == (19200, "--baud", 11, 0.002005)
    turnarounds = [
        item["time"] - (before["time"] + before["length"] * char)
        for before, item in zip(items, items[1:])
        if item["kind"] == "request" and before["kind"] in ("response", "exception")
    ]
    turnaround = bus["turnaround"]
    assert turnaround["count"] == len(turnarounds) == 51
    for key, fraction in (("median", 0.5), ("p95", 0.95), ("max", 1.0)):
        assert abs(turnaround[key] - _nearest(turnarounds, fraction)) <= 1e-5 + 1e-9  # 10 us buckets
    gaps = [item["time"] - (before["time"] + before["length"] * char) for before, item in zip(items, items[1:])]
    assert bus["gaps"]["count"] == len(gaps) and bus["gaps_below_t35"] == sum(gap < 0.002005 for gap in gaps) == 0
    assert sum(entry["count"] for entry in bus["gap_histogram"]) == len(gaps)
    (slave,) = bus["responses"]
    times = [item["response_time"] for item in items if item.get("response_time") is not None]
    assert (slave["slave"], slave["count"], slave["max"]) == (2, len(times), max(times))
    # the margin: to the longest wait after a request was sent (its first byte and its length at this speed)
    length = {item["frame"]: item["length"] for item in items}
    waits = [item["response_time"] - length[item["request_frame"]] * char for item in items
             if item.get("response_time") is not None]
    assert slave["margin"] == round(1.0 - max(waits), 6) != round(1.0 - max(times), 6)
    assert bus["outages"] == []


def test_noisy_bus_lists_slave_5_outage() -> None:
    path = str(CAPTURES / "noisy_bus.pcap")
    bus = _stats(path)["bus"]
    times = {item["frame"]: item["time"] for item in _items(path)}
    assert bus["outages"] == [
        {"slave": 5, "start": times[28], "end": times[29], "requests": 2, "first_frame": 28, "last_frame": 29}
    ]
    assert [entry["slave"] for entry in bus["responses"]] == [1, 12]
    assert bus["responses"][0]["count"] == 8  # the bad-CRC answer of frame 17 is no response time, as --stats says
    functions = {entry["slave"]: entry["response_time"] for entry in _stats(path)["functions"]}
    for entry in bus["responses"]:  # one function a slave here: the same figures as the table above it
        for key in ("count", "min", "median", "p95", "max"):
            assert abs(entry[key] - functions[entry["slave"]][key]) <= 1e-5, key
    status, out, _err = run_cli(["--stats", path])
    assert status == 0
    assert "  slave 5 silent 0.839570 - 1.050219, 2 requests unanswered (frames 28..29)\n" in out
    assert "\nBus timing\nline: 19200 baud (assumed: --baud sets it), 11 bits a character, t3.5 2.005 ms" in out


def test_untimed_input_says_so() -> None:
    bus = _stats(str(CAPTURES / "noisy_bus.bin"))["bus"]
    assert (bus["timed"], bus["load"], bus["turnaround"], bus["gaps_below_t35"], bus["outages"]) == (False, None, None, None, [])
    out = run_cli(["--stats", str(CAPTURES / "noisy_bus.bin")])[1]
    assert "no timestamps in this input: load, gaps, turnaround and outages need a pcap" in out


def _frames() -> list[bytes]:
    return [rtu("0C 03 20 D0 00 03"), rtu("0C 03 06 8000 0003 0002")]


def test_a_line_speed_at_which_frames_overlap_is_said_once() -> None:
    # Review of issue 29 (defect 9): --baud 9600 gave gaps of -27 ms and --baud 2400 a turnaround median
    # of -8.5 ms, silently. Overlaps recomputed from --json: an item starting before the previous ends.
    path = str(CAPTURES / "atv71_commissioning.pcap")
    items = _items(path)
    for baud, expected in ((9600, 49), (2400, 103)):
        char = 11 / baud
        overlaps, busy_until = 0, None  # the line is busy until the latest end heard (as the gaps count)
        for item in items:
            if busy_until is not None and item["time"] - busy_until < -5e-6:
                overlaps += 1
            end = item["time"] + item["length"] * char
            busy_until = end if busy_until is None else max(busy_until, end)
        assert overlaps == expected
        status, out, err = run_cli(["--stats", "--baud", str(baud), path])
        assert status == 0 and err == (f"vw3-decode: warning: --baud {baud}: {expected} frames would overlap the one "
                                       f"before at {baud} baud: the line is faster?\n")
        status, out, err = run_cli(["--stats", "--json", "--baud", str(baud), path])
        assert json.loads(out)["bus"]["overlaps"] == expected and err.count("\n") == 1
    # At the line's speed, or none said: no warning, no overlap.
    status, out, err = run_cli(["--stats", "--json", "--baud", "19200", path])
    assert (status, err, json.loads(out)["bus"]["overlaps"]) == (0, "", 0)
    assert run_cli(["--stats", path])[2] == ""


def test_gaps_below_t35_and_the_pcapng_line_settings(tmp_path: Path) -> None:
    request, response = _frames()
    # 8 bytes at 9600 8N2 (11 bits) last 9.167 ms; the answer 0.5 ms after its end is below t3.5 (4.01 ms).
    path = tmp_path / "tap.pcapng"
    with path.open("wb") as stream:
        writer = PcapngWriter(stream, if_name="/dev/ttyUSB0", if_description=(
            "serial port /dev/ttyUSB0, 9600 baud, 8 data bits, no parity, 2 stop bits (9600 8N2)"))
        writer.write(request, T0)
        writer.write(response, T0 + 8 * 11 / 9600 + 0.0005)
        writer.write(request, T0 + 0.5)
        writer.close()
    bus = _stats(str(path))["bus"]
    assert (bus["baud"], bus["baud_source"], bus["bits_per_char"]) == (9600, "pcapng interface description", 11)
    assert bus["t35"] == round(3.5 * 11 / 9600, 6) and bus["gaps_below_t35"] == 1
    assert bus["gap_histogram"][0] == {"from_ms": None, "to_ms": 1.0, "count": 1}
    assert bus["turnaround"]["count"] == 1
    assert abs(bus["turnaround"]["max"] - (0.5 - (8 * 11 / 9600 + 0.0005) - 11 * 11 / 9600)) < 2e-6
    assert _stats("--baud", "38400", str(path))["bus"]["baud_source"] == "--baud"
    assert _stats("--baud", "38400", str(path))["bus"]["t35"] == 0.00175  # fixed above 19200 baud


def test_outage_needs_two_consecutive_unanswered_requests(tmp_path: Path) -> None:
    request, response = _frames()
    path = tmp_path / "bus.pcap"
    with path.open("wb") as stream:
        writer = PcapWriter(stream)
        times = iter(T0 + 0.1 * index for index in range(20))
        writer.write(request, next(times))  # unanswered once: no outage
        writer.write(request, next(times))
        writer.write(response, next(times) - 0.09)
        for _ in range(3):  # three in a row: one outage
            writer.write(request, next(times))
        writer.write(request, next(times))
        writer.write(response, next(times) - 0.09)
        writer.close()
    bus = _stats("--timeout", "0.05", str(path))["bus"]
    assert [(o["slave"], o["requests"], o["first_frame"], o["last_frame"]) for o in bus["outages"]] == [(12, 3, 4, 6)]


def test_several_captures_are_said_to_be_one_bus() -> None:
    # Review of issue 29 (defect 13): --stats over two captures merged them as one bus without a word.
    p38, noisy = str(CAPTURES / "p38_protection.pcap"), str(CAPTURES / "noisy_bus.pcap")
    status, out, err = run_cli(["--stats", p38, noisy])
    assert (status, err) == (0, "")
    lines = out.splitlines()
    header = next(line for line in lines if " frames, " in line)  # (after any `==> name <==` titles)
    assert header == (f"48 frames, 9 noise bytes in 2 runs, from 2 captures counted as one bus, as mergecap "
                        f"would join them (decode each alone for its own traffic and timing): {p38}, {noisy}")
    bus = lines[lines.index("Bus timing") + 2]
    assert bus == ("2 captures counted as one bus: gaps and turnarounds restart at each capture, the load is "
                   "over the span from the first item to the last")
    status, out, err = run_cli(["--stats", "--json", p38, noisy])
    assert json.loads(out)["merged_captures"] == [p38, noisy]
    import tempfile

    with tempfile.TemporaryDirectory() as folder:
        page = Path(folder) / "two.html"
        assert run_cli(["--report", str(page), p38, noisy])[0] == 0
        text = page.read_text(encoding="utf-8")
    assert (f'<p class="summary">48 frames, 9 noise bytes in 2 runs, 1.550 s, from 2 captures counted as one bus, '
            f"as mergecap would join them (decode each alone for its own traffic and timing): {p38}, {noisy}</p>") in text
    # One capture: nothing said, no key.
    status, out, err = run_cli(["--stats", p38])
    assert out.splitlines()[0] == "12 frames, 0 noise bytes in 0 runs" and "counted as one bus" not in out
    assert "merged_captures" not in json.loads(run_cli(["--stats", "--json", p38])[1])
