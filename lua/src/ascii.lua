-- vw3.ascii: ASCII framing: ':' ... CR LF lines, LRC, the mode of a capture.
-- Mirrors dissector/framing/ascii.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.ascii"]).
-- (the catalogue's texts, data/modbus.toml [texts]: warnings, noise reasons; TEXT: those without parameters,
-- filled in; the others' formats take them in the text's order)
local TEXTS, TEXT = DATA.rules.texts, DATA.plain_texts

-- ---------------------------------------------------------------------------------------------------
-- Modbus ASCII (dissector/framing/ascii.py): ':' + hex pairs (slave, function, data, LRC) + CR LF. The frame
-- delimits itself; the RTU length rules, applied to the same bytes, still say what kind it is. Its sizes
-- and alphabet: dissector/protocol/ascii.py.
local COLON, CR, LF = DATA.ascii.delimiters[1], DATA.ascii.delimiters[2], DATA.ascii.delimiters[3]
local MAX_ASCII, MIN_BINARY, ASCII_SHARE = DATA.ascii.max_ascii, DATA.ascii.min_binary, DATA.ascii.share
local HEX, ALPHABET = DATA.ascii.hex_digits, DATA.ascii.alphabet -- (HEX: each hex digit's value)
local MODE_SAMPLE = DATA.ascii.mode_sample -- (the first bytes that tell a capture's mode: protocol/ascii.py)
local MODE_REACH = 2 * MAX_ASCII -- (how far they grow while they cannot tell: protocol/ascii.py MODE_REACH)
local PUBLIC = DATA.functions -- (the public function codes: an RTU frame that tells a stream is RTU has one)
-- FC8 sub-functions whose data word is a character then 00: the line end they set in place of LF (03).
local SETS_DELIMITER = DATA.ascii.sets_delimiter
local MAX_COUNTED = FRAMING.max_counted -- (a line over MAX_ASCII whose header gives its length: long_line)

local function lrc(bytes_, count)
  local sum = 0
  for k = 0, count - 1 do sum = sum + bytes_[k] end
  return (256 - sum % 256) % 256
end

-- The bytes of `count` hex pairs at b[at], bin[0 .. count - 1], and whether a digit is lower case (nil: no hex).
local function hex_pairs(b, at, count)
  local bin, lower = {}, false
  for k = 0, count - 1 do
    local high, low = b[at + 2 * k], b[at + 1 + 2 * k]
    if not (HEX[high] and HEX[low]) then return nil end
    if high >= 97 or low >= 97 then lower = true end
    bin[k] = HEX[high] * 16 + HEX[low]
  end
  return bin, lower
end

-- Where the first whole ASCII frame in the sample ends (its bytes up to there; nil: none): ':', hex pairs
-- (slave, function and LRC at least), LF (after CR, or alone), its LRC good (the binary bytes and the LRC
-- sum to 0 modulo 256), whatever comes before it.
-- (protocol/ascii.py frame_end: one pass, the hex digits after a ':' looked at once)
local function frame_end(sample)
  for digits, after in sample:gmatch(":(%x*)\r?\n()") do
    local count = floor(#digits / 2)
    if #digits % 2 == 0 and count >= MIN_BINARY then
      local bin = hex_pairs({ digits:byte(1, -1) }, 1, count)
      if lrc(bin, count - 1) == bin[count - 1] then return after - 1 end
    end
  end
  return nil
end

-- Could an RTU frame start at b[at]: a slave address, a public function code or its exception?
local function rtu_start(b, at)
  return b[at] <= MAX_SLAVE and PUBLIC[b[at + 1] % 128] ~= nil
end

-- A pass of rtu_pair_end over a sample that grows: the bytes read (b, n), the places a frame may start less
-- than MAX_ADU bytes back with the running CRC of their bytes so far (starts, los, his), where frames end
-- (ends[k]: one ends right before byte k), and where the first pair ends once it is found.
local function pair_scan()
  return { b = {}, n = 0, starts = {}, los = {}, his = {}, ends = {}, found = nil }
end

-- Where the first two RTU frames back to back end in the sample (its bytes up to there; nil: none), each a
-- slave address, a public function code (or its exception) and bytes ending in their CRC: one alone is no
-- evidence (protocol/ascii.py rtu_pair_end). One pass, a byte a step: a running CRC from each place a frame
-- may start (rtu_start), for MAX_ADU bytes; a frame ends where it runs to 0, a pair where that frame starts
-- at another's end. `scan` (pair_scan) carries the pass of an earlier call on the start of the same sample:
-- the plugin's held records (dissector.lua) are read once, not again from the start at each record.
local function rtu_pair_end(sample, scan)
  scan = scan or pair_scan()
  local b, starts, los, his, ends = scan.b, scan.starts, scan.los, scan.his, scan.ends
  for p = scan.n + 1, #sample do
    if scan.found ~= nil then break end
    local value = sample:byte(p)
    b[p] = value
    if p >= 2 and rtu_start(b, p - 1) then -- (the two bytes that tell a start have come)
      local lo, hi = crc_step(0xFF, 0xFF, b[p - 1])
      starts[#starts + 1], los[#starts + 1], his[#starts + 1] = p - 1, lo, hi
    end
    local kept, count = 0, #starts
    for k = 1, count do
      local start = starts[k]
      if p - start < MAX_ADU then -- (a frame from there would be p - start + 1 bytes long)
        local lo, hi = crc_step(los[k], his[k], value)
        if lo == 0 and hi == 0 and p - start + 1 >= MIN_ADU then
          ends[p + 1] = true
          if ends[start] then scan.found = p end
        end
        kept = kept + 1
        starts[kept], los[kept], his[kept] = start, lo, hi
      end
    end
    for k = count, kept + 1, -1 do starts[k], los[k], his[k] = nil, nil, nil end
    scan.n = p
  end
  return scan.found
end

local function detect_mode(sample)
  -- 'ascii' when the sample holds a whole ASCII frame (whatever noise comes before it), or when a ':' is
  -- followed by hex digits and nine bytes in ten are hex digits, ':', CR or LF (protocol/ascii.py).
  if frame_end(sample) then return "ascii" end
  local colon = sample:find(":", 1, true)
  if colon == nil or colon == #sample then return "rtu" end
  for k = colon + 1, math.min(colon + 2, #sample) do -- (the one or two bytes after it)
    if not HEX[sample:byte(k)] then return "rtu" end
  end
  local inside = 0
  for k = 1, #sample do
    if ALPHABET[sample:byte(k)] then inside = inside + 1 end
  end
  if inside >= ASCII_SHARE * #sample then return "ascii" end
  return "rtu"
end

-- The mode a stream's first bytes give, or nil while they cannot tell yet (more bytes can come); and the mode
-- they give were the stream to end there (protocol/ascii.py sample_mode, without and with `complete`: both
-- from one look at the bytes). ASCII when the first MODE_SAMPLE bytes hold a whole ASCII frame; else, up to
-- MODE_REACH bytes, a whole ASCII frame or two RTU frames back to back, the first to end; else detect_mode.
-- An answer given while more can come stays the answer for any longer sample. `scan`: rtu_pair_end's,
-- carried.
local function sample_modes(sample, scan)
  local told = #sample >= MODE_SAMPLE -- (the first answer holds for any longer sample)
  if frame_end(sample:sub(1, MODE_SAMPLE)) then return told and "ascii" or nil, "ascii" end
  sample = sample:sub(1, MODE_REACH)
  local ascii_end, rtu_end = frame_end(sample), rtu_pair_end(sample, scan)
  local mode
  if rtu_end ~= nil and (ascii_end == nil or rtu_end < ascii_end) then
    mode = "rtu"
  elseif ascii_end ~= nil then
    mode = "ascii"
  else
    mode, told = detect_mode(sample), #sample >= MODE_REACH
  end
  return told and mode or nil, mode
end

-- protocol/ascii.py sample_mode itself (the tests hold it and rtu_pair_end to Python's).
local function sample_mode(sample, complete)
  local now, ended = sample_modes(sample)
  if complete then return ended end
  return now
end
M.sample_mode, M.rtu_pair_end = sample_mode, rtu_pair_end

local function classify_ascii(s, adu, count)
  -- The kind an RTU frame with the same bytes would have, by the framer's length rules.
  local crc = crc16(adu, 0, count)
  local equivalent = { [0] = adu[0], table.unpack(adu, 1, count - 1) }
  equivalent[count], equivalent[count + 1] = crc % 256, floor(crc / 256)
  local length = count + 2
  for _, interpretation in ipairs(interpretations(s, adu[0], adu[1], equivalent, 0, length)) do
    -- A layout without a length rule fits any length from its minimum: ':' and CR LF delimit the frame.
    local found, is_scan = interpretation[2](equivalent, 0, length)
    if found == length or (is_scan and length >= found) then return interpretation[1] end
  end
  return nil
end

-- A normal answer to 08/03 echoes the change: its slave's lines may end with CR and that character (the data's
-- high byte, whatever the low byte) from now on (s.line_ends, any slave's; LF still ends one); back to LF, CR or
-- ':' drops it (ascii.py _changed).
local function changed(s, bin, count)
  if bin[1] ~= 8 or count ~= 7 or not SETS_DELIMITER[bin[2] * 256 + bin[3]] then return end
  local character, delimiters = bin[4], s.delimiters or {}
  local kept = character ~= LF and character ~= CR and character ~= COLON
  delimiters[bin[0]] = kept and character or nil
  s.delimiters, s.line_ends = delimiters, nil
  for _, byte in pairs(delimiters) do
    s.line_ends = s.line_ends or {}
    s.line_ends[byte] = true
  end
end

-- A run of ASCII bytes that is no frame, with the reason: a noise item of its own.
local function reject(s, at, length, reason, items)
  flush_noise(s, items)
  add_noise(s, at, at + length, reason, items)
  flush_noise(s, items)
end

-- The warning for a line ended by CR and `last` that its slave does not take, or nil (ascii.py _check_end;
-- Application Protocol 6.8.1, 08/03: the character replaces LF at the end of the messages the slave takes in).
-- A request to a slave that set one ends with it; a broadcast with LF or any slave's; an answer with LF or its
-- slave's, before (`before`) or after this echo (the spec names the slave's input only).
local function end_warning(s, kind, slave, last, before)
  local delimiter = (s.delimiters or {})[slave]
  if kind == REQUEST and delimiter ~= nil then
    if last == delimiter then return nil end
    return format(TEXTS.delimiter_expected.format, last, slave, delimiter)
  end
  local taken = last == before or last == delimiter
  if slave == 0 then taken = s.line_ends ~= nil and s.line_ends[last] == true end
  if last == LF or taken then return nil end
  return format(TEXTS.cr_then_byte.format, last)
end

-- A line, b[at .. at + length - 1] (':' digits CR LF, or CR and the byte in the LF's place): a frame, or noise
-- with the reason it is none. `at_end`: the line ends the capture.
local function ascii_candidate(s, at, length, items, reason, at_end)
  if reason ~= nil then return reject(s, at, length, reason, items) end
  local b = s.b
  -- Text files lose their CRs: LF alone still ends the frame, with a warning (ascii.py); so does a CR
  -- whose LF was lost (run_ascii: CR, then the next ':' or the end), and one ended LF CR, reversed (the frame
  -- keeps the CR). A tty that turns LF into CR LF doubles the CR: the frame keeps them all, with a warning.
  local reversed = b[at + length - 1] == CR and b[at + length - 2] == LF -- (LF CR: run_ascii)
  local lost_lf = b[at + length - 1] == CR and not reversed
  -- (the last of the digits and CRs after them)
  local stop = lost_lf and at + length - 1 or at + length - (reversed and 3 or 2)
  local crs = 0
  while stop - crs > at and b[stop - crs] == CR do crs = crs + 1 end
  local lost_cr = crs == 0 and not reversed
  local digits = stop - at - crs
  if digits % 2 == 1 then return reject(s, at, length, TEXT.not_hex_pairs, items) end
  local count = floor(digits / 2)
  local bin, lower = hex_pairs(b, at + 1, count)
  if bin == nil then return reject(s, at, length, TEXT.not_hex_pairs, items) end
  if count < MIN_BINARY then return reject(s, at, length, TEXT.ascii_too_short, items) end
  local slave, code = bin[0], bin[1]
  local received, expected = bin[count - 1], lrc(bin, count - 1)
  local kind = classify_ascii(s, bin, count - 1)
  if kind == nil and received ~= expected then
    local check = format(TEXTS.lrc_wrong.format, received, expected)
    return reject(s, at, length, format(TEXTS.no_layout.format, code, check), items)
  end
  -- A line with a good LRC is a frame whatever its length: ':' and its end bound it (ascii.py _candidate)
  if kind == nil then kind = bounded_kind(s, bin, 0, count) end
  local offset = s.base + at
  local frame = {
    kind = kind, offset = offset, length = length, slave = slave, fn = code % 128,
    crc = received, crc_expected = expected, ascii = true,
    b = bin, bi = 0, data_at = 2, data_len = count - 3, time = time_at(s, offset), src = b, src_at = at,
  }
  local before = (s.delimiters or {})[slave]
  if kind == RESPONSE and received == expected then changed(s, bin, count) end
  local warnings = {}
  if lost_lf then
    warnings[1] = at_end and TEXT.cr_at_end or TEXT.cr_without_lf
  elseif lost_cr then
    warnings[1] = TEXT.lf_without_cr
  elseif reversed then
    warnings[1] = TEXT.lf_then_cr
  else
    warnings[1] = end_warning(s, kind, slave, b[at + length - 1], before)
  end
  if length > MAX_ASCII then table.insert(warnings, 1, format(TEXTS.over_ascii.format, length, MAX_ASCII)) end
  if crs > 1 then warnings[#warnings + 1] = format(TEXTS.extra_cr.format, crs) end
  if lower then warnings[#warnings + 1] = TEXT.lower_case_hex end
  if #warnings > 0 then frame.warnings = warnings end
  emit(s, frame, items)
end

-- At the end of the input: do b[i .. n - 1] (':' and hex digits) begin the answer awaited, cut by the end of
-- the capture (ascii.py _cut_answer)? The reason, or nil.
local function ascii_cut_answer(s, b, i, n)
  local count = floor((n - i - 1) / 2)
  if count < 2 then return nil end
  for k = i + 1, n - 1 do
    if not HEX[b[k]] then return nil end
  end
  -- The answer's reading, unless it is not as long as the request implies: then the next, the next request.
  local bin = hex_pairs(b, i + 1, count)
  if not awaited(s, bin, 0, count) then return nil end
  local list, kind, length, longest = interpretations(s, bin[0], bin[1], bin, 0, count), nil, nil, MAX_COUNTED
  for index = 1, #list do
    local found, is_scan, declared = list[index][2](bin, 0, count) -- (the RTU frame's: its CRC an LRC here)
    if is_scan then found = declared ~= nil and declared > 0 and declared or NEED end
    if not not_the_answer(s, list[index][1], found) then
      kind, length, longest = list[index][1], found, is_scan and MAX_ADU or MAX_COUNTED -- (long_line's reach)
      break
    end
  end
  if kind == nil then return nil end
  if length == NEED then return cut_reason(kind, n - i, NEED) end
  local characters = 1 + 2 * (length - 1) + 2 -- ':', the hex pairs of the ADU and the LRC, CR LF
  if n - i < characters and length <= longest then return cut_reason(kind, n - i, characters) end
  return nil
end

-- Where a line from i longer than MAX_ASCII ends when its header gives its length (an RTU frame's over MAX_ADU, up
-- to MAX_COUNTED) and it is that frame: hex pairs, CR LF there, its LRC good (ascii.py _long_line). Its length, 0
-- (not one: noise as before) or NEED (its bytes have not all come).
local function long_line(s, b, i, n, final)
  local head = hex_pairs(b, i + 1, MAX_ADU) -- (MAX_ASCII bytes have come, no LF among them)
  if head == nil then return 0 end
  local list = interpretations(s, head[0], head[1], head, 0, MAX_ADU)
  for index = 1, #list do
    local length, is_scan = list[index][2](head, 0, MAX_ADU)
    if not is_scan and length > MAX_ADU and length <= MAX_COUNTED then
      local characters = 1 + 2 * (length - 1) + 2 -- (':', the ADU's hex pairs and the LRC's, CR LF)
      for k = i + MAX_ASCII, math.min(n, i + characters - 2) - 1 do
        if not HEX[b[k]] then return 0 end
      end
      if n - i < characters then return final and 0 or NEED end
      if b[i + characters - 2] ~= CR or b[i + characters - 1] ~= LF then return 0 end
      local bin = hex_pairs(b, i + 1, length - 1)
      return lrc(bin, length - 2) == bin[length - 2] and characters or 0
    end
  end
  return 0
end

local function run_ascii(s, final, items)
  local b, n = s.b, s.n
  local i = 0
  while i < n do
    if b[i] ~= COLON then
      local stop = i + 1
      while stop < n and b[stop] ~= COLON do stop = stop + 1 end
      add_noise(s, i, stop, TEXT.outside_ascii, items)
      i = stop
    else
      local limit = math.min(n, i + MAX_ASCII)
      -- (the first LF or ':' after it, in one scan that stops there: two scans to the limit cost 513
      -- reads a ':' in a flood of them)
      local stop, ends = nil, s.line_ends -- (ends: the characters 08/03 set, each ending a line after a CR)
      for k = i + 1, limit - 1 do
        local byte = b[k]
        if byte == LF or byte == COLON then
          stop = k
          break
        elseif ends ~= nil and byte == CR and k + 1 < limit and ends[b[k + 1]] then
          stop = k + 1
          break
        end
      end
      local length, reason, at_end = nil, nil, false -- (the line's bytes; reason: why they are no frame)
      if stop ~= nil and b[stop] == COLON then
        length = stop - i
        -- (after a CR, or a CR and another byte: the LF lost or damaged, the CR ends it)
        if b[stop - 1] ~= CR and not (stop - 2 > i and b[stop - 2] == CR) then reason = TEXT.cut_by_colon end
      elseif stop ~= nil then
        length = stop + 1 - i
        if b[stop - 1] ~= CR then -- (no CR before the LF: a CR right after it is the line end reversed, LF CR)
          if stop + 1 == n and not final then break end -- (the next byte tells)
          if stop + 1 < n and b[stop + 1] == CR then length = length + 1 end
        end
      elseif n - i >= MAX_ASCII then
        length = long_line(s, b, i, n, final)
        if length == NEED then break end
        if length == 0 then length, reason = MAX_ASCII, format(TEXTS.no_line_end.format, MAX_ASCII) end
      elseif final and n - i > 2 and (b[n - 2] == CR or b[n - 1] == CR) then
        -- (the line's CR, its LF lost or another byte in its place: a line, as before a ':')
        length, at_end = n - i, true
      elseif final then
        length, reason = n - i, ascii_cut_answer(s, b, i, n) or TEXT.cut_by_end
      else
        break -- wait for the rest of the frame
      end
      ascii_candidate(s, i, length, items, reason, at_end)
      i = i + length
    end
  end
  return i
end
