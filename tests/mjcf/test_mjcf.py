"""The MJCF target: golden files, MuJoCo loads without warnings, numbers equal the IR, gain units,
every example, every input kind through the API."""

from __future__ import annotations

import math
import os
import shutil
from pathlib import Path
from typing import Any

import mujoco
import pytest

from robodesc.api import compile_to_mjcf, compile_to_usd
from robodesc.ir.diagnostics import ValidationFailed
from tests.conftest import EXAMPLES, HOLO_ARM, SPIRIT_XACRO
from tests.mjcf.helpers import check_mass_and_fk, load_clean, normalised

DATA = Path(__file__).parent / "data"
PKG = {"robodesc_examples": str(EXAMPLES / "urdf")}

GOLDEN = {
    "gripper_arm": EXAMPLES / "urdf/gripper_arm.urdf",  # mimic, camera, fixed frame, mesh
    "quadruped": EXAMPLES / "quadruped.yaml",  # floating base, armature, transmissions
    "four_bar": EXAMPLES / "four_bar.py",  # loop joint
    "dae_arm": DATA / "dae_arm.urdf",  # COLLADA converted to OBJ, scale, rotated inertial frame
}


@pytest.mark.parametrize("name", sorted(GOLDEN))
def test_golden(name: str, tmp_path: Path, golden: object) -> None:
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(str(GOLDEN[name]), str(out), package_paths=PKG)
    assert result.validation is not None and result.validation.ok
    golden.check(f"{name}.xml", normalised(out.read_text()))  # type: ignore[attr-defined]
    load_clean(out)
    load_clean(tmp_path / "scene.xml")


@pytest.mark.parametrize("name", sorted(GOLDEN))
def test_numbers_equal_ir(name: str, tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(str(GOLDEN[name]), str(out), package_paths=PKG)
    check_mass_and_fk(result.robot, load_clean(out))


def test_spirit_floats_and_matches(tmp_path: Path) -> None:
    if not SPIRIT_XACRO.exists():
        pytest.skip("corpus not present")
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(str(SPIRIT_XACRO), str(out), fix_base=False)
    model = load_clean(out)
    load_clean(tmp_path / "scene.xml")
    assert model.jnt_type[0] == mujoco.mjtJoint.mjJNT_FREE
    assert model.nu == 12
    check_mass_and_fk(result.robot, model)


def test_dae_converted(tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(str(DATA / "dae_arm.urdf"), str(out), actuator="motor")
    meshes = [p for role, p in result.files.items() if role.startswith("mesh:")]
    assert meshes and all(p.endswith(".obj") and os.path.isfile(p) for p in meshes)
    model = load_clean(out)
    # 10 cm cube in centimetres (unit 0.01), scaled 2 2 1.
    mid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_MESH, "cube")
    verts = model.mesh_vert[model.mesh_vertadr[mid] : model.mesh_vertadr[mid] + model.mesh_vertnum[mid]]
    # MuJoCo turns a mesh into its principal axes: compare the sorted extents.
    assert sorted(verts.max(axis=0) - verts.min(axis=0)) == pytest.approx([0.1, 0.2, 0.2], rel=1e-6)
    # The two-material OBJ is two meshes, each with its .mtl colour.
    for mesh, rgba in (("two_colour_red", [1, 0, 0, 1]), ("two_colour_blue", [0, 0, 1, 0.5])):
        mesh_id = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_MESH, mesh)
        geoms = [g for g in range(model.ngeom) if model.geom_dataid[g] == mesh_id]
        assert len(geoms) == 1 and list(model.geom_rgba[geoms[0]]) == pytest.approx(rgba)
    # The transmission's reduction is the motor's gear; ctrl is motor torque (effort / gear).
    assert model.actuator_gear[0, 0] == 50
    assert list(model.actuator_ctrlrange[0]) == pytest.approx([-30 / 50, 30 / 50])


def test_gain_units_same_as_usd(tmp_path: Path) -> None:
    """The IsaacSim#842 class of bug (per-degree gains in per-radian slots, x57.3) cannot happen:
    the same --stiffness/--damping give USD's per-degree value x 180/pi == MuJoCo's kp/kv."""
    src = str(EXAMPLES / "urdf/gripper_arm.urdf")
    gains: dict[str, Any] = {"stiffness": {"elbow": 250.0, ".*": 40.0}, "damping": 3.0}
    compile_to_mjcf(src, str(tmp_path / "m/robot.xml"), **gains)
    compile_to_usd(src, str(tmp_path / "robot.usda"), **gains)
    from pxr import Usd

    stage = Usd.Stage.Open(str(tmp_path / "robot.usda"))
    model = load_clean(tmp_path / "m/robot.xml")
    checked = 0
    for prim in stage.Traverse():
        kp_attr = prim.GetAttribute("drive:angular:physics:stiffness")
        if not kp_attr.IsValid() or not kp_attr.HasAuthoredValue():
            continue
        name = prim.GetName()
        aid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
        assert aid >= 0, name
        kp = model.actuator_gainprm[aid, 0]
        kv = -model.actuator_biasprm[aid, 2]
        usd_kp = kp_attr.Get() * (180.0 / math.pi)
        usd_kv = prim.GetAttribute("drive:angular:physics:damping").Get() * (180.0 / math.pi)
        assert kp == pytest.approx(usd_kp, rel=1e-6)  # USD stores float32
        assert kv == pytest.approx(usd_kv, rel=1e-6)
        assert kp == (250.0 if name == "elbow" else 40.0)
        checked += 1
    assert checked == 4  # the revolute and continuous joints


