-- vw3.explain: device checks of requests, exceptions explained, device objects and diagnostics.
-- Mirrors dissector/devices/checks.py, dissector/devices/explain.py, dissector/devices/objects.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.explain"]).

-- Each quantity request f's lifting rule checks (FC23: read and write, as the spec's checks name them; without
-- its fields, as vw3_modbus.lua remembers a request, its quantity) with the device's limit for it (nil: none):
-- judge(f, profile, what, quantity, limit) until one returns true.
local function quantities(f, profile, limits, judge)
  local rule = LIFT_OF[REQUEST][f.fn]
  if rule == nil or rule.write_window == nil or f.fields == nil then
    return judge(f, profile, "quantity", f.quantity, limits[1])
  end
  for index, check in ipairs(rule.checks) do
    if judge(f, profile, check.what, f.fields[check.field], limits[index]) then return true end
  end
  return false
end

-- A quantity above the device's limit for the function (limit: nil when the device gives none). (Here a
-- function is named as its frame shows it: f.function_text, the profile's name annotate_with set, or the spec's.)
local function check_limit(f, profile, what, quantity, limit)
  if limit ~= nil and quantity ~= nil and quantity > limit then
    warn(f, say("device_limit", { what = what, quantity = quantity, device = profile.device, limit = limit,
      name = f.function_text or function_name(f.fn) }))
  end
end

