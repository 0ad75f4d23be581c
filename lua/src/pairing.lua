-- vw3.pairing: requests and responses paired, timeouts.
-- Mirrors dissector/decode/pairing.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.pairing"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local UNMATCHED, BROADCAST_ADDRESS = say("unmatched", {}), say("broadcast_address", {})
local NEVER_ANSWERED_NOTE = say("never_answered", {})
local ECHO = DATA.pairing.echo

-- ---------------------------------------------------------------------------------------------------
-- Pairing (dissector/decode/pairing.py): a response answers the open request with its slave and function
-- when it echoes what the spec has it echo (DATA.pairing.echo: an FC8 sub-function); a broadcast awaits nothing
-- (a response from slave 0 answers nothing, with a warning: after a broadcast of its function, naming it),
-- and a request the spec has no server answer (awaits_answer, vw3.stream's: FC8 04) only an exception (the framer
-- awaits nothing after it), never unanswered (f.answerless).
-- The timeout rule: a frame later than the timeout after the open request ends the wait (unanswered).
-- Time going backwards: an answer stamped before its request still answers it, with a warning (its
-- negative response time is shown as it is and left out of the response times).

-- A request whose wait ended unanswered (but an answerless one, which none was expected of): no answer can
-- ask for its fields and bytes any more, and the stream awaits no answer.
local function unanswered(st, pending)
  pending.unanswered, pending.fields = not pending.answerless, nil
  release_run(pending.registers)
  st.pending = nil
end

-- What a frame holds of the bytes the spec has an answer echo (DATA.pairing.echo: FC8's sub-function), as one
-- number; nil: none. (A request keeps it: its byte table is gone when its answer comes.)
local function echoed(f)
  local count = ECHO[f.fn]
  if count == nil or f.data_len < count then return nil end
  local b, at, value = f.b, f.data_at, 0
  for k = 0, count - 1 do value = value * 256 + b[at + k] end
  return value
end

-- Does a normal answer repeat what the spec has it repeat of its request (pairing.py echoes)?
local function echoes(request, answer)
  return ECHO[request.fn] == nil or answer.kind ~= RESPONSE or request.echoed == echoed(answer)
end

local function pair(st, f)
  local pending = st.pending
  local timeout = st.timeout
  local late = nil
  if pending ~= nil and timeout ~= nil and f.time ~= nil and pending.time ~= nil
    and f.time - pending.time > timeout then
    unanswered(st, pending)
    late, pending = pending, nil
  end
  if f.kind == REQUEST then
    if pending ~= nil then unanswered(st, pending) end
    if f.slave == 0 then
      f.broadcast = true
      st.broadcast = f -- (the last request, a broadcast: a response from slave 0 after it answers it wrongly)
    else
      st.broadcast = nil
      if not awaits_answer(f) then
        note(f, NEVER_ANSWERED_NOTE)
        f.answerless = true
      end
      if ECHO[f.fn] ~= nil then f.echoed = echoed(f) end
      st.pending = f
    end
    return
  end
  if pending ~= nil and pending.slave == f.slave and pending.fn == f.fn and echoes(pending, f) then
    f.request = pending
    pending.response = f
    st.pending = nil
    if f.time ~= nil and pending.time ~= nil and f.time < pending.time then
      warn(f, say("backwards", { ahead_ms = (pending.time - f.time) * 1000, number = pending.number }))
    end
  elseif late ~= nil and late.slave == f.slave and late.fn == f.fn and echoes(late, f) then
    warn(f, say("late", { delay_ms = (f.time - late.time) * 1000, number = late.number, timeout_ms = timeout * 1000 }))
  else
    if pending ~= nil then unanswered(st, pending) end
    f.no_request = true
    local broadcast = st.broadcast
    if f.slave == 0 and broadcast ~= nil and broadcast.fn == f.fn then
      warn(f, say("broadcast_answered", { number = broadcast.number }))
    else
      if f.slave == 0 then warn(f, BROADCAST_ADDRESS) end
      note(f, UNMATCHED)
    end
  end
end
