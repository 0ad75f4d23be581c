-- vw3.device: a slave's device: its profile, rows, PLC labels; values interpreted by the map.
-- Mirrors dissector/devices/build.py, dissector/devices/maps.py (interpret).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.device"]).

-- naming.plc_label: `40001 + address` up to 49999, then 6-digit references (`400001 + address`); coil
-- references keep their zeros (00001). PLC_LABELS[base][address], each label made once (at most 65,536
-- a base: addresses are 16 bits).
local PLC_LABELS = made_once(function(base)
  return made_once(function(address)
    local digits = math.max(5, #format("%d", base))
    local power = 10 ^ (digits - 1)
    local number = base + address
    if number > (floor(base / power) + 1) * power - 1 then
      number, digits = base * 10 - 9 + address, digits + 1
    end
    return format("%0" .. digits .. "d", number)
  end)
end)

local function address_name(row, address, label)
  local shown = label or format("%d", address)
  return row and format("%s (%s)", row.code, shown) or shown
end

-- Neighbouring addresses told as ranges (devices/story.py, explain.py): entries (.address, .row, .label)
-- in runs, an entry joining the run before it where joins(last of the run, entry) holds, each run told as
-- alone(its entry) or, of several, many(run); the texts joined by `, `.
local function runs_told(entries, joins, alone, many)
  local runs, run = {}, nil
  for _, entry in ipairs(entries) do
    if run ~= nil and joins(run[#run], entry) then
      run[#run + 1] = entry
    else
      run = { entry }
      runs[#runs + 1] = run
    end
  end
  for index, each in ipairs(runs) do runs[index] = #each == 1 and alone(each[1]) or many(each) end
  return concat(runs, ", ")
end

local function consecutive(a, b) return b.address == a.address + 1 end

-- A run of several addresses as `first..last`.
local function span_name(run)
  local a, b = run[1], run[#run]
  return (a.label or format("%d", a.address)) .. ".." .. (b.label or format("%d", b.address))
end

-- A shallow copy of a table.
local function copied(t)
  local copy = {}
  for key, value in pairs(t) do copy[key] = value end
  return copy
end

-- maps.overlay: `rows` with a layer's rows `mine` laid over it, in place (a layer row hides every row it
-- overlaps, a 32-bit row's two registers counted).
local function overlay(rows, mine)
  for address, row in pairs(mine) do
    local before = rows[address - 1]
    if before ~= nil and before.words == 2 and mine[address - 1] == nil then rows[address - 1] = nil end
    if row.words == 2 and mine[address + 1] == nil then rows[address + 1] = nil end
  end
  for address, row in pairs(mine) do rows[address] = row end
end

-- A profile's map with the map layers given at run time laid over it, those for which applies(layer); and
-- the rows of its input registers apart (DeviceBuilder.build: a layer in PLC references with 3X rows on a
-- device whose FC4 reads a table of its own), nil when the rows name them too. Where FC4 reads the holding
-- registers (profile one_table, the ATV71), a layer's 3X rows join its 4X rows, a 4X row winning.
local function layered_rows(profile, applies)
  if #config.layers == 0 then return profile.map or {}, nil end
  local rows, inputs, split = copied(profile.map or {}), copied(profile.map or {}), false
  for _, layer in ipairs(config.layers) do
    if applies(layer) then
      local extra = layer.inputs
      if extra ~= nil and profile.one_table then
        overlay(rows, extra)
        overlay(rows, layer.rows)
      else
        overlay(rows, layer.rows)
        overlay(inputs, extra or layer.rows)
        split = split or extra ~= nil
      end
    end
  end
  return rows, split and inputs or nil
end

-- The rows naming the registers a function code reads or writes (Device.rows_for): its table's.
local INPUT_FUNCTIONS = DATA.map_format.input_functions
local function rows_for(device, fn)
  if device.inputs ~= nil and INPUT_FUNCTIONS[fn] then return device.inputs end
  return device.rows
end

-- A map written in PLC references (maps_refs.py, message for message): judged on a slave's first
-- REFERENCES_JUDGED frames with registers (maps_refs.JUDGED); the layers that apply to the slave and could name
-- a register at a reference base past its address (FC3's or FC4's base, or one less), nil when none does.
local REFERENCES_JUDGED = DATA.map_format.references_judged
local function reference_base(profile, fn) return (profile.plc_base or {})[fn] or profile.plc_base_default end

local function reference_check(profile, slave)
  local low = math.min(reference_base(profile, 3), reference_base(profile, 4)) - 1
  local layers = {}
  for _, layer in ipairs(config.layers) do
    if layer.high >= low and (layer.slave == nil or layer.slave == slave)
        and (layer.profile == nil or layer.profile == profile.name) then
      layers[#layers + 1] = { layer = layer, own = {}, unnamed = {}, shifted = { {}, {} }, counts = {
        own = 0, unnamed = 0, 0, 0 } }
    end
  end
  if #layers == 0 then return nil end
  return { frames = 0, layers = layers, left = #layers }
end

-- The 32-bit row whose second register `address` is (naming.wide_before), or false.
local function rows_before(rows, address)
  local before = rows[(address + 0xFFFF) % 0x10000]
  return before ~= nil and before.words == 2 and before
end

-- maps_refs.names: a map names this register, a row of its own or a 32-bit row's second word.
local function map_names(rows, address) return rows[address] ~= nil or rows_before(rows, address) ~= false end

-- maps_refs.offsets_text: `40001`, `40001 or 30001` (integers: the profiles' bases less 0 or 1).
local function offsets_text(offsets)
  local list = {}
  for offset in pairs(offsets) do list[#list + 1] = offset end
  table.sort(list, function(a, b) return a > b end)
  return concat(list, " or ")
end

-- maps_refs.reference_note: the variant (the base itself, 1; one less, 2) naming most registers no map
-- names, when it names more of them than the layer names at their own address.
local function reference_note(judged, slave)
  local counts = judged.counts
  local best = counts[2] > counts[1] and 2 or 1
  if counts[best] == 0 or counts[best] <= counts.own then return nil end
  local offsets = {}
  for _, offset in pairs(judged.shifted[best]) do offsets[offset] = true end
  local offset = offsets_text(offsets)
  -- (the references themselves, not one less, in a map without a `reference` column: that column reads them)
  local column = (best == 1 and not judged.layer.references) and fill(MESSAGES.references_column, {}) or ""
  return fill(MESSAGES.references, { map = judged.layer.name, unnamed = counts.unnamed, slave = slave,
    shifted = counts[best], offset = offset, column = column }, python_repr)
end

-- A frame annotated by take_frame: counted while the slave's device judges (maps_refs.ReferenceCheck.observe),
-- the deciding frame noted. Distinct registers by (reference base, address), as the Python check counts them.
local function check_references(f, device)
  local refs = device and device.refs
  local registers = f.registers
  if refs == nil or not device.refs_open or registers == nil or registers.count == 0 or f.slave == 0
      or f.provisional or not verified(f) then
    return
  end
  refs.frames = refs.frames + 1
  if refs.frames >= REFERENCES_JUDGED then device.refs_open = false end
  local base = reference_base(device.profile, f.fn)
  local rows, start = rows_for(device, f.fn), registers.start
  for _, judged in ipairs(refs.layers) do
    if not judged.done and start ~= nil then
      local mine, counts = judged.layer.rows, judged.counts
      if judged.layer.inputs ~= nil and rows == device.inputs then mine = judged.layer.inputs end
      for index = 0, registers.count - 1 do
        local address = (start + index) % 0x10000
        local key = base * 65536 + address
        if map_names(mine, address) then
          if not judged.own[key] then judged.own[key], counts.own = true, counts.own + 1 end
        elseif not map_names(rows, address) then
          if not judged.unnamed[key] then judged.unnamed[key], counts.unnamed = true, counts.unnamed + 1 end
          for variant = 1, 2 do
            local offset = base - variant + 1
            local shifted = judged.shifted[variant]
            if address + offset <= 0xFFFF and shifted[key] == nil and map_names(mine, address + offset) then
              shifted[key], counts[variant] = offset, counts[variant] + 1
            end
          end
        end
      end
      local said = reference_note(judged, f.slave)
      if said ~= nil then
        note(f, said)
        judged.done, refs.left = true, refs.left - 1
        if refs.left == 0 then device.refs_open = false end
      end
    end
  end
end

-- The device of a slave under a profile: merged map, bits_depend rules, address style, and its own
-- parameter memory (a new profile for a slave starts a new memory, as the annotator builds a new Device).
local function build_device(profile, slave)
  local rows, inputs = layered_rows(profile, function(layer)
    return (layer.slave == nil or layer.slave == slave) and (layer.profile == nil or layer.profile == profile.name)
  end)
  local depend, plain = {}, {}
  for _, rule in ipairs(profile.bits_depend or {}) do
    for _, address in ipairs(rule.registers) do
      local row = rows[address]
      if row ~= nil then
        depend[address] = rule
        plain[address] = copied(row)
        plain[address].bits = nil
      end
    end
  end
  local style = config.style or profile.address_style
  local device = { profile = profile, rows = rows, depend = depend, plain = plain, plc_default = profile.plc_base_default,
    seen = {}, inputs = inputs }
  -- Parameters are followed only where it tells something: protection, or bits that depend on a value.
  device.track = profile.protected_value ~= nil or next(depend) ~= nil
  if style == "plc" then device.plc = profile.plc_base or {} end
  -- (a write is checked against the map's read-only rows only where it has one, access.written_read_only)
  for _, row in pairs(rows) do
    if row.read_only then device.read_only = true break end
  end
  device.refs = reference_check(profile, slave)
  device.refs_open = device.refs ~= nil -- (the quick lanes leave its frames to take_frame while it judges)
  return device
end

local function device_for(st, slave)
  local device = st.devices[slave]
  if device ~= nil then return device end
  -- The profile the slave has now (annotator.py profile_for): forced per slave, chosen by `auto` (only
  -- auto chooses: select_device), or the default (auto: the fallback).
  local name = config.per_slave[slave] or (st.chosen and st.chosen[slave]) or config.default
  local profile = PROFILES[name == AUTO and SELECTION.fallback or name]
  device = profile ~= nil and build_device(profile, slave) or false
  st.devices[slave] = device
  return device
end

-- The device a frame was annotated with: a slave's device changes only when `auto` chooses (rarely), so
-- the changes are kept per slave, { item number from which on, device, reason }, rather than a key per
-- frame. Second value: why `auto` gave the slave that device (Frame.profile_choice), nil before a choice.
local function device_of(st, f)
  local history = st.history and st.history[f.slave]
  if history ~= nil then
    for k = #history, 1, -1 do
      if history[k].number <= f.number then return history[k].device, history[k].reason end
    end
  end
  return device_for(st, f.slave)
end

local function has_note(f, text)
  for _, existing in ipairs(f.notes or NO_INTERPRETATION) do
    if existing == text then return true end
  end
  return false
end

local FIXED = made_once(function(decimals) return "%." .. decimals .. "f" end)

-- A value times its row's scale (none: 1), rounded to the decimals the scale was written with, and its text
-- (unit and all).
local function scaled_value(row, value)
  local decimals = row.decimals or 0
  local text = format(FIXED[decimals], value * (row.scale or 1))
  local scaled = tonumber(text)
  if decimals == 0 then scaled = floor(scaled + 0.5) end
  if row.unit ~= nil then text = text .. " " .. row.unit end
  return scaled, text
end

local BIT_NAMES, NO_BIT_SET = DATA.bit_names, DATA.plain_texts.no_bit_set -- (maps.py's texts, filled in)

-- maps.interpret: the scaled value and its display text.
local function interpret(row, value)
  local raw_value = value
  if row.signed and value >= 0x8000 then raw_value = value - 0x10000 end
  if row.enum then return nil, row.enum[value] or say("not_listed", { value = value }) end
  if row.bits then
    local names, bits, rest = {}, row.bits, value
    for bit_ = 0, 15 do
      if rest % 2 == 1 then
        names[#names + 1] = bits[bit_] or BIT_NAMES[bit_]
        rest = rest - 1
      end
      rest = rest / 2
    end
    return nil, #names == 0 and NO_BIT_SET or concat(names, ", ")
  end
  if row.scale_unknown then
    -- the device's settings choose the scale (ACC/DEC: the ramp increment): the raw value, and the unit it
    -- counts in unscaled
    return row.signed and raw_value or nil, say("unscaled", { value = raw_value, unit = row.unit })
  end
  -- (no scale, no unit, unsigned: the word itself; else a number, in its unit where it has one)
  if row.scale == nil and row.unit == nil and not row.signed then return nil, nil end
  return scaled_value(row, raw_value)
end

-- maps._shortest: the fewest significant digits (1 to 9) of `value` nearer to it than half the gap to a
-- neighbour (`spacing` away from zero, `below` toward it; exactly half way, the `even` one takes it), as %.7g
-- writes them. maps.float32_text: a float32 times its scale, the gaps scaled alike.
local function shortest(value, spacing, below, even)
  for digits = 1, 8 do
    local text = format("%." .. digits .. "g", value)
    local gap = math.abs(tonumber(text)) - math.abs(value)
    local half = (gap < 0 and below or spacing) / 2
    if math.abs(gap) < half or (math.abs(gap) == half and even) then
      if value == 0 then return text end -- (Lua 5.4 reads "-0" as the integer 0)
      return format("%." .. math.max(digits, 7) .. "g", tonumber(text)) -- (the same digits: 50, not 5e+01)
    end
  end
  return format("%.9g", value) -- (9 digits always tell a float32 from its neighbours)
end

-- maps.interpret_wide: a 32-bit value from the words of its two registers, in the order they come.
local function interpret_wide(row, first, second)
  local high, low = first, second
  if row.swapped then high, low = second, first end
  local value, text
  if row.kind == "float32" then
    -- IEEE 754 single precision, from its fields (no bitwise operators in Lua 5.2); the sign a float: Lua
    -- 5.4's integer -1 * 0 would lose the sign of -0.0
    local sign = high >= 0x8000 and -1.0 or 1.0
    local exponent = floor(high / 128) % 256
    local fraction = (high % 128) * 65536 + low
    local spacing = 2 ^ -149
    if exponent == 255 then -- (no number JSON can hold)
      return nil, fraction ~= 0 and "nan" or sign > 0 and "inf" or "-inf"
    elseif exponent == 0 then
      value = sign * fraction * spacing
    else
      spacing = 2 ^ (exponent - 150)
      value = sign * (8388608 + fraction) * spacing
    end
    -- (a float has no fixed decimals: the scale multiplies; the product written as the float is, and its
    -- value as the text says it)
    local below = (fraction == 0 and exponent > 1) and spacing / 2 or spacing
    local scale = row.scale or 1.0
    local size = math.abs(scale)
    text = shortest(value * scale, spacing * size, below * size, low % 2 == 0)
    if row.scale ~= nil then value = tonumber(text) + 0.0 end
  else
    value = high * 65536 + low
    if row.kind == "int32" and high >= 0x8000 then value = value - 4294967296 end
  end
  if text == nil then return scaled_value(row, value) end
  if row.unit ~= nil then text = text .. " " .. row.unit end
  return value, text
end
