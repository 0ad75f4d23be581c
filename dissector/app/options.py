"""The command line of `vw3-decode`: the parser, and its conversion to typed options.

argparse stays here (issue 11): the decoding gets a DecodeOptions, checked once, with options that
contradict each other refused in one line rather than one of them silently dropped.
"""
from __future__ import annotations

import argparse
import os
from dataclasses import dataclass

from dissector import __version__
from dissector.app.live_options import BYTESIZE_GIVEN, add_live_arguments, timeout_seconds
from dissector.app.profile_options import add_profile_arguments
from dissector.app.rings import group_files
from dissector.errors import UsageError
from dissector.protocol.printable import printable
from dissector.render.fields import FieldsOptions, parse_fields_options
from dissector.render.output import OutputOptions
from dissector.render.registers import parse_registers_options
from dissector.render.timefmt import TIME_FORMATS
from dissector.sources.common import name_text
from dissector.sources.reader import FORMATS, MODES

PROG = "vw3-decode"

def shown(message: object) -> str:
    """An error or warning as standard error shows it: file names, typed option values and bus bytes
    are data, their control characters escaped as the rule titles and `==>` headers escape them
    (printable: `e\\x1b[2Jmpty.bin`); a filter error's lines are escaped already (FilterError.lines)."""
    lines = getattr(message, "lines", None)
    return "\n".join(lines) if lines is not None else printable(name_text(str(message)))


