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
  value = "modbus.regval_uint16", request = "modbus.request_frame" }) do
  local ok, field = pcall(Field.new, name)
  if ok then modbus_fields[key] = field end
end
local names_state = vw3.new_state(nil)

function names_proto.init()
  names_state = vw3.new_state(nil)
end

function names_proto.dissector(tvb, pinfo, tree)
  if modbus_fields.number == nil or modbus_fields.value == nil then return end
  -- Every packet comes here: the cheapest test first (no register numbers, no table made).
  if modbus_fields.number() == nil then return end
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
  local device
  if done == nil then
    device = vw3.device_now(names_state, f)
    if not device then return end
    vw3.annotate_registers(names_state, f, device, registers, f.kind == vw3.RESPONSE and vw3.reads[f.fn] ~= nil)
    names_state.records[pinfo.number] = { registers = registers, notes = f.notes, device = device }
  else
    device = done.device
    for index, reg in ipairs(done.registers) do
      if registers[index] ~= nil then done.registers[index].field = registers[index].field end
    end
    registers, f.notes = done.registers, done.notes
  end
  local t = tree:add(names_proto, tvb:range(0, tvb:len()))
  t:set_text(format("VW3 register names (%s, unit %d)", device.profile.title, f.slave))
  for _, reg in ipairs(registers) do
    local range = reg.field.range
    local fake = { offset = 0, at = 0, bi = 0, length = tvb:len(), data_at = 2, data_len = 0 }
    if range ~= nil then
      vw3.add_register(t, tvb, fake, reg, range)
    else
      vw3.add_register(t, tvb, fake, reg)
    end
  end
  for _, text in ipairs(f.notes) do vw3.add_text(t:add(pf.note, tvb:range(0, tvb:len()), text), ex.note, text) end
end
register_postdissector(names_proto)
