-- Usage: lua5.2|lua5.4 conformance.lua PLUGIN VECTORS
-- The plugin's modules that need no Wireshark (loaded from the assembled lua/vw3.lua outside Wireshark)
-- against what the Python reference gives at each stage (tests/conformance/vectors.lua, written by
-- tests/conformance/generate.py): framing, pairing, decoding, profile selection, annotation, map reading, repr.
-- Prints one line a difference and `N cases, M checks, K differences`; exits 1 on any difference.
local plugin, vectors_path = arg[1], arg[2]
local vw3 = dofile(plugin)
local M = package.loaded["vw3.env"] -- every module's exports
local V = dofile(vectors_path)
local format, concat = string.format, table.concat

local checks, differences = 0, {}

local function show(value)
  if type(value) == "table" then
    local keys = {}
    for key in pairs(value) do keys[#keys + 1] = key end
    table.sort(keys, function(a, b) return tostring(a) < tostring(b) end)
    local parts = {}
    for _, key in ipairs(keys) do parts[#parts + 1] = tostring(key) .. "=" .. show(value[key]) end
    return "{" .. concat(parts, ",") .. "}"
  end
  if type(value) == "string" then return format("%q", value) end
  return tostring(value)
end

local function same(a, b)
  if type(a) ~= type(b) then return false end
  if type(a) ~= "table" then return a == b end
  for key, value in pairs(a) do
    if not same(value, b[key]) then return false end
  end
  for key in pairs(b) do
    if a[key] == nil then return false end
  end
  return true
end

local function check(where, got, want)
  checks = checks + 1
  if not same(got, want) then
    differences[#differences + 1] = format("%s: plugin %s, Python %s", where, show(got), show(want))
  end
end

local function bytes_of(hex)
  return (hex:gsub("%x%x", function(pair) return string.char(tonumber(pair, 16)) end))
end

local function hex_of(t, first, count)
  local parts = {}
  for k = first, first + count - 1 do parts[#parts + 1] = format("%02x", t[k]) end
  return concat(parts)
end

local function list(t) return t or {} end

-- A decoder's warnings as compared: word for word, a malformed PDU's too (protocol/grammar.py shortfall says
-- what the plugin's readers say).
local function warnings(texts) return texts or {} end

-- The framer's items for the whole input, fed in one piece then finished (generate.py _framing).
local function framed(case)
  local st = M.new_state(nil, case.mode)
  local bytes = bytes_of(case.input)
  local items = {}
  -- (feed hands back one list a stream, emptied by the next feed: its items are copied out)
  for _, item in ipairs(M.feed(st, bytes, nil, false, false)) do items[#items + 1] = item end
  for _, item in ipairs(M.feed(st, "", nil, false, true)) do items[#items + 1] = item end
  return st, items
end

local function framing(case)
  local _, items = framed(case)
  local got = {}
  for index, item in ipairs(items) do
    if item.kind == M.NOISE then
      got[index] = { noise = hex_of(item.bytes, 1, item.length), reason = item.reason }
    else
      local raw = item.ascii and hex_of(item.src, item.src_at, item.length) or hex_of(item.b, item.bi, item.length)
      got[index] = { kind = item.kind, slave = item.slave, ["function"] = item.fn, raw = raw,
        crc_ok = item.crc == item.crc_expected, warnings = list(item.warnings) }
    end
  end
  check(case.name .. " framing", got, case.framing)
end

-- Paired as take_frame pairs (lua/src/pairing), numbered as take_items numbers; the request still awaited
-- at the end has what the display gives it at the second pass (lua/src/pairing ended: unanswered or not
-- known, its note).
local function paired(case)
  local st, items = framed(case)
  for index, item in ipairs(items) do
    item.number = index
    if item.kind ~= M.NOISE then M.pair(st, item) end
  end
  return st, items
end

local function pairing(case)
  local st, items = paired(case)
  local cut = nil
  for _, item in ipairs(items) do
    local reason, prefix = item.reason, M.FRAMING.cut_answer
    if reason ~= nil and reason:sub(1, #prefix) == prefix then cut = reason end
  end
  local got = {}
  for index, item in ipairs(items) do
    if item.kind == M.NOISE then
      got[index] = { number = index }
    else
      local notes = {}
      for _, text in ipairs(list(item.notes)) do notes[#notes + 1] = text end
      local unanswered = item.unanswered == true
      if item == st.pending then
        st.cut_note = cut
        local note
        unanswered, note = M.ended(st, item)
        notes[#notes + 1] = note
      end
      got[index] = { number = index, request = item.request and item.request.number, unanswered = unanswered,
        broadcast = item.broadcast == true, notes = notes }
    end
  end
  check(case.name .. " pairing", got, case.pairing)
end

local function run_list(run, b, at)
  if run == nil then return nil end
  local out = {}
  for index = 0, run.count - 1 do
    local address, value = at(run, b, index)
    out[index + 1] = { address, value }
  end
  return out
end

local function decoding(case)
  local _, items = paired(case)
  local got = {}
  for _, item in ipairs(items) do
    if item.kind ~= M.NOISE then
      M.decode_frame(item)
      local objects = nil
      if item.objects ~= nil then
        objects = {}
        for index, object in ipairs(item.objects) do objects[index] = { object.id, object.name, object.value } end
      end
      got[#got + 1] = { number = item.number, start = item.start, quantity = item.quantity,
        subfunction = item.subfunction, registers = run_list(item.registers, item.b, M.register_at),
        bits = run_list(item.bits, item.b, M.bit_at), objects = objects, warnings = warnings(item.warnings) }
    end
  end
  local want = {}
  for index, row in ipairs(case.decoding) do
    -- (the grammar's fields are Python's Construct containers: the plugin's are compared through what
    -- they give, start, quantity, registers, bits, objects and warnings)
    want[index] = { number = row.number, start = row.start, quantity = row.quantity, subfunction = row.subfunction,
      registers = row.registers, bits = row.bits, objects = row.objects, warnings = warnings(row.warnings) }
  end
  check(case.name .. " decoding", got, want)
end

-- The whole pipeline as Wireshark's first pass runs it (the input as one record), then the second
-- decoding with every slave's device fixed (lane.again), as vw3-decode reads a file.
local function pipeline(case)
  local st = M.new_state(nil, case.mode)
  st.again = { bytes = { [1] = bytes_of(case.input) }, times = { [1] = false } } -- (lane.again: in number order)
  st.records[1] = M.dissect_record(st, bytes_of(case.input), nil, 1)
  M.pack.settle(st)
  M.finish(st)
  local judged = st.judged
  local said = st.said
  M.lane.again(st)
  return st, judged, said
end

-- Every slave the decode met (but the broadcast address) with its choice, or none (Annotator.choices).
local function selection(case, st, judged, said)
  local got = {}
  for slave in pairs(st.devices) do
    local choice = judged and judged[slave] and judged[slave].choice
    if slave ~= 0 and choice ~= nil then
      local frame = nil
      for number, text in pairs(said or {}) do
        if text[2] == choice.reason and (frame == nil or number > frame) then frame = number end
      end
      got[#got + 1] = { slave = slave, profile = choice.profile, reason = choice.reason, frame = frame }
    elseif slave ~= 0 then
      got[#got + 1] = { slave = slave, profile = M.SELECTION.fallback,
        reason = "no evidence of a device: spec semantics only" }
    end
  end
  table.sort(got, function(a, b) return a.slave < b.slave end)
  check(case.name .. " selection", got, case.selection)
end

local function annotation(case, st)
  local got = {}
  local record = st.records[1]
  if type(record) == "number" then record = { record } end
  for _, packed in ipairs(record or {}) do
    local f = M.pack.expand(packed, st)
    if f.kind ~= M.NOISE then
      local b = f.ascii and nil or nil
      local registers = {}
      -- (the registers as the display lists them: register_view over the frame's bytes)
      local bytes = bytes_of(case.input)
      local frame_bytes = {}
      if f.ascii then
        for k = 0, math.floor((f.length - 3) / 2) - 1 do
          frame_bytes[k] = tonumber(bytes:sub(f.offset + 2 + 2 * k, f.offset + 3 + 2 * k), 16)
        end
      else
        for k = 0, f.length - 1 do frame_bytes[k] = bytes:byte(f.offset + 1 + k) end
      end
      local run = f.registers
      if run ~= nil and run.count ~= nil then
        for index = 0, run.count - 1 do
          local view = M.register_view(st, f, run, frame_bytes, index)
          local row = view.row or {}
          registers[#registers + 1] = { address = view.address, value = view.value, code = row.code, name = row.name,
            unit = row.unit, text = view.text, status = view.status, label = view.label, words = view.words or 1 }
        end
      elseif f.inferred then
        for _, reg in ipairs(M.inferred_registers(st, f)) do
          local row = reg.row or {}
          registers[#registers + 1] = { address = reg.address, code = row.code, name = row.name, unit = row.unit,
            text = reg.text, status = reg.status, label = reg.label, words = 1 }
        end
      end
      got[#got + 1] = { number = f.number, function_text = f.function_text, exception_text = f.exception_meaning,
        subfunction_text = f.subfunction_text, span_label = f.span_label, registers = registers,
        warnings = warnings(f.warnings) }
    end
  end
  local want = {}
  for index, row in ipairs(case.annotation) do
    -- (notes: the plugin adds those about pairing and the capture's end when it shows a frame)
    want[index] = { number = row.number, function_text = row.function_text, exception_text = row.exception_text,
      subfunction_text = row.subfunction_text, span_label = row.span_label, registers = row.registers,
      warnings = warnings(row.warnings) }
  end
  check(case.name .. " annotation", got, want)
end

local function maps(entry)
  local profile = M.PROFILES[entry.map]
  local got = {}
  for _, row in ipairs(entry.rows) do
    local mine = profile.map[row.address]
    checks = checks + 1
    if mine == nil then
      differences[#differences + 1] = format("map %s: %d missing", entry.map, row.address)
    else
      check(format("map %s %d", entry.map, row.address),
        { code = mine.code, name = mine.name, unit = mine.unit, scale = mine.scale, words = mine.words or 1,
          signed = mine.signed == true, swapped = mine.swapped == true },
        { code = row.code, name = row.name, unit = row.unit, scale = row.scale, words = row.words,
          signed = row.signed, swapped = row.swapped })
    end
    got[row.address] = true
  end
end

-- Map reading (maps.parse_map): a text's rows as the plugin keeps them (access is checked, not kept), or its
-- message word for word.
local function map_reading(entry)
  local text = entry.text or entry.hex:gsub("%x%x", function(hex) return string.char(tonumber(hex, 16)) end)
  local rows, problem = M.parse_map(text, "map.csv")
  local got = problem
  if rows ~= nil then
    got = {}
    local function keyed(labels)
      local out = {}
      for key, text in pairs(labels or {}) do out[format("%d", key)] = text end
      return out
    end
    -- (a map in references' 3X rows after its 4X rows, table "input": maps.ReferenceRows.inputs)
    local all = {}
    for address, row in pairs(rows) do all[#all + 1] = { address, row, nil } end
    for address, row in pairs(M.map_inputs(rows) or {}) do all[#all + 1] = { address, row, "input" } end
    for _, entry in ipairs(all) do
      local address, row = entry[1], entry[2]
      got[#got + 1] = { table = entry[3], address = address, code = row.code, name = row.name, unit = row.unit, scale = row.scale,
        decimals = row.decimals or 0, enum = keyed(row.enum), bits = keyed(row.bits), signed = row.signed == true,
        words = row.words or 1, type = row.kind, swapped = row.swapped == true, source = row.source,
        ambiguous_8000 = row.ambiguous_8000 == true }
    end
    table.sort(got, function(a, b)
      if (a.table ~= nil) ~= (b.table ~= nil) then return b.table ~= nil end
      return a.address < b.address
    end)
  end
  check("map reading " .. entry.name, got, entry.rows or entry.error)
end

vw3.configure("", "profile", "")
local only = arg[3] -- (a case's name: that case alone)
for _, case in ipairs(V.cases) do
  if only ~= nil and case.name ~= only then goto continue end
  if os.getenv("CONFORMANCE_TRACE") then io.stderr:write(case.name, "\n") end
  -- (a stage that fails is a difference too, and the next stages still run)
  local function stage(name, run, ...)
    local ok, problem = pcall(run, ...)
    if not ok then differences[#differences + 1] = format("%s %s: Lua error: %s", case.name, name, tostring(problem)) end
  end
  stage("framing", framing, case)
  stage("pairing", pairing, case)
  stage("decoding", decoding, case)
  local ok, st, judged, said = pcall(pipeline, case)
  if ok then
    stage("selection", selection, case, st, judged, said)
    stage("annotation", annotation, case, st)
  else
    differences[#differences + 1] = format("%s pipeline: Lua error: %s", case.name, tostring(st))
  end
  ::continue::
end
for _, entry in ipairs(V.maps or {}) do maps(entry) end
for _, entry in ipairs(V.map_reading or {}) do map_reading(entry) end
for _, entry in ipairs(V.repr or {}) do check("repr " .. show(entry.text), M.python_repr(entry.text), entry.repr) end

for _, line in ipairs(differences) do print(line) end
print(format("%s: %d cases, %d checks, %d differences", _VERSION, #V.cases, checks, #differences))
os.exit(#differences == 0 and 0 or 1)
