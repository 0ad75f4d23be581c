-- vw3.layouts: the length rules of every function code, and which layouts a slave's code may have.
-- Mirrors dissector/protocol/table.py (the rules codegen writes into DATA.protocol).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.layouts"]).

-- ---------------------------------------------------------------------------------------------------
-- Framing (dissector/framing/rtu.py): length rules per function code and direction, CRC to confirm.
local FRAMING = DATA.framing
local MAX_ADU, MIN_ADU, MAX_SLAVE = FRAMING.max_adu, FRAMING.min_adu, FRAMING.max_slave
local NOISE_ITEM_MAX = FRAMING.noise_item_max
local NEED, NONE = -1, 0
local REQUEST, RESPONSE, EXCEPTION, NOISE = "request", "response", "exception", "noise"

-- A length rule returns the frame's length, NEED, or NONE; or (minimum, true) when the layout gives no
-- length and the frame is to be found by scanning for a CRC from that minimum (rules.Scan).
local function fixed(length)
  return function() return length end
end

-- A length by a count field (table.Counted): `extra` + the byte (width 1) or word (2) at `position`.
local function counted(position, extra, width)
  if width == 1 then -- (a rule per width: a flood weighs these at every byte, three times)
    return function(b, i, n)
      if i + position >= n then return NEED end
      return extra + b[i + position]
    end
  end
  return function(b, i, n)
    if i + position + 1 >= n then return NEED end
    return extra + b[i + position] * 256 + b[i + position + 1]
  end
end

local function scan(minimum)
  return function() return minimum, true end
end

