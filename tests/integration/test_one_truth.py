"""Issue 27: every output of one input says what its frames say.

The consistency test decodes each input once with --json and derives, from those records alone and
by the rules the README states, what --stats --json counts, what the report lists as events, the
lines --watch prints and the rows -T fields writes; then runs those outputs and compares. Inputs:
every shipped capture, and simulator sessions of each traffic mix (polling, plant, max-size).
"""
from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from conftest import ROOT
from helpers import run_cli

from dissector.sim.mixes import PLANT_PROFILES, max_size_mix, plant_mix
from dissector.sim.simulate import generate_session, write_capture

CAPTURES = ROOT / "captures"
WRITES = (6, 16, 23)
MASK_WRITE = 22  # (a write of its register: its echo gives the masked value where the last is known)
READS = (3, 4, 23)
UNREADABLE = ("protected", "non-existent")


def derive(records: list[dict]) -> tuple[dict, dict, list, list]:
    """(traffic per (slave, function), parameters, state changes, protection events) from --json."""
    by_frame = {record["frame"]: record for record in records}
    traffic: dict[tuple[int, int], dict] = {}
    params: dict[tuple[int, int], dict] = {}
    changes: list[tuple[int, int, int]] = []  # (frame, slave, address)
    protections: list[tuple[int, int]] = []  # (frame, slave)
    moments: set[tuple[int, int, str]] = set()

    def param(slave: int, register: dict) -> dict:
        return params.setdefault((slave, register["address"]), {
            "reads": 0, "unreadable": 0, "writes": 0, "refused": 0, "state": None, "changes": 0, "status": None,
        })

    def state(record: dict, register: dict, new: object, unreadable: bool) -> None:
        entry = param(record["slave"], register)
        old = entry["state"]
        if old is not None and old != new:
            entry["changes"] += 1
            changes.append((record["frame"], record["slave"], register["address"]))
        # The report tells a frame's spans opened as one event, and those it closed as another.
        moment = None
        if unreadable and entry["status"] != new:
            moment = (record["frame"], record["slave"], "opened")  # an unreadable span opens
        elif not unreadable and entry["status"] is not None:
            moment = (record["frame"], record["slave"], "closed")  # readable again
        if moment is not None and moment not in moments:
            moments.add(moment)
            protections.append(moment[:2])
        entry["status"] = new if unreadable else None
        entry["state"] = new

    for record in records:
        if record["kind"] == "noise":
            continue
        row = traffic.setdefault((record["slave"], record["function"]), {
            "requests": 0, "responses": 0, "exceptions": {}, "unanswered": 0, "crc_errors": 0})
        if not record["crc_ok"]:
            row["crc_errors"] += 1
            continue
        slave, function = record["slave"], record["function"]
        registers = [r for r in record.get("registers") or [] if r["address"] is not None]
        request = by_frame.get(record.get("request_frame"))
        if function == MASK_WRITE and record["kind"] != "exception" and "fields" in record:
            registers = [{"address": record["fields"]["address"]}]  # (its one register, as a write's)
        if record["kind"] == "request":
            row["requests"] += 1
            row["unanswered"] += bool(record.get("unanswered"))
            if function in WRITES or function == MASK_WRITE:
                for register in registers:
                    param(slave, register)["writes"] += 1
                    if record["broadcast"]:
                        state(record, register, ("value", register["value"]), False)
            continue
        written = []
        if request is not None and request["crc_ok"] and request["function"] in WRITES:
            written = [r for r in request.get("registers") or [] if r["address"] is not None]
        elif request is not None and request["crc_ok"] and request["function"] == MASK_WRITE and "fields" in request:
            written = [{"address": request["fields"]["address"]}]
        if record["kind"] == "exception":
            code = str(record["exception_code"])
            row["exceptions"][code] = row["exceptions"].get(code, 0) + 1
            for register in written:
                param(slave, register)["refused"] += 1
        else:
            row["responses"] += 1
            confirmed = registers if function == 6 else written if function in (16, 23) else []
            for register in confirmed:
                state(record, register, ("value", register["value"]), False)
            if function == MASK_WRITE and registers:  # (Application Protocol 6.16, where the value is known)
                fields, old = record["fields"], param(slave, registers[0])["state"]
                if fields["and_mask"] == 0 or isinstance(old, tuple):
                    current = old[1] if isinstance(old, tuple) else 0
                    masked = current & fields["and_mask"] | fields["or_mask"] & ~fields["and_mask"] & 0xFFFF
                    state(record, registers[0], ("value", masked), False)
            if function not in READS:
                continue
        for register in registers:
            if register.get("status") in UNREADABLE:
                param(slave, register)["unreadable"] += 1
                state(record, register, register["status"], True)
            else:
                param(slave, register)["reads"] += 1
                state(record, register, ("value", register["value"]), False)
    return traffic, params, changes, protections


