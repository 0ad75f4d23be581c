-- vw3.annotator: a frame annotated with its device; the per-capture state.
-- Mirrors dissector/devices/annotator.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.annotator"]).

-- The codes whose echo confirms masks applied to the value held ([confirm] "mask": FC22).
local MASK_WRITES = DATA.rules.by_confirm.mask

local function annotate_with(st, f, b, device)
  if not device then return end
  local special_name = device.profile.function_names[f.fn]
  if special_name ~= nil then f.function_text = special_name end
  if device.plc ~= nil and f.start ~= nil then span_label(f, device) end
  local kind = f.kind
  -- (a frame that failed its check: its values shown, nothing judged nor remembered)
  local trusted = verified(f)
  local track = device.track and trusted
  if kind == REQUEST then
    check_request(f, device)
    check_writes(f, device)
    -- (one that failed its check keeps none of its fields for its answer, which is decoded by its own bytes
    -- as one with no request, and which no quick lane takes: pairing.py trusted_request)
    if not trusted then f.fields = nil end
  elseif kind == EXCEPTION then
    explain_exception(f, device)
    return
  end
  local request = trusted_request(f)
  if kind == RESPONSE and track and CONFIRMED.answer[f.fn] and request ~= nil
      and request.registers ~= nil and request.registers.count > 0 and request.registers.b ~= nil then
    -- Writes a normal answer confirms ([confirm] "answer": FC16 answers carry no values; FC23 writes
    -- before it reads).
    remember_writes(device.seen, f.number, request.registers, request.registers.b)
  elseif kind == RESPONSE and track and MASK_WRITES[f.fn] and f.fields ~= nil then
    remember_mask(device.seen, f.number, f.fields)
  end
  local registers = f.registers
  if registers ~= nil and registers.count > 0 then
    annotate_registers(f, device, registers, b, kind == RESPONSE and READS[f.fn] ~= nil and trusted)
    if kind == RESPONSE and CONFIRMED.echo[f.fn] and track then
      remember_writes(device.seen, f.number, registers, b) -- ([confirm] "echo": FC6's own values)
    end
  end
  -- (FC8 is the only code with a sub-function; its number tested first: a key most frames lack costs more to
  -- look up, some 800 instructions a record on the plant mix under callgrind)
  if f.subfunction ~= nil then diagnostics_note(f, device, b) end -- (set by the diagnostics handler alone)
  if f.objects ~= nil and #f.objects > 0 then explain_objects(f, device.profile) end
end

-- Profile auto chose a device with a frame (select_device): the slave's provisional frames (their copies,
-- kept by hold) annotated again with it, as they would have been had it been known from the first (-2): it
-- remembers of them what the one annotate path remembers, so a parameter read in one and 16#8000 now
-- `became protected` (annotator.py _observe). What they tell again is dropped with the copies. (vw3_modbus.lua's
-- frames too: its runs are over byte tables of their own.)
function lane.annotate_again(st, device, held)
  for _, copy in ipairs(held) do annotate_with(st, copy, copy.b, device) end
end

-- The registers an exception 02 tells about (explain._all_unreadable): each address of the refused read,
-- its status, no value. Made when shown, from the request and the device, rather than kept.
local function inferred_registers(st, f)
  local text = say("no_value", { code = f.exception_code })
  local registers = refused_registers(device_of(st, f), f.request)
  for _, reg in ipairs(registers) do reg.text, reg.offset = text, -1 end
  return registers
end

local function configure(profiles_text, style, maps_text)
  local default, per_slave, errors = parse_profile_choice(profiles_text)
  -- (auto: the fallback and every candidate, every built-in profile, are in use, as build_annotator names them)
  local in_use = {}
  for name in pairs(default == AUTO and PROFILES or { [default] = true }) do in_use[name] = true end
  for _, name in pairs(per_slave) do in_use[name] = true end
  local layers, map_errors = parse_map_choice(maps_text, in_use)
  for _, problem in ipairs(map_errors) do errors[#errors + 1] = problem end
  local auto = {} -- (the slaves profile auto judges, by number: auto the default, no profile given for it)
  for slave = 0, 255 do auto[slave] = default == AUTO and per_slave[slave] == nil end
  config = { default = default, per_slave = per_slave, auto = auto, style = style, errors = errors, layers = layers }
end

-- ---------------------------------------------------------------------------------------------------
-- One record: frame it, pair and decode every frame, in order. Pure Lua: the Wireshark glue below and
-- the standalone tests both call it.
local function new_state(timeout, mode)
  -- timeout: seconds after which a response is flagged as late (nil: never), as vw3-decode --timeout.
  -- mode: "rtu" or "ascii"; nil: chosen from the first record's bytes, as vw3-decode does.
  return {
    expect = nil, pending = nil, count = 0, records = {}, devices = {}, timeout = timeout,
    mode = mode,
    judged = {}, said = {}, history = {}, chosen = {}, -- profile auto's: what it judged, said and chose
    -- the byte stream (see feed): unframed bytes, their stream offset, record ends, record times
    b = {}, n = 0, base = 0, boundaries = {}, times = {}, noise = nil, items = {},
    glitches_only = true, noise_cut = false, glitch_runs = 0, -- (stream.py: the glitch rule's state)
    open = {}, -- records some of whose bytes are not framed yet (oldest first)
    last = nil, -- the last record fed
    unpacked = {}, -- record, index of each item not packed yet (pack.settle)
    flat = {}, flat_n = 0, -- the items packed as numbers (pack.settle)
  }
end

-- One register of a run as add_register shows it. b nil: the register is one whose status is not ok
-- (its value is the profile's 16#8000, no bytes needed). The device is found again rather than kept
-- with the run, once a frame shown: its registers are shown one after the other (device_of, a call a
-- register, was some 1 % of the plugin's own work on the plant mix); so is the status a register with none of
-- its own has, the same for every register of the frame: ok in a read from a device that marks unreadable
-- parameters, nil in a frame that failed its check (none judged, not even ok) or any other.
local shown_st, shown_f, shown_device, shown_ok, shown_labels = nil, nil, nil, nil, false
local function register_view(st, f, run, b, index)
  local device = shown_device
  if f ~= shown_f or st ~= shown_st then
    device = device_of(st, f)
    shown_st, shown_f, shown_device = st, f, device
    shown_ok = device and f.kind == RESPONSE and READS[f.fn] ~= nil and device.profile.protected_value ~= nil
      and verified(f) and "ok" or nil
    shown_labels = device and frame_labels(device, f)
  end
  local address, value, offset
  if b ~= nil then
    address, value, offset = register_at(run, b, index, true)
  else
    address, value, offset = (run.start + index) % 0x10000, device.profile.protected_value, -1
  end
  local view = { address = address, value = value, offset = offset }
  if device and address ~= nil then
    local status = run.status and run.status[index] or shown_ok
    local words, second = words_at(rows_for(device, f.fn), address, index, run.count), nil
    if words == 2 and b ~= nil then second = select(2, register_at(run, b, index + 1, true)) end
    describe(device, f, view, run.plain and run.plain[index], status, words, second, shown_labels)
  end
  return view
end
