-- vw3.pack: what a record keeps of its frames for the later passes, packed (no Python counterpart: the plugin keeps every record for Wireshark's later dissections).
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.pack"]).

-- What a record keeps of a frame for the later passes, packed: numbers, slots of one flat array per
-- stream (st.flat), the item being the number of its first slot. A table with named keys keeps the hash
-- it grew to while the frame was decoded (some 25 keys, 1.3 KB); numbers are no objects: the collector
-- goes over the array's slots in one sweep instead of following a table (or two, or three) a frame, and
-- its 13 slots take some 200 bytes. Small numbers share a slot (a double holds 53 bits exactly): a slot
-- written costs more than the arithmetic that fills it. A missing value is false. Requests and responses
-- name each other by record (and the request's time): no links between kept tables. The keys a frame
-- holds rarely are kept in a table in its last slot (with its span label). The display unpacks a frame
-- each time it shows it. A key the display reads must have a slot or be in RARE: one missing shows only
-- from the second pass on (`tshark -2`, which the parity tests run). The slots and the code that fills and
-- reads them: DATA.pack (codegen/pack_lua.py SLOTS): put_flat(st, every slot's value), the frame's first
-- slot in st.flat; expand_slots(flat, that slot), its keys and runs in a table, then link and request_time.
local pack = {}
local RARE, has_rare, put_flat, expand_slots = DATA.pack.rare, DATA.pack.has_rare, DATA.pack.put, DATA.pack.expand
-- The kinds by number and the numbers by kind: a packed frame's kind, and vw3.kind's values (lua/src/fields.lua).
local KIND_NUMBER = { [REQUEST] = 1, [RESPONSE] = 2, [EXCEPTION] = 3, [NOISE] = 4 }
local NUMBER_KIND = { REQUEST, RESPONSE, EXCEPTION, NOISE }
local ENCODE = DATA.pack.encode
local head_slot, crc_slot, span_slot, run_slot, bit_slot = ENCODE.head, ENCODE.crcs, ENCODE.span, ENCODE.registers,
  ENCODE.bits

-- A frame's first slot in st.flat; noise in a table of its own, 10 slots (a
-- run of the same noise, take_items, is one: a flood of ':' in ASCII mode is a noise item a byte).
local function pack_item(st, f)
  if f.kind == NOISE then
    return { NOISE, f.at, f.length, f.number, f.offset, f.record, f.time, f.reason, f.raw, f.count }
  end
  local regs, coils = false, false
  local registers, bits = f.registers, f.bits
  if registers ~= nil then regs = run_slot(registers.first, registers.count, registers.start) end
  if bits ~= nil then coils = bit_slot(bits.first, bits.count, bits.start, bits.single) end
  local request, response = f.request, f.response
  local link, request_time = false, nil
  if request ~= nil then
    link, request_time = request.record, request.time
  elseif response ~= nil then
    link = -response.record
  end
  local last = f.span_label
  if has_rare(f) then
    -- (only the keys the frame holds: Lua 5.2 makes a key even for a nil stored under it)
    last = { span_label = last }
    for index = 1, #RARE do
      local key = RARE[index]
      local kept = f[key]
      if kept ~= nil then last[key] = kept end
    end
    if registers ~= nil and (registers.status or registers.plain) then
      last.status, last.plain = registers.status, registers.plain
    end
    -- An exception 02's inferred registers are listed from its request's start and quantity.
    if f.inferred and request ~= nil then last.inferred = { request.start, request.quantity } end
  end
  return put_flat(st, head_slot(KIND_NUMBER[f.kind], f.slave, f.fn, f.length), f.at, f.number, f.offset,
    f.record, f.time, crc_slot(f.crc_expected, f.crc), span_slot(f.quantity, f.start), regs, coils, link,
    request_time, last)
end

local function expand_flat(st, k)
  local f, link, request_time = expand_slots(st.flat, k)
  f.kind = NUMBER_KIND[f.kind]
  local rare = f.span_label
  if type(rare) == "table" then f.span_label = rare.span_label else rare = nil end
  if link ~= nil then
    if link > 0 then
      f.request = { record = link, time = request_time }
    else
      f.response = { record = -link }
    end
  end
  if rare ~= nil then
    for index = 1, #RARE do
      local key = RARE[index]
      local kept = rare[key]
      if kept ~= nil then f[key] = kept end
    end
    if f.registers ~= nil then f.registers.status, f.registers.plain = rare.status, rare.plain end
    local inferred = rare.inferred
    if inferred ~= nil and f.request ~= nil then
      f.request.start, f.request.quantity, f.request.fn, f.inferred = inferred[1], inferred[2], f.fn, true
    end
  end
  return f
end

-- The item as the display reads it: a new table (an item never packed is itself).
function pack.expand(p, st)
  if type(p) == "number" then return expand_flat(st, p) end
  if p.kind ~= nil then return p end
  return { kind = NOISE, at = p[2], length = p[3], number = p[4], offset = p[5], record = p[6], time = p[7],
    reason = p[8], raw = p[9], count = p[10] }
end

-- The time of a record the quick lanes took (lane.again): its one frame's (packed, or awaiting its answer).
function pack.record_time(st, record)
  if type(record) == "number" then return st.flat[record + DATA.pack.time] end
  return type(record) == "table" and record[1] ~= nil and pack.expand(record[1], st).time
end

-- After a record is shown on the first pass: pack the items taken since, but the request still
-- awaiting its answer (pairing and the end of the capture change it; the display knows it as itself).
function pack.settle(st)
  local list = st.unpacked
  local whole = st.whole_record -- a record of one frame (dissect_record's fast lane)
  if whole ~= nil then
    st.whole_record = nil
    local item = whole[1]
    if item == st.pending then
      local count = #list
      list[count + 1], list[count + 2] = whole, 1 -- (packed once answered, with the others)
      if count == 0 then return end -- (nothing else waits: the pending request stays)
    elseif st.records[item.record] == whole then
      st.records[item.record] = pack_item(st, item) -- (the record is closed and holds this frame alone)
    else
      whole[1] = pack_item(st, item)
    end
  end
  if list[1] == nil then return end
  local kept = 0
  for index = 1, #list, 2 do
    local record, at = list[index], list[index + 1]
    local item = record[at]
    if item == st.pending then
      list[kept + 1], list[kept + 2] = record, at
      kept = kept + 2
    else
      local packed, number = pack_item(st, item), item.record
      record[at] = packed
      -- A closed record that is one packed frame and nothing else is kept as that number itself. (A closed
      -- record has no byte left to frame: the end of the capture adds nothing to it.)
      if type(packed) == "number" and record[2] == nil and next(record, 1) == nil and st.records[number] == record then
        st.records[number] = packed
      end
    end
  end
  for index = #list, kept + 1, -1 do list[index] = nil end
end

-- A record decoded again into the state `fresh` by decode(...) (a failure kept as the record's error, shown
-- there), its items packed (vw3.records' lane.again, vw3.dissector's decode_again).
function pack.redo(fresh, number, bytes, decode, ...)
  local ok, result = pcall(decode, ...)
  if not ok then result = { length = #bytes, error = tostring(result) } end
  fresh.records[number] = result
  if fresh.whole_record ~= nil or fresh.unpacked[1] ~= nil then pack.settle(fresh) end
end

-- The state `fresh` takes st's place (the same table: `state` and udp_states keep naming it).
function pack.take_place(st, fresh)
  for key in pairs(st) do st[key] = nil end
  for key, value in pairs(fresh) do st[key] = value end
end
