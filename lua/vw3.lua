-- vw3.lua: Wireshark plugin for Modbus serial (RTU, ASCII) captures of Altivar 71 drives (VW3 A3 303 card)
-- and SEL-749M relays; the same dissection as the vw3-decode command, inside Wireshark.
--
-- Install: copy this one file into the personal Lua plugins folder (Linux, macOS:
-- ~/.local/lib/wireshark/plugins/, Windows: %APPDATA%\Wireshark\plugins\), or load it for one run with
-- `tshark -X lua_script:vw3.lua -r capture.pcap`. It decodes linktype 147 (USER0) records, `rtacser.data`
-- through Decode As, and Modbus RTU over TCP and UDP on the ports set in the preferences.
--
-- GENERATED: python3 -m dissector.codegen assembles this file from lua/src/*.lua (one module a stage,
-- each naming the Python module it mirrors; edit those) and the tables between the GENERATED DATA markers
-- (the package's data files); `python3 -m dissector.codegen --check` fails when it is not that assembly.
-- Each module is a function in package.preload, obtained with require("vw3.NAME"); they share one table
-- of names, vw3.env (each module's exports and DATA, then this script's globals).
--
-- Runs on Wireshark 4.0 (Lua 5.2) and 4.4+ (Lua 5.4): no native bitwise operators, no `//`, integer
-- division with math.floor; the CRC's XOR from tables built with arithmetic alone (vw3.crc).

-- BEGIN GENERATED DATA: python3 -m dissector.codegen.lua (do not edit by hand)
local DATA = {
  ["functions"] = {
    [1] = "Read Coils",
    [2] = "Read Discrete Inputs",
    [3] = "Read Holding Registers",
    [4] = "Read Input Registers",
    [5] = "Write Single Coil",
    [6] = "Write Single Register",
    [7] = "Read Exception Status",
    [8] = "Diagnostics",
    [11] = "Get Comm Event Counter",
    [12] = "Get Comm Event Log",
    [15] = "Write Multiple Coils",
    [16] = "Write Multiple Registers",
    [17] = "Report Server ID",
    [20] = "Read File Record",
    [21] = "Write File Record",
    [22] = "Mask Write Register",
    [23] = "Read/Write Multiple Registers",
    [24] = "Read FIFO Queue",
    [43] = "Encapsulated Interface Transport",
  },
  ["exceptions"] = {
    [1] = "Illegal Function",
    [2] = "Illegal Data Address",
    [3] = "Illegal Data Value",
    [4] = "Server Device Failure",
    [5] = "Acknowledge",
    [6] = "Server Device Busy",
    [7] = "Negative Acknowledge",
    [8] = "Memory Parity Error",
    [10] = "Gateway Path Unavailable",
    [11] = "Gateway Target Device Failed to Respond",
  },
  ["diagnostics"] = {
    [0] = "Return Query Data",
    [1] = "Restart Communications Option",
    [2] = "Return Diagnostic Register",
    [3] = "Change ASCII Input Delimiter",
    [4] = "Force Listen Only Mode",
    [10] = "Clear Counters and Diagnostic Register",
    [11] = "Return Bus Message Count",
    [12] = "Return Bus Communication Error Count",
    [13] = "Return Bus Exception Error Count",
    [14] = "Return Server Message Count",
    [15] = "Return Server No Response Count",
    [16] = "Return Server NAK Count",
    [17] = "Return Server Busy Count",
    [18] = "Return Bus Character Overrun Count",
    [20] = "Clear Overrun Counter and Flag",
  },
  ["device_id_objects"] = {
    [0] = "VendorName",
    [1] = "ProductCode",
    [2] = "MajorMinorRevision",
    [3] = "VendorUrl",
    [4] = "ProductName",
    [5] = "ModelName",
    [6] = "UserApplicationName",
  },
  ["names"] = {
    ["run_indicator"] = {
      [0] = "OFF",
      [255] = "ON",
    },
    ["device_id_conformity"] = {
      [1] = "basic, stream access only",
      [2] = "regular, stream access only",
      [3] = "extended, stream access only",
      [129] = "basic, stream and individual access",
      [130] = "regular, stream and individual access",
      [131] = "extended, stream and individual access",
    },
    ["comm_event"] = {
      [0] = "Initiated Communication Restart",
      [4] = "Entered Listen Only Mode",
    },
    ["comm_event_kind"] = {
      [128] = "Receive Event",
      [64] = "Send Event",
      [0] = "Unknown Event",
    },
    ["comm_event_128"] = {
      [2] = "Communication Error",
      [16] = "Character Overrun",
      [32] = "Currently in Listen Only Mode",
      [64] = "Broadcast Received",
    },
    ["comm_event_64"] = {
      [1] = "Read Exception Sent",
      [2] = "Slave Abort Exception Sent",
      [4] = "Slave Busy Exception Sent",
      [8] = "Slave Program NAK Exception Sent",
      [16] = "Write Timeout Error Occurred",
      [32] = "Currently in Listen Only Mode",
    },
  },
  ["framing"] = {
    ["max_adu"] = 256,
    ["max_counted"] = 268,
    ["min_adu"] = 4,
    ["max_slave"] = 247,
    ["noise_item_max"] = 4096,
    ["glitch_skip"] = 16,
    ["glitch_run"] = 16,
    ["glitchy_after"] = 3,
    ["glitch_score_max"] = 8,
    ["glitch_bytes"] = {
      [0] = true,
      [128] = true,
      [192] = true,
      [224] = true,
      [240] = true,
      [248] = true,
      [252] = true,
      [254] = true,
      [255] = true,
    },
    ["glitch_addresses"] = {
      [0] = true,
      [248] = true,
      [252] = true,
      [254] = true,
      [255] = true,
    },
    ["repeat_probe"] = 16,
    ["repeat_window"] = 768,
    ["cut_answer"] = "the capture ends inside the ",
    ["silence_cuts"] = "a silence cuts ",
  },
  ["ascii"] = {
    ["max_ascii"] = 513,
    ["min_binary"] = 3,
    ["share"] = 0.9,
    ["hex_digits"] = {
      [48] = 0,
      [49] = 1,
      [50] = 2,
      [51] = 3,
      [52] = 4,
      [53] = 5,
      [54] = 6,
      [55] = 7,
      [56] = 8,
      [57] = 9,
      [65] = 10,
      [66] = 11,
      [67] = 12,
      [68] = 13,
      [69] = 14,
      [70] = 15,
      [97] = 10,
      [98] = 11,
      [99] = 12,
      [100] = 13,
      [101] = 14,
      [102] = 15,
    },
    ["alphabet"] = {
      [10] = true,
      [13] = true,
      [48] = true,
      [49] = true,
      [50] = true,
      [51] = true,
      [52] = true,
      [53] = true,
      [54] = true,
      [55] = true,
      [56] = true,
      [57] = true,
      [58] = true,
      [65] = true,
      [66] = true,
      [67] = true,
      [68] = true,
      [69] = true,
      [70] = true,
      [97] = true,
      [98] = true,
      [99] = true,
      [100] = true,
      [101] = true,
      [102] = true,
    },
    ["delimiters"] = { 58, 13, 10 },
    ["mode_sample"] = 64,
    ["sets_delimiter"] = {
      [3] = true,
    },
  },
  ["map_format"] = {
    ["columns"] = {
      ["access"] = true,
      ["address"] = true,
      ["bits"] = true,
      ["code"] = true,
      ["enum"] = true,
      ["name"] = true,
      ["order"] = true,
      ["scale"] = true,
      ["signed"] = true,
      ["source"] = true,
      ["type"] = true,
      ["unit"] = true,
    },
    ["required"] = { "address", "code" },
    ["reference"] = "reference",
    ["reference_bases"] = { 40001, 30001 },
    ["input_functions"] = {
      [4] = true,
    },
    ["max_bytes"] = 16777216,
    ["scale_min"] = 1e-12,
    ["scale_max"] = 1000000000000.0,
    ["scale_unknown"] = "?",
    ["types"] = {
      ["uint16"] = 1,
      ["int16"] = 1,
      ["uint32"] = 2,
      ["int32"] = 2,
      ["float32"] = 2,
    },
    ["orders"] = {
      ["ABCD"] = true,
      ["CDAB"] = true,
    },
    ["order_list"] = { "ABCD", "CDAB" },
    ["default_types"] = { "uint16", "int16" },
    ["signed_types"] = {
      ["int16"] = true,
      ["int32"] = true,
    },
    ["pairs"] = {
      ["enum"] = { 0, 65535 },
      ["bits"] = { 0, 15 },
    },
    ["separators"] = { ",", ";", "\009" },
    ["access"] = {
      ["R"] = true,
      ["RW"] = true,
      ["W"] = true,
    },
    ["read_only"] = "R",
    ["references_judged"] = 32,
    ["messages"] = {
      ["unknown_column"] = {
        ["format"] = "unknown column %s (columns: address, code, name, unit, scale, access, enum, bits, signed, source, type, order)",
        ["params"] = { "name" },
        ["repr"] = {
          ["name"] = true,
        },
      },
      ["missing_column"] = {
        ["format"] = "the header lacks the %s column",
        ["params"] = { "name" },
        ["repr"] = {
          ["name"] = true,
        },
      },
      ["column_twice"] = {
        ["format"] = "a column is named twice in the header",
        ["params"] = {},
        ["repr"] = {},
      },
      ["fields"] = {
        ["format"] = "%d fields, the header has %d (quote a field that holds a %s)",
        ["params"] = { "count", "header", "separator" },
        ["repr"] = {},
      },
      ["not_utf8"] = {
        ["format"] = "not UTF-8 text",
        ["params"] = {},
        ["repr"] = {},
      },
      ["utf16"] = {
        ["format"] = "not UTF-8 text (UTF-16, as Excel's \"Unicode Text\" saves: save the map as \"CSV UTF-8\")",
        ["params"] = {},
        ["repr"] = {},
      },
      ["open_quote"] = {
        ["format"] = "a quoted field is not closed on this line (a line break inside a cell? write each row on one line)",
        ["params"] = {},
        ["repr"] = {},
      },
      ["address_twice"] = {
        ["format"] = "address %d already defined on line %d",
        ["params"] = { "address", "line" },
        ["repr"] = {},
      },
      ["second_register"] = {
        ["format"] = "address %d is the second register of %s (%s, line %d)",
        ["params"] = { "address", "code", "kind", "line" },
        ["repr"] = {},
      },
      ["no_header"] = {
        ["format"] = "no header line (expected: address,code,name,unit,scale,access,enum,bits,signed,source,type,order)",
        ["params"] = {},
        ["repr"] = {},
      },
      ["address"] = {
        ["format"] = "address %s is not a number",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["address_range"] = {
        ["format"] = "address %d is outside 0..65535",
        ["params"] = { "address" },
        ["repr"] = {},
      },
      ["code"] = {
        ["format"] = "code is empty",
        ["params"] = {},
        ["repr"] = {},
      },
      ["scale"] = {
        ["format"] = "scale %s is not a number",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["scale_range"] = {
        ["format"] = "scale %s is outside \194\1771e-12..1e+12",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["scale_zero"] = {
        ["format"] = "scale %s would make every value 0",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["scale_unknown_unit"] = {
        ["format"] = "scale '?' (the device sets it) needs the unit the value counts in",
        ["params"] = {},
        ["repr"] = {},
      },
      ["scale_unknown_wide"] = {
        ["format"] = "scale '?' (the device sets it) is for a 16-bit register: type %s is two",
        ["params"] = { "kind" },
        ["repr"] = {},
      },
      ["access"] = {
        ["format"] = "access %s is not R, W or RW",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["pair"] = {
        ["format"] = "%s entry %s is not `number=label`",
        ["params"] = { "what", "part" },
        ["repr"] = {
          ["part"] = true,
        },
      },
      ["pair_number"] = {
        ["format"] = "%s entry %s: %s is not a number",
        ["params"] = { "what", "part", "key" },
        ["repr"] = {
          ["part"] = true,
          ["key"] = true,
        },
      },
      ["pair_range"] = {
        ["format"] = "%s entry %s: %d is outside %d..%d",
        ["params"] = { "what", "part", "number", "low", "high" },
        ["repr"] = {
          ["part"] = true,
        },
      },
      ["pair_twice"] = {
        ["format"] = "%s entry %s: %d given twice",
        ["params"] = { "what", "part", "number" },
        ["repr"] = {
          ["part"] = true,
        },
      },
      ["signed"] = {
        ["format"] = "signed %s is not 1, 0 or empty",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["type"] = {
        ["format"] = "type %s is not one of uint16, int16, uint32, int32, float32",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["order"] = {
        ["format"] = "order %s is not ABCD or CDAB",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["wide_labels"] = {
        ["format"] = "a %s value cannot carry enum or bit labels",
        ["params"] = { "kind" },
        ["repr"] = {},
      },
      ["wide_last"] = {
        ["format"] = "a %s value needs two registers: %d is the last address",
        ["params"] = { "kind", "address" },
        ["repr"] = {},
      },
      ["signed_enum"] = {
        ["format"] = "a signed register cannot carry enum labels",
        ["params"] = {},
        ["repr"] = {},
      },
      ["signed_type"] = {
        ["format"] = "signed %s contradicts type %s",
        ["params"] = { "text", "kind" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["order_one_word"] = {
        ["format"] = "order %s swaps the words of a 32-bit value: type %s is one register",
        ["params"] = { "text", "kind" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["enum_bits"] = {
        ["format"] = "a register cannot carry both enum and bit labels",
        ["params"] = {},
        ["repr"] = {},
      },
      ["labels_quantity"] = {
        ["format"] = "a register with %s labels cannot carry a %s (its value is a label)",
        ["params"] = { "what", "column" },
        ["repr"] = {},
      },
      ["code_twice"] = {
        ["format"] = "code %s already names address %d (line %d)",
        ["params"] = { "code", "address", "line" },
        ["repr"] = {},
      },
      ["reference_and_address"] = {
        ["format"] = "a map gives each row an address or a reference, not both",
        ["params"] = {},
        ["repr"] = {},
      },
      ["reference_twice"] = {
        ["format"] = "reference %s is %s register %d, as %s on line %d: a map names each register once",
        ["params"] = { "text", "table", "address", "first", "line" },
        ["repr"] = {
          ["text"] = true,
          ["first"] = true,
        },
      },
      ["reference"] = {
        ["format"] = "reference %s is not a 4X or 3X register reference (40001..49999, 400001..465536; 30001..39999, 300001..365536)",
        ["params"] = { "text" },
        ["repr"] = {
          ["text"] = true,
        },
      },
      ["references"] = {
        ["format"] = "map %s names %d of the %d unnamed registers slave %d reads or writes at address + %s: PLC references? A map takes protocol addresses (reference - %s)%s",
        ["params"] = { "map", "shifted", "unnamed", "slave", "offset", "offset", "column" },
        ["repr"] = {},
      },
      ["references_column"] = {
        ["format"] = " or a reference column",
        ["params"] = {},
        ["repr"] = {},
      },
    },
  },
  ["nonprintable"] = {
    ["python"] = "3.11.7",
    ["unicode"] = "14.0.0",
    ["ranges"] = {
      "0-1f 7f-a0 ad-ad 378-379 380-383 38b-38b 38d-38d 3a2-3a2",
      "530-530 557-558 58b-58c 590-590 5c8-5cf 5eb-5ee 5f5-605 61c-61c",
      "6dd-6dd 70e-70f 74b-74c 7b2-7bf 7fb-7fc 82e-82f 83f-83f 85c-85d",
      "85f-85f 86b-86f 88f-897 8e2-8e2 984-984 98d-98e 991-992 9a9-9a9",
      "9b1-9b1 9b3-9b5 9ba-9bb 9c5-9c6 9c9-9ca 9cf-9d6 9d8-9db 9de-9de",
      "9e4-9e5 9ff-a00 a04-a04 a0b-a0e a11-a12 a29-a29 a31-a31 a34-a34",
      "a37-a37 a3a-a3b a3d-a3d a43-a46 a49-a4a a4e-a50 a52-a58 a5d-a5d",
      "a5f-a65 a77-a80 a84-a84 a8e-a8e a92-a92 aa9-aa9 ab1-ab1 ab4-ab4",
      "aba-abb ac6-ac6 aca-aca ace-acf ad1-adf ae4-ae5 af2-af8 b00-b00",
      "b04-b04 b0d-b0e b11-b12 b29-b29 b31-b31 b34-b34 b3a-b3b b45-b46",
      "b49-b4a b4e-b54 b58-b5b b5e-b5e b64-b65 b78-b81 b84-b84 b8b-b8d",
      "b91-b91 b96-b98 b9b-b9b b9d-b9d ba0-ba2 ba5-ba7 bab-bad bba-bbd",
      "bc3-bc5 bc9-bc9 bce-bcf bd1-bd6 bd8-be5 bfb-bff c0d-c0d c11-c11",
      "c29-c29 c3a-c3b c45-c45 c49-c49 c4e-c54 c57-c57 c5b-c5c c5e-c5f",
      "c64-c65 c70-c76 c8d-c8d c91-c91 ca9-ca9 cb4-cb4 cba-cbb cc5-cc5",
      "cc9-cc9 cce-cd4 cd7-cdc cdf-cdf ce4-ce5 cf0-cf0 cf3-cff d0d-d0d",
      "d11-d11 d45-d45 d49-d49 d50-d53 d64-d65 d80-d80 d84-d84 d97-d99",
      "db2-db2 dbc-dbc dbe-dbf dc7-dc9 dcb-dce dd5-dd5 dd7-dd7 de0-de5",
      "df0-df1 df5-e00 e3b-e3e e5c-e80 e83-e83 e85-e85 e8b-e8b ea4-ea4",
      "ea6-ea6 ebe-ebf ec5-ec5 ec7-ec7 ece-ecf eda-edb ee0-eff f48-f48",
      "f6d-f70 f98-f98 fbd-fbd fcd-fcd fdb-fff 10c6-10c6 10c8-10cc 10ce-10cf",
      "1249-1249 124e-124f 1257-1257 1259-1259 125e-125f 1289-1289 128e-128f 12b1-12b1",
      "12b6-12b7 12bf-12bf 12c1-12c1 12c6-12c7 12d7-12d7 1311-1311 1316-1317 135b-135c",
      "137d-137f 139a-139f 13f6-13f7 13fe-13ff 1680-1680 169d-169f 16f9-16ff 1716-171e",
      "1737-173f 1754-175f 176d-176d 1771-1771 1774-177f 17de-17df 17ea-17ef 17fa-17ff",
      "180e-180e 181a-181f 1879-187f 18ab-18af 18f6-18ff 191f-191f 192c-192f 193c-193f",
      "1941-1943 196e-196f 1975-197f 19ac-19af 19ca-19cf 19db-19dd 1a1c-1a1d 1a5f-1a5f",
      "1a7d-1a7e 1a8a-1a8f 1a9a-1a9f 1aae-1aaf 1acf-1aff 1b4d-1b4f 1b7f-1b7f 1bf4-1bfb",
      "1c38-1c3a 1c4a-1c4c 1c89-1c8f 1cbb-1cbc 1cc8-1ccf 1cfb-1cff 1f16-1f17 1f1e-1f1f",
      "1f46-1f47 1f4e-1f4f 1f58-1f58 1f5a-1f5a 1f5c-1f5c 1f5e-1f5e 1f7e-1f7f 1fb5-1fb5",
      "1fc5-1fc5 1fd4-1fd5 1fdc-1fdc 1ff0-1ff1 1ff5-1ff5 1fff-200f 2028-202f 205f-206f",
      "2072-2073 208f-208f 209d-209f 20c1-20cf 20f1-20ff 218c-218f 2427-243f 244b-245f",
      "2b74-2b75 2b96-2b96 2cf4-2cf8 2d26-2d26 2d28-2d2c 2d2e-2d2f 2d68-2d6e 2d71-2d7e",
      "2d97-2d9f 2da7-2da7 2daf-2daf 2db7-2db7 2dbf-2dbf 2dc7-2dc7 2dcf-2dcf 2dd7-2dd7",
      "2ddf-2ddf 2e5e-2e7f 2e9a-2e9a 2ef4-2eff 2fd6-2fef 2ffc-3000 3040-3040 3097-3098",
      "3100-3104 3130-3130 318f-318f 31e4-31ef 321f-321f a48d-a48f a4c7-a4cf a62c-a63f",
      "a6f8-a6ff a7cb-a7cf a7d2-a7d2 a7d4-a7d4 a7da-a7f1 a82d-a82f a83a-a83f a878-a87f",
      "a8c6-a8cd a8da-a8df a954-a95e a97d-a97f a9ce-a9ce a9da-a9dd a9ff-a9ff aa37-aa3f",
      "aa4e-aa4f aa5a-aa5b aac3-aada aaf7-ab00 ab07-ab08 ab0f-ab10 ab17-ab1f ab27-ab27",
      "ab2f-ab2f ab6c-ab6f abee-abef abfa-abff d7a4-d7af d7c7-d7ca d7fc-f8ff fa6e-fa6f",
      "fada-faff fb07-fb12 fb18-fb1c fb37-fb37 fb3d-fb3d fb3f-fb3f fb42-fb42 fb45-fb45",
      "fbc3-fbd2 fd90-fd91 fdc8-fdce fdd0-fdef fe1a-fe1f fe53-fe53 fe67-fe67 fe6c-fe6f",
      "fe75-fe75 fefd-ff00 ffbf-ffc1 ffc8-ffc9 ffd0-ffd1 ffd8-ffd9 ffdd-ffdf ffe7-ffe7",
      "ffef-fffb fffe-ffff 1000c-1000c 10027-10027 1003b-1003b 1003e-1003e 1004e-1004f 1005e-1007f",
      "100fb-100ff 10103-10106 10134-10136 1018f-1018f 1019d-1019f 101a1-101cf 101fe-1027f 1029d-1029f",
      "102d1-102df 102fc-102ff 10324-1032c 1034b-1034f 1037b-1037f 1039e-1039e 103c4-103c7 103d6-103ff",
      "1049e-1049f 104aa-104af 104d4-104d7 104fc-104ff 10528-1052f 10564-1056e 1057b-1057b 1058b-1058b",
      "10593-10593 10596-10596 105a2-105a2 105b2-105b2 105ba-105ba 105bd-105ff 10737-1073f 10756-1075f",
      "10768-1077f 10786-10786 107b1-107b1 107bb-107ff 10806-10807 10809-10809 10836-10836 10839-1083b",
      "1083d-1083e 10856-10856 1089f-108a6 108b0-108df 108f3-108f3 108f6-108fa 1091c-1091e 1093a-1093e",
      "10940-1097f 109b8-109bb 109d0-109d1 10a04-10a04 10a07-10a0b 10a14-10a14 10a18-10a18 10a36-10a37",
      "10a3b-10a3e 10a49-10a4f 10a59-10a5f 10aa0-10abf 10ae7-10aea 10af7-10aff 10b36-10b38 10b56-10b57",
      "10b73-10b77 10b92-10b98 10b9d-10ba8 10bb0-10bff 10c49-10c7f 10cb3-10cbf 10cf3-10cf9 10d28-10d2f",
      "10d3a-10e5f 10e7f-10e7f 10eaa-10eaa 10eae-10eaf 10eb2-10eff 10f28-10f2f 10f5a-10f6f 10f8a-10faf",
      "10fcc-10fdf 10ff7-10fff 1104e-11051 11076-1107e 110bd-110bd 110c3-110cf 110e9-110ef 110fa-110ff",
      "11135-11135 11148-1114f 11177-1117f 111e0-111e0 111f5-111ff 11212-11212 1123f-1127f 11287-11287",
      "11289-11289 1128e-1128e 1129e-1129e 112aa-112af 112eb-112ef 112fa-112ff 11304-11304 1130d-1130e",
      "11311-11312 11329-11329 11331-11331 11334-11334 1133a-1133a 11345-11346 11349-1134a 1134e-1134f",
      "11351-11356 11358-1135c 11364-11365 1136d-1136f 11375-113ff 1145c-1145c 11462-1147f 114c8-114cf",
      "114da-1157f 115b6-115b7 115de-115ff 11645-1164f 1165a-1165f 1166d-1167f 116ba-116bf 116ca-116ff",
      "1171b-1171c 1172c-1172f 11747-117ff 1183c-1189f 118f3-118fe 11907-11908 1190a-1190b 11914-11914",
      "11917-11917 11936-11936 11939-1193a 11947-1194f 1195a-1199f 119a8-119a9 119d8-119d9 119e5-119ff",
      "11a48-11a4f 11aa3-11aaf 11af9-11bff 11c09-11c09 11c37-11c37 11c46-11c4f 11c6d-11c6f 11c90-11c91",
      "11ca8-11ca8 11cb7-11cff 11d07-11d07 11d0a-11d0a 11d37-11d39 11d3b-11d3b 11d3e-11d3e 11d48-11d4f",
      "11d5a-11d5f 11d66-11d66 11d69-11d69 11d8f-11d8f 11d92-11d92 11d99-11d9f 11daa-11edf 11ef9-11faf",
      "11fb1-11fbf 11ff2-11ffe 1239a-123ff 1246f-1246f 12475-1247f 12544-12f8f 12ff3-12fff 1342f-143ff",
      "14647-167ff 16a39-16a3f 16a5f-16a5f 16a6a-16a6d 16abf-16abf 16aca-16acf 16aee-16aef 16af6-16aff",
      "16b46-16b4f 16b5a-16b5a 16b62-16b62 16b78-16b7c 16b90-16e3f 16e9b-16eff 16f4b-16f4e 16f88-16f8e",
      "16fa0-16fdf 16fe5-16fef 16ff2-16fff 187f8-187ff 18cd6-18cff 18d09-1afef 1aff4-1aff4 1affc-1affc",
      "1afff-1afff 1b123-1b14f 1b153-1b163 1b168-1b16f 1b2fc-1bbff 1bc6b-1bc6f 1bc7d-1bc7f 1bc89-1bc8f",
      "1bc9a-1bc9b 1bca0-1ceff 1cf2e-1cf2f 1cf47-1cf4f 1cfc4-1cfff 1d0f6-1d0ff 1d127-1d128 1d173-1d17a",
      "1d1eb-1d1ff 1d246-1d2df 1d2f4-1d2ff 1d357-1d35f 1d379-1d3ff 1d455-1d455 1d49d-1d49d 1d4a0-1d4a1",
      "1d4a3-1d4a4 1d4a7-1d4a8 1d4ad-1d4ad 1d4ba-1d4ba 1d4bc-1d4bc 1d4c4-1d4c4 1d506-1d506 1d50b-1d50c",
      "1d515-1d515 1d51d-1d51d 1d53a-1d53a 1d53f-1d53f 1d545-1d545 1d547-1d549 1d551-1d551 1d6a6-1d6a7",
      "1d7cc-1d7cd 1da8c-1da9a 1daa0-1daa0 1dab0-1deff 1df1f-1dfff 1e007-1e007 1e019-1e01a 1e022-1e022",
      "1e025-1e025 1e02b-1e0ff 1e12d-1e12f 1e13e-1e13f 1e14a-1e14d 1e150-1e28f 1e2af-1e2bf 1e2fa-1e2fe",
      "1e300-1e7df 1e7e7-1e7e7 1e7ec-1e7ec 1e7ef-1e7ef 1e7ff-1e7ff 1e8c5-1e8c6 1e8d7-1e8ff 1e94c-1e94f",
      "1e95a-1e95d 1e960-1ec70 1ecb5-1ed00 1ed3e-1edff 1ee04-1ee04 1ee20-1ee20 1ee23-1ee23 1ee25-1ee26",
      "1ee28-1ee28 1ee33-1ee33 1ee38-1ee38 1ee3a-1ee3a 1ee3c-1ee41 1ee43-1ee46 1ee48-1ee48 1ee4a-1ee4a",
      "1ee4c-1ee4c 1ee50-1ee50 1ee53-1ee53 1ee55-1ee56 1ee58-1ee58 1ee5a-1ee5a 1ee5c-1ee5c 1ee5e-1ee5e",
      "1ee60-1ee60 1ee63-1ee63 1ee65-1ee66 1ee6b-1ee6b 1ee73-1ee73 1ee78-1ee78 1ee7d-1ee7d 1ee7f-1ee7f",
      "1ee8a-1ee8a 1ee9c-1eea0 1eea4-1eea4 1eeaa-1eeaa 1eebc-1eeef 1eef2-1efff 1f02c-1f02f 1f094-1f09f",
      "1f0af-1f0b0 1f0c0-1f0c0 1f0d0-1f0d0 1f0f6-1f0ff 1f1ae-1f1e5 1f203-1f20f 1f23c-1f23f 1f249-1f24f",
      "1f252-1f25f 1f266-1f2ff 1f6d8-1f6dc 1f6ed-1f6ef 1f6fd-1f6ff 1f774-1f77f 1f7d9-1f7df 1f7ec-1f7ef",
      "1f7f1-1f7ff 1f80c-1f80f 1f848-1f84f 1f85a-1f85f 1f888-1f88f 1f8ae-1f8af 1f8b2-1f8ff 1fa54-1fa5f",
      "1fa6e-1fa6f 1fa75-1fa77 1fa7d-1fa7f 1fa87-1fa8f 1faad-1faaf 1fabb-1fabf 1fac6-1facf 1fada-1fadf",
      "1fae8-1faef 1faf7-1faff 1fb93-1fb93 1fbcb-1fbef 1fbfa-1ffff 2a6e0-2a6ff 2b739-2b73f 2b81e-2b81f",
      "2cea2-2ceaf 2ebe1-2f7ff 2fa1e-2ffff 3134b-e00ff e01f0-10ffff",
    },
  },
  ["crc_table"] = {
    0,
    49345,
    49537,
    320,
    49921,
    960,
    640,
    49729,
    50689,
    1728,
    1920,
    51009,
    1280,
    50625,
    50305,
    1088,
    52225,
    3264,
    3456,
    52545,
    3840,
    53185,
    52865,
    3648,
    2560,
    51905,
    52097,
    2880,
    51457,
    2496,
    2176,
    51265,
    55297,
    6336,
    6528,
    55617,
    6912,
    56257,
    55937,
    6720,
    7680,
    57025,
    57217,
    8000,
    56577,
    7616,
    7296,
    56385,
    5120,
    54465,
    54657,
    5440,
    55041,
    6080,
    5760,
    54849,
    53761,
    4800,
    4992,
    54081,
    4352,
    53697,
    53377,
    4160,
    61441,
    12480,
    12672,
    61761,
    13056,
    62401,
    62081,
    12864,
    13824,
    63169,
    63361,
    14144,
    62721,
    13760,
    13440,
    62529,
    15360,
    64705,
    64897,
    15680,
    65281,
    16320,
    16000,
    65089,
    64001,
    15040,
    15232,
    64321,
    14592,
    63937,
    63617,
    14400,
    10240,
    59585,
    59777,
    10560,
    60161,
    11200,
    10880,
    59969,
    60929,
    11968,
    12160,
    61249,
    11520,
    60865,
    60545,
    11328,
    58369,
    9408,
    9600,
    58689,
    9984,
    59329,
    59009,
    9792,
    8704,
    58049,
    58241,
    9024,
    57601,
    8640,
    8320,
    57409,
    40961,
    24768,
    24960,
    41281,
    25344,
    41921,
    41601,
    25152,
    26112,
    42689,
    42881,
    26432,
    42241,
    26048,
    25728,
    42049,
    27648,
    44225,
    44417,
    27968,
    44801,
    28608,
    28288,
    44609,
    43521,
    27328,
    27520,
    43841,
    26880,
    43457,
    43137,
    26688,
    30720,
    47297,
    47489,
    31040,
    47873,
    31680,
    31360,
    47681,
    48641,
    32448,
    32640,
    48961,
    32000,
    48577,
    48257,
    31808,
    46081,
    29888,
    30080,
    46401,
    30464,
    47041,
    46721,
    30272,
    29184,
    45761,
    45953,
    29504,
    45313,
    29120,
    28800,
    45121,
    20480,
    37057,
    37249,
    20800,
    37633,
    21440,
    21120,
    37441,
    38401,
    22208,
    22400,
    38721,
    21760,
    38337,
    38017,
    21568,
    39937,
    23744,
    23936,
    40257,
    24320,
    40897,
    40577,
    24128,
    23040,
    39617,
    39809,
    23360,
    39169,
    22976,
    22656,
    38977,
    34817,
    18624,
    18816,
    35137,
    19200,
    35777,
    35457,
    19008,
    19968,
    36545,
    36737,
    20288,
    36097,
    19904,
    19584,
    35905,
    17408,
    33985,
    34177,
    17728,
    34561,
    18368,
    18048,
    34369,
    33281,
    17088,
    17280,
    33601,
    16640,
    33217,
    32897,
    16448,
  },
  ["not_broadcast"] = {
    [1] = true,
    [2] = true,
    [3] = true,
    [4] = true,
    [7] = true,
    [11] = true,
    [12] = true,
    [17] = true,
    [20] = true,
    [23] = true,
    [24] = true,
    [43] = true,
  },
  ["read_only_exception"] = 2,
  ["plain_texts"] = {
    ["odd_diagnostic_data"] = "diagnostic data is not a whole number of words",
    ["character_then_00"] = "a character, then 00",
    ["never_answered"] = "no response expected: the spec's server returns none",
    ["listen_only_broadcast"] = ", broadcast",
    ["listen_only_echo"] = "an answer to 08/04 (Force Listen Only Mode), which the spec's slave does not answer",
    ["unmatched"] = "response without a matching request in the capture",
    ["broadcast_address"] = "response from slave 0, the broadcast address: a server answers with its own address",
    ["capture_ends_unknown"] = "the capture ends before any response: not known whether it was answered",
    ["lf_without_cr"] = "line ends with LF without CR (the spec ends a frame with CR LF)",
    ["lf_then_cr"] = "line ends with LF then CR, reversed (the spec ends a frame with CR LF)",
    ["cr_without_lf"] = "line ends with CR without LF, before the next ':' (the spec ends a frame with CR LF)",
    ["cr_at_end"] = "line ends with CR without LF, at the end of the capture (the spec ends a frame with CR LF)",
    ["lower_case_hex"] = "lower-case hex digits (the spec wants upper case)",
    ["no_frame"] = "no valid frame",
    ["too_short"] = "too short for a frame",
    ["outside_ascii"] = "outside an ASCII frame",
    ["cut_by_colon"] = "ASCII frame cut short by the next ':'",
    ["cut_by_end"] = "ASCII frame cut off by the end of the capture",
    ["not_hex_pairs"] = "ASCII frame is not made of hex pairs",
    ["ascii_too_short"] = "ASCII frame too short",
    ["became_protected"] = "became protected",
    ["became_unknown"] = "became non-existent or protected",
    ["readable_again"] = "readable again",
    ["marker_now"] = "16#8000 now",
    ["marker_non_existent"] = "16#8000: non-existent (address not in the map)",
    ["marker_protected"] = "16#8000: protected",
    ["no_bit_set"] = "no bit set",
    ["missing_exception"] = "Missing exception code",
  },
  ["bit_names"] = {
    [0] = "bit 0",
    [1] = "bit 1",
    [2] = "bit 2",
    [3] = "bit 3",
    [4] = "bit 4",
    [5] = "bit 5",
    [6] = "bit 6",
    [7] = "bit 7",
    [8] = "bit 8",
    [9] = "bit 9",
    [10] = "bit 10",
    [11] = "bit 11",
    [12] = "bit 12",
    [13] = "bit 13",
    [14] = "bit 14",
    [15] = "bit 15",
  },
  ["pairing"] = {
    ["echo"] = {
      [8] = 2,
    },
    ["never_answered"] = {
      [8] = {
        [4] = true,
      },
    },
    ["same_shape"] = {
      [5] = true,
      [6] = true,
      [8] = true,
      [20] = true,
      [21] = true,
      [22] = true,
      [65] = true,
      [66] = true,
      [67] = true,
      [68] = true,
      [69] = true,
      [70] = true,
      [71] = true,
      [72] = true,
      [96] = true,
      [97] = true,
      [98] = true,
      [100] = true,
      [101] = true,
      [102] = true,
      [103] = true,
      [104] = true,
      [105] = true,
      [106] = true,
      [107] = true,
      [108] = true,
      [109] = true,
      [110] = true,
      [125] = true,
      [126] = true,
    },
    ["listen_only"] = { 8, 4, 1 },
    ["answer_in_part"] = "answer captured in part in #%s",
  },
  ["user_defined"] = {
    [65] = true,
    [66] = true,
    [67] = true,
    [68] = true,
    [69] = true,
    [70] = true,
    [71] = true,
    [72] = true,
    [100] = true,
    [101] = true,
    [102] = true,
    [103] = true,
    [104] = true,
    [105] = true,
    [106] = true,
    [107] = true,
    [108] = true,
    [109] = true,
    [110] = true,
  },
  ["protocol"] = {
    ["rules"] = {
      [1] = {
        { "fixed", 8 },
        { "counted", 2, 5, 1 },
      },
      [2] = {
        { "fixed", 8 },
        { "counted", 2, 5, 1 },
      },
      [3] = {
        { "fixed", 8 },
        { "counted", 2, 5, 1 },
      },
      [4] = {
        { "fixed", 8 },
        { "counted", 2, 5, 1 },
      },
      [5] = {
        { "fixed", 8 },
        { "fixed", 8 },
      },
      [6] = {
        { "fixed", 8 },
        { "fixed", 8 },
      },
      [7] = {
        { "fixed", 4 },
        { "fixed", 5 },
      },
      [8] = {
        {
          "select",
          2,
          2,
          0,
          { "scan", 6 },
          { "fixed", 8 },
        },
        {
          "select",
          2,
          2,
          0,
          { "scan", 6 },
          { "fixed", 8 },
        },
      },
      [11] = {
        { "fixed", 4 },
        { "fixed", 8 },
      },
      [12] = {
        { "fixed", 4 },
        { "counted", 2, 5, 1 },
      },
      [15] = {
        { "counted", 6, 9, 1 },
        { "fixed", 8 },
        { "by_quantity", 4, 9, 0, 6, 9 },
      },
      [16] = {
        { "counted", 6, 9, 1 },
        { "fixed", 8 },
        { "by_quantity", 4, 9, 2, 6, 9 },
      },
      [17] = {
        { "fixed", 4 },
        { "counted", 2, 5, 1 },
      },
      [20] = {
        { "counted", 2, 5, 1 },
        { "counted", 2, 5, 1 },
      },
      [21] = {
        { "counted", 2, 5, 1 },
        { "counted", 2, 5, 1 },
      },
      [22] = {
        { "fixed", 10 },
        { "fixed", 10 },
      },
      [23] = {
        { "counted", 10, 13, 1 },
        { "counted", 2, 5, 1 },
        { "by_quantity", 8, 13, 2, 10, 13 },
      },
      [24] = {
        { "fixed", 6 },
        { "counted", 2, 6, 2 },
      },
      [43] = {
        {
          "select",
          2,
          1,
          14,
          { "fixed", 7 },
          { "scan", 5 },
        },
        {
          "select",
          2,
          1,
          14,
          { "mei_objects", 7, 8 },
          { "scan", 5 },
        },
      },
      [65] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [66] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [67] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [68] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [69] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [70] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [71] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [72] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [96] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [97] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [98] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [100] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [101] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [102] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [103] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [104] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [105] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [106] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [107] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [108] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [109] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [110] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [125] = {
        { "scan", 4 },
        { "scan", 4 },
      },
      [126] = {
        { "scan", 4 },
        { "scan", 4 },
      },
    },
    ["exception_rule"] = { "fixed", 5 },
    ["counts_nothing"] = {
      ["request"] = {
        [15] = 9,
        [16] = 9,
        [20] = 5,
        [21] = 5,
        [23] = 13,
      },
      ["response"] = {
        [1] = 5,
        [2] = 5,
        [3] = 5,
        [4] = 5,
        [12] = 5,
        [17] = 5,
        [20] = 5,
        [21] = 5,
        [23] = 5,
        [24] = 6,
      },
    },
    ["reads"] = {
      [3] = true,
      [4] = true,
      [23] = true,
    },
    ["plain_reads"] = {
      [3] = true,
      [4] = true,
    },
    ["plausible_reads"] = {
      [1] = { 1, 2000 },
      [2] = { 1, 2000 },
      [3] = { 1, 125 },
      [4] = { 1, 125 },
    },
    ["coil_requests"] = {
      [5] = true,
    },
    ["coil_values"] = {
      [0] = true,
      [65280] = true,
    },
  },
  ["lanes"] = {
    ["run_answers"] = {
      [1] = {
        ["bits"] = true,
        ["extra"] = 5,
        ["unit"] = 0,
      },
      [2] = {
        ["bits"] = true,
        ["extra"] = 5,
        ["unit"] = 0,
      },
      [3] = {
        ["bits"] = false,
        ["extra"] = 5,
        ["unit"] = 2,
      },
      [4] = {
        ["bits"] = false,
        ["extra"] = 5,
        ["unit"] = 2,
      },
      [23] = {
        ["bits"] = false,
        ["extra"] = 5,
        ["unit"] = 2,
      },
    },
    ["header_lengths"] = {
      [15] = 7,
      [16] = 7,
      [23] = 11,
    },
  },
  ["render"] = {
    ["provisional"] = "[provisional]",
    ["provisional_line"] = "Profile: provisional (profile auto has not chosen this slave's device yet: values named with spec semantics only, which its device may name otherwise)",
  },
  ["timing"] = {
    ["default_baud"] = 19200,
    ["rtu_bits"] = 11,
    ["ascii_bits"] = 10,
    ["fixed_above"] = 19200,
    ["fixed_t15"] = 0.00075,
    ["fixed_t35"] = 0.00175,
    ["ascii_max_silence"] = 1.0,
    ["min_baud"] = 50,
    ["max_baud"] = 4000000,
    ["rtu_limit"] = "t1.5 = %.3f ms at %d baud",
    ["ascii_limit"] = "the 1 s ASCII limit",
    ["day_zero_end"] = 86400,
    ["held_record_max"] = 65536,
  },
  ["fields"] = {
    ["fields"] = {
      {
        ["abbr"] = "vw3.item",
        ["ftype"] = "uint32",
        ["title"] = "Item",
        ["help"] = "item number, 1-based, as vw3-decode counts them",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.kind",
        ["ftype"] = "uint8",
        ["title"] = "Kind",
        ["help"] = "request, response, exception or noise",
        ["base"] = "DEC",
        ["values"] = "kind",
      },
      {
        ["abbr"] = "vw3.offset",
        ["ftype"] = "uint32",
        ["title"] = "Stream offset",
        ["help"] = "byte offset of the item in the input, as vw3-decode --json's offset",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.mode",
        ["ftype"] = "string",
        ["title"] = "Mode",
        ["help"] = "rtu or ascii",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.slave",
        ["ftype"] = "uint8",
        ["title"] = "Slave",
        ["help"] = "slave address (0: broadcast)",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.function",
        ["ftype"] = "uint8",
        ["title"] = "Function",
        ["help"] = "function code",
        ["base"] = "DEC",
        ["values"] = "functions",
      },
      {
        ["abbr"] = "vw3.function_name",
        ["ftype"] = "string",
        ["title"] = "Function name",
        ["help"] = "function name",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.crc_ok",
        ["ftype"] = "bool",
        ["title"] = "CRC OK",
        ["help"] = "the CRC/LRC checks",
      },
      {
        ["abbr"] = "vw3.crc",
        ["ftype"] = "uint16",
        ["title"] = "CRC",
        ["help"] = "received check value",
        ["base"] = "HEX",
      },
      {
        ["abbr"] = "vw3.crc_expected",
        ["ftype"] = "uint16",
        ["title"] = "Expected CRC",
        ["help"] = "computed check value",
        ["base"] = "HEX",
      },
      {
        ["abbr"] = "vw3.broadcast",
        ["ftype"] = "bool",
        ["title"] = "Broadcast",
        ["help"] = "a request to slave 0",
      },
      {
        ["abbr"] = "vw3.start",
        ["ftype"] = "uint16",
        ["title"] = "Start address",
        ["help"] = "first address",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.quantity",
        ["ftype"] = "uint16",
        ["title"] = "Quantity",
        ["help"] = "count",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.subfunction",
        ["ftype"] = "uint16",
        ["title"] = "Sub-function",
        ["help"] = "FC8 sub-function",
        ["base"] = "DEC",
        ["values"] = "diagnostics",
      },
      {
        ["abbr"] = "vw3.subfunction_name",
        ["ftype"] = "string",
        ["title"] = "Sub-function name",
        ["help"] = "FC8 sub-function name",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.exception_code",
        ["ftype"] = "uint8",
        ["title"] = "Exception code",
        ["help"] = "exception code",
        ["base"] = "DEC",
        ["values"] = "exceptions",
      },
      {
        ["abbr"] = "vw3.exception_name",
        ["ftype"] = "string",
        ["title"] = "Exception name",
        ["help"] = "the spec's exception name",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.request_frame",
        ["ftype"] = "framenum",
        ["title"] = "Request in frame",
        ["help"] = "the request a response answers",
        ["base"] = "NONE",
        ["values"] = "request",
      },
      {
        ["abbr"] = "vw3.response_frame",
        ["ftype"] = "framenum",
        ["title"] = "Response in frame",
        ["help"] = "the response that answered a request",
        ["base"] = "NONE",
        ["values"] = "response",
      },
      {
        ["abbr"] = "vw3.response_time",
        ["ftype"] = "relative_time",
        ["title"] = "Time since request",
        ["help"] = "seconds after the request",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.unanswered",
        ["ftype"] = "bool",
        ["title"] = "Unanswered",
        ["help"] = "a request no response came to",
      },
      {
        ["abbr"] = "vw3.noise.reason",
        ["ftype"] = "string",
        ["title"] = "Why noise",
        ["help"] = "why noise is no frame",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.warning",
        ["ftype"] = "string",
        ["title"] = "Warning",
        ["help"] = "warnings: outside the spec or the device profile",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.note",
        ["ftype"] = "string",
        ["title"] = "Note",
        ["help"] = "notes on the frame",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.exception_meaning",
        ["ftype"] = "string",
        ["title"] = "Exception meaning on this device",
        ["help"] = "what it means on the device",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.span_label",
        ["ftype"] = "string",
        ["title"] = "Addresses as shown",
        ["help"] = "the addresses as shown (PLC style)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.write_span_label",
        ["ftype"] = "string",
        ["title"] = "Written addresses as shown",
        ["help"] = "the addresses written as shown (PLC style: FC23's written window)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.profile",
        ["ftype"] = "string",
        ["title"] = "Device profile",
        ["help"] = "the device profile the frame is annotated with",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.profile_reason",
        ["ftype"] = "string",
        ["title"] = "Why this profile",
        ["help"] = "profile auto: the evidence that gave the slave its device profile",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.provisional",
        ["ftype"] = "bool",
        ["title"] = "Provisional",
        ["help"] = "read before profile auto chose the slave's device (one pass: live, stdin): values named with spec semantics only",
        ["base"] = "NONE",
      },
      {
        ["abbr"] = "vw3.profile_choice",
        ["ftype"] = "string",
        ["title"] = "Profile chosen",
        ["help"] = "profile auto: why this frame decides the slave's profile",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg",
        ["ftype"] = "none",
        ["title"] = "Register",
        ["help"] = "register values (presence)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.bit",
        ["ftype"] = "none",
        ["title"] = "Bit",
        ["help"] = "coils and inputs (presence)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.bit.address",
        ["ftype"] = "uint16",
        ["title"] = "Address",
        ["help"] = "coil or input address",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.bit.value",
        ["ftype"] = "uint8",
        ["title"] = "Value",
        ["help"] = "coil or input value",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.object",
        ["ftype"] = "none",
        ["title"] = "Object",
        ["help"] = "FC43 objects (presence)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.object.id",
        ["ftype"] = "uint8",
        ["title"] = "Object id",
        ["help"] = "FC43 object id",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.object.name",
        ["ftype"] = "string",
        ["title"] = "Name",
        ["help"] = "FC43 object name",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.object.value",
        ["ftype"] = "string",
        ["title"] = "Value",
        ["help"] = "FC43 object value",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.object.text",
        ["ftype"] = "string",
        ["title"] = "Meaning",
        ["help"] = "the object value's meaning on the device",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.data",
        ["ftype"] = "bytes",
        ["title"] = "Data",
        ["help"] = "noise: the bytes outside any frame; a PDU's data (FC8, FC43's other MEI types, a function without a layout)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.byte_count",
        ["ftype"] = "uint16",
        ["title"] = "Byte count",
        ["help"] = "the PDU's byte count",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.server_id",
        ["ftype"] = "uint8",
        ["title"] = "Server id",
        ["help"] = "FC17 server id",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.run_indicator",
        ["ftype"] = "uint8",
        ["title"] = "Run indicator",
        ["help"] = "FC17 run indicator",
        ["base"] = "HEX",
        ["values"] = "run_indicator",
      },
      {
        ["abbr"] = "vw3.additional_data",
        ["ftype"] = "string",
        ["title"] = "Additional data",
        ["help"] = "FC17 additional data, as text",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.additional_bytes",
        ["ftype"] = "bytes",
        ["title"] = "Additional data",
        ["help"] = "FC17 additional data",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.continued_in",
        ["ftype"] = "framenum",
        ["title"] = "Continued in record",
        ["help"] = "the later record that shows the frame these bytes begin",
      },
      {
        ["abbr"] = "vw3.reg.address",
        ["ftype"] = "uint16",
        ["title"] = "Address",
        ["help"] = "register address on the wire",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.reg.value",
        ["ftype"] = "uint16",
        ["title"] = "Value",
        ["help"] = "register value",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.reg.code",
        ["ftype"] = "string",
        ["title"] = "Code",
        ["help"] = "parameter code",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg.name",
        ["ftype"] = "string",
        ["title"] = "Name",
        ["help"] = "parameter name",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg.unit",
        ["ftype"] = "string",
        ["title"] = "Unit",
        ["help"] = "unit",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg.scaled",
        ["ftype"] = "double",
        ["title"] = "Scaled value",
        ["help"] = "scaled value",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg.text",
        ["ftype"] = "string",
        ["title"] = "Meaning",
        ["help"] = "the value's text",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg.status",
        ["ftype"] = "string",
        ["title"] = "Status",
        ["help"] = "ok, protected, non-existent or ambiguous",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg.source",
        ["ftype"] = "string",
        ["title"] = "Source",
        ["help"] = "where the map row comes from",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg.label",
        ["ftype"] = "string",
        ["title"] = "Address as shown",
        ["help"] = "the address as shown (PLC style)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.reg.words",
        ["ftype"] = "uint8",
        ["title"] = "Words of a 32-bit value",
        ["help"] = "words of a 32-bit value: 2 on its first register (read with the next), 0 on that next; absent: 1",
        ["base"] = "DEC",
        ["values"] = {
          [0] = "second word (the value is read on the register before)",
          [2] = "this register and the next",
        },
      },
      {
        ["abbr"] = "vw3.status",
        ["ftype"] = "uint8",
        ["title"] = "Status",
        ["help"] = "FC7's exception status, eight bits",
        ["name"] = "exception_status",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.status",
        ["ftype"] = "uint16",
        ["title"] = "Status",
        ["help"] = "FC11's and FC12's status word",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.bit_status",
        ["ftype"] = "bytes",
        ["title"] = "Status",
        ["help"] = "the coils or inputs as sent, eight a byte (FC1, FC2, FC15)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.value",
        ["ftype"] = "uint16",
        ["title"] = "Value",
        ["help"] = "FC5's and FC6's value as sent",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.event_count",
        ["ftype"] = "uint16",
        ["title"] = "Event count",
        ["help"] = "FC11's and FC12's event count",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.message_count",
        ["ftype"] = "uint16",
        ["title"] = "Message count",
        ["help"] = "FC12's message count",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.events",
        ["ftype"] = "bytes",
        ["title"] = "Events",
        ["help"] = "FC12's events, newest first",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.and_mask",
        ["ftype"] = "uint16",
        ["title"] = "AND mask",
        ["help"] = "FC22's AND mask",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.or_mask",
        ["ftype"] = "uint16",
        ["title"] = "OR mask",
        ["help"] = "FC22's OR mask",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.write_start",
        ["ftype"] = "uint16",
        ["title"] = "Write start",
        ["help"] = "FC23's first address written",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.write_quantity",
        ["ftype"] = "uint16",
        ["title"] = "Write quantity",
        ["help"] = "FC23's registers written",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.odd_byte",
        ["ftype"] = "uint8",
        ["title"] = "Odd byte",
        ["help"] = "the byte after the words of an odd byte count",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.fifo_count",
        ["ftype"] = "uint16",
        ["title"] = "FIFO count",
        ["help"] = "FC24's count of values in the FIFO",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.fifo_value",
        ["ftype"] = "uint16",
        ["title"] = "FIFO value",
        ["help"] = "FC24's values, the FIFO's first first",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.file.subrequest",
        ["ftype"] = "none",
        ["title"] = "Sub-request",
        ["help"] = "FC20's sub-request (presence)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.file.subresponse",
        ["ftype"] = "none",
        ["title"] = "Sub-response",
        ["help"] = "FC20's sub-response (presence)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.file.write",
        ["ftype"] = "none",
        ["title"] = "Record written",
        ["help"] = "FC21's record written (presence)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.file.reference_type",
        ["ftype"] = "uint8",
        ["title"] = "Reference type",
        ["help"] = "FC20's and FC21's reference type (6)",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.file.number",
        ["ftype"] = "uint16",
        ["title"] = "File",
        ["help"] = "FC20's and FC21's file number",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.file.record",
        ["ftype"] = "uint16",
        ["title"] = "Record",
        ["help"] = "FC20's and FC21's record number",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.file.length",
        ["ftype"] = "uint16",
        ["title"] = "Length",
        ["help"] = "FC20's and FC21's length: of the record in words, of a sub-response in bytes",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.file.value",
        ["ftype"] = "uint16",
        ["title"] = "Value",
        ["help"] = "FC20's and FC21's record words",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.mei_type",
        ["ftype"] = "uint8",
        ["title"] = "MEI type",
        ["help"] = "FC43's MEI type",
        ["base"] = "DEC",
        ["values"] = "mei_types",
      },
      {
        ["abbr"] = "vw3.mei.read_code",
        ["ftype"] = "uint8",
        ["title"] = "Read code",
        ["help"] = "FC43/14's read device id code",
        ["base"] = "DEC",
        ["values"] = "device_id_codes",
      },
      {
        ["abbr"] = "vw3.mei.object_id",
        ["ftype"] = "uint8",
        ["title"] = "Object id",
        ["help"] = "FC43/14's first object asked",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.mei.conformity",
        ["ftype"] = "uint8",
        ["title"] = "Conformity",
        ["help"] = "FC43/14's conformity level",
        ["base"] = "DEC_HEX",
        ["values"] = "device_id_conformity",
      },
      {
        ["abbr"] = "vw3.mei.more_follows",
        ["ftype"] = "uint8",
        ["title"] = "More follows",
        ["help"] = "FC43/14: more objects follow (0xFF) or not (0)",
        ["base"] = "DEC_HEX",
      },
      {
        ["abbr"] = "vw3.mei.next_object_id",
        ["ftype"] = "uint8",
        ["title"] = "Next object id",
        ["help"] = "FC43/14's next object id",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.mei.object_count",
        ["ftype"] = "uint8",
        ["title"] = "Object count",
        ["help"] = "FC43/14's number of objects",
        ["base"] = "DEC",
      },
      {
        ["abbr"] = "vw3.trailing",
        ["ftype"] = "bytes",
        ["title"] = "Trailing",
        ["help"] = "bytes after the PDU's data (vw3-decode's fields.trailing; warned: unexpected bytes after the data)",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.server_id_text",
        ["ftype"] = "string",
        ["title"] = "Server id",
        ["help"] = "FC17 server id longer than one byte, as text",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.server_id_bytes",
        ["ftype"] = "bytes",
        ["title"] = "Server id",
        ["help"] = "FC17 server id longer than one byte",
        ["plain"] = true,
      },
      {
        ["abbr"] = "vw3.event_list",
        ["ftype"] = "uint8",
        ["title"] = "Event",
        ["help"] = "PDU key of function 12",
        ["base"] = "DEC",
      },
    },
    ["experts"] = {
      {
        ["name"] = "crc_bad",
        ["filter"] = "vw3.expert.crc_bad",
        ["title"] = "Bad CRC",
        ["group"] = "CHECKSUM",
        ["severity"] = "ERROR",
      },
      {
        ["name"] = "exception",
        ["filter"] = "vw3.expert.exception",
        ["title"] = "Exception response",
        ["group"] = "RESPONSE_CODE",
        ["severity"] = "NOTE",
      },
      {
        ["name"] = "unanswered",
        ["filter"] = "vw3.expert.unanswered",
        ["title"] = "Request not answered",
        ["group"] = "SEQUENCE",
        ["severity"] = "WARN",
      },
      {
        ["name"] = "no_request",
        ["filter"] = "vw3.expert.no_request",
        ["title"] = "Response without a matching request",
        ["group"] = "SEQUENCE",
        ["severity"] = "WARN",
      },
      {
        ["name"] = "warning",
        ["filter"] = "vw3.expert.warning",
        ["title"] = "Outside the spec or the device profile",
        ["group"] = "PROTOCOL",
        ["severity"] = "WARN",
      },
      {
        ["name"] = "malformed",
        ["filter"] = "vw3.expert.malformed",
        ["title"] = "PDU does not fit its layout",
        ["group"] = "MALFORMED",
        ["severity"] = "ERROR",
      },
      {
        ["name"] = "protected",
        ["filter"] = "vw3.expert.protected",
        ["title"] = "Protected or non-existent parameter",
        ["group"] = "RESPONSE_CODE",
        ["severity"] = "WARN",
      },
      {
        ["name"] = "note",
        ["filter"] = "vw3.expert.note",
        ["title"] = "Note",
        ["group"] = "COMMENTS_GROUP",
        ["severity"] = "NOTE",
      },
      {
        ["name"] = "noise",
        ["filter"] = "vw3.expert.noise",
        ["title"] = "Bytes outside any frame",
        ["group"] = "MALFORMED",
        ["severity"] = "WARN",
      },
      {
        ["name"] = "multiple",
        ["filter"] = "vw3.expert.record.multiple",
        ["title"] = "Several frames in one record",
        ["group"] = "REASSEMBLE",
        ["severity"] = "NOTE",
      },
      {
        ["name"] = "partial",
        ["filter"] = "vw3.expert.record.partial",
        ["title"] = "Record ends inside a frame",
        ["group"] = "REASSEMBLE",
        ["severity"] = "NOTE",
      },
      {
        ["name"] = "preference",
        ["filter"] = "vw3.expert.preference",
        ["title"] = "Preference not understood",
        ["group"] = "PROTOCOL",
        ["severity"] = "WARN",
      },
      {
        ["name"] = "internal",
        ["filter"] = "vw3.expert.internal",
        ["title"] = "Plugin error (please report it)",
        ["group"] = "UNDECODED",
        ["severity"] = "ERROR",
      },
      {
        ["name"] = "profile",
        ["filter"] = "vw3.expert.profile",
        ["title"] = "Device profile chosen (profile auto)",
        ["group"] = "COMMENTS_GROUP",
        ["severity"] = "CHAT",
      },
    },
    ["preferences"] = {
      {
        ["name"] = "profiles",
        ["type"] = "string",
        ["title"] = "Device profiles",
        ["default"] = "",
        ["help"] = "Profile per slave, e.g. '12=atv71,3=sel749m'; a name alone sets the default for every other slave",
      },
      {
        ["name"] = "maps",
        ["type"] = "string",
        ["title"] = "Register maps",
        ["default"] = "",
        ["help"] = "CSV register maps as vw3-decode --map takes them, separated by ';': FILE (every slave), 12=FILE (one slave) or sel749m=FILE (the slaves of a profile)",
      },
      {
        ["name"] = "address_style",
        ["type"] = "enum",
        ["title"] = "Register address style",
        ["choices"] = { "profile", "protocol", "plc" },
        ["help"] = "profile: as the device profile says; protocol: as sent (8401); plc: 4X references (48402). The vw3.reg.address field is always the address on the wire; vw3.reg.label is the one shown.",
      },
      {
        ["name"] = "mode",
        ["type"] = "enum",
        ["title"] = "Framing mode",
        ["choices"] = { "auto", "rtu", "ascii" },
        ["help"] = "auto: from the stream's first 64 bytes, across records, as vw3-decode tells it; rtu or ascii: forced, as vw3-decode --mode",
      },
      {
        ["name"] = "timeout_ms",
        ["type"] = "uint",
        ["title"] = "Response timeout (ms)",
        ["default"] = 1000,
        ["help"] = "Flag responses later than this after their request, as vw3-decode --timeout does (0: off)",
      },
      {
        ["name"] = "baud",
        ["type"] = "uint",
        ["title"] = "Line speed (baud)",
        ["default"] = 19200,
        ["help"] = "The serial line's speed, as vw3-decode --baud (50..4000000; another value: 19200, its default): a silence of t3.5 at this speed before a record ends a run of noise (RTU)",
      },
      {
        ["name"] = "tcp_port",
        ["type"] = "uint",
        ["title"] = "RTU over TCP port",
        ["default"] = 0,
        ["help"] = "TCP port of a serial gateway carrying raw RTU frames (0: off)",
      },
      {
        ["name"] = "udp_port",
        ["type"] = "uint",
        ["title"] = "RTU over UDP port",
        ["default"] = 0,
        ["help"] = "UDP port of a serial gateway sending raw RTU frames (0: off)",
      },
      {
        ["name"] = "quick_lanes",
        ["type"] = "bool",
        ["title"] = "Quick lanes",
        ["default"] = true,
        ["help"] = "Take the usual polling records (a known request, its usual answer, a setpoint write) by a shorter path that gives the same dissection; off: every record by the general path",
      },
      {
        ["name"] = "user0",
        ["type"] = "bool",
        ["title"] = "Decode linktype 147 (USER0)",
        ["default"] = false,
        ["help"] = "Decode every USER0 record as VW3 without a DLT_USER entry (which is the usual way: Preferences > Protocols > DLT_USER, payload protocol vw3)",
      },
    },
    ["parameters"] = {
      {
        ["profile"] = "atv71",
        ["address"] = 3015,
        ["abbr"] = "vw3.atv71.bfr",
        ["title"] = "Standard motor frequency (BFR)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3102,
        ["abbr"] = "vw3.atv71.sfr",
        ["title"] = "Switching frequency (SFR), kHz",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3103,
        ["abbr"] = "vw3.atv71.tfr",
        ["title"] = "Maximum output frequency (TFR), Hz",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3104,
        ["abbr"] = "vw3.atv71.hsp",
        ["title"] = "High speed (HSP), Hz",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3105,
        ["abbr"] = "vw3.atv71.lsp",
        ["title"] = "Low speed (LSP), Hz",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3201,
        ["abbr"] = "vw3.atv71.eta",
        ["title"] = "Status word (ETA)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3202,
        ["abbr"] = "vw3.atv71.rfr",
        ["title"] = "Output frequency (RFR), Hz",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3203,
        ["abbr"] = "vw3.atv71.frh",
        ["title"] = "Frequency reference before ramp (FRH), Hz",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3204,
        ["abbr"] = "vw3.atv71.lcr",
        ["title"] = "Motor current (LCR), A",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3205,
        ["abbr"] = "vw3.atv71.otr",
        ["title"] = "Motor torque (OTR), %",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3206,
        ["abbr"] = "vw3.atv71.eti",
        ["title"] = "Extended status word (ETI)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3207,
        ["abbr"] = "vw3.atv71.uln",
        ["title"] = "Mains voltage (ULN), V",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3208,
        ["abbr"] = "vw3.atv71.uop",
        ["title"] = "Motor voltage (UOP), V",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3209,
        ["abbr"] = "vw3.atv71.thd",
        ["title"] = "Drive thermal state (THD), %",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 3211,
        ["abbr"] = "vw3.atv71.opr",
        ["title"] = "Motor power (OPR), %",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 6001,
        ["abbr"] = "vw3.atv71.add",
        ["title"] = "Modbus address (drive port) (ADD)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 6003,
        ["abbr"] = "vw3.atv71.tbr",
        ["title"] = "Modbus baud rate (TBR)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 6004,
        ["abbr"] = "vw3.atv71.tfo",
        ["title"] = "Modbus format (TFO)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 6005,
        ["abbr"] = "vw3.atv71.tto",
        ["title"] = "Modbus time-out (TTO), s",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 7121,
        ["abbr"] = "vw3.atv71.lft",
        ["title"] = "Last fault (LFT)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8401,
        ["abbr"] = "vw3.atv71.chcf",
        ["title"] = "Profile (CHCF)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8402,
        ["abbr"] = "vw3.atv71.cop",
        ["title"] = "Copy channel 1 <> 2 (COP)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8413,
        ["abbr"] = "vw3.atv71.fr1",
        ["title"] = "Ref.1 channel (FR1)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8423,
        ["abbr"] = "vw3.atv71.cd1",
        ["title"] = "Cmd channel 1 (CD1)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8501,
        ["abbr"] = "vw3.atv71.cmd",
        ["title"] = "Control word (CMD)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8502,
        ["abbr"] = "vw3.atv71.lfr",
        ["title"] = "Frequency reference (LFR), Hz",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8503,
        ["abbr"] = "vw3.atv71.pisp",
        ["title"] = "PID setpoint (PISP)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8504,
        ["abbr"] = "vw3.atv71.cmi",
        ["title"] = "Extended control word (CMI)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8602,
        ["abbr"] = "vw3.atv71.lfrd",
        ["title"] = "Speed reference (LFRD), rpm",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8603,
        ["abbr"] = "vw3.atv71.etad",
        ["title"] = "DRIVECOM status word (ETAD)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8604,
        ["abbr"] = "vw3.atv71.rfrd",
        ["title"] = "Output speed (RFRD), rpm",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8605,
        ["abbr"] = "vw3.atv71.frhd",
        ["title"] = "Speed reference before ramp (FRHD), rpm",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 8606,
        ["abbr"] = "vw3.atv71.errd",
        ["title"] = "CiA402 fault code (ERRD)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 9001,
        ["abbr"] = "vw3.atv71.acc",
        ["title"] = "Acceleration (ACC), s",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 9002,
        ["abbr"] = "vw3.atv71.dec",
        ["title"] = "Deceleration (DEC), s",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 9630,
        ["abbr"] = "vw3.atv71.thr",
        ["title"] = "Motor thermal state (THR), %",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12741,
        ["abbr"] = "vw3.atv71.nm1",
        ["title"] = "Com scanner input 1 value (default ETA) (NM1)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12742,
        ["abbr"] = "vw3.atv71.nm2",
        ["title"] = "Com scanner input 2 value (default RFRD) (NM2)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12743,
        ["abbr"] = "vw3.atv71.nm3",
        ["title"] = "Com scanner input 3 value (NM3)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12744,
        ["abbr"] = "vw3.atv71.nm4",
        ["title"] = "Com scanner input 4 value (NM4)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12745,
        ["abbr"] = "vw3.atv71.nm5",
        ["title"] = "Com scanner input 5 value (NM5)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12746,
        ["abbr"] = "vw3.atv71.nm6",
        ["title"] = "Com scanner input 6 value (NM6)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12747,
        ["abbr"] = "vw3.atv71.nm7",
        ["title"] = "Com scanner input 7 value (NM7)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12748,
        ["abbr"] = "vw3.atv71.nm8",
        ["title"] = "Com scanner input 8 value (NM8)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12761,
        ["abbr"] = "vw3.atv71.nc1",
        ["title"] = "Com scanner output 1 value (default CMD) (NC1)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12762,
        ["abbr"] = "vw3.atv71.nc2",
        ["title"] = "Com scanner output 2 value (default LFRD) (NC2)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12763,
        ["abbr"] = "vw3.atv71.nc3",
        ["title"] = "Com scanner output 3 value (NC3)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12764,
        ["abbr"] = "vw3.atv71.nc4",
        ["title"] = "Com scanner output 4 value (NC4)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12765,
        ["abbr"] = "vw3.atv71.nc5",
        ["title"] = "Com scanner output 5 value (NC5)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12766,
        ["abbr"] = "vw3.atv71.nc6",
        ["title"] = "Com scanner output 6 value (NC6)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12767,
        ["abbr"] = "vw3.atv71.nc7",
        ["title"] = "Com scanner output 7 value (NC7)",
      },
      {
        ["profile"] = "atv71",
        ["address"] = 12768,
        ["abbr"] = "vw3.atv71.nc8",
        ["title"] = "Com scanner output 8 value (NC8)",
      },
    },
    ["names"] = {
      ["mei_types"] = {
        [13] = "CANopen General Reference",
        [14] = "Read Device Identification",
      },
      ["device_id_codes"] = {
        [1] = "basic",
        [2] = "regular",
        [3] = "extended",
        [4] = "individual",
      },
    },
    ["start_words"] = {
      [24] = {
        ["title"] = "FIFO pointer address",
      },
    },
    ["info"] = {
      ["forms"] = {
        ["request"] = {
          [5] = "coil",
          [6] = "single",
          [8] = "diagnostics",
          [17] = "report_server_id",
          [20] = "file_record",
          [21] = "file_record",
          [22] = "mask",
          [23] = "read_write",
          [24] = "pointer",
          [43] = "mei",
        },
        ["response"] = {
          [5] = "coil",
          [6] = "single",
          [7] = "status",
          [8] = "diagnostics",
          [11] = "counter",
          [12] = "event_log",
          [15] = "written",
          [16] = "written",
          [17] = "report_server_id",
          [20] = "file_record",
          [21] = "file_record",
          [22] = "mask",
          [24] = "fifo",
          [43] = "mei",
        },
      },
      ["steps"] = {
        ["coil"] = {
          { "label" },
          { "coil", "value" },
        },
        ["single"] = {
          { "label" },
          { "single", "value" },
        },
        ["status"] = {
          "status 0x",
          { "hex", "status", 2 },
        },
        ["diagnostics"] = {
          { "hex", "subfunction", 2 },
          "h ",
          { "subfunction", "subfunction" },
          { "data", "data" },
        },
        ["counter"] = {
          "status 0x",
          { "hex", "status", 4 },
          ", ",
          { "count", "event_count", "event" },
        },
        ["event_log"] = {
          "status 0x",
          { "hex", "status", 4 },
          ", ",
          { "count", "event_count", "event" },
          ", ",
          { "count", "message_count", "message" },
        },
        ["written"] = {
          { "span" },
          " written",
        },
        ["report_server_id"] = "report_server_id",
        ["file_record"] = "file_record",
        ["mask"] = {
          { "dec", "address" },
          " AND 0x",
          { "hex", "and_mask", 4 },
          " OR 0x",
          { "hex", "or_mask", 4 },
        },
        ["read_write"] = {
          "read ",
          { "plain_span" },
          ", write ",
          { "write", "write_start", "write_quantity" },
        },
        ["fifo"] = {
          { "count", "fifo_count", "value" },
          { "fifo", "fifo_count", "values" },
        },
        ["pointer"] = {
          "pointer ",
          { "dec", "address" },
        },
        ["mei"] = "mei",
      },
      ["max_data_bytes"] = 16,
      ["max_fifo_values"] = 8,
      ["unknown_subfunction"] = "unknown sub-function",
    },
  },
  ["profiles"] = {
    ["atv71"] = {
      ["name"] = "atv71",
      ["title"] = "Altivar 71 (VW3 A3 303 Modbus card)",
      ["device"] = "VW3 A3 303",
      ["address_style"] = "protocol",
      ["one_table"] = true,
      ["functions"] = {
        [3] = true,
        [4] = true,
        [6] = true,
        [8] = true,
        [11] = true,
        [16] = true,
        [23] = true,
        [43] = true,
      },
      ["inner_only"] = {},
      ["broadcast"] = {
        [6] = true,
        [16] = true,
      },
      ["broadcast_allowed"] = "6, 16",
      ["protected_value"] = 32768,
      ["all_protected_exception"] = 2,
      ["all_protected_read"] = "address does not exist (also: every parameter read is non-existent or protected)",
      ["limits"] = {
        [3] = { 63 },
        [4] = { 63 },
        [16] = { 61 },
        [23] = { 20, 20 },
      },
      ["exceptions"] = {
        [1] = "function not recognized",
        [2] = "address does not exist",
        [3] = "value not permitted",
        [4] = "execution started but could not be completed",
        [6] = "write refused: the drive is in Forced local mode",
        [7] = "write refused: the motor is running (configuration parameter)",
      },
      ["documented"] = "01, 02, 03, 04, 06, 07",
      ["exception_causes"] = {
        [771] = {
          {
            ["text"] = "quantity beyond the card's limit",
            ["when"] = "quantity",
            ["counters"] = {},
          },
          {
            ["text"] = "value not permitted",
            ["when"] = nil,
            ["counters"] = {},
          },
        },
        [1027] = {
          {
            ["text"] = "quantity beyond the card's limit",
            ["when"] = "quantity",
            ["counters"] = {},
          },
          {
            ["text"] = "value not permitted",
            ["when"] = nil,
            ["counters"] = {},
          },
        },
        [4099] = {
          {
            ["text"] = "quantity beyond the card's limit",
            ["when"] = "quantity",
            ["counters"] = {},
          },
          {
            ["text"] = "value not permitted",
            ["when"] = nil,
            ["counters"] = {},
          },
        },
        [5891] = {
          {
            ["text"] = "quantity beyond the card's limit",
            ["when"] = "quantity",
            ["counters"] = {},
          },
          {
            ["text"] = "value not permitted",
            ["when"] = nil,
            ["counters"] = {},
          },
        },
      },
      ["diagnostics"] = {
        [15] = "broadcast messages received (the spec's 0F counts requests not answered)",
        [16] = "NAK count (always 0 on this card)",
        [17] = "slave-busy count (always 0 on this card)",
      },
      ["subfunctions"] = {
        [0] = true,
        [1] = true,
        [3] = true,
        [4] = true,
        [10] = true,
        [11] = true,
        [12] = true,
        [13] = true,
        [14] = true,
        [15] = true,
        [16] = true,
        [17] = true,
        [18] = true,
      },
      ["diagnostic_constants"] = {
        [16] = 0,
        [17] = 0,
      },
      ["objects"] = {
        [0] = {
          ["meaning"] = "manufacturer name",
          ["format"] = nil,
          ["max_length"] = nil,
        },
        [1] = {
          ["meaning"] = "device catalog number",
          ["format"] = nil,
          ["max_length"] = nil,
        },
        [2] = {
          ["meaning"] = "device version",
          ["format"] = "MMmm",
          ["max_length"] = nil,
        },
        [6] = {
          ["meaning"] = "device name ([DEVICE NAME], 7.1 USER PARAMETERS, up to 16 bytes)",
          ["format"] = nil,
          ["max_length"] = 16,
        },
      },
      ["function_names"] = {},
      ["plc_base"] = {
        [1] = 1,
        [2] = 10001,
        [4] = 30001,
        [5] = 1,
        [15] = 1,
      },
      ["plc_base_default"] = 40001,
      ["bits_depend"] = {
        {
          ["registers"] = { 8501 },
          ["on"] = 8401,
          ["plain_when"] = {
            [3] = true,
          },
          ["reason"] = "CHCF = 3 (I/O profile): CMD bits are assigned by configuration",
        },
      },
      ["map"] = {
        [3015] = {
          ["code"] = "BFR",
          ["name"] = "Standard motor frequency",
          ["source"] = "F",
        },
        [3102] = {
          ["code"] = "SFR",
          ["name"] = "Switching frequency",
          ["unit"] = "kHz",
          ["scale"] = 0.1,
          ["source"] = "A",
          ["decimals"] = 1,
        },
        [3103] = {
          ["code"] = "TFR",
          ["name"] = "Maximum output frequency",
          ["unit"] = "Hz",
          ["scale"] = 0.1,
          ["source"] = "A",
          ["decimals"] = 1,
        },
        [3104] = {
          ["code"] = "HSP",
          ["name"] = "High speed",
          ["unit"] = "Hz",
          ["scale"] = 0.1,
          ["source"] = "A",
          ["decimals"] = 1,
        },
        [3105] = {
          ["code"] = "LSP",
          ["name"] = "Low speed",
          ["unit"] = "Hz",
          ["scale"] = 0.1,
          ["source"] = "A",
          ["decimals"] = 1,
        },
        [3201] = {
          ["code"] = "ETA",
          ["name"] = "Status word",
          ["source"] = "AC",
          ["bits"] = {
            [0] = "Ready to switch on",
            [1] = "Switched on",
            [2] = "Operation enabled",
            [3] = "Fault",
            [4] = "Voltage enabled",
            [5] = "Quick stop inactive",
            [6] = "Switch on disabled",
            [7] = "Warning",
            [9] = "Remote",
            [10] = "Target reached",
            [11] = "Internal limit active",
            [14] = "Stop via STOP key",
            [15] = "Direction of rotation",
          },
          ["ambiguous_8000"] = true,
          ["read_only"] = true,
        },
        [3202] = {
          ["code"] = "RFR",
          ["name"] = "Output frequency",
          ["unit"] = "Hz",
          ["scale"] = 0.1,
          ["source"] = "FB",
          ["signed"] = true,
          ["decimals"] = 1,
          ["ambiguous_8000"] = true,
          ["read_only"] = true,
        },
        [3203] = {
          ["code"] = "FRH",
          ["name"] = "Frequency reference before ramp",
          ["unit"] = "Hz",
          ["scale"] = 0.1,
          ["source"] = "FB",
          ["signed"] = true,
          ["decimals"] = 1,
          ["ambiguous_8000"] = true,
          ["read_only"] = true,
        },
        [3204] = {
          ["code"] = "LCR",
          ["name"] = "Motor current",
          ["unit"] = "A",
          ["scale"] = 0.1,
          ["source"] = "F",
          ["decimals"] = 1,
          ["read_only"] = true,
        },
        [3205] = {
          ["code"] = "OTR",
          ["name"] = "Motor torque",
          ["unit"] = "%",
          ["scale"] = 1.0,
          ["source"] = "FB",
          ["signed"] = true,
          ["ambiguous_8000"] = true,
          ["read_only"] = true,
        },
        [3206] = {
          ["code"] = "ETI",
          ["name"] = "Extended status word",
          ["source"] = "F",
          ["read_only"] = true,
        },
        [3207] = {
          ["code"] = "ULN",
          ["name"] = "Mains voltage",
          ["unit"] = "V",
          ["scale"] = 0.1,
          ["source"] = "F",
          ["decimals"] = 1,
          ["read_only"] = true,
        },
        [3208] = {
          ["code"] = "UOP",
          ["name"] = "Motor voltage",
          ["unit"] = "V",
          ["scale"] = 1.0,
          ["source"] = "F",
          ["read_only"] = true,
        },
        [3209] = {
          ["code"] = "THD",
          ["name"] = "Drive thermal state",
          ["unit"] = "%",
          ["scale"] = 1.0,
          ["source"] = "F",
          ["read_only"] = true,
        },
        [3211] = {
          ["code"] = "OPR",
          ["name"] = "Motor power",
          ["unit"] = "%",
          ["scale"] = 1.0,
          ["source"] = "FB",
          ["signed"] = true,
          ["ambiguous_8000"] = true,
          ["read_only"] = true,
        },
        [6001] = {
          ["code"] = "ADD",
          ["name"] = "Modbus address (drive port)",
          ["source"] = "F",
        },
        [6003] = {
          ["code"] = "TBR",
          ["name"] = "Modbus baud rate",
          ["source"] = "F",
          ["enum"] = {
            [24] = "4800",
            [28] = "9600",
            [32] = "19200",
            [36] = "38400",
          },
        },
        [6004] = {
          ["code"] = "TFO",
          ["name"] = "Modbus format",
          ["source"] = "F",
          ["enum"] = {
            [2] = "8O1",
            [3] = "8E1",
            [4] = "8N1",
            [5] = "8N2",
          },
        },
        [6005] = {
          ["code"] = "TTO",
          ["name"] = "Modbus time-out",
          ["unit"] = "s",
          ["scale"] = 0.1,
          ["source"] = "F",
          ["decimals"] = 1,
        },
        [7121] = {
          ["code"] = "LFT",
          ["name"] = "Last fault",
          ["source"] = "F",
          ["enum"] = {
            [0] = "nOF",
            [1] = "InF",
            [2] = "EEF",
            [3] = "CFF",
            [4] = "CFI",
            [5] = "SLF1",
            [6] = "ILF",
            [7] = "CnF",
            [8] = "EPF1",
            [9] = "OCF",
            [10] = "CrF",
            [11] = "SPF",
            [12] = "AnF",
            [13] = "LFF2",
            [14] = "PtF1",
            [15] = "OtF1",
            [16] = "OHF",
            [17] = "OLF",
            [18] = "ObF",
            [19] = "OSF",
            [20] = "OPF1",
            [21] = "PHF",
            [22] = "USF",
            [23] = "SCF1",
            [24] = "SOF",
            [25] = "tnF",
            [26] = "InF1",
            [27] = "InF2",
            [28] = "InF3",
            [29] = "InF4",
            [30] = "EEF2",
            [31] = "SCF2",
            [32] = "SCF3",
            [33] = "OPF2",
            [34] = "COF",
            [35] = "bLF",
            [37] = "InF7",
            [38] = "EPF2",
            [39] = "APF",
            [40] = "InF8",
            [41] = "brF",
            [42] = "SLF2",
            [43] = "ECF",
            [44] = "SSF",
            [45] = "SLF3",
            [46] = "PrF",
            [47] = "PtF2",
            [48] = "OtF2",
            [49] = "PtFL",
            [50] = "OtFL",
            [51] = "InF9",
            [52] = "InFA",
            [53] = "InFb",
            [54] = "tJF",
            [55] = "SCF4",
            [56] = "SCF5",
            [57] = "SrF",
            [58] = "FCF1",
            [59] = "FCF2",
            [60] = "InFC",
            [61] = "AI2F",
            [62] = "EnF",
            [63] = "CrF2",
            [64] = "LCF",
            [65] = "bUF",
            [66] = "dCF",
            [67] = "HdF",
            [68] = "InF6",
            [69] = "InFE",
            [70] = "bOF",
            [71] = "LFF3",
            [72] = "LFF4",
            [73] = "HCF",
            [76] = "dLF",
            [99] = "CSF",
          },
          ["read_only"] = true,
        },
        [8401] = {
          ["code"] = "CHCF",
          ["name"] = "Profile",
          ["source"] = "S",
          ["enum"] = {
            [1] = "SIM (combined)",
            [2] = "SEP (separate)",
            [3] = "IO (I/O profile)",
          },
        },
        [8402] = {
          ["code"] = "COP",
          ["name"] = "Copy channel 1 <> 2",
          ["source"] = "S",
          ["enum"] = {
            [0] = "nO (no copy)",
            [1] = "SP (reference)",
            [2] = "Cd (command)",
            [3] = "ALL (command and reference)",
          },
        },
        [8413] = {
          ["code"] = "FR1",
          ["name"] = "Ref.1 channel",
          ["source"] = "F",
          ["enum"] = {
            [0] = "nO",
            [1] = "AI1",
            [2] = "AI2",
            [3] = "AI3",
            [4] = "AI4",
            [163] = "LCC",
            [164] = "Mdb",
            [167] = "CAn",
            [169] = "nEt",
            [181] = "PI",
            [182] = "PG",
          },
        },
        [8423] = {
          ["code"] = "CD1",
          ["name"] = "Cmd channel 1",
          ["source"] = "F",
          ["enum"] = {
            [1] = "tEr",
            [3] = "LCC",
            [10] = "Mdb",
            [20] = "CAn",
            [30] = "nEt",
          },
        },
        [8501] = {
          ["code"] = "CMD",
          ["name"] = "Control word",
          ["source"] = "AC",
          ["bits"] = {
            [0] = "Switch on",
            [1] = "Enable voltage",
            [2] = "No quick stop",
            [3] = "Enable operation",
            [7] = "Fault reset",
            [8] = "Halt",
            [11] = "Direction of rotation (default assignment)",
            [12] = "Assignable bit 12",
            [13] = "Assignable bit 13",
            [14] = "Assignable bit 14",
            [15] = "Assignable bit 15",
          },
          ["ambiguous_8000"] = true,
        },
        [8502] = {
          ["code"] = "LFR",
          ["name"] = "Frequency reference",
          ["unit"] = "Hz",
          ["scale"] = 0.1,
          ["source"] = "FB",
          ["signed"] = true,
          ["decimals"] = 1,
          ["ambiguous_8000"] = true,
        },
        [8503] = {
          ["code"] = "PISP",
          ["name"] = "PID setpoint",
          ["source"] = "F",
        },
        [8504] = {
          ["code"] = "CMI",
          ["name"] = "Extended control word",
          ["source"] = "F",
        },
        [8602] = {
          ["code"] = "LFRD",
          ["name"] = "Speed reference",
          ["unit"] = "rpm",
          ["scale"] = 1.0,
          ["source"] = "AB",
          ["signed"] = true,
          ["ambiguous_8000"] = true,
        },
        [8603] = {
          ["code"] = "ETAD",
          ["name"] = "DRIVECOM status word",
          ["source"] = "FC",
          ["bits"] = {
            [0] = "Ready to switch on",
            [1] = "Switched on",
            [2] = "Operation enabled",
            [3] = "Fault",
            [4] = "Voltage enabled",
            [5] = "Quick stop inactive",
            [6] = "Switch on disabled",
            [7] = "Warning",
            [9] = "Remote",
            [10] = "Target reached",
            [11] = "Internal limit active",
            [14] = "Stop via STOP key",
            [15] = "Direction of rotation",
          },
          ["ambiguous_8000"] = true,
          ["read_only"] = true,
        },
        [8604] = {
          ["code"] = "RFRD",
          ["name"] = "Output speed",
          ["unit"] = "rpm",
          ["scale"] = 1.0,
          ["source"] = "AB",
          ["signed"] = true,
          ["ambiguous_8000"] = true,
          ["read_only"] = true,
        },
        [8605] = {
          ["code"] = "FRHD",
          ["name"] = "Speed reference before ramp",
          ["unit"] = "rpm",
          ["scale"] = 1.0,
          ["source"] = "FB",
          ["signed"] = true,
          ["ambiguous_8000"] = true,
          ["read_only"] = true,
        },
        [8606] = {
          ["code"] = "ERRD",
          ["name"] = "CiA402 fault code",
          ["source"] = "F",
          ["read_only"] = true,
        },
        [9001] = {
          ["code"] = "ACC",
          ["name"] = "Acceleration",
          ["unit"] = "s",
          ["source"] = "A",
          ["scale_unknown"] = true,
        },
        [9002] = {
          ["code"] = "DEC",
          ["name"] = "Deceleration",
          ["unit"] = "s",
          ["source"] = "A",
          ["scale_unknown"] = true,
        },
        [9630] = {
          ["code"] = "THR",
          ["name"] = "Motor thermal state",
          ["unit"] = "%",
          ["scale"] = 1.0,
          ["source"] = "F",
          ["read_only"] = true,
        },
        [12741] = {
          ["code"] = "NM1",
          ["name"] = "Com scanner input 1 value (default ETA)",
          ["source"] = "A",
          ["read_only"] = true,
        },
        [12742] = {
          ["code"] = "NM2",
          ["name"] = "Com scanner input 2 value (default RFRD)",
          ["source"] = "A",
          ["read_only"] = true,
        },
        [12743] = {
          ["code"] = "NM3",
          ["name"] = "Com scanner input 3 value",
          ["source"] = "A",
          ["read_only"] = true,
        },
        [12744] = {
          ["code"] = "NM4",
          ["name"] = "Com scanner input 4 value",
          ["source"] = "A",
          ["read_only"] = true,
        },
        [12745] = {
          ["code"] = "NM5",
          ["name"] = "Com scanner input 5 value",
          ["source"] = "A",
          ["read_only"] = true,
        },
        [12746] = {
          ["code"] = "NM6",
          ["name"] = "Com scanner input 6 value",
          ["source"] = "A",
          ["read_only"] = true,
        },
        [12747] = {
          ["code"] = "NM7",
          ["name"] = "Com scanner input 7 value",
          ["source"] = "A",
          ["read_only"] = true,
        },
        [12748] = {
          ["code"] = "NM8",
          ["name"] = "Com scanner input 8 value",
          ["source"] = "A",
          ["read_only"] = true,
        },
        [12761] = {
          ["code"] = "NC1",
          ["name"] = "Com scanner output 1 value (default CMD)",
          ["source"] = "A",
        },
        [12762] = {
          ["code"] = "NC2",
          ["name"] = "Com scanner output 2 value (default LFRD)",
          ["source"] = "A",
        },
        [12763] = {
          ["code"] = "NC3",
          ["name"] = "Com scanner output 3 value",
          ["source"] = "A",
        },
        [12764] = {
          ["code"] = "NC4",
          ["name"] = "Com scanner output 4 value",
          ["source"] = "A",
        },
        [12765] = {
          ["code"] = "NC5",
          ["name"] = "Com scanner output 5 value",
          ["source"] = "A",
        },
        [12766] = {
          ["code"] = "NC6",
          ["name"] = "Com scanner output 6 value",
          ["source"] = "A",
        },
        [12767] = {
          ["code"] = "NC7",
          ["name"] = "Com scanner output 7 value",
          ["source"] = "A",
        },
        [12768] = {
          ["code"] = "NC8",
          ["name"] = "Com scanner output 8 value",
          ["source"] = "A",
        },
      },
      ["identify"] = {
        ["product_codes"] = { "ATV71" },
        ["functions"] = {},
        ["traffic_fit"] = true,
      },
    },
    ["sel749m"] = {
      ["name"] = "sel749m",
      ["title"] = "SEL-749M motor protection relay",
      ["device"] = "SEL-749M",
      ["address_style"] = "plc",
      ["one_table"] = false,
      ["functions"] = {
        [3] = true,
        [4] = true,
        [6] = true,
        [16] = true,
        [96] = true,
        [97] = true,
        [98] = true,
        [125] = true,
        [126] = true,
      },
      ["inner_only"] = {
        [126] = true,
      },
      ["broadcast"] = nil,
      ["broadcast_allowed"] = "none",
      ["protected_value"] = nil,
      ["all_protected_exception"] = nil,
      ["all_protected_read"] = nil,
      ["limits"] = {
        [3] = { 125 },
        [4] = { 125 },
        [16] = { 100 },
      },
      ["exceptions"] = {
        [1] = "Illegal Function Code",
        [2] = "Illegal Data Address",
        [3] = "Illegal Data Value",
      },
      ["documented"] = "01, 02, 03",
      ["exception_causes"] = {
        [770] = {
          {
            ["text"] = "illegal register to read (increments the Invalid Address counter)",
            ["when"] = nil,
            ["counters"] = { "Invalid Address" },
          },
        },
        [771] = {
          {
            ["text"] = "illegal number of registers to read (increments the Illegal Register counter)",
            ["when"] = "quantity",
            ["counters"] = { "Illegal Register" },
          },
          {
            ["text"] = "format error (increments the Bad Packet Format counter)",
            ["when"] = nil,
            ["counters"] = { "Bad Packet Format" },
          },
        },
        [1026] = {
          {
            ["text"] = "illegal register to read (increments the Invalid Address counter)",
            ["when"] = nil,
            ["counters"] = { "Invalid Address" },
          },
        },
        [1027] = {
          {
            ["text"] = "illegal number of registers to read (increments the Illegal Register counter)",
            ["when"] = "quantity",
            ["counters"] = { "Illegal Register" },
          },
          {
            ["text"] = "format error (increments the Bad Packet Format counter)",
            ["when"] = nil,
            ["counters"] = { "Bad Packet Format" },
          },
        },
        [1538] = {
          {
            ["text"] = "illegal register address (increments the Invalid Address and Illegal Write counters)",
            ["when"] = nil,
            ["counters"] = { "Invalid Address", "Illegal Write" },
          },
        },
        [1539] = {
          {
            ["text"] = "illegal value (increments the Illegal Write counter)",
            ["when"] = nil,
            ["counters"] = { "Illegal Write" },
          },
        },
        [4098] = {
          {
            ["text"] = "illegal register to set (increments the Invalid Address and Illegal Write counters)",
            ["when"] = nil,
            ["counters"] = { "Invalid Address", "Illegal Write" },
          },
        },
        [4099] = {
          {
            ["text"] = "illegal number of registers (increments the Illegal Register and Illegal Write counters)",
            ["when"] = "quantity",
            ["counters"] = { "Illegal Register", "Illegal Write" },
          },
          {
            ["text"] = "wrong byte count (increments the Bad Packet Format and Illegal Write counters)",
            ["when"] = "byte_count",
            ["counters"] = { "Bad Packet Format", "Illegal Write" },
          },
          {
            ["text"] = "invalid data value (increments the Illegal Write counter)",
            ["when"] = nil,
            ["counters"] = { "Illegal Write" },
          },
        },
      },
      ["diagnostics"] = {},
      ["subfunctions"] = nil,
      ["diagnostic_constants"] = {},
      ["objects"] = {},
      ["function_names"] = {
        [96] = "Read Parameter Information",
        [97] = "Read Parameter Text",
        [98] = "Read Enumeration Text",
        [125] = "Encapsulated Packet With Control",
        [126] = "NOP",
      },
      ["plc_base"] = {
        [1] = 1,
        [2] = 10001,
        [4] = 40001,
        [5] = 1,
        [15] = 1,
      },
      ["plc_base_default"] = 40001,
      ["bits_depend"] = {},
      ["map"] = {},
      ["identify"] = {
        ["product_codes"] = { "SEL-749M" },
        ["functions"] = {
          [96] = true,
          [97] = true,
          [98] = true,
          [125] = true,
        },
        ["traffic_fit"] = true,
      },
    },
    ["generic"] = {
      ["name"] = "generic",
      ["title"] = "Generic Modbus device (spec semantics only)",
      ["device"] = "device",
      ["address_style"] = "protocol",
      ["one_table"] = false,
      ["functions"] = nil,
      ["inner_only"] = {},
      ["broadcast"] = nil,
      ["broadcast_allowed"] = "none",
      ["protected_value"] = nil,
      ["all_protected_exception"] = nil,
      ["all_protected_read"] = nil,
      ["limits"] = {},
      ["exceptions"] = {},
      ["documented"] = "",
      ["exception_causes"] = {},
      ["diagnostics"] = {},
      ["subfunctions"] = nil,
      ["diagnostic_constants"] = {},
      ["objects"] = {},
      ["function_names"] = {},
      ["plc_base"] = {
        [1] = 1,
        [2] = 10001,
        [4] = 30001,
        [5] = 1,
        [15] = 1,
      },
      ["plc_base_default"] = 40001,
      ["bits_depend"] = {},
      ["map"] = {},
      ["identify"] = {
        ["product_codes"] = {},
        ["functions"] = {},
        ["traffic_fit"] = false,
      },
    },
  },
  ["default_profile"] = "auto",
  ["selection"] = {
    ["auto"] = "auto",
    ["fallback"] = "generic",
    ["candidates"] = { "atv71", "sel749m" },
    ["identifying"] = {
      [96] = { "sel749m", "Read Parameter Information" },
      [97] = { "sel749m", "Read Parameter Text" },
      [98] = { "sel749m", "Read Enumeration Text" },
      [125] = { "sel749m", "Encapsulated Packet With Control" },
    },
    ["product_codes"] = {
      { "ATV71", "atv71" },
      { "SEL-749M", "sel749m" },
    },
    ["fit_answers"] = 8,
    ["fit_frames"] = 32,
    ["fit_reads"] = 2,
    ["product_code_object"] = 1,
  },
  ["map_conflicts"] = {
    { "order_one_word", "one_word", "swapped" },
    { "wide_labels", "wide", "labels" },
    { "wide_last", "wide", "last" },
    { "signed_enum", "signed", "enum" },
    { "enum_bits", "enum", "bits" },
    {
      "labels_quantity",
      "enum",
      "scale",
      {
        ["what"] = "enum",
        ["column"] = "scale",
      },
    },
    {
      "labels_quantity",
      "enum",
      "unit",
      {
        ["what"] = "enum",
        ["column"] = "unit",
      },
    },
    {
      "labels_quantity",
      "bits",
      "scale",
      {
        ["what"] = "bit",
        ["column"] = "scale",
      },
    },
    {
      "labels_quantity",
      "bits",
      "unit",
      {
        ["what"] = "bit",
        ["column"] = "unit",
      },
    },
    { "scale_unknown_wide", "scale_unknown", "wide" },
    { "scale_unknown_unit", "scale_unknown", "no_unit" },
  },
}
do
-- BEGIN RULES: python3 -m dissector.codegen (codegen/rules_lua.py, data/modbus.toml)
local RULES = {["lift"]={["read_request"]={["start"]="start",["quantity"]="quantity",["checks"]={{["what"]="quantity",["field"]="quantity",["test"]="range"}},["span"]=true,["odd_count"]=false},["read_bits_response"]={["start"]="request.start",["quantity"]="request.quantity",["unpaired_unit"]=0,["checks"]={},["span"]=false,["count"]={["of"]="request.quantity",["unit"]=0,["plus"]=0,["text"]="count_asked_bits"},["odd_count"]=false,["padding"]="padding_bits",["values"]={["kind"]="bits",["field"]="status"}},["read_registers_response"]={["start"]="request.start",["quantity"]="request.quantity",["unpaired_unit"]=2,["checks"]={},["span"]=false,["count"]={["of"]="request.quantity",["unit"]=2,["plus"]=0,["text"]="count_asked_registers"},["odd_count"]=true,["values"]={["kind"]="registers",["field"]="values"}},["write_single_coil"]={["start"]="address",["quantity"]=1,["checks"]={},["span"]=false,["odd_count"]=false,["coil"]="value",["echo"]={["fields"]={"address","value"},["names"]="differing",["data"]=false},["values"]={["kind"]="coil",["field"]="value"}},["write_single_register"]={["start"]="address",["quantity"]=1,["checks"]={},["span"]=false,["odd_count"]=false,["echo"]={["fields"]={"address","value"},["names"]="differing",["data"]=false},["values"]={["kind"]="register",["field"]="value"}},["write_coils_request"]={["start"]="start",["quantity"]="quantity",["checks"]={{["what"]="quantity",["field"]="quantity",["test"]="range"}},["span"]=true,["count"]={["of"]="quantity",["unit"]=0,["plus"]=0,["text"]="count_quantity"},["odd_count"]=false,["padding"]="padding_written",["values"]={["kind"]="bits",["field"]="status"}},["write_registers_request"]={["start"]="start",["quantity"]="quantity",["checks"]={{["what"]="quantity",["field"]="quantity",["test"]="range"}},["span"]=true,["count"]={["of"]="quantity",["unit"]=2,["plus"]=0,["text"]="count_quantity"},["odd_count"]=false,["values"]={["kind"]="registers",["field"]="values",["most"]="quantity",["past"]="past_quantity"}},["write_multiple_response"]={["start"]="start",["quantity"]="quantity",["checks"]={},["span"]=false,["odd_count"]=false,["echo"]={["fields"]={"start","quantity"},["names"]="all",["data"]=false}},["mask_write"]={["start"]="address",["quantity"]=1,["checks"]={},["span"]=false,["odd_count"]=false,["echo"]={["fields"]={"address","and_mask","or_mask"},["names"]="differing",["data"]=false}},["read_write_request"]={["start"]="read_start",["quantity"]="read_quantity",["checks"]={{["what"]="read quantity",["field"]="read_quantity",["limit"]="rw_read",["test"]="range"},{["what"]="write quantity",["field"]="write_quantity",["limit"]="rw_write",["test"]="range"}},["span"]=true,["count"]={["of"]="write_quantity",["unit"]=2,["plus"]=0,["text"]="count_write_quantity"},["odd_count"]=false,["values"]={["kind"]="registers",["field"]="values",["start"]="write_start",["most"]="write_quantity",["past"]="past_write_quantity"},["write_window"]={"write_start","write_quantity"}},["fifo_request"]={["start"]="address",["checks"]={},["span"]=false,["odd_count"]=false},["fifo_response"]={["start"]="request.start",["checks"]={{["what"]="FIFO count",["field"]="fifo_count",["limit"]="fifo_count",["test"]="above"}},["span"]=false,["count"]={["of"]="fifo_count",["unit"]=2,["plus"]=2,["text"]="count_fifo"},["odd_count"]=false},["read_file_request"]={["checks"]={{["what"]="byte count",["field"]="byte_count",["limit"]="read_file_bytes",["test"]="range"}},["span"]=false,["odd_count"]=false,["parts"]={["field"]="subrequests",["name"]="sub-request",["fixed"]=7,["checks"]={{["what"]="reference type",["at"]={0,1},["limit"]="file_reference_type",["test"]="range"},{["what"]="record number",["at"]={3,2},["limit"]="file_record",["test"]="range"}},["keep"]={5,2}}},["read_file_response"]={["checks"]={},["span"]=false,["odd_count"]=false,["parts"]={["field"]="subresponses",["name"]="sub-response",["fixed"]=2,["size"]={["at"]={0,1},["minus"]=1,["half"]=true,["words"]=true},["checks"]={{["what"]="reference type",["at"]={1,1},["limit"]="file_reference_type",["test"]="range"}},["request"]="subrequests",["length"]={["at"]={0,1},["unit"]=2,["plus"]=1,["text"]="file_length"}}},["write_file"]={["checks"]={{["what"]="byte count",["field"]="byte_count",["limit"]="write_file_bytes",["test"]="range"}},["span"]=false,["odd_count"]=false,["echo"]={["fields"]={},["names"]="differing",["data"]=true},["parts"]={["field"]="records",["name"]="record",["fixed"]=7,["size"]={["at"]={5,2},["minus"]=0,["half"]=false,["words"]=true},["checks"]={{["what"]="reference type",["at"]={0,1},["limit"]="file_reference_type",["test"]="range"},{["what"]="record number",["at"]={3,2},["limit"]="file_record",["test"]="range"},{["what"]="record length",["at"]={5,2},["limit"]="write_record_length",["test"]="range"}}}}},["by_code"]={["request"]={[1]={["layout"]="read_request",["rule"]="read_request",["limit"]="read_bits"},[2]={["layout"]="read_request",["rule"]="read_request",["limit"]="read_bits"},[3]={["layout"]="read_request",["rule"]="read_request",["limit"]="read_registers"},[4]={["layout"]="read_request",["rule"]="read_request",["limit"]="read_registers"},[5]={["layout"]="write_single",["rule"]="write_single_coil"},[6]={["layout"]="write_single",["rule"]="write_single_register"},[7]={["layout"]="empty"},[8]={["layout"]="diagnostics",["special"]="diagnostics"},[11]={["layout"]="empty"},[12]={["layout"]="empty"},[15]={["layout"]="write_coils_request",["rule"]="write_coils_request",["limit"]="write_coils"},[16]={["layout"]="write_registers_request",["rule"]="write_registers_request",["limit"]="write_registers"},[17]={["layout"]="empty"},[20]={["layout"]="read_file_request",["rule"]="read_file_request"},[21]={["layout"]="write_file",["rule"]="write_file"},[22]={["layout"]="mask_write",["rule"]="mask_write"},[23]={["layout"]="read_write_request",["rule"]="read_write_request"},[24]={["layout"]="fifo_request",["rule"]="fifo_request"},[43]={["layout"]="mei_request",["special"]="mei_request"}},["response"]={[1]={["layout"]="read_bits_response",["rule"]="read_bits_response"},[2]={["layout"]="read_bits_response",["rule"]="read_bits_response"},[3]={["layout"]="read_registers_response",["rule"]="read_registers_response"},[4]={["layout"]="read_registers_response",["rule"]="read_registers_response"},[5]={["layout"]="write_single",["rule"]="write_single_coil"},[6]={["layout"]="write_single",["rule"]="write_single_register"},[7]={["layout"]="exception_status_response"},[8]={["layout"]="diagnostics",["special"]="diagnostics"},[11]={["layout"]="comm_event_counter_response"},[12]={["layout"]="comm_event_log_response"},[15]={["layout"]="write_multiple_response",["rule"]="write_multiple_response"},[16]={["layout"]="write_multiple_response",["rule"]="write_multiple_response"},[17]={["layout"]="report_server_id_response",["special"]="report_server_id_response"},[20]={["layout"]="read_file_response",["rule"]="read_file_response"},[21]={["layout"]="write_file",["rule"]="write_file"},[22]={["layout"]="mask_write",["rule"]="mask_write"},[23]={["layout"]="read_registers_response",["rule"]="read_registers_response"},[24]={["layout"]="fifo_response",["rule"]="fifo_response",["limit"]="fifo_count"},[43]={["layout"]="mei_response",["special"]="mei_response"}}},["confirm"]={[5]="echo",[6]="echo",[15]="answer",[16]="answer",[22]="mask",[23]="answer"},["by_confirm"]={["echo"]={[5]=true,[6]=true},["answer"]={[15]=true,[16]=true,[23]=true},["mask"]={[22]=true}},["confirmed"]={["echo"]={[6]=true},["answer"]={[16]=true,[23]=true},["mask"]={}},["limits"]={["read_bits"]={1,2000},["read_registers"]={1,125},["write_coils"]={1,1968},["write_registers"]={1,123},["rw_read"]={1,125},["rw_write"]={1,121},["fifo_count"]={0,31},["device_id_code"]={1,4},["device_id_mandatory"]={0,2},["file_reference_type"]={6,6},["file_record"]={0,9999},["read_file_bytes"]={7,245},["write_file_bytes"]={9,251},["write_record_length"]={1,122}},["texts"]={["range"]={["template"]="{what} {value} outside the spec's {low}..{high}",["format"]="%s %s outside the spec's %s..%s",["params"]={"what","value","low","high"},["repr"]={}},["above"]={["template"]="{what} {value} above the spec's {high}",["format"]="%s %s above the spec's %s",["params"]={"what","value","high"},["repr"]={}},["span"]={["template"]="addresses {first}..{last} run past 65535",["format"]="addresses %s..%s run past 65535",["params"]={"first","last"},["repr"]={}},["count_asked_bits"]={["template"]="byte count {count} disagrees with the bits asked ({quantity})",["format"]="byte count %s disagrees with the bits asked (%s)",["params"]={"count","quantity"},["repr"]={}},["padding_bits"]={["template"]="padding bits set after the bits asked ({quantity}): 0x{mask:02X}",["format"]="padding bits set after the bits asked (%s): 0x%02X",["params"]={"quantity","mask"},["repr"]={}},["padding_written"]={["template"]="padding bits set after the coils written ({quantity}): 0x{mask:02X}",["format"]="padding bits set after the coils written (%s): 0x%02X",["params"]={"quantity","mask"},["repr"]={}},["count_asked_registers"]={["template"]="byte count {count} disagrees with the registers asked ({quantity})",["format"]="byte count %s disagrees with the registers asked (%s)",["params"]={"count","quantity"},["repr"]={}},["count_quantity"]={["template"]="byte count {count} disagrees with the quantity {quantity}",["format"]="byte count %s disagrees with the quantity %s",["params"]={"count","quantity"},["repr"]={}},["count_write_quantity"]={["template"]="byte count {count} disagrees with the write quantity {quantity}",["format"]="byte count %s disagrees with the write quantity %s",["params"]={"count","quantity"},["repr"]={}},["past_quantity"]={["template"]="{count} bytes past the quantity {quantity}, not written: {data}",["format"]="%s bytes past the quantity %s, not written: %s",["params"]={"count","quantity","data"},["repr"]={}},["past_write_quantity"]={["template"]="{count} bytes past the write quantity {quantity}, not written: {data}",["format"]="%s bytes past the write quantity %s, not written: %s",["params"]={"count","quantity","data"},["repr"]={}},["count_fifo"]={["template"]="byte count {count} disagrees with the FIFO count",["format"]="byte count %s disagrees with the FIFO count",["params"]={"count"},["repr"]={}},["odd_count"]={["template"]="odd byte count {count} for 16-bit registers",["format"]="odd byte count %s for 16-bit registers",["params"]={"count"},["repr"]={}},["coil_value"]={["template"]="coil value 0x{value:04X} is neither 0xFF00 (on) nor 0x0000 (off)",["format"]="coil value 0x%04X is neither 0xFF00 (on) nor 0x0000 (off)",["params"]={"value"},["repr"]={}},["echo"]={["template"]="the response's {fields} {verb} from the request's",["format"]="the response's %s %s from the request's",["params"]={"fields","verb"},["repr"]={}},["reserved_slave"]={["template"]="slave address {slave} is reserved (248..255 are no device's)",["format"]="slave address %s is reserved (248..255 are no device's)",["params"]={"slave"},["repr"]={}},["malformed"]={["template"]="malformed {kind}: {error}",["format"]="malformed %s: %s",["params"]={"kind","error"},["repr"]={}},["unknown_exception"]={["template"]="exception code {code} is not defined by the spec",["format"]="exception code %s is not defined by the spec",["params"]={"code"},["repr"]={}},["trailing"]={["template"]="unexpected bytes after the data ({count})",["format"]="unexpected bytes after the data (%s)",["params"]={"count"},["repr"]={}},["not_broadcast"]={["template"]="{function} cannot be broadcast (slave 0)",["format"]="%s cannot be broadcast (slave 0)",["params"]={"function"},["repr"]={}},["unknown_subfunction"]={["template"]="diagnostic sub-function {subfunction} is not defined by the spec",["format"]="diagnostic sub-function %s is not defined by the spec",["params"]={"subfunction"},["repr"]={}},["odd_diagnostic_data"]={["template"]="diagnostic data is not a whole number of words",["format"]="diagnostic data is not a whole number of words",["params"]={},["repr"]={}},["diagnostic_data"]={["template"]="diagnostic data {data} is not what sub-function {subfunction:02X}h takes ({allowed}): a server answers exception 03",["format"]="diagnostic data %s is not what sub-function %02Xh takes (%s): a server answers exception 03",["params"]={"data","subfunction","allowed"},["repr"]={}},["character_then_00"]={["template"]="a character, then 00",["format"]="a character, then 00",["params"]={},["repr"]={}},["diagnostic_character"]={["template"]="{what}: {character} ({code:02X}h)",["format"]="%s: %s (%02Xh)",["params"]={"what","character","code"},["repr"]={}},["diagnostic_byte"]={["template"]="{what}: {code:02X}h",["format"]="%s: %02Xh",["params"]={"what","code"},["repr"]={}},["run_indicator"]={["template"]="run indicator 0x{value:02X} is neither 0x00 (OFF) nor 0xFF (ON)",["format"]="run indicator 0x%02X is neither 0x00 (OFF) nor 0xFF (ON)",["params"]={"value"},["repr"]={}},["no_run_indicator"]={["template"]="no run indicator status: byte count {count} holds the server id alone",["format"]="no run indicator status: byte count %s holds the server id alone",["params"]={"count"},["repr"]={}},["no_server_id"]={["template"]="no server id and no run indicator status: byte count {count} holds neither",["format"]="no server id and no run indicator status: byte count %s holds neither",["params"]={"count"},["repr"]={}},["no_objects"]={["template"]="no objects: {names} are mandatory",["format"]="no objects: %s are mandatory",["params"]={"names"},["repr"]={}},["object_count"]={["template"]="number of objects {count} disagrees with the objects present ({present})",["format"]="number of objects %s disagrees with the objects present (%s)",["params"]={"count","present"},["repr"]={}},["range_one"]={["template"]="{what} {value} is not the spec's {low}",["format"]="%s %s is not the spec's %s",["params"]={"what","value","low"},["repr"]={}},["file_length"]={["template"]="{part} {index}'s length {count} holds registers ({held}), not the record length asked ({quantity})",["format"]="%s %s's length %s holds registers (%s), not the record length asked (%s)",["params"]={"part","index","count","held","quantity"},["repr"]={}},["part_count"]={["template"]="number of {part}s {count} disagrees with the request's ({quantity})",["format"]="number of %ss %s disagrees with the request's (%s)",["params"]={"part","count","quantity"},["repr"]={}},["device_id_code"]={["template"]="read device id code {code} outside the spec's {low}..{high} (a server answers exception 03)",["format"]="read device id code %s outside the spec's %s..%s (a server answers exception 03)",["params"]={"code","low","high"},["repr"]={}},["unanswered"]={["template"]="request #{number} was not answered",["format"]="request #%s was not answered",["params"]={"number"},["repr"]={}},["never_answered"]={["template"]="no response expected: the spec's server returns none",["format"]="no response expected: the spec's server returns none",["params"]={},["repr"]={}},["listen_only"]={["template"]="slave {slave} is in listen-only mode since #{number} (08/04{how}): it does not answer",["format"]="slave %s is in listen-only mode since #%s (08/04%s): it does not answer",["params"]={"slave","number","how"},["repr"]={}},["listen_only_ends"]={["template"]="slave {slave} leaves listen-only mode (since #{number}, 08/04{how}): the spec's server does not answer this",["format"]="slave %s leaves listen-only mode (since #%s, 08/04%s): the spec's server does not answer this",["params"]={"slave","number","how"},["repr"]={}},["listen_only_broadcast"]={["template"]=", broadcast",["format"]=", broadcast",["params"]={},["repr"]={}},["listen_only_answered"]={["template"]="slave {slave} answers: it is not in listen-only mode (#{number}, 08/04{how})",["format"]="slave %s answers: it is not in listen-only mode (#%s, 08/04%s)",["params"]={"slave","number","how"},["repr"]={}},["listen_only_echo"]={["template"]="an answer to 08/04 (Force Listen Only Mode), which the spec's slave does not answer",["format"]="an answer to 08/04 (Force Listen Only Mode), which the spec's slave does not answer",["params"]={},["repr"]={}},["unmatched"]={["template"]="response without a matching request in the capture",["format"]="response without a matching request in the capture",["params"]={},["repr"]={}},["request_damaged"]={["template"]="addresses unknown: the request's {check} is bad",["format"]="addresses unknown: the request's %s is bad",["params"]={"check"},["repr"]={}},["broadcast_answered"]={["template"]="response from slave 0 after broadcast #{number}: no server answers a broadcast",["format"]="response from slave 0 after broadcast #%s: no server answers a broadcast",["params"]={"number"},["repr"]={}},["broadcast_address"]={["template"]="response from slave 0, the broadcast address: a server answers with its own address",["format"]="response from slave 0, the broadcast address: a server answers with its own address",["params"]={},["repr"]={}},["capture_ends_unknown"]={["template"]="the capture ends before any response: not known whether it was answered",["format"]="the capture ends before any response: not known whether it was answered",["params"]={},["repr"]={}},["capture_ends_within"]={["template"]="the capture ends {waited_ms:.1f} ms after the request, within the {timeout_ms:.0f} ms timeout: not known whether it was answered",["format"]="the capture ends %.1f ms after the request, within the %.0f ms timeout: not known whether it was answered",["params"]={"waited_ms","timeout_ms"},["repr"]={}},["late"]={["template"]="response {delay_ms:.1f} ms after request #{number}, later than the {timeout_ms:.0f} ms timeout: not its answer",["format"]="response %.1f ms after request #%s, later than the %.0f ms timeout: not its answer",["params"]={"delay_ms","number","timeout_ms"},["repr"]={}},["backwards"]={["template"]="response stamped {ahead_ms:.1f} ms before request #{number}: time goes backwards, left out of the response times",["format"]="response stamped %.1f ms before request #%s: time goes backwards, left out of the response times",["params"]={"ahead_ms","number"},["repr"]={}},["lf_without_cr"]={["template"]="line ends with LF without CR (the spec ends a frame with CR LF)",["format"]="line ends with LF without CR (the spec ends a frame with CR LF)",["params"]={},["repr"]={}},["lf_then_cr"]={["template"]="line ends with LF then CR, reversed (the spec ends a frame with CR LF)",["format"]="line ends with LF then CR, reversed (the spec ends a frame with CR LF)",["params"]={},["repr"]={}},["cr_without_lf"]={["template"]="line ends with CR without LF, before the next ':' (the spec ends a frame with CR LF)",["format"]="line ends with CR without LF, before the next ':' (the spec ends a frame with CR LF)",["params"]={},["repr"]={}},["cr_then_byte"]={["template"]="line ends with CR then {byte:02X}h where LF belongs (the spec ends a frame with CR LF)",["format"]="line ends with CR then %02Xh where LF belongs (the spec ends a frame with CR LF)",["params"]={"byte"},["repr"]={}},["cr_at_end"]={["template"]="line ends with CR without LF, at the end of the capture (the spec ends a frame with CR LF)",["format"]="line ends with CR without LF, at the end of the capture (the spec ends a frame with CR LF)",["params"]={},["repr"]={}},["extra_cr"]={["template"]="line ends with {count} CRs where the spec has one (a frame ends with CR LF)",["format"]="line ends with %s CRs where the spec has one (a frame ends with CR LF)",["params"]={"count"},["repr"]={}},["delimiter_expected"]={["template"]="line ends with CR then {byte:02X}h where slave {slave}'s delimiter {delimiter:02X}h belongs (set by its answer to 08/03)",["format"]="line ends with CR then %02Xh where slave %s's delimiter %02Xh belongs (set by its answer to 08/03)",["params"]={"byte","slave","delimiter"},["repr"]={}},["lower_case_hex"]={["template"]="lower-case hex digits (the spec wants upper case)",["format"]="lower-case hex digits (the spec wants upper case)",["params"]={},["repr"]={}},["inner_silence"]={["template"]="silence of {silence_ms:.3f} ms inside the frame before byte {byte} (longer than {limit})",["format"]="silence of %.3f ms inside the frame before byte %s (longer than %s)",["params"]={"silence_ms","byte","limit"},["repr"]={}},["no_frame"]={["template"]="no valid frame",["format"]="no valid frame",["params"]={},["repr"]={}},["too_short"]={["template"]="too short for a frame",["format"]="too short for a frame",["params"]={},["repr"]={}},["frame_length"]={["template"]="frame length {length} disagrees with the spec's layout ({expected} bytes), its CRC good",["format"]="frame length %s disagrees with the spec's layout (%s bytes), its CRC good",["params"]={"length","expected"},["repr"]={}},["over_adu"]={["template"]="frame length {length} above the spec's {limit}-byte ADU (its header gives it)",["format"]="frame length %s above the spec's %s-byte ADU (its header gives it)",["params"]={"length","limit"},["repr"]={}},["over_ascii"]={["template"]="frame length {length} above the spec's {limit} characters (its header gives it)",["format"]="frame length %s above the spec's %s characters (its header gives it)",["params"]={"length","limit"},["repr"]={}},["outside_ascii"]={["template"]="outside an ASCII frame",["format"]="outside an ASCII frame",["params"]={},["repr"]={}},["cut_by_colon"]={["template"]="ASCII frame cut short by the next ':'",["format"]="ASCII frame cut short by the next ':'",["params"]={},["repr"]={}},["no_line_end"]={["template"]="no CR LF within {limit} characters of the ':'",["format"]="no CR LF within %s characters of the ':'",["params"]={"limit"},["repr"]={}},["cut_by_end"]={["template"]="ASCII frame cut off by the end of the capture",["format"]="ASCII frame cut off by the end of the capture",["params"]={},["repr"]={}},["not_hex_pairs"]={["template"]="ASCII frame is not made of hex pairs",["format"]="ASCII frame is not made of hex pairs",["params"]={},["repr"]={}},["ascii_too_short"]={["template"]="ASCII frame too short",["format"]="ASCII frame too short",["params"]={},["repr"]={}},["no_layout"]={["template"]="no Modbus layout fits function {function} ({check})",["format"]="no Modbus layout fits function %s (%s)",["params"]={"function","check"},["repr"]={}},["lrc_wrong"]={["template"]="LRC {received:02X}, expected {expected:02X}",["format"]="LRC %02X, expected %02X",["params"]={"received","expected"},["repr"]={}},["not_supported"]={["template"]="{name} ({function}) is not supported by the {device}",["format"]="%s (%s) is not supported by the %s",["params"]={"name","function","device"},["repr"]={}},["read_only"]={["template"]="{parameter} is read-only (access {access})",["format"]="%s is read-only (access %s)",["params"]={"parameter","access"},["repr"]={}},["subfunction_not_supported"]={["template"]="sub-function {subfunction:02X}h ({name}) is not supported by the {device}",["format"]="sub-function %02Xh (%s) is not supported by the %s",["params"]={"subfunction","name","device"},["repr"]={}},["inner_only"]={["template"]="{name} ({function}) is only valid inside an encapsulated packet on the {device}",["format"]="%s (%s) is only valid inside an encapsulated packet on the %s",["params"]={"name","function","device"},["repr"]={}},["device_broadcast"]={["template"]="{name} cannot be broadcast to the {device} (broadcast functions: {allowed})",["format"]="%s cannot be broadcast to the %s (broadcast functions: %s)",["params"]={"name","device","allowed"},["repr"]={}},["device_limit"]={["template"]="{what} {quantity} is beyond the {device}'s limit of {limit} words for {name}",["format"]="%s %s is beyond the %s's limit of %s words for %s",["params"]={"what","quantity","device","limit","name"},["repr"]={}},["exception_cause"]={["template"]="exception {code:02X} from the {device} to {name}: {causes}",["format"]="exception %02X from the %s to %s: %s",["params"]={"code","device","name","causes"},["repr"]={}},["exception_meaning"]={["template"]="exception {code:02X} from the {device}: {meaning}",["format"]="exception %02X from the %s: %s",["params"]={"code","device","meaning"},["repr"]={}},["read_only_meaning"]={["template"]="write refused: read-only parameter (access {access})",["format"]="write refused: read-only parameter (access %s)",["params"]={"access"},["repr"]={}},["read_only_refusal"]={["template"]="{parameters} read-only (access {access}), not written",["format"]="%s read-only (access %s), not written",["params"]={"parameters","access"},["repr"]={}},["all_protected_read"]={["template"]="{meaning} (also: every parameter read is non-existent or protected)",["format"]="%s (also: every parameter read is non-existent or protected)",["params"]={"meaning"},["repr"]={}},["exception_undocumented"]={["template"]="exception {code:02X} is not one the {device} documents ({known})",["format"]="exception %02X is not one the %s documents (%s)",["params"]={"code","device","known"},["repr"]={}},["revision_form"]={["template"]="{object} '{value}' is not in the MMmm form the {device} uses",["format"]="%s '%s' is not in the MMmm form the %s uses",["params"]={"object","value","device"},["repr"]={}},["object_length"]={["template"]="{object} of {length} bytes is longer than the {device}'s {limit}",["format"]="%s of %s bytes is longer than the %s's %s",["params"]={"object","length","device","limit"},["repr"]={}},["subfunction_meaning"]={["template"]="sub-function {subfunction:02X} on the {device}: {meaning}",["format"]="sub-function %02X on the %s: %s",["params"]={"subfunction","device","meaning"},["repr"]={}},["subfunction_value"]={["template"]="; value {value}",["format"]="; value %s",["params"]={"value"},["repr"]={}},["diagnostic_constant"]={["template"]="the {device} documents sub-function {subfunction:02X} as always {constant}: this answer says {value}",["format"]="the %s documents sub-function %02X as always %s: this answer says %s",["params"]={"device","subfunction","constant","value"},["repr"]={}},["cause_counter"]={["template"]="{error} (increments the {counters} counter)",["format"]="%s (increments the %s counter)",["params"]={"error","counters"},["repr"]={}},["cause_counters"]={["template"]="{error} (increments the {counters} counters)",["format"]="%s (increments the %s counters)",["params"]={"error","counters"},["repr"]={}},["all_unreadable"]={["template"]="exception {code:02X} from the {device}: every parameter of this read is non-existent or protected: {parameters}",["format"]="exception %02X from the %s: every parameter of this read is non-existent or protected: %s",["params"]={"code","device","parameters"},["repr"]={}},["unmapped_run"]={["template"]="{span} non-existent ({count})",["format"]="%s non-existent (%s)",["params"]={"span","count"},["repr"]={}},["unreadable_now"]={["template"]="exception {code:02X} now",["format"]="exception %02X now",["params"]={"code"},["repr"]={}},["no_value"]={["template"]="no value: exception {code:02X}",["format"]="no value: exception %02X",["params"]={"code"},["repr"]={}},["became_protected"]={["template"]="became protected",["format"]="became protected",["params"]={},["repr"]={}},["became_unknown"]={["template"]="became non-existent or protected",["format"]="became non-existent or protected",["params"]={},["repr"]={}},["readable_again"]={["template"]="readable again",["format"]="readable again",["params"]={},["repr"]={}},["known_value"]={["template"]="{how} {value:d}",["format"]="%s %d",["params"]={"how","value"},["repr"]={}},["value_now"]={["template"]="{value:d} now",["format"]="%d now",["params"]={"value"},["repr"]={}},["marker_now"]={["template"]="16#8000 now",["format"]="16#8000 now",["params"]={},["repr"]={}},["event_one"]={["template"]="{name} {what}: {before} in frame #{frame:d}, {now}",["format"]="%s %s: %s in frame #%d, %s",["params"]={"name","what","before","frame","now"},["repr"]={}},["event_runs"]={["template"]="{runs} {what} ({count:d}): {how} in frame #{frame:d}",["format"]="%s %s (%d): %s in frame #%d",["params"]={"runs","what","count","how","frame"},["repr"]={}},["event_runs_now"]={["template"]="{runs} {what} ({count:d}): {how} in frame #{frame:d}, {now}",["format"]="%s %s (%d): %s in frame #%d, %s",["params"]={"runs","what","count","how","frame","now"},["repr"]={}},["marker_non_existent"]={["template"]="16#8000: non-existent (address not in the map)",["format"]="16#8000: non-existent (address not in the map)",["params"]={},["repr"]={}},["marker_protected"]={["template"]="16#8000: protected",["format"]="16#8000: protected",["params"]={},["repr"]={}},["all_marked"]={["template"]="every value is 16#{protected:04X}, but the {device} answers exception {code:02X} when every parameter read is non-existent or protected: one at least is the value {protected:d}",["format"]="every value is 16#%04X, but the %s answers exception %02X when every parameter read is non-existent or protected: one at least is the value %d",["params"]={"protected","device","code","protected"},["repr"]={}},["first_word"]={["template"]="first word of the {kind}, the second is not in this frame",["format"]="first word of the %s, the second is not in this frame",["params"]={"kind"},["repr"]={}},["second_word"]={["template"]="second word of {code}",["format"]="second word of %s",["params"]={"code"},["repr"]={}},["second_word_alone"]={["template"]="second word of the {kind}, the first is not in this frame",["format"]="second word of the %s, the first is not in this frame",["params"]={"kind"},["repr"]={}},["not_listed"]={["template"]="{value:d} (not a listed value)",["format"]="%d (not a listed value)",["params"]={"value"},["repr"]={}},["no_bit_set"]={["template"]="no bit set",["format"]="no bit set",["params"]={},["repr"]={}},["bit_unnamed"]={["template"]="bit {bit:d}",["format"]="bit %d",["params"]={"bit"},["repr"]={}},["unscaled"]={["template"]="{value:d} (unscaled, in {unit})",["format"]="%d (unscaled, in %s)",["params"]={"value","unit"},["repr"]={}},["chosen_product_code"]={["template"]="Read Device Identification in frame #{frame:d}: ProductCode '{value}'",["format"]="Read Device Identification in frame #%d: ProductCode '%s'",["params"]={"frame","value"},["repr"]={}},["chosen_function"]={["template"]="function {function:02X}h ({name}) in frame #{frame:d}",["format"]="function %02Xh (%s) in frame #%d",["params"]={"function","name","frame"},["repr"]={}},["chosen_unsupported"]={["template"]="function {function:d} answered in frame #{frame:d}, which the {device} does not support",["format"]="function %d answered in frame #%d, which the %s does not support",["params"]={"function","frame","device"},["repr"]={}},["chosen_fit"]={["template"]="traffic fits its map: {reads}",["format"]="traffic fits its map: %s",["params"]={"reads"},["repr"]={}},["chosen_fit_marker"]={["template"]="traffic fits its map: {reads}; 16#{protected:04X} at {marker:d}, its answer for a non-existent parameter",["format"]="traffic fits its map: %s; 16#%04X at %d, its answer for a non-existent parameter",["params"]={"reads","protected","marker"},["repr"]={}},["broadcast_profile"]={["template"]="named with profile {profile}, which every slave with a device here has ({slaves}): a broadcast reaches them all",["format"]="named with profile %s, which every slave with a device here has (%s): a broadcast reaches them all",["params"]={"profile","slaves"},["repr"]={}},["broadcast_mixed"]={["template"]="named with spec semantics only: a broadcast reaches every slave, and those here are different devices ({slaves})",["format"]="named with spec semantics only: a broadcast reaches every slave, and those here are different devices (%s)",["params"]={"slaves"},["repr"]={}},["fit_read"]={["template"]="function {function:d} at {span} in frame #{frame:d}",["format"]="function %d at %s in frame #%d",["params"]={"function","span","frame"},["repr"]={}},["fit_read_again"]={["template"]="function {function:d} at {span} in frames #{frame:d} and #{again:d}",["format"]="function %d at %s in frames #%d and #%d",["params"]={"function","span","frame","again"},["repr"]={}},["user_function"]={["template"]="User-defined function {code}",["format"]="User-defined function %s",["params"]={"code"},["repr"]={}},["other_function"]={["template"]="Function {code}",["format"]="Function %s",["params"]={"code"},["repr"]={}},["missing_exception"]={["template"]="Missing exception code",["format"]="Missing exception code",["params"]={},["repr"]={}},["undefined_exception"]={["template"]="Unknown exception {code}",["format"]="Unknown exception %s",["params"]={"code"},["repr"]={}},["other_object"]={["template"]="Object {id}",["format"]="Object %s",["params"]={"id"},["repr"]={}},["mask_written"]={["template"]="AND 0x{and_mask:04X} OR 0x{or_mask:04X}",["format"]="AND 0x%04X OR 0x%04X",["params"]={"and_mask","or_mask"},["repr"]={}},["mask_prior"]={["template"]="AND 0x{and_mask:04X} OR 0x{or_mask:04X}: the result depends on the value before",["format"]="AND 0x%04X OR 0x%04X: the result depends on the value before",["params"]={"and_mask","or_mask"},["repr"]={}},["server_id_read_longer"]={["template"]="server id of {count} bytes, up to the first 00 (OFF) or FF (ON) after its first byte: after a one-byte id, 0x{value:02X} is no run indicator",["format"]="server id of %s bytes, up to the first 00 (OFF) or FF (ON) after its first byte: after a one-byte id, 0x%02X is no run indicator",["params"]={"count","value"},["repr"]={}}},["layouts"]={["read_request"]={{["name"]="start",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="quantity",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0}},["read_bits_response"]={{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="status",["type"]="bytes",["count"]="byte_count",["half"]=false,["minus"]=0,["shown"]={"bit_status"}}},["read_registers_response"]={{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="values",["type"]="words",["count"]="byte_count",["half"]=true,["minus"]=0},{["name"]="odd_byte",["type"]="odd",["count"]="byte_count",["half"]=false,["minus"]=0,["shown"]={"odd_byte"}}},["write_single"]={{["name"]="address",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="value",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"value"}}},["empty"]={},["diagnostics"]={{["name"]="subfunction",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="data",["type"]="rest",["half"]=false,["minus"]=0,["shown"]={"data"}}},["write_coils_request"]={{["name"]="start",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="quantity",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="status",["type"]="bytes",["count"]="byte_count",["half"]=false,["minus"]=0,["shown"]={"bit_status"}}},["write_registers_request"]={{["name"]="start",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="quantity",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="values",["type"]="words",["count"]="byte_count",["half"]=true,["minus"]=0},{["name"]="odd_byte",["type"]="odd",["count"]="byte_count",["half"]=false,["minus"]=0,["shown"]={"odd_byte"}}},["write_multiple_response"]={{["name"]="start",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="quantity",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0}},["exception_status_response"]={{["name"]="status",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"exception_status"}}},["comm_event_counter_response"]={{["name"]="status",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"status"}},{["name"]="event_count",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"event_count"}}},["mask_write"]={{["name"]="address",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="and_mask",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"and_mask"}},{["name"]="or_mask",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"or_mask"}}},["read_write_request"]={{["name"]="read_start",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="read_quantity",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0},{["name"]="write_start",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"write_start"}},{["name"]="write_quantity",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"write_quantity"}},{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="values",["type"]="words",["count"]="byte_count",["half"]=true,["minus"]=0},{["name"]="odd_byte",["type"]="odd",["count"]="byte_count",["half"]=false,["minus"]=0,["shown"]={"odd_byte"}}},["fifo_request"]={{["name"]="address",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0}},["fifo_response"]={{["name"]="byte_count",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="fifo_count",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"fifo_count"}},{["name"]="values",["type"]="words",["count"]="fifo_count",["half"]=false,["minus"]=0,["shown"]={"fifo_value"}}},["exception"]={{["name"]="exception_code",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0}},["raw"]={{["name"]="data",["type"]="rest",["half"]=false,["minus"]=0,["shown"]={"data"}}},["comm_event_log_response"]={{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="status",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"status"}},{["name"]="event_count",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"event_count"}},{["name"]="message_count",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"message_count"}},{["name"]="events",["type"]="bytes",["count"]="byte_count",["half"]=false,["minus"]=6,["shown"]={"events"}}},["report_server_id_response"]={{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="server_id",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"server_id"},["when"]="byte_count",["when_minus"]=0},{["name"]="run_indicator",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"run_indicator"},["when"]="byte_count",["when_minus"]=1},{["name"]="additional_data",["type"]="text",["count"]="byte_count",["half"]=false,["minus"]=2,["shown"]={"additional_data","additional_bytes"},["when"]="byte_count",["when_minus"]=1}},["read_file_request"]={{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="subrequests",["type"]="records",["count"]="byte_count",["half"]=false,["minus"]=0,["part"]="file_subrequest",["shown"]={"file_subrequest"}}},["read_file_response"]={{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="subresponses",["type"]="records",["count"]="byte_count",["half"]=false,["minus"]=0,["part"]="file_subresponse",["shown"]={"file_subresponse"}}},["write_file"]={{["name"]="byte_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"byte_count"}},{["name"]="records",["type"]="records",["count"]="byte_count",["half"]=false,["minus"]=0,["part"]="file_record",["shown"]={"file_write"}}},["mei_request"]={{["name"]="mei_type",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_type"}},{["name"]="body",["type"]="switch",["count"]="mei_type",["half"]=false,["minus"]=0,["cases"]={{["value"]=14,["part"]="device_id_request"},{["part"]="other_mei"}}}},["mei_response"]={{["name"]="mei_type",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_type"}},{["name"]="body",["type"]="switch",["count"]="mei_type",["half"]=false,["minus"]=0,["cases"]={{["value"]=14,["part"]="device_id_response"},{["part"]="other_mei"}}}}},["parts"]={["file_subrequest"]={{["name"]="reference_type",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"file_reference_type"}},{["name"]="file",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"file_number"}},{["name"]="record",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"file_record"}},{["name"]="length",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"file_length"}}},["file_subresponse"]={{["name"]="length",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"file_length"}},{["name"]="reference_type",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"file_reference_type"}},{["name"]="values",["type"]="words",["count"]="length",["half"]=true,["minus"]=1,["shown"]={"file_value"}}},["file_record"]={{["name"]="reference_type",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"file_reference_type"}},{["name"]="file",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"file_number"}},{["name"]="record",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"file_record"}},{["name"]="length",["type"]="u16",["size"]=2,["half"]=false,["minus"]=0,["shown"]={"file_length"}},{["name"]="values",["type"]="words",["count"]="length",["half"]=false,["minus"]=0,["shown"]={"file_value"}}},["device_id_request"]={{["name"]="read_code",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_read_code"}},{["name"]="object_id",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_object_id"}}},["device_id_response"]={{["name"]="read_code",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_read_code"}},{["name"]="conformity",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_conformity"}},{["name"]="more_follows",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_more_follows"}},{["name"]="next_object_id",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_next_object_id"}},{["name"]="object_count",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0,["shown"]={"mei_object_count"}},{["name"]="objects",["type"]="array",["count"]="object_count",["half"]=false,["minus"]=0,["part"]="device_object"}},["device_object"]={{["name"]="id",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0},{["name"]="length",["type"]="u8",["size"]=1,["half"]=false,["minus"]=0},{["name"]="value",["type"]="bytes",["count"]="length",["half"]=false,["minus"]=0}},["other_mei"]={{["name"]="data",["type"]="rest",["half"]=false,["minus"]=0,["shown"]={"data"}}}},["diagnostic_data"]={[1]={["data"]={[0]="",[65280]="clear the communications event log"},["allowed"]="0000 or FF00"},[2]={["data"]={[0]=""},["allowed"]="0000"},[3]={["character"]="new ASCII input delimiter",["names"]={[10]="LF",[13]="CR",[32]="space"},["allowed"]="a character, then 00"},[4]={["data"]={[0]=""},["allowed"]="0000"},[10]={["data"]={[0]=""},["allowed"]="0000"},[11]={["data"]={[0]=""},["allowed"]="0000"},[12]={["data"]={[0]=""},["allowed"]="0000"},[13]={["data"]={[0]=""},["allowed"]="0000"},[14]={["data"]={[0]=""},["allowed"]="0000"},[15]={["data"]={[0]=""},["allowed"]="0000"},[16]={["data"]={[0]=""},["allowed"]="0000"},[17]={["data"]={[0]=""},["allowed"]="0000"},[18]={["data"]={[0]=""},["allowed"]="0000"},[20]={["data"]={[0]=""},["allowed"]="0000"}},["diagnostic_echoes"]={
  [0] = true,
  [1] = true,
  [3] = true,
  [10] = true,
  [20] = true,
},["byte_text"]={[0]="\\x00",[1]="\\x01",[2]="\\x02",[3]="\\x03",[4]="\\x04",[5]="\\x05",[6]="\\x06",[7]="\\x07",[8]="\\x08",[9]="\\t",[10]="\\n",[11]="\\x0b",[12]="\\x0c",[13]="\\r",[14]="\\x0e",[15]="\\x0f",[16]="\\x10",[17]="\\x11",[18]="\\x12",[19]="\\x13",[20]="\\x14",[21]="\\x15",[22]="\\x16",[23]="\\x17",[24]="\\x18",[25]="\\x19",[26]="\\x1a",[27]="\\x1b",[28]="\\x1c",[29]="\\x1d",[30]="\\x1e",[31]="\\x1f",[32]=" ",[33]="!",[34]="\"",[35]="#",[36]="$",[37]="%",[38]="&",[39]="\\'",[40]="(",[41]=")",[42]="*",[43]="+",[44]=",",[45]="-",[46]=".",[47]="/",[48]="0",[49]="1",[50]="2",[51]="3",[52]="4",[53]="5",[54]="6",[55]="7",[56]="8",[57]="9",[58]=":",[59]=";",[60]="<",[61]="=",[62]=">",[63]="?",[64]="@",[65]="A",[66]="B",[67]="C",[68]="D",[69]="E",[70]="F",[71]="G",[72]="H",[73]="I",[74]="J",[75]="K",[76]="L",[77]="M",[78]="N",[79]="O",[80]="P",[81]="Q",[82]="R",[83]="S",[84]="T",[85]="U",[86]="V",[87]="W",[88]="X",[89]="Y",[90]="Z",[91]="[",[92]="\\\\",[93]="]",[94]="^",[95]="_",[96]="`",[97]="a",[98]="b",[99]="c",[100]="d",[101]="e",[102]="f",[103]="g",[104]="h",[105]="i",[106]="j",[107]="k",[108]="l",[109]="m",[110]="n",[111]="o",[112]="p",[113]="q",[114]="r",[115]="s",[116]="t",[117]="u",[118]="v",[119]="w",[120]="x",[121]="y",[122]="z",[123]="{",[124]="|",[125]="}",[126]="~",[127]="\\x7f",[128]="\\x80",[129]="\\x81",[130]="\\x82",[131]="\\x83",[132]="\\x84",[133]="\\x85",[134]="\\x86",[135]="\\x87",[136]="\\x88",[137]="\\x89",[138]="\\x8a",[139]="\\x8b",[140]="\\x8c",[141]="\\x8d",[142]="\\x8e",[143]="\\x8f",[144]="\\x90",[145]="\\x91",[146]="\\x92",[147]="\\x93",[148]="\\x94",[149]="\\x95",[150]="\\x96",[151]="\\x97",[152]="\\x98",[153]="\\x99",[154]="\\x9a",[155]="\\x9b",[156]="\\x9c",[157]="\\x9d",[158]="\\x9e",[159]="\\x9f",[160]="\\xa0",[161]="\\xa1",[162]="\\xa2",[163]="\\xa3",[164]="\\xa4",[165]="\\xa5",[166]="\\xa6",[167]="\\xa7",[168]="\\xa8",[169]="\\xa9",[170]="\\xaa",[171]="\\xab",[172]="\\xac",[173]="\\xad",[174]="\\xae",[175]="\\xaf",[176]="\\xb0",[177]="\\xb1",[178]="\\xb2",[179]="\\xb3",[180]="\\xb4",[181]="\\xb5",[182]="\\xb6",[183]="\\xb7",[184]="\\xb8",[185]="\\xb9",[186]="\\xba",[187]="\\xbb",[188]="\\xbc",[189]="\\xbd",[190]="\\xbe",[191]="\\xbf",[192]="\\xc0",[193]="\\xc1",[194]="\\xc2",[195]="\\xc3",[196]="\\xc4",[197]="\\xc5",[198]="\\xc6",[199]="\\xc7",[200]="\\xc8",[201]="\\xc9",[202]="\\xca",[203]="\\xcb",[204]="\\xcc",[205]="\\xcd",[206]="\\xce",[207]="\\xcf",[208]="\\xd0",[209]="\\xd1",[210]="\\xd2",[211]="\\xd3",[212]="\\xd4",[213]="\\xd5",[214]="\\xd6",[215]="\\xd7",[216]="\\xd8",[217]="\\xd9",[218]="\\xda",[219]="\\xdb",[220]="\\xdc",[221]="\\xdd",[222]="\\xde",[223]="\\xdf",[224]="\\xe0",[225]="\\xe1",[226]="\\xe2",[227]="\\xe3",[228]="\\xe4",[229]="\\xe5",[230]="\\xe6",[231]="\\xe7",[232]="\\xe8",[233]="\\xe9",[234]="\\xea",[235]="\\xeb",[236]="\\xec",[237]="\\xed",[238]="\\xee",[239]="\\xef",[240]="\\xf0",[241]="\\xf1",[242]="\\xf2",[243]="\\xf3",[244]="\\xf4",[245]="\\xf5",[246]="\\xf6",[247]="\\xf7",[248]="\\xf8",[249]="\\xf9",[250]="\\xfa",[251]="\\xfb",[252]="\\xfc",[253]="\\xfd",[254]="\\xfe",[255]="\\xff"},["mandatory_objects"]="VendorName, ProductCode, MajorMinorRevision",["answers"]={[1]={4,0,0,5},[2]={4,0,0,5},[3]={4,2,0,5},[4]={4,2,0,5},[23]={4,2,0,5}}}
-- END RULES
DATA.rules = RULES
end
do
local floor = math.floor
local encode = {}
function encode.head(kind, slave, fn, length)
  return kind + 4 * (slave + 256 * (fn + 256 * (length)))
end
function encode.crcs(crc_expected, crc)
  return crc_expected + 65536 * (crc)
end
function encode.span(quantity, start)
  if quantity == nil then quantity = 0 else quantity = quantity + 1 end
  if start == nil then start = 0 else start = start + 1 end
  return quantity + 65537 * (start)
end
function encode.registers(first, count, start)
  if start == nil then start = 0 else start = start + 1 end
  return first + 65536 * (count + 65536 * (start))
end
function encode.bits(first, count, start, single)
  if start == nil then start = 0 else start = start + 1 end
  if single == nil then single = 0 else single = single + 1 end
  return first + 65536 * (count + 65536 * (start + 65537 * (single)))
end
local function put(st, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11, s12, s13)
  local flat, k = st.flat, st.flat_n
  flat[k + 1] = s1
  flat[k + 2] = s2
  flat[k + 3] = s3
  flat[k + 4] = s4
  flat[k + 5] = s5
  if s6 == nil then s6 = false end
  flat[k + 6] = s6
  flat[k + 7] = s7
  flat[k + 8] = s8
  flat[k + 9] = s9
  flat[k + 10] = s10
  if s11 == nil then s11 = false end
  flat[k + 11] = s11
  if s12 == nil then s12 = false end
  flat[k + 12] = s12
  if s13 == nil then s13 = false end
  flat[k + 13] = s13
  st.flat_n = k + 13
  return k
end
local function expand(flat, k)
  local s1 = flat[k + 1]
  local kind = s1 % 4
  s1 = floor((s1 - kind) / 4)
  local slave = s1 % 256
  s1 = floor((s1 - slave) / 256)
  local fn = s1 % 256
  s1 = floor((s1 - fn) / 256)
  local length = s1
  local s2 = flat[k + 2]
  local at = s2
  local s3 = flat[k + 3]
  local number = s3
  local s4 = flat[k + 4]
  local offset = s4
  local s5 = flat[k + 5]
  local record = s5
  local s6 = flat[k + 6]
  local time = s6
  if time == false then time = nil end
  local s7 = flat[k + 7]
  local crc_expected = s7 % 65536
  s7 = floor((s7 - crc_expected) / 65536)
  local crc = s7
  local s8 = flat[k + 8]
  local quantity = s8 % 65537
  s8 = floor((s8 - quantity) / 65537)
  if quantity == 0 then quantity = nil else quantity = quantity - 1 end
  local start = s8
  if start == 0 then start = nil else start = start - 1 end
  local s9 = flat[k + 9]
  if s9 == false then
    s9 = nil
  else
    local first = s9 % 65536
    s9 = floor((s9 - first) / 65536)
    local count = s9 % 65536
    s9 = floor((s9 - count) / 65536)
    local start = s9
    if start == 0 then start = nil else start = start - 1 end
    s9 = { first = first, count = count, start = start }
  end
  local s10 = flat[k + 10]
  if s10 == false then
    s10 = nil
  else
    local first = s10 % 65536
    s10 = floor((s10 - first) / 65536)
    local count = s10 % 65536
    s10 = floor((s10 - count) / 65536)
    local start = s10 % 65537
    s10 = floor((s10 - start) / 65537)
    if start == 0 then start = nil else start = start - 1 end
    local single = s10
    if single == 0 then single = nil else single = single - 1 end
    s10 = { first = first, count = count, start = start, single = single }
  end
  local s11 = flat[k + 11]
  local link = s11
  if link == false then link = nil end
  local s12 = flat[k + 12]
  local request_time = s12
  if request_time == false then request_time = nil end
  local s13 = flat[k + 13]
  local span_label = s13
  if span_label == false then span_label = nil end
  return { kind = kind, slave = slave, fn = fn, length = length, at = at, number = number, offset = offset,
    record = record, time = time, crc_expected = crc_expected, crc = crc, quantity = quantity, start = start,
    registers = s9, bits = s10, span_label = span_label }, link, request_time
end
local function has_rare(f)
  return f.registers and (f.registers.status or f.registers.plain) or f.warnings or f.notes or f.unanswered or
    f.broadcast or f.no_request or f.malformed or f.function_text or f.exception_code or
    f.exception_meaning or f.subfunction or f.subfunction_text or f.objects or f.ascii or f.raw or
    f.inferred or f.profile_choice or f.profile_said or f.provisional or f.paired_notes or f.server_id_size or
    f.write_span_label
end
DATA.pack = { encode = encode, put = put, expand = expand, has_rare = has_rare, time = 6,
  rare = { "warnings", "notes", "unanswered", "broadcast", "no_request", "malformed", "function_text",
    "exception_code", "exception_meaning", "subfunction", "subfunction_text", "objects", "ascii", "raw",
    "inferred", "profile_choice", "profile_said", "provisional", "paired_notes", "server_id_size",
    "write_span_label" } }
end
do
local PARTS, PARSERS = {}, {} -- (a layout's reader calls its parts' by name)
PARTS.file_subrequest = function(b, d, len)
  if len < 7 then return nil, "too short for reference_type, file, record and length" end
  return 7, {
    ["reference_type"] = b[d], ["file"] = b[d + 1] * 256 + b[d + 2], ["record"] = b[d + 3] * 256 + b[d + 4],
    ["length"] = b[d + 5] * 256 + b[d + 6]
  }
end
PARTS.file_subresponse = function(b, d, len)
  if len < 2 then return nil, "too short for length and reference_type" end
  local v1 = b[d]
  local p = 2
  local s3 = (v1 - 1) - (v1 - 1) % 2
  if s3 < 0 or p + s3 > len then return nil, "length past the end" end
  local a3 = d + p
  p = p + s3
  return p, { ["length"] = v1, ["reference_type"] = b[d + 1], ["values_at"] = a3 }
end
PARTS.file_record = function(b, d, len)
  if len < 7 then return nil, "too short for reference_type, file, record and length" end
  local v4 = b[d + 5] * 256 + b[d + 6]
  local p = 7
  local s5 = 2 * v4
  if p + s5 > len then return nil, "length past the end" end
  local a5 = d + p
  p = p + s5
  return p, {
    ["reference_type"] = b[d], ["file"] = b[d + 1] * 256 + b[d + 2], ["record"] = b[d + 3] * 256 + b[d + 4],
    ["length"] = v4, ["values_at"] = a5
  }
end
PARTS.device_id_request = function(b, d, len)
  if len < 2 then return nil, "too short for read_code and object_id" end
  return 2, { ["read_code"] = b[d], ["object_id"] = b[d + 1] }
end
PARTS.device_id_response = function(b, d, len)
  if len < 5 then return nil, "too short for read_code, conformity, more_follows, next_object_id and object_count" end
  local v5 = b[d + 4]
  local p = 5
  local a6 = {}
  for k = 1, v5 do
    local used, item = PARTS["device_object"](b, d + p, len - p)
    if used == nil then break end
    a6[k], p = item, p + used
  end
  return p, {
    ["read_code"] = b[d], ["conformity"] = b[d + 1], ["more_follows"] = b[d + 2], ["next_object_id"] = b[d + 3],
    ["object_count"] = v5, ["objects"] = a6
  }
end
PARTS.device_object = function(b, d, len)
  if len < 2 then return nil, "too short for id and length" end
  local v2 = b[d + 1]
  local p = 2
  local s3 = v2
  if p + s3 > len then return nil, "length past the end" end
  local a3 = d + p
  p = p + s3
  return p, { ["id"] = b[d], ["length"] = v2, ["value_at"] = a3 }
end
PARTS.other_mei = function(b, d, len)
  return len, { ["data_length"] = len - 0 }
end
PARSERS.read_request = function(b, d, len)
  if len < 4 then return nil, "too short for start and quantity" end
  return 4, { ["start"] = b[d] * 256 + b[d + 1], ["quantity"] = b[d + 2] * 256 + b[d + 3] }
end
PARSERS.read_bits_response = function(b, d, len)
  if len < 1 then return nil, "too short for byte_count" end
  local v1 = b[d]
  local p = 1
  local s2 = v1
  if p + s2 > len then return nil, "byte_count past the end" end
  local a2 = d + p
  p = p + s2
  return p, { ["byte_count"] = v1, ["status_at"] = a2 }
end
PARSERS.read_registers_response = function(b, d, len)
  if len < 1 then return nil, "too short for byte_count" end
  local v1 = b[d]
  local p = 1
  local s2 = v1 - v1 % 2
  if p + s2 > len then return nil, "byte_count past the end" end
  local a2 = d + p
  p = p + s2
  local s3 = v1 % 2
  if p + s3 > len then return nil, "byte_count past the end" end
  p = p + s3
  return p, { ["byte_count"] = v1, ["values_at"] = a2 }
end
PARSERS.write_single = function(b, d, len)
  if len < 4 then return nil, "too short for address and value" end
  return 4, { ["address"] = b[d] * 256 + b[d + 1], ["value"] = b[d + 2] * 256 + b[d + 3] }
end
PARSERS.empty = function(b, d, len)
  return 0, {  }
end
PARSERS.diagnostics = function(b, d, len)
  if len < 2 then return nil, "too short for subfunction" end
  return len, { ["subfunction"] = b[d] * 256 + b[d + 1], ["data_length"] = len - 2 }
end
PARSERS.write_coils_request = function(b, d, len)
  if len < 5 then return nil, "too short for start, quantity and byte_count" end
  local v3 = b[d + 4]
  local p = 5
  local s4 = v3
  if p + s4 > len then return nil, "byte_count past the end" end
  local a4 = d + p
  p = p + s4
  return p, {
    ["start"] = b[d] * 256 + b[d + 1], ["quantity"] = b[d + 2] * 256 + b[d + 3], ["byte_count"] = v3,
    ["status_at"] = a4
  }
end
PARSERS.write_registers_request = function(b, d, len)
  if len < 5 then return nil, "too short for start, quantity and byte_count" end
  local v3 = b[d + 4]
  local p = 5
  local s4 = v3 - v3 % 2
  if p + s4 > len then return nil, "byte_count past the end" end
  local a4 = d + p
  p = p + s4
  local s5 = v3 % 2
  if p + s5 > len then return nil, "byte_count past the end" end
  p = p + s5
  return p, {
    ["start"] = b[d] * 256 + b[d + 1], ["quantity"] = b[d + 2] * 256 + b[d + 3], ["byte_count"] = v3,
    ["values_at"] = a4
  }
end
PARSERS.write_multiple_response = function(b, d, len)
  if len < 4 then return nil, "too short for start and quantity" end
  return 4, { ["start"] = b[d] * 256 + b[d + 1], ["quantity"] = b[d + 2] * 256 + b[d + 3] }
end
PARSERS.exception_status_response = function(b, d, len)
  if len < 1 then return nil, "too short for status" end
  return 1, { ["status"] = b[d] }
end
PARSERS.comm_event_counter_response = function(b, d, len)
  if len < 4 then return nil, "too short for status and event_count" end
  return 4, { ["status"] = b[d] * 256 + b[d + 1], ["event_count"] = b[d + 2] * 256 + b[d + 3] }
end
PARSERS.mask_write = function(b, d, len)
  if len < 6 then return nil, "too short for address, and_mask and or_mask" end
  return 6, {
    ["address"] = b[d] * 256 + b[d + 1], ["and_mask"] = b[d + 2] * 256 + b[d + 3],
    ["or_mask"] = b[d + 4] * 256 + b[d + 5]
  }
end
PARSERS.read_write_request = function(b, d, len)
  if len < 9 then return nil, "too short for read_start, read_quantity, write_start, write_quantity and byte_count" end
  local v5 = b[d + 8]
  local p = 9
  local s6 = v5 - v5 % 2
  if p + s6 > len then return nil, "byte_count past the end" end
  local a6 = d + p
  p = p + s6
  local s7 = v5 % 2
  if p + s7 > len then return nil, "byte_count past the end" end
  p = p + s7
  return p, {
    ["read_start"] = b[d] * 256 + b[d + 1], ["read_quantity"] = b[d + 2] * 256 + b[d + 3],
    ["write_start"] = b[d + 4] * 256 + b[d + 5], ["write_quantity"] = b[d + 6] * 256 + b[d + 7],
    ["byte_count"] = v5, ["values_at"] = a6
  }
end
PARSERS.fifo_request = function(b, d, len)
  if len < 2 then return nil, "too short for address" end
  return 2, { ["address"] = b[d] * 256 + b[d + 1] }
end
PARSERS.fifo_response = function(b, d, len)
  if len < 4 then return nil, "too short for byte_count and fifo_count" end
  local v2 = b[d + 2] * 256 + b[d + 3]
  local p = 4
  local s3 = 2 * v2
  if p + s3 > len then return nil, "fifo_count past the end" end
  local a3 = d + p
  p = p + s3
  return p, { ["byte_count"] = b[d] * 256 + b[d + 1], ["fifo_count"] = v2, ["values_at"] = a3 }
end
PARSERS.exception = function(b, d, len)
  if len < 1 then return nil, "too short for exception_code" end
  return 1, { ["exception_code"] = b[d] }
end
PARSERS.raw = function(b, d, len)
  return len, { ["data_length"] = len - 0 }
end
PARSERS.comm_event_log_response = function(b, d, len)
  if len < 7 then return nil, "too short for byte_count, status, event_count and message_count" end
  local v1 = b[d]
  local p = 7
  local s5 = (v1 - 6)
  if s5 < 0 or p + s5 > len then return nil, "byte_count past the end" end
  local a5 = d + p
  p = p + s5
  return p, {
    ["byte_count"] = v1, ["status"] = b[d + 1] * 256 + b[d + 2], ["event_count"] = b[d + 3] * 256 + b[d + 4],
    ["message_count"] = b[d + 5] * 256 + b[d + 6], ["events_at"] = a5
  }
end
PARSERS.report_server_id_response = function(b, d, len)
  if len < 1 then return nil, "too short for byte_count" end
  local v1 = b[d]
  local p = 1
  local v2
  if v1 - 0 > 0 then
    if p + 1 > len then return nil, "too short for server_id" end
    v2 = b[d + p]
    p = p + 1
  end
  local v3
  if v1 - 1 > 0 then
    if p + 1 > len then return nil, "too short for run_indicator" end
    v3 = b[d + p]
    p = p + 1
  end
  local s4, a4
  if v1 - 1 > 0 then
    s4 = (v1 - 2)
    if s4 < 0 or p + s4 > len then return nil, "byte_count past the end" end
    a4 = d + p
    p = p + s4
  end
  return p, { ["byte_count"] = v1, ["server_id"] = v2, ["run_indicator"] = v3, ["additional_data_at"] = a4 }
end
PARSERS.read_file_request = function(b, d, len)
  if len < 1 then return nil, "too short for byte_count" end
  local v1 = b[d]
  local p = 1
  local s2 = v1
  if p + s2 > len then return nil, "byte_count past the end" end
  local a2 = d + p
  p = p + s2
  return p, { ["byte_count"] = v1, ["subrequests_at"] = a2 }
end
PARSERS.read_file_response = function(b, d, len)
  if len < 1 then return nil, "too short for byte_count" end
  local v1 = b[d]
  local p = 1
  local s2 = v1
  if p + s2 > len then return nil, "byte_count past the end" end
  local a2 = d + p
  p = p + s2
  return p, { ["byte_count"] = v1, ["subresponses_at"] = a2 }
end
PARSERS.write_file = function(b, d, len)
  if len < 1 then return nil, "too short for byte_count" end
  local v1 = b[d]
  local p = 1
  local s2 = v1
  if p + s2 > len then return nil, "byte_count past the end" end
  local a2 = d + p
  p = p + s2
  return p, { ["byte_count"] = v1, ["records_at"] = a2 }
end
PARSERS.mei_request = function(b, d, len)
  if len < 1 then return nil, "too short for mei_type" end
  local v1 = b[d]
  local p = 1
  local used, c2 = (v1 == 14 and PARTS["device_id_request"] or PARTS["other_mei"])(b, d + p, len - p)
  if used == nil then return nil, c2 end
  p = p + used
  return p, { ["mei_type"] = v1, ["body"] = c2 }
end
PARSERS.mei_response = function(b, d, len)
  if len < 1 then return nil, "too short for mei_type" end
  local v1 = b[d]
  local p = 1
  local used, c2 = (v1 == 14 and PARTS["device_id_response"] or PARTS["other_mei"])(b, d + p, len - p)
  if used == nil then return nil, c2 end
  p = p + used
  return p, { ["mei_type"] = v1, ["body"] = c2 }
end
DATA.parsers = PARSERS
DATA.grammars = {
  request = {
    [1] = PARSERS.read_request, [2] = PARSERS.read_request, [3] = PARSERS.read_request,
    [4] = PARSERS.read_request, [5] = PARSERS.write_single, [6] = PARSERS.write_single, [7] = PARSERS.empty,
    [8] = PARSERS.diagnostics, [11] = PARSERS.empty, [12] = PARSERS.empty, [15] = PARSERS.write_coils_request,
    [16] = PARSERS.write_registers_request, [17] = PARSERS.empty, [20] = PARSERS.read_file_request,
    [21] = PARSERS.write_file, [22] = PARSERS.mask_write, [23] = PARSERS.read_write_request,
    [24] = PARSERS.fifo_request, [43] = PARSERS.mei_request
  },
  response = {
    [1] = PARSERS.read_bits_response, [2] = PARSERS.read_bits_response, [3] = PARSERS.read_registers_response,
    [4] = PARSERS.read_registers_response, [5] = PARSERS.write_single, [6] = PARSERS.write_single,
    [7] = PARSERS.exception_status_response, [8] = PARSERS.diagnostics,
    [11] = PARSERS.comm_event_counter_response, [12] = PARSERS.comm_event_log_response,
    [15] = PARSERS.write_multiple_response, [16] = PARSERS.write_multiple_response,
    [17] = PARSERS.report_server_id_response, [20] = PARSERS.read_file_response, [21] = PARSERS.write_file,
    [22] = PARSERS.mask_write, [23] = PARSERS.read_registers_response, [24] = PARSERS.fifo_response,
    [43] = PARSERS.mei_response
  },
}
DATA.lift_of = {
  request = {
    [1] = DATA.rules.lift.read_request, [2] = DATA.rules.lift.read_request,
    [3] = DATA.rules.lift.read_request, [4] = DATA.rules.lift.read_request,
    [5] = DATA.rules.lift.write_single_coil, [6] = DATA.rules.lift.write_single_register,
    [15] = DATA.rules.lift.write_coils_request, [16] = DATA.rules.lift.write_registers_request,
    [20] = DATA.rules.lift.read_file_request, [21] = DATA.rules.lift.write_file,
    [22] = DATA.rules.lift.mask_write, [23] = DATA.rules.lift.read_write_request,
    [24] = DATA.rules.lift.fifo_request
  },
  response = {
    [1] = DATA.rules.lift.read_bits_response, [2] = DATA.rules.lift.read_bits_response,
    [3] = DATA.rules.lift.read_registers_response, [4] = DATA.rules.lift.read_registers_response,
    [5] = DATA.rules.lift.write_single_coil, [6] = DATA.rules.lift.write_single_register,
    [15] = DATA.rules.lift.write_multiple_response, [16] = DATA.rules.lift.write_multiple_response,
    [20] = DATA.rules.lift.read_file_response, [21] = DATA.rules.lift.write_file,
    [22] = DATA.rules.lift.mask_write, [23] = DATA.rules.lift.read_registers_response,
    [24] = DATA.rules.lift.fifo_response
  },
}
function DATA.lifters(
  special, warn, say, echo_check, data_bytes, range_text, check_asked, check_data_echo, past_quantity
)
  local floor, lift = math.floor, DATA.rules.lift
  local handler = {} -- (by rule, and limit where codes give a rule several)
  handler.read_request_read_bits = function(f, b)
    local fields = f.fields
    local first = fields["start"]
    local many = fields["quantity"]
    f.start, f.quantity = first, many
    if fields["quantity"] < 1 or fields["quantity"] > 2000 then
      warn(f, range_text("quantity", fields["quantity"], 1, 2000))
    end
    if first + many > 65536 then warn(f, say("span", { first = first, last = first + many - 1 })) end
  end
  handler.read_request_read_registers = function(f, b)
    local fields = f.fields
    local first = fields["start"]
    local many = fields["quantity"]
    f.start, f.quantity = first, many
    if fields["quantity"] < 1 or fields["quantity"] > 125 then
      warn(f, range_text("quantity", fields["quantity"], 1, 125))
    end
    if first + many > 65536 then warn(f, say("span", { first = first, last = first + many - 1 })) end
  end
  do
    local echo = lift.write_single_coil.echo
    handler.write_single_coil = function(f, b)
      local fields = f.fields
      local request = f.request
      if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
      local first = fields["address"]
      local many = 1
      f.start, f.quantity = first, many
      if fields["value"] ~= 65280 and fields["value"] ~= 0 then
        warn(f, say("coil_value", { value = fields["value"] }))
      end
      if request ~= nil and (
        request.fields["address"] ~= fields["address"] or request.fields["value"] ~= fields["value"]
      ) then echo_check(f, fields, request, echo) end
      if fields["value"] == 65280 or fields["value"] == 0 then
        f.bits = { first = f.data_at + 2, count = 1, start = first, single = fields["value"] == 65280 and 1 or 0 }
      end
    end
  end
  do
    local echo = lift.write_single_register.echo
    handler.write_single_register = function(f, b)
      local fields = f.fields
      local request = f.request
      if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
      local first = fields["address"]
      local many = 1
      f.start, f.quantity = first, many
      if request ~= nil and (
        request.fields["address"] ~= fields["address"] or request.fields["value"] ~= fields["value"]
      ) then echo_check(f, fields, request, echo) end
      f.registers = { b = b, first = f.data_at + 2, count = 1, start = first, shift = nil }
    end
  end
  handler.write_coils_request = function(f, b)
    local fields = f.fields
    local first = fields["start"]
    local many = fields["quantity"]
    f.start, f.quantity = first, many
    if fields["quantity"] < 1 or fields["quantity"] > 1968 then
      warn(f, range_text("quantity", fields["quantity"], 1, 1968))
    end
    if first + many > 65536 then warn(f, say("span", { first = first, last = first + many - 1 })) end
    local of = fields["quantity"]
    if of ~= nil and fields.byte_count ~= 0 + data_bytes(of, 0) then
      warn(f, say("count_quantity", { count = fields.byte_count, quantity = of }))
    elseif of ~= nil and of % 8 > 0 then
      local low = floor(2 ^ (of % 8))
      local unused = b[fields["status_at"] + fields.byte_count - 1] - b[fields["status_at"] + fields.byte_count - 1] % low
      if unused > 0 then warn(f, say("padding_written", { quantity = of, mask = unused })) end
    end
    local count = 8 * fields["byte_count"]
    if many ~= nil and many < count then count = many end
    f.bits = { b = b, first = fields["status_at"], count = count, start = first, shift = nil }
  end
  handler.write_registers_request = function(f, b)
    local fields = f.fields
    local first = fields["start"]
    local many = fields["quantity"]
    f.start, f.quantity = first, many
    if fields["quantity"] < 1 or fields["quantity"] > 123 then
      warn(f, range_text("quantity", fields["quantity"], 1, 123))
    end
    if first + many > 65536 then warn(f, say("span", { first = first, last = first + many - 1 })) end
    local of = fields["quantity"]
    if of ~= nil and fields.byte_count ~= 0 + data_bytes(of, 2) then
      warn(f, say("count_quantity", { count = fields.byte_count, quantity = of }))
    end
    local count, most = floor(fields["byte_count"] / 2), fields["quantity"]
    if count > most then
      past_quantity(f, b, fields["values_at"] + 2 * most, 2 * (count - most), most, "past_quantity")
      count = most
    end
    f.registers = { b = b, first = fields["values_at"], count = count, start = first, shift = nil }
  end
  handler.read_file_request = function(f, b)
    local fields = f.fields
    local first = nil
    local many = nil
    f.start, f.quantity = first, many
    if fields["byte_count"] < 7 or fields["byte_count"] > 245 then
      warn(f, range_text("byte count", fields["byte_count"], 7, 245))
    end
    local p, stop, index = fields["subrequests_at"], fields["subrequests_at"] + fields["byte_count"], 0
    local kept = {}
    while p + 7 <= stop do
      if p + 7 > stop then break end
      index = index + 1
      local v = b[p + 0]
      if v ~= 6 then warn(f, range_text("sub-request " .. index .. "'s reference type", v, 6, 6)) end
      local v = b[p + 3] * 256 + b[p + 4]
      if v > 9999 then warn(f, range_text("sub-request " .. index .. "'s record number", v, 0, 9999)) end
      kept[index] = b[p + 5] * 256 + b[p + 6]
      p = p + 7
    end
    fields["subrequests"] = kept
  end
  handler.write_file = function(f, b)
    local fields = f.fields
    local request = f.request
    if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
    local first = nil
    local many = nil
    f.start, f.quantity = first, many
    if fields["byte_count"] < 9 or fields["byte_count"] > 251 then
      warn(f, range_text("byte count", fields["byte_count"], 9, 251))
    end
    check_data_echo(f, b, request, 0)
    local p, stop, index = fields["records_at"], fields["records_at"] + fields["byte_count"], 0
    while p + 7 <= stop do
      local n = b[p + 5] * 256 + b[p + 6] - 0
      if n < 0 then break end
      if p + 7 + 2 * n > stop then break end
      index = index + 1
      local v = b[p + 0]
      if v ~= 6 then warn(f, range_text("record " .. index .. "'s reference type", v, 6, 6)) end
      local v = b[p + 3] * 256 + b[p + 4]
      if v > 9999 then warn(f, range_text("record " .. index .. "'s record number", v, 0, 9999)) end
      local v = b[p + 5] * 256 + b[p + 6]
      if v < 1 or v > 122 then warn(f, range_text("record " .. index .. "'s record length", v, 1, 122)) end
      p = p + 7 + 2 * n
    end
  end
  do
    local echo = lift.mask_write.echo
    handler.mask_write = function(f, b)
      local fields = f.fields
      local request = f.request
      if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
      local first = fields["address"]
      local many = 1
      f.start, f.quantity = first, many
      if request ~= nil and (
        request.fields["address"] ~= fields["address"] or request.fields["and_mask"] ~= fields["and_mask"] or
        request.fields["or_mask"] ~= fields["or_mask"]
      ) then echo_check(f, fields, request, echo) end
    end
  end
  handler.read_write_request = function(f, b)
    local fields = f.fields
    local first = fields["read_start"]
    local many = fields["read_quantity"]
    f.start, f.quantity = first, many
    if fields["read_quantity"] < 1 or fields["read_quantity"] > 125 then
      warn(f, range_text("read quantity", fields["read_quantity"], 1, 125))
    end
    if fields["write_quantity"] < 1 or fields["write_quantity"] > 121 then
      warn(f, range_text("write quantity", fields["write_quantity"], 1, 121))
    end
    if first + many > 65536 then warn(f, say("span", { first = first, last = first + many - 1 })) end
    if fields["write_start"] + fields["write_quantity"] > 65536 then
      warn(f, say("span", { first = fields["write_start"], last = fields["write_start"] + fields["write_quantity"] - 1 }))
    end
    local of = fields["write_quantity"]
    if of ~= nil and fields.byte_count ~= 0 + data_bytes(of, 2) then
      warn(f, say("count_write_quantity", { count = fields.byte_count, quantity = of }))
    end
    local count, most = floor(fields["byte_count"] / 2), fields["write_quantity"]
    if count > most then
      past_quantity(f, b, fields["values_at"] + 2 * most, 2 * (count - most), most, "past_write_quantity")
      count = most
    end
    f.registers = {
      b = b, first = fields["values_at"], count = count, start = fields["write_start"], shift = nil
    }
  end
  handler.fifo_request = function(f, b)
    local fields = f.fields
    local first = fields["address"]
    local many = nil
    f.start, f.quantity = first, many
  end
  handler.read_bits_response = function(f, b)
    local fields = f.fields
    local request = f.request
    if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
    local first = request and request.start
    local many = request and request.quantity
    if many == nil and fields.byte_count == 0 then many = 0 end
    f.start, f.quantity = first, many
    local of = request and request.quantity
    if of ~= nil and fields.byte_count ~= 0 + data_bytes(of, 0) then
      warn(f, say("count_asked_bits", { count = fields.byte_count, quantity = of }))
    elseif of ~= nil and of % 8 > 0 then
      local low = floor(2 ^ (of % 8))
      local unused = b[fields["status_at"] + fields.byte_count - 1] - b[fields["status_at"] + fields.byte_count - 1] % low
      if unused > 0 then warn(f, say("padding_bits", { quantity = of, mask = unused })) end
    end
    local count = 8 * fields["byte_count"]
    if many ~= nil and many < count then count = many end
    f.bits = { b = b, first = fields["status_at"], count = count, start = first, shift = nil }
  end
  handler.read_registers_response = function(f, b)
    local fields = f.fields
    local request = f.request
    if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
    local first = request and request.start
    local many = request and request.quantity
    if many == nil and fields.byte_count % 2 == 0 then many = floor(fields.byte_count / 2) end
    f.start, f.quantity = first, many
    local of = request and request.quantity
    if of ~= nil and fields.byte_count ~= 0 + data_bytes(of, 2) then
      warn(f, say("count_asked_registers", { count = fields.byte_count, quantity = of }))
    end
    if fields.byte_count % 2 == 1 then warn(f, say("odd_count", { count = fields.byte_count })) end
    f.registers = {
      b = b, first = fields["values_at"], count = floor(fields["byte_count"] / 2), start = first, shift = nil
    }
  end
  do
    local echo = lift.write_multiple_response.echo
    handler.write_multiple_response = function(f, b)
      local fields = f.fields
      local request = f.request
      if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
      local first = fields["start"]
      local many = fields["quantity"]
      f.start, f.quantity = first, many
      if request ~= nil and (
        request.fields["start"] ~= fields["start"] or request.fields["quantity"] ~= fields["quantity"]
      ) then echo_check(f, fields, request, echo) end
    end
  end
  do
    local parts = lift.read_file_response.parts
    handler.read_file_response = function(f, b)
      local fields = f.fields
      local request = f.request
      if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
      local first = nil
      local many = nil
      f.start, f.quantity = first, many
      local p, stop, index = fields["subresponses_at"], fields["subresponses_at"] + fields["byte_count"], 0
      local given = {}
      while p + 2 <= stop do
        local n = b[p + 0] - 1
        if n < 0 then break end
        if p + 2 + n - n % 2 > stop then break end
        index = index + 1
        local v = b[p + 1]
        if v ~= 6 then warn(f, range_text("sub-response " .. index .. "'s reference type", v, 6, 6)) end
        given[index] = b[p + 0]
        p = p + 2 + n - n % 2
      end
      if request ~= nil and request.fields["subrequests"] ~= nil then
        check_asked(f, parts, index, given, request.fields["subrequests"])
      end
    end
  end
  handler.fifo_response = function(f, b)
    local fields = f.fields
    local request = f.request
    if request ~= nil and request.fields == nil then request = nil end -- (its data did not parse)
    local first = request and request.start
    local many = nil
    f.start, f.quantity = first, many
    if fields["fifo_count"] > 31 then
      warn(f, say("above", { what = "FIFO count", value = fields["fifo_count"], high = 31 }))
    end
    local of = fields["fifo_count"]
    if of ~= nil and fields.byte_count ~= 2 + data_bytes(of, 2) then
      warn(f, say("count_fifo", { count = fields.byte_count, quantity = of }))
    end
  end
  return {
    request = {
      [1] = handler.read_request_read_bits, [2] = handler.read_request_read_bits,
      [3] = handler.read_request_read_registers, [4] = handler.read_request_read_registers,
      [5] = handler.write_single_coil, [6] = handler.write_single_register, [8] = special.diagnostics,
      [15] = handler.write_coils_request, [16] = handler.write_registers_request,
      [20] = handler.read_file_request, [21] = handler.write_file, [22] = handler.mask_write,
      [23] = handler.read_write_request, [24] = handler.fifo_request, [43] = special.mei_request
    },
    response = {
      [1] = handler.read_bits_response, [2] = handler.read_bits_response,
      [3] = handler.read_registers_response, [4] = handler.read_registers_response,
      [5] = handler.write_single_coil, [6] = handler.write_single_register, [8] = special.diagnostics,
      [15] = handler.write_multiple_response, [16] = handler.write_multiple_response,
      [17] = special.report_server_id_response, [20] = handler.read_file_response, [21] = handler.write_file,
      [22] = handler.mask_write, [23] = handler.read_registers_response, [24] = handler.fifo_response,
      [43] = special.mei_response
    },
  }
end
end
function DATA.info_forms(DECIMAL, DIAGNOSTICS, count_text, data_text, fifo_values, single_text, span_text, BY_NAME)
  local format = string.format
  local form = {} -- (by form; by code and kind too where its layouts place its fields apart)
  form.coil = function(f, b, base, last, st, device)
    local coil = b[base + 4] * 256 + b[base + 5]
    return span_text(f) .. (coil == 0xFF00 and " = ON" or coil == 0 and " = OFF" or format(" = 0x%04X", coil))
  end
  form.single = function(f, b, base, last, st, device)
    return span_text(f) .. single_text(f, st, device, b[base + 4] * 256 + b[base + 5])
  end
  form.diagnostics = function(f, b, base, last, st, device)
    local subfunction = b[base + 2] * 256 + b[base + 3]
    return format("%02X", subfunction) .. "h "
      .. (f.subfunction_text or DIAGNOSTICS[subfunction] or "unknown sub-function")
      .. data_text(b, base + 4, last)
  end
  form.mask = function(f, b, base, last, st, device)
    return DECIMAL[b[base + 2] * 256 + b[base + 3]] .. " AND 0x"
      .. format("%04X", b[base + 4] * 256 + b[base + 5]) .. " OR 0x"
      .. format("%04X", b[base + 6] * 256 + b[base + 7])
  end
  form.read_write = function(f, b, base, last, st, device)
    return "read " .. span_text(f) .. ", write "
      .. span_text({ start = b[base + 6] * 256 + b[base + 7], quantity = b[base + 8] * 256 + b[base + 9], span_label = f.write_span_label })
  end
  form.pointer = function(f, b, base, last, st, device)
    return "pointer " .. DECIMAL[b[base + 2] * 256 + b[base + 3]]
  end
  form.status = function(f, b, base, last, st, device)
    return "status 0x" .. format("%02X", b[base + 2])
  end
  form.counter = function(f, b, base, last, st, device)
    return "status 0x" .. format("%04X", b[base + 2] * 256 + b[base + 3]) .. ", "
      .. count_text(b[base + 4] * 256 + b[base + 5], "event")
  end
  form.event_log = function(f, b, base, last, st, device)
    return "status 0x" .. format("%04X", b[base + 3] * 256 + b[base + 4]) .. ", "
      .. count_text(b[base + 5] * 256 + b[base + 6], "event") .. ", "
      .. count_text(b[base + 7] * 256 + b[base + 8], "message")
  end
  form.written = function(f, b, base, last, st, device)
    return span_text(f) .. " written"
  end
  form.fifo = function(f, b, base, last, st, device)
    local fifo_count = b[base + 4] * 256 + b[base + 5]
    return count_text(fifo_count, "value") .. fifo_values(b, fifo_count, base + 6, last)
  end
  return {
    [5] = { request = form.coil, response = form.coil },
    [6] = { request = form.single, response = form.single },
    [7] = { response = form.status },
    [8] = { request = form.diagnostics, response = form.diagnostics },
    [11] = { response = form.counter },
    [12] = { response = form.event_log },
    [15] = { response = form.written },
    [16] = { response = form.written },
    [17] = { request = BY_NAME.report_server_id, response = BY_NAME.report_server_id },
    [20] = { request = BY_NAME.file_record, response = BY_NAME.file_record },
    [21] = { request = BY_NAME.file_record, response = BY_NAME.file_record },
    [22] = { request = form.mask, response = form.mask },
    [23] = { request = form.read_write },
    [24] = { request = form.pointer, response = form.fifo },
    [43] = { request = BY_NAME.mei, response = BY_NAME.mei },
  }
end
DATA.info_naming = {
  [6] = {
    ["request"] = true,
    ["response"] = true,
  },
}
DATA.field_places = {
  read_request = { start = { at = 2, size = 2 }, quantity = { at = 4, size = 2 } },
  read_bits_response = { byte_count = { at = 2, size = 1 }, status = { at = 3 } },
  read_registers_response = { byte_count = { at = 2, size = 1 }, values = { at = 3 } },
  write_single = { address = { at = 2, size = 2 }, value = { at = 4, size = 2 } },
  empty = {},
  diagnostics = { subfunction = { at = 2, size = 2 }, data = { at = 4 } },
  write_coils_request = {
    start = { at = 2, size = 2 }, quantity = { at = 4, size = 2 }, byte_count = { at = 6, size = 1 },
    status = { at = 7 }
  },
  write_registers_request = {
    start = { at = 2, size = 2 }, quantity = { at = 4, size = 2 }, byte_count = { at = 6, size = 1 },
    values = { at = 7 }
  },
  write_multiple_response = { start = { at = 2, size = 2 }, quantity = { at = 4, size = 2 } },
  exception_status_response = { status = { at = 2, size = 1 } },
  comm_event_counter_response = { status = { at = 2, size = 2 }, event_count = { at = 4, size = 2 } },
  mask_write = {
    address = { at = 2, size = 2 }, and_mask = { at = 4, size = 2 }, or_mask = { at = 6, size = 2 }
  },
  read_write_request = {
    read_start = { at = 2, size = 2 }, read_quantity = { at = 4, size = 2 },
    write_start = { at = 6, size = 2 }, write_quantity = { at = 8, size = 2 },
    byte_count = { at = 10, size = 1 }, values = { at = 11 }
  },
  fifo_request = { address = { at = 2, size = 2 } },
  fifo_response = {
    byte_count = { at = 2, size = 2 }, fifo_count = { at = 4, size = 2 }, values = { at = 6 }
  },
  exception = { exception_code = { at = 2, size = 1 } },
  raw = { data = { at = 2 } },
  comm_event_log_response = {
    byte_count = { at = 2, size = 1 }, status = { at = 3, size = 2 }, event_count = { at = 5, size = 2 },
    message_count = { at = 7, size = 2 }, events = { at = 9 }
  },
  report_server_id_response = { byte_count = { at = 2, size = 1 }, server_id = { at = 3 } },
  read_file_request = { byte_count = { at = 2, size = 1 }, subrequests = { at = 3 } },
  read_file_response = { byte_count = { at = 2, size = 1 }, subresponses = { at = 3 } },
  write_file = { byte_count = { at = 2, size = 1 }, records = { at = 3 } },
  mei_request = { mei_type = { at = 2, size = 1 }, body = { at = 3 } },
  mei_response = { mei_type = { at = 2, size = 1 }, body = { at = 3 } },
}
DATA.bit_windows = { [1] = true, [2] = true, [5] = true, [15] = true }
DATA.event_bits = {
  [128] = {
    { 2, ".... ..%d. = Communication Error: %d" },
    { 16, "...%d .... = Character Overrun: %d" },
    { 32, "..%d. .... = Currently in Listen Only Mode: %d" },
    { 64, ".%d.. .... = Broadcast Received: %d" },
  },
  [64] = {
    { 1, ".... ...%d = Read Exception Sent: %d" },
    { 2, ".... ..%d. = Slave Abort Exception Sent: %d" },
    { 4, ".... .%d.. = Slave Busy Exception Sent: %d" },
    { 8, ".... %d... = Slave Program NAK Exception Sent: %d" },
    { 16, "...%d .... = Write Timeout Error Occurred: %d" },
    { 32, "..%d. .... = Currently in Listen Only Mode: %d" },
  },
}
DATA.comm_events = {
  [0] = { "Initiated Communication Restart", 0 },
  [1] = { "Unknown Event", 0 },
  [2] = { "Unknown Event", 0 },
  [3] = { "Unknown Event", 0 },
  [4] = { "Entered Listen Only Mode", 0 },
  [5] = { "Unknown Event", 0 },
  [6] = { "Unknown Event", 0 },
  [7] = { "Unknown Event", 0 },
  [8] = { "Unknown Event", 0 },
  [9] = { "Unknown Event", 0 },
  [10] = { "Unknown Event", 0 },
  [11] = { "Unknown Event", 0 },
  [12] = { "Unknown Event", 0 },
  [13] = { "Unknown Event", 0 },
  [14] = { "Unknown Event", 0 },
  [15] = { "Unknown Event", 0 },
  [16] = { "Unknown Event", 0 },
  [17] = { "Unknown Event", 0 },
  [18] = { "Unknown Event", 0 },
  [19] = { "Unknown Event", 0 },
  [20] = { "Unknown Event", 0 },
  [21] = { "Unknown Event", 0 },
  [22] = { "Unknown Event", 0 },
  [23] = { "Unknown Event", 0 },
  [24] = { "Unknown Event", 0 },
  [25] = { "Unknown Event", 0 },
  [26] = { "Unknown Event", 0 },
  [27] = { "Unknown Event", 0 },
  [28] = { "Unknown Event", 0 },
  [29] = { "Unknown Event", 0 },
  [30] = { "Unknown Event", 0 },
  [31] = { "Unknown Event", 0 },
  [32] = { "Unknown Event", 0 },
  [33] = { "Unknown Event", 0 },
  [34] = { "Unknown Event", 0 },
  [35] = { "Unknown Event", 0 },
  [36] = { "Unknown Event", 0 },
  [37] = { "Unknown Event", 0 },
  [38] = { "Unknown Event", 0 },
  [39] = { "Unknown Event", 0 },
  [40] = { "Unknown Event", 0 },
  [41] = { "Unknown Event", 0 },
  [42] = { "Unknown Event", 0 },
  [43] = { "Unknown Event", 0 },
  [44] = { "Unknown Event", 0 },
  [45] = { "Unknown Event", 0 },
  [46] = { "Unknown Event", 0 },
  [47] = { "Unknown Event", 0 },
  [48] = { "Unknown Event", 0 },
  [49] = { "Unknown Event", 0 },
  [50] = { "Unknown Event", 0 },
  [51] = { "Unknown Event", 0 },
  [52] = { "Unknown Event", 0 },
  [53] = { "Unknown Event", 0 },
  [54] = { "Unknown Event", 0 },
  [55] = { "Unknown Event", 0 },
  [56] = { "Unknown Event", 0 },
  [57] = { "Unknown Event", 0 },
  [58] = { "Unknown Event", 0 },
  [59] = { "Unknown Event", 0 },
  [60] = { "Unknown Event", 0 },
  [61] = { "Unknown Event", 0 },
  [62] = { "Unknown Event", 0 },
  [63] = { "Unknown Event", 0 },
  [64] = { "Send Event", 64 },
  [65] = { "Send Event", 64 },
  [66] = { "Send Event", 64 },
  [67] = { "Send Event", 64 },
  [68] = { "Send Event", 64 },
  [69] = { "Send Event", 64 },
  [70] = { "Send Event", 64 },
  [71] = { "Send Event", 64 },
  [72] = { "Send Event", 64 },
  [73] = { "Send Event", 64 },
  [74] = { "Send Event", 64 },
  [75] = { "Send Event", 64 },
  [76] = { "Send Event", 64 },
  [77] = { "Send Event", 64 },
  [78] = { "Send Event", 64 },
  [79] = { "Send Event", 64 },
  [80] = { "Send Event", 64 },
  [81] = { "Send Event", 64 },
  [82] = { "Send Event", 64 },
  [83] = { "Send Event", 64 },
  [84] = { "Send Event", 64 },
  [85] = { "Send Event", 64 },
  [86] = { "Send Event", 64 },
  [87] = { "Send Event", 64 },
  [88] = { "Send Event", 64 },
  [89] = { "Send Event", 64 },
  [90] = { "Send Event", 64 },
  [91] = { "Send Event", 64 },
  [92] = { "Send Event", 64 },
  [93] = { "Send Event", 64 },
  [94] = { "Send Event", 64 },
  [95] = { "Send Event", 64 },
  [96] = { "Send Event", 64 },
  [97] = { "Send Event", 64 },
  [98] = { "Send Event", 64 },
  [99] = { "Send Event", 64 },
  [100] = { "Send Event", 64 },
  [101] = { "Send Event", 64 },
  [102] = { "Send Event", 64 },
  [103] = { "Send Event", 64 },
  [104] = { "Send Event", 64 },
  [105] = { "Send Event", 64 },
  [106] = { "Send Event", 64 },
  [107] = { "Send Event", 64 },
  [108] = { "Send Event", 64 },
  [109] = { "Send Event", 64 },
  [110] = { "Send Event", 64 },
  [111] = { "Send Event", 64 },
  [112] = { "Send Event", 64 },
  [113] = { "Send Event", 64 },
  [114] = { "Send Event", 64 },
  [115] = { "Send Event", 64 },
  [116] = { "Send Event", 64 },
  [117] = { "Send Event", 64 },
  [118] = { "Send Event", 64 },
  [119] = { "Send Event", 64 },
  [120] = { "Send Event", 64 },
  [121] = { "Send Event", 64 },
  [122] = { "Send Event", 64 },
  [123] = { "Send Event", 64 },
  [124] = { "Send Event", 64 },
  [125] = { "Send Event", 64 },
  [126] = { "Send Event", 64 },
  [127] = { "Send Event", 64 },
  [128] = { "Receive Event", 128 },
  [129] = { "Receive Event", 128 },
  [130] = { "Receive Event", 128 },
  [131] = { "Receive Event", 128 },
  [132] = { "Receive Event", 128 },
  [133] = { "Receive Event", 128 },
  [134] = { "Receive Event", 128 },
  [135] = { "Receive Event", 128 },
  [136] = { "Receive Event", 128 },
  [137] = { "Receive Event", 128 },
  [138] = { "Receive Event", 128 },
  [139] = { "Receive Event", 128 },
  [140] = { "Receive Event", 128 },
  [141] = { "Receive Event", 128 },
  [142] = { "Receive Event", 128 },
  [143] = { "Receive Event", 128 },
  [144] = { "Receive Event", 128 },
  [145] = { "Receive Event", 128 },
  [146] = { "Receive Event", 128 },
  [147] = { "Receive Event", 128 },
  [148] = { "Receive Event", 128 },
  [149] = { "Receive Event", 128 },
  [150] = { "Receive Event", 128 },
  [151] = { "Receive Event", 128 },
  [152] = { "Receive Event", 128 },
  [153] = { "Receive Event", 128 },
  [154] = { "Receive Event", 128 },
  [155] = { "Receive Event", 128 },
  [156] = { "Receive Event", 128 },
  [157] = { "Receive Event", 128 },
  [158] = { "Receive Event", 128 },
  [159] = { "Receive Event", 128 },
  [160] = { "Receive Event", 128 },
  [161] = { "Receive Event", 128 },
  [162] = { "Receive Event", 128 },
  [163] = { "Receive Event", 128 },
  [164] = { "Receive Event", 128 },
  [165] = { "Receive Event", 128 },
  [166] = { "Receive Event", 128 },
  [167] = { "Receive Event", 128 },
  [168] = { "Receive Event", 128 },
  [169] = { "Receive Event", 128 },
  [170] = { "Receive Event", 128 },
  [171] = { "Receive Event", 128 },
  [172] = { "Receive Event", 128 },
  [173] = { "Receive Event", 128 },
  [174] = { "Receive Event", 128 },
  [175] = { "Receive Event", 128 },
  [176] = { "Receive Event", 128 },
  [177] = { "Receive Event", 128 },
  [178] = { "Receive Event", 128 },
  [179] = { "Receive Event", 128 },
  [180] = { "Receive Event", 128 },
  [181] = { "Receive Event", 128 },
  [182] = { "Receive Event", 128 },
  [183] = { "Receive Event", 128 },
  [184] = { "Receive Event", 128 },
  [185] = { "Receive Event", 128 },
  [186] = { "Receive Event", 128 },
  [187] = { "Receive Event", 128 },
  [188] = { "Receive Event", 128 },
  [189] = { "Receive Event", 128 },
  [190] = { "Receive Event", 128 },
  [191] = { "Receive Event", 128 },
  [192] = { "Receive Event", 128 },
  [193] = { "Receive Event", 128 },
  [194] = { "Receive Event", 128 },
  [195] = { "Receive Event", 128 },
  [196] = { "Receive Event", 128 },
  [197] = { "Receive Event", 128 },
  [198] = { "Receive Event", 128 },
  [199] = { "Receive Event", 128 },
  [200] = { "Receive Event", 128 },
  [201] = { "Receive Event", 128 },
  [202] = { "Receive Event", 128 },
  [203] = { "Receive Event", 128 },
  [204] = { "Receive Event", 128 },
  [205] = { "Receive Event", 128 },
  [206] = { "Receive Event", 128 },
  [207] = { "Receive Event", 128 },
  [208] = { "Receive Event", 128 },
  [209] = { "Receive Event", 128 },
  [210] = { "Receive Event", 128 },
  [211] = { "Receive Event", 128 },
  [212] = { "Receive Event", 128 },
  [213] = { "Receive Event", 128 },
  [214] = { "Receive Event", 128 },
  [215] = { "Receive Event", 128 },
  [216] = { "Receive Event", 128 },
  [217] = { "Receive Event", 128 },
  [218] = { "Receive Event", 128 },
  [219] = { "Receive Event", 128 },
  [220] = { "Receive Event", 128 },
  [221] = { "Receive Event", 128 },
  [222] = { "Receive Event", 128 },
  [223] = { "Receive Event", 128 },
  [224] = { "Receive Event", 128 },
  [225] = { "Receive Event", 128 },
  [226] = { "Receive Event", 128 },
  [227] = { "Receive Event", 128 },
  [228] = { "Receive Event", 128 },
  [229] = { "Receive Event", 128 },
  [230] = { "Receive Event", 128 },
  [231] = { "Receive Event", 128 },
  [232] = { "Receive Event", 128 },
  [233] = { "Receive Event", 128 },
  [234] = { "Receive Event", 128 },
  [235] = { "Receive Event", 128 },
  [236] = { "Receive Event", 128 },
  [237] = { "Receive Event", 128 },
  [238] = { "Receive Event", 128 },
  [239] = { "Receive Event", 128 },
  [240] = { "Receive Event", 128 },
  [241] = { "Receive Event", 128 },
  [242] = { "Receive Event", 128 },
  [243] = { "Receive Event", 128 },
  [244] = { "Receive Event", 128 },
  [245] = { "Receive Event", 128 },
  [246] = { "Receive Event", 128 },
  [247] = { "Receive Event", 128 },
  [248] = { "Receive Event", 128 },
  [249] = { "Receive Event", 128 },
  [250] = { "Receive Event", 128 },
  [251] = { "Receive Event", 128 },
  [252] = { "Receive Event", 128 },
  [253] = { "Receive Event", 128 },
  [254] = { "Receive Event", 128 },
  [255] = { "Receive Event", 128 },
}
-- END GENERATED DATA

-- ---- vw3.crc: lua/src/crc.lua ----
package.preload["vw3.crc"] = function(...)
-- vw3.crc: CRC-16/MODBUS on table lookups (no bitwise operators: the same on Lua 5.2 and 5.4).
-- Mirrors dissector/protocol/crc.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.crc"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, collectgarbage, math, pcall, setmetatable = DATA, collectgarbage, math, pcall, setmetatable
local string, table = string, table

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
M.concat, M.crc16, M.crc_lengths, M.crc_ok_at, M.crc_scan = concat, crc16, crc_lengths, crc_ok_at, crc_scan
M.crc_step, M.crc_string_ok, M.floor, M.format, M.made_once = crc_step, crc_string_ok, floor, format, made_once
M.scanned = scanned
end

-- ---- vw3.layouts: lua/src/layouts.lua ----
package.preload["vw3.layouts"] = function(...)
-- vw3.layouts: the length rules of every function code, and which layouts a slave's code may have.
-- Mirrors dissector/protocol/table.py (the rules codegen writes into DATA.protocol).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.layouts"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, concat, crc_ok_at, floor, math, pairs, string = DATA, concat, crc_ok_at, floor, math, pairs, string
local table = table

-- ---------------------------------------------------------------------------------------------------
-- Framing (dissector/framing/rtu.py): length rules per function code and direction, CRC to confirm.
local FRAMING = DATA.framing
local MAX_ADU, MIN_ADU, MAX_SLAVE = FRAMING.max_adu, FRAMING.min_adu, FRAMING.max_slave
local NOISE_ITEM_MAX = FRAMING.noise_item_max
local NEED, NONE = -1, 0
local REQUEST, RESPONSE, EXCEPTION, NOISE = "request", "response", "exception", "noise"

-- A length rule returns the frame's length, NEED, or NONE; or (minimum, true) when the layout gives no
-- length and the frame is to be found by scanning for a CRC from that minimum (rules.Scan).
local function fixed(length)
  return function() return length end
end

-- A length by a count field (table.Counted): `extra` + the byte (width 1) or word (2) at `position`.
local function counted(position, extra, width)
  if width == 1 then -- (a rule per width: a flood weighs these at every byte, three times)
    return function(b, i, n)
      if i + position >= n then return NEED end
      return extra + b[i + position]
    end
  end
  return function(b, i, n)
    if i + position + 1 >= n then return NEED end
    return extra + b[i + position] * 256 + b[i + position + 1]
  end
end

local function scan(minimum)
  return function() return minimum, true end
end

-- The rule a field of the frame picks (table.Select, rules.py _select): `chosen` where the byte (width 1)
-- or word (2) at `position` is `value`, else `otherwise` (the field read in place, not by a count rule's call).
local make_rule
local function select(position, width, value, chosen, otherwise)
  chosen, otherwise = make_rule(chosen), make_rule(otherwise)
  return function(b, i, n)
    if i + position + width - 1 >= n then return NEED end
    local found = width == 2 and b[i + position] * 256 + b[i + position + 1] or b[i + position]
    if found == value then return chosen(b, i, n) end
    return otherwise(b, i, n)
  end
end

-- Walk the FC43/14 object list: its count at `position`, then (id, length, value) per object from `start`.
-- Where the walk does not end in a valid CRC (past the bytes there or an RTU frame, or its CRC fails), a CRC
-- scan from the list's start (start + 2, rules.py _mei_objects), with the walk's length (NEED: past the
-- bytes) as a third value: the framer's damaged frame or answer cut by the end of the capture; past the bytes,
-- a fourth: the index of the byte it stopped short of (Scan.wanted: till it comes, lua/src/rtu.lua ends_record's
-- answer holds).
local function mei_objects(position, start)
  local minimum = start + 2
  return function(b, i, n)
    if i + position >= n then return NEED end
    local stop = start
    for _ = 1, b[i + position] do
      if i + stop + 1 >= n then return minimum, true, NEED, stop + 1 end
      stop = stop + 2 + b[i + stop + 1]
      if stop > MAX_ADU then return minimum, true, NONE end
    end
    local length = stop + 2
    if i + length <= n and crc_ok_at(b, i, length) then return length end
    return minimum, true, length
  end
end

-- The bytes of `items` values of `unit` bytes each (0: bits, 8 a byte): rules.data_bytes, the one byte formula.
local function data_bytes(items, unit) return unit > 0 and items * unit or floor((items + 7) / 8) end

-- A request's length by its quantity (a word at `position`): `extra` + its data bytes (data_bytes by `unit`);
-- NONE where its byte count (`count_extra` + the byte at `count_at`) agrees (rules.py quantity_rule).
local function by_quantity(position, extra, unit, count_at, count_extra)
  return function(b, i, n)
    if i + position + 1 >= n or i + count_at >= n then return NEED end
    local items = b[i + position] * 256 + b[i + position + 1]
    local length = extra + (unit > 0 and items * unit or floor((items + 7) / 8)) -- (data_bytes, inline)
    if length == count_extra + b[i + count_at] then return NONE end
    return length
  end
end

local makers = {
  fixed = fixed, counted = counted,
  scan = scan, select = select, mei_objects = mei_objects, by_quantity = by_quantity,
}
function make_rule(spec) return makers[spec[1]](spec[2], spec[3], spec[4], spec[5], spec[6]) end

-- Interpretations in the order they are tried (rules.py REQUEST_FIRST, RESPONSE_FIRST): request first,
-- unless a response is expected; an exception's code (code + 128), the exception. No entry: no frame
-- starts with the code. Each code's length rules (request, response, by quantity): generated from
-- dissector/protocol/table.py.
local AS_REQUEST, AS_RESPONSE = {}, {}
local AS_EXCEPTION = { { EXCEPTION, make_rule(DATA.protocol.exception_rule) } }
for code, rules in pairs(DATA.protocol.rules) do
  local request, response = make_rule(rules[1]), make_rule(rules[2])
  local by_quantity = rules[3] and { REQUEST, make_rule(rules[3]) } -- (the quantity's length, tried last)
  AS_REQUEST[code] = { { REQUEST, request }, { RESPONSE, response }, by_quantity }
  AS_RESPONSE[code] = { { RESPONSE, response }, { REQUEST, request }, by_quantity }
  AS_REQUEST[code + 128] = AS_EXCEPTION -- (no answer is awaited with an exception's code)
end
local NO_INTERPRETATION = {}

-- A Lua string of count bytes from a 0-based (first) or 1-based byte table.
local function string_of(b, first, count)
  if count <= 200 then return string.char(table.unpack(b, first, first + count - 1)) end
  local parts = {}
  for k = 0, count - 1, 200 do -- (200 at a time: unpack puts them on the stack, string.char's arguments)
    parts[#parts + 1] = string.char(table.unpack(b, first + k, first + math.min(k + 200, count) - 1))
  end
  return concat(parts)
end

-- What a frame holds of the bytes the spec has an answer echo (DATA.pairing.echo: FC8's sub-function), as a
-- string (fewer bytes where the frame ends first); nil: none. The framer awaits them in the answer (st.echo:
-- await_echo), the pairing pairs by them (vw3.pairing's same_echo: a request keeps them, f.echoed, as its
-- byte table is gone when its answer comes).
local ECHO_CODES = DATA.pairing.echo
local function echoed(f)
  local count = ECHO_CODES[f.fn]
  if count == nil then return nil end
  if count > f.data_len then count = f.data_len end
  return string_of(f.b, f.data_at, count)
end

-- Do the bytes from b[i] (up to b[n - 1]) repeat the echo awaited (echo.bytes), as far as they have come?
local function echo_at(echo, b, i, n)
  local bytes = echo.bytes
  for k = 1, #bytes do
    local at = i + 1 + k
    if at >= n then return true end
    if b[at] ~= bytes:byte(k) then return false end
  end
  return true
end

-- Do the bytes at b[i] begin the answer awaited (rules.py Awaiting._awaited): its slave and function (an exception's
-- too) and, for a normal answer, what the spec has it repeat of the request (st.echo, kept by await_echo:
-- DATA.pairing.echo, an FC8 sub-function)? An FC8 frame that does not is the master's next request.
local function awaited(st, b, i, n)
  local code = b[i + 1]
  if st.expect ~= b[i] * 256 + code % 128 then return false end
  local echo = st.echo
  return echo == nil or echo.expect ~= st.expect or code >= 128 or echo_at(echo, b, i, n)
end

-- What a frame the line bounds is, whatever length its layout takes (rules.py Awaiting._bounded_kind: the RTU framer's
-- take_bounded, an ASCII line with a good LRC): an exception by its function, else the answer awaited or a request.
local function bounded_kind(st, b, i, n)
  return b[i + 1] >= 128 and EXCEPTION or (awaited(st, b, i, n) and RESPONSE or REQUEST)
end

-- The interpretations at b[i], likeliest first. Without the bytes (b nil: feed_whole, classify_ascii) an
-- echo awaited cannot be weighed: none then, and the general path frames the record.
local function interpretations(st, slave, code, b, i, n)
  if st.expect == slave * 256 + code then
    local echo = st.echo
    if echo ~= nil and echo.expect == st.expect then
      if b == nil then return NO_INTERPRETATION end
      if not echo_at(echo, b, i, n) then return AS_REQUEST[code] or NO_INTERPRETATION end
    end
    return AS_RESPONSE[code] or NO_INTERPRETATION
  end
  return AS_REQUEST[code] or NO_INTERPRETATION
end

-- What the answer awaited after `frame` must repeat of it (st.echo: its echoed bytes, an FC8 sub-function),
-- kept wherever a frame of a code with an echo (ECHO_CODES) sets the expectation (vw3.stream's expect_after,
-- the quick lanes), with the expectation it was kept for: a later request of another code, which does not
-- call this, leaves it aside (echo.expect: awaited).
-- A frame too short for it keeps what it holds (rules.py echoed): the answer is weighed by those bytes.
local function await_echo(st, frame)
  st.echo = nil
  if st.expect ~= nil then st.echo = { expect = st.expect, bytes = echoed(frame) } end
end

-- Can a frame start with this function code (any address before it: rules.py _POSSIBLE_START)?
local function possible_start(code)
  return AS_REQUEST[code] ~= nil
end
M.ECHO_CODES, M.EXCEPTION, M.FRAMING, M.MAX_ADU, M.MAX_SLAVE = ECHO_CODES, EXCEPTION, FRAMING, MAX_ADU, MAX_SLAVE
M.MIN_ADU, M.NEED, M.NOISE, M.NOISE_ITEM_MAX, M.NONE = MIN_ADU, NEED, NOISE, NOISE_ITEM_MAX, NONE
M.NO_INTERPRETATION, M.REQUEST, M.RESPONSE, M.await_echo = NO_INTERPRETATION, REQUEST, RESPONSE, await_echo
M.awaited, M.bounded_kind, M.counted, M.data_bytes, M.echoed = awaited, bounded_kind, counted, data_bytes, echoed
M.interpretations, M.possible_start, M.string_of = interpretations, possible_start, string_of
end

-- ---- vw3.stream: lua/src/stream.lua ----
package.preload["vw3.stream"] = function(...)
-- vw3.stream: the byte stream the framers read: record boundaries and times, noise runs, the glitch rule.
-- Mirrors dissector/framing/stream.py, dissector/framing/evidence.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.stream"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, ECHO_CODES, FRAMING, MAX_ADU, MAX_SLAVE = DATA, ECHO_CODES, FRAMING, MAX_ADU, MAX_SLAVE
local MIN_ADU, NEED, NOISE, NOISE_ITEM_MAX, REQUEST = MIN_ADU, NEED, NOISE, NOISE_ITEM_MAX, REQUEST
local RESPONSE, await_echo, crc_string_ok, data_bytes = RESPONSE, await_echo, crc_string_ok, data_bytes
local format, ipairs, math, string, table = format, ipairs, math, string, table

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
M.GLITCH, M.NS, M.REPEAT_PROBE, M.TOO_SHORT, M.add_noise = GLITCH, NS, REPEAT_PROBE, TOO_SHORT, add_noise
M.add_skipped, M.await_answer, M.awaits_answer = add_skipped, await_answer, awaits_answer
M.boundary_at, M.cut_reason, M.cut_stream, M.drop_first = boundary_at, cut_reason, cut_stream, drop_first
M.emit, M.expect_after, M.first_above, M.first_after = emit, expect_after, first_above, first_after
M.flush_noise, M.lane, M.no_frame, M.not_the_answer = flush_noise, lane, no_frame, not_the_answer
M.part_reason, M.plausible_request, M.record_start = part_reason, plausible_request, record_start
M.repeats, M.sent_in, M.silence_after, M.silent_at_end = repeats, sent_in, silence_after, silent_at_end
M.silent_before, M.time_at, M.whole_crc_good = silent_before, time_at, whole_crc_good
end

-- ---- vw3.rtu: lua/src/rtu.lua ----
package.preload["vw3.rtu"] = function(...)
-- vw3.rtu: RTU framing: frames by their length rules and CRC, damaged frames, CRC scans, the line's evidence.
-- Mirrors dissector/framing/rtu.py, dissector/framing/reach.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.rtu"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, EXCEPTION, FRAMING, GLITCH, MAX_ADU, MAX_SLAVE = DATA, EXCEPTION, FRAMING, GLITCH, MAX_ADU, MAX_SLAVE
local MIN_ADU, NEED, NOISE_ITEM_MAX, NONE = MIN_ADU, NEED, NOISE_ITEM_MAX, NONE
local NO_INTERPRETATION, REPEAT_PROBE, REQUEST, RESPONSE = NO_INTERPRETATION, REPEAT_PROBE, REQUEST, RESPONSE
local TOO_SHORT, add_noise, add_skipped, awaited = TOO_SHORT, add_noise, add_skipped, awaited
local boundary_at, bounded_kind, counted, crc16 = boundary_at, bounded_kind, counted, crc16
local crc_lengths, crc_ok_at, crc_scan, cut_reason, emit = crc_lengths, crc_ok_at, crc_scan, cut_reason, emit
local first_above, first_after, interpretations, math = first_above, first_after, interpretations, math
local no_frame, not_the_answer, plausible_request = no_frame, not_the_answer, plausible_request
local possible_start, record_start, repeats, scanned = possible_start, record_start, repeats, scanned
local silence_after, table, time_at = silence_after, table, time_at
local GLITCH_ADDRESSES, GLITCH_SKIP, GLITCHY_AFTER = FRAMING.glitch_addresses, FRAMING.glitch_skip, FRAMING.glitchy_after
local MAX_COUNTED = FRAMING.max_counted -- (a length rule's frame over MAX_ADU: a good CRC only, warned: rules.py)

-- Does a layout at i check out and end where its record does (a code without a length rule: its CRC checks at
-- the record's end)? The source says a frame ends there: a glitch-byte reading of b[i] before a longer frame
-- crossing that end is not waited for, which in a single pass (tshark without -2) held every later record.
-- Second, the buffer length up to which more bytes cannot change the answer (reach.py _record_end's `until`): n + 1
-- for a rule that needs more bytes, a frame ending at n, a scan with no record end after i or an echo not all come;
-- a reading's end past n; the byte an FC43 object walk stopped short of (its fourth value, `wanted`), past it.
local function ends_record(s, b, i, n)
  local slave, code = b[i], b[i + 1]
  local list = interpretations(s, slave, code, b, i, n)
  local holds = (s.echo ~= nil and s.expect == slave * 256 + code and i + 1 + #s.echo.bytes >= n) and n + 1 or math.huge
  for index = 1, #list do
    local length, is_scan, walk, wanted = list[index][2](b, i, n)
    if length == NEED then holds = math.min(holds, n + 1) end
    if walk == NEED then holds = math.min(holds, i + (wanted or n - i) + 1)
    elseif walk ~= nil and i + walk > n then holds = math.min(holds, i + walk) end
    if is_scan then -- (reach.py _record_end: the record's length, from the scan's minimum on)
      local stop = first_after(s, s.boundaries, i, n) -- (the first record end after i)
      if stop == nil then holds = math.min(holds, n + 1) end
      length = stop ~= nil and stop - i >= length and stop - i or 0
    end
    if length >= MIN_ADU and length <= (is_scan and MAX_ADU or MAX_COUNTED) then
      if i + length >= n then holds = math.min(holds, i + length > n and i + length or n + 1) end
      if i + length <= n and boundary_at(s, i + length) and crc_ok_at(b, i, length) then return true, holds end
    end
  end
  return false, holds
end

-- The record ends' answers to ends_record for one stream and state (the answer awaited, its echo: reach.py EndAnswers):
-- `answered` by stream offset, `trues` those true (ascending), `expiry` by the stream end at which they may change the
-- offsets to ask again, low .. high the span whose every record end is answered (one-byte records: 250 a byte).
local ends = { count = math.huge }

local function answer_end(s, b, offset, n)
  local answer, holds = ends_record(s, b, offset - s.base, n)
  local trues, expiry = ends.trues, ends.expiry
  local at = first_above(trues, offset - 1, 1)
  if answer and trues[at] ~= offset then table.insert(trues, at, offset)
  elseif not answer and trues[at] == offset then table.remove(trues, at) end
  if not ends.answered[offset] then ends.answered[offset], ends.count = true, ends.count + 1 end
  local stop = s.base + holds -- (math.huge: never asked again)
  expiry[stop] = expiry[stop] or {}
  table.insert(expiry[stop], offset)
end

-- Answer the record ends from low up to before high not answered yet.
local function answer_ends(s, b, low, high, n)
  local boundaries = s.boundaries
  for index = first_above(boundaries, low - 1, 1), #boundaries do
    local offset = boundaries[index]
    if offset >= high then return end
    if not ends.answered[offset] then answer_end(s, b, offset, n) end
  end
end

-- Where a CRC scan from i stops (reach.py _framed_reach): the first record after i that is a frame of its own, else
-- n. A scan across it read noise and that frame as one frame, and waited for bytes past it in one pass.
local function framed_reach(s, b, i, n)
  local base = s.base
  local last, low, high = base + n, base + i + 1, base + math.min(n - MIN_ADU + 1, i + MAX_ADU)
  local ahead = s.boundaries[first_above(s.boundaries, base + i, 1)]
  if ahead == nil or ahead >= high then return n end -- (no record end to weigh: a record's own frame, mostly)
  local known = ends
  if known.s ~= s or known.expect ~= s.expect or known.echo ~= s.echo or last < known.last
      or last > known.last + MAX_ADU or known.count > 4 * MAX_ADU then
    known = { s = s, expect = s.expect, echo = s.echo, last = last, answered = {}, trues = {}, expiry = {},
      count = 0, low = low, high = low }
    ends = known
  end
  for stop = known.last + 1, last do -- (answers the bytes come since may change: asked again)
    local list = known.expiry[stop]
    known.expiry[stop] = nil
    for index = 1, list and #list or 0 do
      if list[index] > base then answer_end(s, b, list[index], n) else known.answered[list[index]] = nil end
    end
  end
  known.last = last
  if high > low then
    if low > known.high or high < known.low then known.low, known.high = low, low end -- (a span apart: anew)
    if low < known.low then answer_ends(s, b, low, known.low, n) end -- (the record ends before it, after it)
    if high > known.high then answer_ends(s, b, known.high, high, n) end
    known.low, known.high = low < known.low and low or known.low, high > known.high and high or known.high
  end
  local first = known.trues[first_above(known.trues, low - 1, 1)]
  return first ~= nil and first < high and first - base or n
end

-- Would a reading at i of `length` bytes (NEED: more than there are) swallow a record that is a frame of its own,
-- the first after i (framed_reach) starting inside it (reach.py _crosses_framed_record)? Then it is none, its bytes
-- come or not: waiting for them (a long answer read from noise, an FC23 request's byte count) held every later
-- record in one pass.
local function crosses_framed_record(s, b, i, length, n)
  return framed_reach(s, b, i, n) < (length == NEED and n or math.min(n, i + length))
end

-- Does an intact frame start at i? true, false, or nil when more bytes are needed to know (final: none
-- will come). With scan false, only layouts with a length rule count (rtu.py _valid_frame_at).
local function frame_at(s, b, i, n, final, scan)
  if n - i < MIN_ADU then
    if final then return i == n end
    return nil
  end
  local found = false -- (nil: a CRC scan found nothing yet, but a longer frame may still arrive)
  local list = interpretations(s, b[i], b[i + 1], b, i, n) -- (any address: 248..255 are framed)
  for index = 1, #list do
    local length, is_scan = list[index][2](b, i, n)
    if not is_scan and length == NEED then
      if final then return false end
      -- (bytes that would swallow a record that is a frame: none, not waited for)
      if not crosses_framed_record(s, b, i, length, n) then return nil end
    elseif not is_scan and length >= MIN_ADU and length <= MAX_COUNTED then
      if i + length > n then
        if not final and not crosses_framed_record(s, b, i, length, n) then return nil end
      elseif crc_ok_at(b, i, length) then
        return true
      end
    end
    if is_scan and scan ~= false then
      local reach = framed_reach(s, b, i, n) -- (not across a record that is a frame: rtu.py _valid_frame_at)
      if crc_scan(b, i, length, math.min(reach - i, MAX_ADU)) > 0 then return true end
      if not final and reach == n and n - i < MAX_ADU then found = nil end
    end
  end
  return found
end

-- frame_at's answers by the stream's length and position under one state (the buffer, the answer awaited, its
-- echo): noise asks a position again after each reading of the one before (followed), a flood some three times.
local ANSWER, BY_ANSWER, valid_known, valid_state = { [true] = 1, [false] = 2 }, { true, false, nil }, {}, {}
local function valid_frame_at(s, b, i, n, final, scan)
  local state = valid_state
  if state[1] ~= s or state[2] ~= b or state[3] ~= s.expect or state[4] ~= s.echo or state[5] ~= s.base then
    valid_known, state[1], state[2], state[3], state[4], state[5] = {}, s, b, s.expect, s.echo, s.base
  end
  local known = valid_known[n] or {}
  valid_known[n] = known
  local key = i * 4 + (final and 2 or 0) + (scan == false and 1 or 0)
  if known[key] ~= nil then return BY_ANSWER[known[key]] end
  local found = frame_at(s, b, i, n, final, scan)
  known[key] = ANSWER[found] or 3
  return found
end

-- Does a frame with a length rule and a good CRC start inside the bytes i .. i + length - 1? nil when bytes
-- still to come may tell (bounded.py _intact_inside): deciding before they come made the answer depend on where
-- the input was cut.
local function intact_inside(s, b, i, length, n, final)
  local found = false
  for j = i + 1, i + length - 1 do
    local at = valid_frame_at(s, b, j, n, final, false)
    if at then return true end
    if at == nil then found = nil end
  end
  return found
end

-- intact_inside, where records that are frames (a record that is this one, or the next one a frame: ends_record)
-- say no frame it holds crosses its record's end: one is not waited for (bounded.py _framed_inside).
local function framed_inside(s, b, i, length, n, final)
  local stop = i + length
  local bounded = boundary_at(s, stop) and (record_start(s, i) or (n - stop >= MIN_ADU and ends_record(s, b, stop, n)))
  return intact_inside(s, b, i, length, bounded and stop or n, final or bounded)
end

-- Does the line say a frame ends at `stop` (rtu.py _followed)? The end of the input (unless at_end is
-- false), a record boundary, or an intact frame, right there or after a few glitch bytes; nil: the bytes
-- that tell have not come yet.
local function followed(s, b, stop, n, final, at_end)
  local j = stop
  while true do
    if final and j == n then return at_end ~= false or s.cut_by_silence == true end -- (a silence at the end: a boundary)
    if boundary_at(s, j) then return true end
    local found = valid_frame_at(s, b, j, n, final)
    if found ~= false then return found end
    if j < n and GLITCH[b[j]] and j - stop < GLITCH_SKIP then j = j + 1 else return false end
  end
end

-- Does a frame of the slave at i start at `stop`, after glitch bytes or not, damaged or not (its answer,
-- rtu.py _answered)?
local function answered(s, b, i, stop, n, final)
  local slave = b[i]
  local j = stop
  while j - stop <= GLITCH_SKIP do
    if n - j < 2 then
      if final then return false end
      return nil
    end
    if b[j] == slave and possible_start(b[j + 1]) then return true end
    if not GLITCH[b[j]] then return false end
    j = j + 1
  end
  return false
end

-- May a CRC-valid frame found inside noise count (rtu.py _confirmed)?
local function confirmed(s, b, i, kind, length, n, final)
  local stop = i + length
  local following = followed(s, b, stop, n, final)
  if following ~= false then return following end
  if kind == REQUEST and b[i] ~= 0 then
    if plausible_request(b, i, length) then return true end
    return answered(s, b, i, stop, n, final)
  end
  return false
end

-- A frame without a length rule: the shortest CRC match the line confirms, first by a frame (or the end)
-- right after it, then after glitch bytes (a frame and a 00 check one byte longer). In step a scanned
-- frame is trusted over a short frame inside it; while resynchronising, the inner one wins.
local function scan_match(s, b, i, n, minimum, final)
  local from = 1
  if s.glitch_runs >= GLITCHY_AFTER then from = 2 end -- (a 00 after a frame is a glitch: rtu.py _scan)
  local reach = framed_reach(s, b, i, n)
  local lengths = crc_lengths(b, i, n, minimum, math.min(reach - i, MAX_ADU)) -- (none when minimum is past it)
  for pass = from, 2 do
    for k = 1, #lengths do
      local length = lengths[k]
      local following
      -- (a record's end right after it settles the first pass as a frame there would: _timedframe.h decide_at)
      if pass == 1 then following = boundary_at(s, i + length) or valid_frame_at(s, b, i + length, n, final)
      else following = followed(s, b, i + length, n, final) end
      if following == nil then return NEED end
      if following then
        local inside = s.noise ~= nil and framed_inside(s, b, i, length, n, final)
        if inside == nil then return NEED end
        if not inside then return length end
      end
    end
  end
  -- (up to a record that is a frame, every byte has come: nothing longer to wait for)
  if reach == n and n - i < MAX_ADU and not final then return NEED end
  return NONE
end

-- A counted layout's length when its count is 0, by kind and code (rtu.py _COUNTS_NOTHING): every count of the
-- spec counts something, so a reading with a bad CRC that counts nothing is no frame.
local COUNTS_NOTHING = DATA.protocol.counts_nothing -- (written out from that table by the code generator)
local function counts_nothing(b, i, kind, length)
  local counted = COUNTS_NOTHING[kind]
  return counted ~= nil and counted[b[i + 1]] == length
end

-- At the end of the input: do the bytes from i begin the answer awaited, cut by the end of the capture
-- (rtu.py _cut_answer)? The reason, or nil. (`silence`: by a silence at n: silence_cut)
local function cut_answer(s, b, i, n, silence)
  if n - i < 2 or not awaited(s, b, i, n) then return nil end
  -- (the answer's reading, unless it counts nothing or is not as long as the request implies: then the next, a
  -- request repeated before the answer, or the next one)
  local list, kind, length, is_scan, declared = interpretations(s, b[i], b[i + 1], b, i, n), nil, nil, nil, nil
  for index = 1, #list do
    local other = list[index][1]
    length, is_scan, declared = list[index][2](b, i, n)
    if is_scan or not (counts_nothing(b, i, other, length) or not_the_answer(s, other, length)) then
      kind = other
      break
    end
  end
  if kind == nil then return nil end
  if is_scan then
    -- (a rule with a CRC fallback: cut only when the bytes there hold no frame a scan finds)
    if declared == nil or declared == NONE then return nil end
    scanned.b = nil -- (match's scans are kept for its position only)
    if scan_match(s, b, i, n, length, true) ~= NONE then return nil end
    length = declared
  end
  if length ~= NEED and not (n - i < length and length <= (is_scan and MAX_ADU or MAX_COUNTED)) then return nil end
  if intact_inside(s, b, i, n - i, n, true) then return nil end
  return cut_reason(kind, n - i, length, silence)
end

-- The list with value appended (a new list for nil: most positions have none).
local function added(list, value)
  if list == nil then return { value } end
  list[#list + 1] = value
  return list
end

-- The first reading of `list` ({ kind, length }) after which `test` (followed, valid_frame_at) finds a
-- frame's end confirmed; NEED when the bytes that tell have not come; nil: none.
local function first_confirmed(s, b, i, n, final, list, test)
  for index = 1, #list do
    local following = test(s, b, i + list[index][2], n, final)
    if following == nil then return NEED end
    if following then return list[index] end
  end
  return nil
end

local function shortest_first(list)
  local order = { table.unpack(list) }
  table.sort(order, function(x, y) return x[2] < y[2] end)
  return order
end

-- kind, length, crc_ok for a frame at i; NEED (more bytes needed) or NONE (no frame starts at i).
local function match(s, b, i, n, final)
  scanned.b = nil -- (a scan is kept within one position's match only: s.b may change between them)
  local slave, code = b[i], b[i + 1]
  if GLITCH_ADDRESSES[slave] then -- (a glitch byte that is no device's address, before an intact frame)
    local after = valid_frame_at(s, b, i + 1, n, final)
    if after then return NONE end
    if after == nil and not ends_record(s, b, i, n) then return NEED end
  end
  local valid, damaged, waiting = nil, nil, nil
  local list = interpretations(s, slave, code, b, i, n)
  local awaits = awaited(s, b, i, n) -- (the answer awaited, its echo weighed)
  for index = 1, #list do
    local kind = list[index][1]
    local length, is_scan, declared = list[index][2](b, i, n)
    local sized = not is_scan and length >= MIN_ADU and length <= MAX_COUNTED
    if not is_scan and (length == NEED or (sized and i + length > n)) then
      -- (its bytes have not all come; not waited for if they would swallow a record that is a frame)
      if not final and not crosses_framed_record(s, b, i, length, n) then
        waiting = added(waiting, length)
      end
    elseif sized then
      if crc_ok_at(b, i, length) then
        valid = added(valid, { kind, length })
      elseif length <= MAX_ADU and not counts_nothing(b, i, kind, length) then -- (over it: a good CRC only)
        damaged = added(damaged, { kind, length })
      end
    end
    if is_scan then
      local found = scan_match(s, b, i, n, length, final)
      if found == NEED then
        waiting = added(waiting, NEED)
      elseif found > 0 then
        valid = added(valid, { kind, found })
      elseif declared ~= nil and declared >= MIN_ADU and declared <= MAX_ADU and declared <= n - i then
        damaged = added(damaged, { kind, declared }) -- (the length its fields give, its CRC bad: rtu.py)
      end
    end
  end
  if valid ~= nil then
    local chosen = valid[1]
    if #valid == 1 then
      -- CRC-16/MODBUS has no final XOR: a frame followed by a 00 byte also checks as a frame one byte
      -- longer. Unless this is the answer awaited, wait when a layout one byte longer may still arrive.
      if waiting ~= nil and not (chosen[1] == RESPONSE and awaits) and not boundary_at(s, i + chosen[2]) then
        for index = 1, #waiting do
          if waiting[index] == NEED or waiting[index] == chosen[2] + 1 then return NEED end
        end
      end
    else
      -- Two layouts check out: on a line that leaves 00 glitches the shortest reading it confirms (rtu.py),
      -- else a record boundary, the answer awaited, then what follows decides.
      local glitchy = s.glitch_runs >= GLITCHY_AFTER
      chosen = glitchy and first_confirmed(s, b, i, n, final, shortest_first(valid), followed) or nil
      for index = 1, #valid do
        if chosen == nil and boundary_at(s, i + valid[index][2]) then chosen = valid[index] end
      end
      chosen = chosen or (awaits and valid[1][1] == RESPONSE and valid[1])
        or first_confirmed(s, b, i, n, final, valid, valid_frame_at) or valid[1]
      if chosen == NEED then return NEED end
    end
    return chosen[1], chosen[2], true
  end
  if waiting ~= nil then return NEED end
  -- (a reserved address counts with a good CRC only: a glitch byte is one too; so does a broadcast the
  -- spec does not allow, a read: 00 is a glitch byte)
  if slave > MAX_SLAVE or (slave == 0 and DATA.not_broadcast[code]) then return NONE end
  if GLITCH[slave] then
    -- A glitch byte before a frame (a CRC scan's too, which intact_inside does not try).
    local after = valid_frame_at(s, b, i + 1, n, final)
    if after == nil then return NEED end
    if after then return NONE end
  end
  -- No layout checks out: a damaged frame is shown once if the line confirms its end (followed; the end of
  -- the input only for the answer awaited) and it holds none inside (a cut frame must not swallow the
  -- intact frame that follows it).
  local reach = nil -- (framed_reach at i, asked once for every reading: crosses_framed_record)
  for index = 1, #(damaged or NO_INTERPRETATION) do
    local kind, length = damaged[index][1], damaged[index][2]
    local stop = i + length
    reach = reach or framed_reach(s, b, i, n)
    local following = reach >= math.min(n, stop) and followed(s, b, stop, n, final, awaits)
    if following == nil then return NEED end
    if following then
      local inside = framed_inside(s, b, i, length, n, final)
      if inside == nil then return NEED end
      if not inside then return kind, length, false end
    end
  end
  return NONE
end

-- The frame of `length` bytes at b[i], its first byte at stream offset `offset`, received at `time`.
local function rtu_frame(b, i, offset, time, kind, length, crc_ok)
  local stop = i + length - 2
  local crc = b[stop] + b[stop + 1] * 256
  -- (a frame that checks out has the CRC it carries: no need to compute it again)
  return {
    kind = kind, offset = offset, length = length, slave = b[i], fn = b[i + 1] % 128,
    crc = crc, crc_expected = crc_ok and crc or crc16(b, i, stop), time = time,
    b = b, bi = i, data_at = i + 2, data_len = length - 4,
    number = 0, record = 0, at = 0, -- (set by take_items: in the constructor, the hash is made at its size)
    -- (and the keys decoding adds: a table that outgrows its hash is rebuilt, each key inserted again)
    fields = nil, start = nil, quantity = nil, registers = nil, bits = nil, request = nil, response = nil,
    warnings = length > MAX_ADU and { say("over_adu", { length = length, limit = MAX_ADU }) } or nil, -- (match's)
  }
end

-- Runs the line bounds (framing/bounded.py): bytes with a good CRC from a bound (a record's start or end, a
-- silence, the end of the last frame) to the next (the first intact frame, record's end or silence after it,
-- the end of the input) are a frame, whatever length the table's layout takes: one candidate a bound, once in
-- 65,536 runs for random bytes. Its length: 0 (none) or NEED.
local function bounded_start(s, i)
  return boundary_at(s, i) or record_start(s, i) or s.framed_end == s.base + i
end

local function bounded_run(s, b, i, n, final)
  if not bounded_start(s, i) then return 0 end
  -- (up to a record's end or silence, the frames inside it only: as if the input ended there)
  local stop, last = first_after(s, s.boundaries, i, n), true
  if stop == nil then stop, last = n, final end
  for stop_at = i + 1, math.min(stop, i + MAX_ADU) do
    local found = valid_frame_at(s, b, stop_at, stop, last, false) -- (at `stop` itself: true when last)
    if found == nil then return NEED end
    if found then return stop_at - i >= MIN_ADU and crc_ok_at(b, i, stop_at - i) and stop_at - i or 0 end
  end
  if not last and n - i < MAX_ADU then return NEED end
  return 0
end

-- The reading of `kind` among the interpretations at i: its length rule's answer (length, is_scan, ...), nil: none.
local function reading_of(s, b, i, n, kind)
  local list = interpretations(s, b[i], b[i + 1], b, i, n)
  for index = 1, #list do
    if list[index][1] == kind then return list[index][2](b, i, n) end
  end
  return nil
end

-- Does a layout at i whose length the bytes up to n hold check out (bounded.py _checks_out): an answer nobody
-- asked for, shorter than a request, or cut before its request reading's byte count? (Unlike valid_frame_at, a
-- request reading still without its length does not stop the others.)
local function checks_out(s, b, i, n)
  local list = interpretations(s, b[i], b[i + 1], b, i, n)
  for index = 1, #list do
    local length, is_scan = list[index][2](b, i, n)
    if not is_scan and length >= MIN_ADU and length <= n - i and crc_ok_at(b, i, length) then return true end
    if is_scan and crc_scan(b, i, length, math.min(n - i, MAX_ADU)) > 0 then return true end
  end
  return false
end

-- At the end of the input, where no answer awaited begins (cut_answer weighs that one): do the bytes from i, from
-- a bound, begin a request whose length the table knows (or whose count has not come), cut by the end of the
-- capture (the next poll: bounded.py _cut_request)? The reason, or nil. (`silence`: by a silence at n: silence_cut)
local function cut_request(s, b, i, n, silence)
  if n - i < 2 or awaited(s, b, i, n) or not bounded_start(s, i) then return nil end
  local slave, code = b[i], b[i + 1]
  if not ((slave >= 1 and slave <= MAX_SLAVE) or (slave == 0 and not DATA.not_broadcast[code])) then return nil end
  local length, is_scan = reading_of(s, b, i, n, REQUEST)
  if length == nil or is_scan or (length ~= NEED and not (n - i < length and length <= MAX_COUNTED)) then return nil end
  if checks_out(s, b, i, n) or intact_inside(s, b, i, n - i, n, true) then return nil end
  return cut_reason(REQUEST, n - i, length, silence)
end

-- Do the bytes from i up to the first silence after it begin a frame the silence cuts, weighed as at the end of the
-- input (bounded.py _silence_cut: live closes them there, and a file says what live says)? The silence's index and
-- the reason, or nil. A layout with a good CRC across the silence is a frame (the silence inside it a warning).
local function silence_cut(s, b, i, n)
  if s.expect == nil and not bounded_start(s, i) then return nil end
  local stop = silence_after(s, i, n)
  if stop == nil then return nil end
  local reason = cut_answer(s, b, i, stop, true) or cut_request(s, b, i, stop, true)
  if reason == nil or checks_out(s, b, i, n) then return nil end
  return stop, reason
end

-- Emit the frame of a bounded run at i (bounded.py _take_bounded): its length, 0 (none) or NEED. A warning says
-- the length its layout takes when that is another.
local function take_bounded(s, b, i, n, final, items)
  local length = bounded_run(s, b, i, n, final)
  if length <= 0 then return length end
  local kind = bounded_kind(s, b, i, n)
  local offset = s.base + i
  local frame = rtu_frame(b, i, offset, time_at(s, offset), kind, length, true)
  local expected, is_scan = reading_of(s, b, i, n, kind) -- (the length its layout takes: bounded.py _expected_length)
  if expected ~= nil and not is_scan and expected >= MIN_ADU and expected ~= length then
    frame.warnings = { say("frame_length", { length = length, expected = expected }) }
  end
  emit(s, frame, items)
  return length
end

-- The interpretation the fast paths try at a frame start: the likeliest, unless it is an exception
-- nobody awaits (those are weighed by match). nil: no fast path here.
local function fast_interpretation(s, first, slave, code)
  if first ~= nil and (first[1] ~= EXCEPTION or s.expect == slave * 256 + code % 128) then return first end
  return nil
end

-- Frame what the buffer holds (rtu.py _run): items in stream order; the index of the first byte left.
local function run_rtu(s, final, items)
  local b, n = s.b, s.n
  local i = 0
  local since, retry, was_cut, was_only = -1, 0, false, false
  while n - i >= MIN_ADU or (final and i < n) do
    if n - i < MIN_ADU then
      local stop, cut = silence_cut(s, b, i, n) -- (bytes a silence cuts first, as live closed them there)
      while stop ~= nil do
        add_noise(s, i, stop, cut, items)
        i = stop
        stop, cut = silence_cut(s, b, i, n)
      end
      local silence = s.cut_by_silence -- (a silence before the end of the capture: vw3.records finish)
      add_noise(s, i, n, cut_answer(s, b, i, n, silence) or cut_request(s, b, i, n, silence) or TOO_SHORT, items)
      return n
    end
    local stop = i -- (noise to stop: a repetition decided before, or bytes no frame starts at)
    -- (the answer awaited and the line's glitchiness change with a frame only, which ends the noise)
    if s.noise == nil or final then
      since = -1
    elseif since < 0 or s.noise_cut ~= was_cut or s.glitches_only ~= was_only then
      since, was_cut, was_only = i, s.noise_cut, s.glitches_only
    elseif i >= retry and i - since >= REPEAT_PROBE then
      stop, retry = repeats(s, b, i, since, n, i + NOISE_ITEM_MAX - s.noise.length)
    end
    local slave, code = b[i], b[i + 1]
    local first = stop == i and interpretations(s, slave, code, b, i, n)[1] or nil
    -- (the length of a run the line bounds where no frame starts, or no layout checks out below: take_bounded)
    local taken = first == nil and stop == i and take_bounded(s, b, i, n, final, items) or 0
    if taken == NEED then break end
    if taken > 0 then
      i = i + taken
    elseif first == nil then
      if stop == i then
        -- No frame starts here: skip to the next byte pair that could start one.
        stop = i + 1
        while stop < n - 1 and not possible_start(b[stop + 1]) do stop = stop + 1 end
        if stop >= n - 1 then stop = final and n or n - 1 end
      end
      add_skipped(s, i, stop, items)
      i = stop
    else
      local kind, length, crc_ok = nil, nil, true
      -- Fast path: the likeliest interpretation checks out and the next byte is not a 00 (which may belong
      -- to a longer frame, see match), or the frame ends where the record does (a record boundary settles
      -- what match would weigh): nearly every frame of a clean bus.
      if s.noise == nil and fast_interpretation(s, first, slave, code) and not GLITCH_ADDRESSES[slave] then
        local found, is_scan = first[2](b, i, n)
        if not is_scan and found >= MIN_ADU and found <= MAX_ADU
            and ((i + found < n and b[i + found] ~= 0) or (i + found == n and boundary_at(s, n)))
            and crc_ok_at(b, i, found) then
          kind, length = first[1], found
        end
      end
      if kind == nil then
        local cut = final and (cut_answer(s, b, i, n, s.cut_by_silence) or cut_request(s, b, i, n, s.cut_by_silence))
        if cut then
          -- (noise: up to a silence inside that cuts them first, as live closed them there)
          local upto, silence = silence_cut(s, b, i, n)
          if upto ~= nil then cut = silence else upto = n end
          taken = take_bounded(s, b, i, n, final, items)
          if taken == 0 then
            add_noise(s, i, upto, cut, items)
            taken = upto - i -- (taken as noise)
          end
        else
          kind, length, crc_ok = match(s, b, i, n, final)
          if kind == NEED then break end
          if kind == NONE or not crc_ok then taken = take_bounded(s, b, i, n, final, items) end
          if taken == NEED then break end
        end
        -- Resynchronising inside noise (not in step, at a record boundary, after nothing but glitch bytes
        -- since one): random bytes pass a CRC 1 time in 65,536 per layout tried, so such a frame counts
        -- only when the line confirms it (rtu.py _confirmed).
        if taken == 0 and kind ~= NONE and crc_ok and (kind == REQUEST or not awaited(s, b, i, n))
            and not (s.noise == nil or s.glitches_only or boundary_at(s, i)) then
          local following = confirmed(s, b, i, kind, length, n, final)
          if following == nil then break end
          if not following then kind = NONE end
        end
      end
      if taken > 0 then
        i = i + taken
      elseif kind == NONE then
        -- (bytes up to a silence that begin a frame it cuts: their reason, as live's: silence_cut)
        local upto, why = silence_cut(s, b, i, n)
        if upto == nil then upto, why = i + 1, no_frame(s, i) end
        add_noise(s, i, upto, why, items)
        i = upto
      else
        local offset = s.base + i
        emit(s, rtu_frame(b, i, offset, time_at(s, offset), kind, length, crc_ok), items)
        i = i + length
      end
    end
  end
  return i
end
M.answered, M.fast_interpretation, M.rtu_frame, M.run_rtu = answered, fast_interpretation, rtu_frame, run_rtu
end

-- ---- vw3.ascii: lua/src/ascii.lua ----
package.preload["vw3.ascii"] = function(...)
-- vw3.ascii: ASCII framing: ':' ... CR LF lines, LRC, the mode of a capture.
-- Mirrors dissector/framing/ascii.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.ascii"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, FRAMING, MAX_ADU, MAX_SLAVE, MIN_ADU, NEED = DATA, FRAMING, MAX_ADU, MAX_SLAVE, MIN_ADU, NEED
local REQUEST, RESPONSE, add_noise, awaited, bounded_kind = REQUEST, RESPONSE, add_noise, awaited, bounded_kind
local crc16, crc_step, cut_reason, emit, floor, flush_noise = crc16, crc_step, cut_reason, emit, floor, flush_noise
local format, interpretations, ipairs, math, not_the_answer = format, interpretations, ipairs, math, not_the_answer
local pairs, table, time_at = pairs, table, time_at
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
M.MODE_REACH, M.hex_pairs, M.pair_scan, M.run_ascii = MODE_REACH, hex_pairs, pair_scan, run_ascii
M.sample_modes = sample_modes
end

-- ---- vw3.feed: lua/src/feed.lua ----
package.preload["vw3.feed"] = function(...)
-- vw3.feed: feeding records to the framers (whole-record frames first), what stays buffered.
-- Mirrors dissector/framing/stream.py (feed, finish).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.feed"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local MAX_ADU, MAX_SLAVE, MIN_ADU, drop_first, expect_after = MAX_ADU, MAX_SLAVE, MIN_ADU, drop_first, expect_after
local fast_interpretation, first_above, flush_noise = fast_interpretation, first_above, flush_noise
local interpretations, lane, rtu_frame, run_ascii, run_rtu = interpretations, lane, rtu_frame, run_ascii, run_rtu
local silent_before, string, whole_crc_good = silent_before, string, whole_crc_good

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
M.feed, M.feed_whole, M.takes_whole = feed, feed_whole, takes_whole
end

-- ---- vw3.decode: lua/src/decode.lua ----
package.preload["vw3.decode"] = function(...)
-- vw3.decode: decoding a frame's fields per function code: grammars, handlers, spec limits.
-- Mirrors dissector/decode/fields.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.decode"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, EXCEPTION, MAX_SLAVE, REQUEST, answered, concat = DATA, EXCEPTION, MAX_SLAVE, REQUEST, answered, concat
local data_bytes, floor, format, ipairs, math, pairs = data_bytes, floor, format, ipairs, math, pairs
local string, string_of, table, tostring = string, string_of, table, tostring
local RULES = DATA.rules

-- ---------------------------------------------------------------------------------------------------
-- Protocol names and limits (dissector/protocol/spec.py).
local FUNCTIONS = DATA.functions or {}
local EXCEPTIONS = DATA.exceptions or {}
local DIAGNOSTICS = DATA.diagnostics or {}
local LIMITS = RULES.limits
local NOT_BROADCAST = DATA.not_broadcast or {}
-- FC43's mandatory objects by name (`VendorName, ProductCode, ...`), and a device object's byte as in a Python
-- bytes literal between single quotes (never a control character): RULES.mandatory_objects, RULES.byte_text.
local MANDATORY_OBJECTS, BYTE_TEXT = RULES.mandatory_objects, RULES.byte_text

-- A catalogue entry's text (format, params; repr: the parameters Python writes as `!r`, shown by `quote`)
-- with its parameters by name, as Python fills them in: the texts here and maps.py's MESSAGES alike.
local function fill(entry, values, quote)
  local params, repr, args = entry.params, entry.repr, {}
  for index = 1, #params do
    local name = params[index]
    args[index] = repr and repr[name] and quote(values[name]) or values[name]
  end
  return format(entry.format, table.unpack(args, 1, #params))
end

-- The catalogue's text `key` (data/modbus.toml [texts], protocol/rules.py text()).
local function say(key, values) return fill(RULES.texts[key], values) end

local function function_name(code)
  return FUNCTIONS[code] or say(DATA.user_defined[code] and "user_function" or "other_function", { code = code })
end

local function exception_name(code)
  if code == nil then return say("missing_exception", {}) end
  return EXCEPTIONS[code] or say("undefined_exception", { code = code })
end

-- ---------------------------------------------------------------------------------------------------
-- Decoding (dissector/protocol/grammar.py + decode/fields.py): PDU data after the function code, then the handlers.
local function u16(b, k) return b[k] * 256 + b[k + 1] end

-- A frame's warnings and notes lists are made with their first entry (most frames have none).
local function adder(key)
  return function(f, text)
    local list = f[key]
    if list == nil then f[key] = { text } else list[#list + 1] = text end
  end
end
local warn, note = adder("warnings"), adder("notes")

-- b[first..last] as text where every byte is printable ASCII (as vw3-decode shows a device's data), else nil.
local function printable_ascii(b, first, last)
  local text = string_of(b, first, last - first + 1)
  return not text:find("[^ -~]") and text or nil
end

-- Bytes b[first .. last] in hex, each by `pattern` (%02x, %02X), joined by `gap`.
local function hex_of(b, first, last, pattern, gap)
  local out = {}
  for k = first, last do out[#out + 1] = format(pattern, b[k]) end
  return concat(out, gap)
end

-- Does the frame tell the parameters anything (devices/memory.py)? Not one that failed its check (the
-- device ignored it: Modbus over serial line 2.5.1.2): its values are shown, no status judged, no story
-- told, no memory changed; nor does its answer take addresses from it (pairing.py trusted_request).
local function verified(f)
  return f.crc == f.crc_expected
end

-- The request an answer is read against (its window, its echo, what an exception refuses), nil when the
-- capture has none or the tap's copy of it failed its check: the answer is paired, its addresses unknown
-- and nothing is judged, told or remembered of them (pairing.py trusted_request).
local function trusted_request(f)
  local request = f.request
  if request ~= nil and verified(request) then return request end
  return nil
end

-- Registers and bits are runs (made by the lifting rules' handlers): where their values start in the frame's
-- byte table, how many, the first address. A value is read from the bytes each time it is needed (the first
-- pass reads them from the frame's byte table, .b, dropped once the frame is done with; the display from
-- the tvb), so a record keeps one small table for a read of 125 registers, not 125.

-- A run is done with its frame's byte table (the display reads the tvb): its indices become the
-- frame's own (shift: the frame's first byte in the table it was read from).
local function release_run(run)
  if run == nil then return end
  run.b = nil
  if run.shift ~= nil then
    run.first = run.first - run.shift
    run.shift = nil
  end
end

-- The index-th (0-based) register of a run: address (nil when unknown), value, and its index in b.
local function register_at(run, b, index, shift)
  -- shift: the display's tables hold the frame's own bytes; a run not released yet is 0-based elsewhere
  local k = run.first - (shift and run.shift or 0) + 2 * index
  local address = nil
  if run.start ~= nil then address = (run.start + index) % 0x10000 end
  return address, b[k] * 256 + b[k + 1], k
end

local function bit_at(run, b, index, shift)
  local k = run.first - (shift and run.shift or 0) + floor(index / 8)
  local address = nil
  if run.start ~= nil then address = (run.start + index) % 0x10000 end
  if run.single ~= nil then return address, run.single, k end
  return address, floor(b[k] / 2 ^ (index % 8)) % 2, k
end

-- The readers of the layouts (data/modbus.toml [layouts] and [parts], protocol/shapes.py) by name, written out
-- by the code generator (DATA.parsers, codegen/decode_lua.py); which code uses which: DATA.grammars, below. Each
-- gets the byte table, the first data byte and the data length, and returns the number of bytes its layout
-- consumed (the rest is `trailing`) and the fields, or nil and why the data do not fit (Python: GrammarError
-- -> "malformed ..."). The display reads the fields by their sizes (a fixed one's: its .size, tree.lua).
local PARSERS = DATA.parsers

-- ---------------------------------------------------------------------------------------------------
-- The lifting rules of data/modbus.toml [lift] (decode/fields.py lifter) are handlers written out by the code
-- generator (DATA.lifters, codegen/decode_lua.py), each rule's limits and fields in place; they call the helpers
-- below. Warnings in the table's order: checks, span, byte count, odd count, coil, echo.
local function echo_check(f, fields, request, echo)
  local answered, differ = request.fields, {}
  for _, name in ipairs(echo.fields) do
    if answered[name] ~= fields[name] then differ[#differ + 1] = name end
  end
  if echo.names ~= "differing" then differ = echo.fields end
  warn(f, say("echo", { fields = concat(differ, " and "), verb = #differ == 1 and "differs" or "differ" }))
end

-- A value outside the spec's low..high (protocol/rules.py range_text): one the spec allows alone named.
local function range_text(what, value, low, high)
  if low == high then return say("range_one", { what = what, value = value, low = low }) end
  return say("range", { what = what, value = value, low = low, high = high })
end

-- An answer that repeats its request's data whole (FC21's; from `skip`: an FC8 sub-function's,
-- [diagnostic_answers]): a request keeps them as a string (its byte table is dropped before its answer comes);
-- an answer that differs answered other data (fields._diagnostics, _check_echo).
local function check_data_echo(f, b, request, skip)
  local data = string_of(b, f.data_at + skip, f.data_len - skip)
  if f.kind == REQUEST then
    f.fields.echoed = data
  elseif request ~= nil and request.fields ~= nil and request.fields.echoed ~= data then
    warn(f, say("echo", { fields = "data", verb = "differs" }))
  end
end

-- An answer's parts against its request's (decode/fields.py _check_parts; FC20): as many, each of the length its
-- request part asks (`given`: the answer's length fields, `asked`: what its request kept of its parts).
local function check_asked(f, parts, index, given, asked)
  local length = parts.length
  if #asked ~= index then warn(f, say("part_count", { part = parts.name, count = index, quantity = #asked })) end
  for k = 1, given and math.min(#asked, index) or 0 do
    if given[k] ~= length.plus + length.unit * asked[k] then
      -- (what the length holds in the request's unit: protocol/rules.py PartLength.held)
      local data = math.max(given[k] - length.plus, 0)
      local whole, rest = math.floor(data / length.unit), data % length.unit
      local held = rest > 0 and (whole .. " and " .. rest .. " byte(s)") or tostring(whole)
      warn(f, say(length.text, { part = parts.name, index = k, count = given[k], held = held, quantity = asked[k] }))
    end
  end
end

-- A write's words past its quantity (fields.py _past_quantity), `size` bytes at b[at]: no register written,
-- warned by their bytes (the text `key`).
local function past_quantity(f, b, at, size, quantity, key)
  warn(f, say(key, { count = size, quantity = quantity, data = hex_of(b, at, at + size - 1, "%02x", " ") }))
end

-- An FC8 request's data word as the spec has it for its sub-function (RULES.diagnostic_data, fields.py
-- _diagnostic_data): what it asks (a note), or a warning where the spec allows another.
local DIAGNOSTIC_DATA = RULES.diagnostic_data
local function diagnostic_data(f, b, subfunction, rule)
  local at, count = f.data_at + 2, f.fields.data_length
  local word = count == 2 and u16(b, at) or nil
  local meaning = rule.data and word and rule.data[word]
  if meaning then
    if meaning ~= "" then note(f, meaning) end
  elseif rule.data == nil and word and word % 256 == 0 then
    local code = floor(word / 256)
    local name = rule.names[code] or code > 32 and code < 127 and "'" .. string.char(code) .. "'"
    note(f, name and say("diagnostic_character", { what = rule.character, character = name, code = code })
      or say("diagnostic_byte", { what = rule.character, code = code }))
  else
    -- (the data as sent, in hex; rule.allowed: the words the spec allows, or its character then 00)
    local data = hex_of(b, at, f.data_at + f.data_len - 1, "%02X", "")
    warn(f, say("diagnostic_data", { data = data ~= "" and data or "(none)", subfunction = subfunction,
      allowed = rule.allowed }))
  end
end

-- The FC8 sub-functions whose answer repeats the request's data ([diagnostic_answers]): a request's data are
-- kept in its fields as a string (its byte table is dropped before its answer comes), an answer's compared.
local DIAGNOSTIC_ECHOES = RULES.diagnostic_echoes

-- The named special cases no rule describes (decode/fields.py SPECIAL_HANDLERS).
local SPECIAL = {
  diagnostics = function(f, b)
    local fields = f.fields
    local subfunction, odd = fields.subfunction, fields.data_length % 2 == 1
    local rule = f.kind == REQUEST and DIAGNOSTIC_DATA[subfunction]
    f.subfunction = subfunction
    if DIAGNOSTICS[subfunction] == nil then warn(f, say("unknown_subfunction", { subfunction = subfunction })) end
    if odd then warn(f, say("odd_diagnostic_data", {})) end
    if rule and not odd then diagnostic_data(f, b, subfunction, rule) end
    if DIAGNOSTIC_ECHOES[subfunction] and (f.kind == REQUEST or not odd) then
      check_data_echo(f, b, f.request, 2)
    end
  end,
  mei_request = function(f, b)
    -- (another MEI type: the layout's switch read no Read Device ID code)
    local code, limit = f.fields.body.read_code, LIMITS.device_id_code
    if code ~= nil and (code < limit[1] or code > limit[2]) then
      warn(f, say("device_id_code", { code = code, low = limit[1], high = limit[2] }))
    end
  end,
  mei_response = function(f, b)
    -- The objects the reader listed become the frame's (its fields are dropped once it is done with):
    -- each named, its value as text, where it starts (its id) and its bytes (id and length too).
    local objects = f.fields.body.objects
    if objects == nil then return end -- (another MEI type: the layout's switch read no device identification)
    for _, object in ipairs(objects) do
      -- as a bytes literal's text, shown between single quotes (decode/fields.py _mei_response)
      local chars, at, size = {}, object.value_at, object.length
      for k = at, at + size - 1 do chars[#chars + 1] = BYTE_TEXT[b[k]] end
      object.name = DATA.device_id_objects[object.id] or say("other_object", { id = object.id })
      object.value, object.offset, object.length, object.value_at = concat(chars), at - 2, 2 + size, nil
    end
    f.objects = objects
    -- (a count the frame does not hold: the objects there are shown, decode/fields.py)
    local declared = f.fields.body.object_count
    if #objects < declared then warn(f, say("object_count", { count = declared, present = #objects })) end
    if #objects == 0 then warn(f, say("no_objects", { names = MANDATORY_OBJECTS })) end -- (fields.py _mei_response)
  end,
  report_server_id_response = function(f, b)
    -- (the tree shows its fields from the layout, tree.lua add_pdu)
    local run, names, count = f.fields.run_indicator, DATA.names.run_indicator, f.fields.byte_count
    if count == 0 then -- (no server id either: the layout's ?(byte_count))
      warn(f, say("no_server_id", { count = count }))
    elseif run == nil then -- (byte count 1: the server id alone, the layout's ?(byte_count-1))
      warn(f, say("no_run_indicator", { count = count }))
    elseif names[run] == nil then
      -- An FC17 answer's server id is device specific in length (fields.py _report_server_id_response): the
      -- first byte after its first that is a run indicator (00, FF) may follow a longer id.
      local first, ends = f.data_at + 1, nil -- (the server id's first byte)
      for k = f.data_at + count, first + 1, -1 do ends = names[b[k]] ~= nil and k or ends end
      if ends == nil then
        warn(f, say("run_indicator", { value = run })) -- (OFF, ON: none where any length of server id puts it)
      else -- (the id is read up to the first 00 or FF after its first byte: fields.py _report_server_id_response)
        f.server_id_size = ends - first -- (tree.lua shows the id, its run indicator and data so split)
        warn(f, say("server_id_read_longer", { count = ends - first, value = run }))
      end
    end
  end,
}

-- Per direction and code, written out by the code generator from RULES.by_code: the parser of its layout
-- (GRAMMARS), its lifting rule (LIFT_OF; nil: none or a named special case) and its handler (H): the lifting
-- rule's where the table has one, else the special case's.
local GRAMMARS, LIFT_OF = DATA.grammars, DATA.lift_of
-- The codes whose answer's window is its request's ([lift] start `request.start`: FC1..4, FC23, FC24).
local WINDOW_ASKED = {}
for code, rule in pairs(LIFT_OF.response) do WINDOW_ASKED[code] = rule.start == "request.start" end
local H = DATA.lifters(SPECIAL, warn, say, echo_check, data_bytes, range_text, check_asked, check_data_echo,
  past_quantity)

-- Register writes by how they are confirmed (data/modbus.toml [confirm]; annotator.py _BY_ECHO, _BY_ANSWER):
-- by their echo (FC6), by a normal answer (FC16, FC23).
local CONFIRMED = RULES.confirmed

local function decode_frame(f)
  local b, d, len = f.b, f.data_at, f.data_len
  if f.slave > MAX_SLAVE then warn(f, say("reserved_slave", { slave = f.slave })) end
  if f.kind == EXCEPTION then
    -- (its layout's reader: no code is malformed, bytes after it trailing, as decode/fields.py says)
    local used, why = PARSERS.exception(b, d, len)
    f.fields = {}
    if used == nil then
      warn(f, say("malformed", { kind = f.kind, error = why }))
      return
    end
    f.exception_code = b[d]
    if EXCEPTIONS[f.exception_code] == nil then
      warn(f, say("unknown_exception", { code = f.exception_code }))
    end
    if used < len then warn(f, say("trailing", { count = len - used })) end
    return
  end
  local used, fields = (GRAMMARS[f.kind][f.fn] or PARSERS.raw)(b, d, len)
  if used == nil then -- (fields: the reason)
    f.fields = nil
    f.malformed = true
    warn(f, say("malformed", { kind = f.kind, error = fields }))
    return
  end
  f.fields = fields
  local handler = H[f.kind][f.fn]
  if handler ~= nil then handler(f, b) end
  local request = f.request
  if request ~= nil and not verified(request) and WINDOW_ASKED[f.fn] then
    -- Its request failed its check (annotate_with kept none of its fields): no addresses
    -- (decode/fields.py lifter, pairing.py trusted_request).
    note(f, say("request_damaged", { check = f.ascii and "LRC" or "CRC" }))
  end
  if used < len then warn(f, say("trailing", { count = len - used })) end
  if f.broadcast and NOT_BROADCAST[f.fn] then
    warn(f, say("not_broadcast", { ["function"] = function_name(f.fn) }))
  end
end
M.CONFIRMED, M.DIAGNOSTICS, M.EXCEPTIONS, M.FUNCTIONS = CONFIRMED, DIAGNOSTICS, EXCEPTIONS, FUNCTIONS
M.LIFT_OF, M.LIMITS, M.NOT_BROADCAST, M.bit_at = LIFT_OF, LIMITS, NOT_BROADCAST, bit_at
M.decode_frame, M.exception_name, M.fill, M.function_name = decode_frame, exception_name, fill, function_name
M.hex_of, M.note, M.printable_ascii, M.register_at = hex_of, note, printable_ascii, register_at
M.release_run, M.say, M.trusted_request, M.u16, M.verified = release_run, say, trusted_request, u16, verified
M.warn = warn
end

-- ---- vw3.pairing: lua/src/pairing.lua ----
package.preload["vw3.pairing"] = function(...)
-- vw3.pairing: requests and responses paired, timeouts.
-- Mirrors dissector/decode/pairing.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.pairing"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, EXCEPTION, NS, REQUEST, RESPONSE, awaits_answer = DATA, EXCEPTION, NS, REQUEST, RESPONSE, awaits_answer
local echoed, format, next, note, part_reason, release_run = echoed, format, next, note, part_reason, release_run
local say, sent_in, string_of, table, warn = say, sent_in, string_of, table, warn
local PLAIN = DATA.plain_texts -- (the catalogue's texts without parameters: unmatched, never_answered, ...)
local ECHO = DATA.pairing.echo
-- Times are integer nanoseconds (show.lua record_ns); seconds are their differences divided once by NS
-- (vw3.stream's), as vw3-decode's Stamps subtract (model.py Stamp.__sub__): the same doubles, the same digits.
-- FC8's sub-functions that enter and leave Listen Only Mode (Application Protocol 6.8.1; pairing.py's).
local FC8_CODE, SUB_LISTEN_ONLY, SUB_RESTART = table.unpack(DATA.pairing.listen_only)

-- ---------------------------------------------------------------------------------------------------
-- Pairing (dissector/decode/pairing.py): a response answers the open request with its slave and function
-- when it echoes what the spec has it echo (DATA.pairing.echo: an FC8 sub-function); a broadcast awaits nothing
-- (a response from slave 0 answers nothing, with a warning: after a broadcast of its function, naming it),
-- and a request the spec has no server answer (awaits_answer, vw3.stream's: FC8 04) only an exception (the framer
-- awaits nothing after it), never unanswered (f.answerless).
-- The timeout rule: a frame later than the timeout after the open request was sent ends the wait (unanswered).
-- Time going backwards: an answer stamped before its request still answers it, with a warning (its
-- negative response time is shown as it is and left out of the response times).
-- The retry rule (pairing.py): a frame identical to the open request (FC5, FC6, FC8's echo), later than the
-- timeout, is the master's retry, and the frame after it the framer would read as its answer answers it;
-- until the framer's expectation agrees again (st.retried, st.echoed), a frame of SAME_SHAPE takes the kind
-- the framer would have given it.

-- Listen Only Mode (pairing.py _listen_only): after 08/04 (to the slave or broadcast) a slave answers nothing,
-- until 08/01 (to it or broadcast), which it acts on but does not answer. st.listening (nil: no slave in the
-- mode): the 08/04 each slave is in it since (false: left it); st.listening_all: the broadcast one, for the
-- others. The 08/04 a slave is in the mode since (nil: not in it).
local function listening_since(st, slave)
  local listening = st.listening
  if listening == nil or slave == 0 then return nil end
  local since = listening[slave]
  if since == nil then since = st.listening_all end
  return since or nil -- (false: left the mode)
end

-- The slave leaves the mode (a broadcast 08/04 keeps the others in it).
local function leave(st, slave)
  local listening = st.listening
  if st.listening_all ~= nil then
    listening[slave] = false
  else
    listening[slave] = nil
    if next(listening) == nil then st.listening = nil end
  end
end

-- The texts' values for a slave in the mode since the 08/04 `since` (listen_only, listen_only_answered, ...).
local function listen_values(slave, since)
  return { slave = slave, number = since.number, how = since.slave == 0 and PLAIN.listen_only_broadcast or "" }
end

-- Follows the mode through request f; returns the 08/04 its slave was in the mode since (nil: not in it) and
-- f's sub-function (nil: not an intact FC8 request, which no slave acts on).
-- A slave taken to be in the mode answered (pairing.py _heard): it is not in it; its request's note goes.
local function heard(st, request, answer)
  local slave = request.slave
  local since = listening_since(st, slave)
  if not since then return end -- (the 08/01 that ended the mode: already out of it)
  leave(st, slave)
  local values = listen_values(slave, since)
  local said, notes, kept = say("listen_only", values), request.notes or {}, {}
  for index = 1, #notes do
    if notes[index] ~= said then kept[#kept + 1] = notes[index] end
  end
  request.notes = kept[1] ~= nil and kept or nil -- (notes are made with their first: none is nil)
  note(answer, say("listen_only_answered", values))
end

local function listen_only(st, f)
  local slave, listening, since = f.slave, st.listening, listening_since(st, f.slave)
  local sub = nil
  if f.fn == FC8_CODE and f.data_len >= 2 and f.crc == f.crc_expected then
    local b, at = f.b, f.data_at
    sub = b[at] * 256 + b[at + 1]
    if sub == SUB_LISTEN_ONLY and since == nil then
      if slave == 0 then
        st.listening, st.listening_all = {}, f
      else
        if listening == nil then listening = {}; st.listening = listening end
        listening[slave] = f
      end
    elseif sub == SUB_RESTART and listening ~= nil then
      if slave == 0 then
        st.listening, st.listening_all = nil, nil
      else
        leave(st, slave)
      end
    end
  end
  return since, sub
end

-- Codes whose request and answer have the same layout: framed alike, whichever the framer awaits
-- (pairing.py SAME_SHAPE, from the protocol table).
local SAME_SHAPE = DATA.pairing.same_shape

-- What stands for a frame's bytes after its slave and function once its byte table has gone (kept for the open
-- request as st.sent, st.sent_for: which; a key of the frame's own would outgrow its table): a short one's
-- (up to 4 data bytes, FC5 and FC6's) data and CRC (LRC) as one number, exact in a double; a longer one's
-- length and CRC where the CRC is good (nil), its data as a string where it is not: a damaged frame's CRC
-- says nothing of its data (a request whose answer kept its length and CRC but not its data was read as
-- the request again, the master's retry, where vw3-decode's _repeats compares the data).
local function sent_key(f)
  local b, count, at = f.b, f.data_len, f.data_at
  if count > 4 then
    if f.crc == f.crc_expected then return nil end
    return string_of(b, at, count)
  end
  local value = count
  for k = 0, count - 1 do value = value * 256 + b[at + k] end
  return value * 65536 + f.crc
end

-- Are the bytes of `f` (its byte table at hand) those of `request`, its slave and function included? A request
-- whose byte table has gone: what stands for them (sent_key), else (a request not kept) a longer one's length
-- and good CRC.
local function same_bytes(st, request, f)
  if request.slave ~= f.slave or request.fn ~= f.fn or request.length ~= f.length or request.crc ~= f.crc then
    return false
  end
  local a, b = request.b, f.b
  if a == nil then
    if st.sent_for == request then return st.sent == sent_key(f) end
    return f.data_len > 4 and f.crc == f.crc_expected
  end
  local i, j = request.data_at, f.data_at
  for k = 0, f.data_len - 1 do
    if a[i + k] ~= b[j + k] then return false end
  end
  return true
end

-- A request whose wait ended unanswered (but an answerless one, which none was expected of): no answer can
-- ask for its fields and bytes any more, and the stream awaits no answer.
local function unanswered(st, pending)
  pending.unanswered, pending.fields = not pending.answerless, nil
  release_run(pending.registers)
  st.pending = nil
end

-- Do the two agree on the echo over the bytes of it both hold (pairing.py _same_echo)? A frame too short for
-- it (malformed) pairs by its slave and function, as every malformed frame does.
local function same_echo(request, f)
  local asked = request.echoed
  if asked == nil then return true end
  local got = echoed(f)
  local both = #asked < #got and #asked or #got
  return asked:sub(1, both) == got:sub(1, both)
end

-- Does `answer` answer `request` (nil: none): its slave and function, and a normal answer repeats what the
-- spec has it repeat of its request (pairing.py _echoes)?
local function answers(request, answer)
  return request ~= nil and request.slave == answer.slave and request.fn == answer.fn
    and (answer.kind ~= RESPONSE or same_echo(request, answer))
end

-- Would the framer, awaiting `request`'s answer, read `f` as it (rules.py Awaiting._awaited)?
local function awaited_as(request, f)
  return f.slave == request.slave and f.fn == request.fn and same_echo(request, f)
end

-- Would a server answer request f (pairing.py _answered): not one the spec has none answer, not to a slave in
-- Listen Only Mode?
local function answered(st, f)
  return awaits_answer(f) and listening_since(st, f.slave) == nil
end

-- The timeout rule: is `time` later than the timeout after request `pending` was sent (its first byte's time and
-- its characters' at the line's speed, vw3.stream's sent_in: pairing.py _late)?
local function timed_out(st, pending, time)
  return st.timeout ~= nil and time ~= nil and pending.time ~= nil
    and (time - pending.time) / NS - sent_in(pending) > st.timeout
end

local function pair(st, f)
  local pending = st.pending
  local timeout = st.timeout
  local late = nil
  if pending ~= nil and timed_out(st, pending, f.time) then
    unanswered(st, pending)
    late, pending = pending, nil
  end
  local retried, echoed_by = st.retried, st.echoed
  -- (written only when set: a nil written to a key the table lacks makes the key)
  if retried ~= nil or echoed_by ~= nil then st.retried, st.echoed = nil, nil end
  if SAME_SHAPE[f.fn] and f.b ~= nil then
    -- First the kind the framer would have given the frame had it awaited what the pairing awaits.
    local flipped = false
    if f.kind == REQUEST and retried ~= nil and (retried == pending or retried == late) and awaited_as(retried, f) then
      -- What the framer, had it awaited the retry's answer, would have read as that answer (it awaits this
      -- frame's answer now).
      f.kind, flipped = RESPONSE, true
      if awaits_answer(f) then
        if ECHO[f.fn] ~= nil then f.echoed = echoed(f) end
        st.echoed = f
      end
    elseif f.kind == RESPONSE and pending == nil and late == nil and echoed_by ~= nil and awaited_as(echoed_by, f) then
      -- The framer awaited an answer to an answer: had it not, it would have read a request.
      f.kind = REQUEST
      if answered(st, f) then st.retried = f end
    end
    -- The request again, past the timeout (late: the master's retry), or to a slave in Listen Only Mode, which
    -- answers nothing, the 08/01 that ends the mode included (the master's repeat). (The framer read it as an
    -- answer and awaits nothing, unless it read it as a request: flipped. Never both: late leaves no pending.)
    local again = late or not flipped and pending ~= nil and pending.unheard and pending
    if f.kind == RESPONSE and again and same_bytes(st, again, f) then
      f.kind, st.echoed = REQUEST, nil
      if again == late then late = nil end
      if answered(st, f) and not flipped then st.retried = f end
    end
  end
  -- The open 08/04's sub-function alone, intact: its slave's answer after all, against the spec (pairing.py
  -- _echoes_listen_only: pymodbus's server answers so), too short to be the master's repeat (shorter than the
  -- 08/04, of the same mode: its length, which stays once its bytes went, take_frame).
  if f.kind == REQUEST and f.fn == FC8_CODE and f.data_len == 2 and pending ~= nil and st.listening ~= nil and
      st.listening[f.slave] == pending and pending.length > f.length and f.crc == f.crc_expected and
      f.b[f.data_at] * 256 + f.b[f.data_at + 1] == SUB_LISTEN_ONLY then
    f.kind = RESPONSE
    warn(f, PLAIN.listen_only_echo)
  end
  if f.kind == REQUEST then
    if pending ~= nil then unanswered(st, pending) end
    local since, sub = nil, nil
    if f.fn == FC8_CODE or st.listening ~= nil then since, sub = listen_only(st, f) end
    if f.slave == 0 then
      f.broadcast = true
      st.broadcast = f -- (the last request, a broadcast: a response from slave 0 after it answers it wrongly)
    else
      st.broadcast = nil
      if since ~= nil then
        note(f, say(sub == SUB_RESTART and "listen_only_ends" or "listen_only", listen_values(f.slave, since)))
        f.answerless, f.unheard = true, true
      elseif not awaits_answer(f) then
        note(f, PLAIN.never_answered)
        f.answerless = true
      end
      if ECHO[f.fn] ~= nil then f.echoed = echoed(f) end
      if SAME_SHAPE[f.fn] and f.b ~= nil then st.sent, st.sent_for = sent_key(f), f end
      st.pending = f
    end
    return
  end
  if answers(pending, f) then
    local listening = st.listening
    if listening ~= nil and f.kind == EXCEPTION and listening[f.slave] == pending then
      listening[f.slave] = nil -- (it refused the 08/04: not in the mode)
      if next(listening) == nil and st.listening_all == nil then st.listening = nil end
    elseif pending.unheard then
      heard(st, pending, f)
    end
    f.request = pending
    pending.response = f
    st.pending = nil
    if f.time ~= nil and pending.time ~= nil and f.time < pending.time then
      warn(f, say("backwards", { ahead_ms = (pending.time - f.time) / NS * 1000, number = pending.number }))
    end
  elseif answers(late, f) then
    warn(f, say("late", { delay_ms = (f.time - late.time) / NS * 1000, number = late.number,
      timeout_ms = timeout * 1000 }))
  else
    if pending ~= nil then unanswered(st, pending) end
    f.no_request = true
    local broadcast = st.broadcast
    if f.slave == 0 and broadcast ~= nil and broadcast.fn == f.fn then
      warn(f, say("broadcast_answered", { number = broadcast.number }))
    else
      if f.slave == 0 then warn(f, PLAIN.broadcast_address) end
      note(f, PLAIN.unmatched)
    end
  end
end

-- Is the length on the line of a record of which no byte was captured (RTU bytes; an ASCII line 2 characters a
-- byte, its LRC's too, and `:` and CR LF) one an answer to `pending` has (pairing.py _answer_size): its
-- exception's, or its normal answer's where the request fixes it (a fixed length rule; a run of what it asked,
-- DATA.lanes.run_answers), else any from an exception's up?
local RULES, SHORTEST, RUNS = DATA.protocol.rules, DATA.protocol.exception_rule[2], DATA.lanes.run_answers
local function answer_size(pending, part)
  local size = part.check == "CRC" and part.original or (part.original - 1) / 2
  local rule, run, quantity, normal = RULES[pending.fn], RUNS[pending.fn], pending.quantity, nil
  if rule ~= nil and rule[2][1] == "fixed" then
    normal = rule[2][2]
  elseif run ~= nil and quantity ~= nil then
    local bits = (quantity + 7 - (quantity + 7) % 8) / 8 -- (unit 0: bits, 8 a byte)
    normal = run.extra + (run.unit > 0 and quantity * run.unit or bits)
  end
  return size == SHORTEST or size == normal or (normal == nil and size >= SHORTEST)
end

-- A record captured in part (vw3.stream's cut_stream), numbered, of the open request's slave and function (or
-- its exception's), within the timeout: the slave answered, its answer's bytes cut by the snapshot length
-- (pairing.py _answer_in_part, ANSWER_IN_PART). The request is answered, its note names the item, whose reason
-- names the request (`...; slave 2, function 3; the answer to #1): its CRC cannot be checked`); one of no byte
-- captured, where its length fits (answer_size): only the slave asked speaks then.
local function pair_part(st, item)
  local pending = st.pending
  if pending == nil or pending.answerless or timed_out(st, pending, item.time) then return end
  local part = item.part
  if part.slave == nil then -- (no byte captured: its length on the line tells)
    if not answer_size(pending, part) then return end
  elseif part.slave ~= pending.slave or (part.fn ~= nil and part.fn % 128 ~= pending.fn) then return end
  note(pending, format(DATA.pairing.answer_in_part, item.number))
  part.answers = pending.number
  item.reason = part_reason(part)
  pending.fields = nil
  release_run(pending.registers)
  st.pending = nil
  -- (the stream starts clean after the cut: it awaits nothing, as the pairing now)
  if st.retried ~= nil or st.echoed ~= nil then st.retried, st.echoed = nil, nil end
end

-- The capture ends with request f awaiting its answer (the second pass: the first has read it all):
-- pairing.py capture_ended. The capture's last record (any stream's, empty or not: recorded_until; else
-- st.times' last time, as Dissector.finish takes the later) later than the timeout after f was sent (timed_out):
-- the master gave up, unanswered; sooner, the slave may have answered after the capture stopped: not known.
-- Returns whether f is unanswered and its note (st.cut_note: an answer cut by the end, it did answer).
local function ended(st, f)
  local times, timeout, cut = st.times, st.timeout, st.cut_note
  local last = times[#times]
  if recorded_until ~= nil and (not last or recorded_until > last) then last = recorded_until end
  if timed_out(st, f, last) then return true, cut end
  if cut ~= nil then return false, cut end
  local waited = last and f.time and (last - f.time) / NS or nil
  -- (from f's first byte; from when it was sent where that passes the timeout: the note says "within")
  if waited ~= nil and timeout ~= nil and waited > timeout then waited = waited - sent_in(f) end
  if timeout == nil or waited == nil or waited <= 0 then return false, PLAIN.capture_ends_unknown end
  return false, say("capture_ends_within", { waited_ms = waited * 1000, timeout_ms = timeout * 1000 })
end
M.ended, M.pair, M.pair_part = ended, pair, pair_part
end

-- ---- vw3.maps: lua/src/maps.lua ----
package.preload["vw3.maps"] = function(...)
-- vw3.maps: the profile and map preferences, register maps read from CSV.
-- Mirrors dissector/devices/maps.py, dissector/devices/profiles.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.maps"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, LIMITS, MAX_SLAVE, concat, error, fill, floor = DATA, LIMITS, MAX_SLAVE, concat, error, fill, floor
local format, io, ipairs, math, next, pairs, pcall, select = format, io, ipairs, math, next, pairs, pcall, select
local setmetatable, string, tonumber, tostring, type = setmetatable, string, tonumber, tostring, type


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
M.AUTO, M.MESSAGES, M.PLAIN_READS, M.PROFILES, M.READS = AUTO, MESSAGES, PLAIN_READS, PROFILES, READS
M.READ_LIMIT, M.SELECTION, M.parse_map_choice = READ_LIMIT, SELECTION, parse_map_choice
M.parse_profile_choice, M.python_repr = parse_profile_choice, python_repr
end

-- ---- vw3.device: lua/src/device.lua ----
package.preload["vw3.device"] = function(...)
-- vw3.device: a slave's device: its profile, rows, PLC labels; values interpreted by the map.
-- Mirrors dissector/devices/build.py, dissector/devices/maps.py (interpret).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.device"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local AUTO, DATA, MESSAGES, NO_INTERPRETATION, PROFILES = AUTO, DATA, MESSAGES, NO_INTERPRETATION, PROFILES
local SELECTION, concat, fill, floor, format, ipairs = SELECTION, concat, fill, floor, format, ipairs
local made_once, math, next, note, pairs, python_repr, say = made_once, math, next, note, pairs, python_repr, say
local table, tonumber, verified = table, tonumber, verified

-- naming.plc_label: `40001 + address` up to 49999, then 6-digit references (`400001 + address`); coil
-- references keep their zeros (00001). PLC_LABELS[base][address], each label made once (at most 65,536
-- a base: addresses are 16 bits).
local PLC_LABELS = made_once(function(base)
  return made_once(function(address)
    local digits = math.max(5, #format("%d", base))
    local power = 10 ^ (digits - 1)
    local number = base + address
    if number > (floor(base / power) + 1) * power - 1 then
      number, digits = base * 10 - 9 + address, digits + 1
    end
    return format("%0" .. digits .. "d", number)
  end)
end)

local function address_name(row, address, label)
  local shown = label or format("%d", address)
  return row and format("%s (%s)", row.code, shown) or shown
end

-- Neighbouring addresses told as ranges (devices/story.py, explain.py): entries (.address, .row, .label)
-- in runs, an entry joining the run before it where joins(last of the run, entry) holds, each run told as
-- alone(its entry) or, of several, many(run); the texts joined by `, `.
local function runs_told(entries, joins, alone, many)
  local runs, run = {}, nil
  for _, entry in ipairs(entries) do
    if run ~= nil and joins(run[#run], entry) then
      run[#run + 1] = entry
    else
      run = { entry }
      runs[#runs + 1] = run
    end
  end
  for index, each in ipairs(runs) do runs[index] = #each == 1 and alone(each[1]) or many(each) end
  return concat(runs, ", ")
end

local function consecutive(a, b) return b.address == a.address + 1 end

-- A run of several addresses as `first..last`.
local function span_name(run)
  local a, b = run[1], run[#run]
  return (a.label or format("%d", a.address)) .. ".." .. (b.label or format("%d", b.address))
end

-- A shallow copy of a table.
local function copied(t)
  local copy = {}
  for key, value in pairs(t) do copy[key] = value end
  return copy
end

-- maps.overlay: `rows` with a layer's rows `mine` laid over it, in place (a layer row hides every row it
-- overlaps, a 32-bit row's two registers counted).
local function overlay(rows, mine)
  for address, row in pairs(mine) do
    local before = rows[address - 1]
    if before ~= nil and before.words == 2 and mine[address - 1] == nil then rows[address - 1] = nil end
    if row.words == 2 and mine[address + 1] == nil then rows[address + 1] = nil end
  end
  for address, row in pairs(mine) do rows[address] = row end
end

-- A profile's map with the map layers given at run time laid over it, those for which applies(layer); and
-- the rows of its input registers apart (DeviceBuilder.build: a layer in PLC references with 3X rows on a
-- device whose FC4 reads a table of its own), nil when the rows name them too. Where FC4 reads the holding
-- registers (profile one_table, the ATV71), a layer's 3X rows join its 4X rows, a 4X row winning.
local function layered_rows(profile, applies)
  if #config.layers == 0 then return profile.map or {}, nil end
  local rows, inputs, split = copied(profile.map or {}), copied(profile.map or {}), false
  for _, layer in ipairs(config.layers) do
    if applies(layer) then
      local extra = layer.inputs
      if extra ~= nil and profile.one_table then
        overlay(rows, extra)
        overlay(rows, layer.rows)
      else
        overlay(rows, layer.rows)
        overlay(inputs, extra or layer.rows)
        split = split or extra ~= nil
      end
    end
  end
  return rows, split and inputs or nil
end

-- The rows naming the registers a function code reads or writes (Device.rows_for): its table's.
local INPUT_FUNCTIONS = DATA.map_format.input_functions
local function rows_for(device, fn)
  if device.inputs ~= nil and INPUT_FUNCTIONS[fn] then return device.inputs end
  return device.rows
end

-- A map written in PLC references (maps_refs.py, message for message): judged on a slave's first
-- REFERENCES_JUDGED frames with registers (maps_refs.JUDGED); the layers that apply to the slave and could name
-- a register at a reference base past its address (FC3's or FC4's base, or one less), nil when none does.
local REFERENCES_JUDGED = DATA.map_format.references_judged
local function reference_base(profile, fn) return (profile.plc_base or {})[fn] or profile.plc_base_default end

local function reference_check(profile, slave)
  local low = math.min(reference_base(profile, 3), reference_base(profile, 4)) - 1
  local layers = {}
  for _, layer in ipairs(config.layers) do
    if layer.high >= low and (layer.slave == nil or layer.slave == slave)
        and (layer.profile == nil or layer.profile == profile.name) then
      layers[#layers + 1] = { layer = layer, own = {}, unnamed = {}, shifted = { {}, {} }, counts = {
        own = 0, unnamed = 0, 0, 0 } }
    end
  end
  if #layers == 0 then return nil end
  return { frames = 0, layers = layers, left = #layers }
end

-- The 32-bit row whose second register `address` is (naming.wide_before), or false.
local function rows_before(rows, address)
  local before = rows[(address + 0xFFFF) % 0x10000]
  return before ~= nil and before.words == 2 and before
end

-- maps_refs.names: a map names this register, a row of its own or a 32-bit row's second word.
local function map_names(rows, address) return rows[address] ~= nil or rows_before(rows, address) ~= false end

-- maps_refs.offsets_text: `40001`, `40001 or 30001` (integers: the profiles' bases less 0 or 1).
local function offsets_text(offsets)
  local list = {}
  for offset in pairs(offsets) do list[#list + 1] = offset end
  table.sort(list, function(a, b) return a > b end)
  return concat(list, " or ")
end

-- maps_refs.reference_note: the variant (the base itself, 1; one less, 2) naming most registers no map
-- names, when it names more of them than the layer names at their own address.
local function reference_note(judged, slave)
  local counts = judged.counts
  local best = counts[2] > counts[1] and 2 or 1
  if counts[best] == 0 or counts[best] <= counts.own then return nil end
  local offsets = {}
  for _, offset in pairs(judged.shifted[best]) do offsets[offset] = true end
  local offset = offsets_text(offsets)
  -- (the references themselves, not one less, in a map without a `reference` column: that column reads them)
  local column = (best == 1 and not judged.layer.references) and fill(MESSAGES.references_column, {}) or ""
  return fill(MESSAGES.references, { map = judged.layer.name, unnamed = counts.unnamed, slave = slave,
    shifted = counts[best], offset = offset, column = column }, python_repr)
end

-- A frame annotated by take_frame: counted while the slave's device judges (maps_refs.ReferenceCheck.observe),
-- the deciding frame noted. Distinct registers by (reference base, address), as the Python check counts them.
local function check_references(f, device)
  local refs = device and device.refs
  local registers = f.registers
  if refs == nil or not device.refs_open or registers == nil or registers.count == 0 or f.slave == 0
      or f.provisional or not verified(f) then
    return
  end
  refs.frames = refs.frames + 1
  if refs.frames >= REFERENCES_JUDGED then device.refs_open = false end
  local base = reference_base(device.profile, f.fn)
  local rows, start = rows_for(device, f.fn), registers.start
  for _, judged in ipairs(refs.layers) do
    if not judged.done and start ~= nil then
      local mine, counts = judged.layer.rows, judged.counts
      if judged.layer.inputs ~= nil and rows == device.inputs then mine = judged.layer.inputs end
      for index = 0, registers.count - 1 do
        local address = (start + index) % 0x10000
        local key = base * 65536 + address
        if map_names(mine, address) then
          if not judged.own[key] then judged.own[key], counts.own = true, counts.own + 1 end
        elseif not map_names(rows, address) then
          if not judged.unnamed[key] then judged.unnamed[key], counts.unnamed = true, counts.unnamed + 1 end
          for variant = 1, 2 do
            local offset = base - variant + 1
            local shifted = judged.shifted[variant]
            if address + offset <= 0xFFFF and shifted[key] == nil and map_names(mine, address + offset) then
              shifted[key], counts[variant] = offset, counts[variant] + 1
            end
          end
        end
      end
      local said = reference_note(judged, f.slave)
      if said ~= nil then
        note(f, said)
        judged.done, refs.left = true, refs.left - 1
        if refs.left == 0 then device.refs_open = false end
      end
    end
  end
end

-- The device of a slave under a profile: merged map, bits_depend rules, address style, and its own
-- parameter memory (a new profile for a slave starts a new memory, as the annotator builds a new Device).
local function build_device(profile, slave)
  local rows, inputs = layered_rows(profile, function(layer)
    return (layer.slave == nil or layer.slave == slave) and (layer.profile == nil or layer.profile == profile.name)
  end)
  local depend, plain = {}, {}
  for _, rule in ipairs(profile.bits_depend or {}) do
    for _, address in ipairs(rule.registers) do
      local row = rows[address]
      if row ~= nil then
        depend[address] = rule
        plain[address] = copied(row)
        plain[address].bits = nil
      end
    end
  end
  local style = config.style or profile.address_style
  local device = { profile = profile, rows = rows, depend = depend, plain = plain, plc_default = profile.plc_base_default,
    seen = {}, inputs = inputs }
  -- Parameters are followed only where it tells something: protection, or bits that depend on a value.
  device.track = profile.protected_value ~= nil or next(depend) ~= nil
  if style == "plc" then device.plc = profile.plc_base or {} end
  -- (a write is checked against the map's read-only rows only where it has one, access.written_read_only)
  for _, row in pairs(rows) do
    if row.read_only then device.read_only = true break end
  end
  device.refs = reference_check(profile, slave)
  device.refs_open = device.refs ~= nil -- (the quick lanes leave its frames to take_frame while it judges)
  return device
end

local function device_for(st, slave)
  local device = st.devices[slave]
  if device ~= nil then return device end
  -- The profile the slave has now (annotator.py profile_for): forced per slave, chosen by `auto` (only
  -- auto chooses: select_device), or the default (auto: the fallback).
  local name = config.per_slave[slave] or (st.chosen and st.chosen[slave]) or config.default
  local profile = PROFILES[name == AUTO and SELECTION.fallback or name]
  device = profile ~= nil and build_device(profile, slave) or false
  st.devices[slave] = device
  return device
end

-- The device a frame was annotated with: a slave's device changes only when `auto` chooses (rarely), so
-- the changes are kept per slave, { item number from which on, device, reason }, rather than a key per
-- frame. Second value: why `auto` gave the slave that device (Frame.profile_choice), nil before a choice.
local function device_of(st, f)
  local history = st.history and st.history[f.slave]
  if history ~= nil then
    for k = #history, 1, -1 do
      if history[k].number <= f.number then return history[k].device, history[k].reason end
    end
  end
  return device_for(st, f.slave)
end

local function has_note(f, text)
  for _, existing in ipairs(f.notes or NO_INTERPRETATION) do
    if existing == text then return true end
  end
  return false
end

local FIXED = made_once(function(decimals) return "%." .. decimals .. "f" end)

-- A value times its row's scale (none: 1), rounded to the decimals the scale was written with, and its text
-- (unit and all).
local function scaled_value(row, value)
  local decimals = row.decimals or 0
  local text = format(FIXED[decimals], value * (row.scale or 1))
  local scaled = tonumber(text)
  if decimals == 0 then scaled = floor(scaled + 0.5) end
  if row.unit ~= nil then text = text .. " " .. row.unit end
  return scaled, text
end

local BIT_NAMES, NO_BIT_SET = DATA.bit_names, DATA.plain_texts.no_bit_set -- (maps.py's texts, filled in)

-- maps.interpret: the scaled value and its display text.
local function interpret(row, value)
  local raw_value = value
  if row.signed and value >= 0x8000 then raw_value = value - 0x10000 end
  if row.enum then return nil, row.enum[value] or say("not_listed", { value = value }) end
  if row.bits then
    local names, bits, rest = {}, row.bits, value
    for bit_ = 0, 15 do
      if rest % 2 == 1 then
        names[#names + 1] = bits[bit_] or BIT_NAMES[bit_]
        rest = rest - 1
      end
      rest = rest / 2
    end
    return nil, #names == 0 and NO_BIT_SET or concat(names, ", ")
  end
  if row.scale_unknown then
    -- the device's settings choose the scale (ACC/DEC: the ramp increment): the raw value, and the unit it
    -- counts in unscaled
    return row.signed and raw_value or nil, say("unscaled", { value = raw_value, unit = row.unit })
  end
  -- (no scale, no unit, unsigned: the word itself; else a number, in its unit where it has one)
  if row.scale == nil and row.unit == nil and not row.signed then return nil, nil end
  return scaled_value(row, raw_value)
end

-- maps._shortest: the fewest significant digits (1 to 9) of `value` nearer to it than half the gap to a
-- neighbour (`spacing` away from zero, `below` toward it; exactly half way, the `even` one takes it), as %.7g
-- writes them. maps.float32_text: a float32 times its scale, the gaps scaled alike.
local function shortest(value, spacing, below, even)
  for digits = 1, 8 do
    local text = format("%." .. digits .. "g", value)
    local gap = math.abs(tonumber(text)) - math.abs(value)
    local half = (gap < 0 and below or spacing) / 2
    if math.abs(gap) < half or (math.abs(gap) == half and even) then
      if value == 0 then return text end -- (Lua 5.4 reads "-0" as the integer 0)
      return format("%." .. math.max(digits, 7) .. "g", tonumber(text)) -- (the same digits: 50, not 5e+01)
    end
  end
  return format("%.9g", value) -- (9 digits always tell a float32 from its neighbours)
end

-- maps.interpret_wide: a 32-bit value from the words of its two registers, in the order they come.
local function interpret_wide(row, first, second)
  local high, low = first, second
  if row.swapped then high, low = second, first end
  local value, text
  if row.kind == "float32" then
    -- IEEE 754 single precision, from its fields (no bitwise operators in Lua 5.2); the sign a float: Lua
    -- 5.4's integer -1 * 0 would lose the sign of -0.0
    local sign = high >= 0x8000 and -1.0 or 1.0
    local exponent = floor(high / 128) % 256
    local fraction = (high % 128) * 65536 + low
    local spacing = 2 ^ -149
    if exponent == 255 then -- (no number JSON can hold)
      return nil, fraction ~= 0 and "nan" or sign > 0 and "inf" or "-inf"
    elseif exponent == 0 then
      value = sign * fraction * spacing
    else
      spacing = 2 ^ (exponent - 150)
      value = sign * (8388608 + fraction) * spacing
    end
    -- (a float has no fixed decimals: the scale multiplies; the product written as the float is, and its
    -- value as the text says it)
    local below = (fraction == 0 and exponent > 1) and spacing / 2 or spacing
    local scale = row.scale or 1.0
    local size = math.abs(scale)
    text = shortest(value * scale, spacing * size, below * size, low % 2 == 0)
    if row.scale ~= nil then value = tonumber(text) + 0.0 end
  else
    value = high * 65536 + low
    if row.kind == "int32" and high >= 0x8000 then value = value - 4294967296 end
  end
  if text == nil then return scaled_value(row, value) end
  if row.unit ~= nil then text = text .. " " .. row.unit end
  return value, text
end
M.INPUT_FUNCTIONS, M.PLC_LABELS, M.address_name = INPUT_FUNCTIONS, PLC_LABELS, address_name
M.build_device, M.check_references, M.consecutive, M.copied = build_device, check_references, consecutive, copied
M.device_for, M.device_of, M.has_note, M.interpret = device_for, device_of, has_note, interpret
M.interpret_wide, M.layered_rows, M.rows_before, M.rows_for = interpret_wide, layered_rows, rows_before, rows_for
M.runs_told, M.span_name = runs_told, span_name
end

-- ---- vw3.story: lua/src/story.lua ----
package.preload["vw3.story"] = function(...)
-- vw3.story: the parameter story (became protected, readable again) and registers annotated.
-- Mirrors dissector/devices/story.py, dissector/devices/memory.py, dissector/devices/annotator.py (registers).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.story"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local PLC_LABELS, address_name, consecutive, has_note = PLC_LABELS, address_name, consecutive, has_note
local interpret, interpret_wide, ipairs, math, next, note = interpret, interpret_wide, ipairs, math, next, note
local register_at, rows_before, rows_for, runs_told, say = register_at, rows_before, rows_for, runs_told, say
local span_name, table = span_name, table

-- Parameter events of one frame, told as one note per event kind and past (devices/story.py):
-- neighbouring addresses as ranges, `39193..39288 readable again (96): non-existent in frame #1576`.
-- (The texts are data/modbus.toml [texts]: became_protected, event_one, event_runs, ...)
local story = {} -- tell(), plain_rule()

function story.tell(f)
  local events = f.events
  if events == nil then return end -- (most frames: before the closure below is made)
  local function event_name(e) return address_name(e.row, e.address, e.label) end
  f.events = nil
  local groups, order = {}, {}
  for _, e in ipairs(events) do
    local key = e.what .. "\0" .. e.how .. "\0" .. e.frame .. "\0" .. (e.now_shared or "")
    local group = groups[key]
    if group == nil then group = {}; groups[key] = group; order[#order + 1] = group end
    group[#group + 1] = e
  end
  for _, group in ipairs(order) do
    local first = group[1]
    if #group == 1 then
      first.name = event_name(first)
      note(f, say("event_one", first))
    else
      table.sort(group, function(a, b) return a.address < b.address end)
      note(f, say(first.now_shared and "event_runs_now" or "event_runs", { what = first.what, count = #group,
        runs = runs_told(group, consecutive, event_name, span_name), how = first.how, frame = first.frame,
        now = first.now_shared }))
    end
  end
end

-- The parameter memory (devices/memory.py): per address its value (nil: unreadable), the frame and how
-- it was known; an entry there is changed in place (the quick lanes hold the entries they will change).
-- (By address alone: the one profile here that follows parameters, the ATV71, reads its input registers as
-- its holding registers, profile input_registers "holding"; Python keeps a separate table's apart,
-- Device.memory, for a user's profile, which the plugin does not load.)
local function remember(seen, address, value, number, how)
  local last = seen[address]
  if last ~= nil then
    last.value, last.frame, last.how = value, number, how
  else
    seen[address] = { value = value, frame = number, how = how }
  end
end

-- A register's status followed (memory.py lost, readable_again): an event when it changes the story.
local function track(seen, f, address, row, value, status, now, label)
  local last = seen[address]
  local what, before, shared = nil, nil, nil
  if status == "ok" then
    if last ~= nil and last.value == nil then
      what, before, now = "readable_again", last.how, say("value_now", { value = value })
    end
  elseif status == "protected" or status == "non-existent" then
    if last ~= nil and last.value ~= nil then
      what, before, shared = row ~= nil and "became_protected" or "became_unknown", say("known_value", last), now
    end
    value = nil
  else
    return
  end
  if what ~= nil then
    local events = f.events or {}
    f.events = events
    events[#events + 1] = { what = say(what, {}), address = address, row = row, label = label, before = before,
      how = last.how, frame = last.frame, now = now, now_shared = shared }
  end
  remember(seen, address, value, f.number, status == "ok" and "read" or status)
end

local function remember_writes(seen, number, run, b)
  if run.start == nil then return end
  for index = 0, run.count - 1 do
    local address, value = register_at(run, b, index)
    remember(seen, address, value, number, "written")
  end
end

-- A Mask Write its echo confirms ([confirm] "mask", memory.remember_mask): the register holds (current AND
-- and_mask) OR (or_mask AND NOT and_mask) (Application Protocol 6.16); where the current value is not known
-- (and_mask 0 replaces every bit), the parameter is forgotten.
-- (bit by bit, low first: the current value's where and_mask has a 1, or_mask's where it has a 0)
local function remember_mask(seen, number, fields)
  local and_mask, or_mask, last = fields.and_mask, fields.or_mask, seen[fields.address]
  local current = and_mask == 0 and 0 or last ~= nil and last.value or nil
  if current == nil then
    seen[fields.address] = nil
    return
  end
  local value, weight = 0, 1
  for _ = 1, 16 do
    if (and_mask % 2 == 1 and current or or_mask) % 2 == 1 then value = value + weight end
    current, and_mask, or_mask = math.floor(current / 2), math.floor(and_mask / 2), math.floor(or_mask / 2)
    weight = weight * 2
  end
  remember(seen, fields.address, value, number, "written")
end

-- What register `index` of a frame's consecutive registers is of a 32-bit map row (naming.name_wide):
-- 2 its first word (the value is read here), 0 its second word, 1 a register on its own.
local function words_at(rows, address, index, count)
  local row = rows[address]
  if row ~= nil and row.words == 2 and index + 1 < count then return 2 end
  return index > 0 and rows_before(rows, address) and 0 or 1
end

-- The bits_depend rule under which the register at `address` (its map row `row`) is read with its plain
-- layout now (the register it depends on last held a value that says so), or nil.
function story.plain_rule(device, address, row)
  local rule = row ~= nil and row.words ~= 2 and device.depend[address]
  local last = rule and device.seen[rule.on]
  if last and last.value ~= nil and rule.plain_when[last.value] then return rule end
  return nil
end

-- (16#8000's texts, memory.py's: data/modbus.toml [texts]; a register's by its status, no value left)
local MARKER_NOW = say("marker_now", {})
local MARKER_TEXTS = { ["non-existent"] = say("marker_non_existent", {}), protected = say("marker_protected", {}) }

-- One register of a frame, in capture order: is it read with its plain layout (a bits_depend rule), and
-- its 16#8000 status (nil: the profile has none, or this is no read). Notes and the story go on.
local function annotate_one(f, device, address, value, protected, multi, label, words)
  local rows = rows_for(device, f.fn) -- (FC4's: a map in references' 3X rows, where they are apart)
  local row = rows[address]
  local rule = rows == device.rows and story.plain_rule(device, address, row) or nil -- (rules: holding's)
  if rule ~= nil and not has_note(f, rule.reason) then note(f, rule.reason) end
  local status = nil
  if protected ~= nil then
    status = "ok"
    -- (a word of a 32-bit value is no parameter on its own)
    if value == protected and multi and words == 1 then
      if row == nil then -- (a 32-bit value's second word alone: that value's 16#8000, as its first's)
        status = rows_before(rows, address) and "ambiguous" or "non-existent"
      else
        status = row.ambiguous_8000 and "ambiguous" or "protected"
      end
    end
    track(device.seen, f, address, row, value, status, MARKER_NOW, label)
  end
  return rule ~= nil, status
end

-- Every value at 16#8000 where the device answers an exception when every parameter is unreadable (p.38;
-- annotator._all_marked): one at least is the value itself, so each is ambiguous and none is followed.
-- (the run's count values from b[first] on)
local function all_marked(f, device, count, b, first, protected)
  local code = device.profile.all_protected_exception
  if code == nil then return false end
  for k = first, first + 2 * count - 2, 2 do
    if b[k] * 256 + b[k + 1] ~= protected then return false end
  end
  note(f, say("all_marked", { protected = protected, device = device.profile.device, code = code }))
  return true
end

local function plc_base(device, f)
  return device.plc and (device.plc[f.fn] or device.plc_default)
end

-- The display addresses of a frame's registers on a PLC-style device (`40101`), false on any other:
-- describe's `labels`, which a caller naming many registers of one frame finds once (register_view).
local function frame_labels(device, f)
  return device.plc ~= nil and PLC_LABELS[plc_base(device, f)]
end

-- A register of f as the display shows it (reg: its address and value; naming.name_register, name_wide):
-- the map row that names it, its scaled value and text, status, part of a 32-bit value (words; `second`:
-- the next word, when words is 2) and PLC label (`labels`: frame_labels', nil to find them), from the plain
-- layout flag (a bits_depend rule) and its status: maps.interpret / interpret_wide, then the 16#8000 texts.
local function describe(device, f, reg, plain, status, words, second, labels)
  local rows, address, value = rows_for(device, f.fn), reg.address, reg.value
  local row = rows[address]
  local named, scaled, text = row, nil, nil
  if row ~= nil then -- (nested: most registers of a frame have no row, and each test here is paid per register)
    if row.words ~= 2 then
      scaled, text = interpret(plain and device.plain[address] or row, value)
    elseif words == 2 then
      scaled, text = interpret_wide(row, value, second)
    else
      text = say("first_word", row)
    end
  elseif words == 0 then -- (a row of its own names a second word as any register, naming.py's loop)
    named = rows_before(rows, address)
    text = say("second_word", named)
  else
    local before = rows_before(rows, address) -- (its first word is not in the frame: naming.name_second_alone)
    if before then named, text = before, say("second_word_alone", before) end
  end
  if MARKER_TEXTS[status] ~= nil then scaled, text = nil, MARKER_TEXTS[status] end
  reg.row, reg.scaled, reg.text, reg.status, reg.words = named, scaled, text, status, words
  if labels == nil then labels = frame_labels(device, f) end
  if labels then reg.label = labels[address] end
end

-- A run of a frame: what the display cannot find again from the bytes is kept, and only where it is
-- not the usual: the statuses other than ok, the registers read with their plain layout.
local function annotate_registers(f, device, run, b, read)
  local start = run.start
  if start == nil then return end
  local protected = read and device.profile.protected_value or nil
  local count, first = run.count, run.first
  local multi = count > 1
  if multi and protected ~= nil and b[first] * 256 + b[first + 1] == protected -- (the usual answer: no call)
      and all_marked(f, device, count, b, first, protected) then
    protected = nil
    run.status = {}
    for index = 0, count - 1 do run.status[index] = "ambiguous" end
  end
  -- Nothing to follow: no 16#8000 story, no layout that depends on another register.
  if protected == nil and next(device.depend) == nil then return end
  local labels = frame_labels(device, f)
  local rows = rows_for(device, f.fn)
  for index = 0, count - 1 do
    local k = first + 2 * index
    local address = (start + index) % 0x10000
    local label = labels and labels[address]
    local plain, status = annotate_one(f, device, address, b[k] * 256 + b[k + 1], protected, multi, label,
      words_at(rows, address, index, count))
    if plain then
      run.plain = run.plain or {}
      run.plain[index] = true
    end
    if status ~= nil and status ~= "ok" then
      run.status = run.status or {}
      run.status[index] = status
    end
  end
  story.tell(f)
end
M.annotate_registers, M.describe, M.frame_labels, M.plc_base = annotate_registers, describe, frame_labels, plc_base
M.remember_mask, M.remember_writes, M.story, M.track = remember_mask, remember_writes, story, track
M.words_at = words_at
end

-- ---- vw3.explain: lua/src/explain.lua ----
package.preload["vw3.explain"] = function(...)
-- vw3.explain: device checks of requests, exceptions explained, device objects and diagnostics.
-- Mirrors dissector/devices/checks.py, dissector/devices/explain.py, dissector/devices/objects.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.explain"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, LIFT_OF, NOT_BROADCAST, PLAIN_READS, READS = DATA, LIFT_OF, NOT_BROADCAST, PLAIN_READS, READS
local READ_LIMIT, REQUEST, RESPONSE, address_name, concat = READ_LIMIT, REQUEST, RESPONSE, address_name, concat
local consecutive, format, frame_labels, function_name = consecutive, format, frame_labels, function_name
local ipairs, lane, math, next, note, rows_for, runs_told = ipairs, lane, math, next, note, rows_for, runs_told
local say, span_name, story, tonumber, track = say, span_name, story, tonumber, track
local trusted_request, u16, verified, warn = trusted_request, u16, verified, warn

-- Each quantity request f's lifting rule checks (FC23: read and write, as the spec's checks name them; without
-- its fields, as vw3_modbus.lua remembers a request, its quantity) with the device's limit for it (nil: none):
-- judge(f, profile, what, quantity, limit) until one returns true.
local function quantities(f, profile, limits, judge)
  local rule = LIFT_OF[REQUEST][f.fn]
  if rule == nil or rule.write_window == nil or f.fields == nil then
    return judge(f, profile, "quantity", f.quantity, limits[1])
  end
  for index, check in ipairs(rule.checks) do
    if judge(f, profile, check.what, f.fields[check.field], limits[index]) then return true end
  end
  return false
end

-- A quantity above the device's limit for the function (limit: nil when the device gives none). (Here a
-- function is named as its frame shows it: f.function_text, the profile's name annotate_with set, or the spec's.)
local function check_limit(f, profile, what, quantity, limit)
  if limit ~= nil and quantity ~= nil and quantity > limit then
    warn(f, say("device_limit", { what = what, quantity = quantity, device = profile.device, limit = limit,
      name = f.function_text or function_name(f.fn) }))
  end
end

local function check_request(f, device)
  local profile = device.profile
  local code = f.fn
  local refused = profile.functions ~= nil and not profile.functions[code] and "not_supported"
    or profile.inner_only[code] and "inner_only"
  local sub = f.subfunction
  if refused then
    warn(f, say(refused, { name = f.function_text or function_name(code), ["function"] = code, device = profile.device }))
  elseif sub ~= nil and profile.subfunctions ~= nil and DATA.diagnostics[sub] ~= nil and not profile.subfunctions[sub] then
    warn(f, say("subfunction_not_supported", { subfunction = sub, name = DATA.diagnostics[sub], device = profile.device }))
  end
  local limits = profile.limits[code]
  if limits ~= nil then quantities(f, profile, limits, check_limit) end
  -- (decode_frame already warned where the spec's own rule forbids the broadcast)
  if f.broadcast and profile.broadcast ~= nil and not profile.broadcast[code] and not NOT_BROADCAST[code] then
    warn(f, say("device_broadcast", { name = f.function_text or function_name(code), device = profile.device,
      allowed = profile.broadcast_allowed }))
  end
end

-- The read-only parameters (map access R: row.read_only) a write request touches, named `ETA (3201)`
-- (access.written_read_only): FC6, FC16, FC23 by the registers written (a run), FC22 by its address.
local REGISTER_WRITES, MASK_WRITTEN = DATA.rules.confirmed, DATA.rules.by_confirm.mask
local READ_ONLY = DATA.map_format.read_only -- the access of a parameter no write changes (devices/access.py)
local NONE = {} -- (read only, never changed: a device without a read-only row has none to name)
local function written_read_only(f, device)
  if not device.read_only then return NONE end -- (no list of the addresses written made for nothing)
  local rows, named, code, addresses = rows_for(device, f.fn), {}, f.fn, {}
  local run = f.registers
  if REGISTER_WRITES.echo[code] or REGISTER_WRITES.answer[code] then
    if run ~= nil and run.start ~= nil and run.count ~= nil then
      for index = 0, run.count - 1 do addresses[#addresses + 1] = (run.start + index) % 0x10000 end
    end
  elseif MASK_WRITTEN[code] and f.start ~= nil then
    addresses[1] = f.start
  end
  local labels = frame_labels(device, f) -- (a PLC-style device's reference, as the frame shows it: `SPD (40101)`)
  for _, address in ipairs(addresses) do
    local row = rows[address]
    if row ~= nil and row.read_only then
      named[#named + 1] = address_name(row, address, labels and labels[address])
    end
  end
  return named
end

-- A write request's read-only parameters, one warning each (access.check_writes).
local function check_writes(f, device)
  for _, parameter in ipairs(written_read_only(f, device)) do
    warn(f, say("read_only", { parameter = parameter, access = READ_ONLY }))
  end
end

local function outside(_, _, _, quantity, limit)
  return limit ~= nil and quantity ~= nil and not (quantity >= 1 and quantity <= limit)
end

local function holds(when, request, profile)
  local fields = request.fields
  if when == "quantity" then
    -- Every quantity the request's lifting rule checks (as check_request warns of them) outside the device's
    -- limit for it (without one, a read's READ_LIMIT): explain._holds
    return quantities(request, profile, profile.limits[request.fn] or { READ_LIMIT }, outside)
  end
  return when == "byte_count" and fields ~= nil and fields.byte_count ~= nil and fields.quantity ~= nil
    and fields.byte_count ~= 2 * fields.quantity
end

local function pick_causes(request, profile, causes)
  if request == nil then return causes end
  local hits, plain = {}, {}
  for _, cause in ipairs(causes) do
    if cause.when ~= nil and holds(cause.when, request, profile) then hits[#hits + 1] = cause end
    if cause.when == nil then plain[#plain + 1] = cause end
  end
  return #hits > 0 and hits or #plain > 0 and plain or causes
end

-- An error with the relay counters it increments (explain.counted).
local function counted(error, counters)
  if #counters == 0 then return error end
  return say(#counters > 1 and "cause_counters" or "cause_counter", { error = error,
    counters = concat(counters, " and ") })
end

-- The note of an exception refusing a write of read-only parameters, with the counters the device's causes
-- of the code to the function increment (explain._read_only_note).
local function read_only_note(f, profile, refused, causes)
  local counters, seen = {}, {}
  for _, cause in ipairs(causes and pick_causes(trusted_request(f), profile, causes) or {}) do
    for _, counter in ipairs(cause.counters) do
      if not seen[counter] then counters[#counters + 1], seen[counter] = counter, true end
    end
  end
  local refusal = say("read_only_refusal", { parameters = concat(refused, ", "), access = READ_ONLY })
  return say("exception_meaning", { code = f.exception_code, device = profile.device,
    meaning = counted(refusal, counters) })
end

-- The registers of a read every parameter of which an exception 02 says non-existent or protected
-- (explain._all_unreadable): each address with its row, label and that status, no value.
local function refused_registers(device, request)
  local labels, out = frame_labels(device, request), {}
  for index = 0, math.min(request.quantity, READ_LIMIT) - 1 do
    local address = (request.start + index) % 0x10000
    local row = rows_for(device, request.fn)[address]
    out[index + 1] = { address = address, row = row, status = row == nil and "non-existent" or "protected",
      label = labels and labels[address] or nil }
  end
  return out
end

-- Addresses in a row that are both unmapped (a run of non-existent parameters, told as one range).
local function both_unmapped(a, b) return a.row == nil and b.row == nil and consecutive(a, b) end

local function all_unreadable(f, device)
  -- One note: the device meaning with the parameters of the read (neighbouring unmapped addresses as
  -- a range), then each parameter's story (devices/explain.py).
  local entries = refused_registers(device, f.request)
  local parameters = runs_told(entries, both_unmapped, function(entry)
    return address_name(entry.row, entry.address, entry.label) .. " " .. entry.status
  end, function(run) return say("unmapped_run", { span = span_name(run), count = #run }) end)
  note(f, say("all_unreadable", { code = f.exception_code, device = device.profile.device, parameters = parameters }))
  local now = say("unreadable_now", { code = f.exception_code })
  for _, entry in ipairs(entries) do
    track(device.seen, f, entry.address, entry.row, 0, entry.status, now, entry.label)
  end
end

local function explain_exception(f, device)
  local profile = device.profile
  local code = f.exception_code
  if code == nil then return end
  local name = f.function_text or function_name(f.fn)
  local causes = profile.exception_causes[f.fn * 256 + code]
  local meanings = profile.exceptions
  -- (to a read of registers its all_protected_exception says p.38's clause too: explain.device_meaning)
  local read = READS[f.fn] ~= nil and code == profile.all_protected_exception
  f.exception_meaning = read and profile.all_protected_read or meanings[code]
  local request = trusted_request(f) -- (one that failed its check refused what the tap did not see)
  local refused = code == DATA.read_only_exception and request ~= nil and written_read_only(request, device)
  if refused and #refused > 0 then -- (a write of read-only parameters: named rather than the code's meaning)
    f.exception_meaning = say("read_only_meaning", { access = READ_ONLY })
    note(f, read_only_note(f, profile, refused, causes))
  elseif causes ~= nil and #causes > 0 then
    local texts = {}
    for _, cause in ipairs(pick_causes(request, profile, causes)) do texts[#texts + 1] = cause.text end
    -- (the meaning is the causes the request picks, as the note: explain.exception_meaning)
    f.exception_meaning = concat(texts, " or ")
    note(f, say("exception_cause", { code = code, device = profile.device, name = name,
      causes = f.exception_meaning }))
  -- (a frame that failed its check tells nothing of the parameters, devices/memory.py: only the code's meaning)
  elseif code == profile.all_protected_exception and PLAIN_READS[f.fn] and request ~= nil and verified(f)
      and request.start ~= nil and request.quantity ~= nil and request.quantity > 0 then
    all_unreadable(f, device)
    story.tell(f)
    -- The registers of the refused read, with the status this tells and no value (the display lists
    -- them from the request and the device: inferred_registers), as vw3-decode lists them.
    f.inferred = true
  elseif meanings[code] ~= nil then
    note(f, say("exception_meaning", { code = code, device = profile.device, meaning = f.exception_meaning }))
  elseif next(meanings) ~= nil then
    note(f, say("exception_undocumented", { code = code, device = profile.device, known = profile.documented }))
  end
end

local function explain_objects(f, profile)
  for _, object in ipairs(f.objects) do
    local meaning, value = profile.objects[object.id], object.value
    local size = object.length - 2 -- (its id and length byte, then the bytes sent)
    if meaning ~= nil and meaning.max_length ~= nil and size > meaning.max_length then
      warn(f, say("object_length", { object = object.name, length = size, device = profile.device,
        limit = meaning.max_length }))
    end
    if meaning ~= nil and meaning.format == "MMmm" and value:match("^%d%d%d%d$") then -- (a revision, V5.2)
      object.text = format("V%d.%d", tonumber(value:sub(1, 2)), tonumber(value:sub(3, 4)))
    elseif meaning ~= nil then
      if meaning.format == "MMmm" then
        note(f, say("revision_form", { object = object.name, value = value, device = profile.device }))
      end
      object.text = meaning.meaning
    end
  end
end

local function diagnostics_note(f, device, b)
  local profile = device.profile
  local sub = f.subfunction
  local meaning = profile.diagnostics[sub]
  if meaning == nil then return end
  f.subfunction_text = meaning
  local text = say("subfunction_meaning", { subfunction = sub, device = profile.device, meaning = meaning })
  if f.kind == RESPONSE and f.fields ~= nil and f.fields.data_length == 2 then
    local value = u16(b, f.data_at + 2)
    text = text .. say("subfunction_value", { value = value })
    local constant = profile.diagnostic_constants[sub]
    if constant ~= nil and value ~= constant then
      warn(f, say("diagnostic_constant",
        { subfunction = sub, device = profile.device, constant = constant, value = value }))
    end
  end
  note(f, text)
end

-- naming.window_label: `40501..40504`, one label for a quantity of 0, 1 or none; the last address past 65535
-- as asked.
local function window_label(labels, start, quantity)
  if quantity == nil or quantity <= 1 then return labels[start] end
  return labels[start] .. ".." .. labels[start + quantity - 1]
end

local function span_label(f, device)
  -- `40501..40504` for a PLC-style device, so requests without registers show 4X numbers too; FC23's request
  -- its written window too (annotator._span_label: `write 40006 (0)` where it writes none).
  local labels = frame_labels(device, f)
  f.span_label = window_label(labels, f.start, f.quantity)
  local rule, fields = LIFT_OF[REQUEST][f.fn], f.fields
  if f.kind == REQUEST and rule ~= nil and rule.write_window ~= nil and fields ~= nil then
    local window = rule.write_window
    f.write_span_label = window_label(labels, fields[window[1]], fields[window[2]])
  end
end
lane.span_label = span_label
M.check_request, M.check_writes, M.diagnostics_note = check_request, check_writes, diagnostics_note
M.explain_exception, M.explain_objects, M.refused_registers = explain_exception, explain_objects, refused_registers
M.span_label = span_label
end

-- ---- vw3.selection: lua/src/selection.lua ----
package.preload["vw3.selection"] = function(...)
-- vw3.selection: profile auto: which device each slave is, from evidence in the capture.
-- Mirrors dissector/devices/selection.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.selection"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local INPUT_FUNCTIONS, NOISE, PROFILES, READS, RESPONSE = INPUT_FUNCTIONS, NOISE, PROFILES, READS, RESPONSE
local SELECTION, build_device, concat, copied, device_for = SELECTION, build_device, concat, copied, device_for
local format, ipairs, lane, layered_rows, made_once, math = format, ipairs, lane, layered_rows, made_once, math
local next, note, pairs, register_at, say, span_name, table = next, note, pairs, register_at, say, span_name, table

-- Profile `auto` (devices/selection.py, rule for rule): a slave is taken for a device on evidence, in
-- capture order, as vw3-decode reads its input: a Read Device Identification ProductCode or a function
-- code only that device speaks (final), else its first answers fitting one candidate's map alone (its
-- rows and the maps given for it; 16#8000 where it has none); an answer to a function the chosen device
-- does not support takes the choice back. Until then the fallback: spec semantics only. What a later
-- frame says changes nothing before it, in one pass as with -2: the frames before the evidence are shown
-- as vw3-decode shows them.
local CANDIDATES = SELECTION.candidates
-- The candidate a function code identifies (the first, in the candidates' order, that claims it) and the
-- code's name on it; the ProductCode prefixes that identify one, { prefix, candidate } in that order.
local IDENTIFYING, PRODUCT_CODES = SELECTION.identifying, SELECTION.product_codes
local FIT_ANSWERS, FIT_FRAMES, FIT_READS = SELECTION.fit_answers, SELECTION.fit_frames, SELECTION.fit_reads
local FALLBACK = SELECTION.fallback

-- Does the slave's current choice not support function fn (an answer to it takes the choice back)?
local function unsupported(current, fn)
  local functions = PROFILES[current.profile].functions
  return current.profile ~= FALLBACK and functions ~= nil and not functions[fn]
end

local function settled(judged)
  return judged.answers >= FIT_ANSWERS or judged.frames >= FIT_FRAMES
    or (judged.choice ~= nil and judged.choice.final)
end

-- No device for the slave (none chosen, or the one chosen taken back) while its traffic may still choose
-- one (Selector.open): its frames are provisional. (Written out where every frame asks: lane.quiet.)
local function open(judged)
  local choice = judged.choice
  return (choice == nil or choice.profile == FALLBACK) and not settled(judged)
end

-- A candidate's map as traffic is judged against it: its own rows and the map layers given for it; FC4's
-- registers judged against a map's 3X rows where the device names them apart (layered_rows' inputs;
-- INPUT_FUNCTIONS: lua/src/device.lua's).
local function candidate_rows(name, fn)
  config.fit_rows = config.fit_rows or made_once(function(candidate)
    local rows, inputs = layered_rows(PROFILES[candidate], function(layer) return layer.profile == candidate end)
    return { rows = rows, inputs = inputs }
  end)
  local made = config.fit_rows[name]
  return made.inputs ~= nil and INPUT_FUNCTIONS[fn] and made.inputs or made.rows
end

local function identified(f)
  if f.objects ~= nil and f.kind == RESPONSE then
    for _, object in ipairs(f.objects) do
      if object.id == SELECTION.product_code_object then
        for _, claim in ipairs(PRODUCT_CODES) do
          if object.value:sub(1, #claim[1]) == claim[1] then
            return { profile = claim[2], final = true, reason = say("chosen_product_code",
              { frame = f.number, value = object.value }) }
          end
        end
      end
    end
  end
  if f.kind ~= NOISE and f.crc == f.crc_expected then
    local claim = IDENTIFYING[f.fn]
    if claim ~= nil then
      return { profile = claim[1], final = true, reason = say("chosen_function",
        { ["function"] = f.fn, name = claim[2], frame = f.number }) }
    end
  end
  return nil
end

-- The registers of an answer as { address, value } pairs (a run read from b).
local function register_list(f, b)
  local run = f.registers
  if run == nil then return {} end
  local out = {}
  for index = 0, run.count - 1 do
    local address, value = register_at(run, b, index)
    out[index + 1] = { address = address, value = value }
  end
  return out
end

-- selection._fits: true, an answer the device gives; an address, also its non-existent marker there;
-- false, one it would not give; nil, nothing either way.
local function fits(f, name, registers)
  local profile = PROFILES[name]
  local rows = candidate_rows(name, f.fn)
  if not profile.identify.traffic_fit or next(rows) == nil then return nil end
  if profile.functions ~= nil and not profile.functions[f.fn] then return false end
  if #registers == 0 then return nil end
  local known, marker = 0, nil
  for _, reg in ipairs(registers) do
    if reg.address == nil then return nil end
    if rows[reg.address] ~= nil then
      known = known + 1
    elseif reg.value == profile.protected_value and READS[f.fn] ~= nil then
      marker = marker or reg.address
    else
      return false
    end
  end
  return known > 0 and (marker or true) or nil
end

-- selection._Evidence: the reads a candidate's map explains (found.order: their keys as first seen).
local function enough(found)
  return #found.order >= FIT_READS or (found.marker ~= nil and found.answers >= FIT_READS)
end

-- (the texts: data/modbus.toml [texts] chosen_fit, fit_read, ...; each read named with its first two frames)
local function evidence_reason(found, protected)
  local parts = {}
  for index = 1, math.min(#found.order, FIT_READS) do
    local read = found.reads[found.order[index]]
    read.frame, read.again = read.frames[1], read.frames[2]
    parts[index] = say(read.again and "fit_read_again" or "fit_read", read)
  end
  local reads = table.concat(parts, ", ")
  if #found.order < FIT_READS and found.marker ~= nil and protected ~= nil then
    return say("chosen_fit_marker", { reads = reads, protected = protected, marker = found.marker })
  end
  return say("chosen_fit", { reads = reads })
end

-- A new choice for f.slave when this frame decides (or undoes) one, else nil (Selector.observe).
-- (select_device calls it only for a slave not fixed by the choices of the whole capture)
local function observe(st, f, b)
  local slave = f.slave
  -- (serial slave 0 is the broadcast address; a Modbus/TCP unit 0 is the device itself: f.unit_zero)
  if slave == 0 and not f.unit_zero then return nil end
  local judged = st.judged[slave]
  if judged == nil then
    judged = { answers = 0, frames = 0, evidence = {}, ruled_out = {} }
    st.judged[slave] = judged
  end
  local current = judged.choice
  if current ~= nil and current.final then return nil end
  local judging = not settled(judged)
  judged.frames = judged.frames + 1
  local found = identified(f)
  if found ~= nil then
    judged.choice = found
    -- (the same device, for a new reason: identified after a traffic fit)
    found.same = current ~= nil and current.profile == found.profile
    return found
  end
  if f.kind ~= RESPONSE or f.crc ~= f.crc_expected then return nil end
  judged.answers = judged.answers + 1
  if current ~= nil and current.profile ~= FALLBACK then
    if not unsupported(current, f.fn) then return nil end
    judged.choice = { profile = FALLBACK, final = false, reason = say("chosen_unsupported",
      { ["function"] = f.fn, frame = f.number, device = PROFILES[current.profile].device }) }
    -- (the device taken back is ruled out; the others are judged on, while the slave is)
    judged.ruled_out[current.profile], judged.evidence[current.profile] = true, nil
    return judged.choice
  end
  if not judging then return nil end
  -- Selector._weigh: what this answer says of each candidate; a choice when one alone has enough.
  local registers = register_list(f, b)
  local evidence, ruled_out = judged.evidence, judged.ruled_out
  local ready = nil -- (the candidate whose evidence is enough; false: more than one)
  for _, name in ipairs(CANDIDATES) do
    local verdict = nil
    if not ruled_out[name] then verdict = fits(f, name, registers) end
    if verdict == false then
      ruled_out[name], evidence[name] = true, nil
    elseif verdict ~= nil then
      local found = evidence[name] or { reads = {}, order = {}, answers = 0 }
      evidence[name] = found
      local key = format("%d:%d:%d", f.fn, registers[1].address, #registers)
      local read = found.reads[key]
      if read == nil then
        read = { ["function"] = f.fn, frames = {},
          span = #registers == 1 and format("%d", registers[1].address) or span_name(registers) }
        found.reads[key] = read
        found.order[#found.order + 1] = key
      end
      read.frames[#read.frames + 1] = f.number
      found.answers = found.answers + 1
      if found.marker == nil and verdict ~= true then found.marker = verdict end
    end
    if evidence[name] ~= nil and enough(evidence[name]) then
      ready = ready == nil and name
    end
  end
  if not ready then return nil end
  judged.choice = { profile = ready, final = false,
    reason = evidence_reason(evidence[ready], PROFILES[ready].protected_value) }
  return judged.choice
end

-- Would observe decide nothing with a good frame of slave's function fn, an answer (answer true: no device
-- objects in it) or a request? For a slave met before (and judged, for an answer): true where observe would
-- change nothing (a final choice, or a settled slave: its counts decide nothing more), else the slave's judged
-- table, which the lane that takes the frame counts it in as observe does (answers, frames). false when observe
-- is to weigh the frame (a function that identifies a device, a slave not met or still judged, an answer its
-- device does not support). Changes nothing. (The quick lanes ask this instead.)
function lane.quiet(st, slave, fn, answer)
  if IDENTIFYING[fn] ~= nil then return false end
  local frozen = st.frozen
  if frozen ~= nil and st.fixed[slave] then return frozen[st.count + 1] == nil end -- (the frame that decided says so)
  local judged = st.judged[slave]
  if judged == nil then return false end
  local current = judged.choice
  if current ~= nil and current.final then return true end
  local done = judged.answers >= FIT_ANSWERS or judged.frames >= FIT_FRAMES -- (settled, written out)
  if (current == nil or current.profile == FALLBACK) and not done then return false end -- (open: provisional)
  if answer and current ~= nil and unsupported(current, fn) then return false end
  return done or judged
end

-- A frame provisional (Frame.provisional; st.provisional, lane.again: the later passes show no frame
-- provisional), kept, per slave until its choice, for the chosen device to annotate again
-- (lane.annotate_again; annotator.py _held, _scratch): a copy the annotate path may change freely, taken before the frame is
-- annotated and its bytes released (take_frame): its own runs (its request's too, with their bytes),
-- device objects, no notes or warnings. Bounded: a slave's frames
-- are provisional until FIT_FRAMES of them at most.
local function hold(st, f, b)
  f.provisional, st.provisional = true, true
  local copy = copied(f)
  copy.b, copy.notes, copy.warnings, copy.events = b, nil, nil, nil
  if f.registers ~= nil then copy.registers = copied(f.registers) end
  if f.request ~= nil then
    copy.request = copied(f.request)
    copy.request.registers = f.request.registers and copied(f.request.registers)
  end
  if f.objects ~= nil then
    copy.objects = {}
    for index, object in ipairs(f.objects) do copy.objects[index] = copied(object) end
  end
  st.held = st.held or {}
  local held = st.held[f.slave] or {}
  st.held[f.slave] = held
  held[#held + 1] = copy
end

-- A slave's device from item `number` on and why (`auto`'s reason; nil: none), kept in the slave's history
-- (device_of: the earlier frames keep theirs).
local function keep_device(st, slave, number, device, reason)
  local before = st.devices[slave]
  local history = st.history[slave] or { before and { number = 0, device = before } or nil }
  history[#history + 1] = { number = number, device = device, reason = reason }
  st.history[slave], st.devices[slave] = history, device
end

-- The device for f under profile `auto`: a new one when this frame decides a slave's profile (kept in
-- the slave's history for the display of earlier frames, and said on this frame: f.profile_choice), which
-- then annotates the copies of the slave's provisional frames again (hold; lane.annotate_again).
local function select_device(st, f, b)
  local frozen, slave = st.frozen, f.slave
  if frozen ~= nil and st.fixed[slave] then
    -- Every frame annotated with the device chosen over the whole capture; the frames that chose still
    -- say so (vw3-decode reading a file says where each choice was made too).
    local said = frozen[f.number]
    if said ~= nil then f.profile_choice, f.profile_said = said[2], said[1] end
    return device_for(st, slave)
  end
  local choice = observe(st, f, b)
  if choice == nil then
    -- Read once, no device chosen for the slave yet while evidence may still come: its values are named
    -- with spec semantics only, which its device may name otherwise (annotator.py, Frame.provisional).
    local judged = slave ~= 0 and st.judged[slave]
    -- (decoded again, the capture so far is read as a file: no frame provisional; a record read after
    -- that, in a capture that goes on, is read once again: lane.again's `going_on`)
    if judged and open(judged) and (st.frozen == nil or st.going_on) then
      hold(st, f, b)
    elseif st.held ~= nil and judged and settled(judged) then
      st.held[slave] = nil -- (settled without a choice: the device it has saw those frames)
    end
    return device_for(st, slave)
  end
  -- (said on the later passes, where every frame bears the slave's last reason: the frame it comes from says so)
  st.said[f.number] = { choice.profile, choice.reason }
  -- (choice.same: kept, and said with its new reason from here on, nothing announced, as vw3-decode)
  local device = not choice.same and build_device(PROFILES[choice.profile], slave) or st.devices[slave]
  keep_device(st, slave, f.number, device, choice.reason)
  if not choice.same then
    st.chosen[slave] = choice.profile
    f.profile_choice = choice.reason
    local held = st.held and st.held[slave]
    if held ~= nil then
      st.held[slave] = nil
      lane.annotate_again(st, device, held) -- (defined with the annotate path, lua/src/annotator.lua)
    end
    if open(st.judged[slave]) then -- (a choice taken back: no device while evidence may still come)
      hold(st, f, b)
    end
  end
  return device
end

-- Slave 0 under profile `auto` (Annotator._broadcast): a broadcast reaches every slave, so it is named with
-- the profile of every slave met (forced, or chosen so far; over the whole capture with -2: st.met), its
-- profile reason says so; slaves of different devices, or one met without a device, leave it spec
-- semantics, and a note says why.
local function broadcast_device(st, f)
  local fallback, named, slaves = FALLBACK, {}, {}
  -- (the slaves with a device, forced or chosen so far; then those met without one: unknown)
  for pass, source in ipairs({ config.per_slave, st.chosen, st.met or {}, st.judged }) do
    for slave, name in pairs(source) do
      if pass > 2 then name = "unknown" end
      if slave ~= 0 and name ~= fallback and named[slave] == nil then
        named[slave] = name
        slaves[#slaves + 1] = slave
      end
    end
  end
  table.sort(slaves)
  local name, parts = nil, {}
  for index, slave in ipairs(slaves) do
    name = (index == 1 or name == named[slave]) and named[slave] or false
    parts[index] = format("slave %d %s", slave, named[slave])
  end
  if name == "unknown" then name = nil end -- (every slave met without a device)
  local said = nil -- (the reason the frame says, vw3.profile_reason: Frame.profile_choice)
  if name then
    said = say("broadcast_profile", { profile = name,
      slaves = (#slaves > 1 and "slaves " or "slave ") .. concat(slaves, ", ") })
  elseif name == false then
    note(f, say("broadcast_mixed", { slaves = concat(parts, ", ") }))
  end
  -- Read once, while no slave is met or one met may still get a device, what names a broadcast may change:
  -- provisional.
  if st.frozen == nil or st.going_on then
    local met = false
    for slave, judged in pairs(st.judged) do
      met = met or slave ~= 0
      if open(judged) then f.provisional, st.provisional = true, true end
    end
    if not met then f.provisional, st.provisional = true, true end
  end
  name = name or fallback
  -- (slave 0's device under each profile, built once)
  st.broadcasting = st.broadcasting or made_once(function(named) return build_device(PROFILES[named], 0) end)
  local device, history = st.broadcasting[name], st.history[0]
  local last = history and history[#history]
  if st.devices[0] ~= device or (last and last.reason) ~= said then keep_device(st, 0, f.number, device, said) end
  return device
end

local function device_now(st, f, b)
  if config.auto[f.slave] then
    if f.slave == 0 and not f.unit_zero then return broadcast_device(st, f) end
    return select_device(st, f, b)
  end
  return device_for(st, f.slave)
end
M.device_now = device_now
end

-- ---- vw3.annotator: lua/src/annotator.lua ----
package.preload["vw3.annotator"] = function(...)
-- vw3.annotator: a frame annotated with its device; the per-capture state.
-- Mirrors dissector/devices/annotator.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.annotator"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local AUTO, CONFIRMED, DATA, EXCEPTION, PROFILES, READS = AUTO, CONFIRMED, DATA, EXCEPTION, PROFILES, READS
local REQUEST, RESPONSE, annotate_registers, check_request = REQUEST, RESPONSE, annotate_registers, check_request
local check_writes, describe, device_of, diagnostics_note = check_writes, describe, device_of, diagnostics_note
local explain_exception, explain_objects, frame_labels = explain_exception, explain_objects, frame_labels
local ipairs, lane, pairs, parse_map_choice = ipairs, lane, pairs, parse_map_choice
local parse_profile_choice, refused_registers, register_at = parse_profile_choice, refused_registers, register_at
local remember_mask, remember_writes, rows_for, say, select = remember_mask, remember_writes, rows_for, say, select
local span_label, track, trusted_request, verified = span_label, track, trusted_request, verified
local words_at = words_at

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
M.MASK_WRITES, M.annotate_with, M.configure = MASK_WRITES, annotate_with, configure
M.inferred_registers, M.new_state, M.register_view = inferred_registers, new_state, register_view
end

-- ---- vw3.pack: lua/src/pack.lua ----
package.preload["vw3.pack"] = function(...)
-- vw3.pack: what a record keeps of its frames for the later passes, packed (no Python counterpart: the plugin keeps every record for Wireshark's later dissections).
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.pack"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, EXCEPTION, NOISE, REQUEST, RESPONSE, next = DATA, EXCEPTION, NOISE, REQUEST, RESPONSE, next
local pairs, pcall, tostring, type = pairs, pcall, tostring, type

-- What a record keeps of a frame for the later passes, packed: numbers, slots of one flat array per
-- stream (st.flat), the item being the number of its first slot. A table with named keys keeps the hash
-- it grew to while the frame was decoded (some 25 keys, 1.3 KB); numbers are no objects: the collector
-- goes over the array's slots in one sweep instead of following a table (or two, or three) a frame, and
-- its 13 slots take some 200 bytes. Small numbers share a slot (a double holds 53 bits exactly): a slot
-- written costs more than the arithmetic that fills it. A missing value is false. Requests and responses
-- name each other by record (and the request's time): no links between kept tables. The keys a frame
-- holds rarely are kept in a table in its last slot (with its span label). The display unpacks a frame
-- each time it shows it. A key the display reads must have a slot or be in RARE: one missing shows only
-- from the second pass on (`tshark -2`, which the parity tests run). The slots and the code that fills and
-- reads them: DATA.pack (codegen/pack_lua.py SLOTS): put_flat(st, every slot's value), the frame's first
-- slot in st.flat; expand_slots(flat, that slot), its keys and runs in a table, then link and request_time.
local pack = {}
local RARE, has_rare, put_flat, expand_slots = DATA.pack.rare, DATA.pack.has_rare, DATA.pack.put, DATA.pack.expand
-- The kinds by number and the numbers by kind: a packed frame's kind, and vw3.kind's values (lua/src/fields.lua).
local KIND_NUMBER = { [REQUEST] = 1, [RESPONSE] = 2, [EXCEPTION] = 3, [NOISE] = 4 }
local NUMBER_KIND = { REQUEST, RESPONSE, EXCEPTION, NOISE }
local ENCODE = DATA.pack.encode
local head_slot, crc_slot, span_slot, run_slot, bit_slot = ENCODE.head, ENCODE.crcs, ENCODE.span, ENCODE.registers,
  ENCODE.bits

-- A frame's first slot in st.flat; noise in a table of its own, 10 slots (a
-- run of the same noise, take_items, is one: a flood of ':' in ASCII mode is a noise item a byte).
local function pack_item(st, f)
  if f.kind == NOISE then
    return { NOISE, f.at, f.length, f.number, f.offset, f.record, f.time, f.reason, f.raw, f.count }
  end
  local regs, coils = false, false
  local registers, bits = f.registers, f.bits
  if registers ~= nil then regs = run_slot(registers.first, registers.count, registers.start) end
  if bits ~= nil then coils = bit_slot(bits.first, bits.count, bits.start, bits.single) end
  local request, response = f.request, f.response
  local link, request_time = false, nil
  if request ~= nil then
    link, request_time = request.record, request.time
  elseif response ~= nil then
    link = -response.record
  end
  local last = f.span_label
  if has_rare(f) then
    -- (only the keys the frame holds: Lua 5.2 makes a key even for a nil stored under it)
    last = { span_label = last }
    for index = 1, #RARE do
      local key = RARE[index]
      local kept = f[key]
      if kept ~= nil then last[key] = kept end
    end
    if registers ~= nil and (registers.status or registers.plain) then
      last.status, last.plain = registers.status, registers.plain
    end
    -- An exception 02's inferred registers are listed from its request's start and quantity.
    if f.inferred and request ~= nil then last.inferred = { request.start, request.quantity } end
  end
  return put_flat(st, head_slot(KIND_NUMBER[f.kind], f.slave, f.fn, f.length), f.at, f.number, f.offset,
    f.record, f.time, crc_slot(f.crc_expected, f.crc), span_slot(f.quantity, f.start), regs, coils, link,
    request_time, last)
end

local function expand_flat(st, k)
  local f, link, request_time = expand_slots(st.flat, k)
  f.kind = NUMBER_KIND[f.kind]
  local rare = f.span_label
  if type(rare) == "table" then f.span_label = rare.span_label else rare = nil end
  if link ~= nil then
    if link > 0 then
      f.request = { record = link, time = request_time }
    else
      f.response = { record = -link }
    end
  end
  if rare ~= nil then
    for index = 1, #RARE do
      local key = RARE[index]
      local kept = rare[key]
      if kept ~= nil then f[key] = kept end
    end
    if f.registers ~= nil then f.registers.status, f.registers.plain = rare.status, rare.plain end
    local inferred = rare.inferred
    if inferred ~= nil and f.request ~= nil then
      f.request.start, f.request.quantity, f.request.fn, f.inferred = inferred[1], inferred[2], f.fn, true
    end
  end
  return f
end

-- The item as the display reads it: a new table (an item never packed is itself).
function pack.expand(p, st)
  if type(p) == "number" then return expand_flat(st, p) end
  if p.kind ~= nil then return p end
  return { kind = NOISE, at = p[2], length = p[3], number = p[4], offset = p[5], record = p[6], time = p[7],
    reason = p[8], raw = p[9], count = p[10] }
end

-- The time of a record the quick lanes took (lane.again): its one frame's (packed, or awaiting its answer).
function pack.record_time(st, record)
  if type(record) == "number" then return st.flat[record + DATA.pack.time] end
  return type(record) == "table" and record[1] ~= nil and pack.expand(record[1], st).time
end

-- After a record is shown on the first pass: pack the items taken since, but the request still
-- awaiting its answer (pairing and the end of the capture change it; the display knows it as itself).
function pack.settle(st)
  local list = st.unpacked
  local whole = st.whole_record -- a record of one frame (dissect_record's fast lane)
  if whole ~= nil then
    st.whole_record = nil
    local item = whole[1]
    if item == st.pending then
      local count = #list
      list[count + 1], list[count + 2] = whole, 1 -- (packed once answered, with the others)
      if count == 0 then return end -- (nothing else waits: the pending request stays)
    elseif st.records[item.record] == whole then
      st.records[item.record] = pack_item(st, item) -- (the record is closed and holds this frame alone)
    else
      whole[1] = pack_item(st, item)
    end
  end
  if list[1] == nil then return end
  local kept = 0
  for index = 1, #list, 2 do
    local record, at = list[index], list[index + 1]
    local item = record[at]
    if item == st.pending then
      list[kept + 1], list[kept + 2] = record, at
      kept = kept + 2
    else
      local packed, number = pack_item(st, item), item.record
      record[at] = packed
      -- A closed record that is one packed frame and nothing else is kept as that number itself. (A closed
      -- record has no byte left to frame: the end of the capture adds nothing to it.)
      if type(packed) == "number" and record[2] == nil and next(record, 1) == nil and st.records[number] == record then
        st.records[number] = packed
      end
    end
  end
  for index = #list, kept + 1, -1 do list[index] = nil end
end

-- A record decoded again into the state `fresh` by decode(...) (a failure kept as the record's error, shown
-- there), its items packed (vw3.records' lane.again, vw3.dissector's decode_again).
function pack.redo(fresh, number, bytes, decode, ...)
  local ok, result = pcall(decode, ...)
  if not ok then result = { length = #bytes, error = tostring(result) } end
  fresh.records[number] = result
  if fresh.whole_record ~= nil or fresh.unpacked[1] ~= nil then pack.settle(fresh) end
end

-- The state `fresh` takes st's place (the same table: `state` and udp_states keep naming it).
function pack.take_place(st, fresh)
  for key in pairs(st) do st[key] = nil end
  for key, value in pairs(fresh) do st[key] = value end
end
M.KIND_NUMBER, M.NUMBER_KIND, M.bit_slot, M.crc_slot = KIND_NUMBER, NUMBER_KIND, bit_slot, crc_slot
M.head_slot, M.pack, M.put_flat, M.run_slot, M.span_slot = head_slot, pack, put_flat, run_slot, span_slot
end

-- ---- vw3.records: lua/src/records.lua ----
package.preload["vw3.records"] = function(...)
-- vw3.records: one record: framed, paired, decoded and annotated in order; the quick lanes.
-- Mirrors dissector/pipeline.py.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.records"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local CONFIRMED, DATA, ECHO_CODES, FRAMING, KIND_NUMBER = CONFIRMED, DATA, ECHO_CODES, FRAMING, KIND_NUMBER
local NOISE, PROFILES, READS, REQUEST, RESPONSE = NOISE, PROFILES, READS, REQUEST, RESPONSE
local annotate_with, await_answer, await_echo, bit_slot = annotate_with, await_answer, await_echo, bit_slot
local build_device, check_references, collectgarbage = build_device, check_references, collectgarbage
local crc_slot, crc_string_ok, cut_stream, data_bytes = crc_slot, crc_string_ok, cut_stream, data_bytes
local decode_frame, device_for, device_now, drop_first = decode_frame, device_for, device_now, drop_first
local feed, feed_whole, head_slot, lane, math, new_state = feed, feed_whole, head_slot, lane, math, new_state
local next, pack, pair, pair_part, pairs, pcall, put_flat = next, pack, pair, pair_part, pairs, pcall, put_flat
local release_run, remember_writes, run_slot, sample_mode = release_run, remember_writes, run_slot, sample_mode
local silent_at_end, span_slot, story, string, string_of = silent_at_end, span_slot, story, string, string_of
local takes_whole, tostring, type, warn, whole_crc_good = takes_whole, tostring, type, warn, whole_crc_good

local take_items, dissect_record
-- A run of a known request, for one frame (runs change with their frame: released, packed).
-- (b: the frame's bytes, else the run's)
local function copy_run(run, b)
  if run == nil then return nil end
  return { b = b or run.b, first = run.first, count = run.count, start = run.start, shift = nil, single = run.single }
end

-- Pair, decode and annotate a frame just numbered; the device it was annotated with.
local function take_frame(st, item, whole)
  pair(st, item)
  -- (how many notes pairing gave: the capture end's note goes after them, before decoding's, as the
  -- Python pipeline's pairer finishes before decode_frame; the display puts it there)
  if item.notes ~= nil then item.paired_notes = #item.notes end
  local gaps = item.gaps -- (silences inside the frame, vw3.stream's inner_gaps: after the pairing's warnings)
  if gaps ~= nil then
    for index = 1, #gaps do warn(item, gaps[index]) end
    item.gaps = nil
  end
  decode_frame(item)
  local device = device_now(st, item, item.b)
  annotate_with(st, item, item.b, device)
  check_references(item, device) -- (a map written in PLC references, judged on the slave's first frames)
  -- What the display does not need is dropped (the record is kept for every later pass): the byte
  -- table (the display reads the tvb) and the decoded fields once nothing can ask for them (a
  -- request's, until its answer is decoded or it can have none). (Warnings and notes are lists made
  -- with their first entry: none is empty.)
  -- The request it answers may have come through the stream's buffer: its registers are released.
  local request = item.request
  if request ~= nil then
    request.fields = nil
    release_run(request.registers)
  end
  -- A record's one frame (whole) is copied by pack.settle, which takes none of these keys (and its
  -- indices are the frame's own already); a request awaiting its answer keeps its byte table until then.
  if whole then return device end
  item.b = nil
  -- Indices into the frame's own bytes from now on (the display rebuilds them from the tvb; a
  -- pending request's registers once its answer has been read), and what is known from the kind of
  -- frame dropped: a record keeps fewer keys (Lua tables grow by powers of two).
  local bi = item.bi
  if item.registers ~= nil then item.registers.shift = bi end
  if item.bits ~= nil then
    item.bits.shift = bi
    release_run(item.bits)
  end
  local objects = item.objects
  if objects ~= nil then
    for at = 1, #objects do objects[at].offset = objects[at].offset - bi end
  end
  item.bi, item.data_at, item.data_len = nil, nil, nil
  if item.kind ~= REQUEST or st.pending ~= item then
    item.fields = nil
    release_run(item.registers)
  end
  return device
end

-- Requests met before, by their bytes: a polling master sends the same requests every cycle, and what
-- decoding and the device make of a request depends on its bytes and the device alone. An entry holds
-- the frame's decoded fields, runs, device texts and Info text, and the device they were made with
-- (remember_request makes them, the quick lanes of requests use them). Bounded: a new table after MAX entries.
local known_requests = { entries = {}, headers = {}, count = 0, MAX = 4096 }

-- Requests that write a block of values (FC15, FC16, FC23), by the length of their bytes before the values
-- (DATA.lanes, codegen/lanes_lua.py): decoded from those bytes alone (the values are a run read when shown).
-- A master writes its setpoints every cycle with new values.
known_requests.header_lengths = DATA.lanes.header_lengths

-- Does the device annotate a request's registers (annotate_registers, not reading: only those under a
-- layout rule, which may be noted)?
local function follows_registers(device, run)
  if run == nil or run.start == nil then return false end
  local depend = device.depend
  if next(depend) == nil then return false end
  for index = 0, run.count - 1 do
    if depend[(run.start + index) % 0x10000] ~= nil then return true end
  end
  return false
end

-- Keep a request of one record for the next time its bytes come (see known_requests): one whose
-- decoding and annotation said nothing but its fields and device texts, which nothing else than its
-- bytes and device made (no registers annotated: those under a device's layout rules may be noted).
-- A request that writes is kept by its bytes before the values too (known_requests.headers, for
-- lane.request, which looks at the layout rules again), even where it writes registers under one.
-- Not a provisional one: its Info text says so, the lanes take a request of a settled slave.
local function remember_request(bytes, item, device)
  if item.kind ~= REQUEST or item.slave == 0 or not device or item.warnings or item.notes or item.malformed
      or item.profile_choice or item.subfunction or item.objects or item.crc ~= item.crc_expected
      or item.provisional then
    return
  end
  local header = known_requests.header_lengths[item.fn]
  if header ~= nil and #bytes <= header then header = nil end
  local by_bytes = not follows_registers(device, item.registers)
  if header == nil and not by_bytes then return end
  if known_requests.count >= known_requests.MAX then
    known_requests.entries, known_requests.headers, known_requests.count = {}, {}, 0
  end
  local info = item.info
  if info == nil and summary ~= nil then info = summary(item, nil, nil, device) end -- (nil: loaded without Wireshark)
  item.info = info
  local entry = {
    device = device, crc = item.crc, b = item.b, fields = item.fields, start = item.start,
    quantity = item.quantity, registers = copy_run(item.registers), bits = copy_run(item.bits),
    function_text = item.function_text, span_label = item.span_label, info = info, length = #bytes,
  }
  if by_bytes then
    known_requests.count = known_requests.count + 1
    known_requests.entries[bytes] = entry
  end
  if header ~= nil then
    local key = bytes:sub(1, header)
    local known = known_requests.headers[key]
    if known == nil or known.device ~= device then
      known_requests.count = known_requests.count + 1
      known_requests.headers[key] = entry
    end
  end
end

-- An item's bytes, before take_items drops the tables they are read from.
local function raw_of(item)
  if item.kind == NOISE then return string_of(item.bytes, 1, item.length) end
  if item.ascii then return string_of(item.src, item.src_at, item.length) end
  return string_of(item.b, item.bi, item.length)
end

-- Number, pair, decode and annotate the items the framer gave out while `record` was fed. Each is shown
-- in the record that holds its last byte (the framer may have needed later bytes to decide; Wireshark's
-- later passes show it there): through that record's bytes when they hold it whole, else through its
-- own bytes (a frame or noise run that began in earlier records, which say where it went).
-- showing: `record` is being dissected for the first time. An item it decided whose bytes are all in
-- earlier records (noise known as such only once later bytes came) is kept in the earliest record that
-- shows it on the later passes, but that one has been shown already, once and for all in tshark's one
-- pass: it is shown in `record` too, this time only (st.late, show.lua show_record), from its own bytes,
-- with the records they came from.
take_items = function(st, items, record, showing)
  local open = st.open
  for index = 1, #items do
    local item = items[index]
    st.count = st.count + 1
    item.number = st.count
    local offset, length = item.offset, item.length
    -- (the open records holding its bytes, open[oldest .. holding]: ascending, so the search stops past its end)
    local oldest, holding = nil, 0
    for at = 1, #open do
      local earlier = open[at]
      if earlier.start >= offset + length then break end
      if earlier.start + earlier.length > offset then oldest, holding = oldest or at, at end
    end
    local home = open[holding] -- (the one holding its last byte, else `record`)
    if home == nil or home.start + home.length < offset + length then home = record end
    item.record = home.number
    if showing and home ~= record then
      local from = {} -- (the numbers of the records holding its bytes, in order)
      for at = oldest, holding do from[#from + 1] = open[at].number end
      local late = st.late
      if late == nil or late.record ~= record then
        late = { record = record }
        st.late = late
      end
      late[#late + 1] = { item = item, raw = raw_of(item), from = from }
      item.late_in = record.number -- (where a frame that links to it finds it on that showing; not packed)
    end
    local first = home.start or offset -- (a closed record holds no bytes still to frame)
    local last = home[#home]
    local inside = offset >= first and offset + length <= first + (home.length or length)
    if inside then
      item.at = offset - first
      if item.kind == NOISE and type(last) == "table" and last.kind == NOISE and last.raw == nil
          and last.length == length and last.reason == item.reason and last.time == item.time then
        -- The same noise again right after (a flood of ':' in ASCII mode is an item a byte, as
        -- vw3-decode shows it): one entry for the run, shown item by item (show_record).
        local count = last.count or 1
        local span = count * length
        if last.number + count == item.number and last.at + span == item.at and last.offset + span == offset then
          last.count = count + 1
          item = nil
        end
      end
    else
      item.at = 0
      item.raw = raw_of(item)
      for at = oldest or 1, holding do
        local earlier = open[at]
        local from, to = earlier.start, earlier.start + earlier.length
        if earlier ~= home then
          earlier.continued = earlier.continued or {}
          earlier.continued[#earlier.continued + 1] = {
            item = item.number, record = home.number, count = math.min(to, offset + length) - math.max(from, offset),
            noise = item.kind == NOISE or nil, -- (bytes that continue no frame: the display says noise)
          }
        end
      end
    end
    if item ~= nil then
      home[#home + 1] = item -- (a record holds its items in its array part: one table fewer a record)
      local unpacked = st.unpacked
      unpacked[#unpacked + 1], unpacked[#unpacked + 2] = home, #home
      item.bytes, item.src = nil, nil
      if item.kind ~= NOISE then take_frame(st, item) end
    end
  end
  -- Records all of whose bytes are framed are done with; the others say how many of their bytes wait.
  local waiting_from = st.base
  if st.noise ~= nil then waiting_from = st.noise.offset end
  if showing then
    -- How many of the record's waiting bytes are noise already (a run that goes on: its end is not known),
    -- which its first dissection says rather than that they continue a frame (show_record).
    local stop = record.start + record.length
    st.noise_for, st.noise_waiting = record, math.max(0, math.min(st.base, stop) - math.max(waiting_from, record.start))
  end
  -- (ascending: the records all of whose bytes are framed come first; from the first that starts at or after
  -- waiting_from, every byte waits, as since it was opened with waiting = length)
  local closed = 0
  for index = 1, #open do
    local earlier = open[index]
    local waiting = earlier.start + earlier.length - waiting_from
    if waiting > 0 then
      if earlier.start >= waiting_from then break end
      earlier.waiting = math.min(waiting, earlier.length)
    else
      -- closed: all its bytes are framed (kept: its items and frame count)
      earlier.waiting, earlier.start, earlier.length, earlier.number = nil, nil, nil, nil
      closed = index
    end
  end
  if closed > 0 then drop_first(open, closed) end
end

-- The functions whose answer is a run of the registers or bits its request asked for, from its fourth byte:
-- whether bits, the extra of its length rule (its byte count plus that), the count's unit (DATA.lanes); and
-- the frame the Info text of a quick answer is made from.
local RUN_ANSWERS = DATA.lanes.run_answers
local ANSWER = { kind = RESPONSE, fn = 0, slave = 0, start = 0, quantity = 0, crc = 0, crc_expected = 0 }
local LANE_VALUES, LANE_LASTS = {}, {}

-- The quick lane of answers (see lane.decode): a record that is the usual answer to the request awaited (a
-- run of registers or bits whose byte count agrees with the request, on time, from a device that notes
-- nothing about them and has no name of its own for the function) is framed, paired, annotated and kept
-- as dissect_record, take_frame and pack.settle would do it, without a byte table, frame table or fields.
-- Returns the item kept and its Info text; nil, with nothing changed, for any other record.
function lane.answer(st, bytes, n, time, number, slave, code, quiet)
  local byte = string.byte
  local pending = st.pending
  local run, count = RUN_ANSWERS[code], byte(bytes, 3)
  if pending.slave ~= slave or pending.fn ~= code or run == nil then return nil end
  -- framed by its length rule, its CRC good
  if n ~= run.extra + count or not whole_crc_good(bytes, n) then return nil end
  -- pair: on time (else the request went unanswered)
  local timeout, asked = st.timeout, pending.time
  if timeout ~= nil and time ~= nil and asked ~= nil and (time - asked) / 1e9 > timeout then return nil end -- (ns)
  -- the lifting rules of read_registers_response, read_bits_response: the request's start and quantity, its
  -- byte count agreeing
  if pending.fields == nil then return nil end
  local start, quantity = pending.start, pending.quantity -- (the window its rule lifted: FC23's read window)
  if start == nil or quantity == nil then return nil end
  local bits = run.bits
  if count ~= data_bytes(quantity, run.unit) then return nil end
  -- (bits set past the quantity in the last byte draw a warning: data/modbus.toml [lift] padding)
  if bits and quantity % 8 > 0 and byte(bytes, 3 + count) >= 2 ^ (quantity % 8) then return nil end
  -- annotate_with: nothing but the registers' bookkeeping
  local device = device_for(st, slave)
  -- (its frames judged: check_references, take_frame; input rows apart: named by their table there)
  if not device or device.refs_open or device.inputs ~= nil then return nil end
  local profile = device.profile
  if profile.function_names[code] ~= nil then return nil end
  -- annotate_registers: every register the usual one (not 16#8000, under no layout rule, read before with a
  -- value where 16#8000 is followed), which is only noted as read
  local protected = nil
  if READS[code] ~= nil then protected = profile.protected_value end
  local depend, seen = device.depend, device.seen
  local follow = not bits and quantity > 0 and (protected ~= nil or next(depend) ~= nil)
  local values, lasts = LANE_VALUES, LANE_LASTS -- (each register's value and history, for the changes below)
  if follow then
    for index = 0, quantity - 1 do
      local high, low = byte(bytes, 4 + 2 * index, 5 + 2 * index)
      local address, value = (start + index) % 0x10000, high * 256 + low
      if value == protected or depend[address] ~= nil then return nil end
      if protected ~= nil then
        local last = seen[address]
        if last == nil or last.value == nil then return nil end
        values[index], lasts[index] = value, last
      end
    end
  end
  -- From here on the answer is taken: the same changes, in the same order, as the general path's.
  if quiet and quiet ~= true then quiet.answers, quiet.frames = quiet.answers + 1, quiet.frames + 1 end -- (lane.quiet)
  st.expect = nil -- (expect_after: an answer awaits nothing)
  local offset, item = lane.advance(st, n, time)
  -- (no record table for finish: the stream waits for no byte, and an answer awaits nothing)
  st.last = nil
  st.pending = nil
  local writes = pending.registers
  if device.track and CONFIRMED.answer[code] and writes ~= nil and writes.count > 0 and writes.b ~= nil then
    remember_writes(seen, item, writes, writes.b)
  end
  if follow and protected ~= nil then
    -- (remember_writes changed these tables in place, if any: none was missing)
    for index = 0, quantity - 1 do
      local last = lasts[index]
      last.value, last.frame, last.how = values[index], item, "read"
    end
  end
  release_run(writes)
  -- The request, packed now where it came through the quick lane and waits at the end of the list
  -- pack.settle packs (as_number: its record holds it alone); else it is linked to this record.
  local slots = pending.slots
  local list = st.unpacked
  local last = #list
  local request_record = list[last - 1]
  if slots and last >= 2 and list[last] == 1 and request_record[1] == pending and request_record[2] == nil
      and st.records[pending.record] == request_record then
    local packed = put_flat(st, slots[1], 0, pending.number, pending.offset, pending.record, pending.time,
      crc_slot(pending.crc_expected, pending.crc), slots[2], slots[3], slots[4], -number, nil, slots[5])
    list[last], list[last - 1] = nil, nil
    request_record[1] = packed
    st.records[pending.record] = packed
    local spare, spare_records = lane.spare, lane.spare_records
    if #spare < 4 then spare[#spare + 1] = pending end
    if #spare_records < 4 then spare_records[#spare_records + 1] = request_record end -- (its record too)
  else
    pending.response = { record = number }
  end
  -- What is the same for every answer of the device's function and read window, made once, bounded:
  -- its Info text, span label (PLC-style devices: 4X numbers; false: none) and the slots it is kept in but
  -- those of its place, time and CRC (as pack.settle keeps it: a response at the start of its own record,
  -- whose registers, or bits, are a run from its fourth byte).
  local key = (code * 65536 + start) * 65536 + quantity
  local infos = device.lane_infos
  if infos == nil or infos.count >= 256 then
    infos = { count = 0 }
    device.lane_infos = infos
  end
  local same = infos[key]
  if same == nil then
    ANSWER.fn, ANSWER.slave, ANSWER.start, ANSWER.quantity, ANSWER.span_label = code, slave, start, quantity, nil
    if device.plc ~= nil then lane.span_label(ANSWER, device) end
    local registers, coils = false, false
    if bits then coils = bit_slot(3, quantity, start, nil) else registers = run_slot(3, quantity, start) end
    same = { summary(ANSWER), ANSWER.span_label or false, head_slot(KIND_NUMBER[RESPONSE], slave, code, n),
      span_slot(quantity, start), registers, coils }
    infos[key], infos.count = same, infos.count + 1
  end
  -- Kept with its request in record pending.record, its CRC good.
  local crc_low, crc_high = byte(bytes, n - 1, n)
  local crc = crc_low + crc_high * 256
  return put_flat(st, same[3], 0, item, offset, number, time, crc_slot(crc, crc), same[4], same[5], same[6],
    pending.record, asked, same[2]), same[1]
end

-- The quick lane of requests (see lane.decode): a record that is a request met before (known_requests: by
-- its bytes, or, a request that writes (FC15, FC16, FC23 by the protocol table), by its bytes before the
-- values), for the device it was met with, is framed, paired and decoded as feed_whole, dissect_record and
-- take_frame would do it, in one table. A request known by its bytes before the values has its CRC
-- checked and its runs read from its own bytes, and goes the general path where a register it writes is
-- under a layout rule that holds now (annotate_one would note it).
-- Returns the record, as dissect_record does (shown and kept by dissect_records as such), and its Info
-- text; nil, with nothing changed, for any other record.
lane.spare, lane.spare_records = {}, {}
function lane.request(st, bytes, n, time, number, slave, code, quiet)
  local byte = string.byte
  local known = known_requests.entries[bytes]
  local own = known == nil -- (its own values: known by its bytes before them)
  if own then
    local header = known_requests.header_lengths[code]
    if header == nil or n <= header then return nil end
    known = known_requests.headers[bytes:sub(1, header)]
    if known == nil or known.length ~= n then return nil end
  end
  local device = known.device
  if device_for(st, slave) ~= device or device.refs_open or device.inputs ~= nil then return nil end
  if own then
    local registers = known.registers
    if registers ~= nil and next(device.depend) ~= nil then
      local rows, plain_rule = device.rows, story.plain_rule
      for index = 0, registers.count - 1 do
        local address = (registers.start + index) % 0x10000
        if plain_rule(device, address, rows[address]) ~= nil then return nil end
      end
    end
    if not crc_string_ok(bytes, n) then return nil end
  end
  -- Taken: the same changes as the general path's (the stream, the count, profile auto's count, the frame
  -- decoded as its entry says, awaiting its answer alone in its record, packed by pack.settle).
  if quiet and quiet ~= true then quiet.frames = quiet.frames + 1 end -- (counted as observe does: lane.quiet)
  st.expect = slave * 256 + code -- (expect_after: a request's code is its function)
  local offset, count = lane.advance(st, n, time)
  -- The frame framing finds (the request's layout is the likeliest; its length and CRC checked when it
  -- was met), decoded as its entry says. A frame of the quick lanes packed once answered (lane.answer) is
  -- held by nothing else: it is taken again here, every key set anew, so that a polling bus makes no
  -- table a request (lane.spare, a few at most).
  local spare = lane.spare
  local f = spare[#spare]
  if f == nil then
    -- (the keys below made at once, as the constructor sizes them)
    f = { kind = 0, offset = 0, length = 0, slave = 0, fn = 0, crc = 0, crc_expected = 0, time = 0, b = 0, bi = 0,
      data_at = 0, data_len = 0, number = 0, record = 0, at = 0, fields = 0, start = 0, quantity = 0, registers = 0,
      bits = 0, request = 0, response = 0, function_text = 0, span_label = 0, info = 0, slots = 0 }
  else
    spare[#spare] = nil
  end
  local b, crc = nil, known.crc
  if own then
    local crc_low, crc_high = byte(bytes, n - 1, n)
    b, crc = { [0] = slave, byte(bytes, 2, n) }, crc_low + crc_high * 256
  end
  f.kind, f.offset, f.length, f.slave, f.fn, f.crc, f.crc_expected, f.time = REQUEST, offset, n, slave, code, crc, crc,
    time
  f.b, f.bi, f.data_at, f.data_len, f.number, f.record, f.at = b or known.b, 0, 2, n - 4, count, number, 0
  if ECHO_CODES[code] then await_echo(st, f) end -- (what its answer must repeat, an FC8 sub-function)
  await_answer(st, f) -- (the length of its answer, as vw3.stream's expect_after keeps it)
  f.fields, f.start, f.quantity, f.request, f.response = known.fields, known.start, known.quantity, nil, nil
  f.registers, f.bits = copy_run(known.registers, b), copy_run(known.bits, b)
  f.function_text, f.span_label, f.info = known.function_text, known.span_label, known.info
  local slots = known.slots
  if slots == nil then
    -- The slots of such a request but its number, offset, record, time and CRC (lane.answer packs it with
    -- them), made once for its entry when the lane first takes it (most entries of a mix of random
    -- requests never are); false where it holds a rare key (a name of the device's own: pack.settle).
    local registers, bits = known.registers, known.bits
    slots = known.function_text == nil and {
      head_slot(KIND_NUMBER[REQUEST], slave, code, n),
      span_slot(known.quantity, known.start),
      registers ~= nil and run_slot(registers.first, registers.count, registers.start) or false,
      bits ~= nil and bit_slot(bits.first, bits.count, bits.start, bits.single) or false,
      known.span_label or false,
    }
    known.slots = slots
  end
  f.slots = slots
  st.pending = f
  local spare_records = lane.spare_records
  local record = spare_records[#spare_records]
  if record == nil then
    record = { f }
  else
    spare_records[#spare_records] = nil
    record[1] = f
  end
  st.last = record
  st.whole_record = record
  return record, f.info
end

local function cut_part(st, bytes, time, number, part) -- (captured in part: lua/src/stream.lua cut_stream, after a final run)
  local items = feed(st, "", nil, false, true)
  local record = cut_stream(st, bytes, time, part, number, items)
  take_items(st, items, record, true)
  return record, pair_part(st, items[#items]) -- (numbered, it may answer the request awaited: lua/src/pairing.lua)
end

dissect_record = function(st, bytes, time, number)
  local n = #bytes
  st.late = nil -- (the record before's, shown with it or never: the quick lanes show no tree)
  if st.mode == nil and n > 0 then st.mode = sample_mode(bytes, true) end -- (its bytes alone tell)
  local built = nil
  if st.open[1] == nil then
    -- A record that is one frame (take_items's work for it: the record closed, the frame at 0 in it)
    local frame
    frame, built = feed_whole(st, bytes, time)
    if frame ~= nil then
      local record = { frame }
      st.last = record
      frame.number, frame.record = st.count, number -- (counted by feed_whole)
      remember_request(bytes, frame, take_frame(st, frame, true))
      st.whole_record = record -- (packed by pack.settle; not when take_frame fails: the record is then an error)
      return record
    end
  end
  -- (four keys: a fifth would double the table's hash, and records stay for the whole capture)
  local record = { number = number, start = st.base + st.n, length = n, waiting = n }
  st.open[#st.open + 1] = record
  st.last = record
  take_items(st, feed(st, bytes, time, true, false, built), record, true)
  return record
end

-- The end of the capture: frame what still waits (as vw3-decode does at the end of its input), shown in
-- the last record. Called once, when the first pass is over.
local function finish(st)
  if st.finished then return end
  st.finished = true
  local record = st.last
  if record == nil then return end
  st.cut_by_silence = silent_at_end(st) -- (what it holds is cut by a silence before the end, or by the end)
  local items = feed(st, "", nil, false, true)
  st.cut_by_silence = nil
  for index = 1, #items do
    -- The answer awaited cut by the end of the capture: said on the request (model.py CUT_ANSWER).
    local reason, cut = items[index].reason, FRAMING.cut_answer
    if reason ~= nil and reason:sub(1, #cut) == cut then st.cut_note = reason end
  end
  take_items(st, items, record)
  if st.pending ~= nil then release_run(st.pending.registers) end
end

-- finish, a failure kept as the last record's error (shown there) rather than raised.
local function finish_safely(st)
  local ok, problem = pcall(finish, st)
  if not ok and st.last ~= nil then st.last.error = tostring(problem) end
end

-- A record's first decoding: the quick lanes, else the general path (dissect_record). A lane takes a
-- record framed as feed_whole frames it, one whole frame where no byte waits (lane.advance then leaves the
-- stream as feed_whole leaves it), where profile auto's choice is settled for its slave (device_now); the
-- answer's where a request awaits its answer (and the framer expects it), the requests' where none does.
-- lane.quick false (the `quick_lanes` preference, or VW3_QUICK_LANES = false set before loading): every
-- record the general path, which the quick lanes must equal (the parity tests run both).
lane.quick = VW3_QUICK_LANES ~= false
function lane.decode(st, bytes, n, time, number)
  local slave, code = string.byte(bytes, 1, 2)
  local answer = st.pending ~= nil
  if lane.parts[number] ~= nil then return cut_part(st, bytes, time, number, lane.parts[number]), n end
  if lane.quick and st.open[1] == nil and st.listening == nil and takes_whole(st, n, slave)
      and (st.expect == slave * 256 + code) == answer then
    local quiet = nil -- (what the lane counts the frame in; nil: profile auto is not in use for the slave)
    if config.auto[slave] then quiet = lane.quiet(st, slave, code, answer) end
    if quiet ~= false then
      local kept, info = (answer and lane.answer or lane.request)(st, bytes, n, time, number, slave, code, quiet)
      if kept ~= nil then return kept, n, info end
    end
  end
  return dissect_record(st, bytes, time, number), n
end

-- Profile `auto` over the whole capture (app/preselect.py, issue 27): once the first pass is over, a
-- slave's frames met before its choice (or before it was taken back) are decoded again, the whole
-- capture in order, with every slave's device the one chosen over the capture from its first frame
-- (annotations, statuses and the parameter story follow the device). Framing and pairing give the same
-- items again; only what the device says changes. `tshark -2` and Wireshark's later dissections then
-- show what vw3-decode shows reading a file; a single pass stays as vw3-decode reading a stream.
function lane.again(st)
  local again = st.again
  st.again = nil
  -- (nothing chosen after a slave's first frame, and no frame read before a choice could be made)
  if again == nil or (next(st.said) == nil and not st.provisional) then return end
  local fresh = new_state(st.timeout, st.mode)
  -- The frames packed anew go over the first decoding's slots, from the first (no second array as long
  -- held at the peak): each record's first decoding is dropped as it is decoded again, and none is read.
  fresh.flat = st.flat
  local frozen, chosen, history, fixed = {}, {}, {}, {}
  for number, reason in pairs(st.said) do frozen[number] = reason end
  local met = {} -- (every slave the first pass met: a broadcast reaches them all, the selection stage's broadcast_device)
  for slave, judged in pairs(st.judged) do
    met[slave] = true
    local choice = judged.choice
    if choice ~= nil and PROFILES[choice.profile] ~= nil then
      local device = build_device(PROFILES[choice.profile], slave)
      chosen[slave], fresh.devices[slave], fixed[slave] = choice.profile, device, true
      history[slave] = { { number = 0, device = device, reason = choice.reason } }
    end
  end
  -- (the other slaves are judged again as they come: more records may follow in a live capture)
  fresh.frozen, fresh.chosen, fresh.history, fresh.fixed, fresh.met = frozen, chosen, history, fixed, met
  local records, kept = st.records, again.bytes
  -- So do the records, each over its first decoding (a record the first pass kept no bytes of goes, as it
  -- would from a new table): no second table as long held at the peak.
  fresh.records = records
  for number in pairs(records) do
    if kept[number] == nil then records[number] = nil end
  end
  -- Each record decoded again makes its first decoding garbage, one for one: meanwhile the collector starts
  -- its next cycle at once (the pause lua/src/crc.lua sets let that garbage grow the heap by half what stays),
  -- from a heap without the first pass's garbage (a pause takes effect when a cycle ends).
  local paused, pause = pcall(collectgarbage, "setpause", 100)
  collectgarbage("collect")
  -- The records in number order, the order of their first dissection (a first pass reads the capture in
  -- order): no list of that order kept a record.
  local first, last, times = math.huge, 0, again.times
  for number in pairs(kept) do
    if number < first then first = number end
    if number > last then last = number end
    -- (its time over its first decoding, no table more: kept, or its quick lane frame's, read before any is packed)
    local time = times[number]
    if time == nil then time = pack.record_time(st, records[number]) or false end
    records[number] = time
  end
  for number = first, last do
    local bytes = kept[number]
    if bytes ~= nil then -- (over its first decoding, which is done with)
      pack.redo(fresh, number, bytes, lane.decode, fresh, bytes, #bytes, records[number] or nil, number)
      kept[number] = nil
    end
  end
  if paused then collectgarbage("setpause", pause) end
  fresh.late = nil -- (what the last record decided for earlier ones: shown already, on its first showing)
  finish_safely(fresh)
  -- Records read after this (Wireshark's packet details opened during a live capture) are read once, as
  -- vw3-decode --live reads them: a frame of a slave still judged is provisional again.
  fresh.going_on = true
  pack.take_place(st, fresh)
end
M.dissect_record, M.finish = dissect_record, finish -- (the pure part's entry points: main.lua)
M.finish_safely = finish_safely
end

-- ---- vw3.fields: lua/src/fields.lua ----
package.preload["vw3.fields"] = function(...)
-- vw3.fields: Wireshark: the protocol, its fields, expert infos and preferences.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.fields"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, DIAGNOSTICS, EXCEPTIONS, FUNCTIONS, NUMBER_KIND = DATA, DIAGNOSTICS, EXCEPTIONS, FUNCTIONS, NUMBER_KIND
local PROFILES, Pref, Proto, ProtoExpert, ProtoField, base = PROFILES, Pref, Proto, ProtoExpert, ProtoField, base
local configure, expert, frametype, ipairs, lane, new_state = configure, expert, frametype, ipairs, lane, new_state
local string, type = string, type

local proto = Proto("vw3", "VW3 Modbus serial (Altivar 71, SEL-749M)")

-- The kind is an integer with value strings (pack.lua's numbering): `vw3.kind == "request"` filters by name,
-- and an integer costs less than a string to add and to compare. A register's status is text, as vw3-decode's
-- `status` key: `-T fields` prints `protected` where vw3-decode does, and an empty occurrence where a
-- register has no status (a text field can have one, issue 27).

-- The value strings data/fields.toml names (a field's `values`, when not a table of its own).
local VALUES = { kind = NUMBER_KIND, functions = FUNCTIONS, exceptions = EXCEPTIONS, diagnostics = DIAGNOSTICS,
  run_indicator = DATA.names.run_indicator, request = frametype and frametype.REQUEST,
  response = frametype and frametype.RESPONSE, mei_types = DATA.fields.names.mei_types,
  device_id_codes = DATA.fields.names.device_id_codes }

-- The fields, stated in data/fields.toml with vw3-decode's filter keys (codegen/fields_lua.py):
-- pf.NAME is vw3.NAME's field, dots as `_` (vw3.reg.address: pf.reg_address), or f.name where two fields
-- share a filter (FC7's 8-bit vw3.status: pf.exception_status).
-- Registered in the catalogue's order: a filter names the type of the field of its name registered last
-- (vw3.status: FC11's word after FC7's byte, so `vw3.status == 0xffff` is a filter).
local pf, field_list = {}, {}
for _, f in ipairs(DATA.fields.fields) do
  local name = f.name or string.gsub(string.sub(f.abbr, 5), "%.", "_")
  local values = f.values
  -- (else a [names] table of data/modbus.toml: FC43/14's conformity levels)
  if type(values) == "string" then values = VALUES[values] or DATA.names[values] end
  if f.plain then -- (a constructor of (abbr, title, help): codegen/fields_lua.py PLAIN)
    pf[name] = ProtoField[f.ftype](f.abbr, f.title, f.help)
  else
    pf[name] = ProtoField[f.ftype](f.abbr, f.title, f.base and base[f.base], values, nil, f.help)
  end
  field_list[#field_list + 1] = pf[name]
end

-- The protocol's fields: the catalogue's (pf), then the per-parameter fields, one per row of the built-in
-- register maps (DATA.fields.parameters, codegen/fields_lua.py: vw3.atv71.rfr, ...), by the row they follow
-- (tree.lua add_register).
local PARAMETER_FIELDS = {}
for _, p in ipairs(DATA.fields.parameters) do
  local field = ProtoField.double(p.abbr, p.title)
  PARAMETER_FIELDS[PROFILES[p.profile].map[p.address]] = field
  field_list[#field_list + 1] = field
end
proto.fields = field_list

-- The expert infos, stated in data/fields.toml's [[expert]] entries: ex.NAME, registered in their order.
local ex, experts = {}, {}
for index, e in ipairs(DATA.fields.experts) do
  experts[index] = ProtoExpert.new(e.filter, e.title, expert.group[e.group], expert.severity[e.severity])
  ex[e.name] = experts[index]
end
proto.experts = experts

-- The preferences, stated in data/fields.toml's [[preference]] entries, registered in their order. An enum's
-- value is its choice's place among its choices (`chosen` names it; the first, the default, forces nothing).
local CHOICES = {}
for _, p in ipairs(DATA.fields.preferences) do
  if p.type == "enum" then
    local choices = {}
    for index, choice in ipairs(p.choices) do choices[index] = { index, choice, index } end
    CHOICES[p.name] = p.choices
    proto.prefs[p.name] = Pref.enum(p.title, 1, p.help, choices, false)
  else
    local default = p.default
    if p.name == "quick_lanes" then default = lane.quick end -- (VW3_QUICK_LANES = false before loading: off)
    proto.prefs[p.name] = Pref[p.type](p.title, default, p.help)
  end
end

local function chosen(name)
  local value = proto.prefs[name]
  if value == 1 then return nil end
  return CHOICES[name][value]
end

local function apply_prefs()
  configure(proto.prefs.profiles, chosen("address_style"), proto.prefs.maps)
  lane.quick = proto.prefs.quick_lanes
end

-- A new stream's state, with the preferences' timeout and framing mode.
local function stream_state()
  local timeout = nil
  if proto.prefs.timeout_ms ~= 0 then timeout = proto.prefs.timeout_ms / 1000 end
  return new_state(timeout, chosen("mode"))
end

-- Each capture starts here (Wireshark calls it before the first record is dissected): the plugin's state.
function proto.init()
  newest_record = 0 -- (the newest record's number: show.lua finish_all)
  recorded_until = nil -- (the last timed record's time, any stream's, empty or not: vw3.pairing's ended)
  -- RTAC timestamps per frame number. Wireshark's field extractors see nothing on a first pass without a
  -- tree, so the RTAC header is read by a pass-through in front of Wireshark's own RTAC dissector.
  rtac_times = {}
  rtac_payload = false -- (Decode As gave RTAC data to VW3: dissector.lua rtac_time)
  lane.parts = {} -- (records captured in part, by number: lua/src/stream.lua lane.captured_in_part)
  apply_prefs()
  -- Streams of records: the serial capture's (state); the others (one per UDP conversation, one per TCP
  -- connection, one per further interface: dissector.lua) in udp_states, which the first pass's end finishes.
  state = stream_state()
  udp_states = {}
  record_streams = {} -- (each record's stream, where interfaces are told apart: dissector.lua serial_state)
end
M.PARAMETER_FIELDS, M.apply_prefs, M.ex, M.pf, M.proto = PARAMETER_FIELDS, apply_prefs, ex, pf, proto
M.stream_state = stream_state
end

-- ---- vw3.tree: lua/src/tree.lua ----
package.preload["vw3.tree"] = function(...)
-- vw3.tree: Wireshark: a frame's registers, bits and PDU fields (show.lua show_frame), and its Info text.
-- Mirrors dissector/render/detail.py, dissector/render/summary.py, dissector/render/describe.py (Info forms).
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.tree"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local ByteArray, DATA, DIAGNOSTICS, EXCEPTION, FUNCTIONS = ByteArray, DATA, DIAGNOSTICS, EXCEPTION, FUNCTIONS
local MASK_WRITES, NO_INTERPRETATION, PARAMETER_FIELDS = MASK_WRITES, NO_INTERPRETATION, PARAMETER_FIELDS
local REQUEST, concat, describe, device_of, ex = REQUEST, concat, describe, device_of, ex
local exception_name, floor, format, function_name, hex_of = exception_name, floor, format, function_name, hex_of
local hex_pairs, ipairs, made_once, math, pf = hex_pairs, ipairs, made_once, math, pf
local printable_ascii, python_repr, rows_for, say, string = printable_ascii, python_repr, rows_for, say, string
local table, tostring, u16, words_at = table, tostring, u16, words_at

-- `1 byte`, `2 bytes`: a count and its noun, singular for one (describe.count_text).
local function count_text(count, noun)
  if count == 1 then return "1 " .. noun end
  return format("%d %ss", count, noun)
end

local function add_text(tree, expert_info, text)
  tree:add_proto_expert_info(expert_info, text)
end

-- The tvb range of `size` bytes at `at` in the frame's byte table (ASCII: hex pairs in the record);
-- the whole frame when that would fall outside it (never nil: TreeItem:add would shift its arguments).
local function frame_span(f, at, size)
  -- f.at: where the frame starts in the tvb it is shown from (ASCII: its colon)
  local offset, length = at + f.at, size
  if f.ascii then offset, length = f.at + 1 + 2 * at, 2 * size end
  if length <= 0 or offset < f.at or offset + length > f.at + f.length then
    return f.at, f.length
  end
  return offset, length
end

local function frame_range(tvb, f, at, size)
  return tvb:range(frame_span(f, at, size))
end

-- A text said on the frame: a field of its own (its value `value`) carrying the expert info, or the
-- expert info alone where no tree is wanted (whole: the frame's range in a tree, nil without one).
local function add_said(t, whole, field, value, expert_info, text)
  if whole ~= nil then t = t:add(field, whole, value):set_generated() end
  add_text(t, expert_info, text)
end

-- Invisible trees. Wireshark often builds a tree that nobody sees, only to run filters, coloring rules or
-- field extractors over it (this file's own Modbus field extractors make tshark build one on its second
-- pass). In such a tree an item of a field that nothing refers to is not created: TreeItem:add hands back
-- the parent item ("faked"). A frame's registers and bits repeat the same few fields, so there each field
-- is checked once per dissection (the faked item is the frame's item: it has the frame's length), and
-- the next registers and bits skip a field found faked, doing only what the faked item did: the text
-- and generated flag of the frame's item, and the expert infos. `serial` counts the dissections.
-- unseen.tvb, .offset, .length: the bytes of the register or bit being added (its TvbRange, .range, is
-- made when a field needs it); .frame_length: the length of the frame's item. .checking: fields are
-- checked (an invisible tree; it pays from the second register or bit on).
local LAYOUT_OF = DATA.rules.by_code -- (by kind, then function code: its layout's name)
local START_WORDS = DATA.fields.start_words -- (a start that is no window: FC24's pointer, codegen/fields_lua.py)
local unseen = { serial = 0, faked = {}, checked = {}, generated = false, no_row = {} }

-- The register or bit being added: `size` bytes at `at` in the frame (or the TvbRange `range`).
function unseen.at(tvb, f, at, size, range, checking)
  unseen.tvb, unseen.frame_length, unseen.range, unseen.checking = tvb, f.length, range, checking
  unseen.offset, unseen.length = frame_span(f, at, size)
end

-- Add a field to the register's or bit's item (in a tree that is shown, no field is ever faked).
function unseen.add(parent, field, value, generated, hidden)
  local serial = unseen.serial
  if unseen.faked[field] == serial then
    if generated then unseen.generated = true end
    return parent
  end
  local r = unseen.range
  if r == nil then
    r = unseen.tvb:range(unseen.offset, unseen.length)
    unseen.range = r
  end
  local item
  if value == nil then item = parent:add(field, r) else item = parent:add(field, r, value) end
  if generated then item:set_generated() end
  if unseen.checking and unseen.checked[field] ~= serial then
    unseen.checked[field] = serial
    local frame_length = unseen.frame_length
    if unseen.length ~= frame_length and item.len == frame_length then unseen.faked[field] = serial end
  end
  -- (never the faked item: it is the frame's)
  if hidden and unseen.faked[field] ~= serial then item:set_hidden() end
  return item
end

-- A register's texts: its item's, and its expert info's (16#8000 reads, add_register). Made each time
-- they are shown rather than kept: records stay in memory for the whole capture.
local function register_name(reg)
  local label = reg.label or (reg.address and tostring(reg.address)) or "?"
  local code = reg.row and reg.row.code
  if code then return label .. " " .. code end
  return label
end

local function register_title(reg)
  local parts = { "Register ", register_name(reg) }
  if reg.value ~= nil then parts[#parts + 1] = format(" = %d", reg.value) end
  if reg.text then parts[#parts + 1] = ": " .. reg.text end
  if reg.status then parts[#parts + 1] = " [" .. reg.status .. "]" end
  return concat(parts)
end

-- Where the frame's check starts in its byte table: RTU's CRC, 2 bytes; ASCII's LRC, 1 byte before CR LF.
local function check_at(f) return f.ascii and floor((f.length - 3) / 2) - 1 or f.length - 2 end

-- The frame's byte table for the display, from the tvb it is shown from (ASCII: the hex pairs decoded).
local function frame_bytes(f, tvb)
  if f.ascii then -- (the hex pairs between the colon and CR LF, as the framer read them)
    return (hex_pairs({ string.byte(tvb:raw(f.at + 1, f.length - 3), 1, -1) }, 1, floor((f.length - 3) / 2)))
  end
  local raw = tvb:raw(f.at, f.length) -- (the bytes as they are, 0-based)
  return { [0] = string.byte(raw, 1), string.byte(raw, 2, -1) }
end

-- `full` false: the tree is Wireshark's empty one (a pass that shows no details and filters on nothing):
-- only the expert infos are added, in the same order, since they reach Wireshark's expert tap and
-- column without a tree. checking: an invisible tree's fields are checked (unseen.add).
-- A register's text fields have one occurrence per register, empty (and hidden) where the register has
-- no such key, as vw3-decode's -T fields lists them: `tshark -T fields -e vw3.reg.code` then lines up
-- with -e vw3.reg.address, and -E occurrence=f names the first register's code, not the first code.
-- (Only text fields can: an empty occurrence of a number would need a text field of the same name, and
-- tshark 4.0 crashes comparing numbers with it, `vw3.reg.value == 3`.)
local function add_register(tree, tvb, f, reg, range, full, checking)
  if full ~= false then
    unseen.at(tvb, f, reg.offset or -1, 2, range, checking)
    local add = unseen.add
    local sub = add(tree, pf.reg)
    sub:set_text(register_title(reg)) -- (an FT_NONE item takes no label in add)
    if reg.address ~= nil then add(sub, pf.reg_address, reg.address, true) end
    add(sub, pf.reg_label, reg.label or "", reg.label ~= nil, reg.label == nil)
    if reg.value ~= nil then add(sub, pf.reg_value, reg.value) end -- (none: an exception 02's inferred status)
    local row = reg.row or unseen.no_row
    add(sub, pf.reg_code, row.code or "", row.code ~= nil, row.code == nil)
    add(sub, pf.reg_name, row.name or "", row.name ~= nil, row.name == nil)
    add(sub, pf.reg_unit, row.unit or "", row.unit ~= nil, row.unit == nil)
    if reg.scaled ~= nil then add(sub, pf.reg_scaled, reg.scaled, true) end
    local parameter = PARAMETER_FIELDS[row]
    if parameter ~= nil and reg.status ~= "protected" and reg.value ~= nil and reg.words ~= 0 then
      add(sub, parameter, reg.scaled or reg.value, true)
    end
    add(sub, pf.reg_text, reg.text or "", reg.text ~= nil, reg.text == nil)
    add(sub, pf.reg_source, row.source or "", row.source ~= nil, row.source == nil)
    if reg.words ~= nil and reg.words ~= 1 then add(sub, pf.reg_words, reg.words, true) end
    add(sub, pf.reg_status, reg.status or "", reg.status ~= nil, reg.status == nil)
    tree = sub
  end
  if reg.status and reg.status ~= "ok" then
    add_text(tree, ex.protected, format("Register %s: %s", register_name(reg), reg.text or reg.status))
  end
end

-- The PDU's fields as vw3-decode -V lists them (detail.py _head_lines), in their layout's order
-- (data/modbus.toml [layouts] and [parts], DATA.rules), each by the fields data/pdu_fields.toml gives it
-- (field.shown: their pf names, a text's string field first and its bytes' second; none: shown otherwise,
-- the window, registers, bits, objects). Read from the frame's bytes when shown: a record keeps no fields.
local LAYOUTS, PARTS = DATA.rules.layouts, DATA.rules.parts

-- The name of the layout a frame's kind and function code read ("raw": none).
local function layout_of(kind, fn)
  local entry = LAYOUT_OF[kind] and LAYOUT_OF[kind][fn]
  return entry and entry.layout or "raw"
end

-- A counted field's bytes from its count's value (as codegen/decode_lua.py's _size_of; odd: the byte an
-- odd count leaves).
local function counted_size(field, count)
  if field.type == "odd" then return count % 2 end
  local n = count - field.minus
  if field.half then return n - n % 2 end
  if field.type == "words" then return 2 * n end
  return n
end

-- The range a field of bytes is added on (its value): the frame's own bytes, or an ASCII frame's bytes that
-- its hex pairs stand for, a data source of their own, as vw3-decode -V shows them (`Data: 1234`, not the
-- pairs' characters 31323334). (TreeItem:add takes no value for a field of bytes: it reads the range's.)
local function bytes_range(tvb, f, b, at, size)
  if not f.ascii then return frame_range(tvb, f, at, size) end
  return ByteArray.new(string.char(table.unpack(b, at, at + size - 1)), true):tvb("VW3 ASCII data"):range(0, size)
end

-- b[at..at+size-1] under the field as_text where every byte is printable ASCII (as vw3-decode), else as_bytes.
local function add_text_or_bytes(t, tvb, f, b, at, size, as_text, as_bytes)
  if size <= 0 then return end
  local text = printable_ascii(b, at, at + size - 1)
  if text then t:add(as_text, frame_range(tvb, f, at, size), text)
  else t:add(as_bytes, bytes_range(tvb, f, b, at, size)) end
end

-- FC12's events (b[at..at+size-1], newest first) named as vw3-decode -V names them: DATA.comm_events[byte], its
-- name and kind (decode/fields.py comm_event, event_kind: data/modbus.toml [names.comm_event*]); an event of a
-- kind each bit of that kind, set or not, as tshark -V (DATA.event_bits: decode/fields.py event_bit_lines).
-- Each byte is vw3.event_list, vw3-decode's fields.event_list (tshark's modbus.event), labelled as -V writes it.
local function set(byte, mask) return floor(byte / mask) % 2 == 1 end -- (mask: a power of two)

local function add_events(t, tvb, f, b, at, size)
  local list = t:add(frame_range(tvb, f, at, size), format("Event list (%d)", size))
  for k = 0, size - 1 do
    local byte, range = b[at + k], frame_range(tvb, f, at + k, 1)
    local item, event = list:add(range, format("[%d]", k)), DATA.comm_events[byte]
    item:add(pf.event_list, range, byte, format("Byte: %d (0x%X)", byte, byte))
    item:add(range, "Event: " .. event[1])
    if event[2] > 0 then
      local under = item:add(range, "Flags")
      for _, bit in ipairs(DATA.event_bits[event[2]]) do
        local value = set(byte, bit[1]) and 1 or 0
        under:add(range, format(bit[2], value, value))
      end
    end
  end
end

-- The fields of `shape` read from b[at] on, the data ending before b[stop], added to `t` (nil: only
-- measured); where they end, or nil when one does not fit (a record that ends its records: grammar.py).
-- (values: a table to keep the fields' values in, for a shape measured again and again)
local function add_shape(t, tvb, f, b, shape, at, stop, values)
  values = values or {}
  for index = 1, #shape do
    local field = shape[index]
    local kind, shown, size = field.type, field.shown, field.size
    if field.when ~= nil and values[field.when] - field.when_minus <= 0 then
      -- (?(n-k): absent, its count leaves it no room: data/modbus.toml)
    elseif size ~= nil then
      if at + size > stop then return nil end
      local value = size == 1 and b[at] or u16(b, at)
      values[field.name] = value
      if t and shown then t:add(pf[shown[1]], frame_range(tvb, f, at, size), value) end
      at = at + size
    elseif kind == "switch" then -- (the part for the earlier field's value, else the last: in place)
      local cases = field.cases
      local part = cases[#cases].part
      for _, case in ipairs(cases) do
        if case.value == values[field.count] then part = case.part break end
      end
      at = add_shape(t, tvb, f, b, PARTS[part], at, stop)
      if at == nil then return nil end
    elseif kind == "array" or kind == "records" then -- (parts: `count` of them, or filling `count` bytes)
      local part, last, many = PARTS[field.part], stop, values[field.count]
      if kind == "records" then last, many = at + many, math.huge end
      if last > stop then return nil end
      while many > 0 and at < last do
        local after = add_shape(nil, tvb, f, b, part, at, last)
        if after == nil then break end
        if t and shown then
          add_shape(t:add(pf[shown[1]], frame_range(tvb, f, at, after - at)), tvb, f, b, part, at, last)
        end
        at, many = after, many - 1
      end
      if kind == "records" then at = last end
    else
      size = kind == "rest" and stop - at or counted_size(field, values[field.count])
      if size < 0 or at + size > stop then return nil end
      if t and shown and size > 0 then
        if kind == "words" then
          for k = at, at + size - 2, 2 do t:add(pf[shown[1]], frame_range(tvb, f, k, 2), u16(b, k)) end
        elseif kind == "odd" then
          t:add(pf[shown[1]], frame_range(tvb, f, at, 1), b[at])
        elseif kind == "text" then
          add_text_or_bytes(t, tvb, f, b, at, size, pf[shown[1]], pf[shown[2]])
        else
          t:add(pf[shown[1]], bytes_range(tvb, f, b, at, size))
          if field.name == "events" then add_events(t, tvb, f, b, at, size) end
        end
      end
      at = at + size
    end
  end
  return at
end

-- The register of a write confirmed by its masks (data/modbus.toml [confirm] "mask": FC22), as vw3-decode
-- --json lists it (render/registers.py mask_register): at its address (label: as shown), its value where the
-- value before does not matter (and_mask 0: or_mask), its masks as text; on the or mask's bytes (offset in
-- the frame; vw3_modbus.lua's: none, it gives the range).
local function mask_register(address, and_mask, or_mask, label, offset)
  local masks = { and_mask = and_mask, or_mask = or_mask }
  return { address = address, label = label, offset = offset,
    value = and_mask == 0 and or_mask or nil, text = say(and_mask == 0 and "mask_written" or "mask_prior", masks) }
end

-- FC17's fields where lua/src/decode.lua read a server id longer than one byte (size bytes, up to its run
-- indicator), as vw3-decode -V lists them (decode/fields.py _report_server_id_response); where they end.
local function add_server_id(t, tvb, f, b, size)
  t:add(pf.byte_count, frame_range(tvb, f, 2, 1), b[2])
  add_text_or_bytes(t, tvb, f, b, 3, size, pf.server_id_text, pf.server_id_bytes)
  t:add(pf.run_indicator, frame_range(tvb, f, 3 + size, 1), b[3 + size])
  add_text_or_bytes(t, tvb, f, b, 4 + size, b[2] - 1 - size, pf.additional_data, pf.additional_bytes)
  return 3 + b[2]
end

-- The PDU's fields of a frame that parsed (not an exception's: its code is shown as such), under `t`, the
-- bytes after them (vw3-decode -V's `Trailing: aabb`); an FC22's register after them.
local function add_pdu(t, tvb, f, stop)
  local name = layout_of(f.kind, f.fn)
  if f.malformed or #LAYOUTS[name] == 0 then return end
  local b = frame_bytes(f, tvb)
  local at
  if f.server_id_size then at = add_server_id(t, tvb, f, b, f.server_id_size)
  else at = add_shape(t, tvb, f, b, LAYOUTS[name], 2, stop) end
  if at ~= nil and at < stop then t:add(pf.trailing, bytes_range(tvb, f, b, at, stop - at)) end
  if MASK_WRITES[f.fn] then
    local places = DATA.field_places[name]
    local reg = mask_register(u16(b, places.address.at), u16(b, places.and_mask.at), u16(b, places.or_mask.at),
      f.span_label, places.or_mask.at)
    add_register(t, tvb, f, reg, nil, true)
  end
end

-- Decimal texts of the numbers the Info column shows, made once each (string.format costs more than
-- the rest of a summary; slaves and addresses repeat). Bounded: addresses are 16 bits.
local DECIMAL = made_once(function(number) return format("%d", number) end)

-- The Info text's forms that vw3-decode's describe.TEXT_FORMS gives and the plugin says alike, by kind and
-- function code (codegen/fields_lua.py info_forms): FC8's sub-function and data, FC24's pointer and values,
-- FC5's coil, FC6's value, FC7's and FC12's status, FC11's counters, FC15's and FC16's `written`, FC22's
-- masks, read from the frame's bytes (a record keeps no fields). The other forms keep the plugin's own text,
-- the window (span_text): registers' values and bits are left out by design (fields_lua.py PLUGIN_STEPS).
-- FORMS[fn][kind]: the form as a function of the frame (below: DATA.info_forms; nil for the usual codes).
local INFO = DATA.fields.info
local MAX_DATA_BYTES, MAX_FIFO_VALUES = INFO.max_data_bytes, INFO.max_fifo_values
local HEX_BYTE = made_once(function(value) return format("%02x", value) end)
-- Tables the texts are put together in, reused (Info texts are made for every record shown: a table each
-- time costs more, in the collector, than the text; hex_of, a format a byte, cost 0.7 % a record on max-size).
local HEX, VALUES, GROUP = {}, {}, {}


-- describe._data: FC8's data (b[first..last]), ` = 7` for a word, ` data 0a0b…` (its first MAX_DATA_BYTES
-- bytes, then how many more) for other data, nothing for none.
local function data_text(b, first, last)
  local size = last - first + 1
  if size == 2 then return " = " .. DECIMAL[b[first] * 256 + b[first + 1]] end
  if size <= 0 then return "" end
  local shown = size < MAX_DATA_BYTES and size or MAX_DATA_BYTES
  for k = 1, shown do HEX[k] = HEX_BYTE[b[first + k - 1]] end
  if size <= MAX_DATA_BYTES then return " data " .. concat(HEX, "", 1, shown) end
  return " data " .. concat(HEX, "", 1, shown) .. "… (+" .. count_text(size - MAX_DATA_BYTES, "byte") .. ")"
end

-- describe._fifo: `:` and the first MAX_FIFO_VALUES of `count` values from b[first] (none past b[last]),
-- then how many more (`… (+2)`); nothing for none.
local function fifo_values(b, count, first, last)
  local made = 0
  for k = 0, (count < MAX_FIFO_VALUES and count or MAX_FIFO_VALUES) - 1 do
    local at = first + 2 * k
    if at + 1 > last then break end
    made = made + 1
    VALUES[made] = DECIMAL[b[at] * 256 + b[at + 1]]
  end
  if made == 0 then return "" end
  local more = count > made and made == MAX_FIFO_VALUES and " … (+" .. DECIMAL[count - made] .. ")" or ""
  return ": " .. concat(VALUES, " ", 1, made) .. more
end

-- The describers of describe._BY_NAME (FC43's MEI, FC17's server id, FC20's and FC21's record groups), on
-- the frame's bytes b (its slave byte at b[base], its data ending at b[last]).
local MEI_TYPES, DEVICE_ID_CODES = DATA.fields.names.mei_types, DATA.fields.names.device_id_codes
local RUN_INDICATOR = DATA.names.run_indicator
local BY_NAME = {}

-- describe._mei: `Read Device Identification, basic, from object 0`; an answer its objects' values (a
-- revision the profile decoded as such: `V2.1`), another MEI type its name.
function BY_NAME.mei(f, b, base)
  local mei_type = b[base + 2]
  local mei = MEI_TYPES[mei_type] or "MEI " .. DECIMAL[mei_type]
  if mei_type ~= 14 then return mei end
  local code = DEVICE_ID_CODES[b[base + 3]] or DECIMAL[b[base + 3]]
  if f.kind == REQUEST then return mei .. ", " .. code .. ", from object " .. DECIMAL[b[base + 4]] end
  local parts = {}
  for index, object in ipairs(f.objects or NO_INTERPRETATION) do
    local text = object.text
    if text == nil or not text:match("^V%d+%.%d+$") then text = "'" .. object.value .. "'" end
    parts[index] = object.name .. "=" .. text
  end
  -- (More Follows FF: the server sends the rest from the next object id on, describe._mei)
  local next_id = b[base + 5] == 255 and b[base + 6]
  local more = next_id and " (more follows from object " .. DECIMAL[next_id] .. ")"
  return mei .. ", " .. code .. ":" .. (parts[1] and " " or "") .. concat(parts, " ") .. (more or "")
end

-- describe._report_server_id: an answer's `server id 18, run ON, 'V1.'` (its data as text where every byte
-- is printable ASCII, else counted). A longer id (lua/src/decode.lua read it up to its run indicator:
-- f.server_id_size) as its text, `'Pymodbus'`, or its bytes, `12 34 56`.
function BY_NAME.report_server_id(f, b, base)
  if f.kind == REQUEST or b[base + 2] == 0 then return "" end -- (byte count 0: no server id)
  if b[base + 2] < 2 then return "server id " .. DECIMAL[b[base + 3]] end -- (byte count 1: the id alone)
  local size = f.server_id_size or 1
  local count, run, after = b[base + 2] - 1 - size, b[base + 3 + size], base + 4 + size
  local text = count > 0 and printable_ascii(b, after, after + count - 1)
  local data = text and python_repr(text) or count_text(count, "byte")
  local id = DECIMAL[b[base + 3]]
  if size > 1 then
    local shown = printable_ascii(b, base + 3, base + 2 + size)
    id = shown and python_repr(shown) or hex_of(b, base + 3, base + 2 + size, "%02X", " ")
  end
  return "server id " .. id .. ", run " .. (RUN_INDICATOR[run] or DECIMAL[run]) .. ", " .. data
end

-- describe._file_record: `2 record group(s)`, the sub-requests, sub-responses or records its byte count holds.
function BY_NAME.file_record(f, b, base)
  local field = LAYOUTS[layout_of(f.kind, f.fn)][2] -- (after the byte count: the records)
  local part, at = PARTS[field.part], base + 3
  local last, groups = at + b[base + 2], 0
  while at < last do
    at = add_shape(nil, nil, f, b, part, at, last, GROUP)
    if at == nil then break end
    groups = groups + 1
  end
  return DECIMAL[groups] .. " record group(s)"
end

-- describe.span_text: the frame's window, `8400..8402 (3)`, `9001` (one), `8400 (0)` (none: nothing wraps),
-- past 65535 as asked (`65535..65539 (5)`, as the warning `span` says it), PLC style its label (`40002..40003
-- (2)`); `(3)` where only the quantity is known, nothing without either. (FC24's start is its pointer: its
-- form says it, DATA.info_forms)
local function span_text(f)
  local start, quantity, label = f.start, f.quantity, f.span_label
  if label ~= nil then
    if quantity == nil or quantity == 1 then return label end
    return label .. " (" .. DECIMAL[quantity] .. ")"
  end
  if start == nil then return quantity ~= nil and "(" .. DECIMAL[quantity] .. ")" or "" end
  if quantity == nil or quantity == 1 then return DECIMAL[start] end
  if quantity == 0 then return DECIMAL[start] .. " (0)" end
  return DECIMAL[start] .. ".." .. DECIMAL[start + quantity - 1] .. " (" .. DECIMAL[quantity] .. ")"
end

-- describe._single: FC6's value, ` TFR=50.0 Hz` where the frame's device (device, else the stream st's
-- for the frame) names its register or reads the value as a text, ` = 7` otherwise; the register named as
-- the tree names it (vw3.story's describe), written as describe.register_text writes a write's register
-- (a write's register has no status).
local function single_text(f, st, device, value)
  device = device or device_of(st, f)
  local run = f.registers
  if device ~= nil and run ~= nil and run.count > 0 and run.start ~= nil then
    local reg = { address = run.start, value = value }
    describe(device, f, reg, run.plain and run.plain[0], nil, words_at(rows_for(device, f.fn), run.start, 0, run.count))
    local code = reg.row and reg.row.code
    if code or reg.text then
      return " " .. (code or reg.label or DECIMAL[run.start]) .. "=" .. (reg.text or DECIMAL[value])
    end
  end
  return " = " .. DECIMAL[value]
end

-- Each form by function code, then kind: written out by the code generator from describe.TEXT_FORMS's
-- steps as DATA.fields.info states them, each field read where its layout places it (DATA.info_forms,
-- codegen/display_lua.py), calling the helpers above; a describer of BY_NAME by its name.
local FORMS = DATA.info_forms(DECIMAL, DIAGNOSTICS, count_text, data_text, fifo_values, single_text, span_text, BY_NAME)

-- NAMING[fn][kind]: the forms that name a register as the frame's device does (a `single` step): their
-- text needs the device (summary's st or device). (DATA.info_naming, codegen/display_lua.py)
local NAMING = DATA.info_naming

-- tvb: the frame's, where it is shown; nil where its text is made as it is decoded (vw3.records
-- remember_request), from its byte table then. st: the frame's stream, or device: its device, where the
-- text names a register as the device does (FC6); nil without either for such a frame (its text made
-- where it is shown).
local function summary(f, tvb, st, device)
  -- (one concatenation, one new string, for the usual frame: the Info text is made for every record shown)
  local kind, fn = f.kind, f.fn
  local steps = FORMS[fn]
  if steps ~= nil then steps = steps[kind] end
  local slave, name = DECIMAL[f.slave], f.function_text or FUNCTIONS[fn] or function_name(fn)
  if kind == EXCEPTION then -- (by the spec, as vw3-decode's summary; the device's meaning: its note)
    -- (no code, a malformed exception: `?`, as describe.py's summary)
    local code = f.exception_code and DECIMAL[f.exception_code] or "?"
    kind = kind .. " " .. code .. " (" .. exception_name(f.exception_code) .. ")"
  end
  local tail = ""
  if f.provisional then tail = " " .. DATA.render.provisional end -- (as vw3-decode's summary says it)
  if f.crc ~= f.crc_expected then tail = tail .. (f.ascii and " BAD LRC" or " BAD CRC") end
  -- (describe.info_text: a frame whose fields did not parse says so)
  if f.malformed then return slave .. " " .. name .. " " .. kind .. " (malformed)" .. tail end
  if steps ~= nil then -- (its bytes: the tvb's, else its byte table's while it is decoded)
    if st == nil and device == nil and NAMING[fn] ~= nil and NAMING[fn][f.kind] then return nil end
    local b, base, last = f.b, f.bi, f.b and f.data_at + f.data_len - 1
    if b == nil and tvb ~= nil then
      b, base, last = frame_bytes(f, tvb), 0, check_at(f) - 1
    end
    if b ~= nil then
      local text = steps(f, b, base, last, st, device) -- (describe.info_text's rstrip: no space before none)
      return slave .. " " .. name .. " " .. kind .. (text == "" and "" or " " .. text) .. tail
    end
  end
  if f.kind == EXCEPTION then return slave .. " " .. name .. " " .. kind .. tail end -- (its code said)
  local text = span_text(f)
  if text == "" and LAYOUT_OF[kind][fn] == nil then -- (a code with no describer: its data counted)
    local size = check_at(f) - 2 -- (but slave and code)
    text = count_text(size, "byte") .. " of data"
  end
  return slave .. " " .. name .. " " .. kind .. (text == "" and "" or " " .. text) .. tail
end
M.START_WORDS, M.add_pdu, M.add_register, M.add_said = START_WORDS, add_pdu, add_register, add_said
M.add_text, M.check_at, M.count_text, M.frame_bytes = add_text, check_at, count_text, frame_bytes
M.frame_range, M.mask_register, M.summary, M.unseen = frame_range, mask_register, summary, unseen
end

-- ---- vw3.clock: lua/src/clock.lua ----
package.preload["vw3.clock"] = function(...)
-- vw3.clock: Wireshark: record times in exact nanoseconds; pinfo's fields read through Wireshark's own getters.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.clock"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, NS, NSTime, floor, lane, math, rawget, type = DATA, NS, NSTime, floor, lane, math, rawget, type

-- Wireshark's functions behind pinfo's fields, TreeItem.text and tvb:raw(), called directly: wslua reaches a
-- field through an __index function that looks the name up first (pinfo.port_type: some 1,120 machine
-- instructions a read, its getter alone some 860; tvb:raw() and tree.text save as much). They are in the
-- class metatables Wireshark keeps in the registry; where there are none (the test stub's Lua tables), a
-- field is read as usual.
local registry = debug and debug.getregistry and debug.getregistry() or {}
local function getter(class, name)
  local meta = registry[class]
  local getters = type(meta) == "table" and rawget(meta, "__getters")
  local get = type(getters) == "table" and rawget(getters, name)
  if type(get) == "function" then return get end
  return function(object) return object[name] end
end
local pinfo_number, pinfo_port_type, pinfo_cols = getter("Pinfo", "number"), getter("Pinfo", "port_type"),
  getter("Pinfo", "cols")
local pinfo_abs_ts, pinfo_rel_ts, tree_text = getter("Pinfo", "abs_ts"), getter("Pinfo", "rel_ts"),
  getter("TreeItem", "text")
local function tvb_method(name) -- (Tvb's own function, called directly: no __index look-up)
  local direct = type(Tvb) == "table" and rawget(Tvb, name)
  if type(direct) == "function" then return direct end
  return function(tvb) return tvb[name](tvb) end
end
-- (the check of a record captured in part, tvb:len() and tvb:reported_len(), cost 3,430 instructions a record
-- through __index, 1,610 so: bench/lua_throughput.py --instructions, plant mix)
local tvb_raw, tvb_len, tvb_reported_len = tvb_method("raw"), tvb_method("len"), tvb_method("reported_len")

-- Record times in integer nanoseconds from a base second of the capture (a double holds them exactly up to
-- 2^53: 104 days), as vw3-decode's Stamps keep the nanoseconds the file wrote (model.py Stamp): every
-- difference (response times, silences, the timeout) is then exact, and its text has vw3-decode's digits.
-- pinfo.abs_ts, a double near 1.7e9 s, is 238 ns coarse: a response time of 2.05 ms read 2.0 or 2.1 ms by
-- chance. pinfo.rel_ts (from Wireshark's reference record, the capture's first) and delta_ts (from the record
-- before) are small: their nanoseconds are exact. The clock is the capture's: a new one with each capture's
-- serial stream (`state`, made by proto.init); clock.times: by number (false: none), the times the usual case
-- below does not give (the first record's, a new reference's, ...) and those a stand-in reads again.
local clock = {} -- (NS: vw3.stream's, nanoseconds a second)
local function capture_clock(abs)
  if clock.capture ~= state then clock = { capture = state, times = {}, nanos = false } end
  if clock.base == nil and abs ~= nil then clock.base = floor(abs) end
  return clock
end

-- A time from abs_ts alone (238 ns coarse), on the microsecond while the capture's exact differences are
-- whole microseconds (a pcap's us, where the rounding makes it exact).
local function coarse_ns(c, abs)
  local ns = floor((abs - c.base) * NS + 0.5)
  if not c.nanos then ns = floor(ns / 1000 + 0.5) * 1000 end
  return ns
end

-- An exact difference in ns (seconds read as a double), and whether the capture has nanoseconds.
local function exact_ns(c, seconds)
  local ns = floor(seconds * NS + 0.5)
  if ns % 1000 ~= 0 then c.nanos = true end
  return ns
end

-- The clock record_ns reads the usual record's time from, in upvalues (fewer look-ups a record): the capture's
-- serial stream, the reference record's time (abs_ts - rel_ts) and that in ns, set where the clock learns its
-- reference (other_record_ns); the last usual record's number and time (chained_ns: the record before); the
-- number of the record whose time rel_ts alone gives (record_ns).
local usual_capture, usual_reference, usual_reference_ns, usual_number, usual_ns = nil, nil, nil, nil, nil
local usual_next = nil

-- The record's time from the one before (delta_ts) where that one's is known, else from abs_ts.
local function chained_ns(c, pinfo, number, abs)
  local before, delta = c.times[number - 1], pinfo.delta_ts
  if usual_capture == state and usual_number == number - 1 then before = usual_ns end -- (record_ns's last)
  if before and delta ~= nil and math.abs(delta) < 4e6 then return before + exact_ns(c, delta) end
  return coarse_ns(c, abs)
end

-- A usual record's time: from the reference's, rel_ts exact; the record after it may take rel_ts alone
-- (record_ns) where the reference's time is after the epoch's first second (the record then is not at
-- the epoch: its time is the reference's and rel_ts > 0).
local function usual_record_ns(number, rel)
  local from = rel * NS + 0.5
  local ns = usual_reference_ns + (from - from % 1)
  usual_number, usual_ns = number, ns
  if usual_reference >= 1 then usual_next = number + 1 end
  return ns
end

-- A record's time as record_ns reads it where it is not the usual case below: the first record, a new
-- reference, an RTAC record, one at the epoch, a stand-in (pinfo nil: its time kept). (abs: pinfo.abs_ts,
-- read already)
local function other_record_ns(pinfo, number, abs)
  local c = clock
  if c.capture ~= state or c.base == nil then c = capture_clock(abs ~= 0 and abs or nil) end
  local times = c.times
  if abs == nil then return times[number] or nil end -- (a stand-in for a record's pinfo: its time kept)
  local ns = rtac_times[number]
  if ns == nil and abs ~= 0 then
    -- The first record, or a new reference (a time reference set in the GUI): from the record before. (A
    -- record of the reference the clock knows is record_ns's usual case, which sets the reference with it.)
    local rel = pinfo.rel_ts
    ns = chained_ns(c, pinfo, number, abs)
    local reference = rel ~= nil and abs - rel -- (the reference record's time; 0: it has none)
    if reference and math.abs(reference) >= 1 then
      usual_capture, usual_reference, usual_reference_ns = state, reference, ns - exact_ns(c, rel)
      if reference >= 1 then usual_next = number + 1 end
    end
  end
  times[number] = ns or false
  return ns
end

-- A record's time as vw3-decode reads it, in ns (nil: none): the RTAC's own timestamp for RTAC serial
-- records (when the device saw the bytes: lane.rtac_ns), none for records at the epoch (vw3-decode -w
-- writes those for untimed input), the record's time otherwise. Read once a record; pinfo nil: a stand-in.
local function record_ns(pinfo, number)
  -- Nearly every record: the one after a usual record (usual_next) of the capture, not an RTAC record, a
  -- time after the reference record's (rel_ts > 0): its time from the reference's, read from rel_ts alone.
  -- The reference cannot have changed since the record before: Wireshark's reference is the capture's
  -- first record or one marked in the GUI, whose rel_ts is 0 (and a record of another protocol between
  -- the two breaks usual_next).
  if number == usual_next and pinfo ~= nil and usual_capture == state and rtac_times[number] == nil then
    local rel = pinfo_rel_ts(pinfo)
    if rel > 0 then return usual_record_ns(number, rel) end
  end
  usual_next = nil
  if pinfo == nil then return other_record_ns(nil, number, nil) end
  local abs = pinfo_abs_ts(pinfo)
  -- Else timed, of the capture whose reference record's time the clock knows, no RTAC record: its time
  -- from the reference's where abs_ts - rel_ts is that reference (other_record_ns: the rest).
  if usual_capture ~= state or abs == 0 or abs == nil or rtac_times[number] ~= nil then
    return other_record_ns(pinfo, number, abs)
  end
  local rel = pinfo_rel_ts(pinfo)
  local drift = rel ~= nil and abs - rel - usual_reference
  if not (drift and drift < 1e-6 and drift > -1e-6) then return other_record_ns(pinfo, number, abs) end
  return usual_record_ns(number, rel)
end

-- Is the second record timed (not at the epoch but within day 0: pcap.py within_day_zero), the first
-- record's time then the epoch's (dissector.lua epoch_first)?
function lane.epoch_timed(pinfo)
  local abs = pinfo.abs_ts
  if abs == 0 or abs >= DATA.timing.day_zero_end or rtac_times[pinfo.number] ~= nil then return false end
  local c = capture_clock(abs)
  c.times[1] = -c.base * NS -- (exact: 1.7e18 is a multiple of 2^9)
  return true
end

-- An RTAC record's own timestamp (u32 seconds, u32 microseconds) in ns, exact.
function lane.rtac_ns(seconds, micros)
  local c = capture_clock(seconds)
  return (seconds - c.base) * NS + micros * 1000
end

-- A response's time since its request (vw3.response_time), an NSTime, exact: 0.010157000, not abs_ts's
-- 0.010157108. nil where either has no time.
function lane.response_time(f)
  local request = f.request
  if f.time == nil or request.time == nil then return nil end
  local delta = f.time - request.time
  local sign = delta < 0 and -1 or 1 -- (stamped before its request: both parts negative, as an nstime holds it)
  local seconds = floor(delta * sign / NS)
  return NSTime.new(sign * seconds, sign * (delta * sign - seconds * NS))
end

-- A record's time kept for a stand-in that decodes it again (dissector.lua decode_again; false: none).
local function keep_time(number, ns)
  clock.times[number] = ns or false
end
M.keep_time, M.pinfo_cols, M.pinfo_number, M.pinfo_port_type = keep_time, pinfo_cols, pinfo_number, pinfo_port_type
M.record_ns, M.tree_text, M.tvb_len, M.tvb_raw = record_ns, tree_text, tvb_len, tvb_raw
M.tvb_reported_len = tvb_reported_len
end

-- ---- vw3.show: lua/src/show.lua ----
package.preload["vw3.show"] = function(...)
-- vw3.show: Wireshark: a frame's item and a record's items shown, a record's first dissection, the first pass's end.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.show"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local AUTO, ByteArray, DATA, DIAGNOSTICS, EXCEPTION = AUTO, ByteArray, DATA, DIAGNOSTICS, EXCEPTION
local KIND_NUMBER, LIFT_OF, MASK_WRITES, NOISE = KIND_NUMBER, LIFT_OF, MASK_WRITES, NOISE
local NO_INTERPRETATION, PLC_LABELS, REQUEST, START_WORDS = NO_INTERPRETATION, PLC_LABELS, REQUEST, START_WORDS
local add_pdu, add_register, add_said, add_text, bit_at = add_pdu, add_register, add_said, add_text, bit_at
local check_at, concat, count_text, device_of, ended, ex = check_at, concat, count_text, device_of, ended, ex
local exception_name, finish_safely, format, frame_bytes = exception_name, finish_safely, format, frame_bytes
local frame_range, function_name, inferred_registers = frame_range, function_name, inferred_registers
local ipairs, keep_time, lane, math, pack, pairs, pf = ipairs, keep_time, lane, math, pack, pairs, pf
local pinfo_cols, plc_base, proto, record_ns, register_view = pinfo_cols, plc_base, proto, record_ns, register_view
local say, summary, tostring, tree_text, tvb_raw, type, u16 = say, summary, tostring, tree_text, tvb_raw, type, u16
local unseen = unseen
local UNMATCHED = say("unmatched", {}) -- (data/modbus.toml [texts])
-- The window's start or quantity (what) on the bytes its lifting rule read it from; generated and on no
-- bytes where the frame does not hold it (a read's answer: its request's; FC5's and FC6's quantity of one).
local function add_window(t, tvb, f, field, what, value)
  local entry = f.kind ~= EXCEPTION and DATA.rules.by_code[f.kind][f.fn]
  local rule = entry and DATA.rules.lift[entry.rule]
  local place = rule and type(rule[what]) == "string" and DATA.field_places[entry.layout][rule[what]]
  if not (place and place.size) then return t:add(field, tvb:range(f.at, 0), value):set_generated() end
  local item, name = t:add(field, frame_range(tvb, f, place.at, place.size), value), rule[what]
  -- (named as vw3-decode -V names the PDU field where it is not the window's own: FC23's `Read start`)
  if name ~= what then item:set_text(name:sub(1, 1):upper() .. name:sub(2):gsub("_", " ") .. ": " .. value) end
  return item
end

-- The addresses a frame names without carrying their values (a read request's window, FC15's and FC16's
-- answers, FC22, FC23's read window and its request's written window where it writes none, as FC16's of
-- quantity 0: its lifting rule's write_window), each a hidden vw3.reg.address (vw3.bit.address: a coil function's),
-- as Wireshark's hidden ip.addr: `vw3.reg.address == 8401` finds the request that asked for 8401 too, as
-- vw3-decode's `address == 8401` (the same addresses: render/filter_match.py item_elements, at most 2000).
-- (BIT_WINDOW[fn]: its request or answer carries bits, its lifting rule's values "bits" or "coil";
-- DATA.bit_windows, codegen/display_lua.py)
local BIT_WINDOW = DATA.bit_windows

-- A PLC-style device's (base: its PLC base) register addresses carry their label too, a hidden vw3.reg.label
-- as a register of the window has it: `vw3.reg.label == "40102"` finds the request, as vw3-decode's `label`.
local function add_named(t, tvb, f, full, base)
  local start, quantity, run = f.start, f.quantity, f.registers or f.bits
  if start == nil or quantity == nil or f.kind == EXCEPTION then return end
  local count, first = run and run.count or 0, run and run.start
  if count > 0 and count == quantity and first == start then return end -- (its values cover the window)
  if MASK_WRITES[f.fn] and not f.malformed then return end -- (FC22: its register is shown, tree.lua add_pdu)
  local field, at = BIT_WINDOW[f.fn] and pf.bit_address or pf.reg_address, tvb:range(f.at, 0)
  local labels = base ~= nil and not BIT_WINDOW[f.fn] and PLC_LABELS[base] or nil
  local named, windows = true, { start, quantity }
  local rule = f.kind == REQUEST and not f.malformed and LIFT_OF[REQUEST][f.fn]
  if rule and rule.write_window then
    local b, places = frame_bytes(f, tvb), DATA.field_places[DATA.rules.by_code[REQUEST][f.fn].layout]
    windows[3], windows[4] = u16(b, places[rule.write_window[1]].at), u16(b, places[rule.write_window[2]].at)
  end
  local size = math.min(math.max(quantity, 1), 2000)
  for w = 1, #windows, 2 do
    for address = windows[w], windows[w] + math.min(math.max(windows[w + 1], 1), 2000) - 1 do
      address = address % 0x10000
      -- (not a value carried, nor, in the written window, an address of the read one named already)
      if (first == nil or (address - first) % 0x10000 >= count)
          and (w == 1 or (address - start) % 0x10000 >= size) then
        if named then
          local item = t:add(field, at, address)
          -- (faked, the frame's item handed back: an invisible tree that needs no such field, unseen.add)
          named = not (full == "unseen" and item.len ~= 0)
          if named then item:set_hidden() end
        end
        if labels ~= nil then
          local item = t:add(pf.reg_label, at, labels[address])
          if full == "unseen" and item.len ~= 0 then labels = nil else item:set_hidden() end
        end
        if not named and labels == nil then return end
      end
    end
  end
end

local function show_frame(st, f, tvb, tree, pinfo, full)
  local crc_ok = f.crc == f.crc_expected
  local t, whole, crc_at = tree, nil, nil
  if full then
    whole = tvb:range(f.at, f.length)
    t = tree:add(proto, whole)
    t:set_text(format("VW3 Modbus %s, %s", f.ascii and "ASCII" or "RTU", summary(f, tvb, st)))
    t:add(pf.item, whole, f.number):set_generated()
    t:add(pf.kind, whole, KIND_NUMBER[f.kind]):set_generated()
    t:add(pf.offset, whole, f.offset):set_generated()
    t:add(pf.mode, whole, f.ascii and "ascii" or "rtu"):set_generated()
    t:add(pf.slave, frame_range(tvb, f, 0, 1), f.slave) -- (the slave byte is the first of the frame's byte table)
    t:add(pf["function"], frame_range(tvb, f, 1, 1), f.fn)
    t:add(pf.function_name, whole, f.function_text or function_name(f.fn)):set_generated()
    local device, reason = device_of(st, f)
    if device then t:add(pf.profile, whole, device.profile.name):set_generated() end
    if reason then t:add(pf.profile_reason, whole, reason):set_generated() end
    if f.provisional then -- (vw3-decode -V's line)
      t:add(pf.provisional, whole, true):set_generated():set_text(DATA.render.provisional_line)
    end
    crc_at = check_at(f)
    local crc_range = frame_range(tvb, f, crc_at, f.ascii and 1 or 2)
    local crc = t:add(pf.crc, crc_range, f.crc)
    local expected = t:add(pf.crc_expected, crc_range, f.crc_expected):set_generated()
    local ok = t:add(pf.crc_ok, crc_range, crc_ok):set_generated()
    if f.ascii then -- (the same fields, named for ASCII's check: one byte, an LRC)
      crc:set_text(format("LRC: 0x%02x", f.crc))
      expected:set_text(format("Expected LRC: 0x%02x", f.crc_expected))
      ok:set_text(crc_ok and "LRC OK: True" or "LRC OK: False")
    end
  end
  if not crc_ok then -- (ASCII: the LRC, one byte)
    local text = f.ascii and "Bad LRC: 0x%02X, expected 0x%02X" or "Bad CRC: 0x%04X, expected 0x%04X"
    add_text(t, ex.crc_bad, format(text, f.crc, f.crc_expected))
  end
  if full and f.broadcast then t:add(pf.broadcast, whole, true):set_generated() end
  if f.kind == EXCEPTION then
    local code = f.exception_code -- (nil: none, a malformed exception)
    if full and code ~= nil then
      t:add(pf.exception_code, frame_range(tvb, f, 2, 1), code)
      -- (bytes after its code: vw3-decode --json's fields.trailing, -Y fields.trailing)
      if crc_at > 3 then t:add(pf.trailing, frame_range(tvb, f, 3, crc_at - 3)) end
    end
    add_text(t, ex.exception, format("Exception %s: %s", code or "?", f.exception_meaning or exception_name(code)))
    if full then
      t:add(pf.exception_name, whole, exception_name(f.exception_code)):set_generated()
      if f.exception_meaning then t:add(pf.exception_meaning, whole, f.exception_meaning):set_generated() end
    end
  end
  if full then
    local data_range = frame_range(tvb, f, 2, 2)
    if f.start ~= nil then
      local item = add_window(t, tvb, f, pf.start, "start", f.start)
      local words = START_WORDS[f.fn]
      if words ~= nil then item:set_text(words.title .. ": " .. f.start) end
    end
    if f.quantity ~= nil then add_window(t, tvb, f, pf.quantity, "quantity", f.quantity) end
    if f.span_label ~= nil then t:add(pf.span_label, whole, f.span_label):set_generated() end
    if f.write_span_label ~= nil then t:add(pf.write_span_label, whole, f.write_span_label):set_generated() end
    if f.subfunction ~= nil then t:add(pf.subfunction, data_range, f.subfunction) end
    if f.kind ~= EXCEPTION then add_pdu(t, tvb, f, crc_at) end
    if f.subfunction ~= nil then
      local name = f.subfunction_text or DIAGNOSTICS[f.subfunction]
      if name ~= nil then t:add(pf.subfunction_name, whole, name):set_generated() end
    end
  end
  local registers = f.registers
  if registers and registers.count > 0 and (full or registers.status ~= nil) then
    -- (no tree: only the expert infos of the registers that are not ok, no value needed: it is 16#8000)
    local b, statuses = full and frame_bytes(f, tvb) or nil, registers.status or NO_INTERPRETATION
    local checking = full == "unseen" and registers.count > 1
    for index = 0, registers.count - 1 do
      if full or statuses[index] ~= nil then
        add_register(t, tvb, f, register_view(st, f, registers, b, index), nil, full, checking)
      end
    end
  end
  if f.inferred then
    for _, reg in ipairs(inferred_registers(st, f)) do add_register(t, tvb, f, reg, nil, full and true) end
  end
  if full then
    local bits = f.bits
    if bits and bits.count > 0 then
      local b = bits.single == nil and frame_bytes(f, tvb) or nil
      local checking, add = full == "unseen" and bits.count > 1, unseen.add
      for index = 0, bits.count - 1 do
        local address, value, k = bit_at(bits, b, index, true)
        unseen.at(tvb, f, k, 1, nil, checking)
        local sub = add(t, pf.bit)
        sub:set_text(format("Bit %s = %d", address and tostring(address) or "?", value))
        if address ~= nil then add(sub, pf.bit_address, address, true) end
        add(sub, pf.bit_value, value, true)
      end
    end
    local device = device_of(st, f)
    add_named(t, tvb, f, full, device and plc_base(device, f))
    if unseen.generated then
      -- what the skipped set_generated() calls of faked items would have done
      unseen.generated = false
      t:set_generated()
    end
    if f.objects then
      for _, object in ipairs(f.objects) do
        local r = frame_range(tvb, f, object.offset, object.length)
        local sub = t:add(pf.object, r)
        -- A device's bytes are data: the value holds no control character (printable.py bytes_text: \x1b, \r,
        -- its quotes escaped), shown between quotes as vw3-decode's -V and summary show it, never written
        -- raw into tshark -V or -T fields (a terminal would run an ESC sequence).
        sub:set_text(format("%s: '%s'", object.name, object.value))
        sub:add(pf.object_id, r, object.id)
        sub:add(pf.object_name, r, object.name):set_generated()
        sub:add(pf.object_value, r, object.value)
        if object.text then sub:add(pf.object_text, r, object.text):set_generated() end
      end
    end
    local request = f.request
    if request ~= nil then
      -- (a request a later record settled, on that record's first showing: the record that showed it too)
      local shown_in = request.record
      if request.late_in ~= nil and not pinfo.visited then shown_in = request.late_in end
      t:add(pf.request_frame, whole, shown_in):set_generated()
      local delta = lane.response_time(f) -- (show.lua)
      if delta ~= nil then t:add(pf.response_time, whole, delta):set_generated() end
    end
    if f.response ~= nil then t:add(pf.response_frame, whole, f.response.record):set_generated() end
  end
  -- Known only once the whole capture has been read (second pass; pinfo nil: the record's first
  -- dissection, which is never a later pass's, and asks pinfo nothing).
  -- (a request the spec has no server answer, pairing's answerless, is never unanswered; the end: vw3.pairing's ended)
  local ends_unanswered, ends_note = false, nil
  if f.kind == REQUEST and st.pending == f and not f.answerless and pinfo ~= nil and pinfo.visited then
    ends_unanswered, ends_note = ended(st, f)
  end
  -- (present only when true: `-Y vw3.unanswered` then finds exactly the requests not answered)
  if f.kind == REQUEST and (f.unanswered or ends_unanswered) then
    add_said(t, whole, pf.unanswered, true, ex.unanswered, "Request not answered")
  end
  if f.profile_choice ~= nil then -- (profile auto: this frame decided the slave's device, as ProfileChoice.text)
    -- (profile_said: the device chosen there, where lane.again annotates with the one chosen at last)
    local text = format("slave %d: %s (%s)", f.slave, f.profile_said or device_of(st, f).profile.name,
      f.profile_choice)
    add_said(t, whole, pf.profile_choice, text, ex.profile, text)
  end
  -- Each warning and note is a string field (full text, filterable) carrying its expert info (whose
  -- label Wireshark cuts at 240 bytes).
  local warnings = f.warnings or NO_INTERPRETATION
  for index = 1, #warnings do
    local text = warnings[index]
    local malformed = f.malformed and text:sub(1, 10) == "malformed "
    add_said(t, whole, pf.warning, text, malformed and ex.malformed or ex.warning, text)
  end
  local notes = f.notes or NO_INTERPRETATION
  -- (the capture end's note after the notes pairing gave, before decoding's: paired_notes, take_frame's count)
  local count, at = #notes, ends_note and (f.paired_notes or 0) + 1
  for index = 1, count + (ends_note and 1 or 0) do
    local text = ends_note
    if index ~= at then text = notes[at and index > at and index - 1 or index] end
    local unmatched = f.no_request and text == UNMATCHED
    add_said(t, whole, pf.note, text, unmatched and ex.no_request or ex.note, text)
  end
  return t -- (the frame's item; with no tree, the tree it was given, where the record's own notes go too)
end

-- What kind of tree Wireshark passes. false: none, an empty TreeItem with no proto_tree behind it (a pass
-- that neither shows details nor filters on fields: tshark's first pass, a summary without filters); its
-- `text` is nil, where a real tree's root is Wireshark's own "Wireshark Lua fake item". "unseen": an
-- invisible tree (see unseen.add). true: a tree that is shown, or the test stub's (a Lua table).
-- (TreeItem.text, .visible and .len, which unseen.add reads, are there from Wireshark 4.0 on.)
local function tree_mode(tree)
  if type(tree) ~= "userdata" then return true end
  if tree_text(tree) == nil then return false end
  if tree.visible == false then return "unseen" end
  return true
end

-- The tvb an item is shown from: the record's own, or a new one holding the item's bytes where it began
-- in earlier records (a frame the capture tool cut across records).
local function item_tvb(item, tvb)
  if item.raw == nil then return tvb end
  return ByteArray.new(item.raw, true):tvb(item.kind == NOISE and "VW3 noise" or "VW3 reassembled frame")
end

-- The noise item `k` places after `item` (0: itself; a run of the same noise is kept as one entry).
-- (expert_text: the run's text, made once for all its items by the caller)
local function show_noise(item, tvb, tree, full, k, expert_text)
  local length = item.length
  local t = tree -- (the item's own, when a tree is wanted: as show_frame's)
  if full then
    local r = tvb:range(item.at + k * length, length)
    t = tree:add(proto, r, format("VW3 noise, %s: %s", count_text(length, "byte"), item.reason))
    t:add(pf.item, r, item.number + k):set_generated()
    t:add(pf.kind, r, KIND_NUMBER[NOISE]):set_generated()
    t:add(pf.offset, r, item.offset + k * length):set_generated()
    t:add(pf.noise_reason, r, item.reason):set_generated()
    t:add(pf.data, r)
  end
  add_text(t, ex.noise, expert_text)
  return t
end

-- A record-level note, on the item they go on: the first item shown, else one of their own. Returns it.
local function record_note(anchor, tree, full, tvb, n, expert_info, text)
  if anchor == nil then
    anchor = tree
    if full then anchor = tree:add(proto, tvb:range(0, n), "VW3 record") end
  end
  add_text(anchor, expert_info, text)
  return anchor
end

-- `1 byte continues`, `5 bytes continue`: a record's bytes framed with the next records'.
local function continue_text(count)
  return count_text(count, "byte") .. (count == 1 and " continues" or " continue")
end

-- One more part of a record's Info text: a single part stays a string, a list is made from the second.
local function add_part(summaries, info, text)
  if summaries ~= nil then
    summaries[#summaries + 1] = text
    return summaries, nil
  end
  if info == nil then return nil, text end
  return { info, text }, nil
end

-- Show one item of a record from `shown_from` (the record's tvb, or one of its own bytes) and add its
-- Info text (`from`: where its bytes came from, when they are another record's). Returns its tree item and
-- the Info parts (add_part).
local function show_item(st, item, shown_from, tree, pinfo, full, summaries, info, from)
  local t
  if item.kind == NOISE then
    -- (a run of the same noise, kept as one entry: its texts made once, for each of its items)
    local bytes = count_text(item.length, "byte")
    local text = format("noise (%s)", bytes) .. (from or "")
    -- (a record captured in part, lua/src/stream.lua cut_stream: marked as tshark marks it, `[Packet size limited during
    -- capture]`, and as vw3-decode's summary line, render/summary.py part_mark)
    if item.reason:sub(1, 16) == "captured in part" then text = text .. " [" .. item.reason .. "]" end
    local expert_text = format("%s outside any frame: %s", bytes, item.reason)
    for k = 0, (item.count or 1) - 1 do
      local shown = show_noise(item, shown_from, tree, full, k, expert_text)
      t = t or shown
      summaries, info = add_part(summaries, info, text)
    end
  else
    t = show_frame(st, item, shown_from, tree, pinfo, full)
    local text = item.info or summary(item, shown_from, st) -- (info: see known_requests)
    summaries, info = add_part(summaries, info, from and text .. from or text)
  end
  return t, summaries, info
end

-- Show a record's items; the record-level notes go on the first item shown (or an item of their own),
-- so that they show in the details, not under a hidden item. A record kept as one packed frame is a
-- number (see pack.settle). whole: the record is one frame just taken by dissect_record's fast lane (not
-- packed yet).
local function show_record(st, record, tvb, pinfo, tree, n, whole)
  local cols = pinfo_cols(pinfo)
  cols.protocol = "VW3"
  local full = tree_mode(tree)
  if whole and not full and config.errors[1] == nil then
    -- No tree (a summary's first pass): the frame's expert infos and its Info text, nothing else to say.
    -- (show_frame only adds expert infos here: asked only when the frame has one to add)
    local item = record[1]
    local registers = item.registers
    if item.crc ~= item.crc_expected or item.kind == EXCEPTION or item.warnings or item.notes or item.unanswered
        or item.profile_choice or item.inferred or (registers ~= nil and registers.status ~= nil) then
      show_frame(st, item, tvb, tree, nil, false)
    end
    -- (info: a known request's, see known_requests; the frame is the record's own, its bytes the tvb's)
    cols.info = item.info or summary(item, tvb, st)
    return
  end
  if type(record) == "number" then record = { record } end
  unseen.serial = unseen.serial + 1
  unseen.generated = false
  local anchor = nil
  if record.error then
    anchor = full and tree:add(proto, tvb:range(0, n)) or tree
    add_text(anchor, ex.internal, "Lua Error in vw3.lua: " .. record.error)
  end
  local continued = record.continued
  -- (the Info text is made each time rather than kept: records stay in memory for the whole capture)
  -- (one part as it is, a list of parts only when there are more)
  local info, summaries = nil, nil
  if continued ~= nil then
    summaries = {}
    for _, part in ipairs(continued) do
      -- (noise: bytes of a run that goes on in later records, which continue no frame)
      local said = part.noise and count_text(part.count, "byte") .. " of noise" or continue_text(part.count)
      local text = format("%s in item %d (record %d)", said, part.item, part.record)
      if full then
        local count = math.min(part.count, n) -- (the record's last bytes: those the frame goes on with)
        local range = tvb:range(n - count, count)
        local t = tree:add(proto, range, format("VW3 bytes of %s shown in a later record: %s",
          part.noise and "noise" or "a frame", text))
        t:add(pf.continued_in, range, part.record):set_generated()
        anchor = anchor or t
      end
      summaries[#summaries + 1] = format("(%s in #%d)", said, part.record)
    end
  end
  -- Items this record decided that the later passes show in earlier records (take_items, st.late): its
  -- first dissection, the only one tshark's single pass makes, shows them here, before its own.
  -- (not where lane.again or a change of mode decoded the record again, unseen: only its first showing)
  local late = st.late
  if late ~= nil and late.record == record and not pinfo.visited then
    st.late = nil
    for index = 1, #late do
      local entry = late[index]
      local item, from = entry.item, entry.from
      local shown_from = ByteArray.new(entry.raw, true):tvb(item.kind == NOISE and "VW3 noise" or "VW3 frame from earlier records")
      local at, count = item.at, item.count
      item.at, item.count = 0, nil -- (its own bytes; a run of the same noise is shown item by item)
      local records = "#" .. concat(from, ", #")
      local t
      t, summaries, info = show_item(st, item, shown_from, tree, pinfo, full, summaries, info, " from " .. records)
      item.at, item.count = at, count
      if full then
        local text = format("Bytes from record%s %s", #from > 1 and "s" or "", concat(from, ", "))
        t:add(proto, shown_from:range(0, item.length), text):set_generated()
      end
      anchor = anchor or t
    end
  end
  local frames = 0
  for index = 1, #record do
    local item = pack.expand(record[index], st)
    local t
    t, summaries, info = show_item(st, item, item_tvb(item, tvb), tree, pinfo, full, summaries, info)
    if item.kind ~= NOISE then frames = frames + 1 end
    anchor = anchor or t
  end
  if frames > 1 then
    anchor = record_note(anchor, tree, full, tvb, n, ex.multiple, format("This record holds %d frames", frames))
  end
  local errors = config.errors
  for index = 1, #errors do
    anchor = record_note(anchor, tree, full, tvb, n, ex.preference, "Preferences: " .. errors[index])
  end
  local waiting = record.waiting
  if waiting ~= nil and waiting > 0 then
    -- (the newest record's: the bytes of them that are noise already, in a run whose end is not known)
    local noise = st.noise_for == record and st.noise_waiting or 0
    if noise > 0 then
      local bytes = count_text(noise, "byte")
      local text = format("The record ends inside a noise run: %s of noise so far, shown as an item with the next"
        .. " records' bytes that end the run", bytes)
      local t = anchor or tree
      if full then -- (on those bytes: the record's waiting bytes begin with them)
        local range = tvb:range(n - waiting, noise)
        t = tree:add(proto, range, "VW3 noise so far, " .. bytes)
        t:add(pf.data, range)
      end
      anchor = anchor or t
      add_text(t, ex.partial, text)
      summaries, info = add_part(summaries, info, format("noise (%s so far)", bytes))
      waiting = waiting - noise
    end
    if waiting > 0 then
      local text = format("The record ends inside a frame: its last %s framed with the next records'",
        waiting == 1 and "byte is" or format("%d bytes are", waiting))
      anchor = record_note(anchor, tree, full, tvb, n, ex.partial, text)
      summaries, info = add_part(summaries, info, format("(%s)", continue_text(waiting)))
    end
  end
  cols.info = info or (summaries and concat(summaries, "; ")) or ""
end

-- tshark dissects a record again only in -2's second pass (its live captures dissect each record once):
-- there any record dissected again ends the first pass, the newest too (a file of one record). Wireshark
-- redraws the newest record's row while it captures (nil: a host without gui_enabled, the test stub).
local TSHARK = gui_enabled ~= nil and not gui_enabled()

-- The first pass is over: what still waits at the end of the capture is framed now, in every stream.
-- The first pass is over when Wireshark dissects again a record older than the newest (tshark -2, the
-- packet details), or tshark any record: then the choices apply to every frame (lane.again). Wireshark
-- capturing dissects the record just read again (its row drawn): its records keep their single pass.
-- (newest_record: the newest record's number, reset with each capture by proto.init)
local function finish_all(number)
  for _, st in pairs(udp_states) do finish_safely(st) end
  finish_safely(state)
  if number < newest_record or TSHARK then
    for _, st in pairs(udp_states) do lane.again(st) end
    lane.again(state)
  end
end

-- Each record (serial record, UDP datagram) is a chunk of its stream.
-- The record's first dissection: nil for an empty record, else the record and its length, and the Info
-- text of a record the quick lanes took (its one frame has nothing else to say where no tree is wanted).
-- (bytes: the record's, read from the tvb where not given; pinfo nil: a stand-in, dissector.lua decode_again)
local function dissect_now(st, tvb, pinfo, number, bytes)
  bytes = bytes or tvb_raw(tvb)
  local n = #bytes
  if n == 0 and lane.parts[number] == nil then return nil end -- (one captured in part of no byte: a cut all the same)
  local time = record_ns(pinfo, number)
  if number >= newest_record then
    newest_record = number
    if time ~= nil then recorded_until = time end
  end
  local again = nil
  if config.default == AUTO and not state.finished then
    -- Kept for lane.again: the whole capture decoded again with its choices, once they are known (not
    -- after the first pass is over: a live capture's later records are never decoded again). Their bytes
    -- by number; their times (false: none) but a quick lane's record's (its frame's: pack.record_time).
    again = st.again
    if again == nil then
      again = { bytes = {}, times = {} }
      st.again = again
    end
    again.bytes[number] = bytes
  end
  if st.sample then keep_time(number, time) end -- (kept for a stand-in: dissector.lua decode_again)
  local record, taken, info = lane.decode(st, bytes, n, time, number)
  if again ~= nil and info == nil then again.times[number] = time or false end
  return record, taken, info
end
M.dissect_now, M.finish_all, M.show_record = dissect_now, finish_all, show_record
end

-- ---- vw3.dissector: lua/src/dissector.lua ----
package.preload["vw3.dissector"] = function(...)
-- vw3.dissector: Wireshark: the dissectors (serial records, RTU over TCP and UDP), registration.
-- Mirrors no Python module.
-- Assembled into lua/vw3.lua by python3 -m dissector.codegen (package.preload["vw3.dissector"]).
local M = require("vw3.env")
local _ENV = M -- (the globals and the other modules' exports; the generator binds those used here as locals)
local DATA, DissectorTable, MODE_REACH, Proto, REQUEST = DATA, DissectorTable, MODE_REACH, Proto, REQUEST
local RESPONSE, add_register, add_text, apply_prefs = RESPONSE, add_register, add_text, apply_prefs
local device_now, dissect_now, ended, ex, finish_all = device_now, dissect_now, ended, ex, finish_all
local ipairs, lane, mask_register, new_state, os, pack = ipairs, lane, mask_register, new_state, os, pack
local package, pair_scan, pcall, pf, pinfo_cols = package, pair_scan, pcall, pf, pinfo_cols
local pinfo_number, pinfo_port_type, proto, record_ns = pinfo_number, pinfo_port_type, proto, record_ns
local sample_modes, show_record, stream_state, tostring = sample_modes, show_record, stream_state, tostring
local tree_text, tvb_len, tvb_raw, tvb_reported_len, type = tree_text, tvb_len, tvb_raw, tvb_reported_len, type
local wtap = wtap

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
end

-- The modules in load order: those that need no Wireshark API first (plain lua5.2/lua5.4 loads them,
-- tests/conformance runs them), then the Wireshark glue.
local PURE = { "crc", "layouts", "stream", "rtu", "ascii", "feed", "decode", "pairing", "maps", "device", "story",
  "explain", "selection", "annotator", "pack", "records" }
local WIRESHARK = { "fields", "tree", "clock", "show", "dissector" }

-- (a second load of this file, as the tests do, starts from fresh modules)
for name in pairs(package.loaded) do
  if type(name) == "string" and name:sub(1, 4) == "vw3." then package.loaded[name] = nil end
end
local env = setmetatable({ DATA = DATA }, { __index = _ENV })
package.loaded["vw3.env"] = env
for _, name in ipairs(PURE) do require("vw3." .. name) end

if Proto == nil then -- loaded outside Wireshark (lua5.x tests without a stub): the pure part's entry points
  return { new_state = env.new_state, dissect_record = env.dissect_record, finish = env.finish,
    settle = env.pack.settle, configure = env.configure }
end

if set_plugin_info then
  set_plugin_info({
    version = "1.0.0",
    description = "Modbus RTU/ASCII for Altivar 71 (VW3 A3 303) and SEL-749M, as vw3-decode decodes it",
    repository = "vw3-dissector (lua/vw3.lua)",
  })
end

for _, name in ipairs(WIRESHARK) do require("vw3." .. name) end
-- (each module's chunk is done with once it ran, its functions held by what it exported: some 60 KB freed)
for name in pairs(package.preload) do
  if name:sub(1, 4) == "vw3." then package.preload[name] = nil end
end
