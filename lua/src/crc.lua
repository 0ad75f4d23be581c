-- vw3.crc: CRC-16/MODBUS on table lookups (no bitwise operators: the same on Lua 5.2 and 5.4).
-- Mirrors dissector/protocol/crc.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.crc"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)

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

-- The lengths from `minimum` to `last` at which the bytes from i end in their CRC (protocol/crc.py
-- crc_lengths), written into `lengths`, their count returned; without `lengths`, the first such length (0:
-- none). One running CRC over the growing frame: each length costs one byte, not a new CRC.
local function crc_scan(b, i, minimum, last, lengths)
  if minimum > last then return 0 end
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

-- The lengths from `minimum` to `last` at which the bytes from i end in a valid CRC, in order (rtu.py
-- crc_lengths). Kept for the position being matched: its interpretations (a code without a length rule
-- is scanned as a request and as a response) and scan_match's two passes share one scan, not four. A
-- flood of one byte that starts a scanned frame everywhere (0x2B, 0x69, 0x6E, 0x41: any slave, an
-- unknown code) would otherwise scan at every byte. A window of one byte value (a flood) has the same
-- lengths wherever it starts: they are kept by the byte, minimum and last (at most FLOOD_KEEP of them),
-- and the run of that byte around the position is kept per buffer (buffers are only appended to: a run
-- found stays one).
local scanned = { lengths = {} }
local run = { start = 0, stop = 0 }
local flood_lengths, flood_kept, FLOOD_KEEP = {}, 0, 4096
local function crc_lengths(b, i, n, minimum, last)
  local memo = scanned
  if memo.b == b and memo.i == i and memo.n == n and memo.minimum == minimum and memo.last == last then
    return memo.lengths
  end
  local c = b[i]
  if run.b ~= b or i < run.start or i >= run.stop then run.b, run.start, run.stop = b, i, i + 1 end
  local stop = run.stop
  while stop < n and b[stop] == c do stop = stop + 1 end
  run.stop = stop
  local key, lengths = nil, nil
  if stop - i >= last then -- b[i] .. b[i + last - 1], every byte a scan reads, are c
    key = (c * 512 + minimum) * 512 + last
    lengths = flood_lengths[key]
  end
  if lengths == nil then
    lengths = {}
    crc_scan(b, i, minimum, last, lengths)
    if key ~= nil then
      if flood_kept >= FLOOD_KEEP then flood_lengths, flood_kept = {}, 0 end
      flood_lengths[key], flood_kept = lengths, flood_kept + 1
    end
  end
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
local function crc_ok_at(b, i, length)
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
