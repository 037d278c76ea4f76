"""One small file per class of failure the hostile-input work found (issue 17), each compiled for
the target where it failed: exit 2, one line naming the problem, no traceback, nothing written."""

from __future__ import annotations

import os
import shutil
import signal
import stat
from collections.abc import Iterator
from pathlib import Path

import pytest

import robodesc
from robodesc.cli import main

HERE = Path(__file__).parent / "regressions"

# file -> (CLI target options, output name, a phrase the error line must contain)
CASES: dict[str, tuple[list[str], str, str]] = {
    "float32_overflow.urdf": (["-t", "usd"], "out.usdc", "beyond ±1e+06 m"),
    "eigen_extreme.urdf": (["-t", "usd"], "out.usda", "beyond ±1e+30"),
    "denormal_box.urdf": (["--isaac-sim"], "out_isaac", "a non-zero size must be at least 1e-09 m"),
    "huge_axis.urdf": (["-t", "urdf"], "out.urdf", "axis length is 1.41421e+200"),
    "deep.yaml": (["-t", "sdf"], "out.sdf", "YAML nested more than 100 levels deep"),
    "control_chars.yaml": (["-t", "sdf"], "out.sdf", "contains U+0001, a character XML cannot carry"),
    "composition_overflow.yaml": (["-t", "usd"], "out.usda", "cylinder radius is 1e+200 m, beyond ±1e+06 m"),
    "xacro_power.urdf.xacro": (["-t", "urdf"], "out.urdf", "integer power 9 ** 387420489"),
    "xacro_doubling.urdf.xacro": (["-t", "urdf"], "out.urdf", "property 'p15'"),
    "xacro_python.urdf.xacro": (["-t", "urdf"], "out.urdf", "the 'python' namespace is not available"),
    "xacro_load_yaml.urdf.xacro": (["-t", "urdf"], "out.urdf", "xacro.load_yaml of '/etc/passwd' is outside"),
    "xacro_env.urdf.xacro": (["-t", "urdf"], "out.urdf", "$(env HOME): robodesc reads only environment variables"),
    "xacro_eval.urdf.xacro": (["-t", "urdf"], "out.urdf", "attribute '__class__' is refused"),
    "xacro_find_escape.urdf.xacro": (["-t", "urdf"], "out.urdf", "leaves the folder of package 'fuzzpkg'"),
    "xacro_fanout.urdf.xacro": (["-t", "urdf"], "out.urdf", "more than 10000 macro calls"),
    "holo_infinite_rotation.holo": (["-t", "urdf"], "out.urdf", "object 'Arm': rotation[1]: expected a finite number"),
    "holo_hex_overflow.holo": (["-t", "urdf"], "out.urdf", "object 'Arm': mass: expected a finite number, got inf"),
    "holo_torus_overflow.holo": (["-t", "sdf"], "out.sdf", "the inertia of its torus (8.98847e+307 m, 1 kg) is beyond"),
}


@pytest.fixture
def alarm() -> Iterator[None]:
    """A hang becomes a failure instead of a stuck test run."""

    def fire(_signum: int, _frame: object) -> None:
        raise TimeoutError("no answer within 60 s")

    previous = signal.signal(signal.SIGALRM, fire)
    signal.alarm(60)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, previous)


def _refused(argv: list[str], capsys: pytest.CaptureFixture[str]) -> str:
    """The error lines of a refused run (one per offending value), as one string."""
    code = main(argv)
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert code == 2, err
    lines = [line for line in err.splitlines() if line.startswith("error:")]
    assert lines, err
    return "\n".join(lines)


@pytest.mark.parametrize("name", sorted(CASES))
def test_regression_refused_cleanly(name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str], alarm: None) -> None:
    options, out_name, phrase = CASES[name]
    work = tmp_path / "regressions"
    shutil.copytree(HERE, work)
    out = tmp_path / out_name
    line = _refused(["compile", str(work / name), *options, "-o", str(out), "--no-validate"], capsys)
    assert phrase in line
    assert not out.exists()


def test_every_regression_file_has_a_case() -> None:
    files = {p.name for p in HERE.iterdir() if p.name != "package.xml" and not p.name.startswith("collada_")}
    assert files == set(CASES)


def test_named_pipe_include_and_input_are_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], alarm: None
) -> None:
    os.mkfifo(tmp_path / "pipe.xacro")
    main_file = tmp_path / "robot.urdf.xacro"
    main_file.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:include filename="pipe.xacro"/>'
        '<link name="a"/></robot>'
    )
    line = _refused(["compile", str(main_file), "-o", str(tmp_path / "o.urdf")], capsys)
    assert "is a named pipe, not a regular file" in line
    os.mkfifo(tmp_path / "pipe.urdf")
    line = _refused(["compile", str(tmp_path / "pipe.urdf"), "-o", str(tmp_path / "o.urdf")], capsys)
    assert "is a named pipe" in line
    os.mkfifo(tmp_path / "pipe.yaml")
    line = _refused(["compile", str(tmp_path / "pipe.yaml"), "-o", str(tmp_path / "o.urdf")], capsys)
    assert "is a named pipe" in line