class Parser(argparse.ArgumentParser):
    """argparse that reports a bad command line as one UsageError line, not the usage text."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{message} (see {PROG} --help)")


@dataclass(frozen=True, slots=True)
class DecodeOptions:
    """What decoding files needs from the command line, checked and typed once (issue 11)."""

    files: tuple[str, ...] = ()
    hex: tuple[str, ...] = ()
    format: str | None = None
    mode: str | None = None
    timeout: float = 1.0
    baud: int = 19200
    baud_given: bool = False  # --baud typed (else a pcapng's interface description may say it)
    filter: str | None = None
    count: int | None = None
    write: str | None = None
    file_format: str | None = None  # -F
    ring: tuple[str, ...] = ()  # -b
    frame_records: bool = False  # --frame-records
    print_too: bool = False
    tcp_port: int = 0  # --tcp-port: Modbus RTU over TCP in a network capture (the plugin's vw3.tcp_port)
    udp_port: int = 0  # --udp-port (vw3.udp_port)
    quiet: bool = False  # -q
    stats: bool = False
    watch: str | None = None
    report: str | None = None
    output: OutputOptions = OutputOptions()


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(
        prog=PROG,
        description="Decode Modbus RTU/ASCII serial captures (Altivar 71 VW3 A3 303, SEL-749M) "
        "frame by frame, the way tshark shows packets.",
    )
    parser.add_argument(
        "files",
        nargs="*",
        metavar="FILE",
        help="captures: raw bytes, pcap/pcapng (linktype 147 or 250), hex dump or Modbus ASCII; "
        "- reads stdin",
    )
    parser.add_argument(
        "-r", dest="read", action="append", default=[], metavar="FILE", help="a capture to read, as tshark -r"
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    parser.add_argument(
        "--hex",
        action="append",
        default=[],
        metavar="BYTES",
        help='decode bytes typed from a manual, e.g. --hex "0C 03 20 D0 00 03 0E EF" (also 0x0C 0x03 ..., '
        '0C:03:..., or decimal "12, 3, 32, ..."), an ASCII frame --hex ":02062329000AA2" '
        '(its CR LF may be typed as \\r\\n), packets as tshark -x and Wireshark\'s Copy > Bytes as Hex + '
        'ASCII Dump write them or lines of a Modbus Poll traffic log; all --hex arguments form one stream',
    )
    output = parser.add_argument_group("output")
    output.add_argument("-V", dest="detail", action="store_true", help="detail tree of every field")
    output.add_argument("-x", dest="hexdump", action="store_true", help="hex dump of every item")
    output.add_argument(
        "--json", action="store_true", help="NDJSON, one object per item (with --stats: the statistics)"
    )
    output.add_argument(
        "-T",
        dest="output_format",
        choices=["text", "fields", "json", "registers"],
        help="as tshark -T: text (the default), fields (with -e and -E) or json (NDJSON, as --json); "
        "registers: one line per register value (frame, time, slave, function, access, address, label, "
        "code, name, value, scaled, unit, status, text), -E as for fields",
    )
    output.add_argument(
        "-e", dest="fields", action="append", default=[], metavar="KEY",
        help="with -T fields: a JSON key (frame, time, slave, response_time, ...), fields.KEY or a "
        "register key (address, value, code, scaled, status, ...); repeatable, in column order",
    )
    output.add_argument(
        "-E", dest="field_options", action="append", default=[], metavar="NAME=VALUE",
        help="with -T fields, as tshark: header=y|n, separator=/t|/s|C, quote=d|s|n, "
        "occurrence=f|l|a, aggregator=,|/s|C, bom=y|n, formulas=y|n (y: keep values a spreadsheet would run as formulas; by default they get a leading ' with a , or ; separator)",
    )
    output.add_argument(
        "-t", dest="time_format", choices=list(TIME_FORMATS), default="r",
        help="time column as tshark -t: " + ", ".join(f"{key} {text}" for key, text in TIME_FORMATS.items()),
    )
    output.add_argument(
        "-Y", dest="filter", action="append", default=[], metavar="EXPR",
        help="display filter, e.g. -Y 'slave == 12 and code == \"CHCF\"'; -Y help lists the fields",
    )
    output.add_argument("-G", dest="glossary", choices=["fields"], nargs="?", const="fields",
                        help="-G fields (or -G alone, as tshark's): list the fields of -Y and -T fields, as"
                        " tshark -G fields")
    output.add_argument(
        "-w", dest="write", metavar="FILE",
        help="write the items shown to a pcap (linktype 147, USER0); - for standard output",
    )
    output.add_argument(
        "-F", dest="file_format", choices=["pcap", "pcapng"],
        help="-w file format (default: pcapng for a .pcapng name, else pcap)",
    )
    output.add_argument(
        "-b", dest="ring", action="append", metavar="filesize:KB|duration:S|files:N",
        help="-w ring buffer, as dumpcap: a new file every KB kB or S seconds, keeping the last N",
    )
    output.add_argument(
        "--frame-records", action="store_true",
        help="-w one record per frame (or noise run) at its time, as Wireshark's mbrtu reads frames, "
             "not the reads a frame came in (a tap's silences inside a frame are not kept)",
    )
    output.add_argument("-P", dest="print_too", action="store_true", help="print the items even with -w")
    output.add_argument(
        "-q", dest="quiet", action="store_true",
        help="print no items, as tshark -q (with -w, --stats, --watch or --report: their output alone)",
    )
    output.add_argument(
        "--stats", action="store_true", help="statistics per slave, function and parameter instead of items"
    )
    output.add_argument(
        "--watch",
        metavar="CODES",
        help="one line per change of these parameters (codes or addresses, e.g. CHCF,HSP,3201) "
        "instead of items",
    )
    output.add_argument(
        "--report",
        metavar="FILE",
        help="write a self-contained HTML report (traffic, poll cycle, trends, events) to FILE",
    )
    output.add_argument(
        "--color",
        choices=["auto", "always", "never"],
        default="auto",
        help="colour and layout with rich (auto: only on a terminal)",
    )
    data = parser.add_argument_group("datasets")
    data.add_argument(
        "--parquet", metavar="DIR",
        help="write the captures as Parquet tables DIR/frames, DIR/registers, DIR/events instead of items "
        "(pip install 'vw3-dissector[data]')",
    )
    data.add_argument(
        "--jobs", type=_jobs, default=1, metavar="N",
        help="with --parquet: decode N captures at a time in worker processes (the files of one -b ring "
        "buffer are one capture)",
    )
    data.add_argument(
        "--scheduler", metavar="tcp://HOST:PORT",
        help="with --parquet: decode the captures on a Dask distributed cluster "
        "(pip install 'vw3-dissector[cluster]')",
    )
    decoding = parser.add_argument_group("decoding")
    decoding.add_argument(
        "--format",
        choices=sorted(FORMATS),
        help="input format instead of detecting it from the content",
    )
    decoding.add_argument("--mode", choices=MODES, help="rtu or ascii framing instead of detecting it")
    decoding.add_argument(
        "--tcp-port", type=_port, default=0, metavar="PORT",
        help="in a pcap/pcapng of Ethernet (or Linux cooked, raw IP): the TCP port of a serial gateway carrying "
        "Modbus RTU frames, as the plugin's vw3.tcp_port preference (default 0: none)",
    )
    decoding.add_argument(
        "--udp-port", type=_port, default=0, metavar="PORT",
        help="the same for RTU over UDP, as the plugin's vw3.udp_port preference (default 0: none)",
    )
    decoding.add_argument(
        "--timeout",
        type=timeout_seconds,
        default=1.0,
        metavar="SECONDS",
        help="a response later than this after its request does not answer it (needs timestamps; "
        "default 1 s); live, a request's line waits at most this for its answer",
    )
    decoding.add_argument(
        "-n", dest="no_profile", action="store_true", help="no device profile: Modbus spec semantics only"
    )
    add_profile_arguments(parser)
    add_live_arguments(parser)
    parser.set_defaults(baud=ASSUMED_BAUD)
    return parser


class _Assumed(int):
    """19200 when --baud was not typed: files may say their speed (pcapng interface description)."""


ASSUMED_BAUD = _Assumed(19200)


def baud_given(args: argparse.Namespace) -> bool:
    return type(args.baud) is not _Assumed


def _port(text: str) -> int:
    value = int(text) if text.isdigit() else -1
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"{text!r} is not a port (0..65535)")
    return value


def _jobs(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of processes (1 or more)")
    return value


def _refuse_parquet_conflicts(args: argparse.Namespace) -> None:
    """--parquet replaces the items; --jobs and --scheduler only distribute it."""
    if args.parquet is None:
        if args.jobs != 1 or args.scheduler is not None:
            raise UsageError("--jobs and --scheduler decode into --parquet DIR: give --parquet DIR")
        return
    others = [
        ("-V", args.detail), ("-x", args.hexdump), ("--json", args.json), ("-T", args.output_format is not None),
        ("--stats", args.stats), ("--watch", args.watch is not None), ("--report", args.report is not None),
        ("-w", args.write is not None), ("-Y", bool(args.filter)), ("-c", args.count is not None),
        ("--hex", bool(args.hex)),
    ]
    for option, given in others:
        if given:
            raise UsageError(f"--parquet writes every frame of FILEs as tables: {option} does not apply")
    if args.scheduler is not None and args.jobs != 1:
        raise UsageError("--jobs and --scheduler: choose one (the cluster's workers are its processes)")


def _refuse_stdout_names(args: argparse.Namespace) -> None:
    """`-` is standard output for -w only (tshark -w -); the report and the dataset are files (./- is
    a file named -)."""
    if args.report == "-":
        raise UsageError("--report -: the report is an HTML file, not a stream: give a FILE "
                         "(-w - writes the capture to standard output)")
    if args.parquet == "-":
        raise UsageError("--parquet -: the dataset is a folder of Parquet files, not a stream: give a DIR")


def decode_options(args: argparse.Namespace) -> DecodeOptions:
    """The typed options of a file decode; UsageError for options that contradict each other."""
    _refuse_stdout_names(args)
    _refuse_conflicts(args)
    _refuse_parquet_conflicts(args)
    output_format = args.output_format or ("json" if args.json else "text")
    fields: FieldsOptions | None = None
    if output_format == "fields":
        fields = parse_fields_options(args.fields, args.field_options)
    registers = None
    if output_format == "registers":
        # A file column when several captures are read (one ring buffer's files are one: app/rings.py).
        several = len(group_files(args.files)) + bool(args.hex) > 1
        registers = parse_registers_options(args.field_options, several)
    return DecodeOptions(
        files=tuple(args.files),
        hex=tuple(args.hex),
        format=args.format,
        mode=args.mode,
        timeout=args.timeout,
        baud=args.baud,
        baud_given=baud_given(args),
        filter=args.filter[0] if args.filter else None,
        count=args.count,
        write=args.write,
        file_format=args.file_format,
        ring=tuple(args.ring or ()),
        frame_records=args.frame_records,
        print_too=args.print_too,
        tcp_port=args.tcp_port,
        udp_port=args.udp_port,
        quiet=args.quiet,
        stats=args.stats,
        watch=args.watch,
        report=args.report,
        output=OutputOptions(
            detail=args.detail,
            hexdump=args.hexdump,
            json=output_format == "json",
            color=args.color,
            time_format=args.time_format,
            fields=fields,
            registers=registers,
        ),
    )


# The serial port's frame format, parsed with no default so that a typed one is known (--bytesize notes
# itself: live_options.GivenBytesize): a file's line is --baud's, its characters the mode's (11 bits RTU,
# 10 ASCII), so a typed format is refused there rather than silently left out of the bus timing.
PORT_FORMAT = ("parity", "stopbits")
TWO_PASS = "-2"  # tshark's two-pass option (parse_arguments)


def parse_arguments(parser: argparse.ArgumentParser, argv: list[str] | None) -> argparse.Namespace:
    """parser.parse_args(argv); `port_format`: the frame format options typed (--parity, --stopbits,
    --bytesize), the others at their defaults."""
    args = parser.parse_args(argv, argparse.Namespace(**dict.fromkeys(PORT_FORMAT)))
    # tshark's -2 (two passes) is how vw3-decode always reads a file (profile auto and pairing see all of it
    # first): taken and ignored, as users type it. argparse reads it as a FILE (no option looks negative);
    # a file named -2 stays one.
    args.files = [name for name in args.files if name != TWO_PASS or os.path.lexists(name)]
    args.port_format = [f"--{dest}" for dest in PORT_FORMAT if getattr(args, dest) is not None]
    args.port_format += ["--bytesize"] if getattr(args, BYTESIZE_GIVEN, False) else []
    for dest in PORT_FORMAT:
        if getattr(args, dest) is None:
            setattr(args, dest, parser.get_default(dest))
    return args


def _refuse_conflicts(args: argparse.Namespace) -> None:
    """Options that cannot both be meant are refused, never silently dropped."""
    json_given = args.json or args.output_format == "json"
    conflicts = [
        (args.no_profile and bool(args.profile), "-n (no device profile) contradicts --profile"),
        (args.no_profile and bool(args.map), "-n (no device profile) contradicts --map"),
        (args.detail and json_given, "-V (detail tree) and --json are two outputs: choose one"),
        (args.json and args.output_format not in (None, "json"), f"--json contradicts -T {args.output_format}"),
        (args.output_format == "fields" and args.detail, "-V (detail tree) contradicts -T fields"),
        (args.output_format == "fields" and args.hexdump, "-x (hex dump) contradicts -T fields"),
        (args.output_format == "fields" and not args.fields, "-T fields needs at least one -e KEY"),
        (bool(args.fields) and args.output_format != "fields", "-e KEY needs -T fields"),
        (bool(args.field_options) and args.output_format not in ("fields", "registers"),
         "-E NAME=VALUE needs -T fields or -T registers"),
        (args.output_format == "registers" and (args.detail or args.hexdump),
         "-V and -x contradict -T registers: one line per register"),
        (args.stats and args.output_format == "registers", "--stats replaces the items: -T registers shows none"),
        (len(args.filter) > 1, "-Y given twice: combine the filters with and / or in one -Y"),
        (args.raw is not None, "--raw (write the bytes heard) needs --live PORT"),
        (args.duration is not None, "--duration (-a duration:S) needs --live PORT"),
        (bool(getattr(args, "port_format", ())),
         f"{', '.join(getattr(args, 'port_format', ()))}: the serial port's frame format needs --live PORT "
         "(a file's line is --baud's, its characters the mode's: 11 bits RTU, 10 ASCII)"),
        (args.print_too and args.write is None, "-P (print as well) needs -w FILE"),
        (args.print_too and args.quiet, "-P prints the items, -q prints none: choose one"),
        (bool(args.ring) and args.write is None, "-b (ring buffer) needs -w FILE"),
        (args.file_format is not None and args.write is None, "-F (file format) needs -w FILE"),
        (args.frame_records and args.write is None, "--frame-records needs -w FILE"),
        (args.stats and (args.detail or args.hexdump), "--stats replaces the items: -V and -x show none"),
        (args.stats and args.output_format == "fields", "--stats replaces the items: -T fields shows none"),
        (bool(args.hex) and args.format not in (None, "hex", "hexdump", "decimal"),
         "--format reads FILE inputs; with --hex only --format hex or decimal (how the bytes are written)"),
        (args.watch is not None and (args.detail or args.hexdump or args.output_format == "fields"),
         "--watch replaces the items: -V, -x and -T fields show none"),
        (args.watch is not None and args.output_format == "registers", "--watch replaces the items: -T registers shows none"),
        (args.watch is not None and args.stats, "--watch and --stats are two outputs: choose one"),
    ]
    for contradiction, message in conflicts:
        if contradiction:
            raise UsageError(message)

