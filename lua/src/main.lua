-- vw3.lua: Wireshark plugin for Modbus serial (RTU, ASCII) captures of Altivar 71 drives (VW3 A3 303 card)
-- and SEL-749M relays; the same dissection as the vw3-decode command, inside Wireshark.
--
-- Install: copy this one file into the personal Lua plugins folder (Linux, macOS:
-- ~/.local/lib/wireshark/plugins/, Windows: %APPDATA%\Wireshark\plugins\), or load it for one run with
-- `tshark -X lua_script:vw3.lua -r capture.pcap`. It decodes linktype 147 (USER0) records, `rtacser.data`
-- through Decode As, and Modbus RTU over TCP and UDP on the ports set in the preferences.
--
-- GENERATED: python3 -m dissector.codegen assembles this file from lua/src/*.lua (one module a stage,
-- each naming the Python module it mirrors; edit those) and the tables between the GENERATED DATA markers
-- (the package's data files); `python3 -m dissector.codegen --check` fails when it is not that assembly.
-- Each module is a function in package.preload, obtained with require("vw3.NAME"); they share one table
-- of names, vw3.env (each module's exports and DATA, then this script's globals).
--
-- Runs on Wireshark 4.0 (Lua 5.2) and 4.4+ (Lua 5.4): no native bitwise operators, no `//`, integer
-- division with math.floor; the CRC's XOR from tables built with arithmetic alone (vw3.crc).

-- The modules in load order: those that need no Wireshark API first (plain lua5.2/lua5.4 loads them,
-- tests/conformance runs them), then the Wireshark glue.
local PURE = { "crc", "layouts", "stream", "rtu", "ascii", "feed", "decode", "pairing", "maps", "device", "story",
  "explain", "selection", "annotator", "pack", "records" }
local WIRESHARK = { "fields", "tree", "clock", "show", "dissector" }

-- (a second load of this file, as the tests do, starts from fresh modules)
for name in pairs(package.loaded) do
  if type(name) == "string" and name:sub(1, 4) == "vw3." then package.loaded[name] = nil end
end
local env = setmetatable({ DATA = DATA }, { __index = _ENV })
package.loaded["vw3.env"] = env
for _, name in ipairs(PURE) do require("vw3." .. name) end

if Proto == nil then -- loaded outside Wireshark (lua5.x tests without a stub): the pure part's entry points
  return { new_state = env.new_state, dissect_record = env.dissect_record, finish = env.finish,
    settle = env.pack.settle, configure = env.configure }
end

if set_plugin_info then
  set_plugin_info({
    version = "1.0.0",
    description = "Modbus RTU/ASCII for Altivar 71 (VW3 A3 303) and SEL-749M, as vw3-decode decodes it",
    repository = "vw3-dissector (lua/vw3.lua)",
  })
end

for _, name in ipairs(WIRESHARK) do require("vw3." .. name) end
-- (each module's chunk is done with once it ran, its functions held by what it exported: some 60 KB freed)
for name in pairs(package.preload) do
  if name:sub(1, 4) == "vw3." then package.preload[name] = nil end
end
