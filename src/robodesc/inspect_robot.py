"""``robodesc inspect``: a robot's kinematic tree, DOF, mass and findings."""

from __future__ import annotations

from dataclasses import dataclass, field

from robodesc.frontends.load import Source, load_source
from robodesc.ir.diagnostics import Finding, Findings, Severity
from robodesc.ir.model import Robot
from robodesc.options import CompileOptions


@dataclass(slots=True)
class InspectReport:
    robot: Robot
    findings: list[Finding] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not any(f.severity is Severity.ERROR for f in self.findings)

    def tree_lines(self) -> list[str]:
        robot = self.robot
        children = robot.child_joints()
        lines: list[str] = []
        seen: set[str] = set()

        def walk(link: str, depth: int, via: str) -> None:
            if link in seen:
                lines.append("  " * depth + f"{link} (cycle)")
                return
            seen.add(link)
            lines.append("  " * depth + link + via)
            for joint in children.get(link, []):
                walk(joint.child, depth + 1, f"  <- {joint.name} [{joint.type.value}]")

        for root in robot.root_links():
            walk(root.name, 0, "")
        return lines

    def as_dict(self) -> dict[str, object]:
        robot = self.robot
        return {
            "name": robot.name,
            "links": len(robot.links),
            "joints": len(robot.joints),
            "dof": robot.dof,
            "actuated_joints": [j.name for j in robot.actuated_joints()],
            "total_mass": robot.total_mass(),
            "roots": [link.name for link in robot.root_links()],
            "loop_joints": len(robot.loop_joints),
            "fixed_frames": len(robot.fixed_frames),
            "sensors": len(robot.sensors),
            "materials": len(robot.materials),
            "extensions": len(robot.extensions),
            "tree": self.tree_lines(),
            "findings": [f.as_dict() for f in self.findings],
        }

    def render(self) -> str:
        robot = self.robot
        out = [
            f"robot {robot.name!r}: {len(robot.links)} links, {len(robot.joints)} joints, {robot.dof} DOF, "
            f"total mass {robot.total_mass():.6g} kg",
        ]
        extras = [
            f"{n} {what}"
            for n, what in (
                (len(robot.loop_joints), "loop joints"),
                (len(robot.fixed_frames), "fixed frames"),
                (len(robot.sensors), "sensors"),
                (len(robot.transmissions), "transmissions"),
                (len(robot.ros2_controls), "ros2_control blocks"),
                (len(robot.extensions), "kept extension blocks"),
            )
            if n
        ]
        if extras:
            out.append("also: " + ", ".join(extras))
        out.append("")
        out.extend(self.tree_lines())
        return "\n".join(out) + "\n"


def describe(source: Source, options: CompileOptions) -> InspectReport:
    """The robot as ``compile`` reads it, with the findings ``compile`` would report and the same
    severities: a source defect the outputs carry is a warning (an error under ``--invalid-inertia
    error``); only what leaves nothing to compile raises."""
    from robodesc.pipeline import verify_source

    findings = Findings()
    robot = load_source(source, options.load, findings)
    verify_source(robot, options, findings)
    return InspectReport(robot, list(findings))
