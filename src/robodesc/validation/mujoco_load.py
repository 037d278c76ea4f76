"""Load emitted URDF text into MuJoCo the way a careful user would, recording every obstacle.

Steps: put explicit ``<mujoco><compiler/>`` options into the text (MuJoCo's defaults fuse fixed
links away and invent inertia from geometry), parse with ``MjSpec`` (which opens no files), point
every mesh at an absolute, decodable file, then compile. When MuJoCo refuses the model because of
one element (a massless moving link, an inertia breaking the triangle inequality, an unreadable
mesh), the refusal becomes a failing check naming that link, the element is patched (a tiny mass,
an isotropic inertia, the geom removed) and compilation is retried, so one defect does not hide
every other comparison. Patched links are skipped by the inertial comparison.
"""

from __future__ import annotations

import os
import re
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import mujoco
import numpy as np
from lxml import etree

from robodesc.ir.model import Robot
from robodesc.validation.meshes import MeshProblem, mujoco_readable, resolve_mesh_file
from robodesc.validation.options import ValidateOptions
from robodesc.validation.report import Status, ValidationReport

COMPILER = {"fusestatic": "false", "inertiafromgeom": "false", "strippath": "false", "discardvisual": "true"}
_ELEMENT = re.compile(r"Element name '([^']*)', id (\d+)")
_MAX_RETRIES = 200


@dataclass(slots=True)
class MujocoModel:
    spec: Any  # mujoco.MjSpec
    model: Any  # mujoco.MjModel
    # Links whose inertial MuJoCo refused and that were patched to load; name -> why.
    patched: dict[str, str] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


def with_compiler_options(urdf_text: str) -> str:
    """The URDF text with a ``<mujoco><compiler .../></mujoco>`` block replacing any existing one."""
    parser = etree.XMLParser(resolve_entities=False, no_network=True, remove_blank_text=False, huge_tree=True)
    root = etree.fromstring(urdf_text.encode("utf-8"), parser)
    for old in root.findall("mujoco"):
        root.remove(old)
    block = etree.SubElement(root, "mujoco")
    etree.SubElement(block, "compiler", attrib=COMPILER)
    return etree.tostring(root, encoding="unicode")


@contextmanager
def captured_warnings(sink: list[str]) -> Iterator[None]:
    """Collect MuJoCo's warnings for the report, where they become findings: those it reports
    through its warning callback, and those its parsers print straight to the C streams
    (``WARNING: Geom with duplicate name ...``), which would otherwise reach the user's terminal
    even with ``-q``."""
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(lambda msg: sink.append(str(msg).strip()))
    try:
        with _c_output(sink):
            yield
    finally:
        mujoco.set_mju_user_warning(previous)


