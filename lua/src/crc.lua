-- vw3.crc: CRC-16/MODBUS on table lookups (no bitwise operators: the same on Lua 5.2 and 5.4).
-- Mirrors dissector/protocol/crc.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.crc"]).

local floor = math.floor
local format = string.format
local concat = table.concat

-- A table that makes each entry on its first use, make(key), and keeps it (texts and labels shown again
-- and again: string.format costs more than a look-up).
local function made_once(make)
  return setmetatable({}, { __index = function(made, key)
    local value = make(key)
    made[key] = value
    return value
  end })
end

-- The collector in larger steps, and a new cycle at 1.5 times the memory in use rather than 2: the
-- records of a capture stay for its whole length, the default small steps went over that large heap
-- again and again (bench/README.md), and the default pause let the garbage of a cycle double the peak.
-- Wireshark's Lua state is shared: this tunes speed and memory only.
pcall(collectgarbage, "setstepmul", 1000)
pcall(collectgarbage, "setpause", 150)

-- The CRC runs on table lookups only (a call of `bxor` per byte, a C function on Lua 5.2, cost more than
-- all the rest of the framing), two bytes a step: the register is 16 bits wide, so after two bytes it
-- depends only on (register XOR the two bytes), and one 65,536-entry table (TWO_LO, TWO_HI: its two
-- bytes, times 256) gives it. XOR8[a * 256 + b] = a XOR b; CRC_LO and CRC_HI are the bytes of the
-- one-byte table. No XOR of Lua or Wireshark is needed: XOR8 builds the rest.
local XOR8, CRC_LO, CRC_HI, TWO_LO, TWO_HI = {}, {}, {}, {}, {}
-- XOR8 row by row, each from an earlier one: a XOR b is (a - top) XOR b plus top where b lacks the bit
-- top (a's highest), minus top where b has it (65,536 calls of bxor were most of the plugin's start-up).
for b = 0, 255 do XOR8[b] = b end
do
  local top = 1
  for a = 1, 255 do
    if a == top * 2 then top = a end
    local row, base = a * 256, (a - top) * 256
    for block = 0, 255, 2 * top do
      for b = block, block + top - 1 do XOR8[row + b] = XOR8[base + b] + top end
      for b = block + top, block + 2 * top - 1 do XOR8[row + b] = XOR8[base + b] - top end
    end
  end
end
-- The one-byte table (protocol/crc.py, generated), its bytes apart.
for byte = 0, 255 do
  local entry = DATA.crc_table[byte + 1]
  CRC_LO[byte], CRC_HI[byte] = entry % 256, floor(entry / 256)