local function check_request(f, device)
  local profile = device.profile
  local code = f.fn
  local refused = profile.functions ~= nil and not profile.functions[code] and "not_supported"
    or profile.inner_only[code] and "inner_only"
  local sub = f.subfunction
  if refused then
    warn(f, say(refused, { name = f.function_text or function_name(code), ["function"] = code, device = profile.device }))
  elseif sub ~= nil and profile.subfunctions ~= nil and DATA.diagnostics[sub] ~= nil and not profile.subfunctions[sub] then
    warn(f, say("subfunction_not_supported", { subfunction = sub, name = DATA.diagnostics[sub], device = profile.device }))
  end
  local limits = profile.limits[code]
  if limits ~= nil then quantities(f, profile, limits, check_limit) end
  -- (decode_frame already warned where the spec's own rule forbids the broadcast)
  if f.broadcast and profile.broadcast ~= nil and not profile.broadcast[code] and not NOT_BROADCAST[code] then
    warn(f, say("device_broadcast", { name = f.function_text or function_name(code), device = profile.device,
      allowed = profile.broadcast_allowed }))
  end
end

-- The read-only parameters (map access R: row.read_only) a write request touches, named `ETA (3201)`
-- (access.written_read_only): FC6, FC16, FC23 by the registers written (a run), FC22 by its address.
local REGISTER_WRITES, MASK_WRITTEN = DATA.rules.confirmed, DATA.rules.by_confirm.mask
local READ_ONLY = DATA.map_format.read_only -- the access of a parameter no write changes (devices/access.py)
local NONE = {} -- (read only, never changed: a device without a read-only row has none to name)
local function written_read_only(f, device)
  if not device.read_only then return NONE end -- (no list of the addresses written made for nothing)
  local rows, named, code, addresses = rows_for(device, f.fn), {}, f.fn, {}
  local run = f.registers
  if REGISTER_WRITES.echo[code] or REGISTER_WRITES.answer[code] then
    if run ~= nil and run.start ~= nil and run.count ~= nil then
      for index = 0, run.count - 1 do addresses[#addresses + 1] = (run.start + index) % 0x10000 end
    end
  elseif MASK_WRITTEN[code] and f.start ~= nil then
    addresses[1] = f.start
  end
  local labels = frame_labels(device, f) -- (a PLC-style device's reference, as the frame shows it: `SPD (40101)`)
  for _, address in ipairs(addresses) do
    local row = rows[address]
    if row ~= nil and row.read_only then
      named[#named + 1] = address_name(row, address, labels and labels[address])
    end
  end
  return named
end

-- A write request's read-only parameters, one warning each (access.check_writes).
local function check_writes(f, device)
  for _, parameter in ipairs(written_read_only(f, device)) do
    warn(f, say("read_only", { parameter = parameter, access = READ_ONLY }))
  end
end

local function outside(_, _, _, quantity, limit)
  return limit ~= nil and quantity ~= nil and not (quantity >= 1 and quantity <= limit)
end

local function holds(when, request, profile)
  local fields = request.fields
  if when == "quantity" then
    -- Every quantity the request's lifting rule checks (as check_request warns of them) outside the device's
    -- limit for it (without one, a read's READ_LIMIT): explain._holds
    return quantities(request, profile, profile.limits[request.fn] or { READ_LIMIT }, outside)
  end
  return when == "byte_count" and fields ~= nil and fields.byte_count ~= nil and fields.quantity ~= nil
    and fields.byte_count ~= 2 * fields.quantity
end

local function pick_causes(request, profile, causes)
  if request == nil then return causes end
  local hits, plain = {}, {}
  for _, cause in ipairs(causes) do
    if cause.when ~= nil and holds(cause.when, request, profile) then hits[#hits + 1] = cause end
    if cause.when == nil then plain[#plain + 1] = cause end
  end
  return #hits > 0 and hits or #plain > 0 and plain or causes
end

-- An error with the relay counters it increments (explain.counted).
local function counted(error, counters)
  if #counters == 0 then return error end
  return say(#counters > 1 and "cause_counters" or "cause_counter", { error = error,
    counters = concat(counters, " and ") })
end

-- The note of an exception refusing a write of read-only parameters, with the counters the device's causes
-- of the code to the function increment (explain._read_only_note).
local function read_only_note(f, profile, refused, causes)
  local counters, seen = {}, {}
  for _, cause in ipairs(causes and pick_causes(trusted_request(f), profile, causes) or {}) do
    for _, counter in ipairs(cause.counters) do
      if not seen[counter] then counters[#counters + 1], seen[counter] = counter, true end
    end
  end
  local refusal = say("read_only_refusal", { parameters = concat(refused, ", "), access = READ_ONLY })
  return say("exception_meaning", { code = f.exception_code, device = profile.device,
    meaning = counted(refusal, counters) })
end

-- The registers of a read every parameter of which an exception 02 says non-existent or protected
-- (explain._all_unreadable): each address with its row, label and that status, no value.
local function refused_registers(device, request)
  local labels, out = frame_labels(device, request), {}
  for index = 0, math.min(request.quantity, READ_LIMIT) - 1 do
    local address = (request.start + index) % 0x10000
    local row = rows_for(device, request.fn)[address]
    out[index + 1] = { address = address, row = row, status = row == nil and "non-existent" or "protected",
      label = labels and labels[address] or nil }
  end
  return out
end

-- Addresses in a row that are both unmapped (a run of non-existent parameters, told as one range).
local function both_unmapped(a, b) return a.row == nil and b.row == nil and consecutive(a, b) end

local function all_unreadable(f, device)
  -- One note: the device meaning with the parameters of the read (neighbouring unmapped addresses as
  -- a range), then each parameter's story (devices/explain.py).
  local entries = refused_registers(device, f.request)
  local parameters = runs_told(entries, both_unmapped, function(entry)
    return address_name(entry.row, entry.address, entry.label) .. " " .. entry.status
  end, function(run) return say("unmapped_run", { span = span_name(run), count = #run }) end)
  note(f, say("all_unreadable", { code = f.exception_code, device = device.profile.device, parameters = parameters }))
  local now = say("unreadable_now", { code = f.exception_code })
  for _, entry in ipairs(entries) do
    track(device.seen, f, entry.address, entry.row, 0, entry.status, now, entry.label)
  end
end

local function explain_exception(f, device)
  local profile = device.profile
  local code = f.exception_code
  if code == nil then return end
  local name = f.function_text or function_name(f.fn)
  local causes = profile.exception_causes[f.fn * 256 + code]
  local meanings = profile.exceptions
  -- (to a read of registers its all_protected_exception says p.38's clause too: explain.device_meaning)
  local read = READS[f.fn] ~= nil and code == profile.all_protected_exception
  f.exception_meaning = read and profile.all_protected_read or meanings[code]
  local request = trusted_request(f) -- (one that failed its check refused what the tap did not see)
  local refused = code == DATA.read_only_exception and request ~= nil and written_read_only(request, device)
  if refused and #refused > 0 then -- (a write of read-only parameters: named rather than the code's meaning)
    f.exception_meaning = say("read_only_meaning", { access = READ_ONLY })
    note(f, read_only_note(f, profile, refused, causes))
  elseif causes ~= nil and #causes > 0 then
    local texts = {}
    for _, cause in ipairs(pick_causes(request, profile, causes)) do texts[#texts + 1] = cause.text end
    -- (the meaning is the causes the request picks, as the note: explain.exception_meaning)
    f.exception_meaning = concat(texts, " or ")
    note(f, say("exception_cause", { code = code, device = profile.device, name = name,
      causes = f.exception_meaning }))
  -- (a frame that failed its check tells nothing of the parameters, devices/memory.py: only the code's meaning)
  elseif code == profile.all_protected_exception and PLAIN_READS[f.fn] and request ~= nil and verified(f)
      and request.start ~= nil and request.quantity ~= nil and request.quantity > 0 then
    all_unreadable(f, device)
    story.tell(f)
    -- The registers of the refused read, with the status this tells and no value (the display lists
    -- them from the request and the device: inferred_registers), as vw3-decode lists them.
    f.inferred = true
  elseif meanings[code] ~= nil then
    note(f, say("exception_meaning", { code = code, device = profile.device, meaning = f.exception_meaning }))
  elseif next(meanings) ~= nil then
    note(f, say("exception_undocumented", { code = code, device = profile.device, known = profile.documented }))
  end
end

local function explain_objects(f, profile)
  for _, object in ipairs(f.objects) do
    local meaning, value = profile.objects[object.id], object.value
    local size = object.length - 2 -- (its id and length byte, then the bytes sent)
    if meaning ~= nil and meaning.max_length ~= nil and size > meaning.max_length then
      warn(f, say("object_length", { object = object.name, length = size, device = profile.device,
        limit = meaning.max_length }))
    end
    if meaning ~= nil and meaning.format == "MMmm" and value:match("^%d%d%d%d$") then -- (a revision, V5.2)
      object.text = format("V%d.%d", tonumber(value:sub(1, 2)), tonumber(value:sub(3, 4)))
    elseif meaning ~= nil then
      if meaning.format == "MMmm" then
        note(f, say("revision_form", { object = object.name, value = value, device = profile.device }))
      end
      object.text = meaning.meaning
    end
  end
end

local function diagnostics_note(f, device, b)
  local profile = device.profile
  local sub = f.subfunction
  local meaning = profile.diagnostics[sub]
  if meaning == nil then return end
  f.subfunction_text = meaning
  local text = say("subfunction_meaning", { subfunction = sub, device = profile.device, meaning = meaning })
  if f.kind == RESPONSE and f.fields ~= nil and f.fields.data_length == 2 then
    local value = u16(b, f.data_at + 2)
    text = text .. say("subfunction_value", { value = value })
    local constant = profile.diagnostic_constants[sub]
    if constant ~= nil and value ~= constant then
      warn(f, say("diagnostic_constant",
        { subfunction = sub, device = profile.device, constant = constant, value = value }))
    end
  end
  note(f, text)
end

-- naming.window_label: `40501..40504`, one label for a quantity of 0, 1 or none; the last address past 65535
-- as asked.
local function window_label(labels, start, quantity)
  if quantity == nil or quantity <= 1 then return labels[start] end
  return labels[start] .. ".." .. labels[start + quantity - 1]
end

local function span_label(f, device)
  -- `40501..40504` for a PLC-style device, so requests without registers show 4X numbers too; FC23's request
  -- its written window too (annotator._span_label: `write 40006 (0)` where it writes none).
  local labels = frame_labels(device, f)
  f.span_label = window_label(labels, f.start, f.quantity)
  local rule, fields = LIFT_OF[REQUEST][f.fn], f.fields
  if f.kind == REQUEST and rule ~= nil and rule.write_window ~= nil and fields ~= nil then
    local window = rule.write_window
    f.write_span_label = window_label(labels, fields[window[1]], fields[window[2]])
  end
end
lane.span_label = span_label
