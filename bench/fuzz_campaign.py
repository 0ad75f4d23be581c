"""A long fuzzing campaign: every input format, option set, the compiled engine and the Lua plugin.

    python3 bench/fuzz_campaign.py --seconds 600                  # all engines, time shared by all targets
    python3 bench/fuzz_campaign.py --inputs 1000000 --plugin-records 100000 --json bench/out/fuzz/campaign.json
    python3 bench/fuzz_campaign.py --seconds 120 --engine hypothesis --target rtu_framer

It runs as shipped from a clean clone (no PYTHONPATH: it puts the checkout and tests/ on sys.path).
Every target is a function of one byte string that must return normally or raise the module's own
error (GrammarError, SourceError, ProfileError, FilterError); anything else is a traceback. The
`engine` target decodes a stream with the compiled summary path and with the Python stages (the
reference) and counts a difference when a line differs; the `cli` target runs vw3-decode on a
mutated file of one of the 10 input formats with one of 2^24 combinations of 24 option sets
(-V -x --json --stats --color always -T fields -t ad/ud -Y -w --report --watch -c --map ...), and
checks exit 0 with no error line or exit 2 with one. The `plugin` target writes records (fuzzed,
mutated, floods of `:` and FC43 bytes) into pcaps and runs `tshark -V -X lua_script:lua/vw3.lua`:
a Lua error in its output is a traceback.

Three engines share the time: mutate (deterministic mutations of valid inputs, one seed an input,
fast), hypothesis (the structured strategies of tests/differential/test_fuzz.py, in rounds of 500
examples) and atheris (coverage-guided libFuzzer, when `pip install atheris` worked).

It prints, per target and engine, the inputs tried and the outcome; a crash prints the input (hex)
and the traceback. Exit status 1 when anything crashed or differed. Each crash found becomes a
regression test (tests/differential/test_fuzz.py, tests/unit/test_hostile.py).
"""
from __future__ import annotations

import argparse
import io
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import traceback
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), *(str(ROOT / "tests" / sub) for sub in ("", "support", "differential"))]

if not any((ROOT / "dissector" / "accel").glob("_summary*.so")) and sys.argv[1:2] != ["--atheris-child"]:
    # A clean clone: the engine target compares the compiled path with the Python stages, so build it
    # in place as `pip install -e .` does (without a C compiler the engine target is left out).
    built = subprocess.run([sys.executable, "setup.py", "-q", "build_ext", "--inplace"], cwd=ROOT,
                           capture_output=True, text=True)
    if built.returncode != 0:
        print(f"the compiled extension could not be built (the engine target is left out): "
              f"{(built.stderr.strip().splitlines() or ['?'])[-1]}", file=sys.stderr)

if sys.argv[1:2] == ["--atheris-child"]:
    # Instrument the dissector and construct (its grammars) for coverage as they are first imported
    # (not everything: instrumenting hypothesis too costs a minute per child and guides nothing).
    import atheris

    with atheris.instrument_imports(include=["dissector", "construct"]):
        import dissector.app.cli  # noqa: F401  (imports every stage the targets reach)
        import dissector.sources.hexdump  # noqa: F401
        import dissector.sources.pcap  # noqa: F401
        import dissector.sources.pcapng  # noqa: F401

from hypothesis import HealthCheck, given, seed, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import test_fuzz as tf  # noqa: E402  (the suite's strategies and properties)
from dissector.framing.ascii import AsciiFramer  # noqa: E402
from dissector.app.cli import Environment, run  # noqa: E402
from dissector.render.filters import FilterError, compile_filter  # noqa: E402
from dissector.framing.rtu import RtuFramer  # noqa: E402
from dissector.protocol.grammar import GrammarError, parse_pdu  # noqa: E402
from dissector.model import Kind  # noqa: E402
from dissector.pipeline import dissect  # noqa: E402
from dissector.devices.build import build_annotator  # noqa: E402
from dissector.render.jsonout import item_to_dict  # noqa: E402
from dissector.sim.simulate import generate_session  # noqa: E402
from dissector.sources.reader import SourceError  # noqa: E402
from helpers import rtu  # noqa: E402
from test_fastsummary import LONG_NOTES, fast_lines, python_lines  # noqa: E402

