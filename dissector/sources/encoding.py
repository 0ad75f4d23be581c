"""Text captures in a Unicode encoding that says so with a byte order mark (BOM).

A hex dump, a traffic log or a Modbus ASCII capture saved by Windows Notepad as "UTF-8 with BOM" or
"Unicode" (UTF-16 LE), or written by PowerShell 5's `>` (UTF-16 LE), starts with EF BB BF, FF FE or
FE FF. Such a file is read as its text: the BOM is dropped and UTF-16/UTF-32 is decoded, so that the
readers see the characters the user sees in the editor.

A binary RTU capture may start with those bytes too (FF FE is a broadcast's garbage as much as a BOM),
so the mark alone decides nothing: reader.py takes the input as text only when its first bytes,
decoded, are text that some text format reads (a hex dump, Modbus ASCII...). Anything else is read as
the bytes it is, BOM included.
"""
from __future__ import annotations

import codecs
from dataclasses import dataclass

from dissector.sources.common import Input, SourceError


@dataclass(frozen=True, slots=True)
class Encoding:
    name: str  # as the user's editor calls it
    bom: bytes
    codec: str | None  # None: the bytes after the BOM are the text's bytes (UTF-8)


# UTF-32 LE before UTF-16 LE: its BOM starts with UTF-16 LE's.
ENCODINGS = (
    Encoding("UTF-32 LE", codecs.BOM_UTF32_LE, "utf-32-le"),
    Encoding("UTF-32 BE", codecs.BOM_UTF32_BE, "utf-32-be"),
    Encoding("UTF-8 with a BOM", codecs.BOM_UTF8, None),
    Encoding("UTF-16 LE", codecs.BOM_UTF16_LE, "utf-16-le"),
    Encoding("UTF-16 BE", codecs.BOM_UTF16_BE, "utf-16-be"),
)


def marked(sample: bytes) -> Encoding | None:
    """The encoding the input's BOM names, None without one."""
    return next((encoding for encoding in ENCODINGS if sample.startswith(encoding.bom)), None)


def decoded(sample: bytes, encoding: Encoding, complete: bool) -> tuple[bytes, bool] | None:
    """(text, whether it is all of the input) of an input's first bytes, as UTF-8 without the BOM (a
    character cut by the sample's end left out); None when the bytes are no text in that encoding.

    Bytes that are no text after some whole lines that are (a damaged file) leave those lines, so that
    the input is judged by them and reading it says where the damage is (DecodedStream)."""
    body = sample[len(encoding.bom) :]
    if encoding.codec is None:
        return body, complete
    try:
        return codecs.getincrementaldecoder(encoding.codec)().decode(body, final=complete).encode("utf-8"), complete
    except UnicodeDecodeError as error:
        text = codecs.getincrementaldecoder(encoding.codec)().decode(body[: error.start]).encode("utf-8")
    return (text[: text.rindex(b"\n") + 1], False) if b"\n" in text else None


class DecodedStream:
    """The text of an input (its first bytes already read: `sample`) as a stream of UTF-8 bytes, for
    common.Input: what the readers of text formats read. Decodes as the bytes come (a live pipe is not
    held back); bytes that are no text in the encoding stop the reading with one line."""

    def __init__(self, inp: Input, encoding: Encoding) -> None:
        self._inp = inp
        self._encoding = encoding
        self._decoder = codecs.getincrementaldecoder(encoding.codec or "utf-8")()
        self._pending = b""
        self._done = False

    def read1(self, count: int = -1) -> bytes:
        wanted = count if count > 0 else 65536
        while not self._pending and not self._done:
            data = self._inp.read_some(wanted)
            self._done = not data
            if self._encoding.codec is None:
                self._pending = data
                break
            try:
                self._pending = self._decoder.decode(data, final=self._done).encode("utf-8")
            except UnicodeDecodeError as error:
                where = self._inp.position - len(data) + error.start  # (about: the decoder may hold a byte or 3)
                raise SourceError(
                    f"{self._inp.name}: not {self._encoding.name} text near byte {where} ({error.reason}), "
                    "though it starts with that BOM: save it as UTF-8"
                ) from None
        part, self._pending = self._pending[:wanted], self._pending[wanted:]
        return part

    def read(self, count: int = -1) -> bytes:
        parts: list[bytes] = []
        size = 0
        while count < 0 or size < count:
            part = self.read1(count - size if count > 0 else -1)
            if not part:
                break
            parts.append(part)
            size += len(part)
        return b"".join(parts)


def text_input(inp: Input, encoding: Encoding) -> Input:
    """`inp` (positioned at the start of the input) read as text: its BOM dropped, its text as UTF-8."""
    inp.read(len(encoding.bom))
    return Input(DecodedStream(inp, encoding), inp.name)  # type: ignore[arg-type]