EXAMPLE_FILES = sorted(
    [p for p in EXAMPLES.iterdir() if p.suffix in (".yaml", ".py", ".holo")]
    + [p for p in (EXAMPLES / "urdf").iterdir() if p.suffix in (".urdf", ".xacro")]
)


@pytest.mark.parametrize("path", EXAMPLE_FILES, ids=lambda p: p.name)
def test_every_example_default_flags(path: Path, tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    result = compile_to_mjcf(str(path), str(out), package_paths=PKG)
    assert result.validation.ok
    load_clean(out)
    load_clean(tmp_path / "scene.xml")


def test_every_input_kind(tmp_path: Path) -> None:
    sources: list[object] = [
        str(EXAMPLES / "urdf/gripper_arm.urdf"),
        str(EXAMPLES / "urdf/pendulum.urdf.xacro"),
        str(EXAMPLES / "quadruped.yaml"),
    ]
    if HOLO_ARM.exists():
        sources.append(str(HOLO_ARM))
    import runpy

    sources.append(runpy.run_path(str(EXAMPLES / "four_bar.py"))["build"]())  # a builder-made Robot
    for i, source in enumerate(sources):
        out = tmp_path / str(i) / "robot.xml"
        result = compile_to_mjcf(source, str(out), package_paths=PKG)  # type: ignore[arg-type]
        assert result.validation.ok, source
        load_clean(out)


def _snapshot(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def test_failed_run_leaves_earlier_output(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A run that fails validation after writing leaves every earlier file byte-identical. The
    scene is rewritten only with identical bytes; converted meshes are named by content, so a new
    mesh is an added file (left behind: the documented cost of siblings of a file target)."""
    src = tmp_path / "src"
    shutil.copytree(DATA, src)
    out_dir = tmp_path / "out"
    out = out_dir / "robot.xml"
    compile_to_mjcf(str(src / "dae_arm.urdf"), str(out))
    before = _snapshot(out_dir)
    urdf = src / "dae_arm.urdf"
    urdf.write_text(urdf.read_text().replace('scale="2 2 1"', 'scale="3 3 1"'))

    from robodesc.validation import mujoco_mjcf
    from robodesc.validation.report import Status, ValidationReport

    def failing(*args: object, **kwargs: object) -> ValidationReport:
        report = ValidationReport(robot="x", target="mjcf", consumer="test")
        report.add("forced", Status.FAIL, "document", "forced failure")
        return report

    monkeypatch.setattr(mujoco_mjcf, "validate_mjcf", failing)
    with pytest.raises(ValidationFailed):
        compile_to_mjcf(str(urdf), str(out))
    after = _snapshot(out_dir)
    assert {k: after[k] for k in before} == before
    assert all(k.startswith("meshes/") for k in set(after) - set(before))


def test_home_keyframe_and_mimic(tmp_path: Path) -> None:
    out = tmp_path / "robot.xml"
    compile_to_mjcf(str(EXAMPLES / "urdf/gripper_arm.urdf"), str(out), package_paths=PKG, init_joint_pos={"elbow": 9.0})
    model = load_clean(out)
    key = model.key("home")
    jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "elbow")
    assert key.qpos[model.jnt_qposadr[jid]] == 2.2  # clamped into [-2.2, 2.2]
    assert model.neq == 1 and model.eq_type[0] == mujoco.mjtEq.mjEQ_JOINT
    assert list(model.eq_data[0, :5]) == [0, 1, 0, 0, 0]


def _urdf(joint_type: str, inertia: str, child_inertial: bool = True) -> str:
    inertial = f'<inertial><mass value="0.1"/><inertia {inertia}/></inertial>' if child_inertial else ""
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if joint_type in ("revolute", "prismatic") else ""
    return f"""<robot name="r">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="a">{inertial}</link>
  <link name="b"><inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="{joint_type}"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>{limit}</joint>
  <joint name="k" type="revolute"><parent link="a"/><child link="b"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


GOOD = 'ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"'


def test_what_mujoco_refuses_is_repaired_and_said(tmp_path: Path) -> None:
    # An axial moment of 1e-16 next to 1e-4: MuJoCo's eigen-decomposition refuses the tensor.
    thin = _urdf("revolute", 'ixx="1e-4" iyy="1e-4" izz="1e-16" ixy="1e-12" ixz="0" iyz="1e-12"')
    result = compile_to_mjcf(thin, str(tmp_path / "a/robot.xml"))
    # The verifier finds the tensor below the floor MuJoCo and Newton take (tiny-inertia); the mjcf
    # preset repairs it and says so; the writer's own floor is the last line.
    assert {f.code for f in result.warnings} & {"tiny-inertia", "inertia-repaired", "mjcf-inertia-floor"}
    load_clean(tmp_path / "a/robot.xml")
    # A massless moving link between two jointed links.
    massless = _urdf("revolute", GOOD, child_inertial=False)
    result = compile_to_mjcf(massless, str(tmp_path / "b/robot.xml"))
    assert "mjcf-massless-body" in {f.code for f in result.warnings}
    load_clean(tmp_path / "b/robot.xml")


def test_planar_and_floating(tmp_path: Path) -> None:
    result = compile_to_mjcf(_urdf("planar", GOOD), str(tmp_path / "p/robot.xml"))
    model = load_clean(tmp_path / "p/robot.xml")
    names = [model.joint(i).name for i in range(model.njnt)]
    assert names == ["j_TX", "j_TY", "j_RZ", "k"]  # as MuJoCo's own URDF loader names them
    assert result.validation.ok
    from robodesc.ir.diagnostics import UnsupportedError

    with pytest.raises(UnsupportedError, match="free joint"):
        compile_to_mjcf(_urdf("floating", GOOD), str(tmp_path / "f/robot.xml"))
    assert not (tmp_path / "f/robot.xml").exists()