OUT = ROOT / "bench" / "out" / "fuzz"
SCRATCH = Path(tempfile.mkdtemp(prefix="vw3-fuzz-"))  # -w, --report and --map files of the cli target
FORMATS = (None, "raw", "pcap", "pcapng", "hex", "hexdump", "hexdump-C", "xxd", "traffic", "ascii")
KINDS = (Kind.REQUEST, Kind.RESPONSE, Kind.EXCEPTION)
# A map whose texts are hostile: formulas, markup, an ESC, the report's `<!--` and `</script>`.
MAP_FILE = SCRATCH / "hostile.csv"
MAP_FILE.write_text(
    "address,code,name,unit,scale,enum\n"
    '8401,=HYPERLINK("x"),[/x] <!-- </script>,\x1b[31m,,1=@SUM(1);3=+1+1\n'
    "3201,HSP,[conceal]x,Hz,0.1,\n8402,CMD,-1+1,,1e-3,\n",
    encoding="utf-8",
)
FIELDS = ["-T", "fields", "-e", "frame", "-e", "time", "-e", "code", "-e", "value", "-e", "fields.additional_data",
          "-E", "separator=,", "-E", "header=y"]
# Option sets in groups of choices that go together (one of each group an input): the outputs, the
# device semantics, the time column, the filter, the rest.
CLI_GROUPS: tuple[tuple[list[str], ...], ...] = (
    ([], ["-V"], ["-x"], ["-V", "-x"], ["--json"], FIELDS, ["--stats"], ["--stats", "--json"],
     ["--watch", "CHCF,HSP,3201"], ["--report", str(SCRATCH / "report.html")], ["-w", str(SCRATCH / "out.pcap")],
     ["-w", str(SCRATCH / "out.pcapng"), "-P", "-V"], ["-c", "3"], ["-x", "-c", "5"], FIELDS + ["-E", "quote=d"],
     ["--watch", "8401", "--json"]),
    ([], [], ["-n"], ["--profile", "sel749m"], ["--profile", "atv71"], ["--map", str(MAP_FILE)],
     ["--profile", "atv71", "--map", str(MAP_FILE)], ["--address-style", "plc"]),
    ([], ["-t", "ad"], ["-t", "ud"], ["-t", "d"], ["-t", "dd"], ["-t", "e"], ["-t", "a"], ["-t", "u"]),
    ([], [], ["-Y", "address == 0 or slave == 12"], ["-Y", 'value > 3 and not code == "CHCF"'],
     ["-Y", 'kind == "exception" or not crc_ok'], ["-Y", "function == 43 or function == 17"]),
    ([], [], ["--color", "always"], ["--mode", "ascii"], ["--mode", "rtu"], ["--timeout", "0.001"]),
)
CLI_OPTIONS = tuple(option for group in CLI_GROUPS for option in group if option)
SLOW_SECONDS = 20.0  # an input that takes longer is reported (cost must stay bounded per byte)


def _tool_dump(command: list[str], data: bytes) -> bytes | None:
    """xxd's and hexdump -C's rendering of `data`, from the tools themselves when installed."""
    if shutil.which(command[0]) is None:
        return None
    return subprocess.run(command, input=data, capture_output=True, check=True).stdout


def _valid_files() -> dict[str, bytes]:
    files = dict(tf.VALID_FILES)
    raw = b"".join(tf.FRAMES) * 3  # repeated lines: hexdump -C writes `*` for them
    for name, command in (("xxd", ["xxd"]), ("hexdump-C", ["hexdump", "-C"])):
        dump = _tool_dump(command, raw)
        if dump is not None:
            files[name] = dump
    files["traffic"] = "".join(
        f"{'Tx' if index % 2 == 0 else 'Rx'}:{index:06d}-10:15:{index:02d}.125-{frame.hex(' ').upper()}\n"
        for index, frame in enumerate(tf.FRAMES)
    ).encode()
    return files