def inputs(tmp_path: Path) -> list[tuple[str, list[str]]]:
    found = [(str(path), []) for path in sorted(CAPTURES.iterdir()) if path.suffix in (".bin", ".pcap")]
    polling = write_capture(generate_session(400, seed=7), tmp_path / "polling")
    plant = write_capture(plant_mix(1500, seed=3), tmp_path / "plant")
    big = write_capture(max_size_mix(600, seed=4), tmp_path / "max")
    plant_profiles = [option for profile in PLANT_PROFILES for option in ("--profile", profile)]
    for raw, pcap in (polling,):
        found += [(str(raw), []), (str(pcap), [])]
    for raw, pcap in (plant,):
        found += [(str(raw), plant_profiles), (str(pcap), plant_profiles)]
    for raw, pcap in (big,):
        found += [(str(raw), ["--profile", "generic"]), (str(pcap), ["--profile", "generic"])]
    # The plant and max-size mixes under profile auto as well (the default): the choices made over the
    # whole file name every output alike.
    found += [(str(plant[1]), []), (str(big[1]), [])]
    return found


def test_stats_report_watch_and_fields_say_what_the_json_says(tmp_path: Path) -> None:
    checked = 0
    for path, options in inputs(tmp_path):
        status, out, _ = run_cli([path, "--json", *options])
        assert status == 0, path
        records = [json.loads(line) for line in out.splitlines()]
        traffic, params, changes, protections = derive(records)

        # --stats --json
        status, out, _ = run_cli([path, "--stats", "--json", *options])
        report = json.loads(out)
        assert report["frames"] == sum(record["kind"] != "noise" for record in records), path
        got = {(row["slave"], row["function"]): {key: row[key] for key in
               ("requests", "responses", "exceptions", "unanswered", "crc_errors")} for row in report["functions"]}
        assert got == traffic, path
        got_params = {(row["slave"], row["address"]): row for row in report["parameters"]}
        assert set(got_params) == set(params), path
        for key, entry in params.items():
            row = got_params[key]
            last = entry["state"]
            expected_last = last[1] if isinstance(last, tuple) else None
            assert (row["reads"], row["unreadable"], row["writes"], row["refused"], row["changes"], row["last"],
                    row["last_status"]) == (
                entry["reads"], entry["unreadable"], entry["writes"], entry["refused"], entry["changes"],
                expected_last, last if isinstance(last, str) else None), (path, key)

        # --watch on every address: one line per change of state (of watched registers that changed)
        addresses = sorted({address for _slave, address in params})
        if addresses:
            status, out, err = run_cli([path, "--watch", ",".join(map(str, addresses)), "--json", *options])
            assert status == 0, err
            lines = [json.loads(line) for line in out.splitlines()]
            assert [(c["frame"], c["slave"], c["address"]) for c in lines] == changes, path

        # The report's events: one per protection moment, exception, bad check, noise run, unanswered request
        page = tmp_path / "report.html"
        status, _out, err = run_cli([path, "--report", str(page), *options])
        assert status == 0, err
        data = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(encoding="utf-8")).group(1))
        counts = data["event_counts"]
        assert counts["protection"] == len(protections), path
        assert counts["exception"] == sum(record["kind"] == "exception" and record["crc_ok"] for record in records)
        assert counts["crc"] == sum(record["kind"] != "noise" and not record["crc_ok"] for record in records)
        assert counts["noise"] == sum(record["kind"] == "noise" for record in records)
        assert counts["unanswered"] == sum(
            record["kind"] == "request" and record["crc_ok"] and bool(record.get("unanswered"))
            and not record["broadcast"] for record in records)
        listed = [event for event in data["events"] if event[1] == "protection"]
        origin = 0 if not data["timed"] else None
        if origin == 0 and not data["events_dropped"]:
            assert [(int(event[0]), event[2]) for event in listed] == protections, path

        # -T fields: one row per item, as tshark writes the plugin's: a text key one occurrence per register
        # (empty where it has none; a bit none: the plugin has no bit texts), a number key only the values there are
        status, out, _ = run_cli([path, "-T", "fields", "-e", "frame", "-e", "slave", "-e", "address",
                                  "-e", "value", "-e", "status", "-E", "separator=;", *options])

        def join(record: dict, key: str) -> str:
            registers = record.get("registers") or []
            elements = registers + (record.get("bits") or [])
            cells = ["" if element.get(key) is None else str(element[key]) for index, element in enumerate(elements)
                     if element.get(key) is not None or key == "status" and index < len(registers)]
            start, quantity = record.get("start"), record.get("quantity")
            if start is not None and quantity is not None and record["kind"] != "exception":
                # then the addresses the frame names without carrying them (a read request's window, README),
                # nothing of the other register keys for them
                carried = [element.get("address") for element in elements]
                if carried[:1] != [start] or len(carried) != quantity:
                    window = [(start + k) % 65536 for k in range(min(max(quantity, 1), 2000))]
                    cells += [str(address) for address in window if address not in carried and key == "address"]
            cell = ",".join(cells)
            # A cell holding the aggregator (or ; or ") is one double-quoted CSV cell (issue 32).
            return '"' + cell.replace('"', '""') + '"' if any(char in cell for char in ',;"') else cell

        expected_rows = [
            ";".join([str(record["frame"]), "" if record.get("slave") is None else str(record["slave"]),
                      join(record, "address"), join(record, "value"), join(record, "status")])
            for record in records
        ]
        assert out.splitlines() == expected_rows, path
        checked += 1
    assert checked == 18


