-- vw3.fields: Wireshark: the protocol, its fields, expert infos and preferences.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.fields"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)

local proto = Proto("vw3", "VW3 Modbus serial (Altivar 71, SEL-749M)")

-- The kind is an integer with value strings: `vw3.kind == "request"` filters by name, and an integer costs
-- less than a string to add and to compare. A register's status is text, as vw3-decode's `status` key:
-- `-T fields` prints `protected` where vw3-decode does, and an empty occurrence where a register has no
-- status (a text field can have one, issue 27).
local KIND_NAMES = { [1] = REQUEST, [2] = RESPONSE, [3] = EXCEPTION, [4] = NOISE }
local KIND_VALUES = { [REQUEST] = 1, [RESPONSE] = 2, [EXCEPTION] = 3, [NOISE] = 4 }

-- The value strings data/fields.toml names (a field's `values`, when not a table of its own).
local VALUES = { kind = KIND_NAMES, functions = FUNCTIONS, exceptions = EXCEPTIONS, diagnostics = DIAGNOSTICS,
  run_indicator = DATA.names.run_indicator, request = frametype and frametype.REQUEST,
  response = frametype and frametype.RESPONSE }

-- The fields, stated in data/fields.toml with vw3-decode's filter keys (codegen/fields_lua.py):
-- pf.NAME is vw3.NAME's field, dots as `_` (vw3.reg.address: pf.reg_address).
local pf = {}
for _, f in ipairs(DATA.fields) do
  local name = string.gsub(string.sub(f.abbr, 5), "%.", "_")
  local values = f.values
  if type(values) == "string" then values = VALUES[values] end
  if f.ftype == "string" or f.ftype == "bytes" or f.ftype == "none" or f.ftype == "double"
      or f.ftype == "relative_time" then
    pf[name] = ProtoField[f.ftype](f.abbr, f.title, f.help)
  else
    pf[name] = ProtoField[f.ftype](f.abbr, f.title, f.base and base[f.base], values, nil, f.help)
  end
end

local ex = {
  crc_bad = ProtoExpert.new("vw3.expert.crc_bad", "Bad CRC", expert.group.CHECKSUM, expert.severity.ERROR),
  exception = ProtoExpert.new("vw3.expert.exception", "Exception response", expert.group.RESPONSE_CODE, expert.severity.NOTE),
  unanswered = ProtoExpert.new("vw3.expert.unanswered", "Request not answered", expert.group.SEQUENCE, expert.severity.WARN),
  no_request = ProtoExpert.new("vw3.expert.no_request", "Response without a matching request", expert.group.SEQUENCE, expert.severity.WARN),
  warning = ProtoExpert.new("vw3.expert.warning", "Outside the spec or the device profile", expert.group.PROTOCOL, expert.severity.WARN),
  malformed = ProtoExpert.new("vw3.expert.malformed", "PDU does not fit its layout", expert.group.MALFORMED, expert.severity.ERROR),
  protected = ProtoExpert.new("vw3.expert.protected", "Protected or non-existent parameter", expert.group.RESPONSE_CODE, expert.severity.WARN),
  note = ProtoExpert.new("vw3.expert.note", "Note", expert.group.COMMENTS_GROUP, expert.severity.NOTE),
  noise = ProtoExpert.new("vw3.expert.noise", "Bytes outside any frame", expert.group.MALFORMED, expert.severity.WARN),
  multiple = ProtoExpert.new("vw3.expert.record.multiple", "Several frames in one record", expert.group.REASSEMBLE, expert.severity.NOTE),
  partial = ProtoExpert.new("vw3.expert.record.partial", "Record ends inside a frame", expert.group.REASSEMBLE, expert.severity.WARN),
  internal = ProtoExpert.new("vw3.expert.internal", "Plugin error (please report it)", expert.group.UNDECODED, expert.severity.ERROR),
  preference = ProtoExpert.new("vw3.expert.preference", "Preference not understood", expert.group.PROTOCOL, expert.severity.WARN),
  profile = ProtoExpert.new("vw3.expert.profile", "Device profile chosen (profile auto)", expert.group.COMMENTS_GROUP, expert.severity.CHAT),
}
proto.experts = { ex.crc_bad, ex.exception, ex.unanswered, ex.no_request, ex.warning, ex.malformed,
  ex.protected, ex.note, ex.noise, ex.multiple, ex.partial, ex.preference, ex.internal, ex.profile }
vw3.experts = ex

local STYLE_DEFAULT, STYLE_PROTOCOL, STYLE_PLC = 1, 2, 3
proto.prefs.profiles = Pref.string("Device profiles", "",
  "Profile per slave, e.g. '12=atv71,3=sel749m'; a name alone sets the default for every other slave")
proto.prefs.maps = Pref.string("Register maps", "",
  "CSV register maps as vw3-decode --map takes them, separated by ';': FILE (every slave), 12=FILE (one "
    .. "slave) or sel749m=FILE (the slaves of a profile)")
proto.prefs.address_style = Pref.enum("Register address style", STYLE_DEFAULT,
  "profile: as the device profile says; protocol: as sent (8401); plc: 4X references (48402). "
    .. "The vw3.reg.address field is always the address on the wire; vw3.reg.label is the one shown.",
  { { 1, "profile", STYLE_DEFAULT }, { 2, "protocol", STYLE_PROTOCOL }, { 3, "plc", STYLE_PLC } }, false)
local MODE_AUTO, MODE_RTU, MODE_ASCII = 1, 2, 3
local MODE_NAMES = { [MODE_RTU] = "rtu", [MODE_ASCII] = "ascii" }
proto.prefs.mode = Pref.enum("Framing mode", MODE_AUTO,
  "auto: from the first record's bytes (as vw3-decode looks at the first bytes); rtu or ascii: forced, "
    .. "as vw3-decode --mode", { { 1, "auto", MODE_AUTO }, { 2, "rtu", MODE_RTU }, { 3, "ascii", MODE_ASCII } },
  false)
proto.prefs.timeout_ms = Pref.uint("Response timeout (ms)", 1000,
  "Flag responses later than this after their request, as vw3-decode --timeout does (0: off)")
proto.prefs.tcp_port = Pref.uint("RTU over TCP port", 0, "TCP port of a serial gateway carrying raw RTU frames (0: off)")
proto.prefs.udp_port = Pref.uint("RTU over UDP port", 0, "UDP port of a serial gateway sending raw RTU frames (0: off)")
proto.prefs.quick_lanes = Pref.bool("Quick lanes", VW3_QUICK_LANES ~= false,
  "Take the usual polling records (a known request, its usual answer, a setpoint write) by a shorter path "
  .. "that gives the same dissection; off: every record by the general path")
proto.prefs.user0 = Pref.bool("Decode linktype 147 (USER0)", false,
  "Decode every USER0 record as VW3 without a DLT_USER entry (which is the usual way: Preferences > "
    .. "Protocols > DLT_USER, payload protocol vw3)")

state = new_state(1.0)
-- RTAC timestamps per frame number. Wireshark's field extractors see nothing on a first pass without a
-- tree, so the RTAC header is read by a pass-through in front of Wireshark's own RTAC dissector.
rtac_times = {}
vw3.state = function() return state end

local STYLE_NAMES = { [STYLE_PROTOCOL] = "protocol", [STYLE_PLC] = "plc" }

local function apply_prefs()
  configure(proto.prefs.profiles, STYLE_NAMES[proto.prefs.address_style], proto.prefs.maps)
  lane.quick = proto.prefs.quick_lanes
end

-- A new stream's state, with the preferences' timeout and framing mode.
local function stream_state()
  local timeout = nil
  if proto.prefs.timeout_ms ~= 0 then timeout = proto.prefs.timeout_ms / 1000 end
  return new_state(timeout, MODE_NAMES[proto.prefs.mode])
end

function proto.init()
  newest_record = 0
  rtac_times = {}
  apply_prefs()
  state = stream_state()
  udp_states, tcp_states, tcp_records, tcp_call = {}, {}, {}, { number = -1, index = 0 }
end

M.KIND_VALUES = KIND_VALUES
M.apply_prefs, M.ex, M.pf, M.proto, M.stream_state = apply_prefs, ex, pf, proto, stream_state