VALID_FILES = _valid_files()
_FILE_FORMAT = {"hex": "hex", "xxd": "xxd", "hexdump-C": "hexdump-C", "traffic": "traffic"}


class Difference(AssertionError):
    """The compiled path and the Python stages wrote different lines."""


class Slow(Exception):
    """An input took longer than SLOW_SECONDS."""


# -- targets: bytes in, the module's own error or nothing out ------------------------------------------
def _cuts(data: bytes) -> tuple[list[int], bytes]:
    """The first 4 bytes choose where the rest is split (0..3 cut points), the rest is the stream."""
    head, body = data[:4], data[4:]
    return [byte * 7 for byte in head[: (head[0] % 4 if head else 0)]], body


def rtu_framer(data: bytes) -> None:
    cuts, body = _cuts(data)
    tf._framer_property(body, cuts, RtuFramer)


def ascii_framer(data: bytes) -> None:
    cuts, body = _cuts(data)
    tf._framer_property(body, cuts, AsciiFramer)


def pipeline(data: bytes) -> None:
    cuts, body = _cuts(data)
    items = list(dissect(tf.split(body, cuts), annotate=tf.ANNOTATOR))
    assert b"".join(item.raw for item in items) == body
    for item in items:
        item_to_dict(item)


def grammar(data: bytes) -> None:
    if len(data) < 2:
        return
    try:
        parse_pdu(data[0], KINDS[data[1] % 3], data[2:])
    except GrammarError as error:
        assert str(error) and "\n" not in str(error)


def readers(data: bytes) -> None:
    if not data:
        return
    try:
        tf.read_all(data[1:], FORMATS[data[0] % len(FORMATS)])
    except SourceError as error:
        assert str(error) and "\n" not in str(error)


def map_loader(data: bytes) -> None:
    text = data.decode("utf-8", "replace")
    tf.test_map_loader_names_the_line_of_every_error.hypothesis.inner_test(  # type: ignore[attr-defined]
        "address,code,name,unit,scale,access,enum,bits,signed,source", text.splitlines()
    )


def filter_parser(data: bytes) -> None:
    text = data.decode("utf-8", "replace")
    try:
        predicate = compile_filter(text)
    except FilterError as error:
        assert 0 <= error.position <= len(text)
        return
    for item in tf.SAMPLE_ITEMS:
        assert predicate(item) in (True, False)


def cli_argv(data: bytes) -> list[str]:
    """Options from the first 3 bytes (a choice in each group), the format from the 4th."""
    choices = int.from_bytes(data[:3].ljust(3, b"\0"), "little")
    argv = ["-"]
    for group in CLI_GROUPS:
        choices, pick = divmod(choices, len(group))
        argv += group[pick]
    # Half the inputs detect their format, half force one of the 9 (mostly the wrong one: exit 2).
    pick = data[3] % (2 * len(FORMATS)) if len(data) > 3 else 0
    fmt = FORMATS[pick] if pick < len(FORMATS) else None
    return argv + (["--format", fmt] if fmt is not None else [])


def cli(data: bytes) -> None:
    argv = cli_argv(data)
    out, err = io.StringIO(), io.StringIO()
    env = Environment(io.BufferedReader(io.BytesIO(data[4:])), out, err, stdout_isatty=False,
                      stderr_isatty=False)
    status = run(argv, env)
    lines = err.getvalue().splitlines()
    # A display filter's error shows the filter and a caret under the fault, as tshark: lines of two
    # spaces that continue the error line before them.
    assert not lines or lines[0].startswith("vw3-decode: "), lines
    assert all(line.startswith(("vw3-decode: ", "  ")) for line in lines), lines
    errors = [line for line in lines if line.startswith("vw3-decode: ") and not line.startswith("vw3-decode: warning: ")]
    assert (status, len(errors)) in ((0, 0), (2, 1)), (status, lines)
    if "--color" not in argv:  # bus and map texts never reach the terminal as an escape sequence
        assert "\x1b" not in out.getvalue(), "an ESC in the output"


ANNOTATORS: tuple[Callable[[], object], ...] = (
    lambda: None,
    lambda: build_annotator(["atv71"], [], None),
    lambda: build_annotator([], [], None),  # auto, the default
    lambda: build_annotator(["sel749m"], [], None),
)