@contextmanager
def _c_output(sink: list[str]) -> Iterator[None]:
    """Standard output and error of the C library, written to a file instead and added to ``sink``."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    with tempfile.TemporaryFile() as capture:
        os.dup2(capture.fileno(), 1)
        os.dup2(capture.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)
            capture.seek(0)
            text = capture.read().decode("utf-8", errors="replace")
            sink.extend(line.strip().removeprefix("WARNING: ") for line in text.splitlines() if line.strip())


def _geom_links(spec: Any) -> dict[str, list[tuple[Any, str]]]:
    """Mesh name -> [(geom, link name)] for every geom using that mesh."""
    out: dict[str, list[tuple[Any, str]]] = {}
    for body in spec.bodies:
        for geom in body.geoms:
            if geom.type == mujoco.mjtGeom.mjGEOM_MESH:
                out.setdefault(geom.meshname, []).append((geom, body.name))
    return out


def _drop_mesh(spec: Any, mesh: Any, users: dict[str, list[tuple[Any, str]]]) -> list[str]:
    links = []
    for geom, link in users.pop(mesh.name, []):
        spec.delete(geom)
        links.append(link)
    spec.delete(mesh)
    return sorted(set(links))


def fix_meshes(
    spec: Any, robot: Robot, base_dir: str | None, options: ValidateOptions, report: ValidationReport
) -> None:
    spec.strippath = False
    spec.meshdir = ""
    users = _geom_links(spec)
    problems = 0
    converted = 0
    for mesh in list(spec.meshes):
        try:
            path = resolve_mesh_file(mesh.file, robot, base_dir, options.package_paths)
            readable = mujoco_readable(path, options.mesh_cache_dir)
        except MeshProblem as exc:
            problems += 1
            links = _drop_mesh(spec, mesh, users)
            report.add(
                "mesh-files",
                Status.FAIL,
                f"mesh {mesh.file!r}",
                f"{exc}; used by link(s) {', '.join(links)} (their collision geometry was left out of the remaining checks)",
            )
            continue
        converted += readable != path
        mesh.file = readable
    if not problems:
        report.add(
            "mesh-files",
            Status.PASS,
            f"{len(spec.meshes)} collision meshes",
            f"all found; {converted} converted to STL for MuJoCo" if converted else "all found",
        )


def compile_with_patches(spec: Any, report: ValidationReport, warnings: list[str]) -> tuple[Any, dict[str, str]]:
    """Compile, turning each refusal into a failing check and patching the element it names."""
    patched: dict[str, str] = {}
    # Read the geoms before the first compile: a spec that failed to compile refuses to be walked.
    users = _geom_links(spec)
    for _ in range(_MAX_RETRIES):
        try:
            with captured_warnings(warnings):
                return spec.compile(), patched
        except ValueError as exc:
            text = str(exc)
            match = _ELEMENT.search(text)
            reason = text.splitlines()[0].removeprefix("Error: ").strip()
            if match is None or not _patch(spec, match.group(1), reason, report, patched, users):
                report.add("mujoco-compile", Status.FAIL, "model", f"MuJoCo refuses the model: {text.strip()}")
                return None, patched
    report.add("mujoco-compile", Status.FAIL, "model", "MuJoCo still refuses the model after patching")
    return None, patched


def _patch(
    spec: Any,
    name: str,
    reason: str,
    report: ValidationReport,
    patched: dict[str, str],
    users: dict[str, list[tuple[Any, str]]],
) -> bool:
    lowered = reason.lower()
    if "mass and inertia of moving bodies" in lowered:
        body = spec.body(name)
        if body is None or name in patched:
            return False
        report.add(
            "mujoco-compile",
            Status.FAIL,
            f"link {name!r}",
            "MuJoCo refuses a moving link without mass and inertia; give the link an <inertial> "
            "or make its joint fixed",
        )
        body.mass = max(float(body.mass), 1e-6)
        body.fullinertia = [np.nan, 0, 0, 0, 0, 0]
        body.inertia = [1e-9, 1e-9, 1e-9]
        body.explicitinertial = True
        patched[name] = "massless moving link"
        return True
    mesh = spec.mesh(name) if "mesh" in lowered or "stl" in lowered or "obj" in lowered else None
    if mesh is not None:
        if "volume is too small" in lowered and int(mesh.inertia) != int(mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL):
            # MuJoCo computes a mesh's volume even when no inertia comes from geometry; a flat or
            # open mesh then stops the load. Its own remedy is inertia="shell" on the mesh.
            report.add(
                "mujoco-compile",
                Status.WARN,
                f"mesh {name!r}",
                f"MuJoCo refuses this mesh by default ({reason.split('.')[0]}); it loads with "
                '<mesh inertia="shell"> in MJCF. The masses compared here do not depend on it',
            )
            mesh.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_SHELL
            return True
        links = _drop_mesh(spec, mesh, users)
        report.add(
            "mujoco-compile",
            Status.FAIL,
            f"mesh {name!r}",
            f"MuJoCo cannot use this mesh ({reason}); used by link(s) {', '.join(links)}; "
            "their collision geometry was left out of the remaining checks",
        )
        return True
    if "inertia" in lowered:
        body = spec.body(name)
        if body is None or name in patched:
            return False
        report.add(
            "mujoco-compile",
            Status.FAIL,
            f"link {name!r}",
            f"MuJoCo refuses the inertia ({reason}); the source tensor is not physical: fix the source "
            "or compile with --invalid-inertia repair",
        )
        full = np.asarray(body.fullinertia, dtype=float)
        diag = full[:3] if np.all(np.isfinite(full)) else np.asarray(body.inertia, dtype=float)
        moment = float(np.max(np.abs(diag))) if np.all(np.isfinite(diag)) else 0.0
        moment = max(moment, 1e-9)  # MuJoCo also needs it above mjMINVAL on a moving body
        body.fullinertia = [np.nan, 0, 0, 0, 0, 0]
        body.inertia = [moment, moment, moment]
        body.mass = max(float(body.mass), 1e-6)
        patched[name] = "non-physical inertia"
        return True
    return False


def explain_parse_failure(robot: Robot, text: str, report: ValidationReport) -> None:
    """MuJoCo's parse errors give a line, not a name: say which links and joints the text lacks."""
    root = etree.fromstring(text.encode("utf-8"), etree.XMLParser(resolve_entities=False, no_network=True))
    links = {el.get("name") for el in root.findall("link")}
    joints = {el.get("name"): el for el in root.findall("joint")}
    for link in robot.links:
        if link.name not in links:
            report.add("bodies", Status.FAIL, f"link {link.name!r}", "link is missing from the URDF text")
    for joint in robot.joints:
        if joint.name not in joints:
            report.add("joints", Status.FAIL, f"joint {joint.name!r}", "joint is missing from the URDF text")
    for name, el in joints.items():
        for end in ("parent", "child"):
            ref = el.find(end)
            target = ref.get("link") if ref is not None else None
            if target not in links:
                report.add("parents", Status.FAIL, f"joint {name!r}", f"{end} link {target!r} is not in the URDF text")


