-- vw3.feed: feeding records to the framers (whole-record frames first), what stays buffered.
-- Mirrors dissector/framing/stream.py (feed, finish).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.feed"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local feed
local feed_whole

local NO_BYTES = {} -- (the buffer once every byte is framed: never written to)

-- Drop the first `count` buffered bytes (framed or noise). The old table stays as it is: the frames
-- just found still read their bytes from it until they are decoded.
local function consume(s, count)
  if count == 0 then return end
  local b, n = s.b, s.n
  if count == n then
    -- (every byte framed, the usual case: no bytes to move; feed makes the next record's table)
    s.b, s.n, s.base = NO_BYTES, 0, s.base + count
  else
    local rest = {}
    for k = count, n - 1 do rest[k - count] = b[k] end
    s.b, s.n, s.base = rest, n - count, s.base + count
  end
  local base = s.base
  local times = s.times
  local count, keep = #times, 1
  for index = 1, count, 2 do
    if times[index] <= base then keep = index end
  end
  if keep > 1 then
    -- (moved down in place: no new list)
    local shift = keep - 1
    for index = keep, count do times[index - shift] = times[index] end
    for index = count, count - shift + 1, -1 do times[index] = nil end
  end
  local boundaries = s.boundaries
  boundaries[base] = nil -- (the usual case: the one boundary, the end of the record just framed)
  if next(boundaries) ~= nil then
    for offset in pairs(boundaries) do
      if offset <= base then boundaries[offset] = nil end
    end
  end
end

-- Feed one record's bytes (a Lua string; boundary: its end is a frame boundary) and frame what can be
-- framed; final: nothing more will come. Returns the items in stream order. built: the record's byte
-- table when feed_whole made it.
lane.flush_noise = flush_noise

-- A record that is one whole RTU frame, fed where no byte waits (nearly every record of a clean
-- capture): the frame run_rtu's fast path finds at 0, or nil (and the byte table when it was made) for
-- feed to frame the record. The stream is left as feed and consume leave it: no byte waits, the
-- record's time is the last one kept, no record end (its end is the stream's end).
-- Can a record of n bytes from `slave` be one whole frame where no byte waits (feed_whole, the quick lanes)?
local function takes_whole(s, n, slave)
  return s.n == 0 and s.noise == nil and s.mode == "rtu" and n >= MIN_ADU and n <= MAX_ADU and s.times[3] == nil
    and slave <= MAX_SLAVE and slave ~= 0 -- (a broadcast: is its 00 a glitch before a frame? match weighs it)
end

-- The stream after a whole record of n bytes is framed (its expectation set by the caller): no byte
-- waits, the record's time is the last one kept, no record end (its end is the stream's end).
function lane.advance(s, n, time)
  s.noise_cut = false
  local offset = s.base
  s.base = offset + n
  local times = s.times
  times[1] = offset
  if time == nil then times[2] = false else times[2] = time end
  return offset
end

