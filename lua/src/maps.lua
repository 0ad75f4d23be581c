-- vw3.maps: the profile and map preferences, register maps read from CSV.
-- Mirrors dissector/devices/maps.py, dissector/devices/profiles.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.maps"]).


-- ---------------------------------------------------------------------------------------------------
-- Device profiles and register maps (profiles.py, maps.py, devices/annotator.py): names, scaling, the
-- 16#8000 semantics, exception explanations, device limits. Profile data come from the generated block.
local PROFILES = DATA.profiles or {}
local READS = DATA.protocol.reads
-- Reads whose exception can be explained parameter by parameter (FC23 may fail on its write part).
local PLAIN_READS = DATA.protocol.plain_reads
local READ_LIMIT = LIMITS.read_registers[2]

-- The choices the preferences make: default profile (`auto`: one per slave from evidence, devices/
-- selection.py), profile per slave, address style override, map layers.
local SELECTION = DATA.selection
local AUTO = SELECTION.auto
config = { default = DATA.default_profile, per_slave = {}, style = nil, errors = {}, layers = {} }

local function parse_profile_choice(text)
  -- as build_annotator reads `--profile` options: one default (a profile or auto), SLAVE=PROFILE entries
  local default, per_slave, errors = nil, {}, {}
  -- (spaces around '=' are not a separator: `12 = atv71` is build.py's _split_target's `12=atv71`)
  for part in string.gmatch(string.gsub(text or "", "%s*=%s*", "="), "[^,;%s]+") do
    local target, name = string.match(part, "^([^=]*)=(.*)$")
    local slave = target and string.match(target, "^%d+$") and tonumber(target)
    local problem = nil
    if target == nil and (PROFILES[part] ~= nil or part == AUTO) then
      problem = default and format("%q: a default profile (%s) is already set", part, default)
      default = default or part
    elseif target == nil then
      problem = format("%q is neither a built-in profile, auto, nor SLAVE=PROFILE", part)
    elseif slave == nil then
      problem = format("%q: %q is not a slave address", part, target)
    elseif name == "" then
      problem = format("%q: nothing after '='", part)
    elseif name == AUTO then
      problem = format("%q: auto is for every slave (a default, not SLAVE=auto)", part)
    elseif PROFILES[name] == nil then
      problem = format("profile %q for slave %d is not built in", name, slave)
    elseif slave > MAX_SLAVE then -- (unit 0 is a device's address over Modbus/TCP, which the plugin reads too)
      problem = format("slave %d is outside 0..%d", slave, MAX_SLAVE)
    elseif per_slave[slave] ~= nil then
      problem = format("%q: slave %d already has a profile", part, slave)
    else
      per_slave[slave] = name
    end
    errors[#errors + 1] = problem
  end
  return default or DATA.default_profile, per_slave, errors
end

-- Register maps given at run time (maps.py): the CSV format of dissector/data/maps, read from the files
-- the "Register maps" preference names, like `vw3-decode --map [SLAVE=|PROFILE=]FILE`. The format's
-- facts and its error messages are maps.py's (COLUMNS, REQUIRED, TYPES, ORDERS, ACCESS, MESSAGES,
-- MAX_MAP_BYTES, SCALE_MIN, SCALE_MAX, SCALE_UNKNOWN, DEFAULT_TYPES, SIGNED_TYPES, PAIRS, SEPARATORS),
-- written into the generated data.
local FORMAT = DATA.map_format
local MAX_MAP_BYTES, MESSAGES = FORMAT.max_bytes, FORMAT.messages

local function strip(text) return (text:gsub("^%s+", ""):gsub("%s+$", "")) end

-- A map's texts are shown (maps.py printable): what str.isprintable() refuses (C0, DEL, C1, no-break space,
-- soft hyphen, format characters such as U+202E, line and paragraph separators, private use, unassigned
-- code points: DATA.nonprintable, codegen/printable_table.py) escaped as Python writes it in a literal,
-- \xNN below U+0100, \uNNNN below U+10000, \UNNNNNNNN above, never raw; with a quote (python_repr) the
-- backslash, that quote, \n, \r, \t escaped too, as Python's repr escapes them.
local HIDDEN -- ({ first, last } in order, from DATA.nonprintable.ranges' `first-last` in hex: read on first use)
local function hidden(code)
  if HIDDEN == nil then
    HIDDEN = {}
    for first, last in concat(DATA.nonprintable.ranges, " "):gmatch("(%x+)-(%x+)") do
      HIDDEN[#HIDDEN + 1] = { tonumber(first, 16), tonumber(last, 16) }
    end
  end
  for _, range in ipairs(HIDDEN) do
    if code <= range[2] then return code >= range[1] end
  end
end

-- One character as UTF-8: a byte and the continuation bytes after it. Its code point, or nil when Python's
-- strict decoder refuses it (a stray continuation byte, too few or too many for its lead byte, an overlong
-- form, a surrogate, past U+10FFFF): a map file is read as UTF-8 or refused, as maps.load_map_file does.
local UTF8_CHAR = "[\0-\255][\128-\191]*"
local LEAD_FIRST, LEAD_END = { 0, 192, 224, 240 }, { 128, 224, 240, 248 } -- (lead bytes, by length)
local LEAST = { 0, 0x80, 0x800, 0x10000 } -- (below: an overlong form)
local function code_point(char)
  local size, code = #char, char:byte()
  if size > 4 or code < LEAD_FIRST[size] or code >= LEAD_END[size] then return nil end
  code = code - LEAD_FIRST[size]
  for at = 2, size do code = code * 64 + char:byte(at) - 128 end
  if code < LEAST[size] or code > 0x10FFFF or (code >= 0xD800 and code <= 0xDFFF) then return nil end
  return code
end

local REPR_ESCAPES = { ["\\"] = "\\\\", ["\n"] = "\\n", ["\r"] = "\\r", ["\t"] = "\\t" }
local function printable(text, quote)
  return (text:gsub(UTF8_CHAR, function(char)
    if quote ~= nil and (REPR_ESCAPES[char] or char == quote) then return REPR_ESCAPES[char] or "\\" .. quote end
    local code = code_point(char)
    if (code < 32 or code > 126) and hidden(code) then
      return format(code < 0x100 and "\\x%02x" or code < 0x10000 and "\\u%04x" or "\\U%08x", code)
    end
  end))
end

-- str.__repr__ of a text (a map cell, a server id: UTF-8), quotes as Python picks.
local function python_repr(text)
  local quote = text:find("'", 1, true) and not text:find('"', 1, true) and '"' or "'"
  return quote .. printable(text, quote) .. quote
end

-- A map refused: raised, as maps.py raises ProfileError, with what is wrong; `attempt` tells it.
local function refuse(problem) error({ problem }, 0) end

-- fn's result, or nil and what refused the map (a fault of the reader's own is raised again).
local function attempt(fn, ...)
  local done, result = pcall(fn, ...)
  if done then return result end
  if type(result) ~= "table" then error(result, 0) end
  return nil, result[1]
end

-- A map error in maps.py's words (its MESSAGES, by key), `!r` parameters as Python's repr, after the place
-- of the line read (`origin:line: `, read_map's).
local line_read = ""
local function wrong(key, values) refuse(line_read .. fill(MESSAGES[key], values, python_repr)) end

-- One CSV line as Python's csv.reader (excel dialect) splits it: commas, "quoted" fields, "" for a quote;
-- and whether a quote is left open at the line's end (maps.py refuses that line: open_quote).
local function csv_cells(line, delimiter)
  local cells, at, stop, open = {}, 1, 0, false
  repeat
    local cell = {}
    if line:sub(at, at) == '"' then
      -- quoted up to a quote that is not doubled (`""` stands for one); what follows it is the cell's too
      at = at + 1
      repeat
        local quote = line:find('"', at, true)
        if not quote then open, quote = true, #line + 1 end
        cell[#cell + 1] = line:sub(at, quote - 1)
        local doubled = line:sub(quote + 1, quote + 1) == '"'
        if doubled then cell[#cell + 1] = '"' end
        at = doubled and quote + 2 or quote + 1
      until not doubled
    end
    stop = line:find(delimiter, at, true) or #line + 1
    cell[#cell + 1] = line:sub(at, stop - 1)
    cells[#cells + 1] = concat(cell)
    at = stop + 1
  until stop > #line
  return cells, open
end

local function map_int(text)
  text = strip(text)
  local hex = text:match("^16#(%x+)$") or text:match("^0[xX](%x+)$")
  if hex then return tonumber(hex, 16) end
  return text:match("^[+-]?%d+$") and tonumber(text) or nil
end

-- maps.reference_address: the address a PLC reference stands for (40001 -> 0, 30101 -> 100, 400001 -> 0),
-- decimal digits only; FORMAT.reference_bases: 4X, 3X (five digits, or six: base * 10 - 9).
local REFERENCE = FORMAT.reference
local function map_reference(text)
  text = strip(text)
  local number = text:match("^%d+$") and tonumber(text)
  for _, base in ipairs(number and FORMAT.reference_bases or {}) do
    if number >= base and number <= base + 9998 then return number - base end
    local six = base * 10 - 9
    if number >= six and number <= six + 0xFFFF then return number - six end
  end
  wrong("reference", { text = text })
end

-- The rows read from a map written in PLC references (maps.ReferenceRows), for the reference check's note,
-- -> its 3X rows (ReferenceRows.inputs: input registers, FC4's), kept apart from its 4X rows.
local reference_rows = setmetatable({}, { __mode = "k" })

local function map_pairs(text, what)
  local out, low, high = {}, FORMAT.pairs[what][1], FORMAT.pairs[what][2]
  for part in (text .. ";"):gmatch("([^;]*);") do
    part = strip(part)
    if part ~= "" then
      local key, label = part:match("^([^=]*)=(.*)$")
      if key == nil or strip(label) == "" then wrong("pair", { what = what, part = part }) end
      local number = map_int(key) or wrong("pair_number", { what = what, part = part, key = strip(key) })
      if number < low or number > high then
        wrong("pair_range", { what = what, part = part, number = number, low = low, high = high })
      end
      if out[number] ~= nil then wrong("pair_twice", { what = what, part = part, number = number }) end
      out[number] = printable(strip(label))
    end
  end
  return next(out) ~= nil and out or nil
end

-- Digits after the decimal point of a scale written as text ("0.1" -> 1, "1e-2" -> 2, "10" -> 0), or nil
-- when it is not a plain decimal number (maps.py _SCALE: not tonumber's 0x10, nor inf or nan).
local function scale_decimals(text)
  local mantissa, exponent = text:lower():match("^[+-]?([%d.]+)e([+-]?%d+)$")
  if mantissa == nil then mantissa, exponent = text:match("^[+-]?([%d.]+)$"), "0" end
  if mantissa == nil or not mantissa:match("^%d*%.?%d*$") or not mantissa:match("%d") then return nil end
  local fraction = (mantissa:match("%.(%d*)$") or ""):gsub("0+$", "")
  return math.max(0, #fraction - tonumber(exponent))
end

-- A column of a few choices (access, signed, type, order): its cell, case folded, or `default` when empty;
-- the column's message (maps.py MESSAGES, keyed by the column's name) when it is none of `allowed`.
local SIGNED = { ["0"] = true, ["1"] = true }
local function choice(values, column, fold, default, allowed)
  local text = fold(strip(values[column] or ""))
  if text == "" then text = default end
  if text ~= "" and not allowed[text] then wrong(column, { text = text }) end
  return text
end

local function map_row(values)
  local address = map_int(values.address or "") or wrong("address", { text = values.address or "" })
  if address < 0 or address > 0xFFFF then wrong("address_range", { address = address }) end
  local row = {}
  for _, key in ipairs({ "code", "name", "unit", "source" }) do
    local text = printable(strip(values[key] or ""))
    if text ~= "" then row[key] = text end
  end
  if row.code == nil then wrong("code") end
  local scale_text = strip(values.scale or "")
  if scale_text ~= "" and scale_text ~= FORMAT.scale_unknown then
    row.decimals = scale_decimals(scale_text)
    row.scale = row.decimals and tonumber(scale_text) or wrong("scale", { text = scale_text })
    local size = math.abs(row.scale)
    if size == 0 then wrong("scale_zero", { text = scale_text }) end
    if not (size >= FORMAT.scale_min and size <= FORMAT.scale_max) then -- also 1e999 (inf): finite results
      wrong("scale_range", { text = scale_text })
    end
  end
  -- (a read-only parameter's write is warned, its refusal named: dissector/devices/access.py)
  row.read_only = choice(values, "access", string.upper, "", FORMAT.access) == FORMAT.read_only or nil
  row.enum = map_pairs(values.enum or "", "enum")
  row.bits = map_pairs(values.bits or "", "bits")
  local signed = choice(values, "signed", tostring, "", SIGNED)
  local kind = choice(values, "type", string.lower, FORMAT.default_types[signed == "1" and 2 or 1], FORMAT.types)
  local words = FORMAT.types[kind]
  -- (the signed cell a type agrees with, when both are given: a float32 takes none)
  local agrees = kind ~= "float32" and (FORMAT.signed_types[kind] and "1" or "0") or ""
  if strip(values.type or "") ~= "" and signed ~= "" and signed ~= agrees then
    wrong("signed_type", { text = signed, kind = kind })
  end
  row.signed = (signed == "1" or FORMAT.signed_types[kind]) or nil
  local order = choice(values, "order", string.upper, FORMAT.order_list[1], FORMAT.orders)
  -- (cells that contradict each other: maps.CONFLICTS, judged on maps._row's facts)
  local facts = { one_word = words == 1, wide = words == 2, swapped = order ~= FORMAT.order_list[1],
    last = address == 0xFFFF, signed = row.signed, enum = row.enum, bits = row.bits, labels = row.enum or row.bits,
    scale = scale_text ~= "", unit = row.unit ~= nil, no_unit = row.unit == nil,
    scale_unknown = scale_text == FORMAT.scale_unknown }
  for _, conflict in ipairs(DATA.map_conflicts) do
    if facts[conflict[2]] and facts[conflict[3]] then
      wrong(conflict[1], conflict[4] or { text = order, kind = kind, address = address })
    end
  end
  if words == 2 then -- (a 32-bit value over this register and the next: naming.name_wide reads it on the first)
    row.words, row.kind, row.swapped = 2, kind, order == "CDAB" or nil
  end
  -- (a scale the device's settings choose: the raw word, naming the unit it counts in)
  row.scale_unknown = facts.scale_unknown or nil
  row.ambiguous_8000 = (row.signed or (row.bits and row.bits[15]) or (row.enum and row.enum[0x8000]) or words == 2)
    and true or nil
  return address, row
end

-- The separator of a map from its header line: the one of SEPARATORS that splits it most (maps.py).
local function sniff(header)
  local best, most = FORMAT.separators[1], 0
  for _, separator in ipairs(FORMAT.separators) do
    local count = select(2, header:gsub(separator, ""))
    if count > most then best, most = separator, count end
  end
  return best
end

-- The rows of a map's text (maps.parse_map, message for message; `origin` names it): UTF-8 with
-- or without a BOM, `,` or European Excel's `;` (or tab) with its decimal comma in scale. Bytes that are
-- not UTF-8 are refused as maps.load_map_file refuses them (Python's strict decoder, no surrogateescape).
local function read_map(text, origin)
  for char in (text:find("[\128-\255]") and text or ""):gmatch(UTF8_CHAR) do
    if code_point(char) == nil then
      local bom = text:sub(1, 2) -- (maps.py UTF16_BOMS: UTF-16's byte order marks, Excel's "Unicode Text")
      local key = (bom == "\255\254" or bom == "\254\255") and "utf16" or "not_utf8"
      refuse(origin .. ": " .. fill(MESSAGES[key], {}, python_repr))
    end
  end
  if text:sub(1, 3) == "\239\187\191" then text = text:sub(4) end
  local header, rows, order, delimiter, number = nil, {}, {}, ",", 0
  local named = {} -- (code, ASCII case folded as --watch matches it -> the row that named it first)
  -- (row -> where it was read: its line, reference, address and table, the rows or a reference map's 3X rows)
  local placed = {}
  -- (lines end where str.splitlines ends them: \r\n, \r, \n, \v, \f, \x1c-\x1e, U+0085, U+2028, U+2029)
  text = text:gsub("\r\n", "\n"):gsub("[\r\v\f\28-\30]", "\n")
  text = text:gsub("\194\133", "\n"):gsub("\226\128[\168\169]", "\n")
  for line in (text .. "\n"):gmatch("([^\n]*)\n") do
    number = number + 1
    line_read = format("%s:%d: ", origin, number)
    local stripped = strip(line)
    if stripped ~= "" and stripped:sub(1, 1) ~= "#" then
      if header == nil then delimiter = sniff(line) end
      local cells, open = csv_cells(line, delimiter)
      if open then wrong("open_quote", {}) end
      if header == nil then
        header = {}
        local named, twice = {}, false -- (the columns named, and whether one is named twice: told last)
        for index, cell in ipairs(cells) do
          local name = strip(cell):lower()
          if not FORMAT.columns[name] and name ~= REFERENCE then wrong("unknown_column", { name = name }) end
          header[index], named[name], twice = name, true, twice or named[name] ~= nil
        end
        if named[REFERENCE] then
          if named.address then wrong("reference_and_address") end
          reference_rows[rows] = {}
        end
        for _, required in ipairs(FORMAT.required) do
          if not named[required] and not (required == "address" and named[REFERENCE]) then
            wrong("missing_column", { name = required })
          end
        end
        if twice then wrong("column_twice") end
      else
        if #cells ~= #header then
          local separator = delimiter == "," and "comma" or python_repr(delimiter)
          wrong("fields", { count = #cells, header = #header, separator = separator })
        end
        local values = {}
        for index, name in ipairs(header) do values[name] = cells[index] end
        if delimiter ~= "," and values.scale ~= nil and strip(values.scale):match("^[-+]?%d+,%d+$") then
          values.scale = values.scale:gsub(",", ".") -- `0,1`: the decimal comma of the same spreadsheets
        end
        local reference = values[REFERENCE] ~= nil and strip(values[REFERENCE]) or nil
        if reference ~= nil then values.address = format("%d", map_reference(reference)) end
        local address, row = map_row(values)
        local input = reference ~= nil and reference:sub(1, 1) == "3"
        local into = input and reference_rows[rows] or rows
        local before = placed[into[address]]
        if before ~= nil and reference ~= nil then
          wrong("reference_twice", { text = reference, table = input and "input" or "holding", address = address,
            first = before.reference, line = before.line })
        end
        if before ~= nil then wrong("address_twice", { address = address, line = before.line }) end
        local first = placed[named[row.code:upper()]]
        if first ~= nil then
          wrong("code_twice", { code = row.code, address = first.address, line = first.line })
        end
        named[row.code:upper()] = row
        into[address], placed[row] = row, { line = number, reference = reference, address = address, into = into }
        order[#order + 1] = row
      end
    end
  end
  -- (a 32-bit row's second register defined as a row of its own: told once the file is read, rows in order)
  for _, row in ipairs(order) do
    local at = placed[row]
    local second = at.address + 1
    if row.words == 2 and at.into[second] ~= nil then
      line_read = format("%s:%d: ", origin, placed[at.into[second]].line)
      wrong("second_register", { address = second, code = row.code, kind = row.kind, line = at.line })
    end
  end
  line_read = origin .. ": "
  if header == nil then wrong("no_header") end
  return rows
end

-- The rows of a map's text, or nil and `origin:line: what is wrong` (`origin: ...` for the whole text).
local function parse_map(text, origin) return attempt(read_map, text, origin) end

-- A map file's rows (read_map); what is wrong with it refused.
local function load_map(path)
  -- Read and write, never read only: opening a FIFO read only waits for a writer (tshark hung), read and
  -- write returns at once on Linux and the seek below refuses it. A file without write permission is
  -- opened read only. A directory fails to open (or to read), a device or a file over 16 MiB is refused.
  local handle, open_error = io.open(path, "r+b")
  if handle == nil and tostring(open_error):find("ermission") then handle, open_error = io.open(path, "rb") end
  if handle == nil then refuse(format("%s: cannot read the map: %s", path, tostring(open_error))) end
  local size = handle:seek("end")
  local text = size ~= nil and size <= MAX_MAP_BYTES and handle:seek("set") and handle:read(MAX_MAP_BYTES + 1)
  handle:close()
  if size == nil then refuse(format("%s: not a file that can be read whole (a FIFO or a socket)", path)) end
  if size > MAX_MAP_BYTES or (text and #text > MAX_MAP_BYTES) then
    refuse(format("%s: larger than %d MiB, not a register map", path, floor(MAX_MAP_BYTES / 1048576)))
  end
  if not text and size ~= 0 then refuse(format("%s: cannot read the map: not a file", path)) end
  return read_map(text or "", path)
end

-- "FILE;3=FILE;sel749m=FILE" -> layers { rows, slave, profile, name, high, references } in order, and errors.
local function parse_map_choice(text, profile_names)
  local layers, errors = {}, {}
  for spec in (text or ""):gmatch("[^;]+") do
    spec = strip(spec)
    local target, path = spec:match("^([^=]*)=(.+)$")
    local whole = target and io.open(spec, "rb") -- (a file whose name holds `=`: the spec is its path)
    if whole then whole:close() end
    if whole or target == nil then
      target, path = nil, spec
    end
    target, path = target and strip(target), strip(path) -- (`3 = FILE`: build.py's _split_target)
    local slave = target and target:match("^%d+$") and tonumber(target)
    if spec == "" then
      -- (nothing between two `;`)
    elseif target and not slave and not profile_names[target] then
      errors[#errors + 1] = format("map %q: %q is neither a slave address nor a profile in use", spec, target)
    elseif slave and slave > MAX_SLAVE then -- (unit 0 is a device's over Modbus/TCP: profiles' rule)
      errors[#errors + 1] = format("map %q: slave %d is outside 0..%d", spec, slave, MAX_SLAVE)
    else
      local rows, problem = attempt(load_map, path)
      if rows == nil then
        errors[#errors + 1] = problem
      else
        -- (name, high: what check_references in lua/src/device.lua reads: the file as given, its highest address)
        -- (inputs: a map in references' 3X rows, nil when it has none: its rows then name either table)
        local high, inputs = -1, reference_rows[rows]
        if inputs ~= nil and next(inputs) == nil then inputs = nil end
        for _, table in ipairs({ rows, inputs or {} }) do
          for address in pairs(table) do high = math.max(high, address) end
        end
        layers[#layers + 1] = { rows = rows, slave = slave, profile = not slave and target or nil,
          name = printable(path), high = high, references = reference_rows[rows] ~= nil, inputs = inputs }
      end
    end
  end
  return layers, errors
end

-- (for the conformance runner, which reads map texts: the modules read files, load_map)
M.parse_map = parse_map
-- (a map in references' 3X rows, as the conformance runner compares them: maps.ReferenceRows.inputs)
function M.map_inputs(rows) return reference_rows[rows] end
