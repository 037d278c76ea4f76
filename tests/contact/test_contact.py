"""Contact carried into every target, in each engine's own terms (issue 25): Spirit's toes, read
back by each format's reference parser (usd-core's UsdPhysics, Drake's SDF parser), and the
gazebo_parity preset."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import robodesc
from robodesc.frontends.load import load_string
from tests.conftest import SPIRIT_XACRO

pytest.importorskip("pxr")

TOES = ("toe0", "toe1", "toe2", "toe3")

SHORTHAND = """<robot name="pad">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="foot"><inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.02"/></geometry></collision></link>
  <joint name="knee" type="revolute"><parent link="base"/><child link="foot"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="5"/></joint>
  <gazebo reference="foot"><mu1>0.9</mu1><mu2>0.4</mu2><kp>1e5</kp><kd>50</kd><minDepth>0.001</minDepth>
    <maxVel>0.2</maxVel><fdir1>1 0 0</fdir1><selfCollide>true</selfCollide></gazebo>
</robot>"""


def _usd_materials(path: Path) -> dict[str, dict[str, object]]:
    """Collider path -> the attributes of its bound physics material, read by usd-core."""
    from pxr import Usd, UsdShade

    stage = Usd.Stage.Open(str(path))
    out: dict[str, dict[str, object]] = {}
    for prim in stage.Traverse():
        rel = prim.GetRelationship("material:binding:physics")
        if not rel or not rel.GetTargets():
            continue
        material = stage.GetPrimAtPath(rel.GetTargets()[0])
        assert UsdShade.Material(material)
        out[str(prim.GetPath())] = {a.GetName(): a.Get() for a in material.GetAttributes() if a.HasAuthoredValue()}
    return out


def test_gazebo_shorthand_is_read_with_units() -> None:
    robot = load_string(SHORTHAND).robot
    foot = robot.link("foot")
    assert foot.contact is not None and foot.self_collide is True
    c = foot.contact
    assert (c.mu, c.mu2, c.kp, c.kd, c.min_depth, c.max_vel, c.fdir1) == (
        0.9,
        0.4,
        1e5,
        50.0,
        0.001,
        0.2,
        (1.0, 0.0, 0.0),
    )
    assert robot.link("base").contact is None  # "not given" stays distinct from a default


def test_spirit_toes_in_usd(tmp_path: Path) -> None:
    out = tmp_path / "spirit.usda"
    robodesc.compile_to_usd(str(SPIRIT_XACRO), out, validate=False)
    materials = _usd_materials(out)
    toes = {p: m for p, m in materials.items() if any(f"/{t}/" in p for t in TOES)}
    assert len(toes) == 4
    for attrs in toes.values():
        assert attrs["physics:staticFriction"] == pytest.approx(0.5)
        assert attrs["physics:dynamicFriction"] == pytest.approx(0.5)
        assert attrs["physics:restitution"] == 0.0
        assert attrs["physxMaterial:compliantContactStiffness"] == pytest.approx(30000.0)  # N/m, as kp
        assert attrs["physxMaterial:compliantContactDamping"] == pytest.approx(1000.0)  # N·s/m, as kd
        assert attrs["newton:contactStiffness"] == pytest.approx(30000.0)
        assert "physxMaterial:frictionCombineMode" not in attrs  # PhysX's own default unless asked
    # Colliders with equal properties share one material; the body has none without a source value.
    assert len({tuple(sorted(m.items())) for m in toes.values()}) == 1
    assert not [p for p in materials if "/body/" in p]


def test_spirit_toes_under_gazebo_parity(tmp_path: Path) -> None:
    out = tmp_path / "spirit.usda"
    result = robodesc.compile_to_usd(str(SPIRIT_XACRO), out, validate=False, preset="gazebo_parity")
    notes = [f for f in result.findings if f.code == "preset-applied"]
    assert notes and "friction_combine=min" in notes[0].message
    materials = _usd_materials(out)
    assert {m["physxMaterial:frictionCombineMode"] for m in materials.values()} == {"min"}
    body = [m for p, m in materials.items() if "/body/" in p]
    assert body and body[0]["physics:staticFriction"] == pytest.approx(1.0)  # Gazebo's default surface
    text = out.read_text()
    assert "physxCollision:contactOffset = 0.001" in text and "solverPositionIterationCount = 255" in text
    assert "float newton:damping = 0" in text or "newton:damping" in text  # explicit zero damping


def test_options_given_win_over_the_preset(tmp_path: Path) -> None:
    out = tmp_path / "spirit.usda"
    robodesc.compile_to_usd(str(SPIRIT_XACRO), out, validate=False, preset="gazebo_parity", friction_combine="average")
    assert {m["physxMaterial:frictionCombineMode"] for m in _usd_materials(out).values()} == {"average"}


def test_what_usd_cannot_say_is_a_warning(tmp_path: Path) -> None:
    src = tmp_path / "pad.urdf"
    src.write_text(SHORTHAND)
    result = robodesc.compile_to_usd(str(src), tmp_path / "pad.usda", validate=False)
    lost = [f.message for f in result.findings if f.code == "contact-not-representable"]
    assert any("mu2 0.4" in m for m in lost) and any("fdir1" in m for m in lost)
    text = (tmp_path / "pad.usda").read_text()
    assert "physxCollision:restOffset = -0.001" in text  # ODE's minDepth: it rests that deep
    assert "physxRigidBody:maxDepenetrationVelocity = 0.2" in text  # ODE's maxVel


def test_spirit_toes_in_sdf_read_by_drake(tmp_path: Path) -> None:
    pytest.importorskip("pydrake")
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
    from pydrake.systems.framework import DiagramBuilder

    out = tmp_path / "spirit.sdf"
    robodesc.compile_to_sdf(str(SPIRIT_XACRO), out)
    plant, scene_graph = AddMultibodyPlantSceneGraph(DiagramBuilder(), 0.001)
    Parser(plant).AddModels(str(out))
    plant.Finalize()
    inspector = scene_graph.model_inspector()

    def friction(link: str) -> tuple[float, float]:
        (geometry,) = plant.GetCollisionGeometriesForBody(plant.GetBodyByName(link))
        value = inspector.GetProximityProperties(geometry).GetProperty("material", "coulomb_friction")
        return value.static_friction(), value.dynamic_friction()

    assert [friction(toe) for toe in TOES] == [(0.5, 0.5)] * 4
    assert friction("body") == (1.0, 1.0)  # no source value: the parser's default, not one of ours
    text = out.read_text()
    assert text.count("<kp>30000</kp>") == 4 and text.count("<restitution_coefficient>0</restitution_coefficient>") == 4


def test_urdf_keeps_the_blocks_as_they_came(tmp_path: Path) -> None:
    result = robodesc.compile_to_urdf(str(SPIRIT_XACRO), validate=False)
    assert result.text is not None and result.text.count('<gazebo reference="toe') == 4


YAML = """robot: pad
links:
  base:
    geometry: {box: [0.2, 0.2, 0.1]}
    mass: 2.0
  foot:
    geometry: {sphere: {radius: 0.02}}
    mass: 0.1
    contact: {mu: 0.7, restitution: 0.1, kp: 20000, kd: 300}
