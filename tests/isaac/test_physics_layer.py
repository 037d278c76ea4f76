"""The Isaac Sim 6 route: ``<robot>_physics.usda`` over the USD Isaac Sim 6.2's importer writes.

The paths asserted below were read from Isaac Sim 6.2's import (``isaacsim-asset-isolated`` 6.2,
urdf-usd-converter 0.3.2) of the examples' Isaac folders. The last test runs that importer and PhysX
(ovphysx) where the consumer tier built them, and skips elsewhere.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from pxr import Sdf, Usd

import robodesc
from robodesc.cli import main
from robodesc.emit.isaac.importer_layout import layout_from_rules
from robodesc.frontends.urdf import read_urdf_string
from tests.conftest import EXAMPLES

QUADRUPED = EXAMPLES / "quadruped.yaml"
ENVS = Path(os.environ.get("ROBODESC_CONSUMERS_DIR", Path.home() / ".cache" / "robodesc-consumers"))


@pytest.fixture(scope="module")
def quadruped(tmp_path_factory: pytest.TempPathFactory) -> robodesc.CompileResult:
    return robodesc.compile_for_isaac_sim(str(QUADRUPED), tmp_path_factory.mktemp("quad") / "isaac")


def test_rules_give_the_paths_isaac_sim_6_2_wrote(quadruped: robodesc.CompileResult) -> None:
    layout = layout_from_rules(quadruped.robot)
    calf = "/quadruped/Geometry/trunk/FL_hip/FL_thigh/FL_calf"
    assert layout.robot == "/quadruped"
    assert layout.links["trunk"] == "/quadruped/Geometry/trunk"
    assert layout.links["FL_calf"] == calf
    # The visuals claim "box" and "sphere" first.
    assert layout.colliders["FL_calf"] == [f"{calf}/box_1", f"{calf}/sphere_1"]
    assert layout.joints["FL_knee"] == "/quadruped/Physics/FL_knee"
    assert layout.articulation_root == "/quadruped/Geometry/trunk"


def test_rules_make_names_unique_as_the_importer_does() -> None:
    robot = read_urdf_string(
        """<robot name="r">
  <link name="base"><visual><geometry><box size="1 1 1"/></geometry></visual>
    <collision name="lid"><geometry><box size="1 1 1"/></geometry></collision></link>
  <link name="lid"/>
  <link name="root_joint"/>
  <joint name="a" type="fixed"><parent link="base"/><child link="lid"/></joint>
  <joint name="root_joint" type="fixed"><parent link="base"/><child link="root_joint"/></joint>
