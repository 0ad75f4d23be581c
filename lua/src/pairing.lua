-- vw3.pairing: requests and responses paired, timeouts.
-- Mirrors dissector/decode/pairing.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.pairing"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local UNMATCHED = say("unmatched", {})

-- ---------------------------------------------------------------------------------------------------
-- Pairing (dissector/decode/pairing.py): a response answers the open request with its slave and function.
-- The timeout rule: a frame later than the timeout after the open request ends the wait (unanswered).
-- Time going backwards: an answer stamped before its request still answers it, with a warning (its
-- negative response time is shown as it is and left out of the response times).

-- A request whose wait ended unanswered: no answer can ask for its fields and bytes any more, and the
-- stream awaits no answer.
local function unanswered(st, pending)
  pending.unanswered, pending.fields = true, nil
  release_run(pending.registers)
  st.pending = nil
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
    else
      st.pending = f
    end
    return
  end
  if pending ~= nil and pending.slave == f.slave and pending.fn == f.fn then
    f.request = pending
    pending.response = f
    st.pending = nil
    if f.time ~= nil and pending.time ~= nil and f.time < pending.time then
      warn(f, say("backwards", { ahead_ms = (pending.time - f.time) * 1000, number = pending.number }))
    end
  elseif late ~= nil and late.slave == f.slave and late.fn == f.fn then
    warn(f, say("late", { delay_ms = (f.time - late.time) * 1000, number = late.number, timeout_ms = timeout * 1000 }))
  else
    if pending ~= nil then unanswered(st, pending) end
    f.no_request = true
    note(f, UNMATCHED)
  end
end
