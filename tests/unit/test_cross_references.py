"""The comments that tie a port to its original name real modules (issue 30).

The Lua plugin, the C engine, the code generator, the benches and the tests say in comments which Python
module or function they port or mirror. Nothing else links the copies, so a rename leaves them pointing at
nothing: this test reads those comments and checks that every `something.py`, every `dissector/...` path
and every `module.name` they give exists (and that the name is defined in that module), and that every
`Class.name` of a class the package defines names something that class defines.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from functools import cache
from pathlib import Path

import pytest

from dissector.render.filter_fields import DERIVED_KEYS

ROOT = Path(__file__).resolve().parents[2]
SKIP_DIRS = {".git", "build", "__pycache__", ".pytest_cache"}


def _tree(pattern: str) -> list[Path]:
    return sorted(p for p in ROOT.glob(pattern) if not SKIP_DIRS & set(p.relative_to(ROOT).parts))


def scanned_files() -> list[Path]:
    files = _tree("lua/**/*.lua") + _tree("dissector/accel/*.c") + _tree("dissector/accel/*.h")
    files += [ROOT / "setup.py"] + _tree("dissector/codegen/*.py") + _tree("bench/*.py")
    files += _tree("dissector/accel/*.py") + _tree("tests/**/*.py")
    return [f for f in files if f != Path(__file__).resolve()]  # this file's own examples are stale on purpose


@cache
def python_files() -> tuple[str, ...]:
    return tuple(str(p.relative_to(ROOT)) for p in _tree("**/*.py"))


# --- the comment text of each kind of file ----------------------------------------------------------------

def lua_comments(text: str) -> str:
    blocks = re.findall(r"--\[(=*)\[(.*?)\]\1\]", text, flags=re.S)
    text = re.sub(r"--\[(=*)\[.*?\]\1\]", "", text, flags=re.S)
    return "\n".join([b for _, b in blocks] + re.findall(r"--(.*)$", text, flags=re.M))


def c_comments(text: str) -> str:
    return "\n".join(a or b for a, b in re.findall(r"/\*(.*?)\*/|//(.*)$", text, flags=re.S | re.M))


def python_comments(text: str) -> str:
    """Comments and docstrings: what a reader takes as prose, not string data the code uses."""
    parts = [tok.string for tok in tokenize.generate_tokens(io.StringIO(text).readline)
             if tok.type == tokenize.COMMENT]
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            doc = ast.get_docstring(node, clean=False)
            if doc:
                parts.append(doc)
    return "\n".join(parts)


def comments(path: Path) -> str:
    text = path.read_text(encoding="utf-8")
    if path.suffix == ".lua":
        return lua_comments(text)
    if path.suffix in (".c", ".h"):
        return c_comments(text)
    return python_comments(text)


# --- the references and how each resolves -------------------------------------------------------------------

PY_FILE = re.compile(r"(?<![\w/.-])((?:[A-Za-z_][\w]*/)*[A-Za-z_]\w*\.py)\b")
# After a file name: the names it is said to hold ("framer.py _run", "rtu.py RULES / _FAST").
NAMES_AFTER = re.compile(r"\.py(?:'s)?[ ,(]+((?:(?:_\w+|[A-Z][A-Z0-9_]{2,}|[a-z]\w*\(\))(?:\s*[/,]\s*)?)+)")
COMMAND = re.compile(r"(?:python3?|-m) +$")  # "python3 tests/corpus/sr_uart.py FILE": an argument, not a name
# "python3 tests/corpus/minimalmodbus_responses.py test_omegacn7500.py": another project's file, an argument.
ARGUMENT = re.compile(r"python3? +\S+\.py +(?:\S+ +)*$")
PACKAGE_PATH = re.compile(r"(?<![\w/.-])(dissector/[\w./-]*[\w])")
# `RtuFramer._scan`: a class of the package and a name in it (classes it does not define, the C engine's
# Stats or Wireshark's TreeItem, are not checked).
CLASS_NAME = re.compile(r"(?<![\w/.-])([A-Z][a-z]\w*)\.([A-Za-z_]\w*)\b")
MODULE_NAME = re.compile(r"(?<![\w/.-])([a-z_][a-z0-9_]*)\.([A-Za-z_]\w*)\b(?![./(]?\w*\.py)")


def resolve_file(ref: str) -> list[str]:
    """Repository files a file reference may mean: the path itself, or any file whose path ends with it."""
    if (ROOT / ref).is_file():
        return [ref]
    return [f for f in python_files() if f == ref or f.endswith("/" + ref)]


@cache
def defined_names(relpath: str) -> frozenset[str]:
    """Every name a module defines at any depth (functions, classes, methods, assignments); a name it only
    imports is not its own (`rtu.py RULES` once RULES moved to rules.py points a reader at the wrong file)."""
    return frozenset(names_defined_in(ast.parse((ROOT / relpath).read_text(encoding="utf-8"))))


def names_defined_in(tree: ast.AST) -> set[str]:
    """The functions, classes, methods and assigned names and attributes anywhere in `tree` (an
    annotated assignment's target is a stored Name too)."""
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store):
            names.add(node.attr)
    return names