joints:
  knee: {type: revolute, parent: base, child: foot, axis: [0, 1, 0], limits: {lower: -1, upper: 1, effort: 5, velocity: 2}}
"""

HOLO = """composition Pad {
  object "Base" { @physics { type: "static" mass: 2 } geometry: "cube" scale: 0.2 position: [0, 0, 0.5] }
  object "Foot" {
    @physics { mass: 0.1 friction: 0.7 restitution: 0.1 }
    @collidable
    @joint { jointType: "hinge" connectedBody: "Base" axis: [0, 1, 0] limits: { min: -45, max: 45 } }
    geometry: "sphere" scale: 0.04 position: [0, 0, 0.3]
  }
}
"""


@pytest.mark.parametrize("kind", ["yaml", "holo"])
def test_compositions_carry_contact(tmp_path: Path, kind: str) -> None:
    src = tmp_path / f"pad.{kind}"
    src.write_text(YAML if kind == "yaml" else HOLO)
    robot = robodesc.load(str(src))
    foot = robot.link("foot" if kind == "yaml" else "Foot")
    assert foot.contact is not None and foot.contact.mu == 0.7 and foot.contact.restitution == 0.1
    out = tmp_path / "pad.usda"
    robodesc.compile_to_usd(str(src), out, validate=False)
    (attrs,) = _usd_materials(out).values()
    assert attrs["physics:dynamicFriction"] == pytest.approx(0.7) and attrs["physics:restitution"] == pytest.approx(0.1)


def _spirit_toe_geoms(path: Path) -> list[tuple[float, float, float]]:
    """(slide friction, timeconst, dampratio) of each toe's collision geom, as MuJoCo compiles them."""
    import mujoco

    model = mujoco.MjModel.from_xml_path(str(path))
    out = []
    for toe in TOES:
        # Fixed links are fused by default: the toe is a site on the lower leg, its sphere a geom there.
        site = model.site(toe)
        body = int(site.bodyid[0])
        (geom,) = [
            g
            for g in range(model.ngeom)
            if model.geom_bodyid[g] == body and model.geom_group[g] == 3 and np.allclose(model.geom_pos[g], site.pos)
        ]
        out.append((float(model.geom_friction[geom][0]), *map(float, model.geom_solref[geom])))
    return out


