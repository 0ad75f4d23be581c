"""Pairing: link each response to the request it answers, and say which requests went unanswered.

Runs after the framer, which has already classified every frame. A request to slave 0 is a broadcast
and expects no answer: a response from slave 0 answers nothing and is warned about (no server answers a
broadcast, and a server answers with its own address), naming the broadcast it follows when it is of its
function. A request the spec has no server answer (data/modbus.toml [pairing]
never_answered: FC8 04 Force Listen Only Mode) is noted as such and never unanswered, though an
exception (from a server that does not support it) still answers it. A response answers the open
request of its slave and function when it echoes what the spec has it echo ([pairing] echo: an FC8
answer's sub-function) as far as both hold it (_same_echo); one that does not answers nothing (the RTU
framer weighs the echo so already and frames such an FC8 frame as the master's next request:
RtuFramer._awaited). A frame too short for the echo (malformed) pairs by its slave and function, as every
malformed frame does and as tshark's mbrtu pairs (by unit and function alone). A request followed by another request (or
by the end of the capture more than the timeout after it) was not answered; one the capture ends
sooner after (a live capture stopped by -c, a file cut right after a request) may have been: that is not
known, it is not counted unanswered and its note says so. With `hold=True` (files), a request is held back until
the next frame tells whether it was answered, so its own line can say so, as tshark's second pass
would. With `hold=False`, every item is released at once, and the next request carries the note
instead.

The timeout rule (with timestamps and a timeout): a request is answered only by a response whose first
byte came at most `timeout` seconds after the request was sent (when its last byte was: its first byte's
time and its bytes' transmission time at the line's speed, `char_time`, or later where its last byte came
later, model.sent_in), as a Modbus master starts its response timeout
once it has sent the request (Serial Line Guide 2.4.1): 249 bytes take 2.3 s at 1200 baud; a later frame
ends the wait, the request is unanswered and a late response is shown as such. So whether a request was
answered is known `timeout` seconds after it at the latest: a live capture calls `expire(now)` to release
it then, and shows the line the decode of its capture file gives.

A master's retry (the retry rule): FC5, FC6 and FC8's Return Query Data answer with the bytes of the request,
so the framer reads the frame identical to a request that follows it as its answer. One that comes later
than `timeout` after the request is the master's retry of it, a request (the first was not answered),
and the frame after it that the framer would read as the retry's answer answers it. The framer, which has
no timeout, read the retry as an answer and so awaits nothing after it (and, after the retry's answer,
which it read as a request, awaits an answer): until the next frame agrees with it again (_retried,
_echoed), a frame of the same shape both ways (SAME_SHAPE) takes the kind the framer would have given it
(the pairer is not idle meanwhile, so no other engine takes the stream with the framer's expectation).

Listen Only Mode (Application Protocol 6.8.1): after an FC8 04 request to it (or broadcast), a slave answers
nothing until an FC8 01 Restart Communications Option request (to it or broadcast), which it acts on but
does not answer. Such requests are noted as such (texts listen_only, listen_only_ends) and never unanswered;
an exception to the FC8 04 itself says the slave did not enter the mode; a damaged request (bad CRC or LRC)
is not acted on. The 08/04's sub-function alone after it (intact, too short for a request) is its slave's
answer, which the spec's slave does not give (pymodbus's server answers so: warned, listen_only_echo); the
slave is taken to be in the mode all the same, as its answer acknowledges it. A frame identical to such a
request (FC5, FC6, FC8's echo), which the framer reads as its answer, is the master's repeat of it (the retry
rule's _retried when the slave answers that: after 08/01); a frame that differs from it is the slave's answer
(it did not take the mode), as the framer reads it.
The state is per slave: the C engine, which does not keep it, hands the transactions of a
slave in the mode to the Python stages (in_listen_only; listen_changed: the slaves it must ask about again).

Time going backwards (a pcap whose records go back, a clock step): a response stamped before its
request still answers it, its response time shown as it is (negative, as Wireshark shows a negative
delta) with a warning that it is left out of the response times (--stats, the bus timing).
"""
from __future__ import annotations

