-- vw3.feed: feeding records to the framers (whole-record frames first), what stays buffered.
-- Mirrors dissector/framing/stream.py (feed, finish).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.feed"]).

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
  -- (the record holding the base, or the one before a record starting there: the silence before that record
  -- is measured from it when its bytes join a noise run: add_noise)
  local times = s.times
  drop_first(times, first_above(times, base - 1, 2) - 3)
  -- (one at the new base still counts: the next run starts there, however the feeding went: stream.py)
  drop_first(s.boundaries, first_above(s.boundaries, base - 1, 1) - 1)
  drop_first(s.silences, first_above(s.silences, base - 1, 1) - 1)
end

-- Can a record of n bytes from `slave` be one whole frame where no byte waits (feed_whole, the quick lanes)?
local function takes_whole(s, n, slave)
  return s.n == 0 and s.noise == nil and s.mode == "rtu" and n >= MIN_ADU and n <= MAX_ADU and s.times[3] == nil
    and slave <= MAX_SLAVE and slave ~= 0 -- (a broadcast: is its 00 a glitch before a frame? match weighs it)
end

-- The stream after a whole record's frame of n bytes, counted (its expectation set by the caller); its offset
-- and number: no byte waits, the record's time is the last one kept, no record end (its end is the stream's end).
function lane.advance(s, n, time)
  s.noise_cut = false
  local offset = s.base
  s.base = offset + n
  local times = s.times
  times[1] = offset
  if time == nil then times[2] = false else times[2] = time end
  local count = s.count + 1
  s.count = count
  return offset, count
end

-- A record that is one whole RTU frame, fed where no byte waits (nearly every record of a clean
-- capture): the frame run_rtu's fast path finds at 0, or nil (and the byte table when it was made) for
-- feed to frame the record. The stream is left as feed and consume leave it: no byte waits, the
-- record's time is the last one kept, no record end (its end is the stream's end), the frame counted.
local function feed_whole(s, bytes, time)
  local n = #bytes
  local byte = string.byte
  local slave, code = byte(bytes, 1, 2)
  if not takes_whole(s, n, slave) then return nil end -- (its length checked before its slave: n may be 0)
  local first = fast_interpretation(s, interpretations(s, slave, code)[1], slave, code)
  if first == nil then return nil end
  local b = { [0] = slave, byte(bytes, 2, n) }
  local length, is_scan = first[2](b, 0, n)
  if is_scan or length ~= n or not whole_crc_good(bytes, n) then return nil, b end
  local frame = rtu_frame(b, 0, s.base, time, first[1], n, true)
  expect_after(s, frame)
  lane.advance(s, n, time)
  return frame
end

-- Feed one record's bytes (a Lua string; boundary: its end is a frame boundary) and frame what can be
-- framed; final: nothing more will come. Returns the items in stream order. built: the record's byte
-- table when feed_whole made it.
local function feed(s, bytes, time, boundary, final, built)
  local n = #bytes
  if s.silences == nil then s.silences = {} end -- (vw3.annotator new_state makes the rest of the stream)
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
    local times, silences = s.times, s.silences
    local count = #times
    times[count + 1] = s.base + at
    if time == nil then times[count + 2] = false else times[count + 2] = time end
    -- (a silence of t3.5 before the record: stream.py feed; a record is only ever added after the ones kept)
    if count > 0 and silent_before(times, count - 1, s.base + at, time) then silences[#silences + 1] = s.base + at end
    s.n = at + n
    if boundary then s.boundaries[#s.boundaries + 1] = s.base + s.n end
  end
  local items = s.items -- (one list a stream, emptied each time: its items are taken before the next feed)
  for index = #items, 1, -1 do items[index] = nil end
  local used
  if s.mode == "ascii" then used = run_ascii(s, final, items) else used = run_rtu(s, final, items) end
  consume(s, used)
  if final then flush_noise(s, items) end
  return items
end