@cache
def module_basenames() -> dict[str, list[str]]:
    """Module stem -> its files, for `module.name` references (`pairing.pair`, `rtu.RULES`)."""
    found: dict[str, list[str]] = {}
    for f in python_files():
        if f.startswith("dissector/"):
            stem = Path(f).stem
            if stem != "__init__":
                found.setdefault(stem, []).append(f)
    return found


@cache
def class_names() -> dict[str, frozenset[str]]:
    """Class name -> every name its classes of that name define (methods, attributes), over the package."""
    found: dict[str, set[str]] = {}
    for f in python_files():
        if not f.startswith("dissector/"):
            continue
        for node in ast.walk(ast.parse((ROOT / f).read_text(encoding="utf-8"))):
            if not isinstance(node, ast.ClassDef):
                continue
            found.setdefault(node.name, set()).update(names_defined_in(node))
    return {name: frozenset(names) for name, names in found.items()}


# Stems that once were modules and are gone: a `stem.name` with one of them is stale even though the stem
# is not a module any more (the only way to see `framer.Scan` as a module reference at all).
FORMER_MODULES = {"framer", "decode", "profile_annotator", "annotator", "decoder"}


def problems(path: Path, text: str) -> list[str]:
    where = path.relative_to(ROOT)
    found: list[str] = []
    for match in PY_FILE.finditer(text):
        ref = match.group(1)
        line = text[text.rfind("\n", 0, match.start()) + 1:match.start()]
        if ARGUMENT.search(line):
            continue
        files = resolve_file(ref)
        if not files:
            found.append(f"{where}: names {ref}, which does not exist")
            continue
        after = NAMES_AFTER.match(text, match.end() - 3)
        if after and not COMMAND.search(text, 0, match.start()):
            for name in re.findall(r"\w+", after.group(1)):
                if not any(name in defined_names(f) for f in files):
                    found.append(f"{where}: names {ref} {name}, which {ref} does not define")
    for match in PACKAGE_PATH.finditer(text):
        ref = match.group(1).rstrip(".")
        if not (ROOT / ref).exists() and not resolve_file(ref):
            found.append(f"{where}: names {ref}, which does not exist")
    for match in MODULE_NAME.finditer(text):
        stem, name = match.groups()
        if name == "py":
            continue
        if stem == "fields" and name in DERIVED_KEYS:  # (a -T fields key vw3-decode derives: fields.event_list)
            continue
        files = module_basenames().get(stem)
        if files is None:
            if stem in FORMER_MODULES:
                found.append(f"{where}: names {stem}.{name}; there is no module {stem}")
            continue
        if not any(name in defined_names(f) for f in files):
            found.append(f"{where}: names {stem}.{name}, which {' / '.join(files)} does not define")
    for match in CLASS_NAME.finditer(text):
        cls, name = match.groups()
        names = class_names().get(cls)
        if names is not None and name not in names:
            found.append(f"{where}: names {cls}.{name}, which class {cls} does not define")
    return list(dict.fromkeys(found))  # a path is also a PY_FILE match: one report each


def stale_references() -> list[str]:
    out: list[str] = []
    for path in scanned_files():
        out += problems(path, comments(path))
    return out


def test_every_named_module_and_name_exists():
    assert stale_references() == []


@pytest.mark.parametrize("comment, expected", [
    ("-- mirrors dissector/framing/rtu.py and pairing.py", []),
    ("-- mirrors framer.py and decode.py", ["framer.py", "decode.py"]),
    ("-- as in dissector/framing/nothere.py", ["dissector/framing/nothere.py"]),
    ("-- the rules (framing/rules.py RULES)", []),
    ("-- the rules (framing/rules.py NO_SUCH_RULES)", ["NO_SUCH_RULES"]),
    ("-- scan as framer.Scan does", ["framer.Scan"]),
    ("-- pairing.no_such_function", ["pairing.no_such_function"]),
    ("-- data from dissector/data/nothere.toml", ["dissector/data/nothere.toml"]),
    ("-- made by python3 tests/corpus/sr_uart.py FILE other.py", []),
    ("-- made by python3 tests/corpus/nothere.py FILE", ["tests/corpus/nothere.py"]),
    ("-- as fields._check_echo does, and naming.plc_label", []),
    ("-- as decode._check_echo does", ["decode._check_echo"]),
    ("-- the rules (framing/rtu.py GLITCH_ADDRESSES)", ["GLITCH_ADDRESSES"]),  # imported there, not its own
    ("-- as RtuFramer._shortest_crc does", []),
    ("-- as RtuFramer._no_such_method does", ["RtuFramer._no_such_method"]),
    ("-- a TreeItem.add_le of Wireshark's", []),
])
def test_a_planted_stale_name_is_found(comment, expected):
    """The checker itself: a name that is not there is reported, one that is there is not."""
    found = problems(ROOT / "lua" / "vw3.lua", lua_comments(comment))
    assert len(found) == len(expected), found
    for report, name in zip(found, expected):
        assert name in report