@pytest.mark.parametrize("preset", [None, "gazebo_parity"])
def test_spirit_toes_in_mjcf_read_by_mujoco(tmp_path: Path, preset: str | None) -> None:
    pytest.importorskip("mujoco")
    out = tmp_path / "robot.xml"
    robodesc.compile_to_mjcf(str(SPIRIT_XACRO), out, fix_base=False, **({"preset": preset} if preset else {}))
    import mujoco

    mass = sum(mujoco.MjModel.from_xml_path(str(out)).body_mass) / 4  # a quarter of Spirit per toe
    omega = (30000 / mass) ** 0.5  # kp 30000 N/m
    ratio = 1000 / (2 * (30000 * mass) ** 0.5)  # kd 1000 N·s/m; > 1, so restitution 0 holds as given
    priorities = {int(p) for p in mujoco.MjModel.from_xml_path(str(out)).geom_priority}
    assert priorities == ({0, 1} if preset else {0})  # under gazebo_parity: the colliders', not the visuals'
    for mu, timeconst, dampratio in _spirit_toe_geoms(out):
        assert mu == pytest.approx(0.5)  # MuJoCo's slide friction
        # MuJoCo's damping is 2 / timeconst and its stiffness 1 / (timeconst dampratio)^2 (at full
        # impedance): kd/m and kp/m need timeconst = 1 / (dampratio omega) (docs/contact.md).
        assert dampratio == pytest.approx(ratio, rel=1e-3) and dampratio >= 1.0
        assert timeconst == pytest.approx(1 / (ratio * omega), rel=1e-3)
        assert timeconst == pytest.approx(2 * mass / 1000, rel=1e-3)


def test_spirit_toes_under_gazebo_parity_carry_the_source(tmp_path: Path) -> None:
    """The preset adds PhysX's combine rule and leaves the toes' own numbers as the source gives them."""
    out = tmp_path / "spirit.usda"
    robodesc.compile_to_usd(str(SPIRIT_XACRO), out, validate=False, preset="gazebo_parity")
    toes = {p: m for p, m in _usd_materials(out).items() if any(f"/{t}/" in p for t in TOES)}
    assert len(toes) == 4
    for attrs in toes.values():
        assert attrs["physics:staticFriction"] == pytest.approx(0.5)
        assert attrs["physics:dynamicFriction"] == pytest.approx(0.5)
        assert attrs["physics:restitution"] == 0.0
        assert attrs["physxMaterial:compliantContactStiffness"] == pytest.approx(30000.0)
        assert attrs["physxMaterial:compliantContactDamping"] == pytest.approx(1000.0)
        assert attrs["newton:contactStiffness"] == pytest.approx(30000.0)
        assert attrs["newton:contactDamping"] == pytest.approx(1000.0)
        assert attrs["physxMaterial:frictionCombineMode"] == "min"


BALL = """<robot name="ball">
  <link name="ball"><inertial><mass value="2"/><inertia ixx="0.002" iyy="0.002" izz="0.002" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><sphere radius="0.05"/></geometry></collision></link>
  <gazebo reference="ball"><kp>20000</kp><kd>4</kd></gazebo>
</robot>"""


