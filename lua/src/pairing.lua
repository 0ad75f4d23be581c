-- vw3.pairing: requests and responses paired, timeouts.
-- Mirrors dissector/decode/pairing.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.pairing"]).
local PLAIN = DATA.plain_texts -- (the catalogue's texts without parameters: unmatched, never_answered, ...)
local ECHO = DATA.pairing.echo
-- Times are integer nanoseconds (show.lua record_ns); seconds are their differences divided once by NS
-- (vw3.stream's), as vw3-decode's Stamps subtract (model.py Stamp.__sub__): the same doubles, the same digits.
-- FC8's sub-functions that enter and leave Listen Only Mode (Application Protocol 6.8.1; pairing.py's).
local FC8_CODE, SUB_LISTEN_ONLY, SUB_RESTART = table.unpack(DATA.pairing.listen_only)

-- ---------------------------------------------------------------------------------------------------
-- Pairing (dissector/decode/pairing.py): a response answers the open request with its slave and function
-- when it echoes what the spec has it echo (DATA.pairing.echo: an FC8 sub-function); a broadcast awaits nothing
-- (a response from slave 0 answers nothing, with a warning: after a broadcast of its function, naming it),
-- and a request the spec has no server answer (awaits_answer, vw3.stream's: FC8 04) only an exception (the framer
-- awaits nothing after it), never unanswered (f.answerless).
-- The timeout rule: a frame later than the timeout after the open request was sent ends the wait (unanswered).
-- Time going backwards: an answer stamped before its request still answers it, with a warning (its
-- negative response time is shown as it is and left out of the response times).
-- The retry rule (pairing.py): a frame identical to the open request (FC5, FC6, FC8's echo), later than the
-- timeout, is the master's retry, and the frame after it the framer would read as its answer answers it;
-- until the framer's expectation agrees again (st.retried, st.echoed), a frame of SAME_SHAPE takes the kind
-- the framer would have given it.

-- Listen Only Mode (pairing.py _listen_only): after 08/04 (to the slave or broadcast) a slave answers nothing,
-- until 08/01 (to it or broadcast), which it acts on but does not answer. st.listening (nil: no slave in the
-- mode): the 08/04 each slave is in it since (false: left it); st.listening_all: the broadcast one, for the
-- others. The 08/04 a slave is in the mode since (nil: not in it).
local function listening_since(st, slave)
  local listening = st.listening
  if listening == nil or slave == 0 then return nil end
  local since = listening[slave]
  if since == nil then since = st.listening_all end
  return since or nil -- (false: left the mode)
end

-- The slave leaves the mode (a broadcast 08/04 keeps the others in it).
local function leave(st, slave)
  local listening = st.listening
  if st.listening_all ~= nil then
    listening[slave] = false
  else
    listening[slave] = nil
    if next(listening) == nil then st.listening = nil end
  end
end

-- The texts' values for a slave in the mode since the 08/04 `since` (listen_only, listen_only_answered, ...).
local function listen_values(slave, since)
  return { slave = slave, number = since.number, how = since.slave == 0 and PLAIN.listen_only_broadcast or "" }
end

-- Follows the mode through request f; returns the 08/04 its slave was in the mode since (nil: not in it) and
-- f's sub-function (nil: not an intact FC8 request, which no slave acts on).
-- A slave taken to be in the mode answered (pairing.py _heard): it is not in it; its request's note goes.
local function heard(st, request, answer)
  local slave = request.slave
  local since = listening_since(st, slave)
  if not since then return end -- (the 08/01 that ended the mode: already out of it)
  leave(st, slave)
  local values = listen_values(slave, since)
  local said, notes, kept = say("listen_only", values), request.notes or {}, {}
  for index = 1, #notes do
    if notes[index] ~= said then kept[#kept + 1] = notes[index] end
  end
  request.notes = kept[1] ~= nil and kept or nil -- (notes are made with their first: none is nil)
  note(answer, say("listen_only_answered", values))
end

local function listen_only(st, f)
  local slave, listening, since = f.slave, st.listening, listening_since(st, f.slave)
  local sub = nil
  if f.fn == FC8_CODE and f.data_len >= 2 and f.crc == f.crc_expected then
    local b, at = f.b, f.data_at
    sub = b[at] * 256 + b[at + 1]
    if sub == SUB_LISTEN_ONLY and since == nil then
      if slave == 0 then
        st.listening, st.listening_all = {}, f
      else
        if listening == nil then listening = {}; st.listening = listening end
        listening[slave] = f
      end
    elseif sub == SUB_RESTART and listening ~= nil then
      if slave == 0 then
        st.listening, st.listening_all = nil, nil
      else
        leave(st, slave)
      end
    end
  end
  return since, sub
end

-- Codes whose request and answer have the same layout: framed alike, whichever the framer awaits
-- (pairing.py SAME_SHAPE, from the protocol table).
local SAME_SHAPE = DATA.pairing.same_shape

-- What stands for a frame's bytes after its slave and function once its byte table has gone (kept for the open
-- request as st.sent, st.sent_for: which; a key of the frame's own would outgrow its table): a short one's
-- (up to 4 data bytes, FC5 and FC6's) data and CRC (LRC) as one number, exact in a double; a longer one's
-- length and CRC where the CRC is good (nil), its data as a string where it is not: a damaged frame's CRC
-- says nothing of its data (a request whose answer kept its length and CRC but not its data was read as
-- the request again, the master's retry, where vw3-decode's _repeats compares the data).
local function sent_key(f)
  local b, count, at = f.b, f.data_len, f.data_at
  if count > 4 then
    if f.crc == f.crc_expected then return nil end
    return string_of(b, at, count)
  end
  local value = count
  for k = 0, count - 1 do value = value * 256 + b[at + k] end
  return value * 65536 + f.crc
end

-- Are the bytes of `f` (its byte table at hand) those of `request`, its slave and function included? A request
-- whose byte table has gone: what stands for them (sent_key), else (a request not kept) a longer one's length
-- and good CRC.
local function same_bytes(st, request, f)
  if request.slave ~= f.slave or request.fn ~= f.fn or request.length ~= f.length or request.crc ~= f.crc then
    return false
  end
  local a, b = request.b, f.b
  if a == nil then
    if st.sent_for == request then return st.sent == sent_key(f) end
    return f.data_len > 4 and f.crc == f.crc_expected
  end
  local i, j = request.data_at, f.data_at
  for k = 0, f.data_len - 1 do
    if a[i + k] ~= b[j + k] then return false end
  end
  return true
end

-- A request whose wait ended unanswered (but an answerless one, which none was expected of): no answer can
-- ask for its fields and bytes any more, and the stream awaits no answer.
local function unanswered(st, pending)
  pending.unanswered, pending.fields = not pending.answerless, nil
  release_run(pending.registers)
  st.pending = nil
end

-- Do the two agree on the echo over the bytes of it both hold (pairing.py _same_echo)? A frame too short for
-- it (malformed) pairs by its slave and function, as every malformed frame does.
local function same_echo(request, f)
  local asked = request.echoed
  if asked == nil then return true end
  local got = echoed(f)
  local both = #asked < #got and #asked or #got
  return asked:sub(1, both) == got:sub(1, both)
end

-- Does `answer` answer `request` (nil: none): its slave and function, and a normal answer repeats what the
-- spec has it repeat of its request (pairing.py _echoes)?
local function answers(request, answer)
  return request ~= nil and request.slave == answer.slave and request.fn == answer.fn
    and (answer.kind ~= RESPONSE or same_echo(request, answer))
end

-- Would the framer, awaiting `request`'s answer, read `f` as it (rules.py Awaiting._awaited)?
local function awaited_as(request, f)
  return f.slave == request.slave and f.fn == request.fn and same_echo(request, f)
end

-- Would a server answer request f (pairing.py _answered): not one the spec has none answer, not to a slave in
-- Listen Only Mode?
local function answered(st, f)
  return awaits_answer(f) and listening_since(st, f.slave) == nil
end

-- The timeout rule: is `time` later than the timeout after request `pending` was sent (its first byte's time and
-- its characters' at the line's speed, vw3.stream's sent_in: pairing.py _late)?
local function timed_out(st, pending, time)
  return st.timeout ~= nil and time ~= nil and pending.time ~= nil
    and (time - pending.time) / NS - sent_in(pending) > st.timeout
end

local function pair(st, f)
  local pending = st.pending
  local timeout = st.timeout
  local late = nil
  if pending ~= nil and timed_out(st, pending, f.time) then
    unanswered(st, pending)
    late, pending = pending, nil
  end
  local retried, echoed_by = st.retried, st.echoed
  -- (written only when set: a nil written to a key the table lacks makes the key)
  if retried ~= nil or echoed_by ~= nil then st.retried, st.echoed = nil, nil end
  if SAME_SHAPE[f.fn] and f.b ~= nil then
    -- First the kind the framer would have given the frame had it awaited what the pairing awaits.
    local flipped = false
    if f.kind == REQUEST and retried ~= nil and (retried == pending or retried == late) and awaited_as(retried, f) then
      -- What the framer, had it awaited the retry's answer, would have read as that answer (it awaits this
      -- frame's answer now).
      f.kind, flipped = RESPONSE, true
      if awaits_answer(f) then
        if ECHO[f.fn] ~= nil then f.echoed = echoed(f) end
        st.echoed = f
      end
    elseif f.kind == RESPONSE and pending == nil and late == nil and echoed_by ~= nil and awaited_as(echoed_by, f) then
      -- The framer awaited an answer to an answer: had it not, it would have read a request.
      f.kind = REQUEST
      if answered(st, f) then st.retried = f end
    end
    -- The request again, past the timeout (late: the master's retry), or to a slave in Listen Only Mode, which
    -- answers nothing, the 08/01 that ends the mode included (the master's repeat). (The framer read it as an
    -- answer and awaits nothing, unless it read it as a request: flipped. Never both: late leaves no pending.)
    local again = late or not flipped and pending ~= nil and pending.unheard and pending
    if f.kind == RESPONSE and again and same_bytes(st, again, f) then
      f.kind, st.echoed = REQUEST, nil
      if again == late then late = nil end
      if answered(st, f) and not flipped then st.retried = f end
    end
  end
  -- The open 08/04's sub-function alone, intact: its slave's answer after all, against the spec (pairing.py
  -- _echoes_listen_only: pymodbus's server answers so), too short to be the master's repeat (shorter than the
  -- 08/04, of the same mode: its length, which stays once its bytes went, take_frame).
  if f.kind == REQUEST and f.fn == FC8_CODE and f.data_len == 2 and pending ~= nil and st.listening ~= nil and
      st.listening[f.slave] == pending and pending.length > f.length and f.crc == f.crc_expected and
      f.b[f.data_at] * 256 + f.b[f.data_at + 1] == SUB_LISTEN_ONLY then
    f.kind = RESPONSE
    warn(f, PLAIN.listen_only_echo)
  end
  if f.kind == REQUEST then
    if pending ~= nil then unanswered(st, pending) end
    local since, sub = nil, nil
    if f.fn == FC8_CODE or st.listening ~= nil then since, sub = listen_only(st, f) end
    if f.slave == 0 then
      f.broadcast = true
      st.broadcast = f -- (the last request, a broadcast: a response from slave 0 after it answers it wrongly)
    else
      st.broadcast = nil
      if since ~= nil then
        note(f, say(sub == SUB_RESTART and "listen_only_ends" or "listen_only", listen_values(f.slave, since)))
        f.answerless, f.unheard = true, true
      elseif not awaits_answer(f) then
        note(f, PLAIN.never_answered)
        f.answerless = true
      end
      if ECHO[f.fn] ~= nil then f.echoed = echoed(f) end
      if SAME_SHAPE[f.fn] and f.b ~= nil then st.sent, st.sent_for = sent_key(f), f end
      st.pending = f
    end
    return
  end
  if answers(pending, f) then
    local listening = st.listening
    if listening ~= nil and f.kind == EXCEPTION and listening[f.slave] == pending then
      listening[f.slave] = nil -- (it refused the 08/04: not in the mode)
      if next(listening) == nil and st.listening_all == nil then st.listening = nil end
    elseif pending.unheard then
      heard(st, pending, f)
    end
    f.request = pending
    pending.response = f
    st.pending = nil
    if f.time ~= nil and pending.time ~= nil and f.time < pending.time then
      warn(f, say("backwards", { ahead_ms = (pending.time - f.time) / NS * 1000, number = pending.number }))
    end
  elseif answers(late, f) then
    warn(f, say("late", { delay_ms = (f.time - late.time) / NS * 1000, number = late.number,
      timeout_ms = timeout * 1000 }))
  else
    if pending ~= nil then unanswered(st, pending) end
    f.no_request = true
    local broadcast = st.broadcast
    if f.slave == 0 and broadcast ~= nil and broadcast.fn == f.fn then
      warn(f, say("broadcast_answered", { number = broadcast.number }))
    else
      if f.slave == 0 then warn(f, PLAIN.broadcast_address) end
      note(f, PLAIN.unmatched)
    end
  end
end

-- Is the length on the line of a record of which no byte was captured (RTU bytes; an ASCII line 2 characters a
-- byte, its LRC's too, and `:` and CR LF) one an answer to `pending` has (pairing.py _answer_size): its
-- exception's, or its normal answer's where the request fixes it (a fixed length rule; a run of what it asked,
-- DATA.lanes.run_answers), else any from an exception's up?
local RULES, SHORTEST, RUNS = DATA.protocol.rules, DATA.protocol.exception_rule[2], DATA.lanes.run_answers
local function answer_size(pending, part)
  local size = part.check == "CRC" and part.original or (part.original - 1) / 2
  local rule, run, quantity, normal = RULES[pending.fn], RUNS[pending.fn], pending.quantity, nil
  if rule ~= nil and rule[2][1] == "fixed" then
    normal = rule[2][2]
  elseif run ~= nil and quantity ~= nil then
    local bits = (quantity + 7 - (quantity + 7) % 8) / 8 -- (unit 0: bits, 8 a byte)
    normal = run.extra + (run.unit > 0 and quantity * run.unit or bits)
  end
  return size == SHORTEST or size == normal or (normal == nil and size >= SHORTEST)
end

-- A record captured in part (vw3.stream's cut_stream), numbered, of the open request's slave and function (or
-- its exception's), within the timeout: the slave answered, its answer's bytes cut by the snapshot length
-- (pairing.py _answer_in_part, ANSWER_IN_PART). The request is answered, its note names the item, whose reason
-- names the request (`...; slave 2, function 3; the answer to #1): its CRC cannot be checked`); one of no byte
-- captured, where its length fits (answer_size): only the slave asked speaks then.
local function pair_part(st, item)
  local pending = st.pending
  if pending == nil or pending.answerless or timed_out(st, pending, item.time) then return end
  local part = item.part
  if part.slave == nil then -- (no byte captured: its length on the line tells)
    if not answer_size(pending, part) then return end
  elseif part.slave ~= pending.slave or (part.fn ~= nil and part.fn % 128 ~= pending.fn) then return end
  note(pending, format(DATA.pairing.answer_in_part, item.number))
  part.answers = pending.number
  item.reason = part_reason(part)
  pending.fields = nil
  release_run(pending.registers)
  st.pending = nil
  -- (the stream starts clean after the cut: it awaits nothing, as the pairing now)
  if st.retried ~= nil or st.echoed ~= nil then st.retried, st.echoed = nil, nil end
end

-- The capture ends with request f awaiting its answer (the second pass: the first has read it all):
-- pairing.py capture_ended. The capture's last record (any stream's, empty or not: recorded_until; else
-- st.times' last time, as Dissector.finish takes the later) later than the timeout after f was sent (timed_out):
-- the master gave up, unanswered; sooner, the slave may have answered after the capture stopped: not known.
-- Returns whether f is unanswered and its note (st.cut_note: an answer cut by the end, it did answer).
local function ended(st, f)
  local times, timeout, cut = st.times, st.timeout, st.cut_note
  local last = times[#times]
  if recorded_until ~= nil and (not last or recorded_until > last) then last = recorded_until end
  if timed_out(st, f, last) then return true, cut end
  if cut ~= nil then return false, cut end
  local waited = last and f.time and (last - f.time) / NS or nil
  -- (from f's first byte; from when it was sent where that passes the timeout: the note says "within")
  if waited ~= nil and timeout ~= nil and waited > timeout then waited = waited - sent_in(f) end
  if timeout == nil or waited == nil or waited <= 0 then return false, PLAIN.capture_ends_unknown end
  return false, say("capture_ends_within", { waited_ms = waited * 1000, timeout_ms = timeout * 1000 })
end
