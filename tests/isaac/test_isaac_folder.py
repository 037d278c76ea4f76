"""The Isaac Sim target end to end: golden folders, the Isaac Lab module, and agreement between the
USD drives, the importer settings and the Isaac Lab gains."""

from __future__ import annotations

import json
import math
import runpy
import sys
import types
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest
from pxr import Usd, UsdPhysics

import robodesc
from robodesc.cli import main
from tests.conftest import CORPUS, EXAMPLES, HOLO_ARM, ROOT, SPIRIT_XACRO, Golden

SPIRIT_OPTIONS: dict[str, Any] = {
    "preset": "quad_sdk",
    "fix_base": False,
    "target_type": "none",
    "stiffness": 0.0,
    "damping": 0.0,
    "solver_position_iterations": 64,
    "solver_velocity_iterations": 16,
    "init_pos": (0.0, 0.0, 0.3),
    "contact_offset": 0.005,
    "rest_offset": 0.0005,
    "mesh_paths": "absolute",
}
ARM_OPTIONS: dict[str, Any] = {
    "fix_base": True,
    "target_type": "position",
    "drive_type": "acceleration",
    "stiffness": {"shoulder_.*": 400.0, ".*": 100.0},
    "damping": {"shoulder_.*": 40.0, ".*": 10.0},
    "mesh_paths": "absolute",
}
HOLO_OPTIONS: dict[str, Any] = {
    "missing_mesh": "primitive",
    "target_type": "position",
    "drive_type": "acceleration",
    "solver_position_iterations": 8,
    "solver_velocity_iterations": 4,
    "collision_approximation": "convexDecomposition",
    "mesh_paths": "absolute",
}
CASES = {
    "spirit": (SPIRIT_XACRO, SPIRIT_OPTIONS),
    "gripper_arm": (EXAMPLES / "urdf" / "gripper_arm.urdf", ARM_OPTIONS),
    "holoscript_arm": (HOLO_ARM, HOLO_OPTIONS),
}
GOLDEN_FILES = ("urdf", "usd", "importer_settings", "isaaclab")


def _portable(text: str) -> str:
    return text.replace(str(CORPUS), "$CORPUS").replace(str(ROOT), "$ROOT")


@pytest.fixture(scope="module")
def folders(tmp_path_factory: pytest.TempPathFactory) -> dict[str, robodesc.CompileResult]:
    out = {}
    for name, (source, options) in CASES.items():
        out[name] = robodesc.compile_for_isaac_sim(source, tmp_path_factory.mktemp(name) / "isaac", **options)
    return out


@pytest.mark.parametrize("case", sorted(CASES))
def test_golden_folder(case: str, folders: dict[str, robodesc.CompileResult], golden: Golden) -> None:
    result = folders[case]
    for role in GOLDEN_FILES:
        path = Path(result.files[role])
        golden.check(f"{case}/{path.name}", _portable(path.read_text()))
    assert result.validation is not None and result.validation.ok, result.validation.to_text()
    assert Path(result.files["validation"]).read_text().startswith("# Validation")


def _usd_drives(path: str) -> dict[str, tuple[float, float, str, float | None, float | None]]:
    stage = Usd.Stage.Open(path)
    out = {}
    for prim in stage.Traverse():
        for kind in ("angular", "linear"):
            drive = UsdPhysics.DriveAPI.Get(prim, kind)
            if drive and drive.GetStiffnessAttr().HasAuthoredValue():
                arm = prim.GetAttribute(f"physxJointAxis:{kind}:armature")
                newton = prim.GetAttribute("newton:armature")
                name = prim.GetAttribute("displayName").Get() if prim.HasAttribute("displayName") else None
                out[str(name or prim.GetName())] = (
                    drive.GetStiffnessAttr().Get(),
                    drive.GetDampingAttr().Get(),
                    kind,
                    arm.Get() if arm and arm.HasAuthoredValue() else None,
                    newton.Get() if newton and newton.HasAuthoredValue() else None,
                )
    return out


