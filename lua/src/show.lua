-- vw3.show: Wireshark: a record's items shown, the first dissection of a record, the end of the first pass.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.show"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)

-- The time of a record, as vw3-decode reads it: the RTAC's own timestamp for RTAC serial records (when
-- the device saw the bytes), none for records at the epoch (vw3-decode -w writes those for untimed input),
-- the record's time otherwise.
local function record_time(pinfo, number)
  local rtac = rtac_times[number or pinfo.number]
  if rtac ~= nil then return rtac end
  local time = pinfo.abs_ts
  if time == 0 then return nil end
  return time
end

-- Each record's time from the capture's first (pinfo.rel_ts), by record number: kept across lane.again,
-- which makes the stream's state anew; each record's first dissection writes its own.
local REL_TIMES = {}

-- A response's time since its request (vw3.response_time), an NSTime: from both records' times from the
-- capture's first where they agree with their absolute times (a time reference set between them does
-- not), to the nanosecond: 0.010157000, not abs_ts's 0.010157108. nil where either has no time.
function lane.response_time(f)
  local request = f.request
  if f.time == nil or request.time == nil then return nil end
  local delta, asked, got = f.time - request.time, REL_TIMES[request.record], REL_TIMES[f.record]
  local exact = asked and got and got - asked
  if exact ~= nil and math.abs(exact - delta) < 1e-6 then delta = exact end
  local sign = delta < 0 and -1 or 1 -- (stamped before its request: both parts negative, as an nstime holds it)
  local seconds = math.floor(delta * sign)
  return NSTime.new(sign * seconds, sign * math.floor((delta * sign - seconds) * 1e9 + 0.5))
end

-- What kind of tree Wireshark passes. false: none, an empty TreeItem with no proto_tree behind it (a pass
-- that neither shows details nor filters on fields: tshark's first pass, a summary without filters); its
-- `text` is nil, where a real tree's root is Wireshark's own "Wireshark Lua fake item". "unseen": an
-- invisible tree (see unseen.add). true: a tree that is shown, or the test stub's (a Lua table).
-- (TreeItem.text, .visible and .len, which unseen.add reads, are there from Wireshark 4.0 on.)
local function tree_mode(tree)
  if type(tree) ~= "userdata" then return true end
  if tree.text == nil then return false end
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
  if count == 1 then return "1 byte continues" end
  return format("%d bytes continue", count)
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

-- Show a record's items; the record-level notes go on the first item shown (or an item of their own),
-- so that they show in the details, not under a hidden item. A record kept as one packed frame is a
-- number (see pack.settle). whole: the record is one frame just taken by dissect_record's fast lane (not
-- packed yet).
local function show_record(st, record, tvb, pinfo, tree, n, whole)
  local cols = pinfo.cols
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
    cols.info = item.info or summary(item, tvb)
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
      local text = format("%s in item %d (record %d)", continue_text(part.count), part.item, part.record)
      if full then
        local t = tree:add(proto, tvb:range(0, n), "VW3 bytes of a frame shown in a later record: " .. text)
        t:add(pf.continued_in, tvb:range(0, n), part.record):set_generated()
        anchor = anchor or t
      end
      summaries[#summaries + 1] = format("(%s in #%d)", continue_text(part.count), part.record)
    end
  end
  local frames = 0
  for index = 1, #record do
    local item = pack.expand(record[index], st)
    local shown_from = item_tvb(item, tvb)
    local t
    if item.kind == NOISE then
      -- (a run of the same noise, kept as one entry: its texts made once, for each of its items)
      local bytes = count_text(item.length, "byte")
      local text = format("noise (%s)", bytes)
      local expert_text = format("%s outside any frame: %s", bytes, item.reason)
      for k = 0, (item.count or 1) - 1 do
        local shown = show_noise(item, shown_from, tree, full, k, expert_text)
        t = t or shown
        summaries, info = add_part(summaries, info, text)
      end
    else
      frames = frames + 1
      t = show_frame(st, item, shown_from, tree, pinfo, full)
      summaries, info = add_part(summaries, info, item.info or summary(item, shown_from)) -- (info: see known_requests)
    end
    anchor = anchor or t
  end
  if frames > 1 then
    anchor = record_note(anchor, tree, full, tvb, n, ex.multiple, format("This record holds %d frames", frames))
  end
  local errors = config.errors
  for index = 1, #errors do
    anchor = record_note(anchor, tree, full, tvb, n, ex.preference, "Preferences: " .. errors[index])
  end
  if record.waiting ~= nil and record.waiting > 0 then
    local text = format("The record ends inside a frame: its last %s framed with the next records'",
      record.waiting == 1 and "byte is" or format("%d bytes are", record.waiting))
    anchor = record_note(anchor, tree, full, tvb, n, ex.partial, text)
    summaries, info = add_part(summaries, info, format("(%s)", continue_text(record.waiting)))
  end
  if info ~= nil then
    cols.info = info
  elseif summaries == nil then
    cols.info = ""
  else
    cols.info = concat(summaries, "; ")
  end
end

-- The first pass is over: what still waits at the end of the capture is framed now, in every stream.
-- The first pass is over when Wireshark dissects again a record older than the newest (tshark -2, the
-- packet details): then the choices apply to every frame (lane.again). A live capture dissects the
-- record just read again (tshark -w -P): its records keep their single pass.
-- (newest_record: the newest record's number, reset with each capture by proto.init)
local function finish_all(number)
  for _, st in pairs(udp_states) do finish_safely(st) end
  finish_safely(state)
  if number < newest_record then
    for _, st in pairs(udp_states) do lane.again(st) end
    lane.again(state)
  end
end

-- Each record (serial record, UDP datagram) is a chunk of its stream.
-- The record's first dissection: nil for an empty record, else the record and its length, and the Info
-- text of a record the quick lanes took (its one frame has nothing else to say where no tree is wanted).
local function dissect_now(st, tvb, pinfo, number)
  local bytes = tvb:raw()
  local n = #bytes
  if n == 0 then return nil end
  local time = record_time(pinfo, number)
  -- (its time from the capture's first too: exact to the nanosecond, where abs_ts, a double near 1.7e9,
  -- is not; lane.response_time. Not an RTAC record's, timed by the RTAC; stand-ins for pinfo have none.)
  local rel = pinfo.rel_ts
  if rel ~= nil then REL_TIMES[number] = time ~= nil and rtac_times[number] == nil and rel or nil end
  if number > newest_record then newest_record = number end
  if config.default == AUTO and not state.finished then
    -- Kept for lane.again: the whole capture decoded again with its choices, once they are known (not
    -- after the first pass is over: a live capture's later records are never decoded again).
    local again = st.again
    if again == nil then
      again = { order = {}, bytes = {}, times = {} }
      st.again = again
    end
    again.order[#again.order + 1] = number
    again.bytes[number], again.times[number] = bytes, time or false
  end
  return lane.decode(st, bytes, n, time, number)
end
