-- vw3_modbus.lua: names the registers of Wireshark's own Modbus dissection (Modbus/TCP to the same drives
-- behind an Ethernet card uses the same logic addresses; the unit id picks the profile as the slave does),
-- with the vw3.reg.* fields and the 16#8000 story of vw3.lua's device profiles.
--
-- Optional: copy it beside vw3.lua (it needs vw3.lua, loaded first: plugins load in name order), or load
-- both for one run: `tshark -X lua_script:vw3.lua -X lua_script:vw3_modbus.lua -r modbus-tcp.pcap`. It is
-- apart because its Modbus field extractors make Wireshark build a dissection tree for every packet of
-- every capture, which costs a serial capture about three times its dissection time.
-- Runs on Wireshark 4.0 (Lua 5.2) and 4.4+ (Lua 5.4), as vw3.lua.
local vw3 = package.loaded.vw3_plugin -- (each script has globals of its own)
if vw3 == nil then
  report_failure("vw3_modbus.lua needs vw3.lua, loaded before it (copy both into the plugins folder)")
  return
end
local format = string.format
local pf, ex = vw3.pf, vw3.ex
-- The RTU plugin's modules (package.loaded is shared): an exception is explained by its own functions.
local env = package.loaded["vw3.env"]
-- The codes whose echo confirms masks applied to the value held ([confirm] "mask": FC22).
local MASK_WRITES = env ~= nil and env.DATA.rules.by_confirm.mask or {}

if set_plugin_info then
  set_plugin_info({
    version = "1.0.0",
    description = "VW3 register names for Wireshark's Modbus/TCP dissection (needs vw3.lua)",
    repository = "vw3-dissector (lua/vw3_modbus.lua)",
  })
end

local names_proto = Proto("vw3names", "VW3 register names for Wireshark's Modbus dissection")
names_proto.prefs.enabled = Pref.bool("Name registers in Wireshark's Modbus dissection", true,
  "Add the register names, values and 16#8000 status of the device profiles to modbus packets")
-- Wireshark 4.0's fields; FC6 and FC23 carry no register numbers there (reference and modbus.data).
local modbus_fields = {}
for key, name in pairs({ code = "modbus.func_code", number = "modbus.regnum16", value = "modbus.regval_uint16",
  request = "modbus.request_frame", start = "modbus.reference_num", quantity = "modbus.word_cnt",
  exception = "modbus.exception_code", data = "modbus.data", read_start = "modbus.read_reference_num",
  read_quantity = "modbus.read_word_cnt", write_start = "modbus.write_reference_num",
  write_quantity = "modbus.write_word_cnt", unit = "mbtcp.unit_id", transaction = "mbtcp.trans_id",
  length = "mbtcp.len", and_mask = "modbus.and_mask", or_mask = "modbus.or_mask",
  bit_count = "modbus.bit_cnt", subfunction = "modbus.diagnostic_code" }) do
  local ok, field = pcall(Field.new, name)
  if ok then modbus_fields[key] = field end
end
-- The fields sorted to their ADU (a TCP segment may carry several, each its own unit and transaction).
local ADU_FIELDS = { "code", "number", "value", "request", "start", "quantity", "exception", "data", "read_start",
  "read_quantity", "write_start", "write_quantity", "unit", "and_mask", "or_mask", "bit_count",
  "subfunction" }
local floor = math.floor
local names_state = vw3.new_state(nil)
-- Requests not answered yet, by connection and transaction: Wireshark gives an exception no
-- modbus.request_frame, and an exception 02 to a read is told from the read (p.38); an FC23 answer's
-- registers are those of its request's read window, an FC16 or FC23 answer confirms the request's writes.
local asked, asked_count, ASKED_LIMIT = {}, 0, 4096

function names_proto.init()
  names_state = vw3.new_state(nil)
  asked, asked_count = {}, 0
end

local function first_value(list)
  local found = list and list[1]
  return found and found.value
end

