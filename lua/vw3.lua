-- vw3.lua: Wireshark plugin for Modbus serial (RTU) captures of Altivar 71 drives (VW3 A3 303 card)
-- and SEL-749M relays; the same dissection as the vw3-decode command, inside Wireshark.
--
-- Install: copy this one file into the personal Lua plugins folder (Linux, macOS:
-- ~/.local/lib/wireshark/plugins/, Windows: %APPDATA%\Wireshark\plugins\), or load it for one run with
-- `tshark -X lua_script:vw3.lua -r capture.pcap`. It decodes linktype 147 (USER0) records, `rtacser.data`
-- through Decode As, and Modbus RTU over TCP on the port set in the preferences.
--
-- The framing, pairing and decoding below mirror the Python package (dissector/framer.py, pairing.py,
-- decode.py, profile_annotator.py) rule for rule; a parity test runs tshark with this file and compares
-- every frame with the Python decoder. The tables between the GENERATED markers come from the package's
-- data files (python3 -m dissector.luagen); a test fails when they are stale.
--
-- Runs on Wireshark 4.0 (Lua 5.2) and 4.4+ (Lua 5.4): no native bitwise operators, no `//`, integer
-- division with math.floor; XOR comes from `bit` (Wireshark's bitop), `bit32`, or 5.3+ operators
-- compiled at run time.

-- BEGIN GENERATED DATA: python3 -m dissector.luagen (do not edit by hand)
local DATA = {
  ["functions"] = {
    [1] = "Read Coils",
    [2] = "Read Discrete Inputs",
    [3] = "Read Holding Registers",
    [4] = "Read Input Registers",
    [5] = "Write Single Coil",
    [6] = "Write Single Register",
    [7] = "Read Exception Status",
    [8] = "Diagnostics",
    [11] = "Get Comm Event Counter",
    [12] = "Get Comm Event Log",
    [15] = "Write Multiple Coils",
    [16] = "Write Multiple Registers",
    [17] = "Report Server ID",
    [20] = "Read File Record",
    [21] = "Write File Record",
    [22] = "Mask Write Register",
    [23] = "Read/Write Multiple Registers",
    [24] = "Read FIFO Queue",
    [43] = "Encapsulated Interface Transport",
  },
  ["exceptions"] = {
    [1] = "Illegal Function",
    [2] = "Illegal Data Address",
    [3] = "Illegal Data Value",
    [4] = "Server Device Failure",
    [5] = "Acknowledge",
    [6] = "Server Device Busy",
    [7] = "Negative Acknowledge",
    [8] = "Memory Parity Error",
    [10] = "Gateway Path Unavailable",
    [11] = "Gateway Target Device Failed to Respond",
  },
  ["diagnostics"] = {
    [0] = "Return Query Data",
    [1] = "Restart Communications Option",
    [2] = "Return Diagnostic Register",
    [3] = "Change ASCII Input Delimiter",
    [4] = "Force Listen Only Mode",
    [10] = "Clear Counters and Diagnostic Register",
    [11] = "Return Bus Message Count",
    [12] = "Return Bus Communication Error Count",
    [13] = "Return Bus Exception Error Count",
    [14] = "Return Server Message Count",
    [15] = "Return Server No Response Count",
    [16] = "Return Server NAK Count",
    [17] = "Return Server Busy Count",
    [18] = "Return Bus Character Overrun Count",
    [20] = "Clear Overrun Counter and Flag",
  },
  ["mei_types"] = {
    [13] = "CANopen General Reference",
    [14] = "Read Device Identification",
  },
  ["device_id_objects"] = {
    [0] = "VendorName",
    [1] = "ProductCode",
    [2] = "MajorMinorRevision",
    [3] = "VendorUrl",
    [4] = "ProductName",
    [5] = "ModelName",
    [6] = "UserApplicationName",
  },
  ["limits"] = {
    ["read_bits"] = { 1, 2000 },
    ["read_registers"] = { 1, 125 },
    ["write_coils"] = { 1, 1968 },
    ["write_registers"] = { 1, 123 },
    ["rw_read"] = { 1, 125 },
    ["rw_write"] = { 1, 121 },
    ["fifo_count"] = { 0, 31 },
    ["max_adu"] = 256,
    ["max_slave"] = 247,
  },
  ["framing"] = {
    ["max_adu"] = 256,
    ["min_adu"] = 4,
    ["max_slave"] = 247,
    ["noise_item_max"] = 4096,
  },
  ["other_functions"] = {
    [65] = true,
    [66] = true,
    [67] = true,
    [68] = true,
    [69] = true,
    [70] = true,
    [71] = true,
    [72] = true,
    [96] = true,
    [97] = true,
    [98] = true,
    [100] = true,
    [101] = true,
    [102] = true,
    [103] = true,
    [104] = true,
    [105] = true,
    [106] = true,
    [107] = true,
    [108] = true,
    [109] = true,
    [110] = true,
    [125] = true,
    [126] = true,
  },
  ["not_broadcast"] = {
    [1] = true,
    [2] = true,
    [3] = true,
    [4] = true,
    [7] = true,
    [11] = true,
    [12] = true,
    [17] = true,
    [20] = true,
    [24] = true,
    [43] = true,
  },
  ["profiles"] = {},
  ["default_profile"] = nil,
}
-- END GENERATED DATA

local floor = math.floor
local format = string.format
local concat = table.concat

-- ---------------------------------------------------------------------------------------------------
-- Bit helpers that work on Lua 5.2 and 5.4 alike.
local bxor
if type(bit) == "table" and bit.bxor then
  bxor = bit.bxor
elseif type(bit32) == "table" and bit32.bxor then
  bxor = bit32.bxor
else
  -- Lua 5.3+: the operator is only compiled here, so a 5.2 parser never sees it.
  bxor = load("return function(a, b) return a ~ b end")()
end

local CRC_TABLE = {}
for byte = 0, 255 do
  local crc = byte
  for _ = 1, 8 do
    if crc % 2 == 1 then
      crc = bxor(floor(crc / 2), 0xA001)
    else
      crc = floor(crc / 2)
    end
  end
  CRC_TABLE[byte] = crc
end

-- CRC-16/MODBUS of b[from] .. b[to - 1] (b is a 0-based byte table).
local function crc16(b, from, to)
  local crc = 0xFFFF
  for k = from, to - 1 do
    crc = bxor(floor(crc / 256), CRC_TABLE[bxor(crc, b[k]) % 256])
  end
  return crc
end

local function crc_step(crc, byte)
  return bxor(floor(crc / 256), CRC_TABLE[bxor(crc, byte) % 256])
end

local function crc_ok_at(b, i, length)
  local stop = i + length - 2
  return crc16(b, i, stop) == b[stop] + b[stop + 1] * 256
end

-- ---------------------------------------------------------------------------------------------------
-- Framing (dissector/framer.py): length rules per function code and direction, CRC to confirm.
local FRAMING = DATA.framing or { max_adu = 256, min_adu = 4, max_slave = 247, noise_item_max = 4096 }
local MAX_ADU, MIN_ADU, MAX_SLAVE = FRAMING.max_adu, FRAMING.min_adu, FRAMING.max_slave
local NOISE_ITEM_MAX = FRAMING.noise_item_max
local NEED, NONE = -1, 0
local REQUEST, RESPONSE, EXCEPTION, NOISE = "request", "response", "exception", "noise"

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

-- The shortest length from `minimum` whose CRC checks; NEED while a longer one may still come.
local function scan(b, i, n, minimum)
  minimum = minimum or MIN_ADU
  local last = math.min(n - i, MAX_ADU)
  if minimum <= last then
    local crc = 0xFFFF
    for k = i, i + minimum - 3 do crc = crc_step(crc, b[k]) end
    for length = minimum, last do
      local stop = i + length - 2
      if crc == b[stop] + b[stop + 1] * 256 then return length end
      crc = crc_step(crc, b[stop])
    end
  end
  if n - i < MAX_ADU then return NEED end
  return NONE
end

local function diagnostics_rule(b, i, n)
  -- Return Query Data (sub-function 0) echoes any amount of data; all others carry one word.
  if i + 3 >= n then return NEED end
  if b[i + 2] == 0 and b[i + 3] == 0 then return scan(b, i, n, 6) end
  return 8
end

local function mei_request_rule(b, i, n)
  if i + 2 >= n then return NEED end
  if b[i + 2] == 14 then return 7 end
  return scan(b, i, n, 5)
end

local function mei_response_rule(b, i, n)
  -- Walk the FC43/14 object list: 8 header bytes, then (id, length, value) per object.
  if i + 2 >= n then return NEED end
  if b[i + 2] ~= 14 then return scan(b, i, n, 5) end
  if i + 7 >= n then return NEED end
  local position = 8
  for _ = 1, b[i + 7] do
    if i + position + 1 >= n then return NEED end
    position = position + 2 + b[i + position + 1]
    if position > MAX_ADU then return NONE end
  end
  return position + 2
end

local function scan_any(b, i, n) return scan(b, i, n) end

local RULES = {
  [1] = { fixed(8), count8(2, 5) },
  [2] = { fixed(8), count8(2, 5) },
  [3] = { fixed(8), count8(2, 5) },
  [4] = { fixed(8), count8(2, 5) },
  [5] = { fixed(8), fixed(8) },
  [6] = { fixed(8), fixed(8) },
  [7] = { fixed(4), fixed(5) },
  [8] = { diagnostics_rule, diagnostics_rule },
  [11] = { fixed(4), fixed(8) },
  [12] = { fixed(4), count8(2, 5) },
  [15] = { count8(6, 9), fixed(8) },
  [16] = { count8(6, 9), fixed(8) },
  [17] = { fixed(4), count8(2, 5) },
  [20] = { count8(2, 5), count8(2, 5) },
  [21] = { count8(2, 5), count8(2, 5) },
  [22] = { fixed(10), fixed(10) },
  [23] = { count8(10, 13), count8(2, 5) },
  [24] = { fixed(6), count16(2, 6) },
  [43] = { mei_request_rule, mei_response_rule },
}
for code in pairs(DATA.other_functions or {}) do
  if RULES[code] == nil then RULES[code] = { scan_any, scan_any } end
end

-- Interpretations in the order they are tried: request first, unless a response is expected.
local AS_REQUEST, AS_RESPONSE = {}, {}
for code, rules in pairs(RULES) do
  AS_REQUEST[code] = { { REQUEST, rules[1] }, { RESPONSE, rules[2] } }
  AS_RESPONSE[code] = { { RESPONSE, rules[2] }, { REQUEST, rules[1] } }
end
local AS_EXCEPTION = { { EXCEPTION, fixed(5) } }
local NO_INTERPRETATION = {}

local function interpretations(st, slave, code)
  if code >= 128 then
    if RULES[code - 128] then return AS_EXCEPTION end
    return NO_INTERPRETATION
  end
  if RULES[code] == nil then return NO_INTERPRETATION end
  if st.expect == slave * 256 + code then return AS_RESPONSE[code] end
  return AS_REQUEST[code]
end

-- Does an intact frame start at i? (The end of the record counts as a frame boundary.)
local function valid_frame_at(st, b, i, n)
  if n - i < MIN_ADU then return i == n end
  local slave = b[i]
  if slave > MAX_SLAVE then return false end
  for _, interpretation in ipairs(interpretations(st, slave, b[i + 1])) do
    local length = interpretation[2](b, i, n)
    if length == NEED then return false end
    if length >= MIN_ADU and length <= MAX_ADU and i + length <= n and crc_ok_at(b, i, length) then
      return true
    end
  end
  return false
end

-- kind, length, crc_ok for a frame at i, or nil when i starts no frame.
local function match(st, b, i, n)
  local slave, code = b[i], b[i + 1]
  if slave > MAX_SLAVE then return nil end
  local damaged = {}
  for _, interpretation in ipairs(interpretations(st, slave, code)) do
    local length = interpretation[2](b, i, n)
    if length ~= NEED and length >= MIN_ADU and length <= MAX_ADU and i + length <= n then
      if crc_ok_at(b, i, length) then return interpretation[1], length, true end
      damaged[#damaged + 1] = { interpretation[1], length }
    end
  end
  -- No layout checks out: a damaged frame is shown once if it ends where an intact one begins. A record
  -- boundary counts as such a place (a capture tool cut the record there).
  for _, candidate in ipairs(damaged) do
    local length = candidate[2]
    if valid_frame_at(st, b, i + length, n) then
      return candidate[1], length, false
    end
  end
  return nil
end

-- Split one record into frames and noise runs, in order. st carries the expectation across records.
local function frame_record(st, b, n)
  local items = {}
  local noise_start, noise_length, noise_reason = nil, 0, nil
  local function flush_noise()
    if noise_start ~= nil then
      items[#items + 1] = { kind = NOISE, offset = noise_start, length = noise_length, reason = noise_reason }
      noise_start, noise_length = nil, 0
    end
  end
  local function add_noise(at, count, reason)
    if noise_start == nil then noise_start, noise_reason = at, reason end
    noise_length = noise_length + count
    if noise_length >= NOISE_ITEM_MAX then flush_noise() end
  end
  local i = 0
  while i < n do
    if n - i < MIN_ADU then
      add_noise(i, n - i, "too short for a frame")
      break
    end
    local kind, length, _ = match(st, b, i, n)
    if kind == nil then
      add_noise(i, 1, "no valid frame")
      i = i + 1
    else
      flush_noise()
      local slave, code = b[i], b[i + 1]
      local stop = i + length - 2
      items[#items + 1] = {
        kind = kind, offset = i, length = length, slave = slave, code = code, fn = code % 128,
        crc = b[stop] + b[stop + 1] * 256, crc_expected = crc16(b, i, stop),
        warnings = {}, notes = {},
      }
      if kind == REQUEST and slave ~= 0 then
        st.expect = slave * 256 + code
      else
        st.expect = nil
      end
      i = i + length
    end
  end
  flush_noise()
  return items
end

-- ---------------------------------------------------------------------------------------------------
-- Protocol names and limits (dissector/spec.py).
local FUNCTIONS = DATA.functions or {}
local EXCEPTIONS = DATA.exceptions or {}
local DIAGNOSTICS = DATA.diagnostics or {}
local OBJECTS = DATA.device_id_objects or {}
local LIMITS = DATA.limits or {}
local NOT_BROADCAST = DATA.not_broadcast or {}

local function function_name(code)
  local name = FUNCTIONS[code]
  if name then return name end
  if (code >= 65 and code <= 72) or (code >= 100 and code <= 110) then
    return format("User-defined function %d", code)
  end
  return format("Function %d", code)
end

local function exception_name(code)
  if code == nil then return "Missing exception code" end
  return EXCEPTIONS[code] or format("Unknown exception %d", code)
end

-- ---------------------------------------------------------------------------------------------------
-- Decoding (dissector/grammar.py + decode.py): PDU data after the function code, then the handlers.
local function u16(b, k) return b[k] * 256 + b[k + 1] end

local function check_range(frame, what, value, limit_name)
  local limit = LIMITS[limit_name]
  if limit and (value < limit[1] or value > limit[2]) then
    frame.warnings[#frame.warnings + 1] = format("%s %d outside the spec's %d..%d", what, value, limit[1], limit[2])
  end
end

local function check_span(frame, start, quantity)
  if start + quantity > 0x10000 then
    frame.warnings[#frame.warnings + 1] =
      format("addresses %d..%d run past 65535", start, start + quantity - 1)
  end
end

local function warn(frame, text) frame.warnings[#frame.warnings + 1] = text end

local function make_registers(b, first, count, start)
  local registers = {}
  for index = 0, count - 1 do
    local address = nil
    if start ~= nil then address = (start + index) % 0x10000 end
    registers[#registers + 1] = { address = address, value = u16(b, first + 2 * index), offset = first + 2 * index }
  end
  return registers
end

local function make_bits(b, first, byte_count, start, quantity)
  local count = byte_count * 8
  if quantity ~= nil and quantity < count then count = quantity end
  local bits = {}
  for index = 0, count - 1 do
    local byte = b[first + floor(index / 8)]
    local value = floor(byte / 2 ^ (index % 8)) % 2
    local address = nil
    if start ~= nil then address = (start + index) % 0x10000 end
    bits[#bits + 1] = { address = address, value = floor(value), offset = first + floor(index / 8) }
  end
  return bits
end

local function ceil_bytes(bits) return floor((bits + 7) / 8) end

-- Each parser gets the frame, the byte table, the first data byte and the data length. It returns the
-- number of bytes its grammar consumed (the rest is `trailing`), or nil and a reason when the data do
-- not fit the grammar (Python: GrammarError -> "malformed ...").
local P = {}

local function read_request(f, b, d, len)
  if len < 4 then return nil, "too short for start and quantity" end
  f.fields = { start = u16(b, d), quantity = u16(b, d + 2) }
  return 4
end

local function read_bits_response(f, b, d, len)
  if len < 1 or len < 1 + b[d] then return nil, "byte count past the end" end
  f.fields = { byte_count = b[d], status_at = d + 1 }
  return 1 + b[d]
end

local function read_registers_response(f, b, d, len)
  if len < 1 or len < 1 + b[d] then return nil, "byte count past the end" end
  f.fields = { byte_count = b[d], values_at = d + 1, count = floor(b[d] / 2) }
  return 1 + b[d]
end

local function write_single(f, b, d, len)
  if len < 4 then return nil, "too short for address and value" end
  f.fields = { address = u16(b, d), value = u16(b, d + 2) }
  return 4
end

local function empty(f, b, d, len)
  f.fields = {}
  return 0
end

local function diagnostics(f, b, d, len)
  if len < 2 then return nil, "too short for a sub-function" end
  f.fields = { subfunction = u16(b, d), data_length = len - 2 }
  return len
end

local function write_coils_request(f, b, d, len)
  if len < 5 or len < 5 + b[d + 4] then return nil, "byte count past the end" end
  f.fields = { start = u16(b, d), quantity = u16(b, d + 2), byte_count = b[d + 4], status_at = d + 5 }
  return 5 + b[d + 4]
end

local function write_registers_request(f, b, d, len)
  if len < 5 or len < 5 + b[d + 4] then return nil, "byte count past the end" end
  f.fields = {
    start = u16(b, d), quantity = u16(b, d + 2), byte_count = b[d + 4], values_at = d + 5,
    count = floor(b[d + 4] / 2),
  }
  return 5 + b[d + 4]
end

local function fixed_size(size, what)
  return function(f, b, d, len)
    if len < size then return nil, what end
    f.fields = {}
    return size
  end
end

local function comm_event_log_response(f, b, d, len)
  if len < 7 or b[d] < 6 or len < 1 + b[d] then return nil, "byte count below 6 or past the end" end
  f.fields = {}
  return 1 + b[d]
end

local function byte_counted(f, b, d, len)
  if len < 1 or len < 1 + b[d] then return nil, "byte count past the end" end
  f.fields = {}
  return 1 + b[d]
end

local function mask_write(f, b, d, len)
  if len < 6 then return nil, "too short for address and masks" end
  f.fields = { address = u16(b, d) }
  return 6
end

local function read_write_request(f, b, d, len)
  if len < 9 or len < 9 + b[d + 8] then return nil, "byte count past the end" end
  f.fields = {
    read_start = u16(b, d), read_quantity = u16(b, d + 2), write_start = u16(b, d + 4),
    write_quantity = u16(b, d + 6), byte_count = b[d + 8], values_at = d + 9, count = floor(b[d + 8] / 2),
  }
  return 9 + b[d + 8]
end

local function fifo_request(f, b, d, len)
  if len < 2 then return nil, "too short for an address" end
  f.fields = { address = u16(b, d) }
  return 2
end

local function fifo_response(f, b, d, len)
  if len < 4 or len < 4 + 2 * u16(b, d + 2) then return nil, "FIFO count past the end" end
  f.fields = { byte_count = u16(b, d), fifo_count = u16(b, d + 2) }
  return 4 + 2 * u16(b, d + 2)
end

local function mei_request(f, b, d, len)
  if len < 1 then return nil, "too short for a MEI type" end
  if b[d] == 14 then
    if len < 3 then return nil, "too short for read code and object id" end
    f.fields = { mei_type = 14 }
    return 3
  end
  f.fields = { mei_type = b[d] }
  return len
end

local function mei_response(f, b, d, len)
  if len < 1 then return nil, "too short for a MEI type" end
  if b[d] ~= 14 then
    f.fields = { mei_type = b[d] }
    return len
  end
  if len < 6 then return nil, "too short for the identification header" end
  local objects, position = {}, 6
  for _ = 1, b[d + 5] do
    if position + 2 > len or position + 2 + b[d + position + 1] > len then
      return nil, "object length past the end"
    end
    local size = b[d + position + 1]
    local chars = {}
    for k = 0, size - 1 do chars[#chars + 1] = string.char(b[d + position + 2 + k]) end
    objects[#objects + 1] = { id = b[d + position], value = concat(chars), offset = d + position, length = 2 + size }
    position = position + 2 + size
  end
  f.fields = { mei_type = 14, objects = objects }
  return position
end

local function raw(f, b, d, len)
  f.fields = {}
  return len
end

local GRAMMARS = {
  [REQUEST] = {
    [1] = read_request, [2] = read_request, [3] = read_request, [4] = read_request,
    [5] = write_single, [6] = write_single, [7] = empty, [8] = diagnostics, [11] = empty, [12] = empty,
    [15] = write_coils_request, [16] = write_registers_request, [17] = empty,
    [20] = byte_counted, [21] = byte_counted, [22] = mask_write, [23] = read_write_request,
    [24] = fifo_request, [43] = mei_request,
  },
  [RESPONSE] = {
    [1] = read_bits_response, [2] = read_bits_response, [3] = read_registers_response,
    [4] = read_registers_response, [5] = write_single, [6] = write_single,
    [7] = fixed_size(1, "too short for a status"), [8] = diagnostics,
    [11] = fixed_size(4, "too short for status and event count"), [12] = comm_event_log_response,
    [15] = read_request, [16] = read_request, [17] = byte_counted, [20] = byte_counted,
    [21] = byte_counted, [22] = mask_write, [23] = read_registers_response, [24] = fifo_response,
    [43] = mei_response,
  },
}

-- Handlers (decode.py): lift out start, quantity, registers, bits, objects; check the spec.
local H = { [REQUEST] = {}, [RESPONSE] = {} }

local function read_request_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.start, fields.quantity
  local limit = "read_registers"
  if f.fn == 1 or f.fn == 2 then limit = "read_bits" end
  check_range(f, "quantity", fields.quantity, limit)
  check_span(f, fields.start, fields.quantity)
end

local function request_fields(f)
  if f.request == nil then return nil end
  return f.request.fields
end

local function read_bits_response_handler(f, b)
  local fields = f.fields
  local request = request_fields(f)
  local start, quantity = nil, nil
  if request ~= nil then
    start, quantity = request.start, request.quantity
    if fields.byte_count ~= ceil_bytes(quantity) then
      warn(f, format("byte count %d disagrees with the %d bits asked", fields.byte_count, quantity))
    end
  end
  f.start, f.quantity = start, quantity
  f.bits = make_bits(b, fields.status_at, fields.byte_count, start, quantity)
end

local function read_registers_response_handler(f, b)
  local fields = f.fields
  local request = request_fields(f)
  local start = nil
  if request ~= nil then
    local quantity
    if f.fn == 23 then
      start, quantity = request.read_start, request.read_quantity
    else
      start, quantity = request.start, request.quantity
    end
    if fields.byte_count ~= 2 * quantity then
      warn(f, format("byte count %d disagrees with the %d registers asked", fields.byte_count, quantity))
    end
    f.quantity = quantity
  elseif fields.byte_count % 2 == 0 then
    f.quantity = floor(fields.byte_count / 2)
  end
  if fields.byte_count % 2 == 1 then
    warn(f, format("odd byte count %d for 16-bit registers", fields.byte_count))
  end
  f.start = start
  f.registers = make_registers(b, fields.values_at, fields.count, start)
end

local function write_single_coil_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.address, 1
  if fields.value ~= 0xFF00 and fields.value ~= 0 then
    warn(f, format("coil value 0x%04X is neither 0xFF00 (on) nor 0x0000 (off)", fields.value))
  end
  local value = 0
  if fields.value == 0xFF00 then value = 1 end
  f.bits = { { address = fields.address, value = value, offset = f.data_at + 2 } }
end

local function write_single_register_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.address, 1
  f.registers = { { address = fields.address, value = fields.value, offset = f.data_at + 2 } }
end

local function diagnostics_handler(f, b)
  local fields = f.fields
  f.subfunction = fields.subfunction
  if DIAGNOSTICS[fields.subfunction] == nil then
    warn(f, format("diagnostic sub-function %d is not defined by the spec", fields.subfunction))
  end
  if fields.data_length % 2 == 1 then warn(f, "diagnostic data is not a whole number of words") end
end

local function write_coils_request_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.start, fields.quantity
  check_range(f, "quantity", fields.quantity, "write_coils")
  check_span(f, fields.start, fields.quantity)
  if fields.byte_count ~= ceil_bytes(fields.quantity) then
    warn(f, format("byte count %d disagrees with the quantity %d", fields.byte_count, fields.quantity))
  end
  f.bits = make_bits(b, fields.status_at, fields.byte_count, fields.start, fields.quantity)
end

local function write_registers_request_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.start, fields.quantity
  check_range(f, "quantity", fields.quantity, "write_registers")
  check_span(f, fields.start, fields.quantity)
  if fields.byte_count ~= 2 * fields.quantity then
    warn(f, format("byte count %d disagrees with the quantity %d", fields.byte_count, fields.quantity))
  end
  f.registers = make_registers(b, fields.values_at, fields.count, fields.start)
end

local function write_multiple_response_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.start, fields.quantity
  local request = request_fields(f)
  if request ~= nil and (request.start ~= fields.start or request.quantity ~= fields.quantity) then
    warn(f, "the response's start and quantity differ from the request's")
  end
end

local function mask_write_handler(f, b)
  f.start, f.quantity = f.fields.address, 1
end

local function read_write_request_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.read_start, fields.read_quantity
  check_range(f, "read quantity", fields.read_quantity, "rw_read")
  check_range(f, "write quantity", fields.write_quantity, "rw_write")
  if fields.byte_count ~= 2 * fields.write_quantity then
    warn(f, format("byte count %d disagrees with the write quantity %d", fields.byte_count, fields.write_quantity))
  end
  f.registers = make_registers(b, fields.values_at, fields.count, fields.write_start)
end

local function fifo_request_handler(f, b)
  f.start = f.fields.address
end

local function fifo_response_handler(f, b)
  local fields = f.fields
  local request = request_fields(f)
  if request ~= nil then f.start = request.address end
  f.quantity = fields.fifo_count
  if fields.fifo_count > LIMITS.fifo_count[2] then
    warn(f, format("FIFO count %d above the spec's 31", fields.fifo_count))
  end
  if fields.byte_count ~= 2 + 2 * fields.fifo_count then
    warn(f, format("byte count %d disagrees with the FIFO count", fields.byte_count))
  end
end

local function mei_response_handler(f, b)
  if f.fields.mei_type ~= 14 then return end
  local objects = {}
  for _, object in ipairs(f.fields.objects) do
    objects[#objects + 1] = {
      id = object.id, name = OBJECTS[object.id] or format("Object %d", object.id), value = object.value,
      offset = object.offset, length = object.length,
    }
  end
  f.objects = objects
end

for code = 1, 4 do
  H[REQUEST][code] = read_request_handler
end
H[RESPONSE][1] = read_bits_response_handler
H[RESPONSE][2] = read_bits_response_handler
H[RESPONSE][3] = read_registers_response_handler
H[RESPONSE][4] = read_registers_response_handler
H[REQUEST][5] = write_single_coil_handler
H[RESPONSE][5] = write_single_coil_handler
H[REQUEST][6] = write_single_register_handler
H[RESPONSE][6] = write_single_register_handler
H[REQUEST][8] = diagnostics_handler
H[RESPONSE][8] = diagnostics_handler
H[REQUEST][15] = write_coils_request_handler
H[RESPONSE][15] = write_multiple_response_handler
H[REQUEST][16] = write_registers_request_handler
H[RESPONSE][16] = write_multiple_response_handler
H[REQUEST][22] = mask_write_handler
H[RESPONSE][22] = mask_write_handler
H[REQUEST][23] = read_write_request_handler
H[RESPONSE][23] = read_registers_response_handler
H[REQUEST][24] = fifo_request_handler
H[RESPONSE][24] = fifo_response_handler
H[RESPONSE][43] = mei_response_handler

local function decode_frame(f, b)
  local d, len = f.offset + 2, f.length - 4
  f.data_at = d
  if f.kind == EXCEPTION then
    f.fields = {}
    f.exception_code = b[d]
    if EXCEPTIONS[f.exception_code] == nil then
      warn(f, format("exception code %d is not defined by the spec", f.exception_code))
    end
    return
  end
  local parser = GRAMMARS[f.kind][f.fn] or raw
  local used, reason = parser(f, b, d, len)
  if used == nil then
    f.fields = nil
    f.malformed = true
    warn(f, format("malformed %s: %s", f.kind, reason))
    return
  end
  local handler = H[f.kind][f.fn]
  if handler ~= nil then handler(f, b) end
  if used < len then warn(f, format("%d unexpected bytes after the data", len - used)) end
  if f.broadcast and NOT_BROADCAST[f.fn] then
    warn(f, format("%s cannot be broadcast (slave 0)", function_name(f.fn)))
  end
end

-- ---------------------------------------------------------------------------------------------------
-- Pairing (dissector/pairing.py): a response answers the open request with its slave and function.
local function pair(st, f)
  local pending = st.pending
  if f.kind == REQUEST then
    if pending ~= nil then pending.unanswered = true end
    st.pending = nil
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
  else
    if pending ~= nil then
      pending.unanswered = true
      st.pending = nil
    end
    f.no_request = true
    f.notes[#f.notes + 1] = "response without a matching request in the capture"
  end
end

-- ---------------------------------------------------------------------------------------------------
-- Device profiles and register maps (profile_annotator.py): names, scaling, 16#8000 semantics.
local annotate = function(st, f) end -- replaced below when profile data are present

-- ---------------------------------------------------------------------------------------------------
-- One record: frame it, pair and decode every frame, in order. Pure Lua: the Wireshark glue below and
-- the standalone tests both call it.
local function new_state()
  return { expect = nil, pending = nil, count = 0, records = {} }
end

local function dissect_record(st, bytes, time, number)
  local n = #bytes
  local b = {}
  for k = 1, n do b[k - 1] = string.byte(bytes, k) end
  local items = frame_record(st, b, n)
  local frames = 0
  for _, item in ipairs(items) do
    st.count = st.count + 1
    item.number = st.count
    item.record = number
    item.time = time
    if item.kind ~= NOISE then
      frames = frames + 1
      pair(st, item)
      decode_frame(item, b)
      annotate(st, item)
    end
  end
  local record = { items = items, frames = frames, length = n, bytes = b }
  -- A record that ends in noise which starts like a frame was most likely cut inside that frame.
  local last = items[#items]
  if last ~= nil and last.kind == NOISE and last.offset + last.length == n and n - last.offset >= 2 then
    local slave, code = b[last.offset], b[last.offset + 1]
    if slave <= MAX_SLAVE and (RULES[code] or RULES[code - 128]) then record.partial = true end
  end
  return record
end

local vw3 = {
  DATA = DATA, new_state = new_state, dissect_record = dissect_record, crc16 = crc16,
  function_name = function_name, exception_name = exception_name,
}

-- ---------------------------------------------------------------------------------------------------
-- Wireshark glue.
if Proto == nil then
  return vw3 -- loaded outside Wireshark (lua5.x tests without a stub): the pure part only
end

local proto = Proto("vw3", "VW3 Modbus serial (Altivar 71, SEL-749M)")

local function names(table_)
  local out = {}
  for key, value in pairs(table_) do out[key] = value end
  return out
end

local pf = {
  item = ProtoField.uint32("vw3.item", "Item", base.DEC, nil, nil, "Item number as vw3-decode counts them"),
  kind = ProtoField.string("vw3.kind", "Kind"),
  slave = ProtoField.uint8("vw3.slave", "Slave", base.DEC),
  ["function"] = ProtoField.uint8("vw3.function", "Function", base.DEC, names(FUNCTIONS)),
  crc = ProtoField.uint16("vw3.crc", "CRC", base.HEX),
  crc_expected = ProtoField.uint16("vw3.crc_expected", "Expected CRC", base.HEX),
  crc_ok = ProtoField.bool("vw3.crc_ok", "CRC OK"),
  broadcast = ProtoField.bool("vw3.broadcast", "Broadcast"),
  exception_code = ProtoField.uint8("vw3.exception_code", "Exception code", base.DEC, names(EXCEPTIONS)),
  exception_text = ProtoField.string("vw3.exception_text", "Exception meaning"),
  start = ProtoField.uint16("vw3.start", "Start address", base.DEC),
  quantity = ProtoField.uint16("vw3.quantity", "Quantity", base.DEC),
  subfunction = ProtoField.uint16("vw3.subfunction", "Sub-function", base.DEC, names(DIAGNOSTICS)),
  reg = ProtoField.none("vw3.reg", "Register"),
  reg_address = ProtoField.uint16("vw3.reg.address", "Address", base.DEC),
  reg_label = ProtoField.string("vw3.reg.label", "Address as shown"),
  reg_value = ProtoField.uint16("vw3.reg.value", "Value", base.DEC_HEX),
  reg_code = ProtoField.string("vw3.reg.code", "Code"),
  reg_name = ProtoField.string("vw3.reg.name", "Name"),
  reg_unit = ProtoField.string("vw3.reg.unit", "Unit"),
  reg_scaled = ProtoField.string("vw3.reg.scaled", "Scaled value"),
  reg_text = ProtoField.string("vw3.reg.text", "Meaning"),
  reg_status = ProtoField.string("vw3.reg.status", "Status"),
  reg_source = ProtoField.string("vw3.reg.source", "Source"),
  bit = ProtoField.none("vw3.bit", "Bit"),
  bit_address = ProtoField.uint16("vw3.bit.address", "Address", base.DEC),
  bit_value = ProtoField.uint8("vw3.bit.value", "Value", base.DEC),
  object = ProtoField.none("vw3.object", "Object"),
  object_id = ProtoField.uint8("vw3.object.id", "Object id", base.DEC),
  object_name = ProtoField.string("vw3.object.name", "Name"),
  object_value = ProtoField.string("vw3.object.value", "Value"),
  object_text = ProtoField.string("vw3.object.text", "Meaning"),
  request_frame = ProtoField.framenum("vw3.request_frame", "Request in frame", base.NONE, frametype and frametype.REQUEST),
  response_frame = ProtoField.framenum("vw3.response_frame", "Response in frame", base.NONE, frametype and frametype.RESPONSE),
  response_time = ProtoField.relative_time("vw3.response_time", "Time since request"),
  unanswered = ProtoField.bool("vw3.unanswered", "Unanswered"),
  noise_reason = ProtoField.string("vw3.noise.reason", "Why noise"),
  data = ProtoField.bytes("vw3.data", "Data"),
}
local field_list = {}
for _, field in pairs(pf) do field_list[#field_list + 1] = field end
proto.fields = field_list

local ex = {
  crc_bad = ProtoExpert.new("vw3.crc_bad", "Bad CRC", expert.group.CHECKSUM, expert.severity.ERROR),
  exception = ProtoExpert.new("vw3.exception", "Exception response", expert.group.RESPONSE_CODE, expert.severity.NOTE),
  unanswered = ProtoExpert.new("vw3.unanswered", "Request not answered", expert.group.SEQUENCE, expert.severity.WARN),
  no_request = ProtoExpert.new("vw3.no_request", "Response without a matching request", expert.group.SEQUENCE, expert.severity.WARN),
  warning = ProtoExpert.new("vw3.warning", "Outside the spec or the device profile", expert.group.PROTOCOL, expert.severity.WARN),
  malformed = ProtoExpert.new("vw3.malformed", "PDU does not fit its layout", expert.group.MALFORMED, expert.severity.ERROR),
  protected = ProtoExpert.new("vw3.protected", "Protected or non-existent parameter", expert.group.RESPONSE_CODE, expert.severity.WARN),
  note = ProtoExpert.new("vw3.note", "Note", expert.group.COMMENTS_GROUP, expert.severity.NOTE),
  noise = ProtoExpert.new("vw3.noise", "Bytes outside any frame", expert.group.MALFORMED, expert.severity.WARN),
  multiple = ProtoExpert.new("vw3.record.multiple", "Several frames in one record", expert.group.REASSEMBLE, expert.severity.NOTE),
  partial = ProtoExpert.new("vw3.record.partial", "Record ends inside a frame", expert.group.REASSEMBLE, expert.severity.WARN),
}
proto.experts = { ex.crc_bad, ex.exception, ex.unanswered, ex.no_request, ex.warning, ex.malformed,
  ex.protected, ex.note, ex.noise, ex.multiple, ex.partial }
vw3.experts = ex

local STYLE_DEFAULT, STYLE_PROTOCOL, STYLE_PLC = 1, 2, 3
proto.prefs.profiles = Pref.string("Device profiles", "",
  "Profile per slave, e.g. '12=atv71,3=sel749m'; a name alone sets the default for every other slave")
proto.prefs.address_style = Pref.enum("Register address style", STYLE_DEFAULT,
  "How register addresses are shown (the vw3.reg.address field is always the address on the wire)",
  { { 1, "As the device profile says", STYLE_DEFAULT }, { 2, "As sent on the wire (8401)", STYLE_PROTOCOL },
    { 3, "PLC 4X reference (48402)", STYLE_PLC } }, false)
proto.prefs.tcp_port = Pref.uint("RTU over TCP port", 0, "TCP port of a serial gateway carrying raw RTU frames (0: off)")

local state = new_state()
vw3.state = function() return state end

function proto.init()
  state = new_state()
  if vw3.configure then vw3.configure(proto.prefs) end
end

local function add_text(tree, expert_info, text)
  tree:add_proto_expert_info(expert_info, text)
end

local function range_of(tvb, offset, length)
  if length <= 0 or offset + length > tvb:len() then return nil end
  return tvb:range(offset, length)
end

local function add_register(tree, tvb, reg)
  local r = range_of(tvb, reg.offset, 2)
  local label = reg.label or (reg.address and tostring(reg.address)) or "?"
  local text = format("Register %s", label)
  if reg.code then text = text .. " " .. reg.code end
  text = text .. format(" = %d", reg.value)
  if reg.scaled ~= nil then text = text .. format(" (%s%s)", reg.scaled, reg.unit and (" " .. reg.unit) or "") end
  if reg.text then text = text .. " " .. reg.text end
  if reg.status then text = text .. " [" .. reg.status .. "]" end
  local sub = tree:add(pf.reg, r)
  sub:set_text(text)
  if reg.address ~= nil then
    local item = sub:add(pf.reg_address, r, reg.address)
    if r ~= nil then item:set_generated() end
  end
  if reg.label then sub:add(pf.reg_label, r, reg.label):set_generated() end
  sub:add(pf.reg_value, r, reg.value)
  if reg.code then sub:add(pf.reg_code, r, reg.code):set_generated() end
  if reg.name then sub:add(pf.reg_name, r, reg.name):set_generated() end
  if reg.unit then sub:add(pf.reg_unit, r, reg.unit):set_generated() end
  if reg.scaled ~= nil then sub:add(pf.reg_scaled, r, tostring(reg.scaled)):set_generated() end
  if reg.text then sub:add(pf.reg_text, r, reg.text):set_generated() end
  if reg.source then sub:add(pf.reg_source, r, reg.source):set_generated() end
  if reg.status then
    sub:add(pf.reg_status, r, reg.status):set_generated()
    if reg.status ~= "ok" then add_text(sub, ex.protected, reg.status_text or reg.status) end
  end
end

local function summary(f)
  local parts = { format("%d", f.slave), function_name(f.fn), f.kind }
  if f.kind == EXCEPTION then parts[#parts + 1] = exception_name(f.exception_code) end
  if f.start ~= nil and f.quantity ~= nil and f.quantity > 1 then
    parts[#parts + 1] = format("%d..%d", f.start, (f.start + f.quantity - 1) % 0x10000)
  elseif f.start ~= nil then
    parts[#parts + 1] = format("%d", f.start)
  end
  if not (f.crc == f.crc_expected) then parts[#parts + 1] = "BAD CRC" end
  return concat(parts, " ")
end

local function show_frame(f, tvb, tree, pinfo)
  local whole = tvb:range(f.offset, f.length)
  local t = tree:add(proto, whole)
  t:set_text(format("VW3 Modbus RTU, %s", summary(f)))
  t:add(pf.item, whole, f.number):set_generated()
  t:add(pf.kind, whole, f.kind):set_generated()
  t:add(pf.slave, tvb:range(f.offset, 1), f.slave)
  t:add(pf["function"], tvb:range(f.offset + 1, 1), f.fn)
  local crc_range = tvb:range(f.offset + f.length - 2, 2)
  local crc_ok = f.crc == f.crc_expected
  t:add(pf.crc, crc_range, f.crc)
  t:add(pf.crc_expected, crc_range, f.crc_expected):set_generated()
  t:add(pf.crc_ok, crc_range, crc_ok):set_generated()
  if not crc_ok then add_text(t, ex.crc_bad, format("Bad CRC: 0x%04X, expected 0x%04X", f.crc, f.crc_expected)) end
  if f.broadcast then t:add(pf.broadcast, whole, true):set_generated() end
  if f.kind == EXCEPTION then
    t:add(pf.exception_code, tvb:range(f.offset + 2, 1), f.exception_code)
    add_text(t, ex.exception, format("Exception %d: %s", f.exception_code, f.exception_meaning or exception_name(f.exception_code)))
    if f.exception_meaning then t:add(pf.exception_text, whole, f.exception_meaning):set_generated() end
  end
  local data_range = range_of(tvb, f.offset + 2, 2)
  if f.start ~= nil then
    local item = t:add(pf.start, data_range, f.start)
    if f.kind == RESPONSE and (f.fn <= 4 or f.fn == 23 or f.fn == 24) then item:set_generated() end
  end
  if f.quantity ~= nil then t:add(pf.quantity, whole, f.quantity):set_generated() end
  if f.subfunction ~= nil then t:add(pf.subfunction, data_range, f.subfunction) end
  if f.registers then
    for _, reg in ipairs(f.registers) do add_register(t, tvb, reg) end
  end
  if f.bits then
    for _, bit_ in ipairs(f.bits) do
      local r = range_of(tvb, bit_.offset, 1)
      local sub = t:add(pf.bit, r)
      sub:set_text(format("Bit %s = %d", bit_.address and tostring(bit_.address) or "?", bit_.value))
      if bit_.address ~= nil then sub:add(pf.bit_address, r, bit_.address):set_generated() end
      sub:add(pf.bit_value, r, bit_.value):set_generated()
    end
  end
  if f.objects then
    for _, object in ipairs(f.objects) do
      local r = range_of(tvb, object.offset, object.length)
      local sub = t:add(pf.object, r)
      sub:set_text(format("%s: %s", object.name, object.value))
      sub:add(pf.object_id, r, object.id)
      sub:add(pf.object_name, r, object.name):set_generated()
      sub:add(pf.object_value, r, object.value)
      if object.text then sub:add(pf.object_text, r, object.text):set_generated() end
    end
  end
  if f.request ~= nil then
    t:add(pf.request_frame, whole, f.request.record):set_generated()
    if f.time ~= nil and f.request.time ~= nil then
      local delta = f.time - f.request.time
      local seconds = floor(delta)
      t:add(pf.response_time, whole, NSTime.new(seconds, floor((delta - seconds) * 1e9 + 0.5))):set_generated()
    end
  end
  if f.response ~= nil then t:add(pf.response_frame, whole, f.response.record):set_generated() end
  if f.kind == REQUEST then
    local unanswered = f.unanswered or (pinfo.visited and state.pending == f)
    t:add(pf.unanswered, whole, unanswered and true or false):set_generated()
    if unanswered then add_text(t, ex.unanswered, "Request not answered") end
  end
  for _, text in ipairs(f.warnings) do
    if f.malformed and text:sub(1, 10) == "malformed " then
      add_text(t, ex.malformed, text)
    else
      add_text(t, ex.warning, text)
    end
  end
  for _, text in ipairs(f.notes) do
    if f.no_request and text == "response without a matching request in the capture" then
      add_text(t, ex.no_request, text)
    else
      add_text(t, ex.note, text)
    end
  end
end

local function show_noise(item, tvb, tree)
  local r = tvb:range(item.offset, item.length)
  local t = tree:add(proto, r)
  t:set_text(format("VW3 noise, %d bytes: %s", item.length, item.reason))
  t:add(pf.item, r, item.number):set_generated()
  t:add(pf.kind, r, NOISE):set_generated()
  t:add(pf.noise_reason, r, item.reason):set_generated()
  t:add(pf.data, r)
  add_text(t, ex.noise, format("%d bytes outside any frame: %s", item.length, item.reason))
end

function proto.dissector(tvb, pinfo, tree)
  local n = tvb:len()
  if n == 0 then return 0 end
  local record = state.records[pinfo.number]
  if record == nil then
    -- First pass (pinfo.visited false): frame, pair and decode in capture order; later passes reuse it.
    record = dissect_record(state, tvb:raw(0, n), pinfo.abs_ts, pinfo.number)
    state.records[pinfo.number] = record
  end
  pinfo.cols.protocol = "VW3"
  local summaries = {}
  for _, item in ipairs(record.items) do
    if item.kind == NOISE then
      show_noise(item, tvb, tree)
      summaries[#summaries + 1] = format("noise (%d bytes)", item.length)
    else
      show_frame(item, tvb, tree, pinfo)
      summaries[#summaries + 1] = summary(item)
    end
  end
  if record.frames > 1 then
    add_text(tree, ex.multiple, format("This record holds %d frames", record.frames))
  end
  if record.partial then
    add_text(tree, ex.partial, "The record ends inside a frame; its bytes are shown as noise")
  end
  pinfo.cols.info = concat(summaries, "; ")
  return n
end

-- Registration: linktype 147 (USER0), Decode As for RTAC serial records, and an optional TCP port.
DissectorTable.get("wtap_encap"):add(wtap.USER0, proto)
local ok_rtac, rtac = pcall(DissectorTable.get, "rtacser.data")
if ok_rtac and rtac ~= nil then rtac:add_for_decode_as(proto) end
DissectorTable.get("tcp.port"):add_for_decode_as(proto)

local current_port = 0
function proto.prefs_changed()
  local port = proto.prefs.tcp_port
  if port ~= current_port then
    local tcp = DissectorTable.get("tcp.port")
    if current_port ~= 0 then tcp:remove(current_port, proto) end
    if port ~= 0 then tcp:add(port, proto) end
    current_port = port
  end
  if vw3.configure then vw3.configure(proto.prefs) end
end

return vw3