@pytest.mark.parametrize("suffix", [".bin", ".pcap"])
def test_p38_story_in_every_output(suffix: str) -> None:
    p38 = str(CAPTURES / f"p38_protection{suffix}")
    status, out, _ = run_cli([p38, "--stats", "--json"])
    assert status == 0
    assert [{key: row[key] for key in ("slave", "address", "code", "reads", "unreadable", "writes", "refused", "last",
                                        "last_status", "changes")} for row in json.loads(out)["parameters"]] == [
        {"slave": 12, "address": 8400, "code": None, "reads": 0, "unreadable": 6, "writes": 0, "refused": 0,
         "last": None, "last_status": "non-existent", "changes": 0},
        {"slave": 12, "address": 8401, "code": "CHCF", "reads": 2, "unreadable": 4, "writes": 0, "refused": 0,
         "last": None, "last_status": "protected", "changes": 1},
        {"slave": 12, "address": 8402, "code": "COP", "reads": 4, "unreadable": 2, "writes": 0, "refused": 0,
         "last": None, "last_status": "protected", "changes": 1},
    ]
    status, out, _ = run_cli([p38, "--stats"])
    table = out[out.index("Parameters\n"):].split("\n\n")[0].splitlines()
    assert table[3:6] == [
        "   12      8400            0           6       0        0  non-existent        0",
        "   12      8401  CHCF      2           4       0        0  protected           1",
        "   12      8402  COP       4           2       0        0  protected           1",
    ]


def test_reverse_output_frequency_is_signed() -> None:
    # RFR (3202) reads 16#FFEC when the motor turns in reverse at 2 Hz.
    status, out, _ = run_cli(["--profile", "atv71", "--hex", "02 03 0C 81 00 02",
                              "--hex", "02 03 04 02 37 FF EC", "--json"])
    (rfr,) = [r for r in json.loads(out.splitlines()[1])["registers"] if r["code"] == "RFR"]
    assert (rfr["value"], rfr["scaled"], rfr["text"], rfr["unit"]) == (65516, -2.0, "-2.0 Hz", "Hz")
    status, out, _ = run_cli(["--profile", "atv71", "--hex", "02 03 0C 81 00 02",
                              "--hex", "02 03 04 02 37 FF EC"])
    assert "RFR=-2.0 Hz" in out.splitlines()[1]


