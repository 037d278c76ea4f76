"""What the view tests share: the bundled examples, a robot with defects, a GL backend probe."""

from __future__ import annotations

import functools
import os
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
GRIPPER = str(EXAMPLES / "urdf" / "gripper_arm.urdf")
QUADRUPED = str(EXAMPLES / "quadruped.yaml")
GOLDEN = pathlib.Path(__file__).resolve().parent / "golden"

# The gripper arm with three defects on purpose: an inertia that breaks the triangle inequality on
# 'forearm', a mesh file that does not exist on 'hand', and a fixed joint for the merge pass.
DEFECTS = """<?xml version="1.0"?>
<robot name="defects">
  <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual>
    <inertial><mass value="2"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="forearm"><visual><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.03" length="0.3"/></geometry></visual>
    <collision><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.03" length="0.3"/></geometry></collision>
    <inertial><mass value="1"/><inertia ixx="0.001" iyy="0.001" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="hand"><visual><geometry><mesh filename="does_not_exist.stl"/></geometry></visual>
    <inertial><mass value="0.2"/><inertia ixx="0.0001" iyy="0.0001" izz="0.0001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tool"><visual><geometry><sphere radius="0.02"/></geometry></visual>
    <inertial><mass value="0.1"/><inertia ixx="0.00002" iyy="0.00002" izz="0.00002" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="elbow" type="revolute"><parent link="base"/><child link="forearm"/><origin xyz="0 0 0.05"/>
    <axis xyz="0 1 0"/><limit lower="-1.2" upper="0.8" effort="10" velocity="1"/></joint>
  <joint name="wrist" type="continuous"><parent link="forearm"/><child link="hand"/><origin xyz="0 0 0.3"/><axis xyz="0 0 1"/></joint>
  <joint name="tool_mount" type="fixed"><parent link="hand"/><child link="tool"/><origin xyz="0 0 0.05"/></joint>
</robot>
"""


@functools.cache
def gl_backend() -> tuple[str | None, str]:
    """A backend MuJoCo renders offscreen with here, tried in a child process (so this process's
    OpenGL platform stays unchosen): (name, "") or (None, why not)."""
    from robodesc.view.render import backend_candidates

    candidates = backend_candidates()
    if not candidates:
        return None, "neither libEGL nor libOSMesa is installed"
    probe = (
        "import mujoco; m = mujoco.MjModel.from_xml_string('<mujoco><worldbody><geom size=\"1\"/></worldbody></mujoco>');"
        "r = mujoco.Renderer(m, 32, 32); r.update_scene(mujoco.MjData(m)); r.render(); r.close()"
    )
    why = ""
    for name in candidates:
        env = {**os.environ, "MUJOCO_GL": name, "PYOPENGL_PLATFORM": name}
        done = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, check=False)
        if done.returncode == 0:
            return name, ""
        why += f"MUJOCO_GL={name}: {(done.stderr.strip().splitlines() or ['failed'])[-1]}; "
    return None, why