import weakref

from dissector.framing.answers import answer_length
from dissector.framing.stream import part_reason
from dissector.model import CUT_ANSWER, CapturedPart, Frame, Item, Kind, Noise, sent_in, stamped_before
from dissector.protocol import table
from dissector.protocol.rules import awaits_answer, echoed, text

HOLD_LIMIT = 64  # items held behind an open request before it is released anyway
# Function codes whose request and answer have the same layout: the framer frames such a frame alike
# whichever it awaits, only its kind depends on it (the retry rule).
SAME_SHAPE = frozenset(
    code for code, request, response in table.known_layouts() if request.length == response.length
)
# FC8's sub-functions that enter and leave Listen Only Mode (Application Protocol 6.8.1).
DIAGNOSTICS, LISTEN_ONLY, RESTART = 8, 4, 1
# The note of a request whose answer a record captured in part holds (_answer_in_part); pairing.lua says the same.
ANSWER_IN_PART = "answer captured in part in #{number}"


def capture_ended(request: Frame, cut: str | None = None, waited: float | None = None,
                  timeout: float | None = None, sent: float = 0.0) -> None:
    """A request whose answer the capture does not hold, its last bytes heard `waited` seconds after the
    request's (None: not known), `sent` seconds the request took to send. Past the timeout after it was
    sent (the timeout rule, _late) the master gave up: unanswered, as when later bytes or a live capture's
    clock tell (expire: a live line shown then, before the capture ended, says no more; nor does the decode
    of its file). Sooner, the slave may have answered after the capture stopped: not known, and not counted
    unanswered. The note says why (an answer cut by the end of the capture: it did answer)."""
    if timeout is not None and waited is not None and waited - sent > timeout:
        request.unanswered = True
        if cut is not None:
            request.notes.append(cut)
    elif cut is not None:
        request.notes.append(cut)
    else:
        # Shown from the request's first byte, as the response times; from when it was sent where that would
        # pass the timeout (a long request on a slow line): the note says "within" the timeout, and it is.
        if waited is not None and timeout is not None and waited > timeout:
            waited -= sent
        if waited is None or timeout is None or waited <= 0:
            request.notes.append(text("capture_ends_unknown"))
        else:
            request.notes.append(text("capture_ends_within", waited_ms=waited * 1000, timeout_ms=timeout * 1000))


