-- vw3.story: the parameter story (became protected, readable again) and registers annotated.
-- Mirrors dissector/devices/story.py, dissector/devices/memory.py, dissector/devices/annotator.py (registers).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.story"]).

-- Parameter events of one frame, told as one note per event kind and past (devices/story.py):
-- neighbouring addresses as ranges, `39193..39288 readable again (96): non-existent in frame #1576`.
-- (The texts are data/modbus.toml [texts]: became_protected, event_one, event_runs, ...)
local story = {} -- tell(), plain_rule()

function story.tell(f)
  local events = f.events
  if events == nil then return end -- (most frames: before the closure below is made)
  local function event_name(e) return address_name(e.row, e.address, e.label) end
  f.events = nil
  local groups, order = {}, {}
  for _, e in ipairs(events) do
    local key = e.what .. "\0" .. e.how .. "\0" .. e.frame .. "\0" .. (e.now_shared or "")
    local group = groups[key]
    if group == nil then group = {}; groups[key] = group; order[#order + 1] = group end
    group[#group + 1] = e
  end
  for _, group in ipairs(order) do
    local first = group[1]
    if #group == 1 then
      first.name = event_name(first)
      note(f, say("event_one", first))
    else
      table.sort(group, function(a, b) return a.address < b.address end)
      note(f, say(first.now_shared and "event_runs_now" or "event_runs", { what = first.what, count = #group,
        runs = runs_told(group, consecutive, event_name, span_name), how = first.how, frame = first.frame,
        now = first.now_shared }))
    end
  end
end

-- The parameter memory (devices/memory.py): per address its value (nil: unreadable), the frame and how
-- it was known; an entry there is changed in place (the quick lanes hold the entries they will change).
-- (By address alone: the one profile here that follows parameters, the ATV71, reads its input registers as
-- its holding registers, profile input_registers "holding"; Python keeps a separate table's apart,
-- Device.memory, for a user's profile, which the plugin does not load.)
local function remember(seen, address, value, number, how)
  local last = seen[address]
  if last ~= nil then
    last.value, last.frame, last.how = value, number, how
  else
    seen[address] = { value = value, frame = number, how = how }
  end
end

-- A register's status followed (memory.py lost, readable_again): an event when it changes the story.
local function track(seen, f, address, row, value, status, now, label)
  local last = seen[address]
  local what, before, shared = nil, nil, nil
  if status == "ok" then
    if last ~= nil and last.value == nil then
      what, before, now = "readable_again", last.how, say("value_now", { value = value })
    end
  elseif status == "protected" or status == "non-existent" then
    if last ~= nil and last.value ~= nil then
      what, before, shared = row ~= nil and "became_protected" or "became_unknown", say("known_value", last), now
    end
    value = nil
  else
    return
  end
  if what ~= nil then
    local events = f.events or {}
    f.events = events
    events[#events + 1] = { what = say(what, {}), address = address, row = row, label = label, before = before,
      how = last.how, frame = last.frame, now = now, now_shared = shared }
  end
  remember(seen, address, value, f.number, status == "ok" and "read" or status)
end

local function remember_writes(seen, number, run, b)
  if run.start == nil then return end
  for index = 0, run.count - 1 do
    local address, value = register_at(run, b, index)
    remember(seen, address, value, number, "written")
  end
end

-- A Mask Write its echo confirms ([confirm] "mask", memory.remember_mask): the register holds (current AND
-- and_mask) OR (or_mask AND NOT and_mask) (Application Protocol 6.16); where the current value is not known
-- (and_mask 0 replaces every bit), the parameter is forgotten.
-- (bit by bit, low first: the current value's where and_mask has a 1, or_mask's where it has a 0)
local function remember_mask(seen, number, fields)
  local and_mask, or_mask, last = fields.and_mask, fields.or_mask, seen[fields.address]
  local current = and_mask == 0 and 0 or last ~= nil and last.value or nil
  if current == nil then
    seen[fields.address] = nil
    return
  end
  local value, weight = 0, 1
  for _ = 1, 16 do
    if (and_mask % 2 == 1 and current or or_mask) % 2 == 1 then value = value + weight end
    current, and_mask, or_mask = math.floor(current / 2), math.floor(and_mask / 2), math.floor(or_mask / 2)
    weight = weight * 2
  end
  remember(seen, fields.address, value, number, "written")
end

-- What register `index` of a frame's consecutive registers is of a 32-bit map row (naming.name_wide):
-- 2 its first word (the value is read here), 0 its second word, 1 a register on its own.
local function words_at(rows, address, index, count)
  local row = rows[address]
  if row ~= nil and row.words == 2 and index + 1 < count then return 2 end
  return index > 0 and rows_before(rows, address) and 0 or 1
end

-- The bits_depend rule under which the register at `address` (its map row `row`) is read with its plain
-- layout now (the register it depends on last held a value that says so), or nil.
function story.plain_rule(device, address, row)
  local rule = row ~= nil and row.words ~= 2 and device.depend[address]
  local last = rule and device.seen[rule.on]
  if last and last.value ~= nil and rule.plain_when[last.value] then return rule end
  return nil
end

-- (16#8000's texts, memory.py's: data/modbus.toml [texts]; a register's by its status, no value left)
local MARKER_NOW = say("marker_now", {})
local MARKER_TEXTS = { ["non-existent"] = say("marker_non_existent", {}), protected = say("marker_protected", {}) }

-- One register of a frame, in capture order: is it read with its plain layout (a bits_depend rule), and
-- its 16#8000 status (nil: the profile has none, or this is no read). Notes and the story go on.
local function annotate_one(f, device, address, value, protected, multi, label, words)
  local rows = rows_for(device, f.fn) -- (FC4's: a map in references' 3X rows, where they are apart)
  local row = rows[address]
  local rule = rows == device.rows and story.plain_rule(device, address, row) or nil -- (rules: holding's)
  if rule ~= nil and not has_note(f, rule.reason) then note(f, rule.reason) end
  local status = nil
  if protected ~= nil then
    status = "ok"
    -- (a word of a 32-bit value is no parameter on its own)
    if value == protected and multi and words == 1 then
      if row == nil then -- (a 32-bit value's second word alone: that value's 16#8000, as its first's)
        status = rows_before(rows, address) and "ambiguous" or "non-existent"
      else
        status = row.ambiguous_8000 and "ambiguous" or "protected"
      end
    end
    track(device.seen, f, address, row, value, status, MARKER_NOW, label)
  end
  return rule ~= nil, status
end

-- Every value at 16#8000 where the device answers an exception when every parameter is unreadable (p.38;
-- annotator._all_marked): one at least is the value itself, so each is ambiguous and none is followed.
-- (the run's count values from b[first] on)
local function all_marked(f, device, count, b, first, protected)
  local code = device.profile.all_protected_exception
  if code == nil then return false end
  for k = first, first + 2 * count - 2, 2 do
    if b[k] * 256 + b[k + 1] ~= protected then return false end
  end
  note(f, say("all_marked", { protected = protected, device = device.profile.device, code = code }))
  return true
end

local function plc_base(device, f)
  return device.plc and (device.plc[f.fn] or device.plc_default)
end

-- The display addresses of a frame's registers on a PLC-style device (`40101`), false on any other:
-- describe's `labels`, which a caller naming many registers of one frame finds once (register_view).
local function frame_labels(device, f)
  return device.plc ~= nil and PLC_LABELS[plc_base(device, f)]
end

-- A register of f as the display shows it (reg: its address and value; naming.name_register, name_wide):
-- the map row that names it, its scaled value and text, status, part of a 32-bit value (words; `second`:
-- the next word, when words is 2) and PLC label (`labels`: frame_labels', nil to find them), from the plain
-- layout flag (a bits_depend rule) and its status: maps.interpret / interpret_wide, then the 16#8000 texts.
local function describe(device, f, reg, plain, status, words, second, labels)
  local rows, address, value = rows_for(device, f.fn), reg.address, reg.value
  local row = rows[address]
  local named, scaled, text = row, nil, nil
  if row ~= nil then -- (nested: most registers of a frame have no row, and each test here is paid per register)
    if row.words ~= 2 then
      scaled, text = interpret(plain and device.plain[address] or row, value)
    elseif words == 2 then
      scaled, text = interpret_wide(row, value, second)
    else
      text = say("first_word", row)
    end
  elseif words == 0 then -- (a row of its own names a second word as any register, naming.py's loop)
    named = rows_before(rows, address)
    text = say("second_word", named)
  else
    local before = rows_before(rows, address) -- (its first word is not in the frame: naming.name_second_alone)
    if before then named, text = before, say("second_word_alone", before) end
  end
  if MARKER_TEXTS[status] ~= nil then scaled, text = nil, MARKER_TEXTS[status] end
  reg.row, reg.scaled, reg.text, reg.status, reg.words = named, scaled, text, status, words
  if labels == nil then labels = frame_labels(device, f) end
  if labels then reg.label = labels[address] end
end

-- A run of a frame: what the display cannot find again from the bytes is kept, and only where it is
-- not the usual: the statuses other than ok, the registers read with their plain layout.
local function annotate_registers(f, device, run, b, read)
  local start = run.start
  if start == nil then return end
  local protected = read and device.profile.protected_value or nil
  local count, first = run.count, run.first
  local multi = count > 1
  if multi and protected ~= nil and b[first] * 256 + b[first + 1] == protected -- (the usual answer: no call)
      and all_marked(f, device, count, b, first, protected) then
    protected = nil
    run.status = {}
    for index = 0, count - 1 do run.status[index] = "ambiguous" end
  end
  -- Nothing to follow: no 16#8000 story, no layout that depends on another register.
  if protected == nil and next(device.depend) == nil then return end
  local labels = frame_labels(device, f)
  local rows = rows_for(device, f.fn)
  for index = 0, count - 1 do
    local k = first + 2 * index
    local address = (start + index) % 0x10000
    local label = labels and labels[address]
    local plain, status = annotate_one(f, device, address, b[k] * 256 + b[k + 1], protected, multi, label,
      words_at(rows, address, index, count))
    if plain then
      run.plain = run.plain or {}
      run.plain[index] = true
    end
    if status ~= nil and status ~= "ok" then
      run.status = run.status or {}
      run.status[index] = status
    end
  end
  story.tell(f)
end
