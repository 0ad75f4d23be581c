-- vw3.rtu: RTU framing: frames by their length rules and CRC, damaged frames, CRC scans, the line's evidence.
-- Mirrors dissector/framing/rtu.py, dissector/framing/reach.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.rtu"]).
local GLITCH_ADDRESSES, GLITCH_SKIP, GLITCHY_AFTER = FRAMING.glitch_addresses, FRAMING.glitch_skip, FRAMING.glitchy_after
local MAX_COUNTED = FRAMING.max_counted -- (a length rule's frame over MAX_ADU: a good CRC only, warned: rules.py)

-- Does a layout at i check out and end where its record does (a code without a length rule: its CRC checks at
-- the record's end)? The source says a frame ends there: a glitch-byte reading of b[i] before a longer frame
-- crossing that end is not waited for, which in a single pass (tshark without -2) held every later record.
-- Second, the buffer length up to which more bytes cannot change the answer (reach.py _record_end's `until`): n + 1
-- for a rule that needs more bytes, a frame ending at n, a scan with no record end after i or an echo not all come;
-- a reading's end past n; the byte an FC43 object walk stopped short of (its fourth value, `wanted`), past it.
local function ends_record(s, b, i, n)
  local slave, code = b[i], b[i + 1]
  local list = interpretations(s, slave, code, b, i, n)
  local holds = (s.echo ~= nil and s.expect == slave * 256 + code and i + 1 + #s.echo.bytes >= n) and n + 1 or math.huge
  for index = 1, #list do
    local length, is_scan, walk, wanted = list[index][2](b, i, n)
    if length == NEED then holds = math.min(holds, n + 1) end
    if walk == NEED then holds = math.min(holds, i + (wanted or n - i) + 1)
    elseif walk ~= nil and i + walk > n then holds = math.min(holds, i + walk) end
    if is_scan then -- (reach.py _record_end: the record's length, from the scan's minimum on)
      local stop = first_after(s, s.boundaries, i, n) -- (the first record end after i)
      if stop == nil then holds = math.min(holds, n + 1) end
      length = stop ~= nil and stop - i >= length and stop - i or 0
    end
    if length >= MIN_ADU and length <= (is_scan and MAX_ADU or MAX_COUNTED) then
      if i + length >= n then holds = math.min(holds, i + length > n and i + length or n + 1) end
      if i + length <= n and boundary_at(s, i + length) and crc_ok_at(b, i, length) then return true, holds end
    end
  end
  return false, holds
end

-- The record ends' answers to ends_record for one stream and state (the answer awaited, its echo: reach.py EndAnswers):
-- `answered` by stream offset, `trues` those true (ascending), `expiry` by the stream end at which they may change the
-- offsets to ask again, low .. high the span whose every record end is answered (one-byte records: 250 a byte).
local ends = { count = math.huge }

local function answer_end(s, b, offset, n)
  local answer, holds = ends_record(s, b, offset - s.base, n)
  local trues, expiry = ends.trues, ends.expiry
  local at = first_above(trues, offset - 1, 1)
  if answer and trues[at] ~= offset then table.insert(trues, at, offset)
  elseif not answer and trues[at] == offset then table.remove(trues, at) end
  if not ends.answered[offset] then ends.answered[offset], ends.count = true, ends.count + 1 end
  local stop = s.base + holds -- (math.huge: never asked again)
  expiry[stop] = expiry[stop] or {}
  table.insert(expiry[stop], offset)
end

-- Answer the record ends from low up to before high not answered yet.
local function answer_ends(s, b, low, high, n)
  local boundaries = s.boundaries
  for index = first_above(boundaries, low - 1, 1), #boundaries do
    local offset = boundaries[index]
    if offset >= high then return end
    if not ends.answered[offset] then answer_end(s, b, offset, n) end
  end
end

-- Where a CRC scan from i stops (reach.py _framed_reach): the first record after i that is a frame of its own, else
-- n. A scan across it read noise and that frame as one frame, and waited for bytes past it in one pass.
local function framed_reach(s, b, i, n)
  local base = s.base
  local last, low, high = base + n, base + i + 1, base + math.min(n - MIN_ADU + 1, i + MAX_ADU)
  local ahead = s.boundaries[first_above(s.boundaries, base + i, 1)]
  if ahead == nil or ahead >= high then return n end -- (no record end to weigh: a record's own frame, mostly)
  local known = ends
  if known.s ~= s or known.expect ~= s.expect or known.echo ~= s.echo or last < known.last
      or last > known.last + MAX_ADU or known.count > 4 * MAX_ADU then
    known = { s = s, expect = s.expect, echo = s.echo, last = last, answered = {}, trues = {}, expiry = {},
      count = 0, low = low, high = low }
    ends = known
  end
  for stop = known.last + 1, last do -- (answers the bytes come since may change: asked again)
    local list = known.expiry[stop]
    known.expiry[stop] = nil
    for index = 1, list and #list or 0 do
      if list[index] > base then answer_end(s, b, list[index], n) else known.answered[list[index]] = nil end
    end
  end
  known.last = last
  if high > low then
    if low > known.high or high < known.low then known.low, known.high = low, low end -- (a span apart: anew)
    if low < known.low then answer_ends(s, b, low, known.low, n) end -- (the record ends before it, after it)
    if high > known.high then answer_ends(s, b, known.high, high, n) end
    known.low, known.high = low < known.low and low or known.low, high > known.high and high or known.high
  end
  local first = known.trues[first_above(known.trues, low - 1, 1)]
  return first ~= nil and first < high and first - base or n
end

-- Would a reading at i of `length` bytes (NEED: more than there are) swallow a record that is a frame of its own,
-- the first after i (framed_reach) starting inside it (reach.py _crosses_framed_record)? Then it is none, its bytes
-- come or not: waiting for them (a long answer read from noise, an FC23 request's byte count) held every later
-- record in one pass.
local function crosses_framed_record(s, b, i, length, n)
  return framed_reach(s, b, i, n) < (length == NEED and n or math.min(n, i + length))
end

-- Does an intact frame start at i? true, false, or nil when more bytes are needed to know (final: none
-- will come). With scan false, only layouts with a length rule count (rtu.py _valid_frame_at).
local function frame_at(s, b, i, n, final, scan)
  if n - i < MIN_ADU then
    if final then return i == n end
    return nil
  end
  local found = false -- (nil: a CRC scan found nothing yet, but a longer frame may still arrive)
  local list = interpretations(s, b[i], b[i + 1], b, i, n) -- (any address: 248..255 are framed)
  for index = 1, #list do
    local length, is_scan = list[index][2](b, i, n)
    if not is_scan and length == NEED then
      if final then return false end
      -- (bytes that would swallow a record that is a frame: none, not waited for)
      if not crosses_framed_record(s, b, i, length, n) then return nil end
    elseif not is_scan and length >= MIN_ADU and length <= MAX_COUNTED then
      if i + length > n then
        if not final and not crosses_framed_record(s, b, i, length, n) then return nil end
      elseif crc_ok_at(b, i, length) then
        return true
      end
    end
    if is_scan and scan ~= false then
      local reach = framed_reach(s, b, i, n) -- (not across a record that is a frame: rtu.py _valid_frame_at)
      if crc_scan(b, i, length, math.min(reach - i, MAX_ADU)) > 0 then return true end
      if not final and reach == n and n - i < MAX_ADU then found = nil end
    end
  end
  return found
end

-- frame_at's answers by the stream's length and position under one state (the buffer, the answer awaited, its
-- echo): noise asks a position again after each reading of the one before (followed), a flood some three times.
local ANSWER, BY_ANSWER, valid_known, valid_state = { [true] = 1, [false] = 2 }, { true, false, nil }, {}, {}
local function valid_frame_at(s, b, i, n, final, scan)
  local state = valid_state
  if state[1] ~= s or state[2] ~= b or state[3] ~= s.expect or state[4] ~= s.echo or state[5] ~= s.base then
    valid_known, state[1], state[2], state[3], state[4], state[5] = {}, s, b, s.expect, s.echo, s.base
  end
  local known = valid_known[n] or {}
  valid_known[n] = known
  local key = i * 4 + (final and 2 or 0) + (scan == false and 1 or 0)
  if known[key] ~= nil then return BY_ANSWER[known[key]] end
  local found = frame_at(s, b, i, n, final, scan)
  known[key] = ANSWER[found] or 3
  return found
end

-- Does a frame with a length rule and a good CRC start inside the bytes i .. i + length - 1? nil when bytes
-- still to come may tell (bounded.py _intact_inside): deciding before they come made the answer depend on where
-- the input was cut.
local function intact_inside(s, b, i, length, n, final)
  local found = false
  for j = i + 1, i + length - 1 do
    local at = valid_frame_at(s, b, j, n, final, false)
    if at then return true end
    if at == nil then found = nil end
  end
  return found
end

-- intact_inside, where records that are frames (a record that is this one, or the next one a frame: ends_record)
-- say no frame it holds crosses its record's end: one is not waited for (bounded.py _framed_inside).
local function framed_inside(s, b, i, length, n, final)
  local stop = i + length
  local bounded = boundary_at(s, stop) and (record_start(s, i) or (n - stop >= MIN_ADU and ends_record(s, b, stop, n)))
  return intact_inside(s, b, i, length, bounded and stop or n, final or bounded)
end

-- Does the line say a frame ends at `stop` (rtu.py _followed)? The end of the input (unless at_end is
-- false), a record boundary, or an intact frame, right there or after a few glitch bytes; nil: the bytes
-- that tell have not come yet.
local function followed(s, b, stop, n, final, at_end)
  local j = stop
  while true do
    if final and j == n then return at_end ~= false or s.cut_by_silence == true end -- (a silence at the end: a boundary)
    if boundary_at(s, j) then return true end
    local found = valid_frame_at(s, b, j, n, final)
    if found ~= false then return found end
    if j < n and GLITCH[b[j]] and j - stop < GLITCH_SKIP then j = j + 1 else return false end
  end
end

-- Does a frame of the slave at i start at `stop`, after glitch bytes or not, damaged or not (its answer,
-- rtu.py _answered)?
local function answered(s, b, i, stop, n, final)
  local slave = b[i]
  local j = stop
  while j - stop <= GLITCH_SKIP do
    if n - j < 2 then
      if final then return false end
      return nil
    end
    if b[j] == slave and possible_start(b[j + 1]) then return true end
    if not GLITCH[b[j]] then return false end
    j = j + 1
  end
  return false
end

-- May a CRC-valid frame found inside noise count (rtu.py _confirmed)?
local function confirmed(s, b, i, kind, length, n, final)
  local stop = i + length
  local following = followed(s, b, stop, n, final)
  if following ~= false then return following end
  if kind == REQUEST and b[i] ~= 0 then
    if plausible_request(b, i, length) then return true end
    return answered(s, b, i, stop, n, final)
  end
  return false
end

-- A frame without a length rule: the shortest CRC match the line confirms, first by a frame (or the end)
-- right after it, then after glitch bytes (a frame and a 00 check one byte longer). In step a scanned
-- frame is trusted over a short frame inside it; while resynchronising, the inner one wins.
local function scan_match(s, b, i, n, minimum, final)
  local from = 1
  if s.glitch_runs >= GLITCHY_AFTER then from = 2 end -- (a 00 after a frame is a glitch: rtu.py _scan)
  local reach = framed_reach(s, b, i, n)
  local lengths = crc_lengths(b, i, n, minimum, math.min(reach - i, MAX_ADU)) -- (none when minimum is past it)
  for pass = from, 2 do
    for k = 1, #lengths do
      local length = lengths[k]
      local following
      -- (a record's end right after it settles the first pass as a frame there would: _timedframe.h decide_at)
      if pass == 1 then following = boundary_at(s, i + length) or valid_frame_at(s, b, i + length, n, final)
      else following = followed(s, b, i + length, n, final) end
      if following == nil then return NEED end
      if following then
        local inside = s.noise ~= nil and framed_inside(s, b, i, length, n, final)
        if inside == nil then return NEED end
        if not inside then return length end
      end
    end
  end
  -- (up to a record that is a frame, every byte has come: nothing longer to wait for)
  if reach == n and n - i < MAX_ADU and not final then return NEED end
  return NONE
end

-- A counted layout's length when its count is 0, by kind and code (rtu.py _COUNTS_NOTHING): every count of the
-- spec counts something, so a reading with a bad CRC that counts nothing is no frame.
local COUNTS_NOTHING = DATA.protocol.counts_nothing -- (written out from that table by the code generator)
local function counts_nothing(b, i, kind, length)
  local counted = COUNTS_NOTHING[kind]
  return counted ~= nil and counted[b[i + 1]] == length
end

-- At the end of the input: do the bytes from i begin the answer awaited, cut by the end of the capture
-- (rtu.py _cut_answer)? The reason, or nil. (`silence`: by a silence at n: silence_cut)
local function cut_answer(s, b, i, n, silence)
  if n - i < 2 or not awaited(s, b, i, n) then return nil end
  -- (the answer's reading, unless it counts nothing or is not as long as the request implies: then the next, a
  -- request repeated before the answer, or the next one)
  local list, kind, length, is_scan, declared = interpretations(s, b[i], b[i + 1], b, i, n), nil, nil, nil, nil
  for index = 1, #list do
    local other = list[index][1]
    length, is_scan, declared = list[index][2](b, i, n)
    if is_scan or not (counts_nothing(b, i, other, length) or not_the_answer(s, other, length)) then
      kind = other
      break
    end
  end
  if kind == nil then return nil end
  if is_scan then
    -- (a rule with a CRC fallback: cut only when the bytes there hold no frame a scan finds)
    if declared == nil or declared == NONE then return nil end
    scanned.b = nil -- (match's scans are kept for its position only)
    if scan_match(s, b, i, n, length, true) ~= NONE then return nil end
    length = declared
  end
  if length ~= NEED and not (n - i < length and length <= (is_scan and MAX_ADU or MAX_COUNTED)) then return nil end
  if intact_inside(s, b, i, n - i, n, true) then return nil end
  return cut_reason(kind, n - i, length, silence)
end

-- The list with value appended (a new list for nil: most positions have none).
local function added(list, value)
  if list == nil then return { value } end
  list[#list + 1] = value
  return list
end

-- The first reading of `list` ({ kind, length }) after which `test` (followed, valid_frame_at) finds a
-- frame's end confirmed; NEED when the bytes that tell have not come; nil: none.
local function first_confirmed(s, b, i, n, final, list, test)
  for index = 1, #list do
    local following = test(s, b, i + list[index][2], n, final)
    if following == nil then return NEED end
    if following then return list[index] end
  end
  return nil
end

local function shortest_first(list)
  local order = { table.unpack(list) }
  table.sort(order, function(x, y) return x[2] < y[2] end)
  return order
end

-- kind, length, crc_ok for a frame at i; NEED (more bytes needed) or NONE (no frame starts at i).
local function match(s, b, i, n, final)
  scanned.b = nil -- (a scan is kept within one position's match only: s.b may change between them)
  local slave, code = b[i], b[i + 1]
  if GLITCH_ADDRESSES[slave] then -- (a glitch byte that is no device's address, before an intact frame)
    local after = valid_frame_at(s, b, i + 1, n, final)
    if after then return NONE end
    if after == nil and not ends_record(s, b, i, n) then return NEED end
  end
  local valid, damaged, waiting = nil, nil, nil
  local list = interpretations(s, slave, code, b, i, n)
  local awaits = awaited(s, b, i, n) -- (the answer awaited, its echo weighed)
  for index = 1, #list do
    local kind = list[index][1]
    local length, is_scan, declared = list[index][2](b, i, n)
    local sized = not is_scan and length >= MIN_ADU and length <= MAX_COUNTED
    if not is_scan and (length == NEED or (sized and i + length > n)) then
      -- (its bytes have not all come; not waited for if they would swallow a record that is a frame)
      if not final and not crosses_framed_record(s, b, i, length, n) then
        waiting = added(waiting, length)
      end
    elseif sized then
      if crc_ok_at(b, i, length) then
        valid = added(valid, { kind, length })
      elseif length <= MAX_ADU and not counts_nothing(b, i, kind, length) then -- (over it: a good CRC only)
        damaged = added(damaged, { kind, length })
      end
    end
    if is_scan then
      local found = scan_match(s, b, i, n, length, final)
      if found == NEED then
        waiting = added(waiting, NEED)
      elseif found > 0 then
        valid = added(valid, { kind, found })
      elseif declared ~= nil and declared >= MIN_ADU and declared <= MAX_ADU and declared <= n - i then
        damaged = added(damaged, { kind, declared }) -- (the length its fields give, its CRC bad: rtu.py)
      end
    end
  end
  if valid ~= nil then
    local chosen = valid[1]
    if #valid == 1 then
      -- CRC-16/MODBUS has no final XOR: a frame followed by a 00 byte also checks as a frame one byte
      -- longer. Unless this is the answer awaited, wait when a layout one byte longer may still arrive.
      if waiting ~= nil and not (chosen[1] == RESPONSE and awaits) and not boundary_at(s, i + chosen[2]) then
        for index = 1, #waiting do
          if waiting[index] == NEED or waiting[index] == chosen[2] + 1 then return NEED end
        end
      end
    else
      -- Two layouts check out: on a line that leaves 00 glitches the shortest reading it confirms (rtu.py),
      -- else a record boundary, the answer awaited, then what follows decides.
      local glitchy = s.glitch_runs >= GLITCHY_AFTER
      chosen = glitchy and first_confirmed(s, b, i, n, final, shortest_first(valid), followed) or nil
      for index = 1, #valid do
        if chosen == nil and boundary_at(s, i + valid[index][2]) then chosen = valid[index] end
      end
      chosen = chosen or (awaits and valid[1][1] == RESPONSE and valid[1])
        or first_confirmed(s, b, i, n, final, valid, valid_frame_at) or valid[1]
      if chosen == NEED then return NEED end
    end
    return chosen[1], chosen[2], true
  end
  if waiting ~= nil then return NEED end
  -- (a reserved address counts with a good CRC only: a glitch byte is one too; so does a broadcast the
  -- spec does not allow, a read: 00 is a glitch byte)
  if slave > MAX_SLAVE or (slave == 0 and DATA.not_broadcast[code]) then return NONE end
  if GLITCH[slave] then
    -- A glitch byte before a frame (a CRC scan's too, which intact_inside does not try).
    local after = valid_frame_at(s, b, i + 1, n, final)
    if after == nil then return NEED end
    if after then return NONE end
  end
  -- No layout checks out: a damaged frame is shown once if the line confirms its end (followed; the end of
  -- the input only for the answer awaited) and it holds none inside (a cut frame must not swallow the
  -- intact frame that follows it).
  local reach = nil -- (framed_reach at i, asked once for every reading: crosses_framed_record)
  for index = 1, #(damaged or NO_INTERPRETATION) do
    local kind, length = damaged[index][1], damaged[index][2]
    local stop = i + length
    reach = reach or framed_reach(s, b, i, n)
    local following = reach >= math.min(n, stop) and followed(s, b, stop, n, final, awaits)
    if following == nil then return NEED end
    if following then
      local inside = framed_inside(s, b, i, length, n, final)
      if inside == nil then return NEED end
      if not inside then return kind, length, false end
    end
  end
  return NONE
end

-- The frame of `length` bytes at b[i], its first byte at stream offset `offset`, received at `time`.
local function rtu_frame(b, i, offset, time, kind, length, crc_ok)
  local stop = i + length - 2
  local crc = b[stop] + b[stop + 1] * 256
  -- (a frame that checks out has the CRC it carries: no need to compute it again)
  return {
    kind = kind, offset = offset, length = length, slave = b[i], fn = b[i + 1] % 128,
    crc = crc, crc_expected = crc_ok and crc or crc16(b, i, stop), time = time,
    b = b, bi = i, data_at = i + 2, data_len = length - 4,
    number = 0, record = 0, at = 0, -- (set by take_items: in the constructor, the hash is made at its size)
    -- (and the keys decoding adds: a table that outgrows its hash is rebuilt, each key inserted again)
    fields = nil, start = nil, quantity = nil, registers = nil, bits = nil, request = nil, response = nil,
    warnings = length > MAX_ADU and { say("over_adu", { length = length, limit = MAX_ADU }) } or nil, -- (match's)
  }
end

-- Runs the line bounds (framing/bounded.py): bytes with a good CRC from a bound (a record's start or end, a
-- silence, the end of the last frame) to the next (the first intact frame, record's end or silence after it,
-- the end of the input) are a frame, whatever length the table's layout takes: one candidate a bound, once in
-- 65,536 runs for random bytes. Its length: 0 (none) or NEED.
local function bounded_start(s, i)
  return boundary_at(s, i) or record_start(s, i) or s.framed_end == s.base + i
end

local function bounded_run(s, b, i, n, final)
  if not bounded_start(s, i) then return 0 end
  -- (up to a record's end or silence, the frames inside it only: as if the input ended there)
  local stop, last = first_after(s, s.boundaries, i, n), true
  if stop == nil then stop, last = n, final end
  for stop_at = i + 1, math.min(stop, i + MAX_ADU) do
    local found = valid_frame_at(s, b, stop_at, stop, last, false) -- (at `stop` itself: true when last)
    if found == nil then return NEED end
    if found then return stop_at - i >= MIN_ADU and crc_ok_at(b, i, stop_at - i) and stop_at - i or 0 end
  end
  if not last and n - i < MAX_ADU then return NEED end
  return 0
end

-- The reading of `kind` among the interpretations at i: its length rule's answer (length, is_scan, ...), nil: none.
local function reading_of(s, b, i, n, kind)
  local list = interpretations(s, b[i], b[i + 1], b, i, n)
  for index = 1, #list do
    if list[index][1] == kind then return list[index][2](b, i, n) end
  end
  return nil
end

-- Does a layout at i whose length the bytes up to n hold check out (bounded.py _checks_out): an answer nobody
-- asked for, shorter than a request, or cut before its request reading's byte count? (Unlike valid_frame_at, a
-- request reading still without its length does not stop the others.)
local function checks_out(s, b, i, n)
  local list = interpretations(s, b[i], b[i + 1], b, i, n)
  for index = 1, #list do
    local length, is_scan = list[index][2](b, i, n)
    if not is_scan and length >= MIN_ADU and length <= n - i and crc_ok_at(b, i, length) then return true end
    if is_scan and crc_scan(b, i, length, math.min(n - i, MAX_ADU)) > 0 then return true end
  end
  return false
end

-- At the end of the input, where no answer awaited begins (cut_answer weighs that one): do the bytes from i, from
-- a bound, begin a request whose length the table knows (or whose count has not come), cut by the end of the
-- capture (the next poll: bounded.py _cut_request)? The reason, or nil. (`silence`: by a silence at n: silence_cut)
local function cut_request(s, b, i, n, silence)
  if n - i < 2 or awaited(s, b, i, n) or not bounded_start(s, i) then return nil end
  local slave, code = b[i], b[i + 1]
  if not ((slave >= 1 and slave <= MAX_SLAVE) or (slave == 0 and not DATA.not_broadcast[code])) then return nil end
  local length, is_scan = reading_of(s, b, i, n, REQUEST)
  if length == nil or is_scan or (length ~= NEED and not (n - i < length and length <= MAX_COUNTED)) then return nil end
  if checks_out(s, b, i, n) or intact_inside(s, b, i, n - i, n, true) then return nil end
  return cut_reason(REQUEST, n - i, length, silence)
end

-- Do the bytes from i up to the first silence after it begin a frame the silence cuts, weighed as at the end of the
-- input (bounded.py _silence_cut: live closes them there, and a file says what live says)? The silence's index and
-- the reason, or nil. A layout with a good CRC across the silence is a frame (the silence inside it a warning).
local function silence_cut(s, b, i, n)
  if s.expect == nil and not bounded_start(s, i) then return nil end
  local stop = silence_after(s, i, n)
  if stop == nil then return nil end
  local reason = cut_answer(s, b, i, stop, true) or cut_request(s, b, i, stop, true)
  if reason == nil or checks_out(s, b, i, n) then return nil end
  return stop, reason
end

-- Emit the frame of a bounded run at i (bounded.py _take_bounded): its length, 0 (none) or NEED. A warning says
-- the length its layout takes when that is another.
local function take_bounded(s, b, i, n, final, items)
  local length = bounded_run(s, b, i, n, final)
  if length <= 0 then return length end
  local kind = bounded_kind(s, b, i, n)
  local offset = s.base + i
  local frame = rtu_frame(b, i, offset, time_at(s, offset), kind, length, true)
  local expected, is_scan = reading_of(s, b, i, n, kind) -- (the length its layout takes: bounded.py _expected_length)
  if expected ~= nil and not is_scan and expected >= MIN_ADU and expected ~= length then
    frame.warnings = { say("frame_length", { length = length, expected = expected }) }
  end
  emit(s, frame, items)
  return length
end

-- The interpretation the fast paths try at a frame start: the likeliest, unless it is an exception
-- nobody awaits (those are weighed by match). nil: no fast path here.
local function fast_interpretation(s, first, slave, code)
  if first ~= nil and (first[1] ~= EXCEPTION or s.expect == slave * 256 + code % 128) then return first end
  return nil
end

-- Frame what the buffer holds (rtu.py _run): items in stream order; the index of the first byte left.
local function run_rtu(s, final, items)
  local b, n = s.b, s.n
  local i = 0
  local since, retry, was_cut, was_only = -1, 0, false, false
  while n - i >= MIN_ADU or (final and i < n) do
    if n - i < MIN_ADU then
      local stop, cut = silence_cut(s, b, i, n) -- (bytes a silence cuts first, as live closed them there)
      while stop ~= nil do
        add_noise(s, i, stop, cut, items)
        i = stop
        stop, cut = silence_cut(s, b, i, n)
      end
      local silence = s.cut_by_silence -- (a silence before the end of the capture: vw3.records finish)
      add_noise(s, i, n, cut_answer(s, b, i, n, silence) or cut_request(s, b, i, n, silence) or TOO_SHORT, items)
      return n
    end
    local stop = i -- (noise to stop: a repetition decided before, or bytes no frame starts at)
    -- (the answer awaited and the line's glitchiness change with a frame only, which ends the noise)
    if s.noise == nil or final then
      since = -1
    elseif since < 0 or s.noise_cut ~= was_cut or s.glitches_only ~= was_only then
      since, was_cut, was_only = i, s.noise_cut, s.glitches_only
    elseif i >= retry and i - since >= REPEAT_PROBE then
      stop, retry = repeats(s, b, i, since, n, i + NOISE_ITEM_MAX - s.noise.length)
    end
    local slave, code = b[i], b[i + 1]
    local first = stop == i and interpretations(s, slave, code, b, i, n)[1] or nil
    -- (the length of a run the line bounds where no frame starts, or no layout checks out below: take_bounded)
    local taken = first == nil and stop == i and take_bounded(s, b, i, n, final, items) or 0
    if taken == NEED then break end
    if taken > 0 then
      i = i + taken
    elseif first == nil then
      if stop == i then
        -- No frame starts here: skip to the next byte pair that could start one.
        stop = i + 1
        while stop < n - 1 and not possible_start(b[stop + 1]) do stop = stop + 1 end
        if stop >= n - 1 then stop = final and n or n - 1 end
      end
      add_skipped(s, i, stop, items)
      i = stop
    else
      local kind, length, crc_ok = nil, nil, true
      -- Fast path: the likeliest interpretation checks out and the next byte is not a 00 (which may belong
      -- to a longer frame, see match), or the frame ends where the record does (a record boundary settles
      -- what match would weigh): nearly every frame of a clean bus.
      if s.noise == nil and fast_interpretation(s, first, slave, code) and not GLITCH_ADDRESSES[slave] then
        local found, is_scan = first[2](b, i, n)
        if not is_scan and found >= MIN_ADU and found <= MAX_ADU
            and ((i + found < n and b[i + found] ~= 0) or (i + found == n and boundary_at(s, n)))
            and crc_ok_at(b, i, found) then
          kind, length = first[1], found
        end
      end
      if kind == nil then
        local cut = final and (cut_answer(s, b, i, n, s.cut_by_silence) or cut_request(s, b, i, n, s.cut_by_silence))
        if cut then
          -- (noise: up to a silence inside that cuts them first, as live closed them there)
          local upto, silence = silence_cut(s, b, i, n)
          if upto ~= nil then cut = silence else upto = n end
          taken = take_bounded(s, b, i, n, final, items)
          if taken == 0 then
            add_noise(s, i, upto, cut, items)
            taken = upto - i -- (taken as noise)
          end
        else
          kind, length, crc_ok = match(s, b, i, n, final)
          if kind == NEED then break end
          if kind == NONE or not crc_ok then taken = take_bounded(s, b, i, n, final, items) end
          if taken == NEED then break end
        end
        -- Resynchronising inside noise (not in step, at a record boundary, after nothing but glitch bytes
        -- since one): random bytes pass a CRC 1 time in 65,536 per layout tried, so such a frame counts
        -- only when the line confirms it (rtu.py _confirmed).
        if taken == 0 and kind ~= NONE and crc_ok and (kind == REQUEST or not awaited(s, b, i, n))
            and not (s.noise == nil or s.glitches_only or boundary_at(s, i)) then
          local following = confirmed(s, b, i, kind, length, n, final)
          if following == nil then break end
          if not following then kind = NONE end
        end
      end
      if taken > 0 then
        i = i + taken
      elseif kind == NONE then
        -- (bytes up to a silence that begin a frame it cuts: their reason, as live's: silence_cut)
        local upto, why = silence_cut(s, b, i, n)
        if upto == nil then upto, why = i + 1, no_frame(s, i) end
        add_noise(s, i, upto, why, items)
        i = upto
      else
        local offset = s.base + i
        emit(s, rtu_frame(b, i, offset, time_at(s, offset), kind, length, crc_ok), items)
        i = i + length
      end
    end
  end
  return i
end