class Pairer:
    def __init__(self, hold: bool = True, timeout: float | None = None, char_time: float = 0.0) -> None:
        self._hold = hold
        self._timeout = timeout
        self._char_time = char_time  # (seconds a character takes: a request's timeout starts once it is sent)
        self._pending: Frame | None = None
        self._pending_released = False
        # When the capture's last bytes came (Dissector.feed: its last chunk's time; None: not known).
        self.end: float | None = None
        # The open request is one the spec has no server answer (never_answered): only an exception can
        # answer it, and without one it is not unanswered.
        self._answerless = False
        self._broadcast: Frame | None = None  # the last request, when it was a broadcast
        self._queue: list[Item] = []
        self._count = 0
        # The retry rule: the open request is a retry the framer read as an answer (it awaits nothing);
        # the last frame is an answer the framer read as a request (it awaits that frame's answer).
        self._retried: Frame | None = None
        self._echoed: Frame | None = None
        # A request expire() released (live): the framer still awaits its answer, so the next frame may be
        # its retry, as when the frame itself ends the wait.
        self._expired: Frame | None = None
        # Listen Only Mode: the FC8 04 request each slave is in it since (None: left it), and the broadcast
        # one every slave not in _listening is in it since.
        self._listening: dict[int, Frame | None] = {}
        self._listening_all: Frame | None = None
        self.listen_changed: set[int] = set()  # slaves whose mode changed since the engine last asked
        self._unheard: Frame | None = None  # the last request to a slave in the mode

    @property
    def idle(self) -> bool:
        """No request awaits its answer, nothing is held back, and the framer awaits what this awaits."""
        return self._pending is None and not self._queue and self._echoed is None and self._retried is None

    def in_listen_only(self, slave: int) -> bool:
        """Is the slave in Listen Only Mode (a broadcast's: slave 0 is none)?"""
        return slave != 0 and self._listening.get(slave, self._listening_all) is not None

    def listen_only_slaves(self) -> list[int]:
        """The slaves in Listen Only Mode."""
        if self._listening_all is None:
            return [slave for slave, since in self._listening.items() if since is not None]
        return [slave for slave in range(1, 256) if self._listening.get(slave, self._listening_all) is not None]

    @property
    def timeout(self) -> float | None:
        """The response timeout: a later answer is none (seconds, None: no limit)."""
        return self._timeout

    @property
    def count(self) -> int:
        """Items numbered so far."""
        return self._count

    @count.setter
    def count(self, value: int) -> None:
        if value != self._count:  # items numbered elsewhere (the engine): the last request is not the one kept
            self._broadcast = None
        self._count = value

    def push(self, items: list[Item]) -> list[Item]:
        out: list[Item] = []
        for item in items:
            self._push_one(item, out)
        return out

    def expire(self, now: float) -> list[Item]:
        """Release the open request if no frame from `now` on can answer it (live: `now` is a time
        before which every byte has been framed)."""
        out: list[Item] = []
        pending = self._pending
        if pending is not None and self._late(pending, now):
            self._no_answer(pending)
            self._pending = None
            self._expired = pending  # (and _retried kept: the framer still awaits nothing after a retry)
            self._release(out)
        return out

    def _late(self, pending: Frame, time: float | None) -> bool:
        return (
            self._timeout is not None
            and time is not None
            and pending.time is not None
            and time - pending.time - sent_in(pending, self._char_time) > self._timeout
        )

    def finish(self) -> list[Item]:
        out: list[Item] = []
        pending = self._pending
        if pending is not None and not self._answerless:
            end, asked = self.end, pending.time
            waited = end - asked if end is not None and asked is not None else None
            if self._pending_released:  # (its line is out: only the count can still say it)
                pending.unanswered = self._late(pending, end)
            else:
                # The framer names an answer cut by the end of the capture (RtuFramer._cut_answer).
                cut = next(
                    (item.reason for item in self._queue
                     if isinstance(item, Noise) and item.reason.startswith(CUT_ANSWER)),
                    None,
                )
                capture_ended(pending, cut, waited, self._timeout, sent_in(pending, self._char_time))
        self._pending = None
        self._release(out)
        return out

    # -- internals ---------------------------------------------------------------------------
    def _no_answer(self, pending: Frame) -> bool:
        """The open request's wait ended with no answer: it is unanswered (True), unless the spec has no
        server answer it."""
        if self._answerless:
            return False
        pending.unanswered = True
        return True

    def _release(self, out: list[Item]) -> None:
        count = self._count
        for queued in self._queue:
            count += 1
            queued.number = count
            out.append(queued)
        self._count = count
        self._queue.clear()
        if self._pending is not None:
            self._pending_released = True

    def _push_one(self, item: Item, out: list[Item]) -> None:
        if not isinstance(item, Frame):
            if isinstance(item, Noise) and self._pending is not None and not self._answerless:
                self._answer_in_part(item)
            self._enqueue(item, out)
            return
        pending = self._pending
        late: Frame | None = None
        if pending is not None and self._late(pending, item.time):
            # Past the timeout: the master gave up, this frame cannot be the answer.
            late, pending = pending, None
            self._no_answer(late)
            self._pending = None
            self._release(out)
        retried, echoed_, expired = self._retried, self._echoed, self._expired
        self._retried = self._echoed = self._expired = None
        if item.function in SAME_SHAPE:
            # First the kind the framer would have given the frame had it awaited what the pairer awaits.
            flipped = False
            if (item.kind is Kind.REQUEST and retried is not None
                    and (retried is pending or retried is late or retried is expired) and _awaited(retried, item)):
                # What the framer, had it awaited the retry's answer, would have read as that answer (it
                # awaits this frame's answer now).
                item.kind = Kind.RESPONSE
                flipped = True
                self._echoed = item if awaits_answer(item) else None
            elif (item.kind is Kind.RESPONSE and pending is None and late is None and echoed_ is not None
                    and _awaited(echoed_, item)):
                # The framer awaited an answer to an answer: had it not, it would have read a request.
                item.kind = Kind.REQUEST
                self._retried = item if self._answered(item) else None
            ended = late if late is not None else expired  # (the request whose wait this frame or expire ended)
            if item.kind is Kind.RESPONSE and ended is not None and _repeats(ended, item):
                # The retry rule: the request again, past the timeout: the master's retry. (The framer
                # read it as an answer and awaits nothing, unless it read it as a request: flipped.)
                item.kind = Kind.REQUEST
                late = None
                self._echoed = None
                self._retried = item if self._answered(item) and not flipped else None
            if (not flipped and item.kind is Kind.RESPONSE and pending is not None and pending is self._unheard
                    and _repeats(pending, item)):
                # A slave in Listen Only Mode answers nothing, the 08/01 that ends the mode included: the request
                # again is the master's repeat. (The framer read it as an answer and awaits nothing.)
                item.kind = Kind.REQUEST
                self._echoed = None
                self._retried = item if self._answered(item) else None
        if item.kind is Kind.REQUEST and pending is not None and self._echoes_listen_only(pending, item):
            # The slave answers its 08/04 after all, against the spec (pymodbus's server does): no master's
            # repeat, which holds the data word too. (The framer awaits nothing after either.)
            item.kind = Kind.RESPONSE
            item.warnings.append(text("listen_only_echo"))
        if item.kind is Kind.REQUEST:
            if pending is not None and self._no_answer(pending) and self._pending_released:
                item.notes.append(text("unanswered", number=pending.number))
            self._pending = None
            self._release(out)
            self._broadcast = item if item.slave == 0 else None
            since, ends = self._listen_only(item)
            if item.slave == 0:
                item.broadcast = True
                self._enqueue(item, out)
                return
            # (awaiting nothing: the framer takes the next frame of its function for a request; an
            # exception, which says what it is, may still answer it)
            self._answerless = not awaits_answer(item) or since is not None
            self._unheard = item if since is not None else None
            if since is not None:
                key = "listen_only_ends" if ends else "listen_only"
                how = text("listen_only_broadcast") if since.slave == 0 else ""
                item.notes.append(text(key, slave=item.slave, number=since.number, how=how))
            elif self._answerless:
                item.notes.append(text("never_answered"))
            self._pending = item
            self._pending_released = False
            self._queue.append(item)
            if not self._hold:
                self._release(out)
            return
        # A response or an exception.
        backwards: Frame | None = None
        if (pending is not None and pending.slave == item.slave and pending.function == item.function
                and _echoes(pending, item)):
            if item.kind is Kind.EXCEPTION and self._listening.get(item.slave) is pending:
                self._listening.pop(item.slave)  # (it refused the FC8 04: not in the mode)
                self.listen_changed.add(item.slave)
            elif pending is self._unheard:
                self._heard(pending, item)
            item.request = pending
            pending.response_ref = weakref.ref(item)
            self._pending = None
            time, asked = item.time, pending.time
            if time is not None and asked is not None and stamped_before(time, asked):
                backwards = pending
        elif (gave_up := late if late is not None else expired) is not None and (
                gave_up.slave == item.slave and gave_up.function == item.function and _echoes(gave_up, item)):
            # Its request's wait ended before it: by its own time, or live by the clock (expire), alike.
            assert self._timeout is not None and item.time is not None and gave_up.time is not None
            item.warnings.append(text(
                "late", delay_ms=(item.time - gave_up.time) * 1000, number=gave_up.number,
                timeout_ms=self._timeout * 1000,
            ))
        else:
            if pending is not None:
                if self._no_answer(pending) and self._pending_released:
                    item.notes.append(text("unanswered", number=pending.number))
                self._pending = None
            broadcast = self._broadcast
            if item.slave == 0 and broadcast is not None and broadcast.function == item.function:
                item.warnings.append(text("broadcast_answered", number=broadcast.number))
            else:
                if item.slave == 0:
                    item.warnings.append(text("broadcast_address"))
                item.notes.append(text("unmatched"))
        self._queue.append(item)
        self._release(out)
        if backwards is not None:  # (numbered now)
            ahead_ms = (backwards.time - item.time) * 1000  # type: ignore[operator]
            item.warnings.append(text("backwards", ahead_ms=ahead_ms, number=backwards.number))

    def _answer_in_part(self, noise: Noise) -> None:
        """A record captured in part (framing/stream.py _cut_part) of the open request's slave and function (or
        its exception's), within the timeout: the slave answered, its answer's bytes cut by the snapshot length.
        A record of which no byte was captured (no slave, no function told) is the answer where its length on
        the line is one the answer can have (_answer_size): only the slave asked speaks then.
        The request is answered (not `[no response]`, nor counted so), its note names the item, whose reason
        names the request. Before, the request was unanswered: an engineer was told the slave did not answer."""
        pending = self._pending
        assert pending is not None
        part = noise.part
        if part is None or self._late(pending, noise.time):
            return
        slave, function = part.slave, part.function
        if slave is None:  # (no byte captured: its length on the line tells)
            if not _answer_size(pending, part):
                return
        elif slave != pending.slave or (function is not None and function & 0x7F != pending.function):
            return
        queue = self._queue  # (items are numbered as they are released, in order: pending may still be held)
        if not self._pending_released:
            pending.notes.append(ANSWER_IN_PART.format(number=self._count + len(queue) + 1))
            asked = self._count + 1 + next(index for index, queued in enumerate(queue) if queued is pending)
        else:
            asked = pending.number
        part.answers = asked
        noise.reason = part_reason(part)
        self._pending = None
        # (the framer starts clean after the cut: it awaits nothing, as the pairer now)
        self._retried = self._echoed = self._expired = None

    def _answered(self, request: Frame) -> bool:
        """Would a server answer this request (not one the spec has none answer, not to a slave in Listen Only
        Mode)?"""
        return awaits_answer(request) and not self.in_listen_only(request.slave)

    def _echoes_listen_only(self, pending: Frame, item: Frame) -> bool:
        """Is `item` its slave's answer to the open 08/04 that put it in Listen Only Mode: that sub-function
        alone, intact (too short for a request, so not the master's repeat)?"""
        return (item.crc_ok and item.slave == pending.slave and item.pdu == pending.pdu[:3] != pending.pdu
                and self._listening.get(pending.slave) is pending)

    def _heard(self, request: Frame, answer: Item) -> None:
        """A slave taken to be in Listen Only Mode answered (not the request again: _repeats): it is not in the
        mode (it did not take the 08/04, or restarted), and its request's note is taken back while held."""
        slave = request.slave
        since = self._listening.get(slave, self._listening_all)
        if since is None:  # (the 08/01 that ended the mode: already out of it)
            return
        if self._listening_all is not None:
            self._listening[slave] = None
        else:
            self._listening.pop(slave, None)
        self.listen_changed.add(slave)
        how = text("listen_only_broadcast") if since.slave == 0 else ""
        values = {"slave": slave, "number": since.number, "how": how}
        if not self._pending_released:
            said = text("listen_only", **values)
            request.notes[:] = [note for note in request.notes if note != said]
        answer.notes.append(text("listen_only_answered", **values))

    def _listen_only(self, request: Frame) -> tuple[Frame | None, bool]:
        """Follow Listen Only Mode through a request: the FC8 04 request its slave was in the mode since
        (None: not in it), and whether this request ends the mode. An intact FC8 04 enters it, an intact
        FC8 01 leaves it; slave 0 (broadcast): every slave."""
        slave = request.slave
        since = None if slave == 0 else self._listening.get(slave, self._listening_all)
        sub = _sub_function(request) if request.function == DIAGNOSTICS and request.crc_ok else None
        if sub == LISTEN_ONLY and since is None:
            if slave == 0:
                self._listening_all = request
                self._listening.clear()
            else:
                self._listening[slave] = request
        elif sub == RESTART:
            if slave == 0:
                self._listening_all = None
                self._listening.clear()
            elif self._listening_all is not None:
                self._listening[slave] = None
            else:
                self._listening.pop(slave, None)
        else:
            return since, False
        self.listen_changed.update(range(1, 256) if slave == 0 else (slave,))
        return since, sub == RESTART

    def _enqueue(self, item: Item, out: list[Item]) -> None:
        self._queue.append(item)
        if self._pending is None or not self._hold or len(self._queue) > HOLD_LIMIT:
            self._release(out)