def engine(data: bytes) -> None:
    """The compiled summary path against the Python stages: the same lines, however the stream is cut."""
    if not data:
        return
    make = ANNOTATORS[data[0] % len(ANNOTATORS)]
    cuts, body = _cuts(data[1:])
    expected = python_lines(body, make())
    got = fast_lines(body, make(), [cut for cut in cuts if cut < len(body)]).lines
    if got != expected:
        first = next(index for index, (a, b) in enumerate(zip([*got, None], [*expected, None])) if a != b)
        raise Difference(f"line {first + 1}: engine {got[first:first + 1]} python {expected[first:first + 1]}")


def _long_notes_streams() -> list[bytes]:
    """FC43 answers with long object values (long notes under the ATV71 profile) and a trailing byte,
    as the C path once showed three notes where Python counts them past the 240-character budget."""
    streams = list(LONG_NOTES)
    for count, length, trailing in ((3, 90, 1), (5, 60, 2), (2, 200, 1)):
        objects = b"".join(bytes([2, length]) + bytes([0x41 + index]) * length for index in range(count))
        pdu = bytes([0x2B, 0x0E, 0x03, 0x81, 0x00, 0x00, count]) + objects.replace(bytes([0x41]), b"\x1b")
        streams.append(rtu("0c2b0e0300") + rtu("0c" + pdu.hex()) + bytes(range(1, trailing + 1)))
    return streams


def _sessions() -> list[bytes]:
    return [b"".join(data for data, _time in generate_session(60, seed=number)) for number in range(4)]


def _prefixed(prefix: st.SearchStrategy[bytes], body: st.SearchStrategy[bytes]) -> st.SearchStrategy[bytes]:
    return st.tuples(prefix, body).map(lambda pair: pair[0] + pair[1])


_mutated_file = st.builds(
    lambda name, seed_, count: tf.mutate(VALID_FILES[name], seed_, count),
    st.sampled_from(sorted(VALID_FILES)), st.integers(0, 2**32), st.integers(0, 8),
)
_map_text = st.lists(st.lists(tf.CELLS, min_size=1, max_size=11).map(",".join), max_size=8).map(
    lambda rows: "\n".join(rows).encode("utf-8", "replace")
)
_filter_text = st.one_of(st.lists(tf.FILTER_WORDS, max_size=14).map(" ".join), st.text(max_size=60)).map(
    lambda text: text.encode("utf-8", "replace")
)


@dataclass(frozen=True)
class Target:
    check: Callable[[bytes], None]
    strategy: st.SearchStrategy[bytes]  # for the hypothesis engine
    seeds: tuple[bytes, ...]  # initial corpus for atheris and the mutate engine
    head: int = 0  # leading control bytes (cuts, options, format) the mutate engine draws at random


_FOUR = st.binary(min_size=4, max_size=4)
_ENGINE_SEEDS = (*_long_notes_streams(), *_sessions(), tf.VALID_FILES["raw"])
TARGETS: dict[str, Target] = {
    "rtu_framer": Target(rtu_framer, _prefixed(_FOUR, st.one_of(tf.rtu_streams(), st.binary(max_size=600))),
                         (b"\3\1\2\3" + tf.VALID_FILES["raw"],), 4),
    "ascii_framer": Target(ascii_framer, _prefixed(_FOUR, tf.ascii_streams()),
                           (b"\3\1\2\3" + tf.VALID_FILES["ascii"],), 4),
    "pipeline": Target(pipeline, _prefixed(_FOUR, tf.rtu_streams()), (b"\1\5\0\0" + tf.VALID_FILES["raw"],), 4),
    "grammar": Target(grammar, st.tuples(tf.FUNCTIONS, st.integers(0, 2), st.binary(max_size=300)).map(
        lambda t: bytes([t[0], t[1]]) + t[2]), tuple(bytes([frame[1], 0]) + frame[2:-2] for frame in tf.FRAMES), 2),
    "readers": Target(readers, _prefixed(st.binary(min_size=1, max_size=1), _mutated_file),
                      tuple(bytes([FORMATS.index(name)]) + data for name, data in VALID_FILES.items()), 1),
    "map_loader": Target(map_loader, _map_text, (b"8401,CHCF,[Profile],,,RW,3=IO,,,a\n",
                                                  MAP_FILE.read_bytes().split(b"\n", 1)[1])),
    "filter_parser": Target(filter_parser, _filter_text, (b'slave == 12 and code == "CHCF"',
                                                          b"address == 0 or value > 3 and not fields.x")),
    "cli": Target(cli, _prefixed(st.binary(min_size=4, max_size=4), _mutated_file),
                  tuple(b"\0\0\0\0" + data for data in VALID_FILES.values()), 4),
    "engine": Target(engine, _prefixed(_FOUR, st.one_of(tf.rtu_streams(), st.sampled_from(_ENGINE_SEEDS))),
                     tuple(b"\2\3\1\2" + data for data in _ENGINE_SEEDS), 4),
}


