"""The package's shape: one folder per stage, imports only from earlier stages, no cycles, small modules."""
from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "dissector"
# Pipeline order: a module may import from its own stage or an earlier one, never a later one.
STAGES = {
    "errors": 0, "model": 0,
    "protocol": 1, "sources": 2, "framing": 3, "decode": 4, "devices": 5, "pipeline": 6,
    "render": 7, "accel": 8, "sim": 8, "codegen": 8, "export": 8, "app": 9, "__main__": 10,
}


def _modules() -> dict[str, Path]:
    found = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE).with_suffix("").parts
        found[".".join(parts)] = path
    return found


def _imports(path: Path) -> set[str]:
    names = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("dissector."):
            names.add(node.module.removeprefix("dissector."))
        elif isinstance(node, ast.Import):
            names.update(alias.name.removeprefix("dissector.") for alias in node.names if alias.name.startswith("dissector."))
    return names


def test_no_module_imports_a_later_stage() -> None:
    wrong = []
    for name, path in _modules().items():
        stage = STAGES.get(name.split(".")[0])
        if stage is None:
            continue  # __init__
        for target in _imports(path):
            if target == "accel._summary":
                continue  # the compiled core: a leaf that imports nothing of ours, usable by any stage
            if STAGES[target.split(".")[0]] > stage:
                wrong.append(f"{name} imports {target}")
    assert wrong == []


def test_no_import_cycles() -> None:
    modules = _modules()
    graph = {name: {t for t in _imports(path) if t in modules} for name, path in modules.items()}
    cycles = []

    def visit(name: str, trail: list[str]) -> None:
        for target in graph[name]:
            if target in trail:
                cycles.append(" -> ".join(trail[trail.index(target):] + [target]))
            elif target not in done:
                visit(target, trail + [target])
        done.add(name)

    done: set[str] = set()
    for name in modules:
        if name not in done:
            visit(name, [name])
    assert cycles == []


def test_every_stage_is_a_folder_and_the_top_stays_small() -> None:
    top = sorted(p.stem for p in PACKAGE.glob("*.py") if p.stem not in ("__init__", "__main__"))
    assert len(top) <= 6, top
    folders = {p.name for p in PACKAGE.iterdir() if (p / "__init__.py").exists()}
    assert {"protocol", "sources", "framing", "decode", "devices", "render", "accel", "app", "codegen", "sim"} <= folders


def test_no_python_module_over_600_lines() -> None:
    long = {name: n for name, path in _modules().items() if (n := len(path.read_text().splitlines())) > 600}
    assert long == {}
