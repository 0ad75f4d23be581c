-- vw3.fields: Wireshark: the protocol, its fields, expert infos and preferences.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.fields"]).

local proto = Proto("vw3", "VW3 Modbus serial (Altivar 71, SEL-749M)")

-- The kind is an integer with value strings (pack.lua's numbering): `vw3.kind == "request"` filters by name,
-- and an integer costs less than a string to add and to compare. A register's status is text, as vw3-decode's
-- `status` key: `-T fields` prints `protected` where vw3-decode does, and an empty occurrence where a
-- register has no status (a text field can have one, issue 27).

-- The value strings data/fields.toml names (a field's `values`, when not a table of its own).
local VALUES = { kind = NUMBER_KIND, functions = FUNCTIONS, exceptions = EXCEPTIONS, diagnostics = DIAGNOSTICS,
  run_indicator = DATA.names.run_indicator, request = frametype and frametype.REQUEST,
  response = frametype and frametype.RESPONSE, mei_types = DATA.fields.names.mei_types,
  device_id_codes = DATA.fields.names.device_id_codes }

-- The fields, stated in data/fields.toml with vw3-decode's filter keys (codegen/fields_lua.py):
-- pf.NAME is vw3.NAME's field, dots as `_` (vw3.reg.address: pf.reg_address), or f.name where two fields
-- share a filter (FC7's 8-bit vw3.status: pf.exception_status).
-- Registered in the catalogue's order: a filter names the type of the field of its name registered last
-- (vw3.status: FC11's word after FC7's byte, so `vw3.status == 0xffff` is a filter).
local pf, field_list = {}, {}
for _, f in ipairs(DATA.fields.fields) do
  local name = f.name or string.gsub(string.sub(f.abbr, 5), "%.", "_")
  local values = f.values
  -- (else a [names] table of data/modbus.toml: FC43/14's conformity levels)
  if type(values) == "string" then values = VALUES[values] or DATA.names[values] end
  if f.plain then -- (a constructor of (abbr, title, help): codegen/fields_lua.py PLAIN)
    pf[name] = ProtoField[f.ftype](f.abbr, f.title, f.help)
  else
    pf[name] = ProtoField[f.ftype](f.abbr, f.title, f.base and base[f.base], values, nil, f.help)
  end
  field_list[#field_list + 1] = pf[name]
end

-- The protocol's fields: the catalogue's (pf), then the per-parameter fields, one per row of the built-in
-- register maps (DATA.fields.parameters, codegen/fields_lua.py: vw3.atv71.rfr, ...), by the row they follow
-- (tree.lua add_register).
local PARAMETER_FIELDS = {}
for _, p in ipairs(DATA.fields.parameters) do
  local field = ProtoField.double(p.abbr, p.title)
  PARAMETER_FIELDS[PROFILES[p.profile].map[p.address]] = field
  field_list[#field_list + 1] = field
end
proto.fields = field_list

-- The expert infos, stated in data/fields.toml's [[expert]] entries: ex.NAME, registered in their order.
local ex, experts = {}, {}
for index, e in ipairs(DATA.fields.experts) do
  experts[index] = ProtoExpert.new(e.filter, e.title, expert.group[e.group], expert.severity[e.severity])
  ex[e.name] = experts[index]
end
proto.experts = experts

-- The preferences, stated in data/fields.toml's [[preference]] entries, registered in their order. An enum's
-- value is its choice's place among its choices (`chosen` names it; the first, the default, forces nothing).
local CHOICES = {}
for _, p in ipairs(DATA.fields.preferences) do
  if p.type == "enum" then
    local choices = {}
    for index, choice in ipairs(p.choices) do choices[index] = { index, choice, index } end
    CHOICES[p.name] = p.choices
    proto.prefs[p.name] = Pref.enum(p.title, 1, p.help, choices, false)
  else
    local default = p.default
    if p.name == "quick_lanes" then default = lane.quick end -- (VW3_QUICK_LANES = false before loading: off)
    proto.prefs[p.name] = Pref[p.type](p.title, default, p.help)
  end
end

local function chosen(name)
  local value = proto.prefs[name]
  if value == 1 then return nil end
  return CHOICES[name][value]
end

local function apply_prefs()
  configure(proto.prefs.profiles, chosen("address_style"), proto.prefs.maps)
  lane.quick = proto.prefs.quick_lanes
end

-- A new stream's state, with the preferences' timeout and framing mode.
local function stream_state()
  local timeout = nil
  if proto.prefs.timeout_ms ~= 0 then timeout = proto.prefs.timeout_ms / 1000 end
  return new_state(timeout, chosen("mode"))
end

-- Each capture starts here (Wireshark calls it before the first record is dissected): the plugin's state.
function proto.init()
  newest_record = 0 -- (the newest record's number: show.lua finish_all)
  recorded_until = nil -- (the last timed record's time, any stream's, empty or not: vw3.pairing's ended)
  -- RTAC timestamps per frame number. Wireshark's field extractors see nothing on a first pass without a
  -- tree, so the RTAC header is read by a pass-through in front of Wireshark's own RTAC dissector.
  rtac_times = {}
  rtac_payload = false -- (Decode As gave RTAC data to VW3: dissector.lua rtac_time)
  lane.parts = {} -- (records captured in part, by number: lua/src/stream.lua lane.captured_in_part)
  apply_prefs()
  -- Streams of records: the serial capture's (state); the others (one per UDP conversation, one per TCP
  -- connection, one per further interface: dissector.lua) in udp_states, which the first pass's end finishes.
  state = stream_state()
  udp_states = {}
  record_streams = {} -- (each record's stream, where interfaces are told apart: dissector.lua serial_state)
end