def test_a_file_without_any_valid_frame_says_so_once(tmp_path: Path) -> None:
    import struct
    import zlib

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    png = tmp_path / "photo.png"
    png.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 4, 4, 8, 2, 0, 0, 0))
                    + chunk(b"IDAT", zlib.compress(b"\x00" * 52)) + chunk(b"IEND", b""))
    for extra in ([], ["--stats"], ["--json"]):
        status, out, err = run_cli([str(png), *extra])
        assert status == 0
        assert err == (f"vw3-decode: warning: {png}: no valid Modbus RTU frame in 69 bytes (every item is noise "
                       "or a frame with a bad check): not a Modbus capture, or another format or line speed?\n")
    # A capture with frames says nothing of the kind.
    assert run_cli([str(CAPTURES / "noisy_bus.bin")])[2] == ""


def test_report_with_an_item_format_prints_the_items_too(tmp_path: Path) -> None:
    p38 = str(CAPTURES / "p38_protection.bin")
    page = str(tmp_path / "r.html")
    for extra in (["--json"], ["-T", "fields", "-e", "frame"], ["-V"]):
        alone = run_cli([p38, *extra])
        assert run_cli([p38, "--report", page, *extra]) == alone
        assert Path(page).read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    assert run_cli([p38, "--report", page]) == (0, "", "")


@pytest.mark.parametrize("name", ["p38_protection.pcap", "atv71_commissioning.pcap"])
def test_watch_lines_count_as_stats_changes(name: str) -> None:
    path = str(CAPTURES / name)
    status, out, _ = run_cli([path, "--stats", "--json"])
    report = json.loads(out)
    for row in report["parameters"]:
        if row["code"] is None:
            continue
        status, out, _ = run_cli([path, "--watch", row["code"], "-Y", f"slave == {row['slave']}"])
        assert len(out.splitlines()) == row["changes"], row


def test_detail_of_a_filtered_request_keeps_its_response_frame() -> None:
    p38 = str(CAPTURES / "p38_protection.bin")
    alone = run_cli(["-V", "-c", "1", p38])[1]
    filtered = run_cli(["-V", "-Y", 'kind == "request"', "-c", "1", p38])[1]
    assert "    Response in frame: 2" in alone.splitlines()
    assert filtered == alone


