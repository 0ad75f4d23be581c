-- vw3.decode: decoding a frame's fields per function code: grammars, handlers, spec limits.
-- Mirrors dissector/decode/fields.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.decode"]).
local RULES = DATA.rules

-- ---------------------------------------------------------------------------------------------------
-- Protocol names and limits (dissector/protocol/spec.py).
local FUNCTIONS = DATA.functions or {}
local EXCEPTIONS = DATA.exceptions or {}
local DIAGNOSTICS = DATA.diagnostics or {}
local LIMITS = RULES.limits
local NOT_BROADCAST = DATA.not_broadcast or {}
-- FC43's mandatory objects by name (`VendorName, ProductCode, ...`), and a device object's byte as in a Python
-- bytes literal between single quotes (never a control character): RULES.mandatory_objects, RULES.byte_text.
local MANDATORY_OBJECTS, BYTE_TEXT = RULES.mandatory_objects, RULES.byte_text

-- A catalogue entry's text (format, params; repr: the parameters Python writes as `!r`, shown by `quote`)
-- with its parameters by name, as Python fills them in: the texts here and maps.py's MESSAGES alike.
local function fill(entry, values, quote)
  local params, repr, args = entry.params, entry.repr, {}
  for index = 1, #params do
    local name = params[index]
    args[index] = repr and repr[name] and quote(values[name]) or values[name]
  end
  return format(entry.format, table.unpack(args, 1, #params))
end

-- The catalogue's text `key` (data/modbus.toml [texts], protocol/rules.py text()).
local function say(key, values) return fill(RULES.texts[key], values) end

local function function_name(code)
  return FUNCTIONS[code] or say(DATA.user_defined[code] and "user_function" or "other_function", { code = code })
end

local function exception_name(code)
  if code == nil then return say("missing_exception", {}) end
  return EXCEPTIONS[code] or say("undefined_exception", { code = code })
end

-- ---------------------------------------------------------------------------------------------------
-- Decoding (dissector/protocol/grammar.py + decode/fields.py): PDU data after the function code, then the handlers.
local function u16(b, k) return b[k] * 256 + b[k + 1] end

-- A frame's warnings and notes lists are made with their first entry (most frames have none).
local function adder(key)
  return function(f, text)
    local list = f[key]
    if list == nil then f[key] = { text } else list[#list + 1] = text end
  end
end
local warn, note = adder("warnings"), adder("notes")

-- b[first..last] as text where every byte is printable ASCII (as vw3-decode shows a device's data), else nil.
local function printable_ascii(b, first, last)
  local text = string_of(b, first, last - first + 1)
  return not text:find("[^ -~]") and text or nil
end

-- Bytes b[first .. last] in hex, each by `pattern` (%02x, %02X), joined by `gap`.
local function hex_of(b, first, last, pattern, gap)
  local out = {}
  for k = first, last do out[#out + 1] = format(pattern, b[k]) end
  return concat(out, gap)
end

-- Does the frame tell the parameters anything (devices/memory.py)? Not one that failed its check (the
-- device ignored it: Modbus over serial line 2.5.1.2): its values are shown, no status judged, no story
-- told, no memory changed; nor does its answer take addresses from it (pairing.py trusted_request).
local function verified(f)
  return f.crc == f.crc_expected
end

-- The request an answer is read against (its window, its echo, what an exception refuses), nil when the
-- capture has none or the tap's copy of it failed its check: the answer is paired, its addresses unknown
-- and nothing is judged, told or remembered of them (pairing.py trusted_request).
local function trusted_request(f)
  local request = f.request
  if request ~= nil and verified(request) then return request end
  return nil
end

-- Registers and bits are runs (made by the lifting rules' handlers): where their values start in the frame's
-- byte table, how many, the first address. A value is read from the bytes each time it is needed (the first
-- pass reads them from the frame's byte table, .b, dropped once the frame is done with; the display from
-- the tvb), so a record keeps one small table for a read of 125 registers, not 125.

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

-- The readers of the layouts (data/modbus.toml [layouts] and [parts], protocol/shapes.py) by name, written out
-- by the code generator (DATA.parsers, codegen/decode_lua.py); which code uses which: DATA.grammars, below. Each
-- gets the byte table, the first data byte and the data length, and returns the number of bytes its layout
-- consumed (the rest is `trailing`) and the fields, or nil and why the data do not fit (Python: GrammarError
-- -> "malformed ..."). The display reads the fields by their sizes (a fixed one's: its .size, tree.lua).
local PARSERS = DATA.parsers

-- ---------------------------------------------------------------------------------------------------
-- The lifting rules of data/modbus.toml [lift] (decode/fields.py lifter) are handlers written out by the code
-- generator (DATA.lifters, codegen/decode_lua.py), each rule's limits and fields in place; they call the helpers
-- below. Warnings in the table's order: checks, span, byte count, odd count, coil, echo.
local function echo_check(f, fields, request, echo)
  local answered, differ = request.fields, {}
  for _, name in ipairs(echo.fields) do
    if answered[name] ~= fields[name] then differ[#differ + 1] = name end
  end
  if echo.names ~= "differing" then differ = echo.fields end
  warn(f, say("echo", { fields = concat(differ, " and "), verb = #differ == 1 and "differs" or "differ" }))
end

-- A value outside the spec's low..high (protocol/rules.py range_text): one the spec allows alone named.
local function range_text(what, value, low, high)
  if low == high then return say("range_one", { what = what, value = value, low = low }) end
  return say("range", { what = what, value = value, low = low, high = high })
end

-- An answer that repeats its request's data whole (FC21's; from `skip`: an FC8 sub-function's,
-- [diagnostic_answers]): a request keeps them as a string (its byte table is dropped before its answer comes);
-- an answer that differs answered other data (fields._diagnostics, _check_echo).
local function check_data_echo(f, b, request, skip)
  local data = string_of(b, f.data_at + skip, f.data_len - skip)
  if f.kind == REQUEST then
    f.fields.echoed = data
  elseif request ~= nil and request.fields ~= nil and request.fields.echoed ~= data then
    warn(f, say("echo", { fields = "data", verb = "differs" }))
  end
end

-- An answer's parts against its request's (decode/fields.py _check_parts; FC20): as many, each of the length its
-- request part asks (`given`: the answer's length fields, `asked`: what its request kept of its parts).
local function check_asked(f, parts, index, given, asked)
  local length = parts.length
  if #asked ~= index then warn(f, say("part_count", { part = parts.name, count = index, quantity = #asked })) end
  for k = 1, given and math.min(#asked, index) or 0 do
    if given[k] ~= length.plus + length.unit * asked[k] then
      -- (what the length holds in the request's unit: protocol/rules.py PartLength.held)
      local data = math.max(given[k] - length.plus, 0)
      local whole, rest = math.floor(data / length.unit), data % length.unit
      local held = rest > 0 and (whole .. " and " .. rest .. " byte(s)") or tostring(whole)
      warn(f, say(length.text, { part = parts.name, index = k, count = given[k], held = held, quantity = asked[k] }))
    end
  end
end

-- A write's words past its quantity (fields.py _past_quantity), `size` bytes at b[at]: no register written,
-- warned by their bytes (the text `key`).
local function past_quantity(f, b, at, size, quantity, key)
  warn(f, say(key, { count = size, quantity = quantity, data = hex_of(b, at, at + size - 1, "%02x", " ") }))
end

-- An FC8 request's data word as the spec has it for its sub-function (RULES.diagnostic_data, fields.py
-- _diagnostic_data): what it asks (a note), or a warning where the spec allows another.
local DIAGNOSTIC_DATA = RULES.diagnostic_data
local function diagnostic_data(f, b, subfunction, rule)
  local at, count = f.data_at + 2, f.fields.data_length
  local word = count == 2 and u16(b, at) or nil
  local meaning = rule.data and word and rule.data[word]
  if meaning then
    if meaning ~= "" then note(f, meaning) end
  elseif rule.data == nil and word and word % 256 == 0 then
    local code = floor(word / 256)
    local name = rule.names[code] or code > 32 and code < 127 and "'" .. string.char(code) .. "'"
    note(f, name and say("diagnostic_character", { what = rule.character, character = name, code = code })
      or say("diagnostic_byte", { what = rule.character, code = code }))
  else
    -- (the data as sent, in hex; rule.allowed: the words the spec allows, or its character then 00)
    local data = hex_of(b, at, f.data_at + f.data_len - 1, "%02X", "")
    warn(f, say("diagnostic_data", { data = data ~= "" and data or "(none)", subfunction = subfunction,
      allowed = rule.allowed }))
  end
end

-- The FC8 sub-functions whose answer repeats the request's data ([diagnostic_answers]): a request's data are
-- kept in its fields as a string (its byte table is dropped before its answer comes), an answer's compared.
local DIAGNOSTIC_ECHOES = RULES.diagnostic_echoes

-- The named special cases no rule describes (decode/fields.py SPECIAL_HANDLERS).
local SPECIAL = {
  diagnostics = function(f, b)
    local fields = f.fields
    local subfunction, odd = fields.subfunction, fields.data_length % 2 == 1
    local rule = f.kind == REQUEST and DIAGNOSTIC_DATA[subfunction]
    f.subfunction = subfunction
    if DIAGNOSTICS[subfunction] == nil then warn(f, say("unknown_subfunction", { subfunction = subfunction })) end
    if odd then warn(f, say("odd_diagnostic_data", {})) end
    if rule and not odd then diagnostic_data(f, b, subfunction, rule) end
    if DIAGNOSTIC_ECHOES[subfunction] and (f.kind == REQUEST or not odd) then
      check_data_echo(f, b, f.request, 2)
    end
  end,
  mei_request = function(f, b)
    -- (another MEI type: the layout's switch read no Read Device ID code)
    local code, limit = f.fields.body.read_code, LIMITS.device_id_code
    if code ~= nil and (code < limit[1] or code > limit[2]) then
      warn(f, say("device_id_code", { code = code, low = limit[1], high = limit[2] }))
    end
  end,
  mei_response = function(f, b)
    -- The objects the reader listed become the frame's (its fields are dropped once it is done with):
    -- each named, its value as text, where it starts (its id) and its bytes (id and length too).
    local objects = f.fields.body.objects
    if objects == nil then return end -- (another MEI type: the layout's switch read no device identification)
    for _, object in ipairs(objects) do
      -- as a bytes literal's text, shown between single quotes (decode/fields.py _mei_response)
      local chars, at, size = {}, object.value_at, object.length
      for k = at, at + size - 1 do chars[#chars + 1] = BYTE_TEXT[b[k]] end
      object.name = DATA.device_id_objects[object.id] or say("other_object", { id = object.id })
      object.value, object.offset, object.length, object.value_at = concat(chars), at - 2, 2 + size, nil
    end
    f.objects = objects
    -- (a count the frame does not hold: the objects there are shown, decode/fields.py)
    local declared = f.fields.body.object_count
    if #objects < declared then warn(f, say("object_count", { count = declared, present = #objects })) end
    if #objects == 0 then warn(f, say("no_objects", { names = MANDATORY_OBJECTS })) end -- (fields.py _mei_response)
  end,
  report_server_id_response = function(f, b)
    -- (the tree shows its fields from the layout, tree.lua add_pdu)
    local run, names, count = f.fields.run_indicator, DATA.names.run_indicator, f.fields.byte_count
    if count == 0 then -- (no server id either: the layout's ?(byte_count))
      warn(f, say("no_server_id", { count = count }))
    elseif run == nil then -- (byte count 1: the server id alone, the layout's ?(byte_count-1))
      warn(f, say("no_run_indicator", { count = count }))
    elseif names[run] == nil then
      -- An FC17 answer's server id is device specific in length (fields.py _report_server_id_response): the
      -- first byte after its first that is a run indicator (00, FF) may follow a longer id.
      local first, ends = f.data_at + 1, nil -- (the server id's first byte)
      for k = f.data_at + count, first + 1, -1 do ends = names[b[k]] ~= nil and k or ends end
      if ends == nil then
        warn(f, say("run_indicator", { value = run })) -- (OFF, ON: none where any length of server id puts it)
      else -- (the id is read up to the first 00 or FF after its first byte: fields.py _report_server_id_response)
        f.server_id_size = ends - first -- (tree.lua shows the id, its run indicator and data so split)
        warn(f, say("server_id_read_longer", { count = ends - first, value = run }))
      end
    end
  end,
}

-- Per direction and code, written out by the code generator from RULES.by_code: the parser of its layout
-- (GRAMMARS), its lifting rule (LIFT_OF; nil: none or a named special case) and its handler (H): the lifting
-- rule's where the table has one, else the special case's.
local GRAMMARS, LIFT_OF = DATA.grammars, DATA.lift_of
-- The codes whose answer's window is its request's ([lift] start `request.start`: FC1..4, FC23, FC24).
local WINDOW_ASKED = {}
for code, rule in pairs(LIFT_OF.response) do WINDOW_ASKED[code] = rule.start == "request.start" end
local H = DATA.lifters(SPECIAL, warn, say, echo_check, data_bytes, range_text, check_asked, check_data_echo,
  past_quantity)

-- Register writes by how they are confirmed (data/modbus.toml [confirm]; annotator.py _BY_ECHO, _BY_ANSWER):
-- by their echo (FC6), by a normal answer (FC16, FC23).
local CONFIRMED = RULES.confirmed

local function decode_frame(f)
  local b, d, len = f.b, f.data_at, f.data_len
  if f.slave > MAX_SLAVE then warn(f, say("reserved_slave", { slave = f.slave })) end
  if f.kind == EXCEPTION then
    -- (its layout's reader: no code is malformed, bytes after it trailing, as decode/fields.py says)
    local used, why = PARSERS.exception(b, d, len)
    f.fields = {}
    if used == nil then
      warn(f, say("malformed", { kind = f.kind, error = why }))
      return
    end
    f.exception_code = b[d]
    if EXCEPTIONS[f.exception_code] == nil then
      warn(f, say("unknown_exception", { code = f.exception_code }))
    end
    if used < len then warn(f, say("trailing", { count = len - used })) end
    return
  end
  local used, fields = (GRAMMARS[f.kind][f.fn] or PARSERS.raw)(b, d, len)
  if used == nil then -- (fields: the reason)
    f.fields = nil
    f.malformed = true
    warn(f, say("malformed", { kind = f.kind, error = fields }))
    return
  end
  f.fields = fields
  local handler = H[f.kind][f.fn]
  if handler ~= nil then handler(f, b) end
  local request = f.request
  if request ~= nil and not verified(request) and WINDOW_ASKED[f.fn] then
    -- Its request failed its check (annotate_with kept none of its fields): no addresses
    -- (decode/fields.py lifter, pairing.py trusted_request).
    note(f, say("request_damaged", { check = f.ascii and "LRC" or "CRC" }))
  end
  if used < len then warn(f, say("trailing", { count = len - used })) end
  if f.broadcast and NOT_BROADCAST[f.fn] then
    warn(f, say("not_broadcast", { ["function"] = function_name(f.fn) }))
  end
end
