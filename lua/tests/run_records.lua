-- Usage: lua5.4 run_records.lua PLUGIN [-o key=value]... [-f field=v1,v2]... HEX[@TIME] ...
-- Loads the plugin on the Wireshark stub, runs both passes over the records (as tshark -2 does), and
-- prints the second pass's tree of every record, one `field=value` line per item.
local here = arg[0]:match("^(.*)/[^/]*$") or "."
package.path = here .. "/?.lua;" .. package.path
local stub = require("wireshark_stub")

local plugin = arg[1]
local records, options = {}, {}
local index = 2
while index <= #arg do
  if arg[index] == "-f" then
    -- -f FIELD=v1,v2: values of a Wireshark field the post-dissector reads, in every packet.
    local name, list = arg[index + 1]:match("^([^=]+)=(.*)$")
    local values = {}
    for value in list:gmatch("[^,]+") do values[#values + 1] = { value = tonumber(value) } end
    stub.field_values[name] = values
    index = index + 2
  elseif arg[index] == "-o" then
    local key, value = arg[index + 1]:match("^([^=]+)=(.*)$")
    options[#options + 1] = { key, value }
    index = index + 2
  elseif arg[index] == "!error" then
    -- A record whose bytes cannot be read: exercises the plugin's guard against its own errors.
    records[#records + 1] = { bytes = "\0\0\0\0", time = #records * 0.01, broken = true }
    index = index + 1
  else
    local hex, time = arg[index]:match("^([^@]*)@?(.*)$")
    records[#records + 1] = { bytes = (hex:gsub("%x%x", function(pair) return string.char(tonumber(pair, 16)) end)), time = tonumber(time) or #records * 0.01 }
    index = index + 1
  end
end

dofile(plugin)
-- the optional Modbus/TCP naming file beside it (it builds on what vw3.lua left in package.loaded)
dofile((plugin:gsub("vw3%.lua$", "vw3_modbus.lua")))
local proto = stub.protos.vw3
assert(stub.tables.wtap_encap.entries[wtap.USER0] == nil, "USER0 is the user's to map (DLT_USER)")
proto.set_pref("user0", true) -- the preference that maps it for a session
for _, option in ipairs(options) do
  local value = option[2]
  if tonumber(value) then value = tonumber(value) end
  proto.set_pref(option[1], value)
end
if proto.prefs_changed then proto.prefs_changed() end
assert(stub.tables.wtap_encap.entries[wtap.USER0] == proto, "registered for linktype 147 by the preference")
proto.init()
if stub.protos.vw3names then stub.protos.vw3names.init() end
local function tvb_of(record)
  local tvb = stub.tvb(record.bytes)
  if record.broken then tvb.raw = function() error("unreadable bytes") end end
  return tvb
end
for number, record in ipairs(records) do
  assert(proto.dissector(tvb_of(record), stub.pinfo(number, false, record.time), stub.tree()) == #record.bytes)
end
for number, record in ipairs(records) do
  local tree = stub.tree()
  local pinfo = stub.pinfo(number, true, record.time)
  proto.dissector(tvb_of(record), pinfo, tree)
  -- The post-dissectors run too; without Modbus fields in the packet they add nothing.
  for _, post in ipairs(stub.postdissectors) do post.dissector(stub.tvb(record.bytes), pinfo, tree) end
  print(string.format("record %d: %s", number, tostring(pinfo.cols.info)))
  for _, line in ipairs(stub.dump(tree, 1)) do print(line) end
end
print("lua version: " .. _VERSION)
