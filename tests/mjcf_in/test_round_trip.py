"""MJCF -> IR -> MJCF: the same model in MuJoCo.

Masses, the whole robot's centre and inertia, every joint's world anchor and axis at random joint
positions, mesh geoms' places, effort limits, equalities and the home keyframe, between the source
and robodesc's MJCF of it. robodesc's own MJCF goldens and the feature fixture always; menagerie's
models when ROBODESC_MENAGERIE_DIR names a checkout (tests/mjcf_in/README in docs/mjcf-input.md).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import mujoco
import numpy as np
import pytest

import robodesc
from tests.mjcf_in.compare import _root_shift, compare, unmatched_meshes

DATA = Path(__file__).parent / "data"
ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests" / "mjcf" / "golden"
MENAGERIE = os.environ.get("ROBODESC_MENAGERIE_DIR")
# Models of menagerie covering its features: degrees, eulerseq, refs, ball joints and loop closures
# (cassie), <general> servos, a tendon and a joint equality (panda), position servos and a free base
# (go1), motors (h1), site thrusters and ellipsoids (skydio_x2), inertia from mesh geoms (allegro),
# a wrist camera (gen3). benchmarks/menagerie_input.py runs a whole checkout.
MENAGERIE_MODELS = (
    "unitree_go1/scene.xml",
    "franka_emika_panda/scene.xml",
    "agility_cassie/scene.xml",
    "universal_robots_ur5e/scene.xml",
    "unitree_h1/scene.xml",
    "skydio_x2/scene.xml",
    "wonik_allegro/scene.xml",
    "kinova_gen3/scene.xml",
)


def _golden(name: str, tmp_path: Path) -> Path:
    text = (GOLDEN / f"{name}.xml").read_text()
    if 'file="meshes/' in text:
        # A golden whose meshes the MJCF folder carries (docs/mjcf.md): written afresh beside them.
        path = tmp_path / "golden" / f"{name}.xml"
        robodesc.compile_to(str(ROOT / "examples" / "urdf" / f"{name}.urdf"), "mjcf", str(path))
        return path
    path = tmp_path / f"{name}.xml"
    path.write_text(text.replace("<ROOT>", str(ROOT)))
    return path


def _round_trip(source: Path, tmp_path: Path) -> tuple[Any, Any, Any]:
    out = tmp_path / "out" / "robot.xml"
    result = robodesc.compile_to(str(source), "mjcf", str(out))
    return mujoco.MjModel.from_xml_path(str(source)), mujoco.MjModel.from_xml_path(str(out)), result


def _efforts(model: Any) -> dict[str, float]:
    """Joint name -> the force its joint actuator can give (forcerange, else ctrlrange x gain for a motor)."""
    out = {}
    for a in range(model.nu):
        if int(model.actuator_trntype[a]) != 0:
            continue
        joint = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, int(model.actuator_trnid[a][0]))
        gear = abs(float(model.actuator_gear[a][0]))
        if model.actuator_forcelimited[a]:
            out[joint] = float(np.abs(model.actuator_forcerange[a]).max()) * gear
        elif int(model.actuator_biastype[a]) == 0 and model.actuator_ctrllimited[a]:
            out[joint] = float(np.abs(model.actuator_ctrlrange[a]).max()) * gear * float(model.actuator_gainprm[a][0])
    return out


def _equalities(model: Any) -> list[int]:
    return sorted(int(model.eq_type[e]) for e in range(model.neq))


def _check(source: Any, written: Any) -> None:
    assert compare(source, written) == []
    assert unmatched_meshes(source, written, _root_shift(source, written)) == 0
    want, got = _efforts(source), _efforts(written)
    for joint, effort in want.items():
        assert got.get(joint) == pytest.approx(effort, rel=1e-9), joint
    tendon_or_flex = {3, 4}
    wanted = [t for e, t in enumerate(_equalities(source)) if t not in tendon_or_flex and source.eq_active0[e]]
    assert _equalities(written) == wanted


@pytest.mark.parametrize("name", ["quadruped", "four_bar", "gripper_arm"])
def test_goldens(name: str, tmp_path: Path) -> None:
    source, written, _ = _round_trip(_golden(name, tmp_path), tmp_path)
    _check(source, written)


def test_feature_fixture(tmp_path: Path) -> None:
    source, written, result = _round_trip(DATA / "features.xml", tmp_path)
    _check(source, written)
    # The home keyframe's joints, less their ref, are the written model's home.
    home = mujoco.mj_name2id(source, mujoco.mjtObj.mjOBJ_KEY, "home")
    written_home = mujoco.mj_name2id(written, mujoco.mjtObj.mjOBJ_KEY, "home")
    assert written_home >= 0
    for name in ("shoulder", "wrist_pitch", "wrist_roll", "slide", "follower"):
        j_a = mujoco.mj_name2id(source, mujoco.mjtObj.mjOBJ_JOINT, name)
        j_b = mujoco.mj_name2id(written, mujoco.mjtObj.mjOBJ_JOINT, name)
        a = source.key_qpos[home][source.jnt_qposadr[j_a]] - source.qpos0[source.jnt_qposadr[j_a]]
        b = written.key_qpos[written_home][written.jnt_qposadr[j_b]]
        if name != "follower":  # a mimic joint is placed by its leader
            assert b == pytest.approx(a, abs=1e-9), name
    codes = {f.code for f in result.findings}
    assert "mjcf-not-held" in codes


@pytest.mark.skipif(MENAGERIE is None, reason="ROBODESC_MENAGERIE_DIR names no mujoco_menagerie checkout")
@pytest.mark.parametrize("model", MENAGERIE_MODELS)
def test_menagerie(model: str, tmp_path: Path) -> None:
    path = Path(MENAGERIE or "") / model
    if not path.exists():
        pytest.skip(f"{model} is not in this checkout")
    source, written, _ = _round_trip(path, tmp_path)
    _check(source, written)


def test_source_gains_are_written(tmp_path: Path) -> None:
    """The source's servos come back with their own gains and kinds; a motor gets robodesc's servo."""
    source, written, _ = _round_trip(DATA / "features.xml", tmp_path)

    def servo(model: Any, joint: str) -> tuple[float, float, float]:
        j = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
        a = next(a for a in range(model.nu) if model.actuator_trntype[a] == 0 and model.actuator_trnid[a][0] == j)
        return (
            float(model.actuator_gainprm[a][0]),
            float(model.actuator_biasprm[a][1]),
            float(model.actuator_biasprm[a][2]),
        )

    for joint in ("shoulder", "slide", "wrist_roll"):
        assert servo(written, joint) == pytest.approx(servo(source, joint)), joint
    kp, bias_kp, _ = servo(written, "wrist_pitch")
    assert kp > 0 and bias_kp == -kp  # a position servo with derived gains, not the source's motor


def test_user_gains_win(tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    robodesc.compile_to(str(DATA / "features.xml"), "mjcf", str(out), stiffness=7.0, damping=0.5)
    model = mujoco.MjModel.from_xml_path(str(out))
    j = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "shoulder")
    a = next(a for a in range(model.nu) if model.actuator_trnid[a][0] == j)
    assert (model.actuator_gainprm[a][0], model.actuator_biasprm[a][2]) == pytest.approx((7.0, -0.5))


def test_source_gains_reach_usd(tmp_path: Path) -> None:
    from pxr import Usd

    out = tmp_path / "robot.usda"
    robodesc.compile_to(str(DATA / "features.xml"), "usd", str(out))
    stage = Usd.Stage.Open(str(out))
    joints = {p.GetName(): p for p in stage.Traverse() if p.GetName() in ("shoulder", "slide")}
    # USD's angular gains are per degree; linear ones per metre.
    shoulder = joints["shoulder"].GetAttribute("drive:angular:physics:stiffness").Get()
    assert shoulder == pytest.approx(50.0 * np.pi / 180, rel=1e-6)
    assert joints["slide"].GetAttribute("drive:linear:physics:stiffness").Get() == pytest.approx(200.0, rel=1e-6)
