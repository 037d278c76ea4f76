"""Quirks that urdfdom (ROS), pybullet, Drake or the Isaac importer read without complaint: robodesc
reads them too, says so in a warning naming file:line, and ``--strict`` refuses them.

Each case is a small file in ``quirks/``; docs/diagnostics.md records what each consumer does."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

import robodesc
from robodesc.cli import main

QUIRKS = Path(__file__).parent / "quirks"

# file -> (finding code, "file:line" the warning names)
CASES = {
    "xml_version.urdf": ("xml-declaration", "xml_version.urdf:1"),
    "xml_declaration_late.urdf": ("xml-declaration", "xml_declaration_late.urdf:3"),
    "trailing_garbage.urdf": ("trailing-content", "trailing_garbage.urdf:15"),
    "vector_extra_numbers.urdf": ("extra-numbers", "vector_extra_numbers.urdf:11"),
    "two_shapes.urdf": ("extra-shapes", "two_shapes.urdf:5"),
    "unmodelled_geometry.urdf": ("unmodelled-geometry", "unmodelled_geometry.urdf:4"),
    "carried_values.urdf": ("unreadable-carried", "carried_values.urdf:"),
    "zero_size.urdf": ("zero-size-shape", "zero_size.urdf:4"),
    "folder_package/urdf/folder_package.urdf": ("package-by-folder", "folder_package.urdf:4"),
    "limit_without_bounds.urdf": ("limit-unbounded", "limit_without_bounds.urdf:7"),
    "undeclared_prefix.urdf": ("undeclared-prefix", "undeclared_prefix.urdf:2"),
    "world_parent.urdf": ("world-link", "world_parent.urdf:8"),
    "comma_vector.urdf": ("comma-vector", "comma_vector.urdf:11"),
    "limit_trailing_dot.urdf": ("number-trailing-dot", "limit_trailing_dot.urdf:8"),
}


def _copy(tmp_path: Path) -> Path:
    dst = tmp_path / "quirks"
    shutil.copytree(QUIRKS, dst)
    return dst


@pytest.mark.parametrize("name", sorted(CASES))
def test_quirk_is_read_with_a_warning(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    src = _copy(tmp_path) / name
    monkeypatch.chdir(tmp_path)
    code_name, where = CASES[name]
    out = tmp_path / "out" / "robot.urdf"
    assert main(["compile", str(src), "-o", str(out), "-v"]) == 0
    err = capsys.readouterr().err
    assert any(line.startswith("warning:") and where in line for line in err.splitlines()), err
    result = robodesc.compile_to_urdf(str(src), tmp_path / "api.urdf", validate=False)
    assert code_name in {f.code for f in result.findings}
    assert [link.name for link in result.robot.links if link.name != "world"] == ["base", "arm"]
    # --strict: the same warning refuses the compile, and nothing is written.
    strict = tmp_path / "strict.urdf"
    assert main(["compile", str(src), "-o", str(strict), "--strict"]) == 2
    assert not strict.exists()


def test_extra_numbers_use_the_first_three(tmp_path: Path) -> None:
    robot = robodesc.load(str(QUIRKS / "vector_extra_numbers.urdf"))
    origin = robot.joint_map()["j"].origin
    assert origin is not None and origin.xyz == (0.0, 0.0, 0.1)


def test_two_shapes_keep_the_first() -> None:
    robot = robodesc.load(str(QUIRKS / "two_shapes.urdf"))
    (visual,) = robot.link_map()["base"].visuals
    assert type(visual.geometry).__name__ == "Box"


def test_unmodelled_geometry_is_kept_in_urdf_and_left_out_of_usd(tmp_path: Path) -> None:
    src = str(QUIRKS / "unmodelled_geometry.urdf")
    urdf = robodesc.compile_to_urdf(src, tmp_path / "r.urdf")
    assert '<plane normal="0 0 1"/>' in (tmp_path / "r.urdf").read_text()
    assert not urdf.robot.link_map()["base"].collisions
    robodesc.compile_to_usd(src, tmp_path / "r.usda")
    assert "plane" not in (tmp_path / "r.usda").read_text().lower().replace("physicsscene", "")


def test_unreadable_carried_values_stay_verbatim(tmp_path: Path) -> None:
    robodesc.compile_to_urdf(str(QUIRKS / "carried_values.urdf"), tmp_path / "r.urdf")
    text = (tmp_path / "r.urdf").read_text()
    assert "<mechanicalReduction>1/12</mechanicalReduction>" in text
    assert 'rising="${zero}"' in text and "<mu1>${mu}</mu1>" in text


def test_zero_size_shapes_are_dropped(tmp_path: Path) -> None:
    robot = robodesc.load(str(QUIRKS / "zero_size.urdf"))
    assert not robot.link_map()["base"].collisions and not robot.link_map()["arm"].visuals
    assert len(robot.link_map()["base"].visuals) == 1


def test_env_substitution_in_plain_urdf(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    quirks = _copy(tmp_path)
    monkeypatch.delenv("ROBODESC_QUIRK_MESHES", raising=False)
    robot = robodesc.load(str(quirks / "env_substitution.urdf"))
    mesh = robot.link_map()["base"].visuals[0].geometry
    assert getattr(mesh, "path", None) == str(quirks / "meshes" / "finger.stl")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    shutil.copy(quirks / "meshes" / "finger.stl", elsewhere / "finger.stl")
    monkeypatch.setenv("ROBODESC_QUIRK_MESHES", str(elsewhere))
    # Only variables the user names are read (docs/security.md): without --env the default is used.
    robot = robodesc.load(str(quirks / "env_substitution.urdf"))
    assert getattr(robot.link_map()["base"].visuals[0].geometry, "path", None) == str(quirks / "meshes" / "finger.stl")
    robot = robodesc.load(str(quirks / "env_substitution.urdf"), allowed_env=("ROBODESC_QUIRK_MESHES",))
    assert getattr(robot.link_map()["base"].visuals[0].geometry, "path", None) == str(elsewhere / "finger.stl")


def test_unset_env_is_a_warning_and_the_mesh_is_missing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    src = tmp_path / "r.urdf"
    src.write_text(
        (QUIRKS / "env_substitution.urdf")
        .read_text()
        .replace("$(optenv ROBODESC_QUIRK_MESHES meshes)", "$(env ROBODESC_UNSET_VAR)")
    )
    monkeypatch.delenv("ROBODESC_UNSET_VAR", raising=False)
    result = robodesc.compile_to_urdf(str(src), tmp_path / "o.urdf", validate=False)
    assert {"env-unset", "missing-mesh"} <= {f.code for f in result.findings}


def test_folder_package_resolves_to_the_folder() -> None:
    robot = robodesc.load(str(QUIRKS / "folder_package" / "urdf" / "folder_package.urdf"))
    mesh = robot.link_map()["base"].visuals[0].geometry
    assert getattr(mesh, "path", None) == str(QUIRKS / "folder_package" / "meshes" / "finger.stl")


def test_an_explicit_package_wins_over_the_folder(tmp_path: Path) -> None:
    other = tmp_path / "other"
    (other / "meshes").mkdir(parents=True)
    shutil.copy(QUIRKS / "meshes" / "finger.stl", other / "meshes" / "finger.stl")
    robot = robodesc.load(
        str(QUIRKS / "folder_package" / "urdf" / "folder_package.urdf"), package_paths={"folder_package": str(other)}
    )
    assert getattr(robot.link_map()["base"].visuals[0].geometry, "path", None) == str(other / "meshes" / "finger.stl")


def test_trailing_dot_reads_the_number_before_it(tmp_path: Path) -> None:
    result = robodesc.compile_to_urdf(str(QUIRKS / "limit_trailing_dot.urdf"), tmp_path / "o.urdf", validate=False)
    limit = result.robot.joint("j").limit
    assert limit is not None and limit.lower == -1.57
    assert 'lower="-1.57"' in (tmp_path / "o.urdf").read_text()
