"""False blames the fuzzer found (issue 34): a defective source that validation called robodesc's
fault (exit 1). Each case compiles a one-edit variant of the seed arm with validation on, for the
target where it was blamed, and must exit 0 with a warning naming the defect and its file:line;
what a consumer refused for it is listed as the source's ("a defect of the source")."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

import robodesc
from robodesc.cli import main

SEEDS = Path(__file__).parent / "seeds"
FINGER_INERTIA = '<inertia ixx="0.0001" ixy="0" ixz="0" iyy="0.0001" iyz="0" izz="0.0001"/>'

# name -> (text replaced in arm.urdf, its replacement, extra files under meshes/, target, output,
#          a phrase the warning must hold, the source line the warning must name)
CASES: dict[str, tuple[str, str, dict[str, bytes], str, str, str, int]] = {
    "inertial-without-mass": ('<mass value="1.0"/>', "", {}, "urdf", "o.urdf", "<inertial> has no <mass>", 10),
    "inertia-1e30": ('izz="0.001"', 'izz="1e30"', {}, "urdf", "o.urdf", "principal moments 0.008, 0.008, 1e+30", 10),
    "damping-1e30-urdf": ('damping="0.1"', 'damping="-1e30"', {}, "urdf", "o.urdf", "damping is negative", 21),
    "damping-1e30-mjcf": ('damping="0.1"', 'damping="-1e30"', {}, "mjcf", "o/robot.xml", "damping is negative", 21),
    "damping-1e30-sdf": ('damping="0.1"', 'damping="-1e30"', {}, "sdf", "o.sdf", "damping is negative", 21),
    "empty-obj": (
        "meshes/finger.stl",
        "meshes/e.obj",
        {"e.obj": b""},
        "mjcf",
        "o/robot.xml",
        "mesh has no triangles",
        16,
    ),
    "nan-obj": (
        "meshes/finger.stl",
        "meshes/n.obj",
        {"n.obj": b"v nan 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n"},
        "mjcf",
        "o/robot.xml",
        "a vertex coordinate is NaN or infinite",
        16,
    ),
    "corrupt-obj": (
        "meshes/finger.stl",
        "meshes/c.obj",
        {"c.obj": b"v 1 2\nf 1 2 9\n\x00\xff"},
        "mjcf",
        "o/robot.xml",
        "bad vertex line",
        16,
    ),
    "unreadable-stl": (
        "meshes/finger.stl",
        "meshes/b.stl",
        {"b.stl": b"solid x\nvertex 1 2\n"},
        "mjcf",
        "o/robot.xml",
        "cannot be loaded",
        16,
    ),
}


def _source(tmp_path: Path, old: str, new: str, meshes: dict[str, bytes]) -> Path:
    shutil.copytree(SEEDS / "meshes", tmp_path / "meshes")
    for name, data in meshes.items():
        (tmp_path / "meshes" / name).write_bytes(data)
    text = (SEEDS / "arm.urdf").read_text(encoding="utf-8")
    assert old in text
    source = tmp_path / "arm.urdf"
    source.write_text(text.replace(old, new, 1), encoding="utf-8")
    return source


@pytest.mark.parametrize("name", sorted(CASES))
def test_source_defect_is_not_blamed_on_robodesc(name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    old, new, meshes, target, out, phrase, line = CASES[name]
    source = _source(tmp_path, old, new, meshes)
    code = main(["compile", str(source), "-t", target, "-o", str(tmp_path / out)])
    err = capsys.readouterr().err
    assert code == 0, err
    assert "robodesc's fault" not in err and "Traceback" not in err
    warning = next(w for w in err.splitlines() if phrase in w)
    assert warning.startswith(f"warning: {source.name}:{line}:") or f"arm.urdf:{line}:" in warning, warning
    assert (tmp_path / out).is_file()


def test_zero_length_capsule_is_a_sphere_in_mjcf(tmp_path: Path) -> None:
    """MuJoCo refuses a capsule of half length 0; the same shape is a sphere of its radius."""
    source = _source(tmp_path, '<sphere radius="0.02"/>', '<capsule radius="0.02" length="0"/>', {})
    result = robodesc.compile_to(str(source), "mjcf", str(tmp_path / "o" / "robot.xml"))
    assert result.validation is not None and result.validation.ok
    text = (tmp_path / "o" / "robot.xml").read_text()
    assert '<geom type="sphere" size="0.02" class="collision"' in text


@pytest.mark.parametrize("target", ["urdf", "sdf", "usd", "mjcf"])
def test_fk_tolerance_scales_with_the_distance(target: str, tmp_path: Path) -> None:
    """A prismatic joint whose limit is 1e30 m is sampled near 6e29 m, where doubles are 1e14 m
    apart (float32 in USD: 4e22 m): the FK comparison allows that rounding, relative to the distance."""
    source = _source(tmp_path, 'upper="0.05"', 'upper="1e30"', {})
    text = source.read_text().replace('<mimic joint="shoulder" multiplier="0.01" offset="0"/>', "")
    source.write_text(text)
    out = tmp_path / ("o/robot.xml" if target == "mjcf" else f"o.{target}")
    result = robodesc.compile_to(str(source), target, str(out))
    assert result.validation is not None
    fk = [c for c in result.validation.checks if c.name == "fk"]
    assert fk and all(c.status.name == "PASS" for c in fk), [c.message for c in fk]


@pytest.mark.parametrize(
    ("argv", "phrase"),
    [
        (["--isaac-sim", "--init-pos", "nan,inf,1"], "--init-pos nan: expected a finite number"),
        (["-t", "mjcf", "--init-pos", "0,0,1e31"], "--init-pos 1e+31: expected a finite number within ±1e+30"),
        (["-t", "usd", "--contact-offset", "nan"], "--contact-offset nan"),
        (["-t", "usd", "--stiffness", "sh.*=inf"], "--stiffness 'sh.*=inf'"),
    ],
)
def test_every_numeric_option_is_finite(
    argv: list[str], phrase: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Written into a file, NaN broke every consumer (the Isaac Lab module did not import; USD read
    ``contactOffset = nan``): refused where options are built, exit 2, nothing written."""
    out = tmp_path / ("out.usda" if "usd" in argv else "out")
    code = main(["compile", str(SEEDS / "arm.urdf"), *argv, "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and phrase in err, err
    assert not out.exists()


def test_dynamics_pose_must_be_finite(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", str(SEEDS / "arm.urdf"), "--dynamics", "--pose", "sh.*=nan"]) == 2
    assert "--pose 'sh.*=nan': expected a finite number" in capsys.readouterr().err


def test_dynamics_does_not_fail_an_output_the_source_fails_the_same_way(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """An empty OBJ collider: MuJoCo refuses the URDF output and the source URDF alike (the output
    was run first and failed before the source's refusal was known)."""
    collider = '<collision><geometry><sphere radius="0.02"/></geometry></collision>'
    empty = '<collision><geometry><mesh filename="meshes/e.obj"/></geometry></collision>'
    source = _source(tmp_path, collider, empty, {"e.obj": b""})
    code = main(["validate", str(source), "-t", "urdf", "--dynamics", "--engines", "mujoco"])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "WARN load mujoco/urdf" in out and "(the source fails in mujoco too)" in out


def test_mass_without_tensor_and_unreadable_mesh_is_the_sources(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """23 of issue 34's 33 false blames: a composition link with a mass whose only shape is a mesh
    that cannot be read, so no tensor can be derived; the URDF carries the mass without a tensor,
    MuJoCo refuses it, and that is the source's defect (geometric_inertia's no-geometry warning)."""
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "broken.stl").write_text("solid x\nvertex 1 2\n")
    text = (SEEDS / "four_bar.yaml").read_text(encoding="utf-8")
    old = "geometry: {cylinder: {radius: 0.02, length: 0.03}}"
    assert old in text
    source = tmp_path / "four_bar.yaml"
    source.write_text(text.replace(old, "geometry: {mesh: meshes/broken.stl}"), encoding="utf-8")
    assert main(["compile", str(source), "-t", "urdf", "-o", str(tmp_path / "o.urdf")]) == 0
    err = capsys.readouterr().err
    assert "four_bar.yaml:30:5: link 'crank_hub': has a mass but no inertia tensor" in err
    assert main(["validate", str(source), "--dynamics", "--engines", "mujoco"]) == 0
    out = capsys.readouterr().out
    assert "WARN load mujoco/urdf" in out and "(the source's defect: " in out
