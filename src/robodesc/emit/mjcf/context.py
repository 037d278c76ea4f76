"""State shared by the MJCF modules while one robot is written."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

from robodesc.emit.common.numbers import fmt, fmt_vec
from robodesc.emit.common.paths import PathMode
from robodesc.emit.mjcf.options import MjcfOptions
from robodesc.ir.diagnostics import Findings, Severity, SourceLoc
from robodesc.ir.geometry import Pose
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame, pose_frame

STAGE = "emit:mjcf"


@dataclass(slots=True)
class MjcfContext:
    robot: Robot
    options: MjcfOptions
    findings: Findings
    out_dir: str
    mesh_paths: PathMode = PathMode.RELATIVE
    # The user gave these options explicitly (the rest may follow the robot or other options).
    given: frozenset[str] = frozenset()
    asset: ET.Element = field(default_factory=lambda: ET.Element("asset"))
    # Files written beside robot.xml (converted meshes), by role.
    written: dict[str, str] = field(default_factory=dict)
    # Model joints in qpos order: (MJCF name, kind, IR joint name or None).
    qpos_joints: list[tuple[str, str, str | None]] = field(default_factory=list)
    # Bodies written, by link name (for sites, sensors, equality constraints).
    bodies: dict[str, ET.Element] = field(default_factory=dict)
    site_names: set[str] = field(default_factory=set)

    def warn(self, code: str, message: str, element: str, loc: SourceLoc | None = None) -> None:
        self.findings.add(Severity.WARNING, code, message, element=element, loc=loc, stage=STAGE)

    def info(self, code: str, message: str, element: str, loc: SourceLoc | None = None) -> None:
        self.findings.add(Severity.INFO, code, message, element=element, loc=loc, stage=STAGE)

    def unique_site(self, name: str) -> str:
        candidate, n = name, 1
        while candidate in self.site_names:
            n += 1
            candidate = f"{name}_{n}"
        self.site_names.add(candidate)
        return candidate


def set_pose(el: ET.Element, frame: Frame | Pose | None) -> None:
    """``pos``/``quat`` attributes, left out where they are MuJoCo's default (zero, identity)."""
    if frame is None:
        return
    if isinstance(frame, Pose):
        frame = pose_frame(frame)
    if any(frame.translation):
        el.set("pos", fmt_vec(frame.translation))
    quat = frame.quat()
    if quat != (1.0, 0.0, 0.0, 0.0):
        el.set("quat", fmt_vec(quat))


def insert_site(body: ET.Element, site: ET.Element) -> None:
    """Sites go after the body's own inertial, joints and geoms and before its child bodies."""
    children = list(body)
    index = next((i for i, c in enumerate(children) if c.tag == "body"), len(children))
    body.insert(index, site)


def num(value: float) -> str:
    return fmt(value)