# -- engines ------------------------------------------------------------------------------------------
@dataclass
class Outcome:
    target: str
    engine: str
    inputs: int = 0
    seconds: float = 0.0
    tracebacks: int = 0  # anything but the module's own error (a Lua error for the plugin)
    differences: int = 0  # engine: compiled path != Python stages
    slow: int = 0  # inputs over SLOW_SECONDS
    examples: list[str] = field(default_factory=list)  # the first few, one line each

    @property
    def crash(self) -> str | None:
        return self.examples[0] if self.examples else None

    def found(self, kind: str, data: bytes, error: BaseException | str) -> None:
        setattr(self, kind, getattr(self, kind) + 1)
        if len(self.examples) < 5:
            line = error if isinstance(error, str) else f"{type(error).__name__}: {str(error).splitlines()[0] if str(error) else ''}"
            self.examples.append(f"{kind}: {line[:300]} (input {data[:200].hex()})")
            if not isinstance(error, str):
                traceback.print_exception(error)


def _on_alarm(_signum: int, _frame: object) -> None:
    raise Slow(f"over {SLOW_SECONDS:.0f} s")


def checked(outcome: Outcome, check: Callable[[bytes], None], data: bytes) -> None:
    """One input: a difference, a slow input and a traceback are counted, never raised."""
    outcome.inputs += 1
    signal.setitimer(signal.ITIMER_REAL, SLOW_SECONDS)
    try:
        check(data)
    except Slow as error:
        outcome.found("slow", data, str(error))
    except Difference as error:
        outcome.found("differences", data, error)
    except Exception as error:  # noqa: BLE001  (a traceback: what the campaign looks for)
        outcome.found("tracebacks", data, error)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)


def run_mutate(name: str, seconds: float, budget: int, seed_: int) -> Outcome:
    """Deterministic mutations of the target's seeds, `budget` inputs or `seconds`, whichever first."""
    target = TARGETS[name]
    outcome = Outcome(name, "mutate")
    rng = random.Random(f"{name}/{seed_}")
    started = time.monotonic()
    while outcome.inputs < budget and time.monotonic() - started < seconds:
        base = rng.choice(target.seeds)
        body = tf.mutate(base[target.head:], rng.getrandbits(32), rng.choice((0, 1, 1, 2, 3, 5, 8)))
        checked(outcome, target.check, rng.randbytes(target.head) + body)
    outcome.seconds = time.monotonic() - started
    return outcome


def run_hypothesis(name: str, seconds: float) -> Outcome:
    target = TARGETS[name]
    outcome = Outcome(name, "hypothesis")
    started = time.monotonic()

    def check(data: bytes) -> None:
        checked(outcome, target.check, data)

    round_ = 0
    while time.monotonic() - started < seconds:
        test = seed(round_)(settings(deadline=None, max_examples=500, database=None, derandomize=False,
                                     suppress_health_check=list(HealthCheck))(given(target.strategy)(check)))
        test()
        round_ += 1
    outcome.seconds = time.monotonic() - started
    return outcome