@pytest.mark.parametrize("case", sorted(CASES))
def test_isaac_lab_module_imports_without_isaac_lab_and_matches_usd(
    case: str, folders: dict[str, robodesc.CompileResult]
) -> None:
    result = folders[case]
    assert "isaaclab" not in sys.modules
    module = runpy.run_path(result.files["isaaclab"])
    assert module["ROBOT_CFG"] is None
    robot = module["ROBOT"]
    assert Path(module["USD_PATH"]) == Path(result.files["usd"])
    drives = _usd_drives(result.files["usd"])
    actuated = {j.name: j for j in result.robot.actuated_joints()}
    seen = set()
    for group in robot["actuators"].values():
        for expr in group["joint_names_expr"]:
            name = expr.replace("\\", "")
            seen.add(name)
            joint = actuated[name]
            stiffness, damping, kind, physx_arm, newton_arm = drives[joint.display_name or name]
            per = math.pi / 180 if kind == "angular" else 1.0
            # USD holds angular gains per degree; Isaac Lab takes SI.
            assert stiffness == pytest.approx(group["stiffness"] * per, rel=1e-6, abs=1e-12)
            assert damping == pytest.approx(group["damping"] * per, rel=1e-6, abs=1e-12)
            if group["armature"] is not None:
                assert physx_arm == pytest.approx(group["armature"], rel=1e-6)
                assert newton_arm == pytest.approx(group["armature"], rel=1e-6)
            assert group["joint_effort_limit"] == joint.limit.effort
    assert seen == set(actuated)


def test_spirit_settings_are_quad_sdks(folders: dict[str, robodesc.CompileResult]) -> None:
    result = folders["spirit"]
    module = runpy.run_path(result.files["isaaclab"])["ROBOT"]
    assert module["articulation"]["solver_position_iteration_count"] == 64
    assert module["articulation"]["solver_velocity_iteration_count"] == 16
    assert module["fix_base"] is False and module["init_state"]["pos"] == (0.0, 0.0, 0.3)
    # A floating robot's recommended simulation settings (make_sim_cfg): Isaac Lab 3's MJWarp defaults
    # (pyramidal, impratio 1, one substep) let quadrupeds creep 0.14-0.64 m in 3 s (issue 35).
    assert module["sim"] == {
        "dt": 0.005,
        "num_substeps": 2,
        "mjwarp": {"integrator": "implicitfast", "cone": "elliptic", "impratio": 100.0},
    }
    knees = next(g for g in module["actuators"].values() if "j_knee_0" in g["joint_names_expr"])
    assert knees["armature"] == pytest.approx(1.77264e-2) and knees["stiffness"] == 0.0
    settings = json.loads(Path(result.files["importer_settings"]).read_text())
    sim5, lab = settings["isaac_sim_5_importer"], settings["isaaclab_urdf_converter_cfg"]
    assert sim5["fix_base"] is False and sim5["merge_fixed_joints"] is False and sim5["default_drive_type"] == "none"
    assert lab["joint_drive"]["target_type"] == "none" and lab["root_link_name"] == "body"
    stage = Usd.Stage.Open(result.files["usd"])
    root = stage.GetDefaultPrim()
    body = root.GetChild("body")
    # Floating base: the articulation root sits on the root link and no root_joint exists.
    assert "PhysicsArticulationRootAPI" in body.GetAppliedSchemas()
    assert not root.GetChild("joints").GetChild("root_joint")


def test_arm_settings_both_vocabularies(folders: dict[str, robodesc.CompileResult]) -> None:
    settings = json.loads(Path(folders["gripper_arm"].files["importer_settings"]).read_text())
    per_joint = settings["per_joint_si_gains"]
    assert per_joint["shoulder_yaw"] == {"stiffness": 400.0, "damping": 40.0}
    assert per_joint["elbow"] == {"stiffness": 100.0, "damping": 10.0}
    lab = settings["isaaclab_urdf_converter_cfg"]["joint_drive"]
    assert lab == {
        "drive_type": "acceleration",
        "target_type": "position",
        "gains": {"stiffness": {"shoulder_.*": 400.0, ".*": 100.0}, "damping": {"shoulder_.*": 40.0, ".*": 10.0}},
    }