def trusted_request(answer: Frame) -> Frame | None:
    """The request an answer is read against (its window, its echo, what an exception refuses), None when
    the capture has none or the tap's copy of it failed its check. A slave ignores a request that fails
    its check (Modbus over serial line 2.5.1.2), so a good answer after a damaged one answers the bytes the
    slave got, which the tap did not: the answer is paired (its number, its time) and its values shown,
    but addresses taken from the damaged bytes are unknown (text request_damaged), and nothing is judged,
    told or remembered of them (lua/src/decode.lua trusted_request)."""
    request = answer.request
    return request if request is not None and request.crc_ok else None


def _sub_function(request: Frame) -> int | None:
    pdu = request.pdu
    return pdu[1] << 8 | pdu[2] if len(pdu) >= 3 else None


def _repeats(request: Frame, frame: Frame) -> bool:
    """Is `frame` the request again: its length, slave, function, data and check (in ASCII, hex digits of
    either case: pairing.lua same_bytes)?"""
    return (frame.length == request.length and frame.slave == request.slave and frame.crc == request.crc
            and frame.pdu == request.pdu)


def _same_echo(request: Frame, frame: Frame) -> bool:
    """Do the two frames agree on what the spec has an answer repeat of its request (echoed: an FC8
    sub-function) over the bytes of it both hold (pairing.lua same_echo)? A frame that holds none of it
    disagrees with nothing."""
    echo = echoed(request)
    got = frame.pdu[1 : 1 + len(echo)]
    return got == echo[: len(got)]