-- The ADUs of a packet, in dissection order: each mbtcp.trans_id starts one, its MBAP length gives its
-- end. A field is its ADU's by data source and offset; the source is told by its length, or where two
-- ADUs of one length overlap (a reassembled ADU and the segment's own ones), by its first bytes too.
local function source_key(fi, strong)
  local source = fi.source
  if source == nil then return "" end
  if strong then return tostring(source) end
  return source:len()
end

local function split_adus()
  local transactions = modbus_fields.transaction and { modbus_fields.transaction() } or {}
  local lengths = modbus_fields.length and { modbus_fields.length() } or {}
  if #transactions == 0 or #transactions ~= #lengths then
    return { { all = true, transaction = first_value(transactions) } } -- (no MBAP: the packet is one)
  end
  local adus, strong, last_of = {}, false, {}
  for index, fi in ipairs(transactions) do
    local start = fi.offset
    local adu = { start = start, stop = start + 6 + lengths[index].value, key = source_key(fi, false),
      transaction = fi.value, fi = fi, fields = {} }
    local before = last_of[adu.key]
    if before ~= nil and start < before.stop then strong = true end -- (in one source, ADUs follow each other)
    last_of[adu.key] = adu
    adus[index] = adu
  end
  if strong then
    for _, adu in ipairs(adus) do adu.key = source_key(adu.fi, true) end
  end
  for _, key in ipairs(ADU_FIELDS) do
    local extractor = modbus_fields[key]
    local k = 1
    for _, fi in ipairs(extractor and { extractor() } or {}) do
      local offset, source = fi.offset, source_key(fi, strong)
      -- (fields come in dissection order, as the ADUs do: the search goes on from the last one's)
      for at = k, #adus do
        local adu = adus[at]
        if adu.key == source and offset >= adu.start and offset < adu.stop then
          local list = adu.fields[key] or {}
          list[#list + 1] = fi
          adu.fields[key], k = list, at
          break
        end
      end
    end
  end
  return adus
end

local function whole(key)
  local extractor = modbus_fields[key]
  return extractor and { extractor() } or nil
end

-- The ADU's fields of a kind (the whole packet's where it has no MBAP).
local function fields_of(adu, key)
  if adu.all then return whole(key) end
  return adu.fields[key]
end

-- The transaction an ADU is part of, from the client's side (to_server: the ADU is a request).
local function transaction_key(pinfo, to_server, transaction)
  local client, client_port, server, server_port = pinfo.dst, pinfo.dst_port, pinfo.src, pinfo.src_port
  if to_server then client, client_port, server, server_port = server, server_port, client, client_port end
  -- (tostring: a port may be absent, as under the test stub or a capture whose transport has none)
  return format("%s:%s>%s:%s#%s", tostring(client), tostring(client_port), tostring(server),
    tostring(server_port), tostring(transaction))
end

-- The field a request's written values are at most as many as (data/modbus.toml [lift] values' most:
-- quantity, write_quantity), nil for a code without one.
local function written_at_most(fn)
  local code = env ~= nil and env.DATA.rules.by_code.request[fn]
  local rule = code and code.rule and env.DATA.rules.lift[code.rule]
  return rule and rule.values and rule.values.most
end

-- The registers of an ADU as the RTU plugin's runs (start, count; first: where their values start in the
-- byte table b, its own) and b, their values' bytes: as Wireshark lists them (regnum16, regval: consecutive
-- from the first), or from modbus.data where Wireshark 4.0 lists none: FC6's reference, FC23's write window,
-- and an FC23 answer's read window from its request. nil: none.
local function registers_of(adu, fn, request)
  local numbers, values = fields_of(adu, "number"), fields_of(adu, "value")
  local start, count, b = nil, 0, {}
  if numbers ~= nil and values ~= nil and #numbers > 0 then
    start, count = numbers[1].value, math.min(#numbers, #values)
    local most = fields_of(adu, "request") == nil and written_at_most(fn)
    if most then -- (values past the quantity: no register written)
      count = math.min(count, first_value(fields_of(adu, most)) or count)
    end
    for index = 1, count do
      local value = values[index].value
      b[2 * index - 1], b[2 * index] = floor(value / 256), value % 256
    end
  else
    local data = fields_of(adu, "data")
    data = data and data[1]
    if data == nil then return nil end
    count = floor(data.len / 2)
    if fn == 6 then
      start, count = first_value(fields_of(adu, "start")), math.min(count, 1)
    elseif fn == 23 and fields_of(adu, "request") == nil then
      start, count = first_value(fields_of(adu, "write_start")), math.min(count,
        first_value(fields_of(adu, "write_quantity")) or 0)
    elseif fn == 23 and request ~= nil and request.fn == 23 then
      start, count = request.start, math.min(count, request.quantity or 0)
    end
    local bytes = data.range:bytes()
    for k = 0, 2 * count - 1 do b[k + 1] = bytes:get_index(k) end
  end
  if start == nil or count <= 0 then return nil end
  return { start = start, count = count, first = 1, b = b }, b
end

-- The value ranges of an ADU's registers, in order (a later pass: the names were made on the first).
local function ranges_of(adu)
  local ranges = {}
  local values = fields_of(adu, "value")
  if values ~= nil and #values > 0 then
    for index, value in ipairs(values) do ranges[index] = value.range end
    return ranges
  end
  local or_mask = fields_of(adu, "or_mask") -- (FC22's register: on its or mask, as the RTU plugin's)
  if or_mask ~= nil and #or_mask > 0 then return { or_mask[1].range } end
  local data = fields_of(adu, "data")
  data = data and data[1]
  if data == nil then return ranges end
  for index = 0, floor(data.len / 2) - 1 do ranges[index + 1] = data.range:range(2 * index, 2) end
  return ranges
end

-- A request (first pass): kept until its answer comes, as the RTU plugin pairs it: its window (FC23:
-- the read one) and the registers it writes (a run with its bytes, as the RTU plugin's request keeps them).
local function remember_request(pinfo, adu, fn, slave, registers)
  if asked_count >= ASKED_LIMIT then asked, asked_count = {}, 0 end -- (requests never answered: bounded)
  local start = first_value(fields_of(adu, "start")) or first_value(fields_of(adu, "read_start"))
  local quantity = first_value(fields_of(adu, "quantity")) or first_value(fields_of(adu, "read_quantity"))
  local request = { kind = vw3.REQUEST, fn = fn % 128, start = start, quantity = quantity, slave = slave,
    number = pinfo.number, registers = registers }
  asked[transaction_key(pinfo, true, adu.transaction)] = request
  asked_count = asked_count + 1
  return request
end

local function answered(pinfo, adu)
  local key = transaction_key(pinfo, false, adu.transaction)
  local request = asked[key]
  if request ~= nil then asked[key], asked_count = nil, asked_count - 1 end
  return request
end

-- An exception (first pass) explained as the RTU plugin explains it (explain_exception): the device's
-- meaning, or for an exception 02 to a read, the parameters of the read with the status it tells.
local function explain(pinfo, adu, fn, code, slave)
  local f = { slave = slave, fn = fn % 128, kind = env.EXCEPTION, exception_code = code,
    request = answered(pinfo, adu), notes = {}, warnings = {}, number = pinfo.number, unit_zero = true }
  local device = vw3.device_now(names_state, f)
  if not device then return false end
  env.explain_exception(f, device)
  local registers = f.inferred and env.inferred_registers(names_state, f) or {}
  return { registers = registers, notes = f.notes, device = device, slave = slave }
end

-- An FC22 echo's masks, as the RTU plugin's f.fields (lua/src/story.lua remember_mask), or nil.
local function masks_of(adu)
  local address = first_value(fields_of(adu, "start"))
  local and_mask, or_mask = first_value(fields_of(adu, "and_mask")), first_value(fields_of(adu, "or_mask"))
  if address == nil or and_mask == nil or or_mask == nil then return nil end
  return { address = address, and_mask = and_mask, or_mask = or_mask }
end

-- One ADU, first pass (in capture order: the protection story and profile auto follow it): what its
-- tree shows, or false. A request is remembered, an answer paired; the frame is annotated by the RTU
-- plugin's own path (lua/src/annotator.lua, annotate_with): a request checked against the device (a
-- function it lacks, a quantity past its limit, a read-only parameter written), the writes its answer or
-- echo confirms and an FC22 echo's masks remembered, the registers judged (16#8000).
local function name_adu(pinfo, adu)
  local fn = first_value(fields_of(adu, "code"))
  if fn == nil then return false end
  local slave = first_value(fields_of(adu, "unit")) or 0
  local code = first_value(fields_of(adu, "exception"))
  if code ~= nil then return explain(pinfo, adu, fn, code, slave) end
  local response = fields_of(adu, "request") ~= nil
  local request = response and answered(pinfo, adu) or nil
  local run, b = registers_of(adu, fn % 128, request)
  local f = { slave = slave, fn = fn % 128, kind = response and vw3.RESPONSE or vw3.REQUEST, registers = run,
    request = request, notes = {}, warnings = {}, number = pinfo.number, unit_zero = true }
  local masks = MASK_WRITES[f.fn] and masks_of(adu)
  if response then
    f.fields = masks or nil -- (an FC22 echo: the masks it confirms, as the RTU plugin's f.fields)
  else
    -- (what the request's checks read, as the RTU plugin's decoded fields: lua/src/explain.lua, check_request)
    remember_request(pinfo, adu, fn, slave, run)
    f.fields = {}
    for _, key in ipairs({ "quantity", "read_quantity", "write_quantity" }) do
      f.fields[key] = first_value(fields_of(adu, key))
    end
    f.quantity = f.fields.quantity or first_value(fields_of(adu, "bit_count"))
    f.subfunction, f.start = first_value(fields_of(adu, "subfunction")), first_value(fields_of(adu, "start"))
  end
  if masks then f.start = masks.address end -- (its PLC label, f.span_label, for FC22's register)
  -- (an answer of no registers, FC16's: only where it confirms writes, as an FC22 echo)
  local confirmed = response and request ~= nil and request.registers ~= nil and env.CONFIRMED.answer[f.fn]
  if run == nil and not (confirmed or masks or not response) then return false end
  local device = vw3.device_now(names_state, f, b)
  if not device then return false end
  env.annotate_with(names_state, f, b, device)
  env.check_references(f, device) -- (a map written in PLC references: the RTU plugin's take_frame says it too)
  if run == nil and not masks and #f.warnings == 0 then return false end
  return { f = f, b = b, masks = masks, notes = f.notes, warnings = f.warnings, device = device, slave = slave }
end

-- The registers a named ADU shows: an exception's inferred ones, or the run's as the RTU plugin's display
-- finds them again from the run and its bytes (register_view: row, text, status), or FC22's register.
local function shown_registers(named)
  if named.f == nil then return named.registers end
  local f, run, masks, out = named.f, named.f.registers, named.masks, {}
  for index = 0, (run and run.count or 0) - 1 do
    out[index + 1] = env.register_view(names_state, f, run, named.b, index)
  end
  if masks then out[#out + 1] = vw3.mask_register(masks.address, masks.and_mask, masks.or_mask, f.span_label) end
  return out
end

local function add_tree(tvb, tree, done, registers, whole_range)
  local warnings = done.warnings or {}
  if #registers == 0 and #done.notes == 0 and #warnings == 0 then return end
  local t = tree:add(names_proto, whole_range)
  t:set_text(format("VW3 register names (%s, unit %d)", done.device.profile.title, done.slave))
  local fake = { offset = 0, at = 0, bi = 0, length = tvb:len(), data_at = 2, data_len = 0 }
  for _, reg in ipairs(registers) do vw3.add_register(t, tvb, fake, reg, reg.range or whole_range) end
  for _, text in ipairs(warnings) do vw3.add_text(t:add(pf.warning, whole_range, text), ex.warning, text) end
  for _, text in ipairs(done.notes) do vw3.add_text(t:add(pf.note, whole_range, text), ex.note, text) end
end

function names_proto.dissector(tvb, pinfo, tree)
  -- Every packet comes here: the cheapest test first (no Modbus PDU, no table made).
  if modbus_fields.code == nil or modbus_fields.code() == nil then return end
  if not names_proto.prefs.enabled or env == nil or tvb:len() == 0 then return end
  local adus = split_adus()
  local done = names_state.records[pinfo.number]
  if done == nil then -- (once, in capture order)
    done = {}
    for index, adu in ipairs(adus) do done[index] = name_adu(pinfo, adu) end
    names_state.records[pinfo.number] = done
  end
  for index, adu in ipairs(adus) do
    local named = done[index]
    if named then
      -- (the ranges are this dissection's: a later pass shows the names made on the first)
      local ranges, registers = ranges_of(adu), shown_registers(named)
      for at, reg in ipairs(registers) do reg.range = ranges[at] end
      local whole_range = tvb:range(0, tvb:len())
      if adu.fi ~= nil then
        local source = adu.fi.source
        whole_range = source:range(adu.start, math.min(adu.stop, source:len()) - adu.start)
      end
      add_tree(tvb, tree, named, registers, whole_range)
    end
  end
end
register_postdissector(names_proto)
