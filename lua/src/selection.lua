-- vw3.selection: profile auto: which device each slave is, from evidence in the capture.
-- Mirrors dissector/devices/selection.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.selection"]).

-- Profile `auto` (devices/selection.py, rule for rule): a slave is taken for a device on evidence, in
-- capture order, as vw3-decode reads its input: a Read Device Identification ProductCode or a function
-- code only that device speaks (final), else its first answers fitting one candidate's map alone (its
-- rows and the maps given for it; 16#8000 where it has none); an answer to a function the chosen device
-- does not support takes the choice back. Until then the fallback: spec semantics only. What a later
-- frame says changes nothing before it, in one pass as with -2: the frames before the evidence are shown
-- as vw3-decode shows them.
local CANDIDATES = SELECTION.candidates
-- The candidate a function code identifies (the first, in the candidates' order, that claims it) and the
-- code's name on it; the ProductCode prefixes that identify one, { prefix, candidate } in that order.
local IDENTIFYING, PRODUCT_CODES = SELECTION.identifying, SELECTION.product_codes
local FIT_ANSWERS, FIT_FRAMES, FIT_READS = SELECTION.fit_answers, SELECTION.fit_frames, SELECTION.fit_reads
local FALLBACK = SELECTION.fallback

-- Does the slave's current choice not support function fn (an answer to it takes the choice back)?
local function unsupported(current, fn)
  local functions = PROFILES[current.profile].functions
  return current.profile ~= FALLBACK and functions ~= nil and not functions[fn]
end

local function settled(judged)
  return judged.answers >= FIT_ANSWERS or judged.frames >= FIT_FRAMES
    or (judged.choice ~= nil and judged.choice.final)
end

-- No device for the slave (none chosen, or the one chosen taken back) while its traffic may still choose
-- one (Selector.open): its frames are provisional. (Written out where every frame asks: lane.quiet.)
local function open(judged)
  local choice = judged.choice
  return (choice == nil or choice.profile == FALLBACK) and not settled(judged)
end

-- A candidate's map as traffic is judged against it: its own rows and the map layers given for it; FC4's
-- registers judged against a map's 3X rows where the device names them apart (layered_rows' inputs;
-- INPUT_FUNCTIONS: lua/src/device.lua's).
local function candidate_rows(name, fn)
  config.fit_rows = config.fit_rows or made_once(function(candidate)
    local rows, inputs = layered_rows(PROFILES[candidate], function(layer) return layer.profile == candidate end)
    return { rows = rows, inputs = inputs }
  end)
  local made = config.fit_rows[name]
  return made.inputs ~= nil and INPUT_FUNCTIONS[fn] and made.inputs or made.rows
end

local function identified(f)
  if f.objects ~= nil and f.kind == RESPONSE then
    for _, object in ipairs(f.objects) do
      if object.id == SELECTION.product_code_object then
        for _, claim in ipairs(PRODUCT_CODES) do
          if object.value:sub(1, #claim[1]) == claim[1] then
            return { profile = claim[2], final = true, reason = say("chosen_product_code",
              { frame = f.number, value = object.value }) }
          end
        end
      end
    end
  end
  if f.kind ~= NOISE and f.crc == f.crc_expected then
    local claim = IDENTIFYING[f.fn]
    if claim ~= nil then
      return { profile = claim[1], final = true, reason = say("chosen_function",
        { ["function"] = f.fn, name = claim[2], frame = f.number }) }
    end
  end
  return nil
end

-- The registers of an answer as { address, value } pairs (a run read from b).
local function register_list(f, b)
  local run = f.registers
  if run == nil then return {} end
  local out = {}
  for index = 0, run.count - 1 do
    local address, value = register_at(run, b, index)
    out[index + 1] = { address = address, value = value }
  end
  return out
end

-- selection._fits: true, an answer the device gives; an address, also its non-existent marker there;
-- false, one it would not give; nil, nothing either way.
local function fits(f, name, registers)
  local profile = PROFILES[name]
  local rows = candidate_rows(name, f.fn)
  if not profile.identify.traffic_fit or next(rows) == nil then return nil end
  if profile.functions ~= nil and not profile.functions[f.fn] then return false end
  if #registers == 0 then return nil end
  local known, marker = 0, nil
  for _, reg in ipairs(registers) do
    if reg.address == nil then return nil end
    if rows[reg.address] ~= nil then
      known = known + 1
    elseif reg.value == profile.protected_value and READS[f.fn] ~= nil then
      marker = marker or reg.address
    else
      return false
    end
  end
  return known > 0 and (marker or true) or nil
end

-- selection._Evidence: the reads a candidate's map explains (found.order: their keys as first seen).
local function enough(found)
  return #found.order >= FIT_READS or (found.marker ~= nil and found.answers >= FIT_READS)
end

-- (the texts: data/modbus.toml [texts] chosen_fit, fit_read, ...; each read named with its first two frames)
local function evidence_reason(found, protected)
  local parts = {}
  for index = 1, math.min(#found.order, FIT_READS) do
    local read = found.reads[found.order[index]]
    read.frame, read.again = read.frames[1], read.frames[2]
    parts[index] = say(read.again and "fit_read_again" or "fit_read", read)
  end
  local reads = table.concat(parts, ", ")
  if #found.order < FIT_READS and found.marker ~= nil and protected ~= nil then
    return say("chosen_fit_marker", { reads = reads, protected = protected, marker = found.marker })
  end
  return say("chosen_fit", { reads = reads })
end

-- A new choice for f.slave when this frame decides (or undoes) one, else nil (Selector.observe).
-- (select_device calls it only for a slave not fixed by the choices of the whole capture)
local function observe(st, f, b)
  local slave = f.slave
  -- (serial slave 0 is the broadcast address; a Modbus/TCP unit 0 is the device itself: f.unit_zero)
  if slave == 0 and not f.unit_zero then return nil end
  local judged = st.judged[slave]
  if judged == nil then
    judged = { answers = 0, frames = 0, evidence = {}, ruled_out = {} }
    st.judged[slave] = judged
  end
  local current = judged.choice
  if current ~= nil and current.final then return nil end
  local judging = not settled(judged)
  judged.frames = judged.frames + 1
  local found = identified(f)
  if found ~= nil then
    judged.choice = found
    -- (the same device, for a new reason: identified after a traffic fit)
    found.same = current ~= nil and current.profile == found.profile
    return found
  end
  if f.kind ~= RESPONSE or f.crc ~= f.crc_expected then return nil end
  judged.answers = judged.answers + 1
  if current ~= nil and current.profile ~= FALLBACK then
    if not unsupported(current, f.fn) then return nil end
    judged.choice = { profile = FALLBACK, final = false, reason = say("chosen_unsupported",
      { ["function"] = f.fn, frame = f.number, device = PROFILES[current.profile].device }) }
    -- (the device taken back is ruled out; the others are judged on, while the slave is)
    judged.ruled_out[current.profile], judged.evidence[current.profile] = true, nil
    return judged.choice
  end
  if not judging then return nil end
  -- Selector._weigh: what this answer says of each candidate; a choice when one alone has enough.
  local registers = register_list(f, b)
  local evidence, ruled_out = judged.evidence, judged.ruled_out
  local ready = nil -- (the candidate whose evidence is enough; false: more than one)
  for _, name in ipairs(CANDIDATES) do
    local verdict = nil
    if not ruled_out[name] then verdict = fits(f, name, registers) end
    if verdict == false then
      ruled_out[name], evidence[name] = true, nil
    elseif verdict ~= nil then
      local found = evidence[name] or { reads = {}, order = {}, answers = 0 }
      evidence[name] = found
      local key = format("%d:%d:%d", f.fn, registers[1].address, #registers)
      local read = found.reads[key]
      if read == nil then
        read = { ["function"] = f.fn, frames = {},
          span = #registers == 1 and format("%d", registers[1].address) or span_name(registers) }
        found.reads[key] = read
        found.order[#found.order + 1] = key
      end
      read.frames[#read.frames + 1] = f.number
      found.answers = found.answers + 1
      if found.marker == nil and verdict ~= true then found.marker = verdict end
    end
    if evidence[name] ~= nil and enough(evidence[name]) then
      ready = ready == nil and name
    end
  end
  if not ready then return nil end
  judged.choice = { profile = ready, final = false,
    reason = evidence_reason(evidence[ready], PROFILES[ready].protected_value) }
  return judged.choice
end

-- Would observe decide nothing with a good frame of slave's function fn, an answer (answer true: no device
-- objects in it) or a request? For a slave met before (and judged, for an answer): true where observe would
-- change nothing (a final choice, or a settled slave: its counts decide nothing more), else the slave's judged
-- table, which the lane that takes the frame counts it in as observe does (answers, frames). false when observe
-- is to weigh the frame (a function that identifies a device, a slave not met or still judged, an answer its
-- device does not support). Changes nothing. (The quick lanes ask this instead.)
function lane.quiet(st, slave, fn, answer)
  if IDENTIFYING[fn] ~= nil then return false end
  local frozen = st.frozen
  if frozen ~= nil and st.fixed[slave] then return frozen[st.count + 1] == nil end -- (the frame that decided says so)
  local judged = st.judged[slave]
  if judged == nil then return false end
  local current = judged.choice
  if current ~= nil and current.final then return true end
  local done = judged.answers >= FIT_ANSWERS or judged.frames >= FIT_FRAMES -- (settled, written out)
  if (current == nil or current.profile == FALLBACK) and not done then return false end -- (open: provisional)
  if answer and current ~= nil and unsupported(current, fn) then return false end
  return done or judged
end

-- A frame provisional (Frame.provisional; st.provisional, lane.again: the later passes show no frame
-- provisional), kept, per slave until its choice, for the chosen device to annotate again
-- (lane.annotate_again; annotator.py _held, _scratch): a copy the annotate path may change freely, taken before the frame is
-- annotated and its bytes released (take_frame): its own runs (its request's too, with their bytes),
-- device objects, no notes or warnings. Bounded: a slave's frames
-- are provisional until FIT_FRAMES of them at most.
local function hold(st, f, b)
  f.provisional, st.provisional = true, true
  local copy = copied(f)
  copy.b, copy.notes, copy.warnings, copy.events = b, nil, nil, nil
  if f.registers ~= nil then copy.registers = copied(f.registers) end
  if f.request ~= nil then
    copy.request = copied(f.request)
    copy.request.registers = f.request.registers and copied(f.request.registers)
  end
  if f.objects ~= nil then
    copy.objects = {}
    for index, object in ipairs(f.objects) do copy.objects[index] = copied(object) end
  end
  st.held = st.held or {}
  local held = st.held[f.slave] or {}
  st.held[f.slave] = held
  held[#held + 1] = copy
end

-- A slave's device from item `number` on and why (`auto`'s reason; nil: none), kept in the slave's history
-- (device_of: the earlier frames keep theirs).
local function keep_device(st, slave, number, device, reason)
  local before = st.devices[slave]
  local history = st.history[slave] or { before and { number = 0, device = before } or nil }
  history[#history + 1] = { number = number, device = device, reason = reason }
  st.history[slave], st.devices[slave] = history, device
end

-- The device for f under profile `auto`: a new one when this frame decides a slave's profile (kept in
-- the slave's history for the display of earlier frames, and said on this frame: f.profile_choice), which
-- then annotates the copies of the slave's provisional frames again (hold; lane.annotate_again).
local function select_device(st, f, b)
  local frozen, slave = st.frozen, f.slave
  if frozen ~= nil and st.fixed[slave] then
    -- Every frame annotated with the device chosen over the whole capture; the frames that chose still
    -- say so (vw3-decode reading a file says where each choice was made too).
    local said = frozen[f.number]
    if said ~= nil then f.profile_choice, f.profile_said = said[2], said[1] end
    return device_for(st, slave)
  end
  local choice = observe(st, f, b)
  if choice == nil then
    -- Read once, no device chosen for the slave yet while evidence may still come: its values are named
    -- with spec semantics only, which its device may name otherwise (annotator.py, Frame.provisional).
    local judged = slave ~= 0 and st.judged[slave]
    -- (decoded again, the capture so far is read as a file: no frame provisional; a record read after
    -- that, in a capture that goes on, is read once again: lane.again's `going_on`)
    if judged and open(judged) and (st.frozen == nil or st.going_on) then
      hold(st, f, b)
    elseif st.held ~= nil and judged and settled(judged) then
      st.held[slave] = nil -- (settled without a choice: the device it has saw those frames)
    end
    return device_for(st, slave)
  end
  -- (said on the later passes, where every frame bears the slave's last reason: the frame it comes from says so)
  st.said[f.number] = { choice.profile, choice.reason }
  -- (choice.same: kept, and said with its new reason from here on, nothing announced, as vw3-decode)
  local device = not choice.same and build_device(PROFILES[choice.profile], slave) or st.devices[slave]
  keep_device(st, slave, f.number, device, choice.reason)
  if not choice.same then
    st.chosen[slave] = choice.profile
    f.profile_choice = choice.reason
    local held = st.held and st.held[slave]
    if held ~= nil then
      st.held[slave] = nil
      lane.annotate_again(st, device, held) -- (defined with the annotate path, lua/src/annotator.lua)
    end
    if open(st.judged[slave]) then -- (a choice taken back: no device while evidence may still come)
      hold(st, f, b)
    end
  end
  return device
end

-- Slave 0 under profile `auto` (Annotator._broadcast): a broadcast reaches every slave, so it is named with
-- the profile of every slave met (forced, or chosen so far; over the whole capture with -2: st.met), its
-- profile reason says so; slaves of different devices, or one met without a device, leave it spec
-- semantics, and a note says why.
local function broadcast_device(st, f)
  local fallback, named, slaves = FALLBACK, {}, {}
  -- (the slaves with a device, forced or chosen so far; then those met without one: unknown)
  for pass, source in ipairs({ config.per_slave, st.chosen, st.met or {}, st.judged }) do
    for slave, name in pairs(source) do
      if pass > 2 then name = "unknown" end
      if slave ~= 0 and name ~= fallback and named[slave] == nil then
        named[slave] = name
        slaves[#slaves + 1] = slave
      end
    end
  end
  table.sort(slaves)
  local name, parts = nil, {}
  for index, slave in ipairs(slaves) do
    name = (index == 1 or name == named[slave]) and named[slave] or false
    parts[index] = format("slave %d %s", slave, named[slave])
  end
  if name == "unknown" then name = nil end -- (every slave met without a device)
  local said = nil -- (the reason the frame says, vw3.profile_reason: Frame.profile_choice)
  if name then
    said = say("broadcast_profile", { profile = name,
      slaves = (#slaves > 1 and "slaves " or "slave ") .. concat(slaves, ", ") })
  elseif name == false then
    note(f, say("broadcast_mixed", { slaves = concat(parts, ", ") }))
  end
  -- Read once, while no slave is met or one met may still get a device, what names a broadcast may change:
  -- provisional.
  if st.frozen == nil or st.going_on then
    local met = false
    for slave, judged in pairs(st.judged) do
      met = met or slave ~= 0
      if open(judged) then f.provisional, st.provisional = true, true end
    end
    if not met then f.provisional, st.provisional = true, true end
  end
  name = name or fallback
  -- (slave 0's device under each profile, built once)
  st.broadcasting = st.broadcasting or made_once(function(named) return build_device(PROFILES[named], 0) end)
  local device, history = st.broadcasting[name], st.history[0]
  local last = history and history[#history]
  if st.devices[0] ~= device or (last and last.reason) ~= said then keep_device(st, 0, f.number, device, said) end
  return device
end

local function device_now(st, f, b)
  if config.auto[f.slave] then
    if f.slave == 0 and not f.unit_zero then return broadcast_device(st, f) end
    return select_device(st, f, b)
  end
  return device_for(st, f.slave)
end
