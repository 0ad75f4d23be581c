"""A long fuzzing campaign over the same targets as tests/differential/test_fuzz.py.

    python3 bench/fuzz_campaign.py --seconds 600                  # both engines, time shared by all targets
    python3 bench/fuzz_campaign.py --seconds 120 --engine hypothesis --target rtu_framer

Every target is a function of one byte string that must return normally or raise the module's own
error (GrammarError, SourceError, ProfileError, FilterError); anything else is a crash. Two engines:

- hypothesis: the structured strategies of tests/differential/test_fuzz.py (valid frames and files, mutated), run
  in rounds of 500 examples with a new seed each until the target's time is up;
- atheris (coverage-guided libFuzzer, if `pip install atheris` worked): one child process per target,
  seeded with the valid files, for its share of the time.

It prints, per target and engine, the number of inputs tried and the outcome; a crash prints the input
(hex) and the traceback, and atheris keeps it in bench/out/fuzz/crash-*. Exit status 1 when anything
crashed. Each crash found becomes a regression test (tests/differential/test_fuzz.py or tests/unit/test_bad_files.py).
"""
from __future__ import annotations

import argparse
import io
import os
import re
import subprocess
import sys
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT), str(ROOT / "tests")]

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
from dissector.render.jsonout import item_to_dict  # noqa: E402
from dissector.sources.reader import SourceError  # noqa: E402

OUT = ROOT / "bench" / "out" / "fuzz"
FORMATS = (None, "raw", "pcap", "pcapng", "hex", "ascii")
KINDS = (Kind.REQUEST, Kind.RESPONSE, Kind.EXCEPTION)
CLI_OPTIONS = (["--json"], ["-V"], ["-x"], ["--stats"], ["-n"], ["--mode", "ascii"], ["--profile", "sel749m"],
               ["--address-style", "plc"])


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


def cli(data: bytes) -> None:
    flags = data[0] if data else 0
    argv = ["-", *[word for bit, option in enumerate(CLI_OPTIONS) if flags >> bit & 1 for word in option]]
    fmt = FORMATS[data[1] % len(FORMATS)] if len(data) > 1 else None
    if fmt is not None:
        argv += ["--format", fmt]
    out, err = io.StringIO(), io.StringIO()
    env = Environment(io.BufferedReader(io.BytesIO(data[2:])), out, err, stdout_isatty=False,
                      stderr_isatty=False)
    status = run(argv, env)
    lines = err.getvalue().splitlines()
    assert all(line.startswith("vw3-decode: ") for line in lines), lines
    errors = [line for line in lines if not line.startswith("vw3-decode: warning: ")]
    assert (status, len(errors)) in ((0, 0), (2, 1)), (status, lines)


def _prefixed(prefix: st.SearchStrategy[bytes], body: st.SearchStrategy[bytes]) -> st.SearchStrategy[bytes]:
    return st.tuples(prefix, body).map(lambda pair: pair[0] + pair[1])