def test_isaac_urdf_flavour(folders: dict[str, robodesc.CompileResult]) -> None:
    holo = Path(folders["holoscript_arm"].files["urdf"]).read_text()
    assert "<limit" in holo and 'type="revolute"' in holo
    arm = Path(folders["gripper_arm"].files["urdf"]).read_text()
    assert '<fixed_frame name="tcp">' in arm and '<sensor name="wrist_camera" type="camera"' in arm
    # urdfdom (ROS) refuses <capsule>: the Isaac URDF writes a cylinder and two spheres (the USD keeps it).
    assert "<capsule" not in arm and "<cylinder" in arm and "<sphere" in arm
    robot = folders["gripper_arm"].robot
    for joint in robot.joints:
        if joint.type.needs_limit:
            assert joint.limit is not None and joint.limit.lower is not None and joint.limit.upper is not None


@dataclass
class _FakeCfg3:
    """The fields of Isaac Lab 3.0's ImplicitActuatorCfg the module uses (2.x names kept, deprecated)."""

    joint_names_expr: list[str] = field(default_factory=list)
    stiffness: Any = None
    damping: Any = None
    joint_effort_limit: Any = None
    joint_velocity_limit: Any = None
    effort_limit_sim: Any = None
    velocity_limit_sim: Any = None
    armature: Any = None
    friction: Any = None


@dataclass
class _FakeCfg2:
    """Isaac Lab 2.x: only the *_limit_sim names."""

    joint_names_expr: list[str] = field(default_factory=list)
    stiffness: Any = None
    damping: Any = None
    effort_limit_sim: Any = None
    velocity_limit_sim: Any = None
    armature: Any = None
    friction: Any = None


def _run_with_fake_isaac_lab(
    path: str, monkeypatch: pytest.MonkeyPatch, actuator_cls: type, identity: tuple[float, ...]
) -> dict[str, Any]:
    made: dict[str, Any] = {}

    class ArticulationCfg:
        class InitialStateCfg:
            rot = identity  # the class default tells the module which quaternion order it has

            def __init__(self, **kw: Any) -> None:
                made["init"] = kw

        def __init__(self, **kw: Any) -> None:
            made["cfg"] = kw

    sim = types.SimpleNamespace(UsdFileCfg=lambda **kw: kw, ArticulationRootPropertiesCfg=lambda **kw: kw)
    fakes = {
        "isaaclab": types.ModuleType("isaaclab"),
        "isaaclab.sim": sim,
        "isaaclab.actuators": types.SimpleNamespace(ImplicitActuatorCfg=actuator_cls),
        "isaaclab.assets": types.SimpleNamespace(ArticulationCfg=ArticulationCfg),
    }
    for name, module in fakes.items():
        monkeypatch.setitem(sys.modules, name, module)
    module = runpy.run_path(path)
    assert module["ROBOT_CFG"] is not None
    return made


def test_isaac_lab_module_builds_a_cfg_when_isaac_lab_is_present(
    folders: dict[str, robodesc.CompileResult], monkeypatch: pytest.MonkeyPatch
) -> None:
    made = _run_with_fake_isaac_lab(folders["spirit"].files["isaaclab"], monkeypatch, _FakeCfg3, (0.0, 0.0, 0.0, 1.0))
    actuators = made["cfg"]["actuators"]
    knee = next(a for a in actuators.values() if "j_knee_0" in a.joint_names_expr)
    # 3.x: the current names, not the deprecated *_limit_sim ones; the identity as (x, y, z, w).
    assert knee.joint_effort_limit == 32.0 and knee.effort_limit_sim is None
    assert knee.armature == pytest.approx(1.77264e-2)
    assert made["init"]["rot"] == (0.0, 0.0, 0.0, 1.0)
    assert made["cfg"]["spawn"]["articulation_props"]["solver_position_iteration_count"] == 64