end
-- One byte (b) into the register (lo, hi): lo' = hi XOR T_lo[lo XOR b], hi' = T_hi[lo XOR b].
-- (filled in index order: a table filled out of order keeps its keys in the hash part, rebuilt again and
-- again, until half of them are there: that tripled the plugin's start-up)
for hi = 0, 255 do
  for lo = 0, 255 do
    local index = lo -- the first byte in: lo XOR 0, then the second byte (0) into the result
    local lo1, hi1 = XOR8[hi * 256 + CRC_LO[index]], CRC_HI[index]
    TWO_LO[hi * 256 + lo], TWO_HI[hi * 256 + lo] = XOR8[hi1 * 256 + CRC_LO[lo1]] * 256, CRC_HI[lo1] * 256
  end
end

local byte, unpack = string.byte, table.unpack

-- One byte into a running CRC, its register's two bytes (lo, hi; 0xFF, 0xFF: a new CRC): over bytes and then
-- their CRC it runs to 0, 0. (The mode sample's pair scan, rtu_pair_end, runs one from each place a frame
-- may start.)
local function crc_step(lo, hi, value)
  local index = XOR8[lo * 256 + value]
  return XOR8[hi * 256 + CRC_LO[index]], CRC_HI[index]
end

-- CRC-16/MODBUS of bytes[from] .. bytes[to - 1], from the register l, h (its two bytes times 256, as TWO_LO
-- and TWO_HI hold them: fewer operations a byte; 0xFF00, 0xFF00: a new CRC); returns the register so.
-- `read` reads the bytes sixteen a call (then four, two, one): unpack from a 0-based byte table,
-- string.byte from a string. Called as crc_string_ok(bytes, n), without `read`: does a record's string
-- (the whole frame, n bytes, 1-based) end in its CRC? (A record of one frame is checked before its byte
-- table is needed, and a call of string.byte costs less than the table reads it saves.)
local function crc_string_ok(bytes, to, read, from, l, h)
  local check = read == nil
  if check then read, from, to, l, h = byte, 1, to - 1, 0xFF00, 0xFF00 end
  local k = from
  while k + 15 < to do
    local a, b, c, d, e, f, g, i, a2, b2, c2, d2, e2, f2, g2, i2 = read(bytes, k, k + 15)
    local w = XOR8[h + b] * 256 + XOR8[l + a]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + d] * 256 + XOR8[l + c]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + f] * 256 + XOR8[l + e]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + i] * 256 + XOR8[l + g]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + b2] * 256 + XOR8[l + a2]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + d2] * 256 + XOR8[l + c2]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + f2] * 256 + XOR8[l + e2]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + i2] * 256 + XOR8[l + g2]
    l, h = TWO_LO[w], TWO_HI[w]
    k = k + 16
  end
  while k + 3 < to do
    local a, b, c, d = read(bytes, k, k + 3)
    local w = XOR8[h + b] * 256 + XOR8[l + a]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + d] * 256 + XOR8[l + c]
    l, h = TWO_LO[w], TWO_HI[w]
    k = k + 4
  end
  if k + 1 < to then
    local a, b = read(bytes, k, k + 1)
    local w = XOR8[h + b] * 256 + XOR8[l + a]
    l, h = TWO_LO[w], TWO_HI[w]
    k = k + 2
  end
  if k < to then
    local index = XOR8[l + read(bytes, k, k)]
    l, h = XOR8[h + CRC_LO[index]] * 256, CRC_HI[index] * 256
  end
  if check then
    local crc_lo, crc_hi = read(bytes, to, to + 1) -- (low byte first)
    return l == crc_lo * 256 and h == crc_hi * 256
  end
  return l, h
