"""MJCF input through the commands: compile to every file target (each checked by its consumer),
inspect, view, and the issue's first failure (``root element is <mujoco>, expected <robot>``)."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.cli import main

FEATURES = Path(__file__).parent / "data" / "features.xml"


@pytest.mark.parametrize(("target", "suffix"), [("urdf", "urdf"), ("sdf", "sdf"), ("usd", "usda"), ("mjcf", "xml")])
def test_compile_every_target(target: str, suffix: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / f"robot.{suffix}"
    assert main(["compile", str(FEATURES), "-t", target, "-o", str(out)]) == 0
    assert out.exists()
    printed = capsys.readouterr()
    assert "expected <robot>" not in printed.err
    # The summary line: every link, and the consumer's check passed.
    assert "passed" in printed.out + printed.err


def test_inspect_and_view(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["inspect", str(FEATURES)]) == 0
    shown = capsys.readouterr().out
    assert "robot 'features'" in shown and "shoulder" in shown
    page = tmp_path / "features.html"
    assert main(["view", str(FEATURES), "-o", str(page)]) == 0
    assert page.stat().st_size > 1000


def test_batch_discovers_scenes_not_the_robots_they_include(tmp_path: Path) -> None:
    from robodesc.batch.discover import discover

    body = '<worldbody><body name="b"><freejoint/><geom size="0.1"/></body></worldbody>'
    (tmp_path / "robot.xml").write_text(f'<mujoco model="r">{body}</mujoco>')
    (tmp_path / "scene.xml").write_text('<mujoco model="r scene"><include file="robot.xml"/></mujoco>')
    (tmp_path / "alone.xml").write_text(f'<mujoco model="alone">{body}</mujoco>')
    (tmp_path / "options.xml").write_text('<mujoco><option timestep="0.001"/></mujoco>')
    (tmp_path / "arm.xml").write_text('<robot name="arm"><link name="a"/></robot>')
    found = [job for _, job in discover(str(tmp_path))]
    assert found == ["alone", "arm", "scene"]


def test_sdf_of_an_mjcf_with_low_friction_reads_in_drake(tmp_path: Path) -> None:
    # menagerie Spot's feet have friction 0.8: the SDF wrote <mu>0.8</mu> without <mu2>, SDF's
    # default 1 made Drake read a dynamic friction above the static one and refuse the drop.
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    import robodesc

    source = tmp_path / "foot.xml"
    source.write_text(
        """<mujoco model="foot">
  <worldbody>
    <body name="leg">
      <freejoint/>
      <geom type="capsule" size="0.02 0.1" mass="1" friction="0.7"/>
    </body>
  </worldbody>
</mujoco>
""",
        encoding="utf-8",
    )
    result = robodesc.compile_to(str(source), "sdf", tmp_path / "robot.sdf")
    assert result.validation is not None and result.validation.ok
    plant, scene_graph = AddMultibodyPlantSceneGraph(DiagramBuilder(), 0.001)
    Parser(plant).AddModels(str(tmp_path / "robot.sdf"))
    plant.Finalize()
    inspector = scene_graph.model_inspector()
    frictions = []
    for geometry in inspector.GetAllGeometryIds():
        props = inspector.GetProximityProperties(geometry)
        if props is not None and props.HasProperty("material", "coulomb_friction"):
            friction = props.GetProperty("material", "coulomb_friction")
            frictions.append((friction.static_friction(), friction.dynamic_friction()))
    # Friction 0.7: static and dynamic alike, as MuJoCo's one coefficient.
    assert any(s == pytest.approx(0.7) and d == pytest.approx(0.7) for s, d in frictions), frictions
