-- vw3.stream: the byte stream the framers read: record boundaries and times, noise runs, the glitch rule.
-- Mirrors dissector/framing/stream.py, dissector/framing/evidence.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.stream"]).

-- Functions one module hands to another, in one table (`lane`), defined where their rules are. Among
-- them the quick lanes (lane.answer, lane.request): a record that is the usual answer to the
-- request awaited, or a request met before (by its bytes, or its bytes before the values), framed,
-- paired, annotated and kept in one step; their parts are defined beside the rules they follow.
local lane = {}
-- What a short low pulse on an idle line reads as (stream.py GLITCH_BYTES): FF << k, a bus driver's
-- turn-around after a frame, a break (00).
local GLITCH = FRAMING.glitch_bytes
-- The stream the framers read: every record's bytes appended to the bytes not framed yet, as the Python
-- framers are fed chunks (dissector/framing/stream.py). s.b holds the unframed bytes from index 0,
-- s.n of them; s.base is the stream offset of s.b[0]. A record's end is a frame boundary (pcap records
-- are chunks with boundary=True), yet it is no end of data: a frame cut by it waits for the next
-- record, and the end of the capture (finish) decides what is still waiting.
-- Record ends (s.boundaries) and silences (s.silences, found by feed) are ascending stream offsets, lists asked by
-- bisection (framing/offsets.py Offsets), as are the record starts in s.times: a look-up through all of them made
-- a capture of one-byte records (a USB tap, a line at the wrong speed) cost each byte the buffer's records, many
-- times over. The index of the first entry of `list` above `value` (past the end: none); step 2: the entries at
-- odd indices alone (s.times' offsets).
local function first_above(list, value, step)
  local count = #list -- (a multiple of step: s.times holds pairs)
  if count <= 16 then -- (a few entries, the usual case: looked at in turn)
    for index = 1, count, step do
      if list[index] > value then return index end
    end
    return count + 1
  end
  local low, high = 1, count / step + 1 -- (entry numbers; the answer is in low .. high)
  -- (first where an even spread of the entries puts it: one-byte records' are, and a bisection of them was most
  -- of the cost of their bytes)
  local oldest, newest = list[1], list[count - step + 1]
  local guess = oldest < value and value < newest and (value - oldest) * (high - 2) / (newest - oldest) + 1 or 1
  guess = guess - guess % 1
  if list[guess * step - step + 1] <= value and list[guess * step + 1] > value then return guess * step + 1 end
  while low < high do
    local mid = (low + high) / 2
    mid = mid - mid % 1 -- (floor, without a call: most of a one-byte record's look-ups' cost)
    if list[mid * step - step + 1] > value then high = mid else low = mid + 1 end
  end
  return low * step - step + 1
end

-- The first offset of `list` after buffer index i, up to n (Offsets.first_after), as a buffer index; nil: none.
local function first_after(s, list, i, n)
  local at = list[first_above(list, s.base + i, 1)]
  if at ~= nil and at - s.base <= n then return at - s.base end
  return nil
end

-- Forget the first `count` entries of `list` (below the buffer's new base: Offsets.drop_below), moved down in place.
local function drop_first(list, count)
  if count <= 0 then return end
  local length = #list
  for index = count + 1, length do list[index - count] = list[index] end
  for index = length, length - count + 1, -1 do list[index] = nil end
end

local function boundary_at(s, i)
  return first_after(s, s.boundaries, i - 1, i) == i
end

-- Does a record start at i (stream.py _record_starts_at)? Every record's start is in s.times while its bytes are.
local function record_start(s, i)
  local times = s.times
  return times[first_above(times, s.base + i - 1, 2)] == s.base + i
end

-- The stream offset's time: the time of the record its byte came in (stream.py _time_at). s.times
-- holds (stream offset, time) pairs flat, oldest first, false for a record without a time.
local function time_at(s, offset)
  return s.times[first_above(s.times, offset, 2) - 1] or nil
end

-- Bytes of the noise run being built are copied out of the buffer: the run may outlast the records
-- (and buffers) it came from, and is shown in one piece.
-- A run with silences inside (noise.parts, add_noise) is given out as one item per stretch between them.
local function flush_noise(s, items)
  local noise = s.noise
  if noise ~= nil then
    local parts = noise.parts
    items[#items + 1] = noise
    if parts ~= nil then
      local bytes_, length = noise.bytes, noise.length
      for index = 1, #parts, 3 do
        local begin = parts[index]
        local stop = parts[index + 3] or length
        local piece = { kind = NOISE, offset = noise.offset + begin, length = stop - begin,
                        reason = parts[index + 1], time = parts[index + 2], bytes = {} }
        local copy = piece.bytes
        for k = begin + 1, stop do copy[k - begin] = bytes_[k] end
        items[#items + 1] = piece
      end
      for k = length, parts[1] + 1, -1 do bytes_[k] = nil end
      noise.length, noise.parts = parts[1], nil
    end
    s.noise = nil
  end
end

-- The line's timing as the Python framers take it (framing/timing.py LineTiming; DATA.timing, written from
-- it by codegen/timing_lua.py): at the `baud` preference's speed, as vw3-decode --baud; a speed --baud refuses
-- (linespeed.py MIN_BAUD, MAX_BAUD; 0) is DEFAULT_BAUD, vw3-decode's without it. A silence of t3.5 before a
-- record ends a noise run (found where noise is added, from the records' times: nothing is added to a frame's
-- path); one longer than t1.5 inside a frame (ASCII: 1 s) is warned of (inner_gaps).
local TIMING = DATA.timing
local CHAR_TIME, ASCII_CHAR_TIME, T15, T35, RTU_LIMIT
function lane.line_speed(baud)
  if baud < TIMING.min_baud or baud > TIMING.max_baud then baud = TIMING.default_baud end
  local bits, fixed = TIMING.rtu_bits, baud > TIMING.fixed_above
  CHAR_TIME, ASCII_CHAR_TIME = bits / baud, TIMING.ascii_bits / baud
  -- (in LineTiming._rtu_interval's order of operations: the same doubles)
  T15 = fixed and TIMING.fixed_t15 or 1.5 * bits / baud
  T35 = fixed and TIMING.fixed_t35 or 3.5 * bits / baud
  RTU_LIMIT = format(TIMING.rtu_limit, T15 * 1000, baud)
end
lane.line_speed(TIMING.default_baud)

-- Record times are integer nanoseconds (show.lua record_ns): a difference in seconds is theirs divided
-- once, as vw3-decode's Stamps subtract (model.py Stamp.__sub__), so that every comparison and text agrees.
local NS = 1e9

-- Seconds from a frame's first byte's time until its last byte was sent (a request's timeout starts then:
-- vw3.pairing's timed_out; model.py sent_in): its characters' time at the line's speed, or later where the record
-- holding its last byte says so (frame.tail, frame.tail_chars: tail_at). A function: the speed is the
-- preference's when it is called.
local function sent_in(frame)
  local char_time = frame.ascii and ASCII_CHAR_TIME or CHAR_TIME
  local sent, tail = frame.length * char_time, frame.tail
  if tail and frame.time then
    local last = (tail - frame.time) / NS + frame.tail_chars * char_time
    if last > sent then return last end
  end
  return sent
end

-- The record holding the frame's last byte, where it is not the one the frame starts at (stream.py _tail_at):
-- its time in frame.tail, and the bytes from its start to the frame's end in frame.tail_chars.
local function tail_at(s, frame)
  local times, stop = s.times, frame.offset + frame.length
  local index = first_above(times, stop - 1, 2) - 2
  local start = times[index]
  if start ~= nil and start ~= frame.offset and times[index + 1] then
    frame.tail, frame.tail_chars = times[index + 1], stop - start
  end
end

-- Silences longer than allowed inside the frame (timing.py inner_gaps: between the records it spans, each
-- less its bytes' time on the line), as warnings kept in frame.gaps: take_frame adds them after the
-- pairing's, where vw3-decode's GapChecker adds them (pipeline.py). s.times holds the frame's records yet.
local function inner_gaps(s, frame)
  local times, offset = s.times, frame.offset
  local stop, ascii = offset + frame.length, s.mode == "ascii"
  local char_time, limit = CHAR_TIME, T15
  if ascii then char_time, limit = ASCII_CHAR_TIME, TIMING.ascii_max_silence end
  for index = math.max(3, first_above(times, offset, 2)), #times, 2 do -- (the records after its first)
    local start, time, before = times[index], times[index + 1], times[index - 1]
    if start >= stop then break end -- (oldest first)
    if start > offset and time and before then
      local silence = (time - before) / NS - (start - times[index - 2]) * char_time
      if silence > limit then
        local gaps = frame.gaps or {}
        frame.gaps = gaps
        gaps[#gaps + 1] = say("inner_silence", { silence_ms = silence * 1000, byte = start - offset,
          limit = ascii and TIMING.ascii_limit or RTU_LIMIT })
      end
    end
  end
end

-- Was the line silent for t3.5 before bytes at stream offset `start` that came at `time`, after the record at
-- times[index] (timing.silence_before: from that record's time, less its bytes' time on the line)? Before the next
-- record (feed), before the end of the capture (vw3.records finish): stream.py _silent_until, the one rule.
local function silent_before(times, index, start, time)
  local before = times[index + 1]
  return time and before and (time - before) / NS - (start - times[index]) * CHAR_TIME >= T35
end

-- Was the line silent t3.5 from the bytes held until the capture's last record (any stream's, empty or not:
-- recorded_until), as before the next bytes? Then a silence cuts them, not the end of the capture, as live closes
-- them at one; never on an ASCII line, whose frame ends at its LF (stream.py finish_at).
local function silent_at_end(s)
  local times = s.times
  return s.mode ~= "ascii" and s.n > 0 and silent_before(times, #times - 1, s.base + s.n, recorded_until)
end

-- The index of the first record after i, before n, that a silence of t3.5 comes before (stream.py _silences), nil:
-- none.
local function silence_after(s, i, n)
  return first_after(s, s.silences, i, n - 1)
end

-- Why bytes are noise (data/modbus.toml [texts]): no frame starts there; too few left for one.
local NO_FRAME, TOO_SHORT = DATA.plain_texts.no_frame, DATA.plain_texts.too_short
-- Why the byte at i, where no frame starts, is noise (bounded.py _no_frame): too short for a frame where a silence
-- comes fewer than a frame's minimum bytes after it (live closes the bytes there), else no valid frame.
local function no_frame(s, i)
  return silence_after(s, i, i + MIN_ADU) and TOO_SHORT or NO_FRAME
end

local add_run
local function add_noise(s, start, stop, reason, items)
  local b = s.b
  -- Only glitch bytes since the last frame or boundary (stream.py _add_noise): the next start is anchored.
  if s.noise == nil and not s.noise_cut then s.glitches_only = true end
  local check_from, base, ends = start, s.base, s.boundaries
  local last = ends[first_above(ends, base + stop - 1, 1) - 1] -- (the last record end inside the bytes)
  if last ~= nil and last >= base + start then
    s.glitches_only = true
    check_from = last - base
  end
  if s.glitches_only then
    for k = check_from, stop - 1 do
      if not GLITCH[b[k]] then
        s.glitches_only = false
        break
      end
    end
  end
  local silences = s.silences
  if s.mode ~= "ascii" then -- (ASCII allows a second's silence inside a frame: stream.py)
    -- Records starting inside the bytes after a silence (stream.py feed, silence_before): the run stays one
    -- for the framer's decisions, its items are cut there (_add_noise).
    for index = first_above(silences, base + start - 1, 1), #silences do
      local at = silences[index] - base
      if at >= stop then break end -- (oldest first)
      if at > start then add_run(s, b, start, at, reason, items) end
      local noise = s.noise
      if noise ~= nil then
        local parts = noise.parts
        if parts == nil then
          parts = {}
          noise.parts = parts
        end
        parts[#parts + 1], parts[#parts + 2], parts[#parts + 3] = noise.length, reason, time_at(s, base + at)
      end
      start = at
    end
  end
  add_run(s, b, start, stop, reason, items)
end

-- Bytes start .. stop - 1 go to the noise run (no silence inside them).
add_run = function(s, b, start, stop, reason, items)
  while start < stop do
    local noise = s.noise
    if noise == nil then
      local offset = s.base + start
      noise = { kind = NOISE, offset = offset, length = 0, reason = reason, time = time_at(s, offset), bytes = {} }
      s.noise = noise
    end
    local take = math.min(stop - start, NOISE_ITEM_MAX - noise.length)
    local bytes_, length = noise.bytes, noise.length
    for k = 0, take - 1 do bytes_[length + k + 1] = b[start + k] end
    noise.length = length + take
    start = start + take
    if noise.length >= NOISE_ITEM_MAX then
      flush_noise(s, items)
      s.noise_cut = true
    end
  end
end

-- Bytes i .. stop - 1, where no frame starts, are noise (bounded.py _add_skipped): the bytes from each silence
-- inside on with their own reason (no_frame), as live closes them there.
local function add_skipped(s, i, stop, items)
  local at = silence_after(s, i, stop)
  while at ~= nil do
    add_noise(s, i, at, no_frame(s, i), items)
    i, at = at, silence_after(s, at, stop)
  end
  add_noise(s, i, stop, no_frame(s, i), items)
end

-- Does a request await an answer (protocol/rules.py awaits_answer): not a broadcast, not one the spec has no
-- server answer (DATA.pairing.never_answered, by its first data word: FC8 04 Force Listen Only Mode).
local NEVER_ANSWERED = DATA.pairing.never_answered
local function awaits_answer(frame)
  local values = NEVER_ANSWERED[frame.fn]
  if values == nil or frame.data_len < 2 then return frame.slave ~= 0 end
  local b, at = frame.b, frame.data_at
  return frame.slave ~= 0 and not values[b[at] * 256 + b[at + 1]]
end

-- The length of the normal answer a request implies, where the protocol table fixes it by the request
-- (framing/answers.py ANSWERS, written out as DATA.rules.answers: FC1..4 and FC23's reads). By code: the request's
-- quantity word's place in the frame, the count's unit and plus, the answer's length besides its byte count.
local ANSWERS = DATA.rules.answers

-- The length (CRC included) of the normal answer request `frame` implies (answers.py answer_length), nil: not
-- known. The data a quantity asks: unit bytes an item, or bits 8 to a byte (unit 0: protocol/rules.py data_bytes).
local function answer_length(frame)
  local rule = ANSWERS[frame.fn]
  if rule == nil or frame.data_len < rule[1] then return nil end
  local b, at = frame.b, frame.data_at + rule[1] - 2
  return rule[4] + rule[3] + data_bytes(b[at] * 256 + b[at + 1], rule[2])
end

-- The answer a request of the quick lanes (lane.request, lua/src/records.lua) leaves awaited: the request, with
-- the expectation it set (s.answer_request, s.answer_for); its length is read from its bytes, which it keeps (its
-- entry's), at the end of the capture alone (not_the_answer: false): a poll costs no more.
local function await_answer(s, frame)
  s.answer_for, s.answer_request, s.answer_length = s.expect, frame, false
end

-- What the framer expects after a frame: the answer to a request that awaits one (with its length: the frame's
-- bytes are dropped once it is decoded), else nothing; and what that answer must repeat (_await_after).
local function expect_after(s, frame)
  if frame.kind == REQUEST and awaits_answer(frame) then
    s.expect = frame.slave * 256 + frame.fn -- (a request's code is its function)
    s.answer_for, s.answer_request, s.answer_length = s.expect, frame, answer_length(frame)
  else
    s.expect = nil
  end
  if ECHO_CODES[frame.fn] then await_echo(s, frame) end -- (an FC8 sub-function)
end

local GLITCH_RUN, GLITCH_SCORE_MAX = FRAMING.glitch_run, FRAMING.glitch_score_max
local function emit(s, frame, items)
  -- How much the line shows 00 glitches before frames (stream.py _emit): +1 after a few glitch bytes with
  -- a 00 among them, -1 after other noise.
  local noise = s.noise
  if noise ~= nil then
    if s.glitches_only and noise.length <= GLITCH_RUN and noise.offset > 0 and not s.noise_cut then
      local bytes_ = noise.bytes
      for k = 1, noise.length do
        if bytes_[k] == 0 then
          s.glitch_runs = math.min(GLITCH_SCORE_MAX, s.glitch_runs + 1)
          break
        end
      end
    elseif s.glitch_runs > 0 then
      s.glitch_runs = s.glitch_runs - 1
    end
  end
  flush_noise(s, items)
  s.noise_cut = false
  if s.times[3] ~= nil then inner_gaps(s, frame) end -- (a frame of one record has no silence inside)
  if s.times[3] ~= nil or s.times[1] ~= frame.offset then tail_at(s, frame) end -- (else its record is its own)
  items[#items + 1] = frame
  s.framed_end = frame.offset + frame.length -- (a bound: bounded.py _bounded_start)
  expect_after(s, frame)
end

-- A request whose fields only a real one has (framing/evidence.py): a read within its quantity limits,
-- a coil set ON or OFF (the requests whose lifting rule names a coil value: FC5).
local PLAUSIBLE_READS, COIL_REQUESTS = DATA.protocol.plausible_reads, DATA.protocol.coil_requests
local COIL_VALUES = DATA.protocol.coil_values
local function plausible_request(b, i, length)
  if length ~= 8 or b[i] < 1 or b[i] > MAX_SLAVE then return false end
  local code, word = b[i + 1], b[i + 4] * 256 + b[i + 5]
  if COIL_REQUESTS[code] then return COIL_VALUES[word] == true end
  local limits = PLAUSIBLE_READS[code]
  return limits ~= nil and limits[1] <= word and word <= limits[2] and b[i + 2] * 256 + b[i + 3] + word <= 0x10000
end

-- Is a reading of `kind` and `length` at the answer awaited's start a normal answer of another length than its
-- request implies (rules.py Awaiting._not_the_answer)? Its byte count cannot be the answer's: at the end of the
-- capture the bytes are the next request (0C 03 20 D0 after a read of 3 registers: not a byte count of 32).
-- (A request kept for another expectation, or other than the one the pairing awaits now, s.pending, is left aside:
-- a quick lane that took a request without calling await_answer.)
local function not_the_answer(s, kind, length)
  local request, pending = s.answer_request, s.pending
  if kind ~= RESPONSE or length == NEED or request == nil or s.answer_for ~= s.expect then return false end
  if pending ~= nil and pending ~= request then return false end
  local answer = s.answer_length
  if answer == false then answer = answer_length(request) end
  return answer ~= nil and length ~= answer
end

-- Why bytes are noise when they begin the answer awaited (of `kind`, or a request read in its place) and the
-- capture ends inside them: `got` of its `total` bytes (NEED: not known); `silence`: a silence cuts them, and the
-- capture goes on (rules.py Awaiting._cut_reason; silence_cut, lua/src/rtu.lua).
local function cut_reason(kind, got, total, silence)
  local size = total == NEED and format("%d bytes of it", got) or format("%d of %d bytes", got, total)
  if silence then
    local what = kind == REQUEST and "a request" or kind == RESPONSE and "the response" or "the exception response"
    return format("%s%s (%s)", FRAMING.silence_cuts, what, size)
  end
  if kind == REQUEST then -- ('... inside a request': not the answer's words, which its request takes: rtu.py)
    return format("%sa request (%s)", FRAMING.cut_answer:sub(1, -5), size)
  end
  return format("%s%s (%s)", FRAMING.cut_answer, kind == RESPONSE and "response" or "exception response", size)
end

-- Records that are one frame with a good CRC, by their bytes (a Lua string: interned, or hashed once,
-- so a look-up is cheap): a polling bus sends the same requests every cycle, and the CRC costs most of
-- the framing. A verdict depends on the bytes alone. Bounded: a new table after CRC_SEEN_MAX records.
local CRC_SEEN_MAX = 32768
local crc_seen, crc_seen_count = {}, 0

-- Does a record's string (n bytes) hold one frame with a good CRC (feed_whole, the quick lanes)?
local function whole_crc_good(bytes, n)
  if crc_seen[bytes] then return true end
  if not crc_string_ok(bytes, n) then return false end
  if crc_seen_count >= CRC_SEEN_MAX then crc_seen, crc_seen_count = {}, 0 end
  crc_seen[bytes] = true
  crc_seen_count = crc_seen_count + 1
  return true
end

-- A repeated pattern (a line stuck on one value, a babbling device) makes every position a possible frame
-- start weighed in full: where the bytes repeat with a period, a position whose window (the most a decision
-- reads: REPEAT_WINDOW) lies in the repetition decides as the one a period before it did, under the same
-- state (rtu.py _repeats). Positions since .. i - 1 were noise under the state of now: the end of the noise
-- from i (at most `stop`) and the index before which trying again finds no more.
local REPEAT_WINDOW, REPEAT_PROBE = FRAMING.repeat_window, FRAMING.repeat_probe
local function repeats(s, b, i, since, n, stop)
  local from, period = i - REPEAT_PROBE, nil
  for p = 1, math.min(MAX_ADU, from - since) do -- (the nearest: the last bytes found again)
    local k = 0
    while k < REPEAT_PROBE and b[from + k] == b[from - p + k] do k = k + 1 end
    if k == REPEAT_PROBE then
      period = p
      break
    end
  end
  if period == nil then return i, i + 4 * REPEAT_PROBE end
  local limit = math.min(n, stop + REPEAT_WINDOW)
  limit = first_after(s, s.boundaries, i - period - 1, limit - 1) or limit -- (none inside: evidence)
  local stop_at = i
  while stop_at < limit and b[stop_at] == b[stop_at - period] do stop_at = stop_at + 1 end
  local last = stop_at - REPEAT_WINDOW
  if last < i then return i, math.max(i + 1, stop_at) end
  if last + 1 >= stop then return stop, stop end
  return last + 1, stop_at
end

-- Records captured in part (a snapshot length shorter than the record: editcap -s 5), by number: { captured,
-- original } lengths, as Wireshark's tvb gives them (tvb:len() below tvb:reported_len(): dissector.lua calls
-- lane.captured_in_part; proto.init empties the table). Kept by number: a record decoded again is cut again.
lane.parts = {}
function lane.captured_in_part(number, captured, original)
  lane.parts[number] = { captured, original }
end

-- What the bytes of a frame cut short tell (stream.py _part_fields, ascii.py's): its slave and function, nil
-- where not captured.
local HEX_DIGITS = DATA.ascii.hex_digits
local function part_fields(s, bytes)
  if s.mode ~= "ascii" then return string.byte(bytes, 1, 2) end
  local told = {}
  for k, at in ipairs({ 2, 4 }) do
    local high, low = string.byte(bytes, at, at + 1)
    if string.byte(bytes, 1) ~= 58 or low == nil or HEX_DIGITS[high] == nil or HEX_DIGITS[low] == nil then break end
    told[k] = HEX_DIGITS[high] * 16 + HEX_DIGITS[low] -- (58 above: ':')
  end
  return told[1], told[2]
end

-- `captured in part (5 of its 9 bytes; slave 2, function 3; the answer to #1): its CRC cannot be checked`, written
-- from the item's part (stream.py part_reason), never read back from the text.
local function part_reason(part)
  local told = {}
  if part.slave ~= nil then told[#told + 1] = "slave " .. part.slave end
  if part.fn ~= nil then told[#told + 1] = "function " .. part.fn end
  return "captured in part (" .. part.captured .. " of its " .. part.original .. " bytes"
    .. (told[1] ~= nil and "; " .. table.concat(told, ", ") or "")
    .. (part.answers ~= nil and "; the answer to #" .. part.answers or "") .. "): its " .. part.check .. " cannot be checked"
end

-- A record captured in part, its bytes after the stream's (lua/src/records.lua cut_part closed it): its item added to
-- `items`, whose reason says so (stream.py CAPTURED_IN_PART: no CRC or LRC can be checked on a frame cut short),
-- and its record table opened (take_items closes it); the stream then starts clean after it, as stream.py
-- restart_at leaves it: nothing buffered or awaited, the record's end a boundary and its time the last kept.
local function cut_stream(s, bytes, time, part, number, items)
  local n, start = #bytes, s.base
  local copy = {}
  for k = 1, n do copy[k] = string.byte(bytes, k) end
  local slave, fn = part_fields(s, bytes)
  local told = { captured = part[1], original = part[2], check = s.mode == "ascii" and "LRC" or "CRC", slave = slave, fn = fn }
  items[#items + 1] = {
    kind = NOISE, offset = start, length = n, time = time, bytes = copy, part = told, reason = part_reason(told),
  }
  s.b, s.n, s.base = {}, 0, start + n
  s.times, s.boundaries, s.silences = { start, time or false }, { start + n }, {}
  s.expect, s.echo, s.framed_end = nil, nil, nil
  s.glitches_only, s.noise_cut = true, false
  local record = { number = number, start = start, length = n, waiting = n }
  s.open[#s.open + 1], s.last = record, record
  return record
end