end
local crc_run = crc_string_ok -- (a byte table's CRC: crc_run(b, to, unpack, from, l, h))

-- Windows that repeat a short pattern (a line stuck on one value, a device babbling a few bytes: hostile
-- floods make every position a frame start weighed in full, its CRCs over 28 to 256 bytes each, some of
-- them twice: at a position, then as what follows the one before) have the same CRCs wherever they start
-- in the pattern's phase: their answers are kept by the pattern (its period, bytes) and the lengths asked.
-- The run of one period around the last window asked is kept per buffer (buffers are only appended to: a
-- run found stays one, and grows as bytes come). Windows shorter than PERIODIC_FROM cost less than the look.
local PERIOD_MAX, PERIODIC_FROM, PERIODIC_KEEP = 4, 8, 4096
local run_b, run_p, run_start, run_stop = nil, 0, 0, 0
local run_keys = {} -- (the run's pattern as a window starting at i has it, by i % run_p: pattern_of's keys)
local periodic, periodic_kept = {}, 0

-- The pattern b[i .. i + length - 1] repeats, as a number (its bytes, then its period: PERIOD_MAX bytes and
-- the period keep it exact in a double); nil: none of PERIOD_MAX bytes or less.
local function pattern_of(b, i, length)
  local stop, p, known = i + length, nil, nil
  if b == run_b then
    -- (the run kept, grown to the window where it is near: windows ahead and behind are asked in turn)
    local q, start, k = run_p, run_start, run_stop
    if i < start and start - i <= length then
      while start > i and b[start - 1] == b[start - 1 + q] do start = start - 1 end
      run_start = start
    end
    if i >= start and i - k <= length then
      while k < stop and b[k] == b[k - q] do k = k + 1 end -- (nil past the buffer's end: the run ends there)
      run_stop = k
      if k >= stop then p = q elseif k >= i + q then known = q end -- (known: it ends inside the window)
    end
  end
  if p == nil then
    for q = 1, PERIOD_MAX do
      if q ~= known then
        local k = i + q
        while k < stop and b[k] == b[k - q] do k = k + 1 end
        if k >= stop then
          run_b, run_p, run_start, run_stop, p = b, q, i, k, q
          for start = i, i + q - 1 do
            local key = 0
            for at = start + q - 1, start, -1 do key = key * 256 + b[at] end
            run_keys[start % q] = key * 8 + q
          end
          break
        end
      end
    end
    if p == nil then return nil end
  end
  return run_keys[i % p]
end

-- The answer kept for `key` (a pattern and what was asked of it), or made by make(...) and kept.
local function kept_for(key, make, ...)
  local known = periodic[key]
  if known == nil then
    known = make(...)
    if periodic_kept >= PERIODIC_KEEP then periodic, periodic_kept = {}, 0 end
    periodic[key], periodic_kept = known, periodic_kept + 1
  end
  return known
end

-- The lengths from `minimum` to `last` at which the bytes from i end in their CRC (protocol/crc.py
-- crc_lengths), written into `lengths`, their count returned; without `lengths`, the first such length (0:
-- none). One running CRC over the growing frame: each length costs one byte, not a new CRC.
local function crc_scan_run(b, i, minimum, last, lengths)
  local count = 0
  local l, h = crc_run(b, i + minimum - 2, unpack, i, 0xFF00, 0xFF00)
  local lo, hi = floor(l / 256), floor(h / 256)
  for length = minimum, last do
    local stop = i + length - 2
    local byte = b[stop]
    if lo == byte and hi == b[stop + 1] then
      if lengths == nil then return length end
      count = count + 1
      lengths[count] = length
    end
    local index = XOR8[lo * 256 + byte]
    lo, hi = XOR8[hi * 256 + CRC_LO[index]], CRC_HI[index]
  end
  return count
end

local function all_lengths(b, i, minimum, last)
  local lengths = {}
  crc_scan_run(b, i, minimum, last, lengths)
  return lengths
end

local function crc_scan(b, i, minimum, last, lengths)
  if minimum > last then return 0 end
  local key = last >= PERIODIC_FROM and pattern_of(b, i, last) or nil
  if key == nil then return crc_scan_run(b, i, minimum, last, lengths) end
  -- (a negative key: a scan's, apart from crc_ok_at's; minimum and last below 512)
  local found = kept_for(-((key * 512 + minimum) * 512 + last), all_lengths, b, i, minimum, last)
  if lengths == nil then return found[1] or 0 end
  local count = #found
  for index = 1, count do lengths[index] = found[index] end
  return count
end

-- The lengths from `minimum` to `last` at which the bytes from i end in a valid CRC, in order (rtu.py
-- crc_lengths). Kept for the position being matched: its interpretations (a code without a length rule
-- is scanned as a request and as a response) and scan_match's two passes share one scan, not four. (A
-- flood's windows are kept by their pattern: crc_scan.)
local scanned = { lengths = {} }
local function crc_lengths(b, i, n, minimum, last)
  local memo = scanned
  if memo.b == b and memo.i == i and memo.n == n and memo.minimum == minimum and memo.last == last then
    return memo.lengths
  end
  local lengths = {}
  crc_scan(b, i, minimum, last, lengths)
  memo.b, memo.i, memo.n, memo.minimum, memo.last, memo.lengths = b, i, n, minimum, last, lengths
  return lengths
end

local function crc16(b, from, to)
  local l, h = crc_run(b, to, unpack, from, 0xFF00, 0xFF00)
  return h + floor(l / 256)
end

-- Does the frame of `length` bytes at i carry a good CRC? The running CRC of the last frame start is
-- kept: the layouts tried at one start (a request of 8 bytes, then a response of 5 + byte count, then the
-- frame that follows...) share their first bytes, and the CRC costs most of the framing. (Byte tables
-- are never changed below their end, so a CRC once computed stays right.)
local crc_b, crc_i, crc_to, crc_l, crc_h = nil, -1, -1, 0xFF00, 0xFF00
local function crc_ok_run(b, i, length)
  local stop = i + length - 2
  local l, h
  if b == crc_b and i == crc_i and stop >= crc_to then
    l, h = crc_run(b, stop, unpack, crc_to, crc_l, crc_h)
  else
    l, h = crc_run(b, stop, unpack, i, 0xFF00, 0xFF00)
  end
  crc_b, crc_i, crc_to, crc_l, crc_h = b, i, stop, l, h
  return l == b[stop] * 256 and h == b[stop + 1] * 256
end

local function crc_ok_at(b, i, length)
  if length < PERIODIC_FROM then return crc_ok_run(b, i, length) end
  local key
  -- (a window inside the run kept: its pattern by its phase, pattern_of's answer without the call)
  if b == run_b and i >= run_start and i + length <= run_stop then key = run_keys[i % run_p] else
    key = pattern_of(b, i, length)
  end
  if key == nil then return crc_ok_run(b, i, length) end
  return kept_for(key * 512 + length, crc_ok_run, b, i, length)
end
