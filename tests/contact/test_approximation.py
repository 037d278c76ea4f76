"""Collision approximation per link: --collision-approximation rules on top of the global mode (issue 25)."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.cli import main

MESHES = Path(__file__).resolve().parents[2] / "examples" / "urdf" / "meshes"


def _robot(tmp_path: Path) -> Path:
    # Beside the robot: a mesh outside the input's folder and its packages is not read (meshes/roots.py).
    mesh = tmp_path / "part.stl"
    mesh.write_bytes(next(MESHES.glob("*.stl")).read_bytes())
    links = "".join(
        f'<link name="{name}"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>'
        f'</inertial><collision><geometry><mesh filename="{mesh}"/></geometry></collision></link>'
        for name in ("base", "foot_left", "foot_right")
    )
    joints = "".join(
        f'<joint name="j_{n}" type="fixed"><parent link="base"/><child link="{n}"/></joint>'
        for n in ("foot_left", "foot_right")
    )
    path = tmp_path / "r.urdf"
    path.write_text(f'<robot name="r">{links}{joints}</robot>')
    return path


def _modes(usda: Path) -> dict[str, str]:
    from pxr import Usd, UsdPhysics

    stage = Usd.Stage.Open(str(usda))
    out = {}
    for prim in stage.Traverse():
        if prim.HasAPI(UsdPhysics.MeshCollisionAPI):
            out[str(prim.GetPath()).split("/")[2]] = UsdPhysics.MeshCollisionAPI(prim).GetApproximationAttr().Get()
    return out


def test_rules_over_the_global_mode(tmp_path: Path) -> None:
    pytest.importorskip("pxr")
    out = tmp_path / "r.usda"
    argv = ["compile", str(_robot(tmp_path)), "-t", "usd", "-o", str(out), "-q"]
    assert (
        main(
            [
                *argv,
                "--collision-approximation",
                "foot_.*=convexDecomposition",
                "--collision-approximation",
                "boundingCube",
            ]
        )
        == 0
    )
    assert _modes(out) == {
        "base": "boundingCube",
        "foot_left": "convexDecomposition",
        "foot_right": "convexDecomposition",
    }
    assert "physxConvexDecompositionCollision:maxConvexHulls = 32" in out.read_text()
    assert main([*argv]) == 0
    assert set(_modes(out).values()) == {"convexHull"}


def test_a_bad_mode_names_the_choices(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["compile", str(_robot(tmp_path)), "-t", "usd", "-o", str(tmp_path / "r.usda")]
    assert main([*argv, "--collision-approximation", "foot=convex"]) == 2
    assert "convexDecomposition" in capsys.readouterr().err
