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
local modbus_fields = {}
for key, name in pairs({ unit = "mbtcp.unit_id", code = "modbus.func_code", number = "modbus.regnum16",
  value = "modbus.regval_uint16", request = "modbus.request_frame", start = "modbus.reference_num",
  quantity = "modbus.word_cnt", exception = "modbus.exception_code", transaction = "mbtcp.trans_id" }) do
  local ok, field = pcall(Field.new, name)
  if ok then modbus_fields[key] = field end
end
local names_state = vw3.new_state(nil)
-- Requests not answered yet, by connection and transaction: Wireshark gives an exception no
-- modbus.request_frame, and an exception 02 to a read is told from the read (p.38).
local asked, asked_count, ASKED_LIMIT = {}, 0, 4096

function names_proto.init()
  names_state = vw3.new_state(nil)
  asked, asked_count = {}, 0
end

local function first_value(field)
  local found = field and field()
  return found and found.value
end

-- The transaction a packet is part of, from the client's side (to_server: the packet is a request).
local function transaction_key(pinfo, to_server)
  local client, client_port, server, server_port = pinfo.dst, pinfo.dst_port, pinfo.src, pinfo.src_port
  if to_server then client, client_port, server, server_port = server, server_port, client, client_port end
  -- (tostring: a port may be absent, as under the test stub or a capture whose transport has none)
  return format("%s:%s>%s:%s#%s", tostring(client), tostring(client_port), tostring(server),
    tostring(server_port), tostring(first_value(modbus_fields.transaction)))
end

-- A request (first pass): kept until its answer comes, as the RTU plugin pairs it (start and quantity).
local function remember_request(pinfo, code)
  if asked_count >= ASKED_LIMIT then asked, asked_count = {}, 0 end -- (requests never answered: bounded)
  asked[transaction_key(pinfo, true)] = { kind = vw3.REQUEST, fn = code % 128,
    start = first_value(modbus_fields.start), quantity = first_value(modbus_fields.quantity),
    slave = first_value(modbus_fields.unit) or 0, number = pinfo.number }
  asked_count = asked_count + 1
end

local function answered(pinfo)
  local key = transaction_key(pinfo, false)
  local request = asked[key]
  if request ~= nil then asked[key], asked_count = nil, asked_count - 1 end
  return request
end

-- An exception (first pass) explained as the RTU plugin explains it (explain_exception): the device's
-- meaning, or for an exception 02 to a read, the parameters of the read with the status it tells.
local function explain(pinfo, fn, code)
  local f = { slave = first_value(modbus_fields.unit) or 0, fn = fn % 128,
    kind = env.EXCEPTION, exception_code = code, request = answered(pinfo), notes = {}, warnings = {},
    number = pinfo.number, unit_zero = true }
  local device = vw3.device_now(names_state, f)
  if not device then return nil end
  env.explain_exception(f, device)
  local registers = f.inferred and env.inferred_registers(names_state, f) or {}
  return { registers = registers, notes = f.notes, device = device }
end

local function add_tree(tvb, tree, done, slave)
  if #done.registers == 0 and #done.notes == 0 then return end
  local t = tree:add(names_proto, tvb:range(0, tvb:len()))
  t:set_text(format("VW3 register names (%s, unit %d)", done.device.profile.title, slave))
  local fake = { offset = 0, at = 0, bi = 0, length = tvb:len(), data_at = 2, data_len = 0 }
  for _, reg in ipairs(done.registers) do
    local range = reg.field and reg.field.range
    if range ~= nil then
      vw3.add_register(t, tvb, fake, reg, range)
    else
      vw3.add_register(t, tvb, fake, reg)
    end
  end
  for _, text in ipairs(done.notes) do vw3.add_text(t:add(pf.note, tvb:range(0, tvb:len()), text), ex.note, text) end
end

-- A packet without register numbers: a request to remember, or an exception to explain.
local function dissect_other(tvb, pinfo, tree)
  local fn, code = first_value(modbus_fields.code), first_value(modbus_fields.exception)
  local done = names_state.records[pinfo.number]
  if done == nil and fn ~= nil then -- (once, in capture order, as the registers below)
    if code ~= nil then
      done = explain(pinfo, fn, code)
    elseif first_value(modbus_fields.request) == nil then
      remember_request(pinfo, fn)
    else
      answered(pinfo)
    end
    names_state.records[pinfo.number] = done or false
  end
  if done then add_tree(tvb, tree, done, first_value(modbus_fields.unit) or 0) end
end

function names_proto.dissector(tvb, pinfo, tree)
  if modbus_fields.number == nil or modbus_fields.value == nil then return end
  -- Every packet comes here: the cheapest test first (no register numbers, no table made).
  if modbus_fields.number() == nil then
    if (modbus_fields.start and modbus_fields.start() or modbus_fields.exception and modbus_fields.exception())
        and names_proto.prefs.enabled and modbus_fields.code and env then
      dissect_other(tvb, pinfo, tree)
    end
    return
  end
  if not names_proto.prefs.enabled then return end
  if tvb:len() == 0 then return end
  local numbers = { modbus_fields.number() }
  if #numbers == 0 then return end
  local values = { modbus_fields.value() }
  local codes = modbus_fields.code and { modbus_fields.code() } or {}
  local units = modbus_fields.unit and { modbus_fields.unit() } or {}
  local requests = modbus_fields.request and { modbus_fields.request() } or {}
  local registers = {}
  for index = 1, math.min(#numbers, #values) do
    registers[index] = { address = numbers[index].value, value = values[index].value, field = values[index] }
  end
  local code = codes[1] and codes[1].value or 3
  local f = {
    slave = units[1] and units[1].value or 0, fn = code % 128,
    kind = (#requests > 0) and vw3.RESPONSE or vw3.REQUEST,
    registers = registers, notes = {}, warnings = {}, number = pinfo.number, unit_zero = true,
  }
  -- The protection story and profile auto follow the capture order: computed once, on the first pass,
  -- then reused.
  local done = names_state.records[pinfo.number]
  if done == nil then
    local device = vw3.device_now(names_state, f)
    if not device then return end
    if f.kind == vw3.REQUEST then remember_request(pinfo, code) else answered(pinfo) end
    vw3.annotate_registers(names_state, f, device, registers, f.kind == vw3.RESPONSE and vw3.reads[f.fn] ~= nil)
    done = { registers = registers, notes = f.notes, device = device }
    names_state.records[pinfo.number] = done
  else
    for index, reg in ipairs(done.registers) do
      if registers[index] ~= nil then reg.field = registers[index].field end
    end
  end
  add_tree(tvb, tree, done, f.slave)
end
register_postdissector(names_proto)