def add_floating_base(spec: Any, robot: Robot) -> None:
    """A free joint on the root body, unless the root is MuJoCo's world or already moves."""
    roots = robot.root_links()
    if len(roots) != 1:
        return
    body = spec.body(roots[0].name)
    if body is None or body.name == "world" or (body.parent is not None and body.parent.name != "world"):
        return
    if not body.joints:
        body.add_freejoint()


# MuJoCo refuses a kinematic tree deeper than this ("depth limit exceeded in signature
# computation"), and its compiler takes superlinear time to find out: 15 s at 2,000 links, longer
# than anyone waits at 50,000.
MUJOCO_MAX_DEPTH = 1023


def tree_depth(robot: Robot) -> int:
    """The number of joints on the longest path from a root link."""
    return robot.tree_depth()


def load_urdf_in_mujoco(
    robot: Robot, urdf_text: str, base_dir: str | None, options: ValidateOptions, report: ValidationReport
) -> MujocoModel | None:
    depth = tree_depth(robot) + (1 if options.floating_base else 0)
    if depth > MUJOCO_MAX_DEPTH:
        report.add(
            "mujoco-compile",
            Status.WARN,
            "model",
            f"not loaded: the kinematic tree is {depth} joints deep and MuJoCo refuses trees deeper than "
            f"{MUJOCO_MAX_DEPTH} (its signature depth limit); the other targets' consumers (Drake for SDF, "
            "usd-core for USD) do not have this limit",
        )
        return None
    try:
        text = with_compiler_options(urdf_text)
    except etree.XMLSyntaxError as exc:
        report.add("mujoco-parse", Status.FAIL, "document", f"the URDF text is not well-formed XML: {exc}")
        return None
    warnings: list[str] = []
    try:
        with captured_warnings(warnings):
            spec = mujoco.MjSpec.from_string(text)
    except ValueError as exc:
        report.add("mujoco-parse", Status.FAIL, "document", f"MuJoCo cannot parse the URDF: {str(exc).strip()}")
        explain_parse_failure(robot, text, report)
        return None
    report.add("mujoco-parse", Status.PASS, "document", f"parsed by MuJoCo {mujoco.__version__}")
    fix_meshes(spec, robot, base_dir, options, report)
    if options.floating_base:
        add_floating_base(spec, robot)
    model, patched = compile_with_patches(spec, report, warnings)
    if model is None:
        return None
    if not report.by_name("mujoco-compile"):
        report.add("mujoco-compile", Status.PASS, "model", f"{model.nbody - 1} bodies, {model.njnt} joints")
    for msg in dict.fromkeys(warnings):
        report.add("mujoco-warning", Status.WARN, "model", msg)
    return MujocoModel(spec, model, patched, warnings)
