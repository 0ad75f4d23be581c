-- vw3.pack: what a record keeps of its frames for the later passes, packed (no Python counterpart: the plugin keeps every record for Wireshark's later dissections).
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.pack"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)

-- What a record keeps of a frame for the later passes, packed: numbers, ITEM slots of one flat array per
-- stream (st.flat), the item being the number of its first slot. A table with named keys keeps the hash
-- it grew to while the frame was decoded (some 25 keys, 1.3 KB); numbers are no objects: the collector
-- goes over the array's slots in one sweep instead of following a table (or two, or three) a frame, and
-- its 13 slots take some 200 bytes. Small numbers share a slot (a double holds 53 bits exactly): a slot
-- written costs more than the arithmetic that fills it. A missing value is false. Requests and responses
-- name each other by record (and the request's time): no links between kept tables. The keys a frame
-- holds rarely are kept in a table in its last slot (with its span label). The display unpacks a frame
-- each time it shows it. A key the display reads must have a slot or be in RARE: one missing shows only
-- from the second pass on (`tshark -2`, which the parity tests run).
local pack = {}
local RARE = { "warnings", "notes", "unanswered", "broadcast", "no_request", "malformed", "function_text",
  "exception_code", "exception_meaning", "subfunction", "subfunction_text", "objects", "server", "ascii",
  "raw", "inferred", "profile_choice", "profile_said", "provisional" }
local KIND_NUMBER = { [REQUEST] = 1, [RESPONSE] = 2, [EXCEPTION] = 3 }
local NUMBER_KIND = { REQUEST, RESPONSE, EXCEPTION }
local ITEM = 13

-- Does the frame hold a rare key, or a run one (a status other than ok, a register read with its plain
-- layout)? (one expression, made from RARE: no loop a frame; a rare key is never false: its truth is
-- the test)
local tests = { "f.registers and (f.registers.status or f.registers.plain)" }
for index = 1, #RARE do tests[#tests + 1] = "f." .. RARE[index] end
local has_rare = assert(load("return function(f) return " .. concat(tests, " or ") .. " end"))()

-- Slots: kind, slave, function and length; at; number; offset; record; time; CRC and expected CRC; start
-- and quantity; the register run; the bit run; the request's record (or minus the response's); the
-- request's time; span label (or the table of the rare keys and the span label). A missing start, quantity or run start is 0 and the others are one more
-- than they are.
local SHORT = 65536 -- (the runs' first byte and count: frame indices, under 65,536 in any frame)

-- A register run's slot: its first byte, count and start (nil: none).
local function run_slot(first, count, start)
  if start == nil then start = 0 else start = start + 1 end
  return first + SHORT * (count + SHORT * start)
end

-- A bit run's slot: its first byte, count, start and single coil's value (nil: none).
local function bit_slot(first, count, start, single)
  if start == nil then start = 0 else start = start + 1 end
  if single == nil then single = 0 else single = single + 1 end
  return first + SHORT * (count + SHORT * (start + 65537 * single))
end

-- The shared slots: kind, slave, function and length; the CRC and the expected CRC; start and quantity
-- (each one more than it is, 0 for none: 16-bit fields).
local function head_slot(kind, slave, fn, length) return kind + 4 * (slave + 256 * (fn + 256 * length)) end
local function crc_slot(crc, expected) return crc * SHORT + expected end
local function span_slot(start, quantity)
  if start == nil then start = 0 else start = start + 1 end
  if quantity == nil then quantity = 0 else quantity = quantity + 1 end
  return start * 65537 + quantity
end

-- Write a frame's 13 slots (the order expand_flat reads them in); time, request_time and label nil when
-- missing, regs and bits a run's slot or false, link the request's record, minus the response's, or false.
local function put_flat(st, head, at, number, offset, record, time, crcs, span, regs, bits, link, request_time,
    label)
  if time == nil then time = false end
  if request_time == nil then request_time = false end
  if label == nil then label = false end
  local flat, k = st.flat, st.flat_n
  -- (one statement a slot, in order: a multiple assignment stores its last target first, past the end
  -- of the array part, where the key goes to the hash part until the table is rebuilt)
  flat[k + 1] = head; flat[k + 2] = at; flat[k + 3] = number; flat[k + 4] = offset; flat[k + 5] = record
  flat[k + 6] = time; flat[k + 7] = crcs; flat[k + 8] = span; flat[k + 9] = regs; flat[k + 10] = bits
  flat[k + 11] = link; flat[k + 12] = request_time; flat[k + 13] = label
  st.flat_n = k + ITEM
  return k
end

-- An answer of the quick lane (lane.answer): a response with a good CRC, at the start of its own
-- record, whose registers (or bits) are a run from its fourth byte and whose request is in record `link`.
function pack.answer(st, slave, fn, length, number, offset, record, time, crc, start, quantity, count, link,
    request_time, label, bits)
  local registers, coils = false, false
  if bits then coils = bit_slot(3, count, start, nil) else registers = run_slot(3, count, start) end
  return put_flat(st, head_slot(2, slave, fn, length), 0, number, offset, record, time, crc_slot(crc, crc),
    span_slot(start, quantity), registers, coils, link, request_time, label)
end

-- A request of the quick lanes (lane.request, lane.write), answered in the quick lane (lane.answer): its
-- slots but its number, offset, record, time and CRC come from its entry in known_requests (the same for
-- every request with its bytes, or its bytes before the values), made once; false when such a request
-- holds a rare key (a name of the device's own: packed by pack.settle).
local function entry_slots(known, n, slave, fn)
  local slots = known.slots
  if slots ~= nil then return slots end
  slots = false
  local registers, bits = known.registers, known.bits
  if known.function_text == nil then
    slots = { head_slot(1, slave, fn, n), span_slot(known.start, known.quantity),
      registers ~= nil and run_slot(registers.first, registers.count, registers.start) or false,
      bits ~= nil and bit_slot(bits.first, bits.count, bits.start, bits.single) or false,
      known.span_label or false }
  end
  known.slots = slots
  return slots
end
pack.entry_slots = entry_slots

-- The request's flat item.
function pack.answered_request(st, f, slots, response_record)
  return put_flat(st, slots[1], 0, f.number, f.offset, f.record, f.time, crc_slot(f.crc, f.crc_expected), slots[2],
    slots[3], slots[4], -response_record, nil, slots[5])
end

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
    f.record, f.time, crc_slot(f.crc, f.crc_expected), span_slot(f.start, f.quantity), regs, coils, link,
    request_time, last)
end

local function value(x)
  if x == false then return nil end
  return x
end

-- n split into its low part (below `base`) and the rest (math.floor: integers on Lua 5.4, as they were)
local function split(n, base)
  local low = n % base
  return low, floor((n - low) / base)
end

-- one more than a value, or 0: the value, or nil
local function less_one(n)
  if n == 0 then return nil end
  return n - 1
end

local function expand_flat(st, k)
  local flat = st.flat
  local kind, rest = split(flat[k + 1], 4)
  local slave, fn
  slave, rest = split(rest, 256)
  fn, rest = split(rest, 256)
  local crc, crc_expected = flat[k + 7], nil
  crc_expected, crc = split(crc, SHORT)
  local quantity, start = split(flat[k + 8], 65537)
  local f = { kind = NUMBER_KIND[kind], at = flat[k + 2], length = rest, number = flat[k + 3],
    offset = flat[k + 4], record = flat[k + 5], time = value(flat[k + 6]), slave = slave,
    fn = fn, crc = crc, crc_expected = crc_expected, start = less_one(start),
    quantity = less_one(quantity), span_label = value(flat[k + 13]) }
  local rare = f.span_label
  if type(rare) == "table" then f.span_label = rare.span_label else rare = nil end
  local regs = flat[k + 9]
  if regs ~= false then
    local first, count, run_start
    first, rest = split(regs, SHORT)
    count, run_start = split(rest, SHORT)
    f.registers = { first = first, count = count, start = less_one(run_start) }
  end
  local bits = flat[k + 10]
  if bits ~= false then
    local first, count, run_start, single
    first, rest = split(bits, SHORT)
    count, rest = split(rest, SHORT)
    run_start, single = split(rest, 65537)
    f.bits = { first = first, count = count, start = less_one(run_start), single = less_one(single) }
  end
  local link = flat[k + 11]
  if link ~= false then
    if link > 0 then
      f.request = { record = link, time = value(flat[k + 12]) }
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

-- A closed record that is one packed frame and nothing else is kept as that number itself. (A closed
-- record has no byte left to frame: the end of the capture adds nothing to it.)
local function as_number(st, record, number, packed)
  if record[2] == nil and next(record, 1) == nil and st.records[number] == record then
    st.records[number] = packed
  end
end

-- The item as the display reads it: a new table (an item never packed is itself).
function pack.expand(p, st)
  if type(p) == "number" then return expand_flat(st, p) end
  if p.kind ~= nil then return p end
  return { kind = NOISE, at = p[2], length = p[3], number = p[4], offset = p[5], record = p[6], time = p[7],
    reason = p[8], raw = p[9], count = p[10] }
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
      local packed = pack_item(st, item)
      record[at] = packed
      if type(packed) == "number" then as_number(st, record, item.record, packed) end
    end
  end
  for index = #list, kept + 1, -1 do list[index] = nil end
end

M.pack = pack
