"""Small robots written into a test's folder: URDF with meshes, a xacro with an include and an
argument, compositions, and Python compositions that crash, hang or sleep."""

from __future__ import annotations

from pathlib import Path

STL = """solid t
facet normal 0 0 1
outer loop
vertex 0 0 0
vertex {s} 0 0
vertex 0 {s} 0
endloop
endfacet
facet normal 0 0 1
outer loop
vertex 0 0 0
vertex 0 {s} 0
vertex 0 0 {s}
endloop
endfacet
facet normal 0 0 1
outer loop
vertex 0 0 0
vertex 0 0 {s}
vertex {s} 0 0
endloop
endfacet
facet normal 1 1 1
outer loop
vertex {s} 0 0
vertex 0 0 {s}
vertex 0 {s} 0
endloop
endfacet
endsolid t
"""

INERTIAL = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>'


def mesh_urdf(name: str, mesh: str) -> str:
    return f"""<?xml version="1.0"?>
<robot name="{name}">
  <link name="base">{INERTIAL}
    <visual><geometry><mesh filename="{mesh}"/></geometry></visual>
  </link>
  <link name="tip">{INERTIAL}<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="tip"/><axis xyz="0 0 1"/>
    <origin xyz="0 0 0.5"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""


XACRO = """<?xml version="1.0"?>
<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="length" default="0.5"/>
  <xacro:include filename="parts.xacro"/>
  <xacro:part name="base"/>
  <xacro:part name="upper"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 1 0"/>
    <origin xyz="0 0 $(arg length)"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""

PARTS = f"""<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="name">
    <link name="${{name}}">{INERTIAL}<visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
  </xacro:macro>
</robot>
"""

YAML_ROBOT = """robot: pendulum
links:
  base: {geometry: {box: [0.1, 0.1, 0.1]}, mass: 1}
  bob: {geometry: {sphere: 0.05}, mass: 0.2, pose: [0, 0, -0.5]}
joints:
  swing: {type: revolute, parent: base, child: bob, axis: y, limits: {lower: -1, upper: 1}}
"""

PYTHON_ROBOT = """from robodesc.frontends.compose.builder import RobotBuilder
from robodesc.frontends.compose.shapes import box

{prelude}

def build():
    {body}
    b = RobotBuilder("{name}", fixed_base=True)
    b.link("base", box(0.1, 0.1, 0.1), mass=1.0)
    b.link("arm", box(0.05, 0.05, 0.3), mass=0.5, pose=(0, 0, 0.2))
    b.joint("j", "revolute", "base", "arm", axis="y", lower=-1, upper=1, effort=1, velocity=1)
    robot = b.build()
    {after}
    return robot
"""


def python_robot(path: Path, name: str, body: str = "pass", prelude: str = "", after: str = "pass") -> Path:
    """A Python composition; ``body`` runs before it builds, ``after`` on the built ``robot``."""
    path.write_text(PYTHON_ROBOT.format(name=name, body=body, prelude=prelude, after=after), encoding="utf-8")
    return path


# A composition's own exception is an input error (exit 2 at its line); one in robodesc's code is a
# crash. A robot that is not valid IR (a None visual) makes robodesc's own code raise.
CORRUPT_IR = "robot.links[0].visuals.append(None)"


def make_collection(root: Path) -> Path:
    """``root/robots``: two URDFs with their own meshes, one with a shared mesh, a xacro with a
    macro include, a composition, and files that are not robots."""
    robots = root / "robots"
    (robots / "meshes").mkdir(parents=True)
    (robots / "meshes" / "a.stl").write_text(STL.format(s=0.1))
    (robots / "meshes" / "b.stl").write_text(STL.format(s=0.2))
    (robots / "alpha.urdf").write_text(mesh_urdf("alpha", "meshes/a.stl"))
    (robots / "beta.urdf").write_text(mesh_urdf("beta", "meshes/b.stl"))
    (robots / "arm").mkdir()
    (robots / "arm" / "arm.urdf.xacro").write_text(XACRO)
    (robots / "arm" / "parts.xacro").write_text(PARTS)
    (robots / "pendulum.yaml").write_text(YAML_ROBOT)
    (robots / "controllers.yaml").write_text("controller_manager: {ros__parameters: {update_rate: 100}}\n")
    (robots / "notes.py").write_text("print('not a robot')\n")
    return robots