def atheris_child(name: str, argv: list[str]) -> None:
    import atheris

    check = TARGETS[name].check

    def one_input(data: bytes) -> None:
        try:
            check(data)
        except Slow:
            pass

    atheris.Setup([sys.argv[0], *argv], one_input)
    atheris.Fuzz()


def run_atheris(name: str, seconds: float) -> Outcome:
    outcome = Outcome(name, "atheris")
    corpus = OUT / f"corpus-{name}"
    corpus.mkdir(parents=True, exist_ok=True)
    for index, data in enumerate(TARGETS[name].seeds):
        (corpus / f"seed-{index}").write_bytes(data)
    command = [sys.executable, __file__, "--atheris-child", name, f"-max_total_time={max(1, int(seconds))}",
               f"-artifact_prefix={OUT}/crash-{name}-", "-max_len=4096", "-print_final_stats=1", str(corpus)]
    started = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True, cwd=ROOT, env={**os.environ, "PYTHONHASHSEED": "0"})
    outcome.seconds = time.monotonic() - started
    log = done.stderr
    runs = re.findall(r"stat::number_of_executed_units: (\d+)", log) or re.findall(r"^#(\d+)", log, re.M)
    outcome.inputs = int(runs[-1]) if runs else 0
    if done.returncode != 0:
        found = re.search(r"(Uncaught Python exception: .*|Test unit written to .*)", log)
        outcome.found("tracebacks", b"", found.group(1).strip() if found else f"exit status {done.returncode}")
        print(log[-4000:], file=sys.stderr)
    return outcome


# -- the plugin: records through tshark -V -X lua_script:lua/vw3.lua ------------------------------------
PLUGIN_BATCH = 10_000  # records a tshark run