def test_plc_style_is_the_same_in_every_output(tmp_path: Path) -> None:
    commissioning = str(CAPTURES / "atv71_commissioning.bin")
    lines = run_cli(["--address-style", "plc", commissioning])[1].splitlines()
    # The FC23 request names its read window as its answer does.
    assert lines[18].startswith("    19            -   2 request   Read/Write Multiple Registers read 43202..43203 (2), write CMD=")
    assert lines[19].startswith("    20            -   2 response  Read/Write Multiple Registers 43202..43203 (2): ETA=")
    sel = str(CAPTURES / "sel749m_polling.bin")
    assert run_cli(["--address-style", "plc", "-c", "1", sel])[1].startswith(
        "     1            -   1 request   Read Holding Registers 40001..40016 (16)")
    stats = run_cli(["--address-style", "plc", "--stats", sel])[1].splitlines()
    assert "    1  3 Read Holding Registers  40001..40016 (16)     12       -       -       0" in stats
    assert "    1  4 Read Input Registers    30101..30108 (8)      12       -       -       0" in stats
    page = tmp_path / "sel.html"
    run_cli(["--address-style", "plc", "--report", str(page), sel])
    text = page.read_text(encoding="utf-8")
    assert "<td>40001..40016 (16)</td>" in text
    # Review of issue 27 (defect 4): every other output in the same style, one helper (naming.plc_label).
    plc = ["--address-style", "plc"]
    # summary and -V
    assert run_cli([*plc, "-c", "4", sel])[1].splitlines()[3].startswith(
        "     4            -   1 response  Read Input Registers 30101..30108 (8): 30101=250 ")
    detail = run_cli([*plc, "-V", "-c", "2", sel])[1].splitlines()
    assert "        Register 40001: 403 (0x0193)" in detail and "        Register 40016: 958 (0x03BE)" in detail
    assert detail[4:8] == ["        Start address: 0 (0x0)", "        Quantity: 16 (0x10)", "        PLC references: 40001..40016",
                           "        CRC: 0x0644 [CRC ok]"]
    assert detail.count("        PLC references: 40001..40016") == 2  # the request and its answer
    assert "PLC references" not in run_cli(["-V", "-c", "2", sel])[1]  # (a cached detail keeps no style)
    assert "        PLC references (read): 43202..43203" in run_cli([*plc, "-V", commissioning])[1].splitlines()
    # --stats: the Parameters table as the poll cycle (input registers 3x, holding 4x)
    assert "    1  40001..40016 (16)           12           0       0        0  (various)       11" in stats
    assert "    1   30101..30108 (8)           12           0       0        0  (various)       11" in stats
    assert "    1              40302            0           0       3        2  1                0" in stats
    parameters = json.loads(run_cli([*plc, "--stats", "--json", sel])[1])["parameters"]
    assert [(row["address"], row["label"]) for row in parameters[:1] + parameters[16:17]] == [(0, "40001"), (100, "30101")]
    assert "label" not in json.loads(run_cli(["--stats", "--json", sel])[1])["parameters"][0]
    # the report: the parameter index, the trends' titles and the single-value table
    assert '<a href="#p0" title="slave 1, 40001: ">40001</a>' in text
    assert '<h3>Slave 1: <span class="code">30101</span>' in text
    # (the single-value table counts as --stats: reads 0, writes 3, of which 2 refused)
    assert "<tr><td>1</td><td>40302</td><td></td><td></td><td>1</td><td>0</td><td>3</td></tr>" in text
    assert "<td>0..15 (16)</td>" not in text and "Slave 1: 0 " not in text
    # --watch: a number selects what -Y 'address == N' selects, the protocol address or the reference
    by_reference = run_cli([*plc, "--watch", "40001", sel])[1]
    assert by_reference.splitlines()[:2] == ["     6            -   1 40001 403 -> 407",
                                             "    10            -   1 40001 407 -> 404"]
    assert run_cli([*plc, "--watch", "0", sel])[1] == by_reference  # the protocol address: the same register
    assert run_cli(["--watch", "0", sel])[1].splitlines()[0] == "     6            -   1 0 403 -> 407"
    changes = json.loads(run_cli([*plc, "--watch", "30101", "--json", sel])[1].splitlines()[0])
    assert (changes["address"], changes["label"], changes["old"], changes["new"]) == (100, "30101", "250", "251")
    frames = run_cli([*plc, "-T", "fields", "-e", "frame", "-Y", "address == 40001", sel])[1].split()
    watched = {line.split()[0] for line in by_reference.splitlines()}
    assert watched <= set(frames)
    # -T fields and -T registers
    assert run_cli([*plc, "-T", "fields", "-e", "frame", "-e", "label", "-E", "occurrence=f", "-c", "4", sel])[1] == (
        "1\t40001\n2\t40001\n3\t30101\n4\t30101\n")  # (a request's window labelled too, as vw3.reg.label)
    assert run_cli([*plc, "-T", "registers", "-c", "2", sel])[1].splitlines()[0] == "2\t\t1\t3\tread\t0\t40001\t\t\t403\t\t\t\t\t\t"


def test_exception_counts_read_the_same_in_stats_and_report(tmp_path: Path) -> None:
    p38 = str(CAPTURES / "p38_protection.bin")
    stats = run_cli(["--stats", p38])[1].splitlines()
    assert "   12  3 Read Holding Registers    6     4  02:2               0        0" in stats
    page = tmp_path / "p38.html"
    run_cli(["--report", str(page), p38])
    text = page.read_text(encoding="utf-8")
    assert "<td>02:2</td>" in text and "<td>2:2</td>" not in text


def test_ramps_say_their_unit_unscaled() -> None:
    # ACC/DEC count in s, at a scale the drive's ramp increment (Inr) sets: unit named, number unscaled.
    lines = run_cli([str(CAPTURES / "atv71_commissioning.pcap")])[1].splitlines()
    assert lines[16] == ("    17     0.206804   2 request   Write Multiple Registers 9001..9002 (2): "
                         "ACC=10 (unscaled, in s) DEC=10 (unscaled, in s)  CRC ok")
    status, out, _ = run_cli([str(CAPTURES / "atv71_commissioning.pcap"), "--json", "-Y", "frame == 17"])
    (acc, dec) = json.loads(out)["registers"]
    assert (acc["code"], acc["value"], acc["unit"], acc["text"], acc.get("scaled")) == (
        "ACC", 10, "s", "10 (unscaled, in s)", None)


