-- vw3.records: one record: framed, paired, decoded and annotated in order; the quick lanes.
-- Mirrors dissector/pipeline.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.records"]).

local take_items, dissect_record
-- A run of a known request, for one frame (runs change with their frame: released, packed).
-- (b: the frame's bytes, else the run's)
local function copy_run(run, b)
  if run == nil then return nil end
  return { b = b or run.b, first = run.first, count = run.count, start = run.start, shift = nil, single = run.single }
end

-- Pair, decode and annotate a frame just numbered; the device it was annotated with.
local function take_frame(st, item, whole)
  pair(st, item)
  -- (how many notes pairing gave: the capture end's note goes after them, before decoding's, as the
  -- Python pipeline's pairer finishes before decode_frame; the display puts it there)
  if item.notes ~= nil then item.paired_notes = #item.notes end
  local gaps = item.gaps -- (silences inside the frame, vw3.stream's inner_gaps: after the pairing's warnings)
  if gaps ~= nil then
    for index = 1, #gaps do warn(item, gaps[index]) end
    item.gaps = nil
  end
  decode_frame(item)
  local device = device_now(st, item, item.b)
  annotate_with(st, item, item.b, device)
  check_references(item, device) -- (a map written in PLC references, judged on the slave's first frames)
  -- What the display does not need is dropped (the record is kept for every later pass): the byte
  -- table (the display reads the tvb) and the decoded fields once nothing can ask for them (a
  -- request's, until its answer is decoded or it can have none). (Warnings and notes are lists made
  -- with their first entry: none is empty.)
  -- The request it answers may have come through the stream's buffer: its registers are released.
  local request = item.request
  if request ~= nil then
    request.fields = nil
    release_run(request.registers)
  end
  -- A record's one frame (whole) is copied by pack.settle, which takes none of these keys (and its
  -- indices are the frame's own already); a request awaiting its answer keeps its byte table until then.
  if whole then return device end
  item.b = nil
  -- Indices into the frame's own bytes from now on (the display rebuilds them from the tvb; a
  -- pending request's registers once its answer has been read), and what is known from the kind of
  -- frame dropped: a record keeps fewer keys (Lua tables grow by powers of two).
  local bi = item.bi
  if item.registers ~= nil then item.registers.shift = bi end
  if item.bits ~= nil then
    item.bits.shift = bi
    release_run(item.bits)
  end
  local objects = item.objects
  if objects ~= nil then
    for at = 1, #objects do objects[at].offset = objects[at].offset - bi end
  end
  item.bi, item.data_at, item.data_len = nil, nil, nil
  if item.kind ~= REQUEST or st.pending ~= item then
    item.fields = nil
    release_run(item.registers)
  end
  return device
end

-- Requests met before, by their bytes: a polling master sends the same requests every cycle, and what
-- decoding and the device make of a request depends on its bytes and the device alone. An entry holds
-- the frame's decoded fields, runs, device texts and Info text, and the device they were made with
-- (remember_request makes them, the quick lanes of requests use them). Bounded: a new table after MAX entries.
local known_requests = { entries = {}, headers = {}, count = 0, MAX = 4096 }

-- Requests that write a block of values (FC15, FC16, FC23), by the length of their bytes before the values
-- (DATA.lanes, codegen/lanes_lua.py): decoded from those bytes alone (the values are a run read when shown).
-- A master writes its setpoints every cycle with new values.
known_requests.header_lengths = DATA.lanes.header_lengths

-- Does the device annotate a request's registers (annotate_registers, not reading: only those under a
-- layout rule, which may be noted)?
local function follows_registers(device, run)
  if run == nil or run.start == nil then return false end
  local depend = device.depend
  if next(depend) == nil then return false end
  for index = 0, run.count - 1 do
    if depend[(run.start + index) % 0x10000] ~= nil then return true end
  end
  return false
end

-- Keep a request of one record for the next time its bytes come (see known_requests): one whose
-- decoding and annotation said nothing but its fields and device texts, which nothing else than its
-- bytes and device made (no registers annotated: those under a device's layout rules may be noted).
-- A request that writes is kept by its bytes before the values too (known_requests.headers, for
-- lane.request, which looks at the layout rules again), even where it writes registers under one.
-- Not a provisional one: its Info text says so, the lanes take a request of a settled slave.
local function remember_request(bytes, item, device)
  if item.kind ~= REQUEST or item.slave == 0 or not device or item.warnings or item.notes or item.malformed
      or item.profile_choice or item.subfunction or item.objects or item.crc ~= item.crc_expected
      or item.provisional then
    return
  end
  local header = known_requests.header_lengths[item.fn]
  if header ~= nil and #bytes <= header then header = nil end
  local by_bytes = not follows_registers(device, item.registers)
  if header == nil and not by_bytes then return end
  if known_requests.count >= known_requests.MAX then
    known_requests.entries, known_requests.headers, known_requests.count = {}, {}, 0
  end
  local info = item.info
  if info == nil and summary ~= nil then info = summary(item, nil, nil, device) end -- (nil: loaded without Wireshark)
  item.info = info
  local entry = {
    device = device, crc = item.crc, b = item.b, fields = item.fields, start = item.start,
    quantity = item.quantity, registers = copy_run(item.registers), bits = copy_run(item.bits),
    function_text = item.function_text, span_label = item.span_label, info = info, length = #bytes,
  }
  if by_bytes then
    known_requests.count = known_requests.count + 1
    known_requests.entries[bytes] = entry
  end
  if header ~= nil then
    local key = bytes:sub(1, header)
    local known = known_requests.headers[key]
    if known == nil or known.device ~= device then
      known_requests.count = known_requests.count + 1
      known_requests.headers[key] = entry
    end
  end
end

-- An item's bytes, before take_items drops the tables they are read from.
local function raw_of(item)
  if item.kind == NOISE then return string_of(item.bytes, 1, item.length) end
  if item.ascii then return string_of(item.src, item.src_at, item.length) end
  return string_of(item.b, item.bi, item.length)
end

-- Number, pair, decode and annotate the items the framer gave out while `record` was fed. Each is shown
-- in the record that holds its last byte (the framer may have needed later bytes to decide; Wireshark's
-- later passes show it there): through that record's bytes when they hold it whole, else through its
-- own bytes (a frame or noise run that began in earlier records, which say where it went).
-- showing: `record` is being dissected for the first time. An item it decided whose bytes are all in
-- earlier records (noise known as such only once later bytes came) is kept in the earliest record that
-- shows it on the later passes, but that one has been shown already, once and for all in tshark's one
-- pass: it is shown in `record` too, this time only (st.late, show.lua show_record), from its own bytes,
-- with the records they came from.
take_items = function(st, items, record, showing)
  local open = st.open
  for index = 1, #items do
    local item = items[index]
    st.count = st.count + 1
    item.number = st.count
    local offset, length = item.offset, item.length
    -- (the open records holding its bytes, open[oldest .. holding]: ascending, so the search stops past its end)
    local oldest, holding = nil, 0
    for at = 1, #open do
      local earlier = open[at]
      if earlier.start >= offset + length then break end
      if earlier.start + earlier.length > offset then oldest, holding = oldest or at, at end
    end
    local home = open[holding] -- (the one holding its last byte, else `record`)
    if home == nil or home.start + home.length < offset + length then home = record end
    item.record = home.number
    if showing and home ~= record then
      local from = {} -- (the numbers of the records holding its bytes, in order)
      for at = oldest, holding do from[#from + 1] = open[at].number end
      local late = st.late
      if late == nil or late.record ~= record then
        late = { record = record }
        st.late = late
      end
      late[#late + 1] = { item = item, raw = raw_of(item), from = from }
      item.late_in = record.number -- (where a frame that links to it finds it on that showing; not packed)
    end
    local first = home.start or offset -- (a closed record holds no bytes still to frame)
    local last = home[#home]
    local inside = offset >= first and offset + length <= first + (home.length or length)
    if inside then
      item.at = offset - first
      if item.kind == NOISE and type(last) == "table" and last.kind == NOISE and last.raw == nil
          and last.length == length and last.reason == item.reason and last.time == item.time then
        -- The same noise again right after (a flood of ':' in ASCII mode is an item a byte, as
        -- vw3-decode shows it): one entry for the run, shown item by item (show_record).
        local count = last.count or 1
        local span = count * length
        if last.number + count == item.number and last.at + span == item.at and last.offset + span == offset then
          last.count = count + 1
          item = nil
        end
      end
    else
      item.at = 0
      item.raw = raw_of(item)
      for at = oldest or 1, holding do
        local earlier = open[at]
        local from, to = earlier.start, earlier.start + earlier.length
        if earlier ~= home then
          earlier.continued = earlier.continued or {}
          earlier.continued[#earlier.continued + 1] = {
            item = item.number, record = home.number, count = math.min(to, offset + length) - math.max(from, offset),
            noise = item.kind == NOISE or nil, -- (bytes that continue no frame: the display says noise)
          }
        end
      end
    end
    if item ~= nil then
      home[#home + 1] = item -- (a record holds its items in its array part: one table fewer a record)
      local unpacked = st.unpacked
      unpacked[#unpacked + 1], unpacked[#unpacked + 2] = home, #home
      item.bytes, item.src = nil, nil
      if item.kind ~= NOISE then take_frame(st, item) end
    end
  end
  -- Records all of whose bytes are framed are done with; the others say how many of their bytes wait.
  local waiting_from = st.base
  if st.noise ~= nil then waiting_from = st.noise.offset end
  if showing then
    -- How many of the record's waiting bytes are noise already (a run that goes on: its end is not known),
    -- which its first dissection says rather than that they continue a frame (show_record).
    local stop = record.start + record.length
    st.noise_for, st.noise_waiting = record, math.max(0, math.min(st.base, stop) - math.max(waiting_from, record.start))
  end
  -- (ascending: the records all of whose bytes are framed come first; from the first that starts at or after
  -- waiting_from, every byte waits, as since it was opened with waiting = length)
  local closed = 0
  for index = 1, #open do
    local earlier = open[index]
    local waiting = earlier.start + earlier.length - waiting_from
    if waiting > 0 then
      if earlier.start >= waiting_from then break end
      earlier.waiting = math.min(waiting, earlier.length)
    else
      -- closed: all its bytes are framed (kept: its items and frame count)
      earlier.waiting, earlier.start, earlier.length, earlier.number = nil, nil, nil, nil
      closed = index
    end
  end
  if closed > 0 then drop_first(open, closed) end
end

-- The functions whose answer is a run of the registers or bits its request asked for, from its fourth byte:
-- whether bits, the extra of its length rule (its byte count plus that), the count's unit (DATA.lanes); and
-- the frame the Info text of a quick answer is made from.
local RUN_ANSWERS = DATA.lanes.run_answers
local ANSWER = { kind = RESPONSE, fn = 0, slave = 0, start = 0, quantity = 0, crc = 0, crc_expected = 0 }
local LANE_VALUES, LANE_LASTS = {}, {}

-- The quick lane of answers (see lane.decode): a record that is the usual answer to the request awaited (a
-- run of registers or bits whose byte count agrees with the request, on time, from a device that notes
-- nothing about them and has no name of its own for the function) is framed, paired, annotated and kept
-- as dissect_record, take_frame and pack.settle would do it, without a byte table, frame table or fields.
-- Returns the item kept and its Info text; nil, with nothing changed, for any other record.
function lane.answer(st, bytes, n, time, number, slave, code, quiet)
  local byte = string.byte
  local pending = st.pending
  local run, count = RUN_ANSWERS[code], byte(bytes, 3)
  if pending.slave ~= slave or pending.fn ~= code or run == nil then return nil end
  -- framed by its length rule, its CRC good
  if n ~= run.extra + count or not whole_crc_good(bytes, n) then return nil end
  -- pair: on time (else the request went unanswered)
  local timeout, asked = st.timeout, pending.time
  if timeout ~= nil and time ~= nil and asked ~= nil and (time - asked) / 1e9 > timeout then return nil end -- (ns)
  -- the lifting rules of read_registers_response, read_bits_response: the request's start and quantity, its
  -- byte count agreeing
  if pending.fields == nil then return nil end
  local start, quantity = pending.start, pending.quantity -- (the window its rule lifted: FC23's read window)
  if start == nil or quantity == nil then return nil end
  local bits = run.bits
  if count ~= data_bytes(quantity, run.unit) then return nil end
  -- (bits set past the quantity in the last byte draw a warning: data/modbus.toml [lift] padding)
  if bits and quantity % 8 > 0 and byte(bytes, 3 + count) >= 2 ^ (quantity % 8) then return nil end
  -- annotate_with: nothing but the registers' bookkeeping
  local device = device_for(st, slave)
  -- (its frames judged: check_references, take_frame; input rows apart: named by their table there)
  if not device or device.refs_open or device.inputs ~= nil then return nil end
  local profile = device.profile
  if profile.function_names[code] ~= nil then return nil end
  -- annotate_registers: every register the usual one (not 16#8000, under no layout rule, read before with a
  -- value where 16#8000 is followed), which is only noted as read
  local protected = nil
  if READS[code] ~= nil then protected = profile.protected_value end
  local depend, seen = device.depend, device.seen
  local follow = not bits and quantity > 0 and (protected ~= nil or next(depend) ~= nil)
  local values, lasts = LANE_VALUES, LANE_LASTS -- (each register's value and history, for the changes below)
  if follow then
    for index = 0, quantity - 1 do
      local high, low = byte(bytes, 4 + 2 * index, 5 + 2 * index)
      local address, value = (start + index) % 0x10000, high * 256 + low
      if value == protected or depend[address] ~= nil then return nil end
      if protected ~= nil then
        local last = seen[address]
        if last == nil or last.value == nil then return nil end
        values[index], lasts[index] = value, last
      end
    end
  end
  -- From here on the answer is taken: the same changes, in the same order, as the general path's.
  if quiet and quiet ~= true then quiet.answers, quiet.frames = quiet.answers + 1, quiet.frames + 1 end -- (lane.quiet)
  st.expect = nil -- (expect_after: an answer awaits nothing)
  local offset, item = lane.advance(st, n, time)
  -- (no record table for finish: the stream waits for no byte, and an answer awaits nothing)
  st.last = nil
  st.pending = nil
  local writes = pending.registers
  if device.track and CONFIRMED.answer[code] and writes ~= nil and writes.count > 0 and writes.b ~= nil then
    remember_writes(seen, item, writes, writes.b)
  end
  if follow and protected ~= nil then
    -- (remember_writes changed these tables in place, if any: none was missing)
    for index = 0, quantity - 1 do
      local last = lasts[index]
      last.value, last.frame, last.how = values[index], item, "read"
    end
  end
  release_run(writes)
  -- The request, packed now where it came through the quick lane and waits at the end of the list
  -- pack.settle packs (as_number: its record holds it alone); else it is linked to this record.
  local slots = pending.slots
  local list = st.unpacked
  local last = #list
  local request_record = list[last - 1]
  if slots and last >= 2 and list[last] == 1 and request_record[1] == pending and request_record[2] == nil
      and st.records[pending.record] == request_record then
    local packed = put_flat(st, slots[1], 0, pending.number, pending.offset, pending.record, pending.time,
      crc_slot(pending.crc_expected, pending.crc), slots[2], slots[3], slots[4], -number, nil, slots[5])
    list[last], list[last - 1] = nil, nil
    request_record[1] = packed
    st.records[pending.record] = packed
    local spare, spare_records = lane.spare, lane.spare_records
    if #spare < 4 then spare[#spare + 1] = pending end
    if #spare_records < 4 then spare_records[#spare_records + 1] = request_record end -- (its record too)
  else
    pending.response = { record = number }
  end
  -- What is the same for every answer of the device's function and read window, made once, bounded:
  -- its Info text, span label (PLC-style devices: 4X numbers; false: none) and the slots it is kept in but
  -- those of its place, time and CRC (as pack.settle keeps it: a response at the start of its own record,
  -- whose registers, or bits, are a run from its fourth byte).
  local key = (code * 65536 + start) * 65536 + quantity
  local infos = device.lane_infos
  if infos == nil or infos.count >= 256 then
    infos = { count = 0 }
    device.lane_infos = infos
  end
  local same = infos[key]
  if same == nil then
    ANSWER.fn, ANSWER.slave, ANSWER.start, ANSWER.quantity, ANSWER.span_label = code, slave, start, quantity, nil
    if device.plc ~= nil then lane.span_label(ANSWER, device) end
    local registers, coils = false, false
    if bits then coils = bit_slot(3, quantity, start, nil) else registers = run_slot(3, quantity, start) end
    same = { summary(ANSWER), ANSWER.span_label or false, head_slot(KIND_NUMBER[RESPONSE], slave, code, n),
      span_slot(quantity, start), registers, coils }
    infos[key], infos.count = same, infos.count + 1
  end
  -- Kept with its request in record pending.record, its CRC good.
  local crc_low, crc_high = byte(bytes, n - 1, n)
  local crc = crc_low + crc_high * 256
  return put_flat(st, same[3], 0, item, offset, number, time, crc_slot(crc, crc), same[4], same[5], same[6],
    pending.record, asked, same[2]), same[1]
end

-- The quick lane of requests (see lane.decode): a record that is a request met before (known_requests: by
-- its bytes, or, a request that writes (FC15, FC16, FC23 by the protocol table), by its bytes before the
-- values), for the device it was met with, is framed, paired and decoded as feed_whole, dissect_record and
-- take_frame would do it, in one table. A request known by its bytes before the values has its CRC
-- checked and its runs read from its own bytes, and goes the general path where a register it writes is
-- under a layout rule that holds now (annotate_one would note it).
-- Returns the record, as dissect_record does (shown and kept by dissect_records as such), and its Info
-- text; nil, with nothing changed, for any other record.
lane.spare, lane.spare_records = {}, {}
function lane.request(st, bytes, n, time, number, slave, code, quiet)
  local byte = string.byte
  local known = known_requests.entries[bytes]
  local own = known == nil -- (its own values: known by its bytes before them)
  if own then
    local header = known_requests.header_lengths[code]
    if header == nil or n <= header then return nil end
    known = known_requests.headers[bytes:sub(1, header)]
    if known == nil or known.length ~= n then return nil end
  end
  local device = known.device
  if device_for(st, slave) ~= device or device.refs_open or device.inputs ~= nil then return nil end
  if own then
    local registers = known.registers
    if registers ~= nil and next(device.depend) ~= nil then
      local rows, plain_rule = device.rows, story.plain_rule
      for index = 0, registers.count - 1 do
        local address = (registers.start + index) % 0x10000
        if plain_rule(device, address, rows[address]) ~= nil then return nil end
      end
    end
    if not crc_string_ok(bytes, n) then return nil end
  end
  -- Taken: the same changes as the general path's (the stream, the count, profile auto's count, the frame
  -- decoded as its entry says, awaiting its answer alone in its record, packed by pack.settle).
  if quiet and quiet ~= true then quiet.frames = quiet.frames + 1 end -- (counted as observe does: lane.quiet)
  st.expect = slave * 256 + code -- (expect_after: a request's code is its function)
  local offset, count = lane.advance(st, n, time)
  -- The frame framing finds (the request's layout is the likeliest; its length and CRC checked when it
  -- was met), decoded as its entry says. A frame of the quick lanes packed once answered (lane.answer) is
  -- held by nothing else: it is taken again here, every key set anew, so that a polling bus makes no
  -- table a request (lane.spare, a few at most).
  local spare = lane.spare
  local f = spare[#spare]
  if f == nil then
    -- (the keys below made at once, as the constructor sizes them)
    f = { kind = 0, offset = 0, length = 0, slave = 0, fn = 0, crc = 0, crc_expected = 0, time = 0, b = 0, bi = 0,
      data_at = 0, data_len = 0, number = 0, record = 0, at = 0, fields = 0, start = 0, quantity = 0, registers = 0,
      bits = 0, request = 0, response = 0, function_text = 0, span_label = 0, info = 0, slots = 0 }
  else
    spare[#spare] = nil
  end
  local b, crc = nil, known.crc
  if own then
    local crc_low, crc_high = byte(bytes, n - 1, n)
    b, crc = { [0] = slave, byte(bytes, 2, n) }, crc_low + crc_high * 256
  end
  f.kind, f.offset, f.length, f.slave, f.fn, f.crc, f.crc_expected, f.time = REQUEST, offset, n, slave, code, crc, crc,
    time
  f.b, f.bi, f.data_at, f.data_len, f.number, f.record, f.at = b or known.b, 0, 2, n - 4, count, number, 0
  if ECHO_CODES[code] then await_echo(st, f) end -- (what its answer must repeat, an FC8 sub-function)
  await_answer(st, f) -- (the length of its answer, as vw3.stream's expect_after keeps it)
  f.fields, f.start, f.quantity, f.request, f.response = known.fields, known.start, known.quantity, nil, nil
  f.registers, f.bits = copy_run(known.registers, b), copy_run(known.bits, b)
  f.function_text, f.span_label, f.info = known.function_text, known.span_label, known.info
  local slots = known.slots
  if slots == nil then
    -- The slots of such a request but its number, offset, record, time and CRC (lane.answer packs it with
    -- them), made once for its entry when the lane first takes it (most entries of a mix of random
    -- requests never are); false where it holds a rare key (a name of the device's own: pack.settle).
    local registers, bits = known.registers, known.bits
    slots = known.function_text == nil and {
      head_slot(KIND_NUMBER[REQUEST], slave, code, n),
      span_slot(known.quantity, known.start),
      registers ~= nil and run_slot(registers.first, registers.count, registers.start) or false,
      bits ~= nil and bit_slot(bits.first, bits.count, bits.start, bits.single) or false,
      known.span_label or false,
    }
    known.slots = slots
  end
  f.slots = slots
  st.pending = f
  local spare_records = lane.spare_records
  local record = spare_records[#spare_records]
  if record == nil then
    record = { f }
  else
    spare_records[#spare_records] = nil
    record[1] = f
  end
  st.last = record
  st.whole_record = record
  return record, f.info
end

local function cut_part(st, bytes, time, number, part) -- (captured in part: lua/src/stream.lua cut_stream, after a final run)
  local items = feed(st, "", nil, false, true)
  local record = cut_stream(st, bytes, time, part, number, items)
  take_items(st, items, record, true)
  return record, pair_part(st, items[#items]) -- (numbered, it may answer the request awaited: lua/src/pairing.lua)
end

dissect_record = function(st, bytes, time, number)
  local n = #bytes
  st.late = nil -- (the record before's, shown with it or never: the quick lanes show no tree)
  if st.mode == nil and n > 0 then st.mode = sample_mode(bytes, true) end -- (its bytes alone tell)
  local built = nil
  if st.open[1] == nil then
    -- A record that is one frame (take_items's work for it: the record closed, the frame at 0 in it)
    local frame
    frame, built = feed_whole(st, bytes, time)
    if frame ~= nil then
      local record = { frame }
      st.last = record
      frame.number, frame.record = st.count, number -- (counted by feed_whole)
      remember_request(bytes, frame, take_frame(st, frame, true))
      st.whole_record = record -- (packed by pack.settle; not when take_frame fails: the record is then an error)
      return record
    end
  end
  -- (four keys: a fifth would double the table's hash, and records stay for the whole capture)
  local record = { number = number, start = st.base + st.n, length = n, waiting = n }
  st.open[#st.open + 1] = record
  st.last = record
  take_items(st, feed(st, bytes, time, true, false, built), record, true)
  return record
end

-- The end of the capture: frame what still waits (as vw3-decode does at the end of its input), shown in
-- the last record. Called once, when the first pass is over.
local function finish(st)
  if st.finished then return end
  st.finished = true
  local record = st.last
  if record == nil then return end
  st.cut_by_silence = silent_at_end(st) -- (what it holds is cut by a silence before the end, or by the end)
  local items = feed(st, "", nil, false, true)
  st.cut_by_silence = nil
  for index = 1, #items do
    -- The answer awaited cut by the end of the capture: said on the request (model.py CUT_ANSWER).
    local reason, cut = items[index].reason, FRAMING.cut_answer
    if reason ~= nil and reason:sub(1, #cut) == cut then st.cut_note = reason end
  end
  take_items(st, items, record)
  if st.pending ~= nil then release_run(st.pending.registers) end
end

-- finish, a failure kept as the last record's error (shown there) rather than raised.
local function finish_safely(st)
  local ok, problem = pcall(finish, st)
  if not ok and st.last ~= nil then st.last.error = tostring(problem) end
end

-- A record's first decoding: the quick lanes, else the general path (dissect_record). A lane takes a
-- record framed as feed_whole frames it, one whole frame where no byte waits (lane.advance then leaves the
-- stream as feed_whole leaves it), where profile auto's choice is settled for its slave (device_now); the
-- answer's where a request awaits its answer (and the framer expects it), the requests' where none does.
-- lane.quick false (the `quick_lanes` preference, or VW3_QUICK_LANES = false set before loading): every
-- record the general path, which the quick lanes must equal (the parity tests run both).
lane.quick = VW3_QUICK_LANES ~= false
function lane.decode(st, bytes, n, time, number)
  local slave, code = string.byte(bytes, 1, 2)
  local answer = st.pending ~= nil
  if lane.parts[number] ~= nil then return cut_part(st, bytes, time, number, lane.parts[number]), n end
  if lane.quick and st.open[1] == nil and st.listening == nil and takes_whole(st, n, slave)
      and (st.expect == slave * 256 + code) == answer then
    local quiet = nil -- (what the lane counts the frame in; nil: profile auto is not in use for the slave)
    if config.auto[slave] then quiet = lane.quiet(st, slave, code, answer) end
    if quiet ~= false then
      local kept, info = (answer and lane.answer or lane.request)(st, bytes, n, time, number, slave, code, quiet)
      if kept ~= nil then return kept, n, info end
    end
  end
  return dissect_record(st, bytes, time, number), n
end

-- Profile `auto` over the whole capture (app/preselect.py, issue 27): once the first pass is over, a
-- slave's frames met before its choice (or before it was taken back) are decoded again, the whole
-- capture in order, with every slave's device the one chosen over the capture from its first frame
-- (annotations, statuses and the parameter story follow the device). Framing and pairing give the same
-- items again; only what the device says changes. `tshark -2` and Wireshark's later dissections then
-- show what vw3-decode shows reading a file; a single pass stays as vw3-decode reading a stream.
function lane.again(st)
  local again = st.again
  st.again = nil
  -- (nothing chosen after a slave's first frame, and no frame read before a choice could be made)
  if again == nil or (next(st.said) == nil and not st.provisional) then return end
  local fresh = new_state(st.timeout, st.mode)
  -- The frames packed anew go over the first decoding's slots, from the first (no second array as long
  -- held at the peak): each record's first decoding is dropped as it is decoded again, and none is read.
  fresh.flat = st.flat
  local frozen, chosen, history, fixed = {}, {}, {}, {}
  for number, reason in pairs(st.said) do frozen[number] = reason end
  local met = {} -- (every slave the first pass met: a broadcast reaches them all, the selection stage's broadcast_device)
  for slave, judged in pairs(st.judged) do
    met[slave] = true
    local choice = judged.choice
    if choice ~= nil and PROFILES[choice.profile] ~= nil then
      local device = build_device(PROFILES[choice.profile], slave)
      chosen[slave], fresh.devices[slave], fixed[slave] = choice.profile, device, true
      history[slave] = { { number = 0, device = device, reason = choice.reason } }
    end
  end
  -- (the other slaves are judged again as they come: more records may follow in a live capture)
  fresh.frozen, fresh.chosen, fresh.history, fresh.fixed, fresh.met = frozen, chosen, history, fixed, met
  local records, kept = st.records, again.bytes
  -- So do the records, each over its first decoding (a record the first pass kept no bytes of goes, as it
  -- would from a new table): no second table as long held at the peak.
  fresh.records = records
  for number in pairs(records) do
    if kept[number] == nil then records[number] = nil end
  end
  -- Each record decoded again makes its first decoding garbage, one for one: meanwhile the collector starts
  -- its next cycle at once (the pause lua/src/crc.lua sets let that garbage grow the heap by half what stays),
  -- from a heap without the first pass's garbage (a pause takes effect when a cycle ends).
  local paused, pause = pcall(collectgarbage, "setpause", 100)
  collectgarbage("collect")
  -- The records in number order, the order of their first dissection (a first pass reads the capture in
  -- order): no list of that order kept a record.
  local first, last, times = math.huge, 0, again.times
  for number in pairs(kept) do
    if number < first then first = number end
    if number > last then last = number end
    -- (its time over its first decoding, no table more: kept, or its quick lane frame's, read before any is packed)
    local time = times[number]
    if time == nil then time = pack.record_time(st, records[number]) or false end
    records[number] = time
  end
  for number = first, last do
    local bytes = kept[number]
    if bytes ~= nil then -- (over its first decoding, which is done with)
      pack.redo(fresh, number, bytes, lane.decode, fresh, bytes, #bytes, records[number] or nil, number)
      kept[number] = nil
    end
  end
  if paused then collectgarbage("setpause", pause) end
  fresh.late = nil -- (what the last record decided for earlier ones: shown already, on its first showing)
  finish_safely(fresh)
  -- Records read after this (Wireshark's packet details opened during a live capture) are read once, as
  -- vw3-decode --live reads them: a frame of a slave still judged is provisional again.
  fresh.going_on = true
  pack.take_place(st, fresh)
end
M.dissect_record, M.finish = dissect_record, finish -- (the pure part's entry points: main.lua)
