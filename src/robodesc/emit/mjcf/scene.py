"""``scene.xml``: the robot, a floor, a light and a sky, as mujoco_menagerie's scenes are written.

Its text depends only on the robot file's name and the floor's height (floor.py: under the lowest
collider of a welded robot), so writing it again for the same output is byte-identical: it can be
written in place before validation (see docs/mjcf.md, Outputs)."""

from __future__ import annotations

import os

from robodesc.emit.common.numbers import fmt

SCENE = """<mujoco model="{stem} scene">
  <include file="{robot}"/>
  <visual>
    <headlight diffuse="0.6 0.6 0.6" ambient="0.3 0.3 0.3" specular="0 0 0"/>
    <rgba haze="0.15 0.25 0.35 1"/>
    <global azimuth="120" elevation="-20"/>
  </visual>
  <asset>
    <texture type="skybox" builtin="gradient" rgb1="0.3 0.5 0.7" rgb2="0 0 0" width="512" height="3072"/>
    <texture type="2d" name="groundplane" builtin="checker" mark="edge" rgb1="0.2 0.3 0.4" rgb2="0.1 0.2 0.3" markrgb="0.8 0.8 0.8" width="300" height="300"/>
    <material name="groundplane" texture="groundplane" texuniform="true" texrepeat="5 5" reflectance="0.2"/>
  </asset>
  <worldbody>
    <light pos="0 0 1.5" dir="0 0 -1" directional="true"/>
    <geom name="floor"{floor_pos} size="0 0 0.05" type="plane" material="groundplane"/>
  </worldbody>
</mujoco>
"""


def scene_name(robot_file: str) -> str:
    """``scene.xml`` beside ``robot.xml``; ``<stem>_scene.xml`` beside any other name, so several
    robots can share a folder (``robodesc batch``)."""
    stem = os.path.splitext(os.path.basename(robot_file))[0]
    return "scene.xml" if stem == "robot" else f"{stem}_scene.xml"


def scene_text(robot_file: str, floor: float = 0.0) -> str:
    """The scene for ``robot_file``, its floor at height ``floor`` (m)."""
    base = os.path.basename(robot_file)
    floor_pos = f' pos="0 0 {fmt(floor)}"' if floor else ""
    return SCENE.format(stem=os.path.splitext(base)[0], robot=base, floor_pos=floor_pos)
