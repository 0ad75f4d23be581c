-- vw3.layouts: the length rules of every function code, and which layouts a slave's code may have.
-- Mirrors dissector/protocol/table.py (the rules codegen writes into DATA.protocol).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.layouts"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)

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

local function count8(position, extra)
  return function(b, i, n)
    if i + position >= n then return NEED end
    return extra + b[i + position]
  end
end

local function count16(position, extra)
  return function(b, i, n)
    if i + position + 1 >= n then return NEED end
    return extra + b[i + position] * 256 + b[i + position + 1]
  end
end

local function diagnostics_rule(b, i, n)
  -- Return Query Data (sub-function 0) echoes any amount of data; all others carry one word.
  if i + 3 >= n then return NEED end
  if b[i + 2] == 0 and b[i + 3] == 0 then return 6, true end
  return 8
end

local function mei_request_rule(b, i, n)
  if i + 2 >= n then return NEED end
  if b[i + 2] == 14 then return 7 end
  return 5, true
end

local function mei_response_rule(b, i, n)
  -- Walk the FC43/14 object list: 8 header bytes, then (id, length, value) per object.
  if i + 2 >= n then return NEED end
  if b[i + 2] ~= 14 then return 5, true end
  if i + 7 >= n then return NEED end
  local position = 8
  for _ = 1, b[i + 7] do
    if i + position + 1 >= n then return NEED end
    position = position + 2 + b[i + position + 1]
    if position > MAX_ADU then return NONE end
  end
  return position + 2
end

local function scan_any() return MIN_ADU, true end

-- Length rules per function code (request, response): generated from dissector/protocol/table.py.
local RULES = {}
local makers = {
  fixed = fixed, count8 = count8, count16 = count16,
  diagnostics = function() return diagnostics_rule end,
  mei_request = function() return mei_request_rule end,
  mei_response = function() return mei_response_rule end,
  scan = function() return scan_any end,
}
local function make_rule(spec) return makers[spec[1]](spec[2], spec[3]) end
for code, rules in pairs(DATA.protocol.rules) do
  RULES[code] = { make_rule(rules[1]), make_rule(rules[2]) }
end
-- A request's length by its quantity where its byte count says otherwise (rtu.py quantity_rule).
for code, spec in pairs(DATA.protocol.by_quantity or {}) do
  local position, extra, unit = spec[1], spec[2], spec[3]
  local counted = RULES[code][1] -- (the byte count's length: { "count8", position, extra })
  local need = math.max(position + 1, DATA.protocol.rules[code][1][2])
  RULES[code][3] = function(b, i, n)
    if i + need >= n then return NEED end
    local quantity = b[i + position] * 256 + b[i + position + 1]
    local length
    if unit > 0 then length = extra + quantity * unit else length = extra + math.floor((quantity + 7) / 8) end
    if length == counted(b, i, n) then return NONE end
    return length
  end
end
for code in pairs(DATA.other_functions or {}) do
  if RULES[code] == nil then RULES[code] = { scan_any, scan_any } end
end

-- Interpretations in the order they are tried (rules.py REQUEST_FIRST, RESPONSE_FIRST): request first,
-- unless a response is expected; an exception's code (code + 128), the exception. No entry: no frame
-- starts with the code.
local AS_REQUEST, AS_RESPONSE = {}, {}
local AS_EXCEPTION = { { EXCEPTION, make_rule(DATA.protocol.exception_rule) } }
for code, rules in pairs(RULES) do
  local by_quantity = rules[3] and { REQUEST, rules[3] } -- (the quantity's length, tried last)
  AS_REQUEST[code] = { { REQUEST, rules[1] }, { RESPONSE, rules[2] }, by_quantity }
  AS_RESPONSE[code] = { { RESPONSE, rules[2] }, { REQUEST, rules[1] }, by_quantity }
  AS_REQUEST[code + 128] = AS_EXCEPTION -- (no answer is awaited with an exception's code)
end
local NO_INTERPRETATION = {}

local function interpretations(st, slave, code)
  if st.expect == slave * 256 + code then return AS_RESPONSE[code] or NO_INTERPRETATION end
  return AS_REQUEST[code] or NO_INTERPRETATION
end

-- Can a frame start with this function code (any address before it: rules.py _POSSIBLE_START)?
local function possible_start(code)
  return AS_REQUEST[code] ~= nil
end

M.EXCEPTION, M.FRAMING, M.MAX_ADU, M.MAX_SLAVE, M.MIN_ADU = EXCEPTION, FRAMING, MAX_ADU, MAX_SLAVE, MIN_ADU
M.NEED, M.NOISE, M.NOISE_ITEM_MAX, M.NONE = NEED, NOISE, NOISE_ITEM_MAX, NONE
M.NO_INTERPRETATION, M.REQUEST, M.RESPONSE = NO_INTERPRETATION, REQUEST, RESPONSE
M.interpretations, M.possible_start = interpretations, possible_start
