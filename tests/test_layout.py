"""The layout of ev3sim2d, as its imports show it: two houses, and layers whose imports point down.

Every module's imports are read with `ast` (nothing is imported), those inside functions included.
From the top down: the front doors (`commands/`, `cli`, `serve`, `join`, `simulate`), the readers
(`grading/`, `live/`, `render/`, `editor/`), the simulator process (`simulator/`), its parts
(`world/`, `devices/`, `results/`), and `protocol/`.  A module imports its own layer and those
below it, never one above.  The brick's house (`brick/`) and the shim (`ev3dev2/`) stand apart:
the brick imports only the protocol, the shim nothing of ev3sim2d, and of the simulator's side
only the front doors may import the brick (`doctor` asks it what isolation this computer gives).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

FRONT_DOORS = {"commands", "cli", "serve", "join", "simulate", "__main__", ""}  # "": the package itself
LAYERS = [  # top to bottom
    ("the front doors", FRONT_DOORS),
    ("the readers", {"grading", "live", "render", "editor"}),
    ("the simulator", {"simulator"}),
    ("the simulator's parts", {"world", "devices", "results"}),
    ("the protocol", {"protocol"}),
]
BRICK = "brick"
EDITOR_USERS = {"ev3sim2d.commands.edit", "ev3sim2d.live.server"}
# The one allowed circle: grading/check.py loads the checks package so that each check module
# registers its kind, and each check module imports the Check base class it registers under.
ALLOWED_CIRCLE_PREFIXES = ("ev3sim2d.grading.check", "ev3sim2d.grading.checks")


def module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def read_imports(root: Path, package: str) -> dict[str, set[str]]:
    """Each module of `package` under `root` and the modules of `package` it imports (anywhere in it)."""
    paths = {module_name(p, root): p for p in sorted((root / package).rglob("*.py"))}
    graph: dict[str, set[str]] = {}
    for name, path in paths.items():
        is_package = path.name == "__init__.py"
        here = name.split(".") if is_package else name.split(".")[:-1]
        found: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.Import):
                found.update(alias.name for alias in node.names)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = here[: len(here) - node.level + 1]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                for alias in node.names:  # `from . import palette` imports a module
                    found.add(f"{target}.{alias.name}" if f"{target}.{alias.name}" in paths else target)
        graph[name] = {m for m in found if m in paths or m.split(".")[0] == package} - {name}
    return graph


def part_of(module: str) -> str:
    """The folder (or front-door file) a module of ev3sim2d belongs to: ev3sim2d.world.grid -> world."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def layer_of(module: str) -> int | None:
    part = part_of(module)
    return next((i for i, (_, parts) in enumerate(LAYERS) if part in parts), None)


def layout_faults(graph: dict[str, set[str]]) -> list[str]:
    """What in the import graph of ev3sim2d breaks the layout, one line each."""
    faults = []
    for module, imported in sorted(graph.items()):
        here = part_of(module)
        if here != BRICK and layer_of(module) is None:
            faults.append(f"{module}: in no layer; add its folder to LAYERS in tests/test_layout.py")
            continue
        for target in sorted(imported):
            there = part_of(target)
            if here == BRICK:
                if there not in (BRICK, "protocol"):
                    faults.append(f"{module} imports {target}: the brick imports only brick/ and protocol/")
            elif there == BRICK:
                if here not in FRONT_DOORS:
                    faults.append(f"{module} imports {target}: only the front doors may import the brick")
            elif there == "editor" and here != "editor" and module not in EDITOR_USERS:
                faults.append(
                    f"{module} imports {target}: only the edit command and the live server use editor/"
                )
            elif layer_of(target) is not None and layer_of(target) < layer_of(module):
                upper, lower = LAYERS[layer_of(target)][0], LAYERS[layer_of(module)][0]
                faults.append(
                    f"{module} imports {target}: {lower} must not import {upper} (imports point down)"
                )
    for circle in circles(graph):
        if not all(m.startswith(ALLOWED_CIRCLE_PREFIXES) for m in circle):
            faults.append(f"a circle of imports between files: {' -> '.join(sorted(circle))}")
    return faults


