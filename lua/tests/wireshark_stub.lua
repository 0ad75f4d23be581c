-- A minimal stand-in for the Wireshark Lua API, enough to load lua/vw3.lua in a plain Lua interpreter
-- (lua5.4 here, as in Wireshark 4.4+) and run its dissector over records. Tree items are kept as plain
-- tables so a test can print and check them. Only what vw3.lua calls exists; anything else fails loudly.
local stub = { protos = {}, tables = {}, postdissectors = {} }

base = { NONE = 0, DEC = 1, HEX = 2, OCT = 3, DEC_HEX = 4, HEX_DEC = 5 }
frametype = { NONE = 0, REQUEST = 1, RESPONSE = 2, ACK = 3, DUP_ACK = 4 }
wtap = { USER0 = 45 }
expert = {
  group = {
    CHECKSUM = 1, SEQUENCE = 2, RESPONSE_CODE = 3, REQUEST_CODE = 4, UNDECODED = 5, REASSEMBLE = 6,
    MALFORMED = 7, DEBUG = 8, PROTOCOL = 9, SECURITY = 10, COMMENTS_GROUP = 11, DECRYPTION = 12,
    ASSUMPTION = 13, DEPRECATED = 14,
  },
  severity = { COMMENT = 1, CHAT = 2, NOTE = 3, WARN = 4, ERROR = 5 },
}

local FIELD_TYPES = {
  uint8 = true, uint16 = true, uint32 = true, string = true, bool = true, none = true, bytes = true,
  framenum = true, relative_time = true, double = true,
}
ProtoField = setmetatable({}, {
  __index = function(_, ftype)
    if not FIELD_TYPES[ftype] then error("stub: ProtoField." .. tostring(ftype) .. " is not stubbed", 2) end
    return function(abbr, name)
      assert(type(abbr) == "string" and abbr:match("^vw3"), "field abbreviations start with vw3")
      return { abbr = abbr, name = name, ftype = ftype, kind = "field" }
    end
  end,
})

ProtoExpert = {
  new = function(abbr, text, group, severity)
    assert(group ~= nil and severity ~= nil, "expert group and severity must exist: " .. abbr)
    return { abbr = abbr, text = text, kind = "expert" }
  end,
}

local function pref(kind)
  return function(label, default, descr, ...)
    return { pref = kind, default = default, label = label }
  end
end
Pref = { string = pref("string"), enum = pref("enum"), uint = pref("uint"), bool = pref("bool") }

NSTime = {
  new = function(secs, nsecs) return { secs = secs, nsecs = nsecs } end,
}

function Proto(name, description)
  local values = {}
  local prefs = setmetatable({}, {
    __newindex = function(_, key, value) values[key] = value.default end,
    __index = function(_, key) return values[key] end,
  })
  local proto = { name = name, description = description, prefs = prefs, kind = "proto", set_pref = function(key, value) values[key] = value end }
  stub.protos[name] = proto
  return proto
end

