-- vw3.api: the pure part's entry points (tests load vw3.lua outside Wireshark).
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.api"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)

M.vw3 = {
  new_state = new_state, dissect_record = dissect_record, finish = finish, settle = pack.settle,
  configure = configure,
}
