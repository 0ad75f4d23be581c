-- vw3.tree: Wireshark: a frame's registers, bits and PDU fields (show.lua show_frame), and its Info text.
-- Mirrors dissector/render/detail.py, dissector/render/summary.py, dissector/render/describe.py (Info forms).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.tree"]).

-- `1 byte`, `2 bytes`: a count and its noun, singular for one (describe.count_text).
local function count_text(count, noun)
  if count == 1 then return "1 " .. noun end
  return format("%d %ss", count, noun)
end

local function add_text(tree, expert_info, text)
  tree:add_proto_expert_info(expert_info, text)
end

-- The tvb range of `size` bytes at `at` in the frame's byte table (ASCII: hex pairs in the record);
-- the whole frame when that would fall outside it (never nil: TreeItem:add would shift its arguments).
local function frame_span(f, at, size)
  -- f.at: where the frame starts in the tvb it is shown from (ASCII: its colon)
  local offset, length = at + f.at, size
  if f.ascii then offset, length = f.at + 1 + 2 * at, 2 * size end
  if length <= 0 or offset < f.at or offset + length > f.at + f.length then
    return f.at, f.length
  end
  return offset, length
end

local function frame_range(tvb, f, at, size)
  return tvb:range(frame_span(f, at, size))
end

-- A text said on the frame: a field of its own (its value `value`) carrying the expert info, or the
-- expert info alone where no tree is wanted (whole: the frame's range in a tree, nil without one).
local function add_said(t, whole, field, value, expert_info, text)
  if whole ~= nil then t = t:add(field, whole, value):set_generated() end
  add_text(t, expert_info, text)
end

-- Invisible trees. Wireshark often builds a tree that nobody sees, only to run filters, coloring rules or
-- field extractors over it (this file's own Modbus field extractors make tshark build one on its second
-- pass). In such a tree an item of a field that nothing refers to is not created: TreeItem:add hands back
-- the parent item ("faked"). A frame's registers and bits repeat the same few fields, so there each field
-- is checked once per dissection (the faked item is the frame's item: it has the frame's length), and
-- the next registers and bits skip a field found faked, doing only what the faked item did: the text
-- and generated flag of the frame's item, and the expert infos. `serial` counts the dissections.
-- unseen.tvb, .offset, .length: the bytes of the register or bit being added (its TvbRange, .range, is
-- made when a field needs it); .frame_length: the length of the frame's item. .checking: fields are
-- checked (an invisible tree; it pays from the second register or bit on).
local LAYOUT_OF = DATA.rules.by_code -- (by kind, then function code: its layout's name)
local START_WORDS = DATA.fields.start_words -- (a start that is no window: FC24's pointer, codegen/fields_lua.py)
local unseen = { serial = 0, faked = {}, checked = {}, generated = false, no_row = {} }

-- The register or bit being added: `size` bytes at `at` in the frame (or the TvbRange `range`).
function unseen.at(tvb, f, at, size, range, checking)
  unseen.tvb, unseen.frame_length, unseen.range, unseen.checking = tvb, f.length, range, checking
  unseen.offset, unseen.length = frame_span(f, at, size)
end

-- Add a field to the register's or bit's item (in a tree that is shown, no field is ever faked).
function unseen.add(parent, field, value, generated, hidden)
  local serial = unseen.serial
  if unseen.faked[field] == serial then
    if generated then unseen.generated = true end
    return parent
  end
  local r = unseen.range
  if r == nil then
    r = unseen.tvb:range(unseen.offset, unseen.length)
    unseen.range = r
  end
  local item
  if value == nil then item = parent:add(field, r) else item = parent:add(field, r, value) end
  if generated then item:set_generated() end
  if unseen.checking and unseen.checked[field] ~= serial then
    unseen.checked[field] = serial
    local frame_length = unseen.frame_length
    if unseen.length ~= frame_length and item.len == frame_length then unseen.faked[field] = serial end
  end
  -- (never the faked item: it is the frame's)
  if hidden and unseen.faked[field] ~= serial then item:set_hidden() end
  return item
end

-- A register's texts: its item's, and its expert info's (16#8000 reads, add_register). Made each time
-- they are shown rather than kept: records stay in memory for the whole capture.
local function register_name(reg)
  local label = reg.label or (reg.address and tostring(reg.address)) or "?"
  local code = reg.row and reg.row.code
  if code then return label .. " " .. code end
  return label
end

local function register_title(reg)
  local parts = { "Register ", register_name(reg) }
  if reg.value ~= nil then parts[#parts + 1] = format(" = %d", reg.value) end
  if reg.text then parts[#parts + 1] = ": " .. reg.text end
  if reg.status then parts[#parts + 1] = " [" .. reg.status .. "]" end
  return concat(parts)
end

-- Where the frame's check starts in its byte table: RTU's CRC, 2 bytes; ASCII's LRC, 1 byte before CR LF.
local function check_at(f) return f.ascii and floor((f.length - 3) / 2) - 1 or f.length - 2 end

-- The frame's byte table for the display, from the tvb it is shown from (ASCII: the hex pairs decoded).
local function frame_bytes(f, tvb)
  if f.ascii then -- (the hex pairs between the colon and CR LF, as the framer read them)
    return (hex_pairs({ string.byte(tvb:raw(f.at + 1, f.length - 3), 1, -1) }, 1, floor((f.length - 3) / 2)))
  end
  local raw = tvb:raw(f.at, f.length) -- (the bytes as they are, 0-based)
  return { [0] = string.byte(raw, 1), string.byte(raw, 2, -1) }
end

-- `full` false: the tree is Wireshark's empty one (a pass that shows no details and filters on nothing):
-- only the expert infos are added, in the same order, since they reach Wireshark's expert tap and
-- column without a tree. checking: an invisible tree's fields are checked (unseen.add).
-- A register's text fields have one occurrence per register, empty (and hidden) where the register has
-- no such key, as vw3-decode's -T fields lists them: `tshark -T fields -e vw3.reg.code` then lines up
-- with -e vw3.reg.address, and -E occurrence=f names the first register's code, not the first code.
-- (Only text fields can: an empty occurrence of a number would need a text field of the same name, and
-- tshark 4.0 crashes comparing numbers with it, `vw3.reg.value == 3`.)
local function add_register(tree, tvb, f, reg, range, full, checking)
  if full ~= false then
    unseen.at(tvb, f, reg.offset or -1, 2, range, checking)
    local add = unseen.add
    local sub = add(tree, pf.reg)
    sub:set_text(register_title(reg)) -- (an FT_NONE item takes no label in add)
    if reg.address ~= nil then add(sub, pf.reg_address, reg.address, true) end
    add(sub, pf.reg_label, reg.label or "", reg.label ~= nil, reg.label == nil)
    if reg.value ~= nil then add(sub, pf.reg_value, reg.value) end -- (none: an exception 02's inferred status)
    local row = reg.row or unseen.no_row
    add(sub, pf.reg_code, row.code or "", row.code ~= nil, row.code == nil)
    add(sub, pf.reg_name, row.name or "", row.name ~= nil, row.name == nil)
    add(sub, pf.reg_unit, row.unit or "", row.unit ~= nil, row.unit == nil)
    if reg.scaled ~= nil then add(sub, pf.reg_scaled, reg.scaled, true) end
    local parameter = PARAMETER_FIELDS[row]
    if parameter ~= nil and reg.status ~= "protected" and reg.value ~= nil and reg.words ~= 0 then
      add(sub, parameter, reg.scaled or reg.value, true)
    end
    add(sub, pf.reg_text, reg.text or "", reg.text ~= nil, reg.text == nil)
    add(sub, pf.reg_source, row.source or "", row.source ~= nil, row.source == nil)
    if reg.words ~= nil and reg.words ~= 1 then add(sub, pf.reg_words, reg.words, true) end
    add(sub, pf.reg_status, reg.status or "", reg.status ~= nil, reg.status == nil)
    tree = sub
  end
  if reg.status and reg.status ~= "ok" then
    add_text(tree, ex.protected, format("Register %s: %s", register_name(reg), reg.text or reg.status))
  end
end

-- The PDU's fields as vw3-decode -V lists them (detail.py _head_lines), in their layout's order
-- (data/modbus.toml [layouts] and [parts], DATA.rules), each by the fields data/pdu_fields.toml gives it
-- (field.shown: their pf names, a text's string field first and its bytes' second; none: shown otherwise,
-- the window, registers, bits, objects). Read from the frame's bytes when shown: a record keeps no fields.
local LAYOUTS, PARTS = DATA.rules.layouts, DATA.rules.parts

-- The name of the layout a frame's kind and function code read ("raw": none).
local function layout_of(kind, fn)
  local entry = LAYOUT_OF[kind] and LAYOUT_OF[kind][fn]
  return entry and entry.layout or "raw"
end

-- A counted field's bytes from its count's value (as codegen/decode_lua.py's _size_of; odd: the byte an
-- odd count leaves).
local function counted_size(field, count)
  if field.type == "odd" then return count % 2 end
  local n = count - field.minus
  if field.half then return n - n % 2 end
  if field.type == "words" then return 2 * n end
  return n
end

-- The range a field of bytes is added on (its value): the frame's own bytes, or an ASCII frame's bytes that
-- its hex pairs stand for, a data source of their own, as vw3-decode -V shows them (`Data: 1234`, not the
-- pairs' characters 31323334). (TreeItem:add takes no value for a field of bytes: it reads the range's.)
local function bytes_range(tvb, f, b, at, size)
  if not f.ascii then return frame_range(tvb, f, at, size) end
  return ByteArray.new(string.char(table.unpack(b, at, at + size - 1)), true):tvb("VW3 ASCII data"):range(0, size)
end

-- b[at..at+size-1] under the field as_text where every byte is printable ASCII (as vw3-decode), else as_bytes.
local function add_text_or_bytes(t, tvb, f, b, at, size, as_text, as_bytes)
  if size <= 0 then return end
  local text = printable_ascii(b, at, at + size - 1)
  if text then t:add(as_text, frame_range(tvb, f, at, size), text)
  else t:add(as_bytes, bytes_range(tvb, f, b, at, size)) end
end

-- FC12's events (b[at..at+size-1], newest first) named as vw3-decode -V names them: DATA.comm_events[byte], its
-- name and kind (decode/fields.py comm_event, event_kind: data/modbus.toml [names.comm_event*]); an event of a
-- kind each bit of that kind, set or not, as tshark -V (DATA.event_bits: decode/fields.py event_bit_lines).
-- Each byte is vw3.event_list, vw3-decode's fields.event_list (tshark's modbus.event), labelled as -V writes it.
local function set(byte, mask) return floor(byte / mask) % 2 == 1 end -- (mask: a power of two)

local function add_events(t, tvb, f, b, at, size)
  local list = t:add(frame_range(tvb, f, at, size), format("Event list (%d)", size))
  for k = 0, size - 1 do
    local byte, range = b[at + k], frame_range(tvb, f, at + k, 1)
    local item, event = list:add(range, format("[%d]", k)), DATA.comm_events[byte]
    item:add(pf.event_list, range, byte, format("Byte: %d (0x%X)", byte, byte))
    item:add(range, "Event: " .. event[1])
    if event[2] > 0 then
      local under = item:add(range, "Flags")
      for _, bit in ipairs(DATA.event_bits[event[2]]) do
        local value = set(byte, bit[1]) and 1 or 0
        under:add(range, format(bit[2], value, value))
      end
    end
  end
end

-- The fields of `shape` read from b[at] on, the data ending before b[stop], added to `t` (nil: only
-- measured); where they end, or nil when one does not fit (a record that ends its records: grammar.py).
-- (values: a table to keep the fields' values in, for a shape measured again and again)
local function add_shape(t, tvb, f, b, shape, at, stop, values)
  values = values or {}
  for index = 1, #shape do
    local field = shape[index]
    local kind, shown, size = field.type, field.shown, field.size
    if field.when ~= nil and values[field.when] - field.when_minus <= 0 then
      -- (?(n-k): absent, its count leaves it no room: data/modbus.toml)
    elseif size ~= nil then
      if at + size > stop then return nil end
      local value = size == 1 and b[at] or u16(b, at)
      values[field.name] = value
      if t and shown then t:add(pf[shown[1]], frame_range(tvb, f, at, size), value) end
      at = at + size
    elseif kind == "switch" then -- (the part for the earlier field's value, else the last: in place)
      local cases = field.cases
      local part = cases[#cases].part
      for _, case in ipairs(cases) do
        if case.value == values[field.count] then part = case.part break end
      end
      at = add_shape(t, tvb, f, b, PARTS[part], at, stop)
      if at == nil then return nil end
    elseif kind == "array" or kind == "records" then -- (parts: `count` of them, or filling `count` bytes)
      local part, last, many = PARTS[field.part], stop, values[field.count]
      if kind == "records" then last, many = at + many, math.huge end
      if last > stop then return nil end
      while many > 0 and at < last do
        local after = add_shape(nil, tvb, f, b, part, at, last)
        if after == nil then break end
        if t and shown then
          add_shape(t:add(pf[shown[1]], frame_range(tvb, f, at, after - at)), tvb, f, b, part, at, last)
        end
        at, many = after, many - 1
      end
      if kind == "records" then at = last end
    else
      size = kind == "rest" and stop - at or counted_size(field, values[field.count])
      if size < 0 or at + size > stop then return nil end
      if t and shown and size > 0 then
        if kind == "words" then
          for k = at, at + size - 2, 2 do t:add(pf[shown[1]], frame_range(tvb, f, k, 2), u16(b, k)) end
        elseif kind == "odd" then
          t:add(pf[shown[1]], frame_range(tvb, f, at, 1), b[at])
        elseif kind == "text" then
          add_text_or_bytes(t, tvb, f, b, at, size, pf[shown[1]], pf[shown[2]])
        else
          t:add(pf[shown[1]], bytes_range(tvb, f, b, at, size))
          if field.name == "events" then add_events(t, tvb, f, b, at, size) end
        end
      end
      at = at + size
    end
  end
  return at
end

-- The register of a write confirmed by its masks (data/modbus.toml [confirm] "mask": FC22), as vw3-decode
-- --json lists it (render/registers.py mask_register): at its address (label: as shown), its value where the
-- value before does not matter (and_mask 0: or_mask), its masks as text; on the or mask's bytes (offset in
-- the frame; vw3_modbus.lua's: none, it gives the range).
local function mask_register(address, and_mask, or_mask, label, offset)
  local masks = { and_mask = and_mask, or_mask = or_mask }
  return { address = address, label = label, offset = offset,
    value = and_mask == 0 and or_mask or nil, text = say(and_mask == 0 and "mask_written" or "mask_prior", masks) }
end

-- FC17's fields where lua/src/decode.lua read a server id longer than one byte (size bytes, up to its run
-- indicator), as vw3-decode -V lists them (decode/fields.py _report_server_id_response); where they end.
local function add_server_id(t, tvb, f, b, size)
  t:add(pf.byte_count, frame_range(tvb, f, 2, 1), b[2])
  add_text_or_bytes(t, tvb, f, b, 3, size, pf.server_id_text, pf.server_id_bytes)
  t:add(pf.run_indicator, frame_range(tvb, f, 3 + size, 1), b[3 + size])
  add_text_or_bytes(t, tvb, f, b, 4 + size, b[2] - 1 - size, pf.additional_data, pf.additional_bytes)
  return 3 + b[2]
end

-- The PDU's fields of a frame that parsed (not an exception's: its code is shown as such), under `t`, the
-- bytes after them (vw3-decode -V's `Trailing: aabb`); an FC22's register after them.
local function add_pdu(t, tvb, f, stop)
  local name = layout_of(f.kind, f.fn)
  if f.malformed or #LAYOUTS[name] == 0 then return end
  local b = frame_bytes(f, tvb)
  local at
  if f.server_id_size then at = add_server_id(t, tvb, f, b, f.server_id_size)
  else at = add_shape(t, tvb, f, b, LAYOUTS[name], 2, stop) end
  if at ~= nil and at < stop then t:add(pf.trailing, bytes_range(tvb, f, b, at, stop - at)) end
  if MASK_WRITES[f.fn] then
    local places = DATA.field_places[name]
    local reg = mask_register(u16(b, places.address.at), u16(b, places.and_mask.at), u16(b, places.or_mask.at),
      f.span_label, places.or_mask.at)
    add_register(t, tvb, f, reg, nil, true)
  end
end

-- Decimal texts of the numbers the Info column shows, made once each (string.format costs more than
-- the rest of a summary; slaves and addresses repeat). Bounded: addresses are 16 bits.
local DECIMAL = made_once(function(number) return format("%d", number) end)

-- The Info text's forms that vw3-decode's describe.TEXT_FORMS gives and the plugin says alike, by kind and
-- function code (codegen/fields_lua.py info_forms): FC8's sub-function and data, FC24's pointer and values,
-- FC5's coil, FC6's value, FC7's and FC12's status, FC11's counters, FC15's and FC16's `written`, FC22's
-- masks, read from the frame's bytes (a record keeps no fields). The other forms keep the plugin's own text,
-- the window (span_text): registers' values and bits are left out by design (fields_lua.py PLUGIN_STEPS).
-- FORMS[fn][kind]: the form as a function of the frame (below: DATA.info_forms; nil for the usual codes).
local INFO = DATA.fields.info
local MAX_DATA_BYTES, MAX_FIFO_VALUES = INFO.max_data_bytes, INFO.max_fifo_values
local HEX_BYTE = made_once(function(value) return format("%02x", value) end)
-- Tables the texts are put together in, reused (Info texts are made for every record shown: a table each
-- time costs more, in the collector, than the text; hex_of, a format a byte, cost 0.7 % a record on max-size).
local HEX, VALUES, GROUP = {}, {}, {}


-- describe._data: FC8's data (b[first..last]), ` = 7` for a word, ` data 0a0b…` (its first MAX_DATA_BYTES
-- bytes, then how many more) for other data, nothing for none.
local function data_text(b, first, last)
  local size = last - first + 1
  if size == 2 then return " = " .. DECIMAL[b[first] * 256 + b[first + 1]] end
  if size <= 0 then return "" end
  local shown = size < MAX_DATA_BYTES and size or MAX_DATA_BYTES
  for k = 1, shown do HEX[k] = HEX_BYTE[b[first + k - 1]] end
  if size <= MAX_DATA_BYTES then return " data " .. concat(HEX, "", 1, shown) end
  return " data " .. concat(HEX, "", 1, shown) .. "… (+" .. count_text(size - MAX_DATA_BYTES, "byte") .. ")"
end

-- describe._fifo: `:` and the first MAX_FIFO_VALUES of `count` values from b[first] (none past b[last]),
-- then how many more (`… (+2)`); nothing for none.
local function fifo_values(b, count, first, last)
  local made = 0
  for k = 0, (count < MAX_FIFO_VALUES and count or MAX_FIFO_VALUES) - 1 do
    local at = first + 2 * k
    if at + 1 > last then break end
    made = made + 1
    VALUES[made] = DECIMAL[b[at] * 256 + b[at + 1]]
  end
  if made == 0 then return "" end
  local more = count > made and made == MAX_FIFO_VALUES and " … (+" .. DECIMAL[count - made] .. ")" or ""
  return ": " .. concat(VALUES, " ", 1, made) .. more
end

-- The describers of describe._BY_NAME (FC43's MEI, FC17's server id, FC20's and FC21's record groups), on
-- the frame's bytes b (its slave byte at b[base], its data ending at b[last]).
local MEI_TYPES, DEVICE_ID_CODES = DATA.fields.names.mei_types, DATA.fields.names.device_id_codes
local RUN_INDICATOR = DATA.names.run_indicator
local BY_NAME = {}

-- describe._mei: `Read Device Identification, basic, from object 0`; an answer its objects' values (a
-- revision the profile decoded as such: `V2.1`), another MEI type its name.
function BY_NAME.mei(f, b, base)
  local mei_type = b[base + 2]
  local mei = MEI_TYPES[mei_type] or "MEI " .. DECIMAL[mei_type]
  if mei_type ~= 14 then return mei end
  local code = DEVICE_ID_CODES[b[base + 3]] or DECIMAL[b[base + 3]]
  if f.kind == REQUEST then return mei .. ", " .. code .. ", from object " .. DECIMAL[b[base + 4]] end
  local parts = {}
  for index, object in ipairs(f.objects or NO_INTERPRETATION) do
    local text = object.text
    if text == nil or not text:match("^V%d+%.%d+$") then text = "'" .. object.value .. "'" end
    parts[index] = object.name .. "=" .. text
  end
  -- (More Follows FF: the server sends the rest from the next object id on, describe._mei)
  local next_id = b[base + 5] == 255 and b[base + 6]
  local more = next_id and " (more follows from object " .. DECIMAL[next_id] .. ")"
  return mei .. ", " .. code .. ":" .. (parts[1] and " " or "") .. concat(parts, " ") .. (more or "")
end

-- describe._report_server_id: an answer's `server id 18, run ON, 'V1.'` (its data as text where every byte
-- is printable ASCII, else counted). A longer id (lua/src/decode.lua read it up to its run indicator:
-- f.server_id_size) as its text, `'Pymodbus'`, or its bytes, `12 34 56`.
function BY_NAME.report_server_id(f, b, base)
  if f.kind == REQUEST or b[base + 2] == 0 then return "" end -- (byte count 0: no server id)
  if b[base + 2] < 2 then return "server id " .. DECIMAL[b[base + 3]] end -- (byte count 1: the id alone)
  local size = f.server_id_size or 1
  local count, run, after = b[base + 2] - 1 - size, b[base + 3 + size], base + 4 + size
  local text = count > 0 and printable_ascii(b, after, after + count - 1)
  local data = text and python_repr(text) or count_text(count, "byte")
  local id = DECIMAL[b[base + 3]]
  if size > 1 then
    local shown = printable_ascii(b, base + 3, base + 2 + size)
    id = shown and python_repr(shown) or hex_of(b, base + 3, base + 2 + size, "%02X", " ")
  end
  return "server id " .. id .. ", run " .. (RUN_INDICATOR[run] or DECIMAL[run]) .. ", " .. data
end

-- describe._file_record: `2 record group(s)`, the sub-requests, sub-responses or records its byte count holds.
function BY_NAME.file_record(f, b, base)
  local field = LAYOUTS[layout_of(f.kind, f.fn)][2] -- (after the byte count: the records)
  local part, at = PARTS[field.part], base + 3
  local last, groups = at + b[base + 2], 0
  while at < last do
    at = add_shape(nil, nil, f, b, part, at, last, GROUP)
    if at == nil then break end
    groups = groups + 1
  end
  return DECIMAL[groups] .. " record group(s)"
end

-- describe.span_text: the frame's window, `8400..8402 (3)`, `9001` (one), `8400 (0)` (none: nothing wraps),
-- past 65535 as asked (`65535..65539 (5)`, as the warning `span` says it), PLC style its label (`40002..40003
-- (2)`); `(3)` where only the quantity is known, nothing without either. (FC24's start is its pointer: its
-- form says it, DATA.info_forms)
local function span_text(f)
  local start, quantity, label = f.start, f.quantity, f.span_label
  if label ~= nil then
    if quantity == nil or quantity == 1 then return label end
    return label .. " (" .. DECIMAL[quantity] .. ")"
  end
  if start == nil then return quantity ~= nil and "(" .. DECIMAL[quantity] .. ")" or "" end
  if quantity == nil or quantity == 1 then return DECIMAL[start] end
  if quantity == 0 then return DECIMAL[start] .. " (0)" end
  return DECIMAL[start] .. ".." .. DECIMAL[start + quantity - 1] .. " (" .. DECIMAL[quantity] .. ")"
end

-- describe._single: FC6's value, ` TFR=50.0 Hz` where the frame's device (device, else the stream st's
-- for the frame) names its register or reads the value as a text, ` = 7` otherwise; the register named as
-- the tree names it (vw3.story's describe), written as describe.register_text writes a write's register
-- (a write's register has no status).
local function single_text(f, st, device, value)
  device = device or device_of(st, f)
  local run = f.registers
  if device ~= nil and run ~= nil and run.count > 0 and run.start ~= nil then
    local reg = { address = run.start, value = value }
    describe(device, f, reg, run.plain and run.plain[0], nil, words_at(rows_for(device, f.fn), run.start, 0, run.count))
    local code = reg.row and reg.row.code
    if code or reg.text then
      return " " .. (code or reg.label or DECIMAL[run.start]) .. "=" .. (reg.text or DECIMAL[value])
    end
  end
  return " = " .. DECIMAL[value]
end

-- Each form by function code, then kind: written out by the code generator from describe.TEXT_FORMS's
-- steps as DATA.fields.info states them, each field read where its layout places it (DATA.info_forms,
-- codegen/display_lua.py), calling the helpers above; a describer of BY_NAME by its name.
local FORMS = DATA.info_forms(DECIMAL, DIAGNOSTICS, count_text, data_text, fifo_values, single_text, span_text, BY_NAME)

-- NAMING[fn][kind]: the forms that name a register as the frame's device does (a `single` step): their
-- text needs the device (summary's st or device). (DATA.info_naming, codegen/display_lua.py)
local NAMING = DATA.info_naming

-- tvb: the frame's, where it is shown; nil where its text is made as it is decoded (vw3.records
-- remember_request), from its byte table then. st: the frame's stream, or device: its device, where the
-- text names a register as the device does (FC6); nil without either for such a frame (its text made
-- where it is shown).
local function summary(f, tvb, st, device)
  -- (one concatenation, one new string, for the usual frame: the Info text is made for every record shown)
  local kind, fn = f.kind, f.fn
  local steps = FORMS[fn]
  if steps ~= nil then steps = steps[kind] end
  local slave, name = DECIMAL[f.slave], f.function_text or FUNCTIONS[fn] or function_name(fn)
  if kind == EXCEPTION then -- (by the spec, as vw3-decode's summary; the device's meaning: its note)
    -- (no code, a malformed exception: `?`, as describe.py's summary)
    local code = f.exception_code and DECIMAL[f.exception_code] or "?"
    kind = kind .. " " .. code .. " (" .. exception_name(f.exception_code) .. ")"
  end
  local tail = ""
  if f.provisional then tail = " " .. DATA.render.provisional end -- (as vw3-decode's summary says it)
  if f.crc ~= f.crc_expected then tail = tail .. (f.ascii and " BAD LRC" or " BAD CRC") end
  -- (describe.info_text: a frame whose fields did not parse says so)
  if f.malformed then return slave .. " " .. name .. " " .. kind .. " (malformed)" .. tail end
  if steps ~= nil then -- (its bytes: the tvb's, else its byte table's while it is decoded)
    if st == nil and device == nil and NAMING[fn] ~= nil and NAMING[fn][f.kind] then return nil end
    local b, base, last = f.b, f.bi, f.b and f.data_at + f.data_len - 1
    if b == nil and tvb ~= nil then
      b, base, last = frame_bytes(f, tvb), 0, check_at(f) - 1
    end
    if b ~= nil then
      local text = steps(f, b, base, last, st, device) -- (describe.info_text's rstrip: no space before none)
      return slave .. " " .. name .. " " .. kind .. (text == "" and "" or " " .. text) .. tail
    end
  end
  if f.kind == EXCEPTION then return slave .. " " .. name .. " " .. kind .. tail end -- (its code said)
  local text = span_text(f)
  if text == "" and LAYOUT_OF[kind][fn] == nil then -- (a code with no describer: its data counted)
    local size = check_at(f) - 2 -- (but slave and code)
    text = count_text(size, "byte") .. " of data"
  end
  return slave .. " " .. name .. " " .. kind .. (text == "" and "" or " " .. text) .. tail
end
