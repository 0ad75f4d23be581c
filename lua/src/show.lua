-- vw3.show: Wireshark: a frame's item and a record's items shown, a record's first dissection, the first pass's end.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.show"]).
local UNMATCHED = say("unmatched", {}) -- (data/modbus.toml [texts])
-- The window's start or quantity (what) on the bytes its lifting rule read it from; generated and on no
-- bytes where the frame does not hold it (a read's answer: its request's; FC5's and FC6's quantity of one).
local function add_window(t, tvb, f, field, what, value)
  local entry = f.kind ~= EXCEPTION and DATA.rules.by_code[f.kind][f.fn]
  local rule = entry and DATA.rules.lift[entry.rule]
  local place = rule and type(rule[what]) == "string" and DATA.field_places[entry.layout][rule[what]]
  if not (place and place.size) then return t:add(field, tvb:range(f.at, 0), value):set_generated() end
  local item, name = t:add(field, frame_range(tvb, f, place.at, place.size), value), rule[what]
  -- (named as vw3-decode -V names the PDU field where it is not the window's own: FC23's `Read start`)
  if name ~= what then item:set_text(name:sub(1, 1):upper() .. name:sub(2):gsub("_", " ") .. ": " .. value) end
  return item
end

-- The addresses a frame names without carrying their values (a read request's window, FC15's and FC16's
-- answers, FC22, FC23's read window and its request's written window where it writes none, as FC16's of
-- quantity 0: its lifting rule's write_window), each a hidden vw3.reg.address (vw3.bit.address: a coil function's),
-- as Wireshark's hidden ip.addr: `vw3.reg.address == 8401` finds the request that asked for 8401 too, as
-- vw3-decode's `address == 8401` (the same addresses: render/filter_match.py item_elements, at most 2000).
-- (BIT_WINDOW[fn]: its request or answer carries bits, its lifting rule's values "bits" or "coil";
-- DATA.bit_windows, codegen/display_lua.py)
local BIT_WINDOW = DATA.bit_windows