def test_mjcf_contact_rings_at_the_sources_frequency(tmp_path: Path) -> None:
    """kp 20000 N/m under 2 kg rings at sqrt(kp / m) = 100 rad/s in MuJoCo reading the MJCF (a
    period of 63 ms; MuJoCo's impedance, 0.9 to 0.95 at this depth, makes it up to 6 % slower)."""
    mujoco = pytest.importorskip("mujoco")
    import numpy as np

    src = tmp_path / "ball.urdf"
    src.write_text(BALL)
    out = tmp_path / "ball.xml"
    robodesc.compile_to_mjcf(str(src), out, fix_base=False)
    spec = mujoco.MjSpec.from_file(str(out))
    # A floor whose own solref does not mix in (MuJoCo averages two geoms' by their solmix weights).
    spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1], solmix=1e-9)
    spec.option.timestep = 0.0002
    model = spec.compile()
    data = mujoco.MjData(model)
    root = next(j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE)
    address = int(model.jnt_qposadr[root])
    data.qpos[address + 2] = 0.05 - 2e-4  # pressed in, so it rings without leaving the floor
    heights = []
    for _ in range(2500):  # 0.5 s
        mujoco.mj_step(model, data)
        heights.append(float(data.qpos[address + 2]))
    z = np.asarray(heights[500:]) - np.mean(heights[500:])
    rising = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))
    period = float(np.mean(np.diff(rising))) * 0.0002
    assert 2 * np.pi / 100 <= period <= 1.07 * 2 * np.pi / 100


@pytest.mark.parametrize(("preset", "applied"), [(None, 1.0), ("gazebo_parity", 0.5)])
def test_mjcf_friction_against_a_floor(tmp_path: Path, preset: str | None, applied: float) -> None:
    """A ball of mu 0.5 on MuJoCo's default floor (mu 1): MuJoCo's rule takes the larger; under
    gazebo_parity the ball's priority gives ODE's minimum, 0.5, and its own solref."""
    mujoco = pytest.importorskip("mujoco")
    src = tmp_path / "ball.urdf"
    src.write_text(BALL.replace("<kp>", "<mu1>0.5</mu1><mu2>0.5</mu2><kp>"))
    out = tmp_path / "ball.xml"
    result = robodesc.compile_to_mjcf(str(src), out, fix_base=False, **({"preset": preset} if preset else {}))
    if preset:
        notes = [f.message for f in result.findings if f.code == "preset-applied"]
        assert notes and "friction_combine=min" in notes[0]
    spec = mujoco.MjSpec.from_file(str(out))
    spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1])
    model = spec.compile()
    data = mujoco.MjData(model)
    data.qpos[2] = 0.05 - 1e-4
    mujoco.mj_forward(model, data)
    assert data.ncon == 1 and data.contact.friction[0][0] == pytest.approx(applied)
    ball = next(g for g in range(model.ngeom) if model.geom_bodyid[g] != 0)
    if preset:
        assert data.contact.solref[0] == pytest.approx(model.geom_solref[ball])


def test_mjcf_refuses_a_combine_rule_mujoco_has_not(tmp_path: Path) -> None:
    from robodesc.ir.diagnostics import ConfigError

    with pytest.raises(ConfigError, match="no average or product"):
        robodesc.compile_to_mjcf(str(SPIRIT_XACRO), tmp_path / "r.xml", friction_combine="average")


def test_mjcf_warns_when_a_contact_is_stiffer_than_mujocos_step(tmp_path: Path) -> None:
    """kp 1.8e7 N/m (iCub's feet) and kd 2000 N·s/m on 2 kg need a 2 ms time constant (2 m / kd):
    MuJoCo clamps it to two 2 ms steps, which the compile says."""
    src = tmp_path / "ball.urdf"
    src.write_text(BALL.replace("<kp>20000</kp><kd>4</kd>", "<kp>1.8e7</kp><kd>2000</kd>"))
    result = robodesc.compile_to_mjcf(str(src), tmp_path / "ball.xml", fix_base=False)
    (warning,) = [f.message for f in result.findings if f.code == "contact-too-stiff-for-timestep"]
    assert "0.004 s" in warning
    src.write_text(BALL)
    result = robodesc.compile_to_mjcf(str(src), tmp_path / "ball.xml", fix_base=False)
    assert not [f for f in result.findings if f.code == "contact-too-stiff-for-timestep"]