def _echoes(request: Frame, answer: Frame) -> bool:
    """Does an answer of the request's slave and function answer it: an exception always, a normal answer
    where it repeats what the spec has it repeat (_same_echo)?"""
    return answer.kind is not Kind.RESPONSE or _same_echo(request, answer)


def _awaited(request: Frame, frame: Frame) -> bool:
    """Would the framer, awaiting `request`'s answer, read `frame` as it (rules.py Awaiting._awaited)?"""
    return (frame.slave, frame.function) == (request.slave, request.function) and _same_echo(request, frame)


def _answer_size(request: Frame, part: CapturedPart) -> bool:
    """Is `part`'s length on the line (RTU bytes; an ASCII line is 2 characters a byte, its LRC's too, and `:`
    and CR LF) one an answer to `request` has: its exception's, or its normal answer's where the request fixes
    it (a fixed length, a count of what the request asks: answers.py), else any from an exception's up?"""
    size = part.original if part.check == "CRC" else (part.original - 1) / 2
    shortest = table.EXCEPTION_LAYOUT.length.length  # type: ignore[union-attr]
    rule = table.layout_for(request.function, Kind.RESPONSE).length  # type: ignore[arg-type]
    normal = rule.length if isinstance(rule, table.Fixed) else answer_length(request)
    return size == shortest or size == normal or (normal is None and size >= shortest)
