"""Compliant cords (--cords FILE.yaml): chains of capsules on spherical joints hanging from anchors,
the same field in MuJoCo (ball joints), PhysX (D6 joints with drives) and SDF (ball joints), each
engine settling a cord under tilted gravity where the statics of a springy chain put it."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import mujoco
import numpy as np
import pytest
from lxml import etree

from robodesc.api import compile_to_mjcf, compile_to_sdf, compile_to_usd
from robodesc.cli import main
from robodesc.validation.physx_python import physx_python
from tests.conftest import EXAMPLES
from tests.worlds.physx_scripts import positions

QUADRUPED = EXAMPLES / "quadruped.yaml"
N, LENGTH, K, RADIUS = 6, 0.6, 0.1, 0.008
GX, GZ = 2.0, -9.6

CORDS = f"""cords:
  - {{name: vines, count: 1, length: {LENGTH}, segments: {N}, radius: {RADIUS}, stiffness: {K}, damping: 0.05,
     anchor_height: [1.0, 1.0], area: [5, 0, 5, 0], seed: 1}}
"""
TILTED = f"""<sdf version="1.6"><world name="tilt"><gravity>{GX} 0 {GZ}</gravity>
<model name="ground"><static>true</static><pose>0 0 -0.05 0 0 0</pose><link name="l"><collision name="c">
<geometry><box><size>20 20 0.1</size></box></geometry></collision></link></model></world></sdf>"""


def equilibrium() -> np.ndarray:
    """The segment tops (x, z) of the chain at rest: the minimum of its potential energy (springs at
    every joint, gravity (GX, GZ) on each segment's middle), by Newton's method on the angles."""
    mass = 1000 * np.pi * RADIUS**2 * LENGTH / N
    step = LENGTH / N

    def grad(phi: np.ndarray) -> np.ndarray:
        rel = np.diff(np.concatenate([[0.0], phi]))
        g = K * rel - K * np.concatenate([rel[1:], [0.0]])
        for s in range(N):  # d(potential)/d(phi_s): every segment at or below s moves with phi_s
            arm = (np.arange(N) > s) * step + (np.arange(N) == s) * step / 2
            g[s] -= mass * np.sum(arm * (GX * np.cos(phi[s]) + GZ * np.sin(phi[s])))
        return g

    phi = np.zeros(N)
    for _ in range(50):
        jac = np.array([(grad(phi + h) - grad(phi - h)) / 2e-7 for h in np.eye(N) * 1e-7]).T
        phi = phi - np.linalg.solve(jac, grad(phi))
    tops = np.cumsum(np.c_[step * np.sin(phi), -step * np.cos(phi)], axis=0)
    return np.array([5.0, 1.0]) + np.vstack([[0.0, 0.0], tops[:-1]])


@pytest.fixture
def scene(tmp_path: Path) -> tuple[Path, Path]:
    (tmp_path / "cords.yaml").write_text(CORDS)
    (tmp_path / "tilt.world").write_text(TILTED)
    return tmp_path / "cords.yaml", tmp_path / "tilt.world"


def test_mujoco_settles_where_the_statics_say(scene: tuple[Path, Path], tmp_path: Path) -> None:
    cords, world = scene
    compile_to_mjcf(str(QUADRUPED), str(tmp_path / "m" / "robot.xml"), cords=str(cords), world=str(world))
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "m" / "scene.xml"))
    data = mujoco.MjData(model)
    while data.time < 10.0:
        mujoco.mj_step(model, data)
    tops = np.array([data.xpos[model.body(f"vines_0_{k}").id][[0, 2]] for k in range(N)])
    assert model.jnt_type[model.joint("vines_0_0").id] == mujoco.mjtJoint.mjJNT_BALL
    assert np.abs(tops - equilibrium()).max() < 3e-3


@pytest.mark.skipif(physx_python() is None, reason="no PhysX interpreter (tests/consumers/run.sh builds one)")
def test_physx_settles_where_the_statics_say(scene: tuple[Path, Path], tmp_path: Path) -> None:
    cords, world = scene
    compile_to_usd(str(QUADRUPED), str(tmp_path / "q.usda"), cords=str(cords), world=str(world))
    python = physx_python()
    assert python is not None
    done = subprocess.run(
        [python, "-c", positions("ARTICULATION_LINK", "position"), str(tmp_path / "q_world.usda"), "10"],
        capture_output=True, text=True, timeout=900, check=False, env={**os.environ},
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    rows = np.array([r for r in json.loads(done.stdout.strip().splitlines()[-1]) if r[0] > 4.5])
    tops = rows[1:, [0, 2]]  # the anchor link first, then the segments in order
    assert len(tops) == N
    assert np.abs(tops - equilibrium()).max() < 3e-3


def test_sdf_ball_joints_and_the_lost_spring(scene: tuple[Path, Path], tmp_path: Path) -> None:
    cords, _ = scene
    result = compile_to_sdf(str(QUADRUPED), str(tmp_path / "q.sdf"), cords=str(cords))
    world = etree.parse(str(tmp_path / "q.sdf")).getroot().find("world")
    assert world is not None and world.find("model[@name='ground_plane']") is not None
    cord = world.find("model[@name='vines_0']")
    assert cord is not None and len(cord.findall("joint[@type='ball']")) == N
    assert any(f.code == "sdf-cords-no-spring" for f in result.findings)


def test_urdf_refuses_cords_and_bad_files_are_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    good = tmp_path / "cords.yaml"
    good.write_text(CORDS)
    code = main(["compile", str(QUADRUPED), "-t", "urdf", "-o", str(tmp_path / "r.urdf"), "--cords", str(good)])
    assert code == 2 and "cannot hold a world" in capsys.readouterr().err
    for text, said in (
        ("cords:\n  - {count: 0}\n", "count must be a whole number"),
        ("cords:\n  - {length: .nan}\n", "length must be a finite number"),
        ("cords:\n  - {colour: red}\n", "unknown field(s) colour"),
        ("cords: [\n", "not YAML"),
    ):
        bad = tmp_path / "bad.yaml"
        bad.write_text(text)
        code = main(["compile", str(QUADRUPED), "-t", "mjcf", "-o", str(tmp_path / "x.xml"), "--cords", str(bad)])
        assert code == 2 and said in capsys.readouterr().err


def test_the_example_field(tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    compile_to_mjcf(str(QUADRUPED), str(out), cords=str(EXAMPLES / "worlds" / "underbrush.yaml"))
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
    assert sum(1 for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_BALL) == 12 * 6