def watch_lines(file_records: list[dict], stream_records: list[dict]) -> list[tuple[int, int, int, bool]]:
    """The --watch lines of an input read once (standard input, live), from --json of the same bytes:
    a frame decoded before profile auto chose its slave's device (`provisional` in the stream's --json)
    shows the changes between such frames as decoded, marked provisional; every other frame the changes
    of the parameter history, which reads the provisional frames again with the device (what --json of
    the file, read twice, says of them): re-reading itself is no change."""
    provisional = [record for record in stream_records if record.get("provisional")]
    early = {record["frame"] for record in provisional}
    lines = [(frame, slave, address, True) for frame, slave, address in derive(provisional)[2]]
    lines += [(frame, slave, address, False) for frame, slave, address in derive(file_records)[2]
              if frame not in early]
    return sorted(lines, key=lambda line: line[0])  # stable: a frame's registers in their order


def test_standard_input_says_what_the_file_says(tmp_path: Path) -> None:
    # Read once, a slave's frames before profile auto chose its device are provisional; --stats and
    # the report see the whole input before they print: they count exactly what the file (read twice)
    # counts. --watch writes as the frames come: provisional lines are marked, the rest are the file's.
    marked = checked = 0
    for path, options in inputs(tmp_path):
        data = Path(path).read_bytes()
        file_records = [json.loads(line) for line in run_cli([path, "--json", *options])[1].splitlines()]
        status, out, _ = run_cli(["-", "--json", *options], stdin=data)
        assert status == 0, path
        stream_records = [json.loads(line) for line in out.splitlines()]
        assert [record["frame"] for record in stream_records] == [record["frame"] for record in file_records]
        traffic, params, _changes, protections = derive(file_records)

        status, out, _ = run_cli(["-", "--stats", "--json", *options], stdin=data)
        stream_stats = json.loads(out)
        assert stream_stats == json.loads(run_cli([path, "--stats", "--json", *options])[1]), path
        got = {(row["slave"], row["address"]): row for row in stream_stats["parameters"]}
        assert {key: (row["reads"], row["unreadable"], row["writes"], row["refused"], row["changes"])
                for key, row in got.items()} == {
            key: (entry["reads"], entry["unreadable"], entry["writes"], entry["refused"], entry["changes"])
            for key, entry in params.items()}, path

        page = tmp_path / "stream.html"
        assert run_cli(["-", "--report", str(page), *options], stdin=data)[0] == 0
        data_ = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(encoding="utf-8")).group(1))
        assert data_["event_counts"]["protection"] == len(protections), path
        if not data_["timed"] and not data_["events_dropped"]:
            assert [(int(event[0]), event[2]) for event in data_["events"] if event[1] == "protection"] == protections
        assert run_cli([path, "--report", str(page), *options])[0] == 0
        from_file = json.loads(re.search(r'id="report-data">(.*?)</script>', page.read_text(encoding="utf-8")).group(1))
        # The whole report's data, but which series it keeps beyond its bound (first come: the frames
        # held until their slave's choice come later).
        # The setpoints listed are those of the series drawn (html.py), so they follow the same choice.
        keys = [key for key in from_file
                if key not in ("parameters", "written") or not from_file["parameters_dropped"]]
        assert {key: data_[key] for key in keys} == {key: from_file[key] for key in keys}, path
        drawn = [{"%d:%d" % (row["slave"], row["address"]) for row in page_["parameters"]}
                 for page_ in (data_, from_file)]
        assert set(data_["written"]) <= drawn[0] and set(from_file["written"]) <= drawn[1], path
        both = drawn[0] & drawn[1]
        assert set(data_["written"]) & both == set(from_file["written"]) & both, path

        addresses = sorted({address for _slave, address in params})
        if addresses:
            status, out, err = run_cli(["-", "--watch", ",".join(map(str, addresses)), "--json", *options], stdin=data)
            assert status == 0, err
            lines = [json.loads(line) for line in out.splitlines()]
            assert [(c["frame"], c["slave"], c["address"], c.get("provisional", False)) for c in lines] == (
                watch_lines(file_records, stream_records)), path
            marked += sum(c.get("provisional", False) for c in lines)
        checked += 1
    assert checked == 18 and marked > 0