def circles(graph: dict[str, set[str]]) -> list[set[str]]:
    """The strongly connected groups of more than one module (Tarjan's algorithm, iteratively)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next((c for c in children if c in graph), None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                group = set()
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    group.add(member)
                    if member == node:
                        break
                if len(group) > 1:
                    found.append(group)
    return found


def test_every_import_of_ev3sim2d_points_down_the_layers():
    assert layout_faults(read_imports(ROOT, "ev3sim2d")) == []


def test_the_grading_checks_registry_is_the_only_circle_and_is_there():
    """The allowed circle is real (if it goes, drop the exception); no other exists."""
    found = circles(read_imports(ROOT, "ev3sim2d"))
    assert len(found) == 1 and all(m.startswith(ALLOWED_CIRCLE_PREFIXES) for m in found[0])


@pytest.mark.parametrize("shim", ["ev3dev2", "pybricks"])
def test_the_shim_imports_nothing_of_ev3sim2d_nor_of_the_other_shim(shim):
    """A student's program imports a shim on the brick; it reaches the simulator only through the
    backend the brick connects (ev3dev2/_link.py, pybricks/_link.py), and a program gets one shim, never
    both (brick/program_kind.py), so neither leans on the other."""
    graph = read_imports(ROOT, shim)
    assert len(graph) > 10
    forbidden = {"ev3sim2d", *({"ev3dev2", "pybricks"} - {shim})}
    for path in sorted((ROOT / shim).rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = (
                [a.name for a in node.names]
                if isinstance(node, ast.Import)
                else [node.module or ""]
                if isinstance(node, ast.ImportFrom) and not node.level
                else []
            )
            assert not any(n.split(".")[0] in forbidden for n in names), f"{path}: imports {names}"


def test_readme_names_every_folder_of_the_tree_in_its_layout_section():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("## How the code is laid out", 1)[1].split("\n## ", 1)[0]
    folders = {path.parent.name for path in (ROOT / "ev3sim2d").glob("*/__init__.py")}
    assert set(re.findall(r"`(\w+)/`", section)) == folders | {"ev3sim2d", "ev3dev2", "pybricks"}
    front_door_files = {part for part in FRONT_DOORS if (ROOT / "ev3sim2d" / f"{part}.py").is_file()}
    assert {f"{name}.py" for name in front_door_files - {"__main__"}} <= set(
        re.findall(r"`(\w+\.py)`", section)
    )


def plant(tmp_path: Path, files: dict[str, str]) -> dict[str, set[str]]:
    for name, text in files.items():
        path = tmp_path / "ev3sim2d" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return read_imports(tmp_path, "ev3sim2d")


LAYERED = {
    "__init__.py": "",
    "protocol/__init__.py": "",
    "world/__init__.py": "",
    "world/grid.py": "from ..protocol import x\n",
    "simulator/__init__.py": "",
    "simulator/session.py": "from ..world.grid import Grid\n",
    "render/__init__.py": "",
    "render/frame.py": "from ..simulator import session\n",
    "editor/__init__.py": "",
    "editor/writer.py": "",
    "brick/__init__.py": "",
    "brick/link.py": "from ..protocol import x\n",
    "commands/__init__.py": "",
    "commands/run.py": "from ..render.frame import draw\nfrom ..brick import link\n",
}


def test_the_check_passes_a_layered_package(tmp_path):
    assert layout_faults(plant(tmp_path, LAYERED)) == []


def test_the_check_fails_an_upward_import(tmp_path):
    graph = plant(
        tmp_path, {**LAYERED, "world/pose.py": "def later():\n    from ..simulator.session import S\n"}
    )
    assert layout_faults(graph) == [
        "ev3sim2d.world.pose imports ev3sim2d.simulator.session: the simulator's parts must not import "
        "the simulator (imports point down)"
    ]


def test_the_check_fails_a_brick_importing_the_simulator_side(tmp_path):
    graph = plant(tmp_path, {**LAYERED, "brick/link.py": "from ev3sim2d.world import grid\n"})
    assert layout_faults(graph) == [
        "ev3sim2d.brick.link imports ev3sim2d.world.grid: the brick imports only brick/ and protocol/"
    ]


def test_the_check_fails_the_world_importing_the_editor(tmp_path):
    graph = plant(tmp_path, {**LAYERED, "world/grid.py": "from ..editor import writer\n"})
    assert [f.split(":")[0] for f in layout_faults(graph)] == [
        "ev3sim2d.world.grid imports ev3sim2d.editor.writer"
    ]


def test_the_check_fails_a_circle_and_a_folder_in_no_layer(tmp_path):
    graph = plant(
        tmp_path,
        {
            **LAYERED,
            "render/frame.py": "from .video import SIZE\n",
            "render/video.py": "from .frame import draw\n",
            "gadgets/__init__.py": "",
        },
    )
    assert layout_faults(graph) == [
        "ev3sim2d.gadgets: in no layer; add its folder to LAYERS in tests/test_layout.py",
        "a circle of imports between files: ev3sim2d.render.frame -> ev3sim2d.render.video",
    ]