def test_named_pipe_mesh_is_not_opened(tmp_path: Path, capsys: pytest.CaptureFixture[str], alarm: None) -> None:
    os.mkfifo(tmp_path / "pipe.stl")
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"><visual><geometry><mesh filename="pipe.stl"/></geometry></visual></link></robot>'
    )
    code = main(
        ["compile", str(urdf), "-t", "usd", "-o", str(tmp_path / "o.usda"), "--missing-mesh", "warn", "--no-validate"]
    )
    assert "Traceback" not in capsys.readouterr().err
    assert code in (0, 2)
    assert stat.S_ISFIFO(os.stat(tmp_path / "pipe.stl").st_mode)


def test_copy_meshes_refuses_system_files(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = tmp_path / "robot"
    (src / "meshes").mkdir(parents=True)
    shutil.copy(Path(__file__).parent / "seeds" / "meshes" / "finger.stl", src / "meshes" / "finger.stl")
    os.symlink("/etc/passwd", src / "meshes" / "passwd.stl")
    (src / "meshes" / "fake.stl").write_text("this is not a mesh\n")
    refs = ["meshes/finger.stl", "meshes/passwd.stl", "/etc/hostname", "file:///etc/passwd", "../../../../etc/passwd", "meshes/fake.stl"]  # fmt: skip
    links = "".join(
        f'<link name="l{i}"><visual><geometry><mesh filename="{ref}"/></geometry></visual></link>'
        for i, ref in enumerate(refs)
    )
    joints = "".join(
        f'<joint name="j{i}" type="fixed"><parent link="l0"/><child link="l{i}"/></joint>' for i in range(1, len(refs))
    )
    urdf = src / "r.urdf"
    urdf.write_text(f'<robot name="r">{links}{joints}</robot>')
    out = tmp_path / "out" / "r.urdf"
    code = main(["compile", str(urdf), "-o", str(out), "--copy-meshes", "--no-validate", "-v"])  # -v: every finding
    err = capsys.readouterr().err
    assert code == 0, err
    assert sorted(os.listdir(out.parent / "meshes")) == ["finger.stl"]
    assert err.count("mesh-not-copied") + err.count("not copied") >= 4
    assert "passwd" not in "".join(os.listdir(out.parent / "meshes"))


def test_trust_xacro_restores_upstream(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    xacro = tmp_path / "r.urdf.xacro"
    xacro.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="${python.len([1, 2])}"/></robot>'
    )
    assert main(["expand", str(xacro)]) == 2
    capsys.readouterr()
    assert main(["expand", str(xacro), "--trust-xacro"]) == 0
    assert '<link name="2"/>' in capsys.readouterr().out


def test_env_option_names_readable_variables(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("ROBODESC_TEST_VAR", "from_env")
    xacro = tmp_path / "r.urdf.xacro"
    xacro.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="$(env ROBODESC_TEST_VAR)"/>'
        '<link name="$(optenv HOME fallback)"/></robot>'
    )
    assert main(["expand", str(xacro), "--env", "ROBODESC_TEST_VAR"]) == 0
    out = capsys.readouterr().out
    assert '<link name="from_env"/>' in out
    assert '<link name="fallback"/>' in out  # HOME is set but not named: the default is used


@pytest.mark.parametrize("name", ["collada_stride.urdf", "collada_fanout.urdf"])
def test_hostile_collada_is_left_out_with_a_warning(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str], alarm: None
) -> None:
    """An absurd accessor stride (was an OverflowError traceback) and instance_node fan-out (was a
    hang): the USD emitter leaves the unreadable mesh out and says why."""
    work = tmp_path / "regressions"
    shutil.copytree(HERE, work)
    code = main(["compile", str(work / name), "-t", "usd", "-o", str(tmp_path / "o.usda"), "--no-validate"])
    err = capsys.readouterr().err
    assert code == 0 and "Traceback" not in err
    assert "could not be read" in err and ("exceeds the 9 values" in err or "instancing visits more than" in err)


def test_a_chain_deeper_than_mujoco_takes_is_not_loaded_in_mujoco(tmp_path: Path) -> None:
    """MuJoCo refuses trees deeper than 1,023 joints after superlinear work (15 s at 2,000 links,
    without end at 50,000): validation says so at once instead of loading it."""
    links = "".join(
        f'<link name="l{i}"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1"/></inertial></link>'
        for i in range(1100)
    )
    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/><axis xyz="0 0 1"/>'
        '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        for i in range(1, 1100)
    )
    source = tmp_path / "chain.urdf"
    source.write_text(f'<robot name="chain">{links}{joints}</robot>')
    out = tmp_path / "chain_out.urdf"
    result = robodesc.compile_to_urdf(str(source), str(out))
    check = result.validation.by_name("mujoco-compile")[0]
    assert check.status.name == "WARN" and "1099 joints deep" in check.message
    assert out.is_file()


def test_collada_fanout_does_not_hang_urdf_validation(tmp_path: Path, alarm: None) -> None:
    """The same limits wherever a mesh is read: validation's conversion for MuJoCo goes through
    robodesc's COLLADA reader (was: a hang inside trimesh's DAE loader)."""
    import robodesc

    work = tmp_path / "regressions"
    shutil.copytree(HERE, work)
    result = robodesc.compile_to_urdf(str(work / "collada_fanout_collision.urdf"), tmp_path / "o.urdf")
    assert result.validation is not None and result.validation.ok
    messages = [c.message for c in result.validation.checks if c.name == "mesh-files"]
    assert any("instancing visits more than" in m for m in messages), messages
