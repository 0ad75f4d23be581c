"""One error hierarchy and one set of exit statuses for the whole package.

Every error a user can cause derives from Vw3Error and carries a one-line message and the exit status
it ends the program with. As dpkt separates NeedData from UnpackError, bytes that end too soon
(NeedData: wait for more, or report a cut) are kept apart from bytes that cannot be what they claim
(MalformedInput).
"""
from __future__ import annotations

from enum import IntEnum


class ExitStatus(IntEnum):
    OK = 0
    ERROR = 1  # a failure while running (a device vanished, an output could not be written)
    BAD_INPUT = 2  # usage errors, unreadable inputs, bad maps or filters


class Vw3Error(Exception):
    """Base of every error the package raises on purpose; str() is one line for the user."""

    status: ExitStatus = ExitStatus.BAD_INPUT


class NeedData(Vw3Error):
    """The bytes end before the structure they start does: more bytes may complete it."""


class MalformedInput(Vw3Error, ValueError):
    """Bytes that cannot be what they claim, however many more follow."""


class UsageError(Vw3Error):
    """A bad command line: one line for stderr, exit status 2."""


class SourceError(Vw3Error):
    """A capture that cannot be read; the message is one line for the user."""


class ProfileError(Vw3Error, ValueError):
    """A profile or register map cannot be used; the message names the file (and line)."""


class OutputError(Vw3Error):
    """An output that cannot be written (a full disk, a closed pipe): exit status 1."""

    status = ExitStatus.ERROR


class LiveError(Vw3Error):
    """A live capture that cannot start or go on; `status` says how the program ends."""

    def __init__(self, message: str, status: int = ExitStatus.BAD_INPUT) -> None:
        super().__init__(message)
        self.status = ExitStatus(status)


class PortVanished(Vw3Error):
    """The serial port went away during a capture (an unplugged adapter)."""

    status = ExitStatus.ERROR


class GenerateError(Vw3Error):
    """A generated file cannot be written or checked (missing or repeated markers)."""
