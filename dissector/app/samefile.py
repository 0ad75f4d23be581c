"""No output may be an input or another output: `vw3-decode same.pcap -w same.pcap` would truncate
the capture before reading it, `-w X --report X` would leave only the last writer's bytes.

Files are the same when they are the same device and inode (hard links, symlinks followed, `./x` and
`x`); outputs that do not exist yet are the same when their real paths are. Standard input read as `-`
is an input too: `vw3-decode - -w st.pcap < st.pcap` is refused by the fstat of file descriptor 0.
"""
from __future__ import annotations

import argparse
import os
import stat

from dissector.errors import UsageError

STDIO = "-"


def _identity(path: str) -> tuple[object, ...] | None:
    """What makes two names one file; None for a character device (-w /dev/null --report /dev/null)."""
    try:
        info = os.stat(path)  # follows symlinks
    except (OSError, ValueError):
        return ("path", os.path.normcase(os.path.realpath(path)))
    if stat.S_ISCHR(info.st_mode):
        return None
    return ("inode", info.st_dev, info.st_ino)


def _stream_identity(stream: object) -> tuple[object, ...] | None:
    """What a standard stream is (its fstat, as _identity's stat): None for a terminal or no descriptor."""
    try:
        info = os.fstat(stream.fileno())  # type: ignore[attr-defined]
    except (AttributeError, OSError, ValueError):  # a BytesIO, a closed stdin
        return None
    return None if stat.S_ISCHR(info.st_mode) else ("inode", info.st_dev, info.st_ino)


def _named_files(values: list[str] | None) -> list[str]:
    """The files of --profile/--map values ([SLAVE=|PROFILE=]FILE) that exist."""
    found = []
    for value in values or []:
        for candidate in (value, value.partition("=")[2]):
            if candidate and os.path.isfile(candidate):
                found.append(candidate)
                break
    return found


def refuse_same_files(args: argparse.Namespace, stdin: object = None, stdout: object = None) -> None:
    """UsageError (exit 2) when an output is an input or another output; checked before any is opened.
    `stdin`: the stream `-` reads, `stdout` the one text (or -w -) goes to: their descriptors are compared
    (`vw3-decode st.pcap >> st.pcap` would read what it writes). Standard input given twice is refused: the
    second read of it is empty (`vw3-decode - -` decoded it, then warned `-: standard input: the input is empty`)."""
    if args.files.count(STDIO) > 1:
        raise UsageError("standard input (-) is given twice: it can be read once")
    inputs = [(name, path) for name, path in (
        *(("input", path) for path in args.files if path != STDIO),
        *(("--profile", path) for path in _named_files(getattr(args, "profile", None))),
        *(("--map", path) for path in _named_files(getattr(args, "map", None))),
        *((("--live", args.live),) if getattr(args, "live", None) and os.path.exists(args.live) else ()),
    )]
    outputs = []
    if args.write is not None and args.write != STDIO and not args.ring:
        outputs.append(("-w", args.write))
    for option, attribute in (("--report", "report"), ("--raw", "raw"), ("--parquet", "parquet")):
        path = getattr(args, attribute, None)
        if path is not None and path != STDIO:
            outputs.append((option, path))
    seen = {_identity(path): f"the {name} {path}" for name, path in inputs}
    if STDIO in args.files and (identity := _stream_identity(stdin)) is not None:
        seen[identity] = "standard input (-)"
    identity = _stream_identity(stdout)  # against the inputs only: -w /dev/stdout > out.pcap is one output
    if identity is not None and identity in seen:
        raise UsageError(f"standard output is {seen[identity]}: redirect it to another file")
    for option, path in outputs:
        identity = _identity(path)
        if identity is None:
            continue
        if identity in seen:
            raise UsageError(f"{option} {path} is {seen[identity]}: it would be overwritten; give another file")
        seen[identity] = f"the {option} file {path}"
