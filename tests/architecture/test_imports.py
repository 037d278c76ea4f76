"""The import rule of docs/architecture.md, checked on the source with ``ast``.

Every import counts, including those inside functions (a lazy import is still a dependency). An
edge goes to the module named: ``from a.b import c`` reaches ``a.b.c`` when that is a module and the
package ``a.b`` otherwise. The parent packages Python initialises on the way are not edges: a
package's ``__init__`` re-exporting its own submodules is not a cycle. ``from robodesc import x``
reaches the root package, which would come back round through the API: that is what this catches.
"""

from __future__ import annotations

import ast
import pathlib

import pytest

SRC = pathlib.Path(__file__).resolve().parents[2] / "src"
PACKAGE = SRC / "robodesc"

# Stage packages and what each may import (besides itself). The top-level modules are the driver
# (api, pipeline, cli and their helpers): the only code that imports everything.
DRIVER = "<driver>"
ALLOWED: dict[str, set[str]] = {
    "ir": set(),
    "usdfile": set(),
    "meshes": {"ir"},
    "frontends": {"ir"},
    "passes": {"ir", "meshes"},
    # Validation is a library of consumers and comparisons; each target's package says which of
    # them checks its output (its ``Target.validate``), so emit sits above validation.
    "validation": {"ir", "meshes", "usdfile"},
    "emit": {"ir", "meshes", "usdfile", "validation"},
}
# Frontends and compositions are one stage (compositions are frontends that live in their own
# package); they must still not form a module cycle, which the cycle check below sees.


def module_name(path: pathlib.Path) -> str:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES: dict[str, pathlib.Path] = {module_name(p): p for p in PACKAGE.rglob("*.py")}
EXTENSIONS = {module_name(p) for p in PACKAGE.rglob("*.c")}


def _resolve(name: str) -> str | None:
    """The robodesc module an import name refers to (a submodule or, failing that, its package)."""
    while name:
        if name in MODULES or name in EXTENSIONS:
            return name
        name = name.rpartition(".")[0]
    return None


def imports_of(module: str) -> set[str]:
    path = MODULES[module]
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(tree):
        names: list[str] = []
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")
                anchor = anchor[: len(anchor) - node.level + 1]
                base = ".".join([*anchor, base] if base else anchor)
            # ``from pkg import name``: name may be a submodule.
            names = [f"{base}.{a.name}" for a in node.names] + [base]
        for name in names:
            if not name.startswith("robodesc"):
                continue
            target = _resolve(name)
            if target is None or target == module:
                continue
            found.add(target)
    return found


GRAPH = {m: imports_of(m) for m in MODULES}


# A leaf every stage may name.
LEAVES = {"robodesc._version", "robodesc._files"}


# Packages of the driver layer: they may import everything, and only the CLI imports them.
DRIVER_PACKAGES = {"batch", "cli", "view"}


def stage(module: str) -> str:
    if module in LEAVES:
        return "leaf"
    parts = module.split(".")
    if len(parts) >= 2 and parts[1] in DRIVER_PACKAGES:
        return DRIVER
    if len(parts) >= 3 or (len(parts) == 2 and (PACKAGE / parts[1]).is_dir()):
        return parts[1]
    return DRIVER


def test_every_module_is_seen() -> None:
    assert "robodesc.emit.usd.joints" in GRAPH and "robodesc.meshes.collada" in GRAPH
    assert "robodesc.meshes._weld" in EXTENSIONS and "robodesc.meshes._numtext" in EXTENSIONS


