-- vw3.decode: decoding a frame's fields per function code: grammars, handlers, spec limits.
-- Mirrors dissector/decode/fields.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.decode"]).
local M = require("vw3.env")
local ipairs, pairs, string = ipairs, pairs, string
local _ENV = M -- (the other modules' names: their exports in M)
local DATA, EXCEPTION, MAX_SLAVE, REQUEST, RESPONSE = DATA, EXCEPTION, MAX_SLAVE, REQUEST, RESPONSE
local concat, floor, format, lane = concat, floor, format, lane

-- ---------------------------------------------------------------------------------------------------
-- Protocol names and limits (dissector/protocol/spec.py).
local FUNCTIONS = DATA.functions or {}
local EXCEPTIONS = DATA.exceptions or {}
local DIAGNOSTICS = DATA.diagnostics or {}
local OBJECTS = DATA.device_id_objects or {}
local LIMITS = DATA.limits or {}
local NOT_BROADCAST = DATA.not_broadcast or {}

local function function_name(code)
  local name = FUNCTIONS[code]
  if name then return name end
  if (DATA.user_defined or {})[code] then
    return format("User-defined function %d", code)
  end
  return format("Function %d", code)
end

local function exception_name(code)
  if code == nil then return "Missing exception code" end
  return EXCEPTIONS[code] or format("Unknown exception %d", code)
end

-- ---------------------------------------------------------------------------------------------------
-- Decoding (dissector/protocol/grammar.py + decode/fields.py): PDU data after the function code, then the handlers.
local function u16(b, k) return b[k] * 256 + b[k + 1] end

-- A frame's warnings and notes lists are made with their first entry (most frames have none).
local function warn(frame, text)
  local warnings = frame.warnings
  if warnings == nil then frame.warnings = { text } else warnings[#warnings + 1] = text end
end

local function check_range(frame, what, value, limit_name)
  local limit = LIMITS[limit_name]
  if limit and (value < limit[1] or value > limit[2]) then
    warn(frame, format("%s %d outside the spec's %d..%d", what, value, limit[1], limit[2]))
  end
end

local function check_span(frame, start, quantity)
  if start + quantity > 0x10000 then
    warn(frame, format("addresses %d..%d run past 65535", start, start + quantity - 1))
  end
end

-- Registers and bits are runs: where their values start in the frame's byte table, how many, the first
-- address. A value is read from the bytes each time it is needed (the first pass reads them from the
-- frame's byte table, .b, dropped once the frame is done with; the display from the tvb), so a record
-- keeps one small table for a read of 125 registers, not 125.
local function make_registers(b, first, count, start)
  return { b = b, first = first, count = count, start = start, shift = nil } -- (shift: see release_run)
end

local function make_bits(b, first, byte_count, start, quantity)
  local count = byte_count * 8
  if quantity ~= nil and quantity < count then count = quantity end
  return { b = b, first = first, count = count, start = start, shift = nil }
end

-- A run is done with its frame's byte table (the display reads the tvb): its indices become the
-- frame's own (shift: the frame's first byte in the table it was read from).
local function release_run(run)
  if run == nil then return end
  run.b = nil
  if run.shift ~= nil then
    run.first = run.first - run.shift
    run.shift = nil
  end
end

-- The index-th (0-based) register of a run: address (nil when unknown), value, and its index in b.
local function register_at(run, b, index, shift)
  -- shift: the display's tables hold the frame's own bytes; a run not released yet is 0-based elsewhere
  local k = run.first - (shift and run.shift or 0) + 2 * index
  local address = nil
  if run.start ~= nil then address = (run.start + index) % 0x10000 end
  return address, b[k] * 256 + b[k + 1], k
end

local function bit_at(run, b, index, shift)
  local k = run.first - (shift and run.shift or 0) + floor(index / 8)
  local address = nil
  if run.start ~= nil then address = (run.start + index) % 0x10000 end
  if run.single ~= nil then return address, run.single, k end
  return address, floor(b[k] / 2 ^ (index % 8)) % 2, k
end

local function ceil_bytes(bits) return floor((bits + 7) / 8) end

-- Each parser gets the frame, the byte table, the first data byte and the data length. It returns the
-- number of bytes its grammar consumed (the rest is `trailing`), or nil and a reason when the data do
-- not fit the grammar (Python: GrammarError -> "malformed ...").
local P = {}

local function read_request(f, b, d, len)
  if len < 4 then return nil, "too short for start and quantity" end
  f.fields = { start = b[d] * 256 + b[d + 1], quantity = b[d + 2] * 256 + b[d + 3] }
  return 4
end

local function read_bits_response(f, b, d, len)
  if len < 1 or len < 1 + b[d] then return nil, "byte count past the end" end
  f.fields = { byte_count = b[d], status_at = d + 1 }
  return 1 + b[d]
end

local function read_registers_response(f, b, d, len)
  if len < 1 or len < 1 + b[d] then return nil, "byte count past the end" end
  f.fields = { byte_count = b[d], values_at = d + 1, count = (b[d] - b[d] % 2) / 2 }
  return 1 + b[d]
end

local function write_single(f, b, d, len)
  if len < 4 then return nil, "too short for address and value" end
  f.fields = { address = b[d] * 256 + b[d + 1], value = b[d + 2] * 256 + b[d + 3] }
  return 4
end

local function empty(f, b, d, len)
  f.fields = {}
  return 0
end

local function diagnostics(f, b, d, len)
  if len < 2 then return nil, "too short for a sub-function" end
  f.fields = { subfunction = b[d] * 256 + b[d + 1], data_length = len - 2 }
  return len
end

local function write_coils_request(f, b, d, len)
  if len < 5 or len < 5 + b[d + 4] then return nil, "byte count past the end" end
  f.fields = { start = b[d] * 256 + b[d + 1], quantity = b[d + 2] * 256 + b[d + 3], byte_count = b[d + 4], status_at = d + 5 }
  return 5 + b[d + 4]
end

local function write_registers_request(f, b, d, len)
  if len < 5 or len < 5 + b[d + 4] then return nil, "byte count past the end" end
  f.fields = {
    start = b[d] * 256 + b[d + 1], quantity = b[d + 2] * 256 + b[d + 3], byte_count = b[d + 4], values_at = d + 5,
    count = (b[d + 4] - b[d + 4] % 2) / 2,
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
  f.fields = { address = b[d] * 256 + b[d + 1] }
  return 6
end

local function read_write_request(f, b, d, len)
  if len < 9 or len < 9 + b[d + 8] then return nil, "byte count past the end" end
  f.fields = {
    read_start = b[d] * 256 + b[d + 1], read_quantity = b[d + 2] * 256 + b[d + 3], write_start = b[d + 4] * 256 + b[d + 5],
    write_quantity = b[d + 6] * 256 + b[d + 7], byte_count = b[d + 8], values_at = d + 9, count = (b[d + 8] - b[d + 8] % 2) / 2,
  }
  return 9 + b[d + 8]
end

local function fifo_request(f, b, d, len)
  if len < 2 then return nil, "too short for an address" end
  f.fields = { address = b[d] * 256 + b[d + 1] }
  return 2
end

local function fifo_response(f, b, d, len)
  if len < 4 or len < 4 + 2 * (b[d + 2] * 256 + b[d + 3]) then return nil, "FIFO count past the end" end
  f.fields = { byte_count = b[d] * 256 + b[d + 1], fifo_count = b[d + 2] * 256 + b[d + 3] }
  return 4 + 2 * (b[d + 2] * 256 + b[d + 3])
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
    -- The bytes read as latin-1 (as the Python decoder does), held as UTF-8 for Wireshark's strings.
    local chars = {}
    for k = 0, size - 1 do
      local byte = b[d + position + 2 + k]
      if byte < 128 then
        chars[#chars + 1] = string.char(byte)
      else
        chars[#chars + 1] = string.char(192 + floor(byte / 64), 128 + byte % 64)
      end
    end
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

-- Parsers by layout name (dissector/protocol/layouts.py); which code uses which: the generated table.
local GRAMMARS = { [REQUEST] = {}, [RESPONSE] = {} }
  local PARSERS = {
    read_request = read_request, write_multiple_response = read_request,
    read_bits_response = read_bits_response, read_registers_response = read_registers_response,
    write_single = write_single, empty = empty, diagnostics = diagnostics,
    write_coils_request = write_coils_request, write_registers_request = write_registers_request,
    exception_status_response = fixed_size(1, "too short for a status"),
    comm_event_counter_response = fixed_size(4, "too short for status and event count"),
    comm_event_log_response = comm_event_log_response, byte_counted = byte_counted,
    read_file_request = byte_counted, read_file_response = byte_counted, write_file = byte_counted,
    mask_write = mask_write, read_write_request = read_write_request, fifo_request = fifo_request,
    fifo_response = fifo_response, mei_request = mei_request, mei_response = mei_response,
    report_server_id_response = function(f, b, d, len)
      if len < 3 or b[d] < 2 or len < 1 + b[d] then return nil, "byte count below 2 or past the end" end
      f.fields = { byte_count = b[d], server_id = b[d + 1], run_indicator = b[d + 2] }
      return 1 + b[d]
    end,
  }
  for code, name in pairs(DATA.protocol.parsers.request) do GRAMMARS[REQUEST][code] = PARSERS[name] end
  for code, name in pairs(DATA.protocol.parsers.response) do GRAMMARS[RESPONSE][code] = PARSERS[name] end

-- Handlers (decode/fields.py): lift out start, quantity, registers, bits, objects; check the spec.
local H = { [REQUEST] = {}, [RESPONSE] = {} }

local function read_request_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.start, fields.quantity
  check_range(f, "quantity", fields.quantity, DATA.protocol.limits.request[f.fn])
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

-- The registers an answer of function fn reads, from its request's fields: FC23 reads its read window.
function lane.asked_window(fn, request)
  if fn == 23 then return request.read_start, request.read_quantity end
  return request.start, request.quantity
end

local function read_registers_response_handler(f, b)
  local fields = f.fields
  local request = request_fields(f)
  local start = nil
  if request ~= nil then
    local quantity
    start, quantity = lane.asked_window(f.fn, request)
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

-- fields._check_echo: an FC5/FC6 answer echoes its request; one that does not wrote something else.
local write_single_coil_handler, write_single_register_handler
  local function check_echo(f, fields)
    local request = request_fields(f)
    if request == nil then return end
    local address, value = request.address ~= fields.address, request.value ~= fields.value
    if address and value then
      warn(f, "the response's address and value differ from the request's")
    elseif address then
      warn(f, "the response's address differs from the request's")
    elseif value then
      warn(f, "the response's value differs from the request's")
    end
  end

  write_single_coil_handler = function(f, b)
    local fields = f.fields
    f.start, f.quantity = fields.address, 1
    if fields.value ~= 0xFF00 and fields.value ~= 0 then
      warn(f, format("coil value 0x%04X is neither 0xFF00 (on) nor 0x0000 (off)", fields.value))
    end
    check_echo(f, fields)
    local value = 0
    if fields.value == 0xFF00 then value = 1 end
    f.bits = { first = f.data_at + 2, count = 1, start = fields.address, single = value }
  end

  write_single_register_handler = function(f, b)
    local fields = f.fields
    f.start, f.quantity = fields.address, 1
    check_echo(f, fields)
    f.registers = make_registers(b, f.data_at + 2, 1, fields.address)
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
  check_range(f, "quantity", fields.quantity, DATA.protocol.limits.request[f.fn])
  check_span(f, fields.start, fields.quantity)
  if fields.byte_count ~= ceil_bytes(fields.quantity) then
    warn(f, format("byte count %d disagrees with the quantity %d", fields.byte_count, fields.quantity))
  end
  f.bits = make_bits(b, fields.status_at, fields.byte_count, fields.start, fields.quantity)
end

local function write_registers_request_handler(f, b)
  local fields = f.fields
  f.start, f.quantity = fields.start, fields.quantity
  check_range(f, "quantity", fields.quantity, DATA.protocol.limits.request[f.fn])
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

-- Handlers by name (dissector/decode/fields.py); which code uses which: the generated table.
  local HANDLERS = {
    read_request = read_request_handler, read_bits_response = read_bits_response_handler,
    read_registers_response = read_registers_response_handler, write_single_coil = write_single_coil_handler,
    write_single_register = write_single_register_handler, diagnostics = diagnostics_handler,
    write_coils_request = write_coils_request_handler, write_registers_request = write_registers_request_handler,
    write_multiple_response = write_multiple_response_handler, mask_write = mask_write_handler,
    read_write_request = read_write_request_handler, fifo_request = fifo_request_handler,
    fifo_response = fifo_response_handler, mei_response = mei_response_handler,
    report_server_id_response = function(f, b)
      -- the additional data as text when every byte is printable ASCII (a version string), as Python
      local fields, d = f.fields, f.data_at
      local run, length, chars = fields.run_indicator, fields.byte_count - 2, {}
      if run ~= 0 and run ~= 255 then
        warn(f, format("run indicator 0x%02X is neither 0x00 (OFF) nor 0xFF (ON)", run))
      end
      for k = 0, length - 1 do
        local byte = b[d + 3 + k]
        if byte < 32 or byte > 126 then chars = nil break end
        chars[#chars + 1] = string.char(byte)
      end
      f.server = { at = d, byte_count = fields.byte_count, id = fields.server_id, run = run, length = length,
        text = length > 0 and chars and concat(chars) or nil }
    end,
  }
  for code, name in pairs(DATA.protocol.handlers.request) do H[REQUEST][code] = HANDLERS[name] end
  for code, name in pairs(DATA.protocol.handlers.response) do H[RESPONSE][code] = HANDLERS[name] end

local function decode_frame(f)
  local b, d, len = f.b, f.data_at, f.data_len
  if f.slave > MAX_SLAVE then warn(f, format("slave address %d is reserved (248..255 are no device's)", f.slave)) end
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

M.DIAGNOSTICS, M.EXCEPTIONS, M.FUNCTIONS, M.LIMITS = DIAGNOSTICS, EXCEPTIONS, FUNCTIONS, LIMITS
M.NOT_BROADCAST, M.bit_at, M.ceil_bytes, M.decode_frame = NOT_BROADCAST, bit_at, ceil_bytes, decode_frame
M.exception_name, M.function_name, M.register_at = exception_name, function_name, register_at
M.release_run, M.u16, M.warn = release_run, u16, warn
