-- vw3.decode: decoding a frame's fields per function code: grammars, handlers, spec limits.
-- Mirrors dissector/decode/fields.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.decode"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local RULES = DATA.rules

-- ---------------------------------------------------------------------------------------------------
-- Protocol names and limits (dissector/protocol/spec.py).
local FUNCTIONS = DATA.functions or {}
local EXCEPTIONS = DATA.exceptions or {}
local DIAGNOSTICS = DATA.diagnostics or {}
local LIMITS = RULES.limits
local NOT_BROADCAST = DATA.not_broadcast or {}

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
local function warn(frame, text)
  local warnings = frame.warnings
  if warnings == nil then frame.warnings = { text } else warnings[#warnings + 1] = text end
end

-- Registers and bits are runs (made by the lifter below): where their values start in the frame's byte
-- table, how many, the first address. A value is read from the bytes each time it is needed (the first
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

-- Each parser gets the byte table, the first data byte and the data length. It returns the number of
-- bytes its grammar consumed (the rest is `trailing`) and the fields, or nil and a reason when the data
-- do not fit the grammar (Python: GrammarError -> "malformed ...").
-- Every layout is read as its description says (data/modbus.toml [layouts] and [parts], protocol/shapes.py):
-- u8 and u16 fields by name, a counted field (bytes, text, words, odd, records) by where it starts
-- (NAME_at), the rest of the data by its length (NAME_length), an array of parts as a list of their
-- fields, a switch as the fields of the part it chose. Each description is made into a Lua function once
-- (load), so that a frame costs what a hand-written parser costs: one length check for the fixed fields
-- that come first, read at constant offsets, and the fields in one table constructor.
local SIZES = { u8 = 1, u16 = 2 }
local PARTS = {} -- (the parts' readers, which the layouts' call by name)

-- A counted field's size in bytes, from the local holding its count: less `minus` (which may make it
-- negative: the data do not fit), words(n/2) a whole number of words.
local function size_of(field, count)
  if field.type == "odd" then return format("%s %% 2", count) end
  local n = field.minus > 0 and format("(%s - %d)", count, field.minus) or count
  if field.half then return format("%s - %s %% 2", n, n) end
  return field.type == "words" and "2 * " .. n or n
end

local function shape_parser(shape, offsets) -- (offsets: filled with where each field at a constant offset is)
  local lines, keys, index_of, names = { "local PARTS = ...", "return function(b, d, len)" }, {}, {}, {}
  local function add(...) lines[#lines + 1] = format(...) end
  local counts = {} -- (the fields a later one counts by: read into a local; the others in the constructor)
  for _, field in ipairs(shape) do
    if field.count ~= nil then counts[field.count] = true end
  end
  local static = 0 -- where the next field starts while it is a constant; then `p`
  for index, field in ipairs(shape) do
    local name, kind, size = field.name, field.type, SIZES[field.type]
    index_of[name], offsets[name] = index, static
    local here = static and (static == 0 and "d" or format("d + %d", static)) or "d + p"
    if size ~= nil then
      if not static then add("if p + %d > len then return nil, %q end", size, "too short for " .. name) end
      if static then names[#names + 1] = name end -- (the fixed fields first: one length check for them all, below)
      local value = format("b[%s]", here)
      if size == 2 then value = format("%s * 256 + b[%s]", value, static and format("d + %d", static + 1) or "d + p + 1") end
      if counts[name] or not static then
        add("local v%d = %s", index, value)
        value = format("v%d", index)
      end
      keys[#keys + 1] = format("[%q] = %s", name, value)
      if static then static = static + size else add("p = p + %d", size) end
    elseif kind == "rest" then
      keys[#keys + 1] = format("[%q] = len - %s", name .. "_length", static and format("%d", static) or "p")
    else
      if static then add("local p = %d", static) end
      static = nil
      local count = format("v%d", index_of[field.count])
      if kind == "array" then -- (count parts one after the other; one that does not fit ends them: layouts._UpTo)
        add("local a%d = {}", index)
        add("for k = 1, %s do", count)
        add("  local used, item = PARTS[%q](b, d + p, len - p)", field.part)
        add("  if used == nil then break end")
        add("  a%d[k], p = item, p + used", index)
        add("end")
        keys[#keys + 1] = format("[%q] = a%d", name, index)
      elseif kind == "switch" then -- (the part for the field's value, else the last one)
        local choice = {}
        for _, case in ipairs(field.cases) do
          choice[#choice + 1] = case.value and format("%s == %d and PARTS[%q]", count, case.value, case.part)
            or format("PARTS[%q]", case.part)
        end
        add("local used, c%d = (%s)(b, d + p, len - p)", index, concat(choice, " or "))
        add("if used == nil then return nil, c%d end", index)
        add("p = p + used")
        keys[#keys + 1] = format("[%q] = c%d", name, index)
      else
        add("local s%d = %s", index, size_of(field, count))
        local negative = field.minus > 0 and format("s%d < 0 or ", index) or "" -- (less `minus`: maybe below 0)
        add("if %sp + s%d > len then return nil, %q end", negative, index, field.count .. " past the end")
        if kind ~= "odd" then -- (where an odd byte is, nothing asks)
          add("local a%d = d + p", index)
          keys[#keys + 1] = format("[%q] = a%d", name .. "_at", index)
        end
        add("p = p + s%d", index)
      end
    end
  end
  if #names > 0 then
    local last = table.remove(names)
    local what = #names > 0 and concat(names, ", ") .. " and " .. last or last
    local fixed = offsets[last] + SIZES[shape[index_of[last]].type] -- (where the last of them ends)
    table.insert(lines, 3, format("if len < %d then return nil, %q end", fixed, "too short for " .. what))
  end
  local trailing = #shape == 0 or shape[#shape].type ~= "rest"
  add("return %s, { %s }", not trailing and "len" or static and format("%d", static) or "p", concat(keys, ", "))
  add("end")
  return load(concat(lines, "\n"))(PARTS)
end

-- Parsers by layout name (dissector/protocol/layouts.py), and where their fields are when that is a
-- constant; which code uses which: the generated table (RULES.by_code, below).
local PARSERS, OFFSETS = {}, {}
for name, shape in pairs(RULES.parts) do PARTS[name] = shape_parser(shape, {}) end
for name, shape in pairs(RULES.layouts) do
  OFFSETS[name] = {}
  PARSERS[name] = shape_parser(shape, OFFSETS[name])
end

-- ---------------------------------------------------------------------------------------------------
-- The generic lifter (decode/fields.py lifter): one rule of data/modbus.toml [lift] prepared for one
-- function code and direction, as a handler. Warnings in the table's order: checks, span, byte count,
-- odd count, coil, echo. Like the parsers, each rule is written out as a Lua function once (load), its
-- limits and fields in place, so that a frame costs what a hand-written handler costs.
local REQUEST_START, REQUEST_QUANTITY = "request.start", "request.quantity"

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

-- The data bytes after the function code (after `skip` more: FC8's sub-function), as a string.
local function data_bytes_of(f, b, skip)
  return string.char(table.unpack(b, f.data_at + skip, f.data_at + f.data_len - 1))
end

-- An answer that repeats its request's data whole (FC21's; from `skip`: an FC8 sub-function's,
-- [diagnostic_answers]): a request keeps them as a string (its byte table is dropped before its answer comes);
-- an answer that differs answered other data (fields._diagnostics, _check_echo).
local function check_data_echo(f, b, request, skip)
  local data = data_bytes_of(f, b, skip)
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
      warn(f, say(length.text, { part = parts.name, index = k, count = given[k], quantity = asked[k] }))
    end
  end
end

-- The line that checks `value` (an expression) against low..high, `what` (an expression) naming it; test
-- "above": the high bound only (its text names no low one). The fields are unsigned: a low bound of 0 is none.
local function check_line(check, value, what, low, high)
  if check.test == "above" then
    return format("if %s > %d then warn(f, say(\"above\", { what = %s, value = %s, high = %d })) end", value, high,
      what, value, high)
  end
  local outside = low == high and format("%s ~= %d", value, low) or low == 0 and format("%s > %d", value, high)
    or format("%s < %d or %s > %d", value, low, value, high)
  return format("if %s then warn(f, range_text(%s, %s, %d, %d)) end", outside, what, value, low, high)
end

-- The lines of a lifter walking each part of a records field in the frame's bytes (FC20, FC21): its checks
-- (range_text, "above"), what an answer asks of a request's part kept (`keep`), an answer's length fields
-- (check_asked). Where its fields are and its size come from RULES (codegen/rules_lua.py); a part that does
-- not fit ends them, as the grammar's. Constants in place, no table a part.
local function parts_lines(add, parts, at, size, request)
  local function read(spec) -- (a field of the part at `p`: its offset and width)
    return spec[2] == 1 and format("b[p + %d]", spec[1]) or format("b[p + %d] * 256 + b[p + %d]", spec[1], spec[1] + 1)
  end
  add("local p, stop, index = %s, %s + %s, 0", at, at, size)
  if parts.keep then add("local kept = {}") end
  if parts.length then add("local given = {}") end
  add("while p + %d <= stop do", parts.fixed)
  local bytes = format("%d", parts.fixed)
  if parts.size then
    local counted = parts.size
    add("local n = %s - %d", read(counted.at), counted.minus)
    add("if n < 0 then break end")
    bytes = format("%d + %s", parts.fixed, counted.half and "n - n % 2" or counted.words and "2 * n" or "n")
  end
  add("if p + %s > stop then break end", bytes)
  add("index = index + 1")
  for _, check in ipairs(parts.checks) do
    add("local v = %s", read(check.at))
    local what = format("%q .. index .. %q", parts.name .. " ", "'s " .. check.what)
    add("%s", check_line(check, "v", what, table.unpack(LIMITS[check.limit])))
  end
  if parts.keep then add("kept[index] = %s", read(parts.keep)) end
  if parts.length then add("given[index] = %s", read(parts.length.at)) end
  add("p = p + %s", bytes)
  add("end")
  if parts.keep then add("fields[%q] = kept", parts.field) end
  if parts.request then
    add("if %s ~= nil and request.fields[%q] ~= nil then", request, parts.request)
    add("  check_asked(f, parts, index, %s, request.fields[%q])", parts.length and "given" or "nil", parts.request)
    add("end")
  end
end

local function lifter(rule, limit, layout)
  local named = {} -- (the layout's fields by name)
  for _, item in ipairs(RULES.layouts[layout] or {}) do named[item.name] = item end
  local function field(name) return format("fields[%q]", name) end
  local out = { "local warn, say, floor, echo_check, echo, data_bytes, range_text, check_asked, parts, check_data_echo = ...",
    "return function(f, b)", "local fields = f.fields" }
  local function add(...) out[#out + 1] = format(...) end
  local start, quantity, count, values = rule.start, rule.quantity, rule.count, rule.values
  if start == REQUEST_START or quantity == REQUEST_QUANTITY or (count and count.of == REQUEST_QUANTITY) or rule.echo
    or (rule.parts and rule.parts.request) then
    add("local request = f.request")
    add("if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)")
  end
  if start == REQUEST_START then add("local first = request and request.start")
  else add("local first = %s", start and field(start) or "nil") end
  if type(quantity) == "number" then add("local many = %d", quantity)
  elseif quantity == REQUEST_QUANTITY then
    add("local many = request and request.quantity")
    if rule.unpaired_unit then
      add("if many == nil and fields.byte_count %% %d == 0 then many = floor(fields.byte_count / %d) end",
        rule.unpaired_unit, rule.unpaired_unit)
    end
  else add("local many = %s", quantity and field(quantity) or "nil") end
  add("f.start, f.quantity = first, many")
  for _, check in ipairs(rule.checks) do
    local low, high = table.unpack(LIMITS[check.limit or limit])
    add("%s", check_line(check, field(check.field), format("%q", check.what), low, high))
  end
  local function span(first, many) -- (a window past the last address, 65535)
    local text = "if %s + %s > 65536 then warn(f, say(\"span\", { first = %s, last = %s + %s - 1 })) end"
    add(text, first, many, first, first, many)
  end
  if rule.span then span("first", "many") end
  local window = rule.write_window -- (FC23: its written window too)
  if rule.span and window then span(field(window[1]), field(window[2])) end
  if count then
    add("local of = %s", count.of == REQUEST_QUANTITY and "request and request.quantity" or field(count.of))
    add("if of ~= nil and fields.byte_count ~= %d + data_bytes(of, %d) then", count.plus, count.unit)
    add("  warn(f, say(%q, { count = fields.byte_count, quantity = of }))", count.text)
    add("end")
  end
  if rule.odd_count then
    add("if fields.byte_count %% 2 == 1 then warn(f, say(\"odd_count\", { count = fields.byte_count })) end")
  end
  if rule.coil then
    add("if %s ~= 65280 and %s ~= 0 then warn(f, say(\"coil_value\", { value = %s })) end", field(rule.coil),
      field(rule.coil), field(rule.coil))
  end
  if rule.echo and rule.echo.data then -- (FC21: the answer repeats the request's data whole)
    add("check_data_echo(f, b, request, 0)")
  elseif rule.echo then -- (an answer that repeats its request but differs from it wrote something else)
    local differs = {}
    for index, name in ipairs(rule.echo.fields) do differs[index] = format("request.fields[%q] ~= %s", name, field(name)) end
    add("if request ~= nil and (%s) then echo_check(f, fields, request, echo) end", concat(differs, " or "))
  end
  if values then -- (a run's `shift`: see release_run; a block's from its count field, in words or bytes)
    local at, item = field(values.field .. "_at"), named[values.field] or {}
    local counted = item.count and (item.half and format("floor(%s / 2)", field(item.count)) or field(item.count))
    local offset = (OFFSETS[layout] or {})[values.field] -- (one value at a fixed offset of the data)
    if values.kind == "registers" then
      add("f.registers = { b = b, first = %s, count = %s, start = %s, shift = nil }", at, counted,
        values.start and field(values.start) or "first")
    elseif values.kind == "bits" then
      add("local count = 8 * %s", counted)
      add("if many ~= nil and many < count then count = many end")
      add("f.bits = { b = b, first = %s, count = count, start = first, shift = nil }", at)
    elseif values.kind == "register" then
      add("f.registers = { b = b, first = f.data_at + %d, count = 1, start = first, shift = nil }", offset)
    else
      add("f.bits = { first = f.data_at + %d, count = 1, start = first, single = %s == 65280 and 1 or 0 }", offset,
        field(values.field))
    end
  end
  if rule.parts then -- (its parts by the layout's part, in the bytes its count gives)
    local name = rule.parts.field
    parts_lines(add, rule.parts, field(name .. "_at"), field(named[name].count), "request")
  end
  add("end")
  return load(concat(out, "\n"))(warn, say, floor, echo_check, rule.echo, data_bytes, range_text, check_asked,
    rule.parts, check_data_echo)
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
    local allowed = {} -- (the words the spec allows, or its character then 00; the data as sent, in hex)
    for index, value in ipairs(rule.words or {}) do allowed[index] = format("%04X", value) end
    local data = data_bytes_of(f, b, 2):gsub(".", function(byte) return format("%02X", byte:byte()) end)
    warn(f, say("diagnostic_data", { data = data ~= "" and data or "(none)", subfunction = subfunction,
      allowed = rule.data and concat(allowed, " or ") or say("character_then_00", {}) }))
  end
end

-- An FC17 answer's server id is device specific in length (fields.py _report_server_id_response): is a byte
-- from b[from] to b[last] a run indicator (00, FF) that may follow a longer id?
local function run_indicator_after(b, from, last, names)
  for k = from, last do
    if names[b[k]] ~= nil then return true end
  end
  return false
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
      -- The bytes read as latin-1 (as the Python decoder does), held as UTF-8 for Wireshark's strings.
      local chars, at, size = {}, object.value_at, object.length
      for k = at, at + size - 1 do
        local byte = b[k]
        chars[#chars + 1] = byte < 128 and string.char(byte) or string.char(192 + floor(byte / 64), 128 + byte % 64)
      end
      object.name = DATA.device_id_objects[object.id] or say("other_object", { id = object.id })
      object.value, object.offset, object.length, object.value_at = concat(chars), at - 2, 2 + size, nil
    end
    f.objects = objects
    -- (a count the frame does not hold: the objects there are shown, decode/fields.py)
    local declared = f.fields.body.object_count
    if #objects < declared then warn(f, say("object_count", { count = declared, present = #objects })) end
  end,
  report_server_id_response = function(f, b)
    -- (the tree shows its fields from the layout, tree.lua add_pdu)
    local run, names = f.fields.run_indicator, DATA.names.run_indicator
    if names[run] == nil and not run_indicator_after(b, f.data_at + 2, f.data_at + f.fields.byte_count, names) then
      warn(f, say("run_indicator", { value = run })) -- (OFF, ON: none where any length of server id puts it)
    end
  end,
}

-- Per direction and code: the parser of its layout (GRAMMARS), its lifting rule (LIFT_OF; nil: none or a
-- named special case) and its handler (H): the generic lifter where the table has a rule, else the special case.
local GRAMMARS, LIFT_OF, H = {}, {}, {}
for kind, codes in pairs({ [REQUEST] = RULES.by_code.request, [RESPONSE] = RULES.by_code.response }) do
  GRAMMARS[kind], LIFT_OF[kind], H[kind] = {}, {}, {}
  for code, entry in pairs(codes) do
    local rule = RULES.lift[entry.rule]
    GRAMMARS[kind][code], LIFT_OF[kind][code] = PARSERS[entry.layout], rule
    H[kind][code] = rule and lifter(rule, entry.limit, entry.layout) or SPECIAL[entry.special]
  end
end

-- Register writes by how they are confirmed (data/modbus.toml [confirm]; annotator.py _BY_ECHO, _BY_ANSWER):
-- by their echo (FC6), by a normal answer (FC16, FC23).
local CONFIRMED = RULES.confirmed

local function decode_frame(f)
  local b, d, len = f.b, f.data_at, f.data_len
  if f.slave > MAX_SLAVE then warn(f, say("reserved_slave", { slave = f.slave })) end
  if f.kind == EXCEPTION then
    f.fields = {}
    f.exception_code = b[d]
    if EXCEPTIONS[f.exception_code] == nil then
      warn(f, say("unknown_exception", { code = f.exception_code }))
    end
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
  if used < len then warn(f, say("trailing", { count = len - used })) end
  if f.broadcast and NOT_BROADCAST[f.fn] then
    warn(f, say("not_broadcast", { ["function"] = function_name(f.fn) }))
  end
end