</robot>"""
    )
    layout = layout_from_rules(robot)
    # The collision took "lid" before the child link did; the importer's base weld took root_joint.
    assert layout.colliders["base"] == ["/r/Geometry/base/lid"]
    assert layout.links["lid"] == "/r/Geometry/base/lid_1"
    assert layout.joints["root_joint"] == "/r/Physics/root_joint_1"


def test_layer_carries_robodesc_usd_physics_as_overs(quadruped: robodesc.CompileResult) -> None:
    layer = Sdf.Layer.FindOrOpen(quadruped.files["physics_layer"])
    defined = []

    def visit(path: Sdf.Path) -> None:
        spec = layer.GetPrimAtPath(path)
        if spec.specifier == Sdf.SpecifierDef:
            defined.append(str(path))

    layer.Traverse(Sdf.Path.absoluteRootPath, lambda p: visit(p) if p.IsPrimPath() else None)
    # Only robodesc's own additions are defined: the contact materials and the scene (none here).
    assert all(p.startswith("/quadruped/PhysicsMaterials") or p == "/PhysicsScene" for p in defined), defined
    own = Usd.Stage.Open(quadruped.files["usd"])
    knee = layer.GetPrimAtPath("/quadruped/Physics/FL_knee")
    ours = own.GetPrimAtPath("/quadruped/joints/FL_knee")
    for name in (
        "drive:angular:physics:stiffness",
        "drive:angular:physics:damping",
        "drive:angular:physics:maxForce",
        "physics:lowerLimit",
        "physics:upperLimit",
        "physxJointAxis:angular:armature",
        "physxJointAxis:angular:maxJointVelocity",
        "physxJointAxis:angular:staticFrictionEffort",
    ):
        assert knee.attributes[name].default == pytest.approx(ours.GetAttribute(name).Get(), rel=1e-7), name
    assert "physics:body0" not in knee.properties  # the importer's joint names its own bodies
    calf = layer.GetPrimAtPath("/quadruped/Geometry/trunk/FL_hip/FL_thigh/FL_calf")
    assert calf.attributes["physics:mass"].default == pytest.approx(0.25)
    # The articulation settings go where the importer put the root API; the API is not applied twice.
    trunk = layer.GetPrimAtPath("/quadruped/Geometry/trunk")
    assert "physxArticulation:enabledSelfCollisions" in trunk.attributes
    assert "PhysicsArticulationRootAPI" not in trunk.GetInfo("apiSchemas").prependedItems


def test_layer_command_names_the_prims_it_cannot_find(
    quadruped: robodesc.CompileResult, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # An "import" that lost a joint and a link: robodesc's own USD, edited.
    imported = tmp_path / "imported.usda"
    stage = Usd.Stage.Open(quadruped.files["usd"])
    stage.Flatten().Export(str(imported))
    edited = Sdf.Layer.FindOrOpen(str(imported))
    edit = Sdf.BatchNamespaceEdit()
    edit.Add(Sdf.NamespaceEdit.Remove("/quadruped/joints/FR_knee"))
    edit.Add(Sdf.NamespaceEdit.Remove("/quadruped/RR_calf"))
    assert edited.Apply(edit)
    edited.Save()
    out = tmp_path / "physics.usda"
    composed = tmp_path / "stage.usda"
    argv = ["layer", str(QUADRUPED), "--onto", str(imported), "-o", str(out), "--stage", str(composed)]
    code = main([*argv, "--no-validate"])
    err = capsys.readouterr().err
    assert code == 0
    assert "cannot address" in err and "joint 'FR_knee'" in err and "link 'RR_calf'" in err
    assert f"stage {composed} (open this one)" in err
    # The stage to open: the layer over the import, the layer stronger (its mass of FL_calf wins).
    root = Sdf.Layer.FindOrOpen(str(composed))
    assert root.subLayerPaths == ["./physics.usda", "./imported.usda"] and root.defaultPrim == "quadruped"
    opened = Usd.Stage.Open(str(composed))
    assert opened.GetPrimAtPath("/quadruped/FL_calf").GetAttribute("physics:mass").Get() == pytest.approx(0.25)
    layer = Sdf.Layer.FindOrOpen(str(out))
    # The rest is addressed at the paths read from that USD (robodesc's own flat layout here).
    assert layer.GetPrimAtPath("/quadruped/joints/FL_knee") is not None
    assert layer.GetPrimAtPath("/quadruped/joints/FR_knee") is None
    assert layer.GetPrimAtPath("/quadruped/FL_calf").attributes["physics:mass"].default == pytest.approx(0.25)


def test_import_plus_layer_equals_robodesc_usd_in_physx(tmp_path: Path) -> None:
    import sys

    from robodesc.validation.physx_python import physx_python

    if not (ENVS / "isaacsim" / ".built").is_file():
        pytest.skip(f"no isaacsim consumer environment in {ENVS} (tests/consumers/run.sh builds it)")
    if physx_python() is None:
        pytest.skip("PhysX (ovphysx) is not installed (tests/consumers/run.sh)")
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "consumers"))
    from isaac6_layer import run_robot  # type: ignore[import-not-found]

    # Hold, drop and slide on each route's stage, shortened (0.3 s: the robot has landed by then).
    result = run_robot("quadruped", str(QUADRUPED), {}, str(ENVS), str(tmp_path), {"duration": 0.3})
    assert result["import"] == "pass"
    assert result["prims_missing"] == [] and result["rules_match_import"]
    assert (result["links"], result["joints"]) == (13, 12)
    assert result["layer_diffs"] == []
    # importer_settings.json alone: the gains arrive, the armature (0.005 kg·m²) does not.
    assert len(result["importer_settings_diffs"]) == 12
    assert all("jointArmature: [0.0]" in d for d in result["importer_settings_diffs"])
    # The composed stage behaves as robodesc's USD: PhysX reads the same numbers, so the same run.
    assert result["layer_behaviour_diffs"] == [] and result["behaves"] == "same"
    runs = result["behaviour"]
    for scenario, quantity in (("drop", "height"), ("drop", "mass"), ("hold-fixed", "drift"), ("slide", "mu")):
        ours = runs["robodesc"][scenario][quantity]
        assert runs["layer"][scenario][quantity] == pytest.approx(ours, rel=1e-5, abs=1e-7), (scenario, quantity)
    assert runs["robodesc"]["drop"]["height"] > 0.3  # it stands
    # Without the armature the importer-only route lands within the thresholds too (armature moves
    # the landing's torques, not where the robot settles: docs/isaac.md).
    assert result["settings_behaviour_diffs"] == []


def test_fixed_base_root_moves_to_the_robot_prim(tmp_path: Path) -> None:
    result = robodesc.compile_for_isaac_sim(str(EXAMPLES / "arm6_gripper.yaml"), tmp_path / "isaac")
    layer = Sdf.Layer.FindOrOpen(result.files["physics_layer"])
    base = layer.GetPrimAtPath("/arm6_gripper/Geometry/base_link").GetInfo("apiSchemas")
    robot = layer.GetPrimAtPath("/arm6_gripper").GetInfo("apiSchemas")
    # The importer roots the articulation at base_link, which PhysX floats; robodesc's place is the robot.
    assert list(base.deletedItems) == ["PhysicsArticulationRootAPI", "NewtonArticulationRootAPI"]
    assert "PhysicsArticulationRootAPI" in robot.prependedItems
    # Composed over an "import" whose root API sits on base_link, one root remains: the robot prim.
    imported = tmp_path / "imported.usda"
    imported.write_text(
        '#usda 1.0\n(defaultPrim = "arm6_gripper")\ndef Xform "arm6_gripper" {\n def Scope "Geometry" {\n'
        '  def Xform "base_link" (prepend apiSchemas = ["PhysicsRigidBodyAPI", "PhysicsArticulationRootAPI"]) {}\n'
        " }\n}\n"
    )
    root = Sdf.Layer.CreateAnonymous(".usda")
    root.subLayerPaths = [result.files["physics_layer"], str(imported)]
    stage = Usd.Stage.Open(root)
    roots = [str(p.GetPath()) for p in stage.Traverse() if "PhysicsArticulationRootAPI" in p.GetAppliedSchemas()]
    assert roots == ["/arm6_gripper"]


def test_fixed_arm_import_plus_layer_has_a_fixed_base_in_physx(tmp_path: Path) -> None:
    import sys

    from robodesc.validation.physx_python import physx_python

    if not (ENVS / "isaacsim" / ".built").is_file() or physx_python() is None:
        pytest.skip(f"no isaacsim environment or ovphysx in {ENVS} (tests/consumers/run.sh builds them)")
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "consumers"))
    from isaac6_layer import run_robot  # type: ignore[import-not-found]

    result = run_robot("arm6_gripper", str(EXAMPLES / "arm6_gripper.yaml"), {}, str(ENVS), str(tmp_path))
    assert result["layer_diffs"] == []
    # The importer's own root (on base_link): PhysX floats the base, held only by the root joint. And
    # importer_settings.json carries no armature (the isaac_sim preset's estimate): 0 on every joint.
    diffs = result["importer_settings_diffs"]
    assert (
        "articulations: [\"{'dofCount': [8.0], 'linkCount': [10.0], 'isFixedBase': [0.0]}\"] "
        "(robodesc USD [\"{'dofCount': [8.0], 'linkCount': [10.0], 'isFixedBase': [1.0]}\"])"
    ) in diffs
    others = [d for d in diffs if not d.startswith("articulations:")]
    # The importer alone keeps the mimic follower's velocity limit (0.1 m/s), which robodesc's USD
    # leaves out (PhysX runs away with one on a follower) and the layer lifts (layer_diffs above).
    follower = [d for d in others if d.startswith("joint finger_right jointMaxVelocity: [0.1")]
    assert len(follower) == 1, others
    others = [d for d in others if d not in follower]
    assert others and all(" jointArmature: [0.0] (robodesc USD [" in d for d in others), others


def test_contact_materials_are_defined_and_bound(tmp_path: Path) -> None:
    result = robodesc.compile_for_isaac_sim(str(QUADRUPED), tmp_path / "isaac", friction_combine="min")
    stage = Usd.Stage.Open(result.files["physics_layer"])
    materials = [p for p in stage.TraverseAll() if p.GetTypeName() == "Material"]
    assert [str(p.GetPath()) for p in materials] == ["/quadruped/PhysicsMaterials/contact"]
    assert materials[0].GetAttribute("physxMaterial:frictionCombineMode").Get() == "min"
    assert materials[0].GetAttribute("physics:staticFriction").Get() == pytest.approx(0.5)
    foot = stage.GetPrimAtPath("/quadruped/Geometry/trunk/FL_hip/FL_thigh/FL_calf/sphere_1")
    assert foot.GetRelationship("material:binding:physics").GetTargets() == [materials[0].GetPath()]


def test_loop_joints_are_defined_between_the_importers_bodies(tmp_path: Path) -> None:
    # Isaac Sim 6.2's importer drops <loop_joint>: the layer closes the chain itself. In PhysX the
    # four-bar's hold then equals robodesc's USD (crank at 3.5 % of its effort; 42 % left open).
    result = robodesc.compile_for_isaac_sim(str(EXAMPLES / "four_bar.yaml"), tmp_path / "isaac")
    assert [f.message for f in result.findings if f.code == "isaac-layer-missing"] == []
    stage = Usd.Stage.Open(result.files["physics_layer"])
    loop = stage.GetPrimAtPath("/four_bar/Physics/coupler_rocker")
    assert loop.GetSpecifier() == Sdf.SpecifierDef and loop.GetTypeName() == "PhysicsSphericalJoint"
    assert [str(t) for t in loop.GetRelationship("physics:body0").GetTargets()] == [
        "/four_bar/Geometry/ground/crank/coupler"
    ]
    assert [str(t) for t in loop.GetRelationship("physics:body1").GetTargets()] == ["/four_bar/Geometry/ground/rocker"]
    assert loop.GetAttribute("physics:excludeFromArticulation").Get() is True
    assert tuple(loop.GetAttribute("physics:localPos0").Get()) == pytest.approx((0.4, 0.0, 0.2))
    assert not stage.GetPrimAtPath("/four_bar/loop_joints")  # robodesc's own scope does not travel


def test_instanced_collider_read_from_the_import_is_made_editable(quadruped: robodesc.CompileResult) -> None:
    # Isaac Sim 6.2 instances a mesh collider (Talos': friction 0.9 and a rest offset, read as 0.5
    # and 0 in PhysX while the layer could not reach inside). When the import was read, the layer
    # knows the shapes inside: it makes the collider not instanceable and carries robodesc's
    # collider opinions onto each shape.
    from robodesc.emit.isaac.folder import usd_options
    from robodesc.emit.isaac.physics_layer import physics_layer
    from robodesc.emit.isaac.settings import IsaacSettings
    from robodesc.ir.diagnostics import Findings
    from robodesc.usdfile.usda import usda_text

    robot = quadruped.robot
    options = usd_options(IsaacSettings(rest_offset=0.0005))
    foot = "/quadruped/Geometry/trunk/FL_hip/FL_thigh/FL_calf/sphere_1"
    for shapes in ({}, {foot: [f"{foot}/mesh_0", f"{foot}/mesh_1"]}):
        layout = layout_from_rules(robot)
        layout.instanced = {foot}
        layout.instance_shapes = shapes
        made = physics_layer(robot, options, layout, Findings())
        missing = [m for m in made.missing if foot in m]
        text = usda_text(made.layer)
        if not shapes:  # the naming rules cannot name the shapes: named in the warning
            assert len(missing) == 1 and "physxCollision:restOffset" in missing[0]
            assert "instanceable" not in text
            continue
        assert missing == []
        layer = Sdf.Layer.CreateAnonymous(".usda")
        layer.ImportFromString(text)
        assert layer.GetPrimAtPath(foot).GetInfo("instanceable") is False
        for shape in shapes[foot]:
            spec = layer.GetPrimAtPath(shape)
            assert spec.attributes["physxCollision:restOffset"].default == pytest.approx(0.0005)
            assert "PhysxCollisionAPI" in spec.GetInfo("apiSchemas").prependedItems


def test_a_name_the_importer_transcodes_is_named_not_guessed(tmp_path: Path) -> None:
    # iCub's mesh stems ("sim_sea_2-5_lap_belt_1_prt-binary") are no USD identifiers: Isaac Sim 6.2
    # transcodes them (tn__...), and the rules predicted a path that does not exist, silently.
    (tmp_path / "part-1.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    (tmp_path / "arm.urdf").write_text(
        '<robot name="arm"><link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" '
        'izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><mesh filename="part-1.obj"/>'
        "</geometry></collision></link></robot>"
    )
    result = robodesc.compile_for_isaac_sim(str(tmp_path / "arm.urdf"), tmp_path / "isaac", validate=False)
    assert layout_from_rules(result.robot).colliders["base"] == [""]
    missing = [f.message for f in result.findings if f.code == "isaac-layer-missing"]
    assert len(missing) == 1 and "collision 0 of link 'base' (the importer transcodes its name" in missing[0]
    assert "part-1" not in Path(result.files["physics_layer"]).read_text()


def test_a_mesh_file_of_several_meshes_is_found_inside_its_group(tmp_path: Path) -> None:
    # HyQ's trunk.dae: the importer writes a plain Xform holding one instance per mesh; the layer
    # must find the shapes there and make those instances (not the group) editable.
    from robodesc.emit.isaac.importer_layout import layout_from_usd

    (tmp_path / "proto.usda").write_text(
        '#usda 1.0\n(defaultPrim = "m")\ndef Xform "m" {\n def Mesh "shape" (prepend apiSchemas = ["PhysicsCollisionAPI"]) {}\n}\n'
    )
    (tmp_path / "imported.usda").write_text(
        '#usda 1.0\n(defaultPrim = "bot")\ndef Xform "bot" {\n def Xform "Geometry" {\n'
        '  def Xform "trunk" (prepend apiSchemas = ["PhysicsRigidBodyAPI"]) {\n   def Xform "trunk_1" {\n'
        '    def Xform "Frame001" (instanceable = true\n     prepend references = @./proto.usda@) {}\n'
        '    def Xform "Frame002" (instanceable = true\n     prepend references = @./proto.usda@) {}\n   }\n  }\n }\n}\n'
    )
    robot = read_urdf_string(
        '<robot name="bot"><link name="trunk"><collision><geometry><mesh filename="trunk.dae"/></geometry>'
        "</collision></link></robot>"
    )
    layout = layout_from_usd(str(tmp_path / "imported.usda"), robot)
    group = "/bot/Geometry/trunk/trunk_1"
    assert layout.colliders["trunk"] == [group] and group in layout.instanced
    assert layout.instance_shapes[group] == [f"{group}/Frame001/shape", f"{group}/Frame002/shape"]
    assert layout.instance_roots[group] == [f"{group}/Frame001", f"{group}/Frame002"]
