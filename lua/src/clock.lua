-- vw3.clock: Wireshark: record times in exact nanoseconds; pinfo's fields read through Wireshark's own getters.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.clock"]).

-- Wireshark's functions behind pinfo's fields, TreeItem.text and tvb:raw(), called directly: wslua reaches a
-- field through an __index function that looks the name up first (pinfo.port_type: some 1,120 machine
-- instructions a read, its getter alone some 860; tvb:raw() and tree.text save as much). They are in the
-- class metatables Wireshark keeps in the registry; where there are none (the test stub's Lua tables), a
-- field is read as usual.
local registry = debug and debug.getregistry and debug.getregistry() or {}
local function getter(class, name)
  local meta = registry[class]
  local getters = type(meta) == "table" and rawget(meta, "__getters")
  local get = type(getters) == "table" and rawget(getters, name)
  if type(get) == "function" then return get end
  return function(object) return object[name] end
end
local pinfo_number, pinfo_port_type, pinfo_cols = getter("Pinfo", "number"), getter("Pinfo", "port_type"),
  getter("Pinfo", "cols")
local pinfo_abs_ts, pinfo_rel_ts, tree_text = getter("Pinfo", "abs_ts"), getter("Pinfo", "rel_ts"),
  getter("TreeItem", "text")
local function tvb_method(name) -- (Tvb's own function, called directly: no __index look-up)
  local direct = type(Tvb) == "table" and rawget(Tvb, name)
  if type(direct) == "function" then return direct end
  return function(tvb) return tvb[name](tvb) end
end
-- (the check of a record captured in part, tvb:len() and tvb:reported_len(), cost 3,430 instructions a record
-- through __index, 1,610 so: bench/lua_throughput.py --instructions, plant mix)
local tvb_raw, tvb_len, tvb_reported_len = tvb_method("raw"), tvb_method("len"), tvb_method("reported_len")

-- Record times in integer nanoseconds from a base second of the capture (a double holds them exactly up to
-- 2^53: 104 days), as vw3-decode's Stamps keep the nanoseconds the file wrote (model.py Stamp): every
-- difference (response times, silences, the timeout) is then exact, and its text has vw3-decode's digits.
-- pinfo.abs_ts, a double near 1.7e9 s, is 238 ns coarse: a response time of 2.05 ms read 2.0 or 2.1 ms by
-- chance. pinfo.rel_ts (from Wireshark's reference record, the capture's first) and delta_ts (from the record
-- before) are small: their nanoseconds are exact. The clock is the capture's: a new one with each capture's
-- serial stream (`state`, made by proto.init); clock.times: by number (false: none), the times the usual case
-- below does not give (the first record's, a new reference's, ...) and those a stand-in reads again.
local clock = {} -- (NS: vw3.stream's, nanoseconds a second)
local function capture_clock(abs)
  if clock.capture ~= state then clock = { capture = state, times = {}, nanos = false } end
  if clock.base == nil and abs ~= nil then clock.base = floor(abs) end
  return clock
end

-- A time from abs_ts alone (238 ns coarse), on the microsecond while the capture's exact differences are
-- whole microseconds (a pcap's us, where the rounding makes it exact).
local function coarse_ns(c, abs)
  local ns = floor((abs - c.base) * NS + 0.5)
  if not c.nanos then ns = floor(ns / 1000 + 0.5) * 1000 end
  return ns
end

-- An exact difference in ns (seconds read as a double), and whether the capture has nanoseconds.
local function exact_ns(c, seconds)
  local ns = floor(seconds * NS + 0.5)
  if ns % 1000 ~= 0 then c.nanos = true end
  return ns
end

-- The clock record_ns reads the usual record's time from, in upvalues (fewer look-ups a record): the capture's
-- serial stream, the reference record's time (abs_ts - rel_ts) and that in ns, set where the clock learns its
-- reference (other_record_ns); the last usual record's number and time (chained_ns: the record before); the
-- number of the record whose time rel_ts alone gives (record_ns).
local usual_capture, usual_reference, usual_reference_ns, usual_number, usual_ns = nil, nil, nil, nil, nil
local usual_next = nil

-- The record's time from the one before (delta_ts) where that one's is known, else from abs_ts.
local function chained_ns(c, pinfo, number, abs)
  local before, delta = c.times[number - 1], pinfo.delta_ts
  if usual_capture == state and usual_number == number - 1 then before = usual_ns end -- (record_ns's last)
  if before and delta ~= nil and math.abs(delta) < 4e6 then return before + exact_ns(c, delta) end
  return coarse_ns(c, abs)
end

-- A usual record's time: from the reference's, rel_ts exact; the record after it may take rel_ts alone
-- (record_ns) where the reference's time is after the epoch's first second (the record then is not at
-- the epoch: its time is the reference's and rel_ts > 0).
local function usual_record_ns(number, rel)
  local from = rel * NS + 0.5
  local ns = usual_reference_ns + (from - from % 1)
  usual_number, usual_ns = number, ns
  if usual_reference >= 1 then usual_next = number + 1 end
  return ns
end

-- A record's time as record_ns reads it where it is not the usual case below: the first record, a new
-- reference, an RTAC record, one at the epoch, a stand-in (pinfo nil: its time kept). (abs: pinfo.abs_ts,
-- read already)
local function other_record_ns(pinfo, number, abs)
  local c = clock
  if c.capture ~= state or c.base == nil then c = capture_clock(abs ~= 0 and abs or nil) end
  local times = c.times
  if abs == nil then return times[number] or nil end -- (a stand-in for a record's pinfo: its time kept)
  local ns = rtac_times[number]
  if ns == nil and abs ~= 0 then
    -- The first record, or a new reference (a time reference set in the GUI): from the record before. (A
    -- record of the reference the clock knows is record_ns's usual case, which sets the reference with it.)
    local rel = pinfo.rel_ts
    ns = chained_ns(c, pinfo, number, abs)
    local reference = rel ~= nil and abs - rel -- (the reference record's time; 0: it has none)
    if reference and math.abs(reference) >= 1 then
      usual_capture, usual_reference, usual_reference_ns = state, reference, ns - exact_ns(c, rel)
      if reference >= 1 then usual_next = number + 1 end
    end
  end
  times[number] = ns or false
  return ns
end

-- A record's time as vw3-decode reads it, in ns (nil: none): the RTAC's own timestamp for RTAC serial
-- records (when the device saw the bytes: lane.rtac_ns), none for records at the epoch (vw3-decode -w
-- writes those for untimed input), the record's time otherwise. Read once a record; pinfo nil: a stand-in.
local function record_ns(pinfo, number)
  -- Nearly every record: the one after a usual record (usual_next) of the capture, not an RTAC record, a
  -- time after the reference record's (rel_ts > 0): its time from the reference's, read from rel_ts alone.
  -- The reference cannot have changed since the record before: Wireshark's reference is the capture's
  -- first record or one marked in the GUI, whose rel_ts is 0 (and a record of another protocol between
  -- the two breaks usual_next).
  if number == usual_next and pinfo ~= nil and usual_capture == state and rtac_times[number] == nil then
    local rel = pinfo_rel_ts(pinfo)
    if rel > 0 then return usual_record_ns(number, rel) end
  end
  usual_next = nil
  if pinfo == nil then return other_record_ns(nil, number, nil) end
  local abs = pinfo_abs_ts(pinfo)
  -- Else timed, of the capture whose reference record's time the clock knows, no RTAC record: its time
  -- from the reference's where abs_ts - rel_ts is that reference (other_record_ns: the rest).
  if usual_capture ~= state or abs == 0 or abs == nil or rtac_times[number] ~= nil then
    return other_record_ns(pinfo, number, abs)
  end
  local rel = pinfo_rel_ts(pinfo)
  local drift = rel ~= nil and abs - rel - usual_reference
  if not (drift and drift < 1e-6 and drift > -1e-6) then return other_record_ns(pinfo, number, abs) end
  return usual_record_ns(number, rel)
end

-- Is the second record timed (not at the epoch but within day 0: pcap.py within_day_zero), the first
-- record's time then the epoch's (dissector.lua epoch_first)?
function lane.epoch_timed(pinfo)
  local abs = pinfo.abs_ts
  if abs == 0 or abs >= DATA.timing.day_zero_end or rtac_times[pinfo.number] ~= nil then return false end
  local c = capture_clock(abs)
  c.times[1] = -c.base * NS -- (exact: 1.7e18 is a multiple of 2^9)
  return true
end

-- An RTAC record's own timestamp (u32 seconds, u32 microseconds) in ns, exact.
function lane.rtac_ns(seconds, micros)
  local c = capture_clock(seconds)
  return (seconds - c.base) * NS + micros * 1000
end

-- A response's time since its request (vw3.response_time), an NSTime, exact: 0.010157000, not abs_ts's
-- 0.010157108. nil where either has no time.
function lane.response_time(f)
  local request = f.request
  if f.time == nil or request.time == nil then return nil end
  local delta = f.time - request.time
  local sign = delta < 0 and -1 or 1 -- (stamped before its request: both parts negative, as an nstime holds it)
  local seconds = floor(delta * sign / NS)
  return NSTime.new(sign * seconds, sign * (delta * sign - seconds * NS))
end

-- A record's time kept for a stand-in that decodes it again (dissector.lua decode_again; false: none).
local function keep_time(number, ns)
  clock.times[number] = ns or false
end