_mutated_file = st.builds(
    lambda name, seed_, count: tf.mutate(tf.VALID_FILES[name], seed_, count),
    st.sampled_from(sorted(tf.VALID_FILES)), st.integers(0, 2**32), st.integers(0, 8),
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
    seeds: tuple[bytes, ...]  # initial corpus for atheris


_FOUR = st.binary(min_size=4, max_size=4)
TARGETS: dict[str, Target] = {
    "rtu_framer": Target(rtu_framer, _prefixed(_FOUR, st.one_of(tf.rtu_streams(), st.binary(max_size=600))),
                         (b"\3\1\2\3" + tf.VALID_FILES["raw"],)),
    "ascii_framer": Target(ascii_framer, _prefixed(_FOUR, tf.ascii_streams()),
                           (b"\3\1\2\3" + tf.VALID_FILES["ascii"],)),
    "pipeline": Target(pipeline, _prefixed(_FOUR, tf.rtu_streams()), (b"\1\5\0\0" + tf.VALID_FILES["raw"],)),
    "grammar": Target(grammar, st.tuples(tf.FUNCTIONS, st.integers(0, 2), st.binary(max_size=300)).map(
        lambda t: bytes([t[0], t[1]]) + t[2]), tuple(bytes([frame[1], 0]) + frame[2:-2] for frame in tf.FRAMES)),
    "readers": Target(readers, _prefixed(st.binary(min_size=1, max_size=1), _mutated_file),
                      tuple(bytes([index]) + data for index, data in enumerate(tf.VALID_FILES.values()))),
    "map_loader": Target(map_loader, _map_text, (b"8401,CHCF,[Profile],,,RW,3=IO,,,a\n",)),
    "filter_parser": Target(filter_parser, _filter_text, (b'slave == 12 and code == "CHCF"',)),
    "cli": Target(cli, _prefixed(st.binary(min_size=2, max_size=2), _mutated_file),
                  tuple(b"\0\0" + data for data in tf.VALID_FILES.values())),
}


# -- engines ------------------------------------------------------------------------------------------
@dataclass
class Outcome:
    target: str
    engine: str
    inputs: int = 0
    seconds: float = 0.0
    crash: str | None = None  # one line; details printed when found


def run_hypothesis(name: str, seconds: float) -> Outcome:
    target = TARGETS[name]
    outcome = Outcome(name, "hypothesis")
    started = time.monotonic()
    count = [0]

    def check(data: bytes) -> None:
        count[0] += 1
        target.check(data)

    round_ = 0
    while time.monotonic() - started < seconds and outcome.crash is None:
        test = seed(round_)(settings(deadline=None, max_examples=500, database=None, derandomize=False,
                                     suppress_health_check=list(HealthCheck))(given(target.strategy)(check)))
        try:
            test()
        except Exception as error:  # a crash: hypothesis has shrunk it and printed the example
            outcome.crash = f"{type(error).__name__}: {str(error).splitlines()[0] if str(error) else ''}"
            traceback.print_exc()
        round_ += 1
    outcome.inputs, outcome.seconds = count[0], time.monotonic() - started
    return outcome


def atheris_child(name: str, argv: list[str]) -> None:
    import atheris

    check = TARGETS[name].check

    def one_input(data: bytes) -> None:
        check(data)

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
        outcome.crash = found.group(1).strip() if found else f"exit status {done.returncode}"
        print(log[-4000:], file=sys.stderr)
    return outcome


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--atheris-child"]:
        atheris_child(argv[1], argv[2:])
        return 0
    parser = argparse.ArgumentParser(description="Fuzz the dissector's parsers for a while.")
    parser.add_argument("--seconds", type=float, default=600, help="total time, shared by targets and engines")
    parser.add_argument("--engine", choices=["both", "hypothesis", "atheris"], default="both")
    parser.add_argument("--target", action="append", choices=sorted(TARGETS), help="only these targets")
    args = parser.parse_args(argv)
    engines = ["hypothesis", "atheris"] if args.engine == "both" else [args.engine]
    if "atheris" in engines:
        try:
            import atheris  # noqa: F401
        except ImportError:
            print("atheris is not installed (pip install atheris): hypothesis only", file=sys.stderr)
            engines = [engine for engine in engines if engine != "atheris"] or ["hypothesis"]
    names = args.target or list(TARGETS)
    share = args.seconds / (len(names) * len(engines))
    OUT.mkdir(parents=True, exist_ok=True)
    outcomes: list[Outcome] = []
    for name in names:
        for engine in engines:
            outcome = (run_hypothesis if engine == "hypothesis" else run_atheris)(name, share)
            outcomes.append(outcome)
            print(f"{name:14} {engine:10} {outcome.inputs:>10,} inputs {outcome.seconds:7.1f} s  "
                  f"{outcome.crash or 'no crash'}", flush=True)
    total = sum(outcome.inputs for outcome in outcomes)
    crashes = [outcome for outcome in outcomes if outcome.crash]
    print(f"total: {total:,} inputs in {sum(o.seconds for o in outcomes):.0f} s, {len(crashes)} crashing target(s)")
    return 1 if crashes else 0


if __name__ == "__main__":
    sys.exit(main())