-- The frame of a request met before (known_requests), its stream offset and time given: what framing
-- finds (the request's layout is the likeliest; its length and CRC checked when it was met). A frame of
-- the quick lanes packed once answered (lane.answer) is held by nothing else: it is taken again here, every
-- key set anew, so that a polling bus makes no table a request (lane.spare, a few at most).
lane.spare = {}
function lane.known_frame(known, offset, n, slave, code, time)
  local spare = lane.spare
  local count = #spare
  local f = spare[count]
  if f == nil then
    -- (the keys below made at once, as the constructor sizes them)
    f = { kind = 0, offset = 0, length = 0, slave = 0, fn = 0, crc = 0, crc_expected = 0, time = 0, b = 0, bi = 0,
      data_at = 0, data_len = 0, number = 0, record = 0, at = 0, fields = 0, start = 0, quantity = 0, registers = 0,
      bits = 0, request = 0, response = 0, known = 0, function_text = 0, span_label = 0, info = 0, slots = 0 }
  else
    spare[count] = nil
  end
  f.kind, f.offset, f.length, f.slave, f.fn, f.crc, f.crc_expected, f.time = REQUEST, offset, n, slave, code, known.crc,
    known.crc, time
  f.b, f.bi, f.data_at, f.data_len, f.number, f.record, f.at = known.b, 0, 2, n - 4, 0, 0, 0
  f.fields, f.start, f.quantity, f.registers, f.bits, f.request, f.response = nil, nil, nil, nil, nil, nil, nil
  f.known, f.function_text, f.span_label, f.info, f.slots = nil, nil, nil, nil, nil
  return f
end

feed_whole = function(s, bytes, time)
  local n = #bytes
  local byte = string.byte
  local slave, code = byte(bytes, 1, 2)
  if n < MIN_ADU or not takes_whole(s, n, slave) then return nil end
  local known = known_requests.entries[bytes]
  if known ~= nil and s.expect ~= slave * 256 + code then
    -- A request met before, where no answer of its slave and function is awaited, and the stream left as
    -- the lines below leave it (expect_after: a request's code is its function).
    local frame = lane.known_frame(known, s.base, n, slave, code, time)
    frame.known = known -- (take_frame decodes it from the entry)
    s.expect = slave * 256 + code
    lane.advance(s, n, time)
    return frame
  end
  local first = fast_interpretation(s, interpretations(s, slave, code)[1], slave, code)
  if first == nil then return nil end
  local b = { [0] = slave, byte(bytes, 2, n) }
  local length, is_scan = first[2](b, 0, n)
  if is_scan or length ~= n or not whole_crc_good(b, n, bytes) then return nil, b end
  local frame = rtu_frame(b, 0, s.base, time, first[1], n, true)
  expect_after(s, frame)
  lane.advance(s, n, time)
  return frame
end

-- The quick lane's framing (lane.answer): would feed_whole take the record (n bytes, its first two the
-- slave and function awaited) as one whole answer, by the function's length rule, with a good CRC? Only
-- for the functions whose answer's length is a byte count (count8: the rule's byte, plus its extra).
-- Changes nothing but the CRC verdicts kept. lane.advance then leaves the stream as feed_whole leaves it.
local COUNTED_ANSWERS = {}
for code, rules in pairs(DATA.protocol.rules) do
  if rules[2][1] == "count8" then COUNTED_ANSWERS[code] = { rules[2][2], rules[2][3] } end
end

function lane.frames_answer(s, bytes, n, slave, code)
  if not takes_whole(s, n, slave) or s.expect ~= slave * 256 + code then return false end
  local counted = COUNTED_ANSWERS[code]
  if counted == nil or counted[1] + 1 > n or counted[2] + string.byte(bytes, counted[1] + 1) ~= n then
    return false
  end
  return whole_crc_good(nil, n, bytes)
end

-- Would feed_whole take the record as a request met before (the slave and function of its first two
-- bytes; known_requests)?
function lane.frames_known(s, n, slave, code)
  return takes_whole(s, n, slave) and s.expect ~= slave * 256 + code
end

feed = function(s, bytes, time, boundary, final, built)
  local n = #bytes
  if n > 0 then
    local b, at = s.b, s.n
    local byte = string.byte
    local k = 1
    if at == 0 and n <= 4096 then
      -- Nothing left over (the usual case): the record's bytes in one constructor, b[0] in its hash
      -- part, the rest in its array part. (Frames already found keep the old table.)
      b = built or { [0] = byte(bytes, 1), byte(bytes, 2, n) }
      s.b = b
      k = n + 1
      s.whole = bytes -- (the buffer holds this record alone: see crc_good)
    elseif at == 0 then
      b = {} -- (never NO_BYTES, which stays empty)
      s.b = b
    end
    while k + 7 <= n do
      b[at + k - 1], b[at + k], b[at + k + 1], b[at + k + 2], b[at + k + 3], b[at + k + 4], b[at + k + 5],
        b[at + k + 6] = byte(bytes, k, k + 7)
      k = k + 8
    end
    for rest = k, n do b[at + rest - 1] = byte(bytes, rest) end
    local times = s.times
    local count = #times
    times[count + 1] = s.base + at
    if time == nil then times[count + 2] = false else times[count + 2] = time end
    s.n = at + n
    if boundary then s.boundaries[s.base + s.n] = true end
  end
  local items = s.items -- (one list a stream, emptied each time: its items are taken before the next feed)
  for index = #items, 1, -1 do items[index] = nil end
  local used
  if s.mode == "ascii" then used = run_ascii(s, final, items) else used = run_rtu(s, final, items) end
  s.whole = nil
  consume(s, used)
  if final then flush_noise(s, items) end
  return items
end

M.feed, M.feed_whole = feed, feed_whole
