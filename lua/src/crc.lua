-- vw3.crc: CRC-16/MODBUS on table lookups (no bitwise operators: the same on Lua 5.2 and 5.4).
-- Mirrors dissector/protocol/crc.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.crc"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)

local floor = math.floor
local format = string.format
local concat = table.concat

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
-- The one-byte table, bit by bit: shifted right, and XOR the polynomial 0xA001 (bytes A0 01) when the bit
-- shifted out is 1.
for byte = 0, 255 do
  local lo, hi = byte, 0
  for _ = 1, 8 do
    local out = lo % 2
    lo, hi = floor(lo / 2) + hi % 2 * 128, floor(hi / 2)
    if out == 1 then lo, hi = XOR8[lo * 256 + 0x01], XOR8[hi * 256 + 0xA0] end
  end
  CRC_LO[byte], CRC_HI[byte] = lo, hi
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

-- CRC-16/MODBUS of b[from] .. b[to - 1] (b is a 0-based byte table), from the register lo, hi (0xFF,
-- 0xFF: a new CRC); returns the register's two bytes. (The loop keeps them times 256, as TWO_LO and
-- TWO_HI hold them, and takes four bytes a turn: fewer operations a byte.)
local function crc_bytes(b, from, to, lo, hi)
  local k = from
  if k + 1 < to then
    local l, h = lo * 256, hi * 256
    while k + 3 < to do
      local w = XOR8[h + b[k + 1]] * 256 + XOR8[l + b[k]]
      l, h = TWO_LO[w], TWO_HI[w]
      w = XOR8[h + b[k + 3]] * 256 + XOR8[l + b[k + 2]]
      l, h = TWO_LO[w], TWO_HI[w]
      k = k + 4
    end
    if k + 1 < to then
      local w = XOR8[h + b[k + 1]] * 256 + XOR8[l + b[k]]
      l, h = TWO_LO[w], TWO_HI[w]
      k = k + 2
    end
    lo, hi = floor(l / 256), floor(h / 256)
  end
  if k < to then
    local index = XOR8[lo * 256 + b[k]]
    lo, hi = XOR8[hi * 256 + CRC_LO[index]], CRC_HI[index]
  end
  return lo, hi
end

-- The lengths from `minimum` to `last` at which the bytes from i end in their CRC (protocol/crc.py
-- crc_lengths), written into `lengths`, their count returned; without `lengths`, the first such length (0:
-- none). One running CRC over the growing frame: each length costs one byte, not a new CRC.
local function crc_scan(b, i, minimum, last, lengths)
  if minimum > last then return 0 end
  local count = 0
  local lo, hi = crc_bytes(b, i, i + minimum - 2, 0xFF, 0xFF)
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

local function crc16(b, from, to)
  local lo, hi = crc_bytes(b, from, to, 0xFF, 0xFF)
  return hi * 256 + lo
end

-- Does a record's string (the whole frame, `n` bytes) end in its CRC? The same steps as crc_bytes, the
-- bytes read sixteen a call from the string (then four, two, one): a record of one frame is checked
-- before its byte table is needed, and a call of string.byte costs less than the table reads it saves.
local function crc_string_ok(bytes, n)
  local byte = string.byte
  local stop = n - 2 -- (the bytes 1 .. stop are covered; then the CRC, low byte first)
  local l, h = 0xFF00, 0xFF00
  local k = 1
  while k + 15 <= stop do
    local a, b, c, d, e, f, g, i, a2, b2, c2, d2, e2, f2, g2, i2 = byte(bytes, k, k + 15)
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
  while k + 3 <= stop do
    local a, b, c, d = byte(bytes, k, k + 3)
    local w = XOR8[h + b] * 256 + XOR8[l + a]
    l, h = TWO_LO[w], TWO_HI[w]
    w = XOR8[h + d] * 256 + XOR8[l + c]
    l, h = TWO_LO[w], TWO_HI[w]
    k = k + 4
  end
  if k + 1 <= stop then
    local a, b = byte(bytes, k, k + 1)
    local w = XOR8[h + b] * 256 + XOR8[l + a]
    l, h = TWO_LO[w], TWO_HI[w]
    k = k + 2
  end
  local lo, hi = (l - l % 256) / 256, (h - h % 256) / 256
  if k <= stop then
    local index = XOR8[lo * 256 + byte(bytes, k)]
    lo, hi = XOR8[hi * 256 + CRC_LO[index]], CRC_HI[index]
  end
  local crc_lo, crc_hi = byte(bytes, n - 1, n)
  return lo == crc_lo and hi == crc_hi
end


-- Does the frame of `length` bytes at i carry a good CRC? The running CRC of the last frame start is
-- kept: the layouts tried at one start (a request of 8 bytes, then a response of 5 + byte count, then the
-- frame that follows...) share their first bytes, and the CRC costs most of the framing. (Byte tables
-- are never changed below their end, so a CRC once computed stays right.)
local crc_b, crc_i, crc_to, crc_lo, crc_hi = nil, -1, -1, 0xFF, 0xFF
local function crc_ok_at(b, i, length)
  local stop = i + length - 2
  local lo, hi
  if b == crc_b and i == crc_i and stop >= crc_to then
    lo, hi = crc_bytes(b, crc_to, stop, crc_lo, crc_hi)
  else
    lo, hi = crc_bytes(b, i, stop, 0xFF, 0xFF)
  end
  crc_b, crc_i, crc_to, crc_lo, crc_hi = b, i, stop, lo, hi
  return hi * 256 + lo == b[stop] + b[stop + 1] * 256
end

M.CRC_HI, M.CRC_LO, M.XOR8, M.concat, M.crc16, M.crc_bytes = CRC_HI, CRC_LO, XOR8, concat, crc16, crc_bytes
M.crc_ok_at, M.crc_scan, M.crc_string_ok, M.floor, M.format = crc_ok_at, crc_scan, crc_string_ok, floor, format