def test_isaac_lab_3_module_fits_an_installed_2x(
    folders: dict[str, robodesc.CompileResult], monkeypatch: pytest.MonkeyPatch
) -> None:
    made = _run_with_fake_isaac_lab(folders["spirit"].files["isaaclab"], monkeypatch, _FakeCfg2, (1.0, 0.0, 0.0, 0.0))
    knee = next(a for a in made["cfg"]["actuators"].values() if "j_knee_0" in a.joint_names_expr)
    assert knee.effort_limit_sim == 32.0
    assert made["init"]["rot"] == (1.0, 0.0, 0.0, 0.0)  # reordered to 2.x's (w, x, y, z)


def test_isaac_lab_version_2_module(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "arm_isaac"
    code = main(
        [
            "compile",
            str(EXAMPLES / "urdf" / "gripper_arm.urdf"),
            "--isaac-sim",
            "-o",
            str(out),
            "-q",
            "--no-validate",
            "--isaac-lab-version",
            "2",
            "--init-pos",
            "0,0,0.5",
        ]
    )
    assert code == 0
    path = str(out / "gripper_arm_isaaclab.py")
    data = runpy.run_path(path)["ROBOT"]
    assert data["init_state"]["rot"] == (1.0, 0.0, 0.0, 0.0) and data["quaternion_order"] == "wxyz"
    assert all("effort_limit_sim" in g and "joint_effort_limit" not in g for g in data["actuators"].values())
    made = _run_with_fake_isaac_lab(path, monkeypatch, _FakeCfg2, (1.0, 0.0, 0.0, 0.0))
    assert made["init"]["rot"] == (1.0, 0.0, 0.0, 0.0)
    made = _run_with_fake_isaac_lab(path, monkeypatch, _FakeCfg3, (0.0, 0.0, 0.0, 1.0))
    assert made["init"]["rot"] == (0.0, 0.0, 0.0, 1.0)  # a 2.x module on 3.x: reordered, still upright


def test_cli_isaac_sim_writes_the_folder(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "arm_isaac"
    code = main(
        [
            "compile",
            str(EXAMPLES / "urdf" / "gripper_arm.urdf"),
            "--isaac-sim",
            "-o",
            str(out),
            "--stiffness",
            "shoulder_.*=400",
            "--stiffness",
            ".*=100",
        ]
    )
    err = capsys.readouterr().err
    assert code == 0, err
    assert err.splitlines()[-1].startswith("robodesc: isaac ")  # the one summary line
    from robodesc.view.render import backend_candidates

    # preview.png: the robot as compiled, where this machine can render offscreen (docs/view.md).
    preview = {"preview.png"} if backend_candidates() else set()
    assert {p.name for p in out.iterdir()} == {
        "gripper_arm.usda",
        "gripper_arm.urdf",
        "importer_settings.json",
        "gripper_arm_isaaclab.py",
        "gripper_arm_physics.usda",
        "validation.md",
        "validation.json",
        "findings.md",
        *preview,
    }
    assert (
        main(
            [
                "compile",
                str(EXAMPLES / "urdf" / "gripper_arm.urdf"),
                "--isaac-sim",
                "-o",
                str(out),
                "--stiffness",
                "[bad=1",
                "-q",
            ]
        )
        == 2
    )
    assert "bad regular expression" in capsys.readouterr().err
    assert (out / "gripper_arm.usda").exists()  # the earlier folder is untouched


def test_unknown_isaac_option_names_the_closest(tmp_path: Path) -> None:
    with pytest.raises(robodesc.ir.ConfigError, match="did you mean 'solver_position_iterations'"):
        robodesc.compile_for_isaac_sim(
            SPIRIT_XACRO, tmp_path / "x", solver_position_iteration=64, invalid_inertia="warn"
        )