def test_no_import_cycle() -> None:
    # Tarjan's algorithm, iterative; every strongly connected component must be a single module.
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    cycles: list[list[str]] = []
    counter = 0
    for start in sorted(GRAPH):
        if start in index:
            continue
        work = [(start, iter(sorted(GRAPH[start])))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, edges = work[-1]
            for nxt in edges:
                if nxt not in GRAPH:
                    continue
                if nxt not in index:
                    index[nxt] = low[nxt] = counter
                    counter += 1
                    stack.append(nxt)
                    on_stack.add(nxt)
                    work.append((nxt, iter(sorted(GRAPH[nxt]))))
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        top = stack.pop()
                        on_stack.discard(top)
                        component.append(top)
                        if top == node:
                            break
                    if len(component) > 1:
                        cycles.append(sorted(component))
    assert not cycles, "import cycles:\n" + "\n".join(" <-> ".join(c) for c in cycles)


@pytest.mark.parametrize("module", sorted(m for m in GRAPH if stage(m) not in (DRIVER, "leaf")))
def test_imports_follow_the_stage_order(module: str) -> None:
    own = stage(module)
    wrong = sorted(
        target
        for target in GRAPH[module]
        if stage(target) not in (own, "leaf") and (stage(target) == DRIVER or stage(target) not in ALLOWED[own])
    )
    assert not wrong, f"{module} ({own}) imports {wrong}; {own} may import {sorted(ALLOWED[own]) or 'nothing'}"


def test_the_root_package_imports_only_its_version_eagerly() -> None:
    tree = ast.parse((PACKAGE / "__init__.py").read_text(encoding="utf-8"))
    top_level = [n for n in tree.body if isinstance(n, ast.ImportFrom) and (n.module or "").startswith("robodesc")]
    assert [n.module for n in top_level] == ["robodesc._version"]


def test_public_import_paths_of_the_docs() -> None:
    """The import paths README.md and docs/ show keep working."""
    import robodesc
    from robodesc.emit.common.numbers import fmt
    from robodesc.emit.isaac import write_isaac_folder
    from robodesc.emit.ros2 import Ros2Options, build_ros2_package, emit_ros2_package
    from robodesc.emit.sdf import SdfOptions, build_sdf, emit_sdf
    from robodesc.emit.urdf import UrdfOptions, emit_urdf
    from robodesc.emit.usd import UsdOptions, emit_usd

    for name in robodesc.__all__:
        assert getattr(robodesc, name) is not None
    assert callable(robodesc.compile_for_isaac_sim) and callable(robodesc.load)
    assert all(
        callable(x)
        for x in (
            fmt,
            write_isaac_folder,
            build_ros2_package,
            emit_ros2_package,
            build_sdf,
            emit_sdf,
            emit_urdf,
            emit_usd,
        )
    )
    assert {SdfOptions, UsdOptions, Ros2Options, UrdfOptions}


def test_only_the_cli_imports_driver_packages() -> None:
    def package(module: str) -> str:
        parts = module.split(".")
        return parts[1] if len(parts) > 1 and parts[1] in DRIVER_PACKAGES else ""

    entry_points = {"robodesc.__main__", "robodesc._console"}  # they start the CLI
    for module, targets in sorted(GRAPH.items()):
        if package(module) == "cli":
            continue
        reached = {t for t in targets if package(t) and package(t) != package(module)}
        if module in entry_points:
            reached = {t for t in reached if package(t) != "cli"}
        if package(module) == "batch":  # a batch's summary.html draws its robots
            reached = {t for t in reached if package(t) != "view"}
        assert not reached, f"{module} imports {sorted(reached)}: only robodesc.cli may"


# ---- the driver knows no target by name ------------------------------------------------------
# The one table that names them, and the places a name is the point: the CLI's --ros2/--isaac-sim
# shortcuts, and the API's named shortcuts (compile_to_usd, compile_for_isaac_sim ...) which match
# them. Every other target reaches the driver through the table (robodesc.compile_to(src, "mjcf") and
# robodesc.compile_to_mjcf work for a new target without an edit).
TARGET_NAMES = {"urdf", "sdf", "usd", "ros2", "isaac", "mjcf"}
NAMING_ALLOWED = {
    "robodesc.targets": None,  # the table: everywhere in the module
    "robodesc.cli.commands": {"compile_target"},
    "robodesc.api": {
        "compile_to_urdf",
        "compile_to_sdf",
        "compile_to_usd",
        "compile_for_ros2",
        "compile_for_gazebo",
        "compile_for_isaac_sim",
        "isaac_physics_layer",  # robodesc layer: the Isaac folder's physics layer for an existing import
        "validate_file",
    },
}


def _named_targets(module: str) -> list[str]:
    path = MODULES[module]
    tree = ast.parse(path.read_text(encoding="utf-8"))
    allowed = NAMING_ALLOWED.get(module, set())
    if allowed is None:
        return []
    found: list[str] = []

    def visit(node: ast.AST, function: str) -> None:
        for child in ast.iter_child_nodes(node):
            name = (
                child.name if isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef) and function == "" else function
            )
            if name not in allowed:
                if isinstance(child, ast.Constant) and child.value in TARGET_NAMES:
                    found.append(f"line {child.lineno}: {child.value!r}")
                if isinstance(child, ast.ImportFrom | ast.Import):
                    modules = (
                        [child.module or ""] if isinstance(child, ast.ImportFrom) else [a.name for a in child.names]
                    )
                    for m in modules:
                        if (
                            m.split(".")[:2] == ["robodesc", "emit"]
                            and len(m.split(".")) > 2
                            and m.split(".")[2] in TARGET_NAMES
                        ):
                            found.append(f"line {child.lineno}: imports {m}")
            visit(child, name)

    visit(tree, "")
    return found


@pytest.mark.parametrize("module", sorted(m for m in MODULES if stage(m) == DRIVER and m not in LEAVES))
def test_no_driver_module_names_a_target(module: str) -> None:
    named = _named_targets(module)
    assert not named, f"{module} names targets ({', '.join(named)}); a target's name belongs in robodesc.targets only"


def test_targets_use_each_other_through_their_public_names() -> None:
    """A target builds on another target through that package's ``__init__`` (ROS 2 writes SDF's
    world through ``robodesc.emit.sdf``), never through its internal modules."""
    wrong = []
    for module, targets in sorted(GRAPH.items()):
        parts = module.split(".")
        if len(parts) < 3 or parts[1] != "emit" or parts[2] == "common":
            continue
        for target in targets:
            tparts = target.split(".")
            if len(tparts) > 3 and tparts[1] == "emit" and tparts[2] not in (parts[2], "common"):
                wrong.append(f"{module} -> {target}")
    assert not wrong, "import another target's public names (robodesc.emit.<target>): " + "; ".join(wrong)
