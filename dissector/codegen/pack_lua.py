"""How the plugin packs what a record keeps of a frame (lua/src/pack.lua): the slots of one flat array of
numbers per stream, described once here (SLOTS), and the Lua that fills and reads them derived from it
(straight code, no loop a frame): DATA.pack's encode[name] (a named slot from its keys), put (every slot's
value into st.flat: the frame's first slot), expand (a frame's keys and runs in a table, then the keys
APART) and has_rare (does a frame hold a key kept apart, in RARE, or a run one).
"""
from __future__ import annotations

SHORT = 65536  # (the runs' first byte and count: frame indices, under 65,536 in any frame)
# The slots of a packed frame, in order: each the keys it packs, lowest first, each but the last followed
# by its radix (the next key multiplies it). A key that may be missing is one more than it is, 0 for none
# (`+`), or false for none (`?`). A slot with a name is made by encode[name] from its keys; a run's
# (registers, bits) packs the keys of the frame's run (false where it has none). The kind is pack.lua's
# KIND_NUMBER's; link is the request's record, or minus the response's; span_label the span label, or the
# table of the rare keys and the span label.
SLOTS: tuple[tuple[str | None, tuple[str | int, ...]], ...] = (
    ("head", ("kind", 4, "slave", 256, "fn", 256, "length")), (None, ("at",)), (None, ("number",)),
    (None, ("offset",)), (None, ("record",)), (None, ("time?",)), ("crcs", ("crc_expected", SHORT, "crc")),
    ("span", ("quantity+", 65537, "start+")), ("registers", ("first", SHORT, "count", SHORT, "start+")),
    ("bits", ("first", SHORT, "count", SHORT, "start+", 65537, "single+")),
    (None, ("link?",)), (None, ("request_time?",)), (None, ("span_label?",)),
)
RUNS, APART = {"registers", "bits"}, {"link", "request_time"}
# The keys a frame holds rarely: kept in a table in its last slot (with its span label).
RARE = ("warnings", "notes", "unanswered", "broadcast", "no_request", "malformed", "function_text",
        "exception_code", "exception_meaning", "subfunction", "subfunction_text", "objects", "ascii",
        "raw", "inferred", "profile_choice", "profile_said", "provisional", "paired_notes", "server_id_size",
        "write_span_label")
# (a key's code put and got, X its name)
PUT = {"+": "if X == nil then X = 0 else X = X + 1 end", "?": "", "": ""}
GOT = {"+": "if X == 0 then X = nil else X = X - 1 end", "?": "if X == false then X = nil end", "": ""}


def _keys(slot: tuple[str | int, ...]) -> list[tuple[str, str, int | None]]:
    """A slot's keys, lowest first: (name, how it may be missing, the radix after it or None)."""
    out = []
    for index in range(0, len(slot), 2):
        key = str(slot[index])
        name, how = (key[:-1], key[-1]) if key[-1] in "+?" else (key, "")
        radix = slot[index + 1] if index + 1 < len(slot) else None
        out.append((name, how, radix))  # type: ignore[arg-type]
    return out


def _wrapped(head: str, parts: list[str], joint: str, tail: str) -> list[str]:
    """`head`, the parts joined by `joint` and a space, then `tail`, in lines of at most 110 characters (the
    next ones indented by four spaces)."""
    lines, line = [], head
    for index, part in enumerate(parts):
        part += joint if index < len(parts) - 1 else tail
        if len(line) + len(part) + 1 > 110 and line.strip():
            lines.append(line.rstrip())
            line = "    "
        line += part if line in (head, "    ") else " " + part
    return [*lines, line]


def render_pack() -> list[str]:
    """The Lua lines, inside the generated block, that define DATA.pack."""
    lines = ["do", "local floor = math.floor", "local encode = {}"]
    params, put, get, keys, apart = [], [], [], [], []
    for at, (name, slot) in enumerate(SLOTS, 1):
        v, fields = f"s{at}", _keys(slot)
        params.append(v)
        if name:
            lines.append(f"function encode.{name}({', '.join(key for key, _, _ in fields)})")
            lines += [f"  {PUT[how].replace('X', key)}" for key, how, _ in fields if PUT[how]]
            total = ""
            for key, _, radix in reversed(fields):
                total = f"{key} + {radix} * ({total})" if total else key
            lines += [f"  return {total}", "end"]
        got = []
        for key, how, radix in fields:
            if radix is None:
                got.append(f"local {key} = {v}")
            else:
                got += [f"local {key} = {v} % {radix}", f"{v} = floor(({v} - {key}) / {radix})"]
            if GOT[how]:
                got.append(GOT[how].replace("X", key))
        get.append(f"  local {v} = flat[k + {at}]")
        if name in RUNS:
            # (a run's keys in a table of their own, made where the slot holds one)
            run = ", ".join(f"{key} = {key}" for key, _, _ in fields)
            get += [f"  if {v} == false then", f"    {v} = nil", "  else", *(f"    {line}" for line in got),
                    f"    {v} = {{ {run} }}", "  end"]
            keys.append(f"{name} = {v}")
        else:
            get += [f"  {line}" for line in got]
            for key, _, _ in fields:
                (apart if key in APART else keys).append(key if key in APART else f"{key} = {key}")
        if any(how == "?" for _, how, _ in fields):
            put.append(f"  if {v} == nil then {v} = false end")
        put.append(f"  flat[k + {at}] = {v}")
    # (put writes one statement a slot, in order: a multiple assignment stores its last target first, past
    # the end of the array part, where the key goes to the hash part until the table is rebuilt)
    lines += [f"local function put(st, {', '.join(params)})", "  local flat, k = st.flat, st.flat_n", *put,
              f"  st.flat_n = k + {len(SLOTS)}", "  return k", "end"]
    lines += ["local function expand(flat, k)", *get,
              *_wrapped("  return { ", [*keys[:-1], keys[-1] + " }, " + ", ".join(apart)], ",", ""), "end"]
    # (one expression: no loop a frame; a rare key is never false: its truth is the test)
    tests = ["f.registers and (f.registers.status or f.registers.plain)", *(f"f.{key}" for key in RARE)]
    lines += ["local function has_rare(f)", *_wrapped("  return ", tests, " or", ""), "end"]
    # (the slot of a frame's time, after its first: pack.record_time)
    time = next(at for at, (_, slot) in enumerate(SLOTS, 1) if "time?" in slot)
    lines += [f"DATA.pack = {{ encode = encode, put = put, expand = expand, has_rare = has_rare, time = {time},",
              *_wrapped("  rare = { ", [f'"{key}"' for key in RARE], ",", " } }"), "end"]
    return lines
