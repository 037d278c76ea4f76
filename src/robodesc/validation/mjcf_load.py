"""The MJCF target's minimal check, used until :mod:`robodesc.validation.mujoco_mjcf` (the full
comparison with the IR) is present: MuJoCo loads robot.xml and scene.xml with zero warnings.

The scene includes robot.xml by its final name, and during a compile robot.xml is still staged
under another name: the scene is checked through a temporary copy that includes the staged file.
"""

from __future__ import annotations

import os
import tempfile
from typing import Any

from robodesc.ir.model import Robot
from robodesc.validation.mujoco_load import captured_warnings
from robodesc.validation.report import Status, ValidationReport


def validate_mjcf(robot: Robot, emitted: Any, options: Any = None) -> ValidationReport:
    report = ValidationReport(robot=robot.name, target="mjcf", consumer="mujoco")
    files: dict[str, str] = emitted.files
    robot_xml = files["mjcf"]
    _load(report, "mujoco-compile", robot_xml, robot_xml)
    scene = files.get("scene")
    if scene is not None:
        with open(scene, encoding="utf-8") as handle:
            text = handle.read()
        staged = os.path.basename(robot_xml)
        fd, tmp = tempfile.mkstemp(prefix=".robodesc-scene-", suffix=".xml", dir=os.path.dirname(robot_xml))
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as handle:
                handle.write(_include(text, staged))
            _load(report, "mujoco-compile", tmp, scene)  # same name: classified as the other targets
        finally:
            os.unlink(tmp)
    return report


def _include(text: str, staged: str) -> str:
    """The scene text with its ``<include file=...>`` naming ``staged``."""
    start = text.index("<include file=")
    end = text.index("/>", start)
    return text[:start] + f'<include file="{staged}"' + text[end:]


def _load(report: ValidationReport, name: str, path: str, shown: str) -> None:
    import mujoco

    warnings: list[str] = []
    try:
        with captured_warnings(warnings):
            model = mujoco.MjModel.from_xml_path(path)
            data = mujoco.MjData(model)
            mujoco.mj_forward(model, data)
    except ValueError as exc:
        report.add(name, Status.FAIL, os.path.basename(shown), f"MuJoCo cannot load it: {str(exc).strip()}")
        return
    if warnings:
        report.add(name, Status.FAIL, os.path.basename(shown), "MuJoCo warned: " + "; ".join(warnings))
        return
    report.add(
        name,
        Status.PASS,
        os.path.basename(shown),
        f"loaded with no warning: {model.nbody - 1} bodies, {model.njnt} joints, {model.nu} actuators",
    )
