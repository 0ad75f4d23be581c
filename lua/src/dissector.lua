-- vw3.dissector: Wireshark: the dissectors (serial records, RTU over TCP and UDP), registration.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.dissector"]).

-- A stream's mode, where no preference sets it, is told from its first bytes as vw3-decode tells it
-- (protocol/ascii.py sample_mode: MODE_SAMPLE bytes, up to MODE_REACH after line noise), and those may
-- come in several records (vw3-decode -w writes a run of noise before the first frame as a record of its
-- own). Until they tell, each record's bytes and time are kept (st.sample, with the bytes sampled), and
-- the mode is what the bytes so far would give were the capture to end there: where a record changes it,
-- the records kept are decoded again, in order, into a new state with the mode their bytes give, as if it
-- had been known from the start (as lane.again does). st.sample: false once the mode is settled (or set by
-- the preference). Then the record's first dissection (an error in either shown on the record).
-- The records `kept` ({ number, bytes } each; but `except`) decoded again, in order, into a new state of
-- `mode`, which takes st's place (the same table: `state` and udp_states keep naming it). Their times are
-- those kept (show.lua record_ns).
local function decode_again(st, kept, mode, except)
  local fresh = new_state(st.timeout, mode)
  fresh.sample = st.sample
  for index = 1, #kept do
    local number, bytes_kept = kept[index][1], kept[index][2]
    if number ~= except then -- (no pinfo: the record's is gone; its time is the one kept)
      pack.redo(fresh, number, bytes_kept, dissect_now, fresh, nil, nil, number, bytes_kept)
    end
  end
  pack.take_place(st, fresh)
end

-- A capture's first record at the epoch is timed (time 0) when the second is not, untimed otherwise
-- (sources/pcap.py EpochRecord: a time-of-day log of day 0 starts there; vw3-decode -w writes untimed input
-- at the epoch, every record), where it has bytes, at most a chunk of them (reader.py open_source). Its
-- bytes are kept (st.epoch_first) until the second record's first dissection says: then, timed, it is
-- decoded again with its time. (tshark without -2 has shown it already: untimed, as read.)
local function epoch_first(st, tvb, pinfo, number)
  if number == 1 then
    local n = tvb:len()
    if n > 0 and n <= DATA.timing.held_record_max and pinfo.abs_ts == 0 and rtac_times[1] == nil then
      st.epoch_first = tvb:raw()
    end
  elseif st.epoch_first ~= nil then
    local bytes = st.epoch_first
    st.epoch_first = nil
    if lane.epoch_timed(pinfo) then decode_again(st, { { 1, bytes } }, st.mode) end
  end
end

local function sample_and_dissect(st, tvb, pinfo, number)
  local sample = st.sample
  if sample == nil then
    if st.mode ~= nil then -- (the preference's)
      st.sample = false
      return dissect_now(st, tvb, pinfo, number)
    end
    sample = { text = "", scan = pair_scan() }
    st.sample = sample
  end
  local bytes = tvb_raw(tvb)
  if bytes == "" then return dissect_now(st, tvb, pinfo, number, bytes) end -- (nothing, unless captured in part)
  sample.text = sample.text .. bytes:sub(1, MODE_REACH - #sample.text)
  -- (ended: what vw3-decode would choose were the capture to end here; one look at the bytes gives both, and
  -- the bytes of the records before are not scanned again: sample.scan)
  local mode, ended = sample_modes(sample.text, sample.scan)
  if mode ~= nil then
    st.sample = false
  else
    sample[#sample + 1] = { number, bytes }
    mode = ended
  end
  if st.mode == nil then
    st.mode = mode
  elseif mode ~= st.mode then
    decode_again(st, sample, mode, number)
  end
  return dissect_now(st, tvb, pinfo, number, bytes)
end

-- Are the trees Wireshark's (userdata), not the test stub's (Lua tables)? The same for every record: asked
-- of the first (a call of type() a record costs more than the test).
local wireshark_trees = nil

local function dissect_records(st, tvb, pinfo, tree)
  local number = pinfo_number(pinfo) -- (each field of pinfo is a call into Wireshark: read once)
  local record = st.records[number]
  if record == nil then
    -- First pass (pinfo.visited false): frame, pair and decode in capture order; later passes reuse it.
    if number <= 2 then epoch_first(st, tvb, pinfo, number) end
    -- A record captured in part (a snapshot length shorter than it: tshark's `[Packet size limited during
    -- capture]`) is a cut: lua/src/records.lua cut_part.
    local captured, original = tvb_len(tvb), tvb_reported_len(tvb)
    if original > captured then lane.captured_in_part(number, captured, original) end
    -- (A record is kept from its first dissection on: the first pass asks pinfo nothing more.)
    local ok, result, n, info = pcall(st.sample ~= false and sample_and_dissect or dissect_now, st, tvb, pinfo, number)
    if ok then
      if result == nil then
        -- An empty record: nothing to decode, but the tap was recording then (vw3.pairing's ended).
        local time = number >= newest_record and record_ns(pinfo, number) or nil
        if time ~= nil then recorded_until = time end
        return 0
      end
      record = result
    else
      -- A bug must not make later passes dissect this record again (pairing twice): keep the error.
      n = tvb:len()
      record = { length = n, error = tostring(result) }
    end
    st.records[number] = record
    -- (not tree_mode(tree), written out: no tree)
    if wireshark_trees == nil then wireshark_trees = type(tree) == "userdata" end
    if info ~= nil and wireshark_trees and tree_text(tree) == nil and config.errors[1] == nil then
      -- A record of the quick lanes: its one frame, a request or its answer (kept already), has nothing to
      -- say but its Info text where no tree is wanted.
      local cols = pinfo_cols(pinfo)
      cols.protocol = "VW3"
      cols.info = info
    else
      show_record(st, record, tvb, pinfo, tree, n, st.whole_record == record)
    end
    -- (after the first showing, which reads the items as they were decoded; asked only when some wait)
    if st.whole_record ~= nil or st.unpacked[1] ~= nil then pack.settle(st) end
    return n
  end
  if not state.finished and pinfo.visited then
    finish_all(number)
    record = st.records[number] -- (lane.again may have decoded the capture again)
    if record == nil then return 0 end
  end
  local n = tvb:len()
  show_record(st, record, tvb, pinfo, tree, n)
  return n
end

-- The stream kept under `key` in `states` (a connection's, a conversation's, an interface's), new the first time.
local function stream_of(states, key)
  local st = states[key]
  if st == nil then
    st = stream_state()
    states[key] = st
  end
  return st
end

-- A TCP connection's or UDP conversation's stream, by its transport and its two ends (the same both ways),
-- kept with the other streams the first pass's end finishes (udp_states). RTU over TCP: each segment is a
-- record of its connection's stream (both directions one stream, as the bus they carry: a request, its
-- echo and its answer framed and paired in capture order), read as UDP datagrams and serial records are:
-- bytes the framer cannot decide yet (a frame cut by the segment's end, a write it must tell from its
-- echo) wait in the stream, not in TCP's reassembly, which is per direction and would hold one
-- direction's bytes back from the other's. A frame is shown in the record that completes it, as on a
-- serial capture (vw3-decode reading the same bytes).
local function conversation_state(transport, pinfo)
  local a = tostring(pinfo.src) .. "/" .. tostring(pinfo.src_port)
  local b = tostring(pinfo.dst) .. "/" .. tostring(pinfo.dst_port)
  return stream_of(udp_states, transport .. (a < b and a .. " " .. b or b .. " " .. a))
end

-- A stream's key by its transport's port type (Wireshark's port_type enum: TCP 2, UDP 3).
local TRANSPORTS = { [2] = "tcp ", [3] = "udp " }

-- A pcapng of several interfaces (mergecap -I none) holds several buses, as vw3-decode reads them: with
-- VW3_INTERFACES=1 in the environment, each interface's records are a stream of their own (interface 0:
-- `state`, the others kept with the UDP streams, which the first pass's end finishes too). Opt-in: Lua
-- reads frame.interface_id only through a field extractor, and one makes Wireshark build every record's
-- tree (tshark's one pass some 6 times slower on bench/lua_throughput.py's plant mix). tshark -2's first
-- pass builds no tree without a display filter (-Y): there the extractor sees nothing, and a record
-- keeps the stream its first dissection chose (record_streams), so both passes agree.
local INTERFACE = os.getenv("VW3_INTERFACES") == "1" and Field.new("frame.interface_id") or nil

local function serial_state(pinfo)
  local number = pinfo.number
  local st = record_streams[number]
  if st ~= nil then return st end
  local id = INTERFACE()
  st = state
  if id ~= nil and id.value ~= 0 then st = stream_of(udp_states, "interface " .. id.value) end
  record_streams[number] = st
  return st
end

function proto.dissector(tvb, pinfo, tree)
  local transport = TRANSPORTS[pinfo_port_type(pinfo)]
  if transport ~= nil then return dissect_records(conversation_state(transport, pinfo), tvb, pinfo, tree) end
  return dissect_records(INTERFACE and serial_state(pinfo) or state, tvb, pinfo, tree)
end

-- Registration: Decode As for RTAC serial records and TCP, and an optional TCP port. Linktype 147 (USER0)
-- is the user's to map (Preferences > Protocols > DLT_USER: payload protocol "vw3"): a plugin that took
-- it over would override a user who mapped it to mbrtu. The "user0" preference does it for one session.
local wtap_encap = DissectorTable.get("wtap_encap")
local ok_rtac, rtac = pcall(DissectorTable.get, "rtacser.data")
if ok_rtac and rtac ~= nil then rtac:add_for_decode_as(proto) end

-- RTAC serial records: note the RTAC's own timestamp (u32 seconds, u32 microseconds, big-endian: when the
-- device saw the bytes, which response times need), then hand the record to Wireshark's RTAC dissector.
-- A record shorter than the 12-byte header tells no time and Wireshark's RTAC dissector takes none of it
-- (Data): where Decode As gave this capture's RTAC data to VW3 (rtac_payload: a record of it reached VW3,
-- Lua cannot read that table), its bytes are VW3's, at its record's time, as vw3-decode reads them
-- (sources/common.py rtac_header: noise).
local RTAC_ENCAP = wtap.RTAC_SERIAL
local ok_original, rtac_original = pcall(function() return RTAC_ENCAP and wtap_encap:get_dissector(RTAC_ENCAP) end)
if ok_original and rtac_original ~= nil then
  local rtac_time = Proto("vw3rtac", "VW3 RTAC timestamp")
  local vw3_handle = Dissector.get("vw3")
  function rtac_time.dissector(tvb, pinfo, tree)
    local n = tvb:len()
    if n < 12 and rtac_payload then return vw3_handle:call(tvb, pinfo, tree) end
    if n >= 12 and not pinfo.visited then
      local seconds, micros = tvb:range(0, 4):uint(), tvb:range(4, 4):uint()
      local number, ns = pinfo.number, lane.rtac_ns(seconds, micros)
      rtac_times[number] = ns -- (in ns, exact: show.lua record_ns)
      -- A record of the header alone (an RTAC event: a break, a control line) reaches no VW3 dissection, yet
      -- the tap was recording then (vw3.pairing's ended; sources/common.py record_chunks' `stamped`).
      if n == 12 and number >= newest_record then recorded_until = ns end
      if n > 12 and not rtac_payload then
        local taken = rtac_original:call(tvb, pinfo, tree)
        rtac_payload = (record_streams[number] or state).records[number] ~= nil
        return taken
      end
    end
    return rtac_original:call(tvb, pinfo, tree)
  end
  wtap_encap:add(RTAC_ENCAP, rtac_time)
end
DissectorTable.get("tcp.port"):add_for_decode_as(proto)
DissectorTable.get("udp.port"):add_for_decode_as(proto)

-- What the optional Modbus/TCP naming file (vw3_modbus.lua, loaded after this one) builds on. It is a
-- file of its own so that serial captures pay nothing for it: its field extractors make Wireshark build
-- a tree for every packet. (Each script has globals of its own; package.loaded is shared.)
package.loaded.vw3_plugin = {
  new_state = new_state, device_now = device_now,
  mask_register = mask_register,
  add_register = add_register, add_text = add_text, pf = pf, ex = ex, REQUEST = REQUEST, RESPONSE = RESPONSE,
}

-- What the preferences registered: TCP and UDP ports (0: none), USER0 taken over.
local registered = { tcp_port = 0, udp_port = 0, user0 = false }
function proto.prefs_changed()
  for _, pref in ipairs({ "tcp_port", "udp_port" }) do
    local port = proto.prefs[pref]
    if port ~= registered[pref] then
      local ports = DissectorTable.get(pref == "tcp_port" and "tcp.port" or "udp.port")
      if registered[pref] ~= 0 then ports:remove(registered[pref], proto) end
      if port ~= 0 then ports:add(port, proto) end
      registered[pref] = port
    end
  end
  if proto.prefs.user0 ~= registered.user0 then
    if proto.prefs.user0 then wtap_encap:add(wtap.USER0, proto) else wtap_encap:remove(wtap.USER0, proto) end
    registered.user0 = proto.prefs.user0
  end
  lane.line_speed(proto.prefs.baud)
  apply_prefs()
end