def test_p38_read_once_counts_as_the_file() -> None:
    # Frame 2 reads 8400..8402 before profile auto chose the ATV71 (frame 4): 16#8000 at 8400 is the
    # VW3 card's non-existent marker there too once the choice is made, never a value that changed.
    pcap = CAPTURES / "p38_protection.pcap"
    data = pcap.read_bytes()
    assert run_cli(["-", "--watch", "8400,CHCF"], stdin=data) == (
        0, "     6     1.059949  12 CHCF IO (I/O profile) -> protected\n", "")
    status, out, _ = run_cli(["-", "--stats"], stdin=data)
    table = out[out.index("Parameters\n"):].split("\n\n")[0].splitlines()
    assert table[3:6] == [
        "   12      8400            0           6       0        0  non-existent        0",
        "   12      8401  CHCF      2           4       0        0  protected           1",
        "   12      8402  COP       4           2       0        0  protected           1",
    ]


def test_plant_mix_read_once_marks_its_early_watch_lines(tmp_path: Path) -> None:
    # Slaves 3 to 5 of the plant mix write LFR (8502) before profile auto chose the ATV71: those lines
    # are provisional, by address (no device names 8502 yet) and unscaled; the file names them LFR.
    _raw, pcap = write_capture(plant_mix(1500, seed=3), tmp_path / "plant")
    stream = run_cli(["-", "--watch", "LFR"], stdin=pcap.read_bytes())[1].splitlines()
    assert stream[:5] == [
        "    30     0.604164   2 LFR 0.0 -> 1.3 (Hz)",
        "    32     0.637298   3 8502 97 -> 110 [provisional]",
        "    36     0.701086   4 8502 194 -> 207 [provisional]",
        "    38     0.730595   5 8502 291 -> 304 [provisional]",
        "    54     1.155817   2 LFR 1.3 -> 2.6 (Hz)",
    ]
    assert run_cli([str(pcap), "--watch", "LFR"])[1].splitlines()[1:4] == [
        "    32     0.637298   3 LFR 9.7 -> 11.0 (Hz)",
        "    36     0.701086   4 LFR 19.4 -> 20.7 (Hz)",
        "    38     0.730595   5 LFR 29.1 -> 30.4 (Hz)",
    ]
    # The first line after the choice compares with the re-read value: no invented change.
    assert not any("[provisional]" in line for line in stream[5:] if line.split()[2] == "2")


def test_live_watch_says_what_standard_input_says(tmp_path: Path) -> None:
    # Live through a pseudo-terminal, a frame at a time: the --watch lines (provisional ones marked)
    # are those of the capture it wrote read once, and derive from --json of those bytes as above.
    from live_bus import live_on_pty

    from dissector.sources.reader import open_source

    _raw, session = write_capture(generate_session(40, seed=11), tmp_path / "session")
    marked = 0
    for source in (CAPTURES / "p38_protection.pcap", CAPTURES / "atv71_commissioning.pcap", session):
        frames = [chunk.data for chunk in open_source(str(source))]
        written = tmp_path / "live.pcap"
        records = [json.loads(line) for line in run_cli([str(source), "--json"])[1].splitlines()]
        addresses = ",".join(map(str, sorted({address for _slave, address in derive(records)[1]})))
        lines, err, status = live_on_pty(frames, "--watch", addresses, "--json", "-w", str(written), pause=0.02)
        assert status == 0, err
        live = [json.loads(line) for line in lines]
        data = written.read_bytes()
        assert run_cli(["-", "--watch", addresses, "--json"], stdin=data)[1].splitlines() == lines, source
        file_records = [json.loads(line) for line in run_cli([str(written), "--json"])[1].splitlines()]
        stream_records = [json.loads(line) for line in run_cli(["-", "--json"], stdin=data)[1].splitlines()]
        assert len(file_records) == len(frames), source  # a frame a record: the live line framed them all
        assert [(c["frame"], c["slave"], c["address"], c.get("provisional", False)) for c in live] == (
            watch_lines(file_records, stream_records)), source
        marked += sum(c.get("provisional", False) for c in live)
    assert marked > 0  # the session's slaves are judged over several answers: its early lines say so