-- A PLC-style device's (base: its PLC base) register addresses carry their label too, a hidden vw3.reg.label
-- as a register of the window has it: `vw3.reg.label == "40102"` finds the request, as vw3-decode's `label`.
local function add_named(t, tvb, f, full, base)
  local start, quantity, run = f.start, f.quantity, f.registers or f.bits
  if start == nil or quantity == nil or f.kind == EXCEPTION then return end
  local count, first = run and run.count or 0, run and run.start
  if count > 0 and count == quantity and first == start then return end -- (its values cover the window)
  if MASK_WRITES[f.fn] and not f.malformed then return end -- (FC22: its register is shown, tree.lua add_pdu)
  local field, at = BIT_WINDOW[f.fn] and pf.bit_address or pf.reg_address, tvb:range(f.at, 0)
  local labels = base ~= nil and not BIT_WINDOW[f.fn] and PLC_LABELS[base] or nil
  local named, windows = true, { start, quantity }
  local rule = f.kind == REQUEST and not f.malformed and LIFT_OF[REQUEST][f.fn]
  if rule and rule.write_window then
    local b, places = frame_bytes(f, tvb), DATA.field_places[DATA.rules.by_code[REQUEST][f.fn].layout]
    windows[3], windows[4] = u16(b, places[rule.write_window[1]].at), u16(b, places[rule.write_window[2]].at)
  end
  local size = math.min(math.max(quantity, 1), 2000)
  for w = 1, #windows, 2 do
    for address = windows[w], windows[w] + math.min(math.max(windows[w + 1], 1), 2000) - 1 do
      address = address % 0x10000
      -- (not a value carried, nor, in the written window, an address of the read one named already)
      if (first == nil or (address - first) % 0x10000 >= count)
          and (w == 1 or (address - start) % 0x10000 >= size) then
        if named then
          local item = t:add(field, at, address)
          -- (faked, the frame's item handed back: an invisible tree that needs no such field, unseen.add)
          named = not (full == "unseen" and item.len ~= 0)
          if named then item:set_hidden() end
        end
        if labels ~= nil then
          local item = t:add(pf.reg_label, at, labels[address])
          if full == "unseen" and item.len ~= 0 then labels = nil else item:set_hidden() end
        end
        if not named and labels == nil then return end
      end
    end
  end
end

local function show_frame(st, f, tvb, tree, pinfo, full)
  local crc_ok = f.crc == f.crc_expected
  local t, whole, crc_at = tree, nil, nil
  if full then
    whole = tvb:range(f.at, f.length)
    t = tree:add(proto, whole)
    t:set_text(format("VW3 Modbus %s, %s", f.ascii and "ASCII" or "RTU", summary(f, tvb, st)))
    t:add(pf.item, whole, f.number):set_generated()
    t:add(pf.kind, whole, KIND_NUMBER[f.kind]):set_generated()
    t:add(pf.offset, whole, f.offset):set_generated()
    t:add(pf.mode, whole, f.ascii and "ascii" or "rtu"):set_generated()
    t:add(pf.slave, frame_range(tvb, f, 0, 1), f.slave) -- (the slave byte is the first of the frame's byte table)
    t:add(pf["function"], frame_range(tvb, f, 1, 1), f.fn)
    t:add(pf.function_name, whole, f.function_text or function_name(f.fn)):set_generated()
    local device, reason = device_of(st, f)
    if device then t:add(pf.profile, whole, device.profile.name):set_generated() end
    if reason then t:add(pf.profile_reason, whole, reason):set_generated() end
    if f.provisional then -- (vw3-decode -V's line)
      t:add(pf.provisional, whole, true):set_generated():set_text(DATA.render.provisional_line)
    end
    crc_at = check_at(f)
    local crc_range = frame_range(tvb, f, crc_at, f.ascii and 1 or 2)
    local crc = t:add(pf.crc, crc_range, f.crc)
    local expected = t:add(pf.crc_expected, crc_range, f.crc_expected):set_generated()
    local ok = t:add(pf.crc_ok, crc_range, crc_ok):set_generated()
    if f.ascii then -- (the same fields, named for ASCII's check: one byte, an LRC)
      crc:set_text(format("LRC: 0x%02x", f.crc))
      expected:set_text(format("Expected LRC: 0x%02x", f.crc_expected))
      ok:set_text(crc_ok and "LRC OK: True" or "LRC OK: False")
    end
  end
  if not crc_ok then -- (ASCII: the LRC, one byte)
    local text = f.ascii and "Bad LRC: 0x%02X, expected 0x%02X" or "Bad CRC: 0x%04X, expected 0x%04X"
    add_text(t, ex.crc_bad, format(text, f.crc, f.crc_expected))
  end
  if full and f.broadcast then t:add(pf.broadcast, whole, true):set_generated() end
  if f.kind == EXCEPTION then
    local code = f.exception_code -- (nil: none, a malformed exception)
    if full and code ~= nil then
      t:add(pf.exception_code, frame_range(tvb, f, 2, 1), code)
      -- (bytes after its code: vw3-decode --json's fields.trailing, -Y fields.trailing)
      if crc_at > 3 then t:add(pf.trailing, frame_range(tvb, f, 3, crc_at - 3)) end
    end
    add_text(t, ex.exception, format("Exception %s: %s", code or "?", f.exception_meaning or exception_name(code)))
    if full then
      t:add(pf.exception_name, whole, exception_name(f.exception_code)):set_generated()
      if f.exception_meaning then t:add(pf.exception_meaning, whole, f.exception_meaning):set_generated() end
    end
  end
  if full then
    local data_range = frame_range(tvb, f, 2, 2)
    if f.start ~= nil then
      local item = add_window(t, tvb, f, pf.start, "start", f.start)
      local words = START_WORDS[f.fn]
      if words ~= nil then item:set_text(words.title .. ": " .. f.start) end
    end
    if f.quantity ~= nil then add_window(t, tvb, f, pf.quantity, "quantity", f.quantity) end
    if f.span_label ~= nil then t:add(pf.span_label, whole, f.span_label):set_generated() end
    if f.write_span_label ~= nil then t:add(pf.write_span_label, whole, f.write_span_label):set_generated() end
    if f.subfunction ~= nil then t:add(pf.subfunction, data_range, f.subfunction) end
    if f.kind ~= EXCEPTION then add_pdu(t, tvb, f, crc_at) end
    if f.subfunction ~= nil then
      local name = f.subfunction_text or DIAGNOSTICS[f.subfunction]
      if name ~= nil then t:add(pf.subfunction_name, whole, name):set_generated() end
    end
  end
  local registers = f.registers
  if registers and registers.count > 0 and (full or registers.status ~= nil) then
    -- (no tree: only the expert infos of the registers that are not ok, no value needed: it is 16#8000)
    local b, statuses = full and frame_bytes(f, tvb) or nil, registers.status or NO_INTERPRETATION
    local checking = full == "unseen" and registers.count > 1
    for index = 0, registers.count - 1 do
      if full or statuses[index] ~= nil then
        add_register(t, tvb, f, register_view(st, f, registers, b, index), nil, full, checking)
      end
    end
  end
  if f.inferred then
    for _, reg in ipairs(inferred_registers(st, f)) do add_register(t, tvb, f, reg, nil, full and true) end
  end
  if full then
    local bits = f.bits
    if bits and bits.count > 0 then
      local b = bits.single == nil and frame_bytes(f, tvb) or nil
      local checking, add = full == "unseen" and bits.count > 1, unseen.add
      for index = 0, bits.count - 1 do
        local address, value, k = bit_at(bits, b, index, true)
        unseen.at(tvb, f, k, 1, nil, checking)
        local sub = add(t, pf.bit)
        sub:set_text(format("Bit %s = %d", address and tostring(address) or "?", value))
        if address ~= nil then add(sub, pf.bit_address, address, true) end
        add(sub, pf.bit_value, value, true)
      end
    end
    local device = device_of(st, f)
    add_named(t, tvb, f, full, device and plc_base(device, f))
    if unseen.generated then
      -- what the skipped set_generated() calls of faked items would have done
      unseen.generated = false
      t:set_generated()
    end
    if f.objects then
      for _, object in ipairs(f.objects) do
        local r = frame_range(tvb, f, object.offset, object.length)
        local sub = t:add(pf.object, r)
        -- A device's bytes are data: the value holds no control character (printable.py bytes_text: \x1b, \r,
        -- its quotes escaped), shown between quotes as vw3-decode's -V and summary show it, never written
        -- raw into tshark -V or -T fields (a terminal would run an ESC sequence).
        sub:set_text(format("%s: '%s'", object.name, object.value))
        sub:add(pf.object_id, r, object.id)
        sub:add(pf.object_name, r, object.name):set_generated()
        sub:add(pf.object_value, r, object.value)
        if object.text then sub:add(pf.object_text, r, object.text):set_generated() end
      end
    end
    local request = f.request
    if request ~= nil then
      -- (a request a later record settled, on that record's first showing: the record that showed it too)
      local shown_in = request.record
      if request.late_in ~= nil and not pinfo.visited then shown_in = request.late_in end
      t:add(pf.request_frame, whole, shown_in):set_generated()
      local delta = lane.response_time(f) -- (show.lua)
      if delta ~= nil then t:add(pf.response_time, whole, delta):set_generated() end
    end
    if f.response ~= nil then t:add(pf.response_frame, whole, f.response.record):set_generated() end
  end
  -- Known only once the whole capture has been read (second pass; pinfo nil: the record's first
  -- dissection, which is never a later pass's, and asks pinfo nothing).
  -- (a request the spec has no server answer, pairing's answerless, is never unanswered; the end: vw3.pairing's ended)
  local ends_unanswered, ends_note = false, nil
  if f.kind == REQUEST and st.pending == f and not f.answerless and pinfo ~= nil and pinfo.visited then
    ends_unanswered, ends_note = ended(st, f)
  end
  -- (present only when true: `-Y vw3.unanswered` then finds exactly the requests not answered)
  if f.kind == REQUEST and (f.unanswered or ends_unanswered) then
    add_said(t, whole, pf.unanswered, true, ex.unanswered, "Request not answered")
  end
  if f.profile_choice ~= nil then -- (profile auto: this frame decided the slave's device, as ProfileChoice.text)
    -- (profile_said: the device chosen there, where lane.again annotates with the one chosen at last)
    local text = format("slave %d: %s (%s)", f.slave, f.profile_said or device_of(st, f).profile.name,
      f.profile_choice)
    add_said(t, whole, pf.profile_choice, text, ex.profile, text)
  end
  -- Each warning and note is a string field (full text, filterable) carrying its expert info (whose
  -- label Wireshark cuts at 240 bytes).
  local warnings = f.warnings or NO_INTERPRETATION
  for index = 1, #warnings do
    local text = warnings[index]
    local malformed = f.malformed and text:sub(1, 10) == "malformed "
    add_said(t, whole, pf.warning, text, malformed and ex.malformed or ex.warning, text)
  end
  local notes = f.notes or NO_INTERPRETATION
  -- (the capture end's note after the notes pairing gave, before decoding's: paired_notes, take_frame's count)
  local count, at = #notes, ends_note and (f.paired_notes or 0) + 1
  for index = 1, count + (ends_note and 1 or 0) do
    local text = ends_note
    if index ~= at then text = notes[at and index > at and index - 1 or index] end
    local unmatched = f.no_request and text == UNMATCHED
    add_said(t, whole, pf.note, text, unmatched and ex.no_request or ex.note, text)
  end
  return t -- (the frame's item; with no tree, the tree it was given, where the record's own notes go too)
end

-- What kind of tree Wireshark passes. false: none, an empty TreeItem with no proto_tree behind it (a pass
-- that neither shows details nor filters on fields: tshark's first pass, a summary without filters); its
-- `text` is nil, where a real tree's root is Wireshark's own "Wireshark Lua fake item". "unseen": an
-- invisible tree (see unseen.add). true: a tree that is shown, or the test stub's (a Lua table).
-- (TreeItem.text, .visible and .len, which unseen.add reads, are there from Wireshark 4.0 on.)
local function tree_mode(tree)
  if type(tree) ~= "userdata" then return true end
  if tree_text(tree) == nil then return false end
  if tree.visible == false then return "unseen" end
  return true
end

-- The tvb an item is shown from: the record's own, or a new one holding the item's bytes where it began
-- in earlier records (a frame the capture tool cut across records).
local function item_tvb(item, tvb)
  if item.raw == nil then return tvb end
  return ByteArray.new(item.raw, true):tvb(item.kind == NOISE and "VW3 noise" or "VW3 reassembled frame")
end

-- The noise item `k` places after `item` (0: itself; a run of the same noise is kept as one entry).
-- (expert_text: the run's text, made once for all its items by the caller)
local function show_noise(item, tvb, tree, full, k, expert_text)
  local length = item.length
  local t = tree -- (the item's own, when a tree is wanted: as show_frame's)
  if full then
    local r = tvb:range(item.at + k * length, length)
    t = tree:add(proto, r, format("VW3 noise, %s: %s", count_text(length, "byte"), item.reason))
    t:add(pf.item, r, item.number + k):set_generated()
    t:add(pf.kind, r, KIND_NUMBER[NOISE]):set_generated()
    t:add(pf.offset, r, item.offset + k * length):set_generated()
    t:add(pf.noise_reason, r, item.reason):set_generated()
    t:add(pf.data, r)
  end
  add_text(t, ex.noise, expert_text)
  return t
end

-- A record-level note, on the item they go on: the first item shown, else one of their own. Returns it.
local function record_note(anchor, tree, full, tvb, n, expert_info, text)
  if anchor == nil then
    anchor = tree
    if full then anchor = tree:add(proto, tvb:range(0, n), "VW3 record") end
  end
  add_text(anchor, expert_info, text)
  return anchor
end

-- `1 byte continues`, `5 bytes continue`: a record's bytes framed with the next records'.
local function continue_text(count)
  return count_text(count, "byte") .. (count == 1 and " continues" or " continue")
end

-- One more part of a record's Info text: a single part stays a string, a list is made from the second.
local function add_part(summaries, info, text)
  if summaries ~= nil then
    summaries[#summaries + 1] = text
    return summaries, nil
  end
  if info == nil then return nil, text end
  return { info, text }, nil
end

-- Show one item of a record from `shown_from` (the record's tvb, or one of its own bytes) and add its
-- Info text (`from`: where its bytes came from, when they are another record's). Returns its tree item and
-- the Info parts (add_part).
local function show_item(st, item, shown_from, tree, pinfo, full, summaries, info, from)
  local t
  if item.kind == NOISE then
    -- (a run of the same noise, kept as one entry: its texts made once, for each of its items)
    local bytes = count_text(item.length, "byte")
    local text = format("noise (%s)", bytes) .. (from or "")
    -- (a record captured in part, lua/src/stream.lua cut_stream: marked as tshark marks it, `[Packet size limited during
    -- capture]`, and as vw3-decode's summary line, render/summary.py part_mark)
    if item.reason:sub(1, 16) == "captured in part" then text = text .. " [" .. item.reason .. "]" end
    local expert_text = format("%s outside any frame: %s", bytes, item.reason)
    for k = 0, (item.count or 1) - 1 do
      local shown = show_noise(item, shown_from, tree, full, k, expert_text)
      t = t or shown
      summaries, info = add_part(summaries, info, text)
    end
  else
    t = show_frame(st, item, shown_from, tree, pinfo, full)
    local text = item.info or summary(item, shown_from, st) -- (info: see known_requests)
    summaries, info = add_part(summaries, info, from and text .. from or text)
  end
  return t, summaries, info
end

-- Show a record's items; the record-level notes go on the first item shown (or an item of their own),
-- so that they show in the details, not under a hidden item. A record kept as one packed frame is a
-- number (see pack.settle). whole: the record is one frame just taken by dissect_record's fast lane (not
-- packed yet).
local function show_record(st, record, tvb, pinfo, tree, n, whole)
  local cols = pinfo_cols(pinfo)
  cols.protocol = "VW3"
  local full = tree_mode(tree)
  if whole and not full and config.errors[1] == nil then
    -- No tree (a summary's first pass): the frame's expert infos and its Info text, nothing else to say.
    -- (show_frame only adds expert infos here: asked only when the frame has one to add)
    local item = record[1]
    local registers = item.registers
    if item.crc ~= item.crc_expected or item.kind == EXCEPTION or item.warnings or item.notes or item.unanswered
        or item.profile_choice or item.inferred or (registers ~= nil and registers.status ~= nil) then
      show_frame(st, item, tvb, tree, nil, false)
    end
    -- (info: a known request's, see known_requests; the frame is the record's own, its bytes the tvb's)
    cols.info = item.info or summary(item, tvb, st)
    return
  end
  if type(record) == "number" then record = { record } end
  unseen.serial = unseen.serial + 1
  unseen.generated = false
  local anchor = nil
  if record.error then
    anchor = full and tree:add(proto, tvb:range(0, n)) or tree
    add_text(anchor, ex.internal, "Lua Error in vw3.lua: " .. record.error)
  end
  local continued = record.continued
  -- (the Info text is made each time rather than kept: records stay in memory for the whole capture)
  -- (one part as it is, a list of parts only when there are more)
  local info, summaries = nil, nil
  if continued ~= nil then
    summaries = {}
    for _, part in ipairs(continued) do
      -- (noise: bytes of a run that goes on in later records, which continue no frame)
      local said = part.noise and count_text(part.count, "byte") .. " of noise" or continue_text(part.count)
      local text = format("%s in item %d (record %d)", said, part.item, part.record)
      if full then
        local count = math.min(part.count, n) -- (the record's last bytes: those the frame goes on with)
        local range = tvb:range(n - count, count)
        local t = tree:add(proto, range, format("VW3 bytes of %s shown in a later record: %s",
          part.noise and "noise" or "a frame", text))
        t:add(pf.continued_in, range, part.record):set_generated()
        anchor = anchor or t
      end
      summaries[#summaries + 1] = format("(%s in #%d)", said, part.record)
    end
  end
  -- Items this record decided that the later passes show in earlier records (take_items, st.late): its
  -- first dissection, the only one tshark's single pass makes, shows them here, before its own.
  -- (not where lane.again or a change of mode decoded the record again, unseen: only its first showing)
  local late = st.late
  if late ~= nil and late.record == record and not pinfo.visited then
    st.late = nil
    for index = 1, #late do
      local entry = late[index]
      local item, from = entry.item, entry.from
      local shown_from = ByteArray.new(entry.raw, true):tvb(item.kind == NOISE and "VW3 noise" or "VW3 frame from earlier records")
      local at, count = item.at, item.count
      item.at, item.count = 0, nil -- (its own bytes; a run of the same noise is shown item by item)
      local records = "#" .. concat(from, ", #")
      local t
      t, summaries, info = show_item(st, item, shown_from, tree, pinfo, full, summaries, info, " from " .. records)
      item.at, item.count = at, count
      if full then
        local text = format("Bytes from record%s %s", #from > 1 and "s" or "", concat(from, ", "))
        t:add(proto, shown_from:range(0, item.length), text):set_generated()
      end
      anchor = anchor or t
    end
  end
  local frames = 0
  for index = 1, #record do
    local item = pack.expand(record[index], st)
    local t
    t, summaries, info = show_item(st, item, item_tvb(item, tvb), tree, pinfo, full, summaries, info)
    if item.kind ~= NOISE then frames = frames + 1 end
    anchor = anchor or t
  end
  if frames > 1 then
    anchor = record_note(anchor, tree, full, tvb, n, ex.multiple, format("This record holds %d frames", frames))
  end
  local errors = config.errors
  for index = 1, #errors do
    anchor = record_note(anchor, tree, full, tvb, n, ex.preference, "Preferences: " .. errors[index])
  end
  local waiting = record.waiting
  if waiting ~= nil and waiting > 0 then
    -- (the newest record's: the bytes of them that are noise already, in a run whose end is not known)
    local noise = st.noise_for == record and st.noise_waiting or 0
    if noise > 0 then
      local bytes = count_text(noise, "byte")
      local text = format("The record ends inside a noise run: %s of noise so far, shown as an item with the next"
        .. " records' bytes that end the run", bytes)
      local t = anchor or tree
      if full then -- (on those bytes: the record's waiting bytes begin with them)
        local range = tvb:range(n - waiting, noise)
        t = tree:add(proto, range, "VW3 noise so far, " .. bytes)
        t:add(pf.data, range)
      end
      anchor = anchor or t
      add_text(t, ex.partial, text)
      summaries, info = add_part(summaries, info, format("noise (%s so far)", bytes))
      waiting = waiting - noise
    end
    if waiting > 0 then
      local text = format("The record ends inside a frame: its last %s framed with the next records'",
        waiting == 1 and "byte is" or format("%d bytes are", waiting))
      anchor = record_note(anchor, tree, full, tvb, n, ex.partial, text)
      summaries, info = add_part(summaries, info, format("(%s)", continue_text(waiting)))
    end
  end
  cols.info = info or (summaries and concat(summaries, "; ")) or ""
end

-- tshark dissects a record again only in -2's second pass (its live captures dissect each record once):
-- there any record dissected again ends the first pass, the newest too (a file of one record). Wireshark
-- redraws the newest record's row while it captures (nil: a host without gui_enabled, the test stub).
local TSHARK = gui_enabled ~= nil and not gui_enabled()

-- The first pass is over: what still waits at the end of the capture is framed now, in every stream.
-- The first pass is over when Wireshark dissects again a record older than the newest (tshark -2, the
-- packet details), or tshark any record: then the choices apply to every frame (lane.again). Wireshark
-- capturing dissects the record just read again (its row drawn): its records keep their single pass.
-- (newest_record: the newest record's number, reset with each capture by proto.init)
local function finish_all(number)
  for _, st in pairs(udp_states) do finish_safely(st) end
  finish_safely(state)
  if number < newest_record or TSHARK then
    for _, st in pairs(udp_states) do lane.again(st) end
    lane.again(state)
  end
end

-- Each record (serial record, UDP datagram) is a chunk of its stream.
-- The record's first dissection: nil for an empty record, else the record and its length, and the Info
-- text of a record the quick lanes took (its one frame has nothing else to say where no tree is wanted).
-- (bytes: the record's, read from the tvb where not given; pinfo nil: a stand-in, dissector.lua decode_again)
local function dissect_now(st, tvb, pinfo, number, bytes)
  bytes = bytes or tvb_raw(tvb)
  local n = #bytes
  if n == 0 and lane.parts[number] == nil then return nil end -- (one captured in part of no byte: a cut all the same)
  local time = record_ns(pinfo, number)
  if number >= newest_record then
    newest_record = number
    if time ~= nil then recorded_until = time end
  end
  local again = nil
  if config.default == AUTO and not state.finished then
    -- Kept for lane.again: the whole capture decoded again with its choices, once they are known (not
    -- after the first pass is over: a live capture's later records are never decoded again). Their bytes
    -- by number; their times (false: none) but a quick lane's record's (its frame's: pack.record_time).
    again = st.again
    if again == nil then
      again = { bytes = {}, times = {} }
      st.again = again
    end
    again.bytes[number] = bytes
  end
  if st.sample then keep_time(number, time) end -- (kept for a stand-in: dissector.lua decode_again)
  local record, taken, info = lane.decode(st, bytes, n, time, number)
  if again ~= nil and info == nil then again.times[number] = time or false end
  return record, taken, info
end