def plugin_records(seed_: int, count: int) -> list[tuple[bytes, float]]:
    """Fuzzed records (lua_session.random_records), mutated frames and files, FC43 answers with ESC and
    markup in their objects, and floods of `:` and of the bytes that once cost the plugin most."""
    from lua_session import random_records

    rng = random.Random(seed_)
    records = random_records(seed_, count * 3 // 4)
    stamp = records[-1][1] if records else 0.0
    hostile = [
        rtu("0c2b0e0100"),
        rtu("0c2b0e01010000020014" + b"\x1b]8;;http://x\x1b\\LINK\x1b[2J".hex() + "0104" + b"[/x]".hex()),
        rtu("0c0304" + b"[/x]".hex()),
    ]
    while len(records) < count:
        stamp += 0.001
        roll = rng.random()
        if roll < 0.02:
            data = bytes([rng.choice(b":+inA")]) * rng.randint(1, 20_000)  # floods
        elif roll < 0.4:
            data = tf.mutate(rng.choice([*tf.FRAMES, *hostile]), rng.getrandbits(32), rng.randint(0, 4))
        else:
            base = rng.choice([tf.VALID_FILES["raw"], tf.VALID_FILES["ascii"], *_ENGINE_SEEDS])
            data = tf.mutate(base, rng.getrandbits(32), rng.randint(0, 6))[: rng.randint(1, 600)]
        records.append((data, stamp))
    return records


def run_plugin(records_wanted: int, seconds: float, seed_: int) -> Outcome:
    from lua_harness import lua_errors, run_tshark, write_pcap

    outcome = Outcome("plugin", "tshark")
    started = time.monotonic()
    batch = 0
    while outcome.inputs < records_wanted and time.monotonic() - started < seconds:
        records = plugin_records(seed_ * 1000 + batch, min(PLUGIN_BATCH, records_wanted - outcome.inputs))
        pcap = write_pcap(SCRATCH / "plugin.pcap", records)
        for options in ((), ("-o", "vw3.mode:ascii")) if batch % 4 == 3 else ((),):
            result = run_tshark(pcap, "-V", *options)
            errors = lua_errors(result.stdout + result.stderr)
            if result.returncode != 0 and not errors:
                errors = [f"tshark exit status {result.returncode}: {result.stderr[-300:]}"]
            if "\x1b" in result.stdout:
                errors.append("an ESC byte in tshark -V")
            for error in errors:
                outcome.found("tracebacks", b"", f"batch {batch}: {error}")
        outcome.inputs += len(records)
        batch += 1
    outcome.seconds = time.monotonic() - started
    return outcome


def _print(outcome: Outcome) -> None:
    found = (f"{outcome.tracebacks} tracebacks, {outcome.differences} differences, {outcome.slow} slow"
             if outcome.examples else "no crash")
    print(f"{outcome.target:14} {outcome.engine:10} {outcome.inputs:>10,} inputs {outcome.seconds:7.1f} s  {found}",
          flush=True)
    for example in outcome.examples:
        print(f"    {example}", flush=True)


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--atheris-child"]:
        atheris_child(argv[1], argv[2:])
        return 0
    parser = argparse.ArgumentParser(description="Fuzz the dissector's parsers, engine and plugin for a while.")
    parser.add_argument("--seconds", type=float, default=600, help="time of the hypothesis and atheris engines, "
                        "shared by the targets (the mutate engine and the plugin have their own budgets)")
    parser.add_argument("--inputs", type=int, default=20_000, help="inputs of the mutate engine, shared by the targets")
    parser.add_argument("--plugin-records", type=int, default=10_000, help="records through tshark and the plugin "
                        "(0: none; needs tshark)")
    parser.add_argument("--engine", choices=["all", "mutate", "hypothesis", "atheris"], default="all")
    parser.add_argument("--target", action="append", choices=sorted(TARGETS), help="only these targets")
    parser.add_argument("--seed", type=int, default=1, help="seed of the mutate engine and the plugin's records")
    parser.add_argument("--json", type=Path, help="write the figures to this file")
    args = parser.parse_args(argv)
    engines = ["mutate", "hypothesis", "atheris"] if args.engine == "all" else [args.engine]
    if "atheris" in engines:
        try:
            import atheris  # noqa: F401
        except ImportError:
            print("atheris is not installed (pip install atheris): mutate and hypothesis only", file=sys.stderr)
            engines = [engine for engine in engines if engine != "atheris"] or ["hypothesis"]
    signal.signal(signal.SIGALRM, _on_alarm)
    names = args.target or list(TARGETS)
    from dissector.accel import fastsummary

    if fastsummary._summary is None and "engine" in names:
        print("dissector.accel._summary is not built: the engine target is left out", file=sys.stderr)
        names.remove("engine")
    timed = [engine for engine in engines if engine != "mutate"]
    share = args.seconds / (len(names) * len(timed)) if timed else 0.0
    OUT.mkdir(parents=True, exist_ok=True)
    outcomes: list[Outcome] = []
    started = time.monotonic()
    try:
        for name in names:
            for engine in engines:
                if engine == "mutate":
                    outcome = run_mutate(name, float("inf"), args.inputs // len(names), args.seed)
                elif engine == "hypothesis":
                    outcome = run_hypothesis(name, share)
                else:
                    outcome = run_atheris(name, share)
                outcomes.append(outcome)
                _print(outcome)
        if args.plugin_records and not args.target:
            outcomes.append(run_plugin(args.plugin_records, float("inf"), args.seed))
            _print(outcomes[-1])
    finally:
        shutil.rmtree(SCRATCH, ignore_errors=True)
    inputs = sum(outcome.inputs for outcome in outcomes if outcome.target != "plugin")
    records = sum(outcome.inputs for outcome in outcomes if outcome.target == "plugin")
    totals = {key: sum(getattr(outcome, key) for outcome in outcomes) for key in ("tracebacks", "differences", "slow")}
    print(f"total: {inputs:,} inputs and {records:,} plugin records in {time.monotonic() - started:.0f} s: "
          f"{totals['tracebacks']} tracebacks, {totals['differences']} differences, {totals['slow']} slow")
    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps({
            "inputs": inputs, "plugin_records": records, **totals, "seconds": round(time.monotonic() - started),
            "formats": [name or "detected" for name in FORMATS], "option_sets": [" ".join(o) for o in CLI_OPTIONS],
            "outcomes": [{**asdict(outcome), "seconds": round(outcome.seconds, 1)} for outcome in outcomes],
        }, indent=1) + "\n")
    return 1 if any(totals.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