local function dissector_table(name)
  local tbl = stub.tables[name]
  if tbl == nil then
    tbl = { name = name, entries = {}, decode_as = {} }
    function tbl:add(key, proto) self.entries[key] = proto end
    function tbl:remove(key, proto) self.entries[key] = nil end
    function tbl:add_for_decode_as(proto) self.decode_as[#self.decode_as + 1] = proto end
    stub.tables[name] = tbl
  end
  return tbl
end
DissectorTable = { get = dissector_table }

function register_postdissector(proto) stub.postdissectors[#stub.postdissectors + 1] = proto end

-- Field extractors: stub.field_values[name] holds the FieldInfo-like tables the next call returns.
stub.field_values = {}
Field = {
  new = function(name)
    return function() return table.unpack(stub.field_values[name] or {}) end
  end,
}

-- Tvb and TvbRange over a Lua string.
function stub.tvb(bytes)
  local tvb = { bytes = bytes }
  function tvb:len() return #self.bytes end
  function tvb:reported_len() return self.reported or #self.bytes end -- (a record captured in part: more)
  function tvb:raw(offset, length)
    offset = offset or 0
    length = length or (#self.bytes - offset)
    return self.bytes:sub(offset + 1, offset + length)
  end
  function tvb:range(offset, length)
    assert(offset >= 0 and length >= 0 and offset + length <= #self.bytes, -- (0: an empty range, as Wireshark allows)
      string.format("stub: range(%d, %d) outside a %d-byte tvb", offset, length, #self.bytes))
    return { kind = "range", offset = offset, length = length }
  end
  return tvb
end

-- ByteArray: only what a reassembled frame needs (raw bytes in, a tvb out).
ByteArray = {
  new = function(bytes, raw)
    assert(raw == true, "stub: ByteArray.new only with raw bytes")
    return { tvb = function(_, name) return stub.tvb(bytes) end }
  end,
}

-- Tree items: { label, field, value, range, generated, children }.
local TreeItem = {}
TreeItem.__index = TreeItem

local function new_item(field, range, value)
  return setmetatable({ field = field, range = range, value = value, children = {} }, TreeItem)
end

function TreeItem:add(field, range, value, ...)
  if type(field) == "table" and field.kind == "range" then  -- (a text item on a range, as wslua's add allows)
    assert(type(range) == "string", "stub: a text item's label must be a string")
    local child = new_item(nil, field, nil)
    child.text = range
    self.children[#self.children + 1] = child
    return child
  end
  assert(type(field) == "table" and (field.kind == "field" or field.kind == "proto"), "stub: add() needs a field or proto")
  assert(range == nil or (type(range) == "table" and range.kind == "range"), "stub: the second argument must be a TvbRange")
  if field.kind == "field" and field.ftype ~= "none" and field.ftype ~= "bytes" then
    assert(value ~= nil, "stub: no value for " .. field.abbr)
  end
  local child = new_item(field, range, value)
  if field.kind == "proto" and type(value) == "string" then child.value, child.text = nil, value end
  self.children[#self.children + 1] = child
  return child
end

function TreeItem:set_text(text) self.text = text return self end
function TreeItem:append_text(text) self.text = (self.text or "") .. text return self end
function TreeItem:set_generated() self.generated = true return self end
function TreeItem:set_hidden() self.hidden = true return self end
function TreeItem:add_proto_expert_info(info, text)
  assert(type(info) == "table" and info.kind == "expert", "stub: add_proto_expert_info needs a ProtoExpert")
  local child = new_item(nil, nil, nil)
  child.expert, child.text = info.abbr, text or info.text
  self.children[#self.children + 1] = child
  return self
end

function stub.tree() return new_item(nil, nil, nil) end

-- One line per item: indentation, then `abbr=value` (fields), `expert:abbr=text`, or the item text.
function stub.dump(item, depth, out)
  depth, out = depth or 0, out or {}
  for _, child in ipairs(item.children) do
    local pad = string.rep("  ", depth)
    if child.hidden then -- (not shown, as tshark -V does not show it)
    elseif child.expert then
      out[#out + 1] = pad .. "expert:" .. child.expert .. "=" .. tostring(child.text)
    elseif child.field == nil then
      out[#out + 1] = pad .. tostring(child.text)
    elseif child.field.kind == "proto" then
      out[#out + 1] = pad .. child.field.name .. ": " .. tostring(child.text)
    else
      local value = child.value
      if type(value) == "table" and value.secs then value = string.format("%d.%09d", value.secs, value.nsecs) end
      if value == nil then value = child.text end
      out[#out + 1] = pad .. child.field.abbr .. "=" .. tostring(value)
    end
    stub.dump(child, depth + 1, out)
  end
  return out
end

function stub.pinfo(number, visited, time)
  return { number = number, visited = visited, abs_ts = time, cols = {} }
end

return stub