-- The rule a field of the frame picks (table.Select, rules.py _select): `chosen` where the byte (width 1)
-- or word (2) at `position` is `value`, else `otherwise` (the field read in place, not by a count rule's call).
local make_rule
local function select(position, width, value, chosen, otherwise)
  chosen, otherwise = make_rule(chosen), make_rule(otherwise)
  return function(b, i, n)
    if i + position + width - 1 >= n then return NEED end
    local found = width == 2 and b[i + position] * 256 + b[i + position + 1] or b[i + position]
    if found == value then return chosen(b, i, n) end
    return otherwise(b, i, n)
  end
end

-- Walk the FC43/14 object list: its count at `position`, then (id, length, value) per object from `start`.
-- Where the walk does not end in a valid CRC (past the bytes there or an RTU frame, or its CRC fails), a CRC
-- scan from the list's start (start + 2, rules.py _mei_objects), with the walk's length (NEED: past the
-- bytes) as a third value: the framer's damaged frame or answer cut by the end of the capture; past the bytes,
-- a fourth: the index of the byte it stopped short of (Scan.wanted: till it comes, lua/src/rtu.lua ends_record's
-- answer holds).
local function mei_objects(position, start)
  local minimum = start + 2
  return function(b, i, n)
    if i + position >= n then return NEED end
    local stop = start
    for _ = 1, b[i + position] do
      if i + stop + 1 >= n then return minimum, true, NEED, stop + 1 end
      stop = stop + 2 + b[i + stop + 1]
      if stop > MAX_ADU then return minimum, true, NONE end
    end
    local length = stop + 2
    if i + length <= n and crc_ok_at(b, i, length) then return length end
    return minimum, true, length
  end
end

-- The bytes of `items` values of `unit` bytes each (0: bits, 8 a byte): rules.data_bytes, the one byte formula.
local function data_bytes(items, unit) return unit > 0 and items * unit or floor((items + 7) / 8) end

-- A request's length by its quantity (a word at `position`): `extra` + its data bytes (data_bytes by `unit`);
-- NONE where its byte count (`count_extra` + the byte at `count_at`) agrees (rules.py quantity_rule).
local function by_quantity(position, extra, unit, count_at, count_extra)
  return function(b, i, n)
    if i + position + 1 >= n or i + count_at >= n then return NEED end
    local items = b[i + position] * 256 + b[i + position + 1]
    local length = extra + (unit > 0 and items * unit or floor((items + 7) / 8)) -- (data_bytes, inline)
    if length == count_extra + b[i + count_at] then return NONE end
    return length
  end
end

local makers = {
  fixed = fixed, counted = counted,
  scan = scan, select = select, mei_objects = mei_objects, by_quantity = by_quantity,
}
function make_rule(spec) return makers[spec[1]](spec[2], spec[3], spec[4], spec[5], spec[6]) end

-- Interpretations in the order they are tried (rules.py REQUEST_FIRST, RESPONSE_FIRST): request first,
-- unless a response is expected; an exception's code (code + 128), the exception. No entry: no frame
-- starts with the code. Each code's length rules (request, response, by quantity): generated from
-- dissector/protocol/table.py.
local AS_REQUEST, AS_RESPONSE = {}, {}
local AS_EXCEPTION = { { EXCEPTION, make_rule(DATA.protocol.exception_rule) } }
for code, rules in pairs(DATA.protocol.rules) do
  local request, response = make_rule(rules[1]), make_rule(rules[2])
  local by_quantity = rules[3] and { REQUEST, make_rule(rules[3]) } -- (the quantity's length, tried last)
  AS_REQUEST[code] = { { REQUEST, request }, { RESPONSE, response }, by_quantity }
  AS_RESPONSE[code] = { { RESPONSE, response }, { REQUEST, request }, by_quantity }
  AS_REQUEST[code + 128] = AS_EXCEPTION -- (no answer is awaited with an exception's code)
end
local NO_INTERPRETATION = {}

-- A Lua string of count bytes from a 0-based (first) or 1-based byte table.
local function string_of(b, first, count)
  if count <= 200 then return string.char(table.unpack(b, first, first + count - 1)) end
  local parts = {}
  for k = 0, count - 1, 200 do -- (200 at a time: unpack puts them on the stack, string.char's arguments)
    parts[#parts + 1] = string.char(table.unpack(b, first + k, first + math.min(k + 200, count) - 1))
  end
  return concat(parts)
end

-- What a frame holds of the bytes the spec has an answer echo (DATA.pairing.echo: FC8's sub-function), as a
-- string (fewer bytes where the frame ends first); nil: none. The framer awaits them in the answer (st.echo:
-- await_echo), the pairing pairs by them (vw3.pairing's same_echo: a request keeps them, f.echoed, as its
-- byte table is gone when its answer comes).
local ECHO_CODES = DATA.pairing.echo
local function echoed(f)
  local count = ECHO_CODES[f.fn]
  if count == nil then return nil end
  if count > f.data_len then count = f.data_len end
  return string_of(f.b, f.data_at, count)
end

-- Do the bytes from b[i] (up to b[n - 1]) repeat the echo awaited (echo.bytes), as far as they have come?
local function echo_at(echo, b, i, n)
  local bytes = echo.bytes
  for k = 1, #bytes do
    local at = i + 1 + k
    if at >= n then return true end
    if b[at] ~= bytes:byte(k) then return false end
  end
  return true
end

-- Do the bytes at b[i] begin the answer awaited (rules.py Awaiting._awaited): its slave and function (an exception's
-- too) and, for a normal answer, what the spec has it repeat of the request (st.echo, kept by await_echo:
-- DATA.pairing.echo, an FC8 sub-function)? An FC8 frame that does not is the master's next request.
local function awaited(st, b, i, n)
  local code = b[i + 1]
  if st.expect ~= b[i] * 256 + code % 128 then return false end
  local echo = st.echo
  return echo == nil or echo.expect ~= st.expect or code >= 128 or echo_at(echo, b, i, n)
end

-- What a frame the line bounds is, whatever length its layout takes (rules.py Awaiting._bounded_kind: the RTU framer's
-- take_bounded, an ASCII line with a good LRC): an exception by its function, else the answer awaited or a request.
local function bounded_kind(st, b, i, n)
  return b[i + 1] >= 128 and EXCEPTION or (awaited(st, b, i, n) and RESPONSE or REQUEST)
end

-- The interpretations at b[i], likeliest first. Without the bytes (b nil: feed_whole, classify_ascii) an
-- echo awaited cannot be weighed: none then, and the general path frames the record.
local function interpretations(st, slave, code, b, i, n)
  if st.expect == slave * 256 + code then
    local echo = st.echo
    if echo ~= nil and echo.expect == st.expect then
      if b == nil then return NO_INTERPRETATION end
      if not echo_at(echo, b, i, n) then return AS_REQUEST[code] or NO_INTERPRETATION end
    end
    return AS_RESPONSE[code] or NO_INTERPRETATION
  end
  return AS_REQUEST[code] or NO_INTERPRETATION
end

-- What the answer awaited after `frame` must repeat of it (st.echo: its echoed bytes, an FC8 sub-function),
-- kept wherever a frame of a code with an echo (ECHO_CODES) sets the expectation (vw3.stream's expect_after,
-- the quick lanes), with the expectation it was kept for: a later request of another code, which does not
-- call this, leaves it aside (echo.expect: awaited).
-- A frame too short for it keeps what it holds (rules.py echoed): the answer is weighed by those bytes.
local function await_echo(st, frame)
  st.echo = nil
  if st.expect ~= nil then st.echo = { expect = st.expect, bytes = echoed(frame) } end
end

-- Can a frame start with this function code (any address before it: rules.py _POSSIBLE_START)?
local function possible_start(code)
  return AS_REQUEST[code] ~= nil
end
